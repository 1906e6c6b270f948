"""Issue 38, item 10: -check_input, a data check before a batch job (abaqus datacheck, MOOSE
--check-input). It builds the case as a run does, prints the start-up report with each physical
group's node and element counts, the planned steps and output size and a first-contact estimate,
and exits 0 without stepping or writing (no output directory, no lock); what a run refuses, it
refuses the same way. Its counts are checked against the .msh file read here, its numbers against
what a normal run prints and writes."""
import os
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import EXE, MPIEXEC, ROOT, UNUSED, run


def check_input(case, tmp_path, *extra, np_=1):
    """mmcontact -check_input on options/<case>.opts (or a file): the run, its outdir unused."""
    r = run(case, tmp_path, "-check_input", *extra, np_=np_, name="check_out", check=False)
    assert r.returncode == 0, r.output[-3000:]
    assert UNUSED not in r.output, r.output[-2000:]
    # nothing written: no output directory (so no lock in it), nothing else under tmp_path
    assert not os.path.exists(r.outdir), os.listdir(r.outdir)
    assert "mmcontact data check: the case is valid; no step was taken and nothing was written" in r.output, r.output[-2000:]
    return r


def msh_groups(path):
    """Each physical group of a gmsh 4.1 ASCII file: {name: (elements, nodes)}, read from the file's
    own sections (names, entities, elements), independently of mmcontact and PETSc."""
    lines = open(path).read().split("\n")

    def section(name):
        return lines.index("$" + name) + 1

    names = {}
    i = section("PhysicalNames")
    for k in range(int(lines[i])):
        d, tag, name = lines[i + 1 + k].split(maxsplit=2)
        names[(int(d), int(tag))] = name.strip('"')
    i = section("Entities")
    counts = list(map(int, lines[i].split()))
    i += 1
    phys = {}
    for d in range(4):
        for _ in range(counts[d]):
            f = lines[i].split()
            i += 1
            k = 4 if d == 0 else 7
            phys[(d, int(f[0]))] = [int(x) for x in f[k + 1:k + 1 + int(f[k])]]
    i = section("Elements")
    nblocks = int(lines[i].split()[0])
    i += 1
    groups = {}
    for _ in range(nblocks):
        edim, etag, _, n = map(int, lines[i].split())
        elems = [tuple(int(x) for x in lines[i + 1 + k].split()[1:]) for k in range(n)]
        i += 1 + n
        for p in phys.get((edim, etag), []):
            groups.setdefault(names[(edim, p)], []).extend(elems)
    return {name: (len(set(tuple(sorted(e)) for e in el)), len({v for e in el for v in e})) for name, el in groups.items()}


def reported_groups(output):
    return {m[1]: (int(m[2]), int(m[4])) for m in re.finditer(r"^  group (\S+): (\d+) (cells|facets|points), (\d+) nodes", output, re.M)}


def mesh_of(case):
    return re.search(r"^-mesh (\S+)", open(os.path.join(ROOT, "options", case + ".opts")).read(), re.M)[1]


CFL = r"c_p dt / h_c' = (\S+)"


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("case", ["d1_disk", "d2_ball", "two_balls"])
def test_groups_counted_as_in_the_mesh_file_and_nothing_written(tmp_path, case, np_):
    """2D, 3D and two bodies, on 1 and 2 ranks: every physical group of the .msh file is reported
    with its element and node counts as the file has them, the contact line and c_p dt / h_c' are a
    normal run's, and nothing is written."""
    c = check_input(case, tmp_path, np_=np_)
    assert reported_groups(c.output) == msh_groups(os.path.join(ROOT, mesh_of(case))), c.output[-3000:]
    r = run(case, tmp_path, "-ts_max_steps", 1, "-output_every", 0, np_=np_)
    assert re.search(CFL, c.output)[1] == re.search(CFL, r.output)[1]
    for line in ("  contact: ", "  pair p: ", "  material: "):
        assert [l for l in c.output.splitlines() if l.startswith(line)] == [l for l in r.output.splitlines() if l.startswith(line)]


def number(text, unit):
    return float(text) * {"B": 1, "kB": 1e3, "MB": 1e6, "GB": 1e9}[unit]


@pytest.mark.parametrize("case,extra,np_,contact_step", [
    ("d1_disk", ["-ts_max_time", 0.05, "-output_every", 4], 1, 5),                          # thrown at the plane
    ("d1_disk", ["-ts_max_time", 0.06, "-v0", "0,0", "-gravity", "0,-10"], 2, 23),          # dropped from rest
    ("cube_groove", ["-ts_max_time", 0.06, "-output_every", 7], 1, 23),                     # 3D, two walls
    ("d1_disk", ["-ts_max_steps", 7, "-output_every", 3], 1, 5),                            # -ts_max_steps ends it
])
def test_plan_output_size_and_first_contact_are_a_runs(tmp_path, case, extra, np_, contact_step):
    """The planned steps, snapshots and history rows are those the run takes and writes;
    solution.h5 and solution.xmf are within 3% and 1% (and 300 bytes) of the planned sizes, history.csv below its
    bound; the first-contact step is the run's first step with an active contact node (D1 thrown at
    the plane: step 5; D1 and the cube dropped from rest under gravity, which the massless contact
    dofs must not hide: step 23)."""
    c = check_input(case, tmp_path, *extra, np_=np_)
    plan = re.search(r"plan: (\d+) steps of dt = \S+ from t = 0 \(step 0\) to t = (\S+)", c.output)
    out = re.search(r"output: (\d+) snapshots .* each: (\S+) (\w+) in solution.h5 with the mesh, (\S+) (\w+) in solution.xmf; (\d+) history rows: at most (\S+) (\w+) in history.csv", c.output)
    first = re.search(r"first contact: t ~ \S+ \(step (\d+)\)", c.output)
    assert plan and out and first, c.output[-2000:]
    r = run(case, tmp_path, *extra, np_=np_)
    h = r.history
    assert int(plan[1]) == int(h["step"][-1]) and float(plan[2]) == pytest.approx(h["time"][-1], rel=1e-12)
    with r.fields() as f:
        assert int(out[1]) == f["time"].shape[0]
    assert int(out[6]) == len(h)
    size = lambda name: os.path.getsize(os.path.join(r.outdir, name))
    assert abs(size("solution.h5") / number(out[2], out[3]) - 1) <= 0.03, (size("solution.h5"), out[0])
    # the index's grids and, since the views (item 8), its opening and closing lines (300 bytes)
    assert abs(size("solution.xmf") - number(out[4], out[5])) <= 0.01 * size("solution.xmf") + 300, (size("solution.xmf"), out[0])
    assert 0.5 * number(out[7], out[8]) <= size("history.csv") <= number(out[7], out[8]) * 1.005
    active = np.flatnonzero(h["active"] > 0)
    assert ("(-ts_max_steps ends the run before -ts_max_time)" in c.output) == ("-ts_max_steps" in extra)
    assert len(active) and int(first[1]) == int(h["step"][active[0]]) == contact_step, (first[0], h["step"][active[:1]])


OUTPUT = re.compile(r"output: (\d+) snapshots \((.*?)\) of (\S+) (\w+) each: (\S+) (\w+) in solution.h5 with the mesh, (\S+) (\w+) in solution.xmf; (\d+) history rows: at most (\S+) (\w+) in history.csv")


def printed(size, text, unit):
    """Whether size in bytes, written as the data check writes sizes (3 significant digits, or whole
    bytes), is the printed text."""
    scaled = size / number(1, unit)
    return (f"{scaled:.0f}" if unit == "B" else f"{scaled:.3g}") == text


@pytest.mark.parametrize("case,extra,np_,cadence", [
    # T not a multiple of dt (snapshots at steps 0, 4, 7, 11, 14, 18 and the last, 20); rows 0, 3, ..., 18, 20
    ("d1_disk", ["-ts_max_steps", 20, "-history_every", 3, "-output_interval", 0.007, "-probes", "contact"], 1, "at t = k 0.007 and the last"),
    # T = 5 dt (t = k T to round-off), the last step on both cadences, two probes, 2 ranks
    ("d1_disk", ["-ts_max_time", 0.05, "-history_every", 5, "-output_interval", 0.01, "-probes", "contact,upper"], 2, "at t = k 0.01 and the last"),
    # 3D: the last step (16) off the history's cadence, -output_every with -history_every
    ("cube_groove", ["-ts_max_time", 0.032, "-history_every", 5, "-output_every", 3, "-probes", "top"], 1, "every 3 steps and the last"),
])
def test_plan_follows_history_every_output_interval_and_probes(tmp_path, case, extra, np_, cadence):
    """Item 11's output options in the plan: the snapshots by time (-output_interval, by the run's own
    rule) or by steps, the rows of -history_every (0, N, 2N, ... and the last) are the run's; the
    index is the run's solution.xmf to the digits printed; the history's bound is the run's header
    and, for each row, 24 bytes for each of the run's columns, the probes' included; solution.h5
    within 3% of its plan."""
    c = check_input(case, tmp_path, *extra, np_=np_)
    out = OUTPUT.search(c.output)
    assert out and out[2] == cadence, c.output[-2000:]
    every = extra[extra.index("-history_every") + 1]
    assert f"history.csv (every {every} steps and the last)" in c.output, c.output[-2000:]
    r = run(case, tmp_path, *extra, np_=np_)
    h = r.history
    with r.fields() as f:
        assert int(out[1]) == f["time"].shape[0], (out[0], f["time"][:, 0])
    steps = [int(s) for s in h["step"]]
    assert int(out[9]) == len(h) and steps == sorted(set(range(0, steps[-1] + 1, every)) | {steps[-1]}), (out[0], steps)
    size = lambda name: os.path.getsize(os.path.join(r.outdir, name))
    assert printed(size("solution.xmf"), out[7], out[8]), (size("solution.xmf"), out[0])
    header = open(os.path.join(r.outdir, "history.csv")).readline()
    columns = header.count(",") + 1
    probes = extra[extra.index("-probes") + 1].split(",")
    assert len([c for c in header.split(",") if c.startswith("probe_")]) == 2 * len(probes) * (3 if case == "cube_groove" else 2)
    assert printed(len(header) + len(h) * 24 * columns, out[10], out[11]), (len(header), len(h), columns, out[0])
    assert size("history.csv") <= number(out[10], out[11]) * 1.005
    assert abs(size("solution.h5") / number(out[5], out[6]) - 1) <= 0.03, (size("solution.h5"), out[0])


def test_large_output_warning_is_the_plan(tmp_path):
    """The run's large-output warning (item 11) and the data check's plan are one computation
    (MMOutputPlanMake): on a run of 1.25e6 steps with -history_every 10 and a probe, the steps, rows,
    history bytes and snapshots of the warning are the plan's."""
    from conftest import stop
    extra = ["-ts_max_time", 2500, "-output_every", 0, "-history_every", 10, "-probes", "contact"]
    c = check_input("d1_disk", tmp_path, *extra)
    plan = re.search(r"plan: (\d+) steps", c.output)
    out = OUTPUT.search(c.output)
    assert plan and out, c.output[-2000:]
    args = MPIEXEC + ["-n", "1", EXE, "-options_file", os.path.join(ROOT, "options", "d1_disk.opts"), *extra,
                      "-output_dir", str(tmp_path / "out"), "-quiet"]
    proc = subprocess.Popen(list(map(str, args)), cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        line = proc.stdout.readline()
    finally:
        stop(proc)
    w = re.match(r"mmcontact warning: this run plans (\S+) steps, (\S+) GB of history.csv \((\S+) rows\) and (\S+) GB of snapshots in solution.h5 \((\S+)\)", line)
    assert w, line
    assert float(w[1]) == int(plan[1]) == 1250000
    assert int(out[9]) == 125001 and w[3] == f"{125001:.4g}"  # the warning's %.4g
    assert float(w[2]) * 1e9 == pytest.approx(number(out[10], out[11]), rel=5e-3), (line, out[0])
    assert float(w[5]) == int(out[1]) == 2
    assert float(w[4]) * 1e9 == pytest.approx(2 * number(out[3], out[4]), rel=5e-3), (line, out[0])


def first_error(args):
    p = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=300)
    return p.returncode, (p.stderr.splitlines() or [""])[0]


@pytest.mark.parametrize("case,extra,message", [
    ("d1_disk", ["-contact_boundary", "contac"], 'no physical group named "contac"'),            # a misspelt group
    ("d1_disk", ["-mu_", 0.2], "set but never read"),                                         # a bad option (-mu_: did you mean -mu?)
    ("d1_disk", ["-dirichlet", "contact"], "is also on a Dirichlet boundary"),                # contact and Dirichlet overlap
    ("d1_disk", ["-dirichlet", "upper"], "is also on a Dirichlet boundary"),                  # ... at the groups' common ends
    ("two_bars", ["-contact_pair_p_master", "a_right"], "master node cannot carry a constraint"),  # overlapping surfaces
    ("d1_disk", ["-traction", "nowhere", "-traction_nowhere_value", "0,1"], 'no physical group named "nowhere"'),
    ("d1_disk", ["-probes", "contact,nowhere"], 'no physical group named "nowhere"'),             # a probe on a missing group
])
def test_refused_as_a_run_is(tmp_path, case, extra, message):
    """What a run refuses, -check_input refuses with the same status (64) and the same first line of
    stderr, and leaves no output directory (the run's refusal may leave its empty one)."""
    base = [EXE, "-options_file", os.path.join(ROOT, "options", case + ".opts"), *map(str, extra)]
    rc, line = first_error(base + ["-output_dir", str(tmp_path / "run")])
    crc, cline = first_error(base + ["-output_dir", str(tmp_path / "check"), "-check_input"])
    assert rc == crc == 64 and line == cline and message in line, (rc, line, crc, cline)
    assert not os.path.exists(tmp_path / "check")


def test_refused_as_a_run_is_on_two_ranks(tmp_path):
    """The contact/Dirichlet overlap on 2 ranks: the same status and first line as the run's."""
    base = MPIEXEC + ["-n", "2", EXE, "-options_file", "options/d1_disk.opts", "-dirichlet", "contact"]
    rc, line = first_error(base + ["-output_dir", str(tmp_path / "run")])
    crc, cline = first_error(base + ["-output_dir", str(tmp_path / "check"), "-check_input"])
    assert rc == crc == 64 and line == cline and "is also on a Dirichlet boundary" in line, (rc, line, crc, cline)
    assert not os.path.exists(tmp_path / "check")


def test_check_case_script_is_mmcontact_check_input(tmp_path):
    """scripts/check_case.py runs mmcontact -check_input: --help works (it used to crash), a case
    at c_p dt / h_c' 1.52, which mmcontact runs, is valid (the script used to refuse it above 1.5),
    and a traction on a group the mesh lacks is refused (the script ignored tractions)."""
    script = [sys.executable, "-s", os.path.join(ROOT, "scripts", "check_case.py")]
    h = subprocess.run(script + ["--help"], cwd=ROOT, capture_output=True, text=True)
    assert h.returncode == 0 and "mmcontact -check_input" in h.stdout, h.stdout + h.stderr
    out = ["-output_dir", str(tmp_path / "out")]
    c = subprocess.run(script + ["options/d1_disk.opts", "--", "-ts_dt", "3.3e-3", *out], cwd=ROOT, capture_output=True, text=True)
    assert c.returncode == 0 and "c_p dt / h_c' = 1.52" in c.stdout and "the case is valid" in c.stdout, c.stdout + c.stderr
    c = subprocess.run(script + ["options/d1_disk.opts", "--", "-traction", "nowhere", "-traction_nowhere_value", "0,1", *out], cwd=ROOT, capture_output=True, text=True)
    assert c.returncode == 64 and 'no physical group named "nowhere"' in c.stderr, c.stdout + c.stderr
    assert not os.path.exists(tmp_path / "out")


def test_load_groups_named_with_their_role(tmp_path):
    """The groups that carry a pressure or a point force (item 12) are named with that role, as the
    contact and Dirichlet groups are, so a user sees which load lands where before the run."""
    r = check_input("plate_loads", tmp_path, "-pressure", "top", "-pressure_top_value", 2)
    assert re.search(r"group top: 8 facets, 9 nodes \(-pressure\)", r.output), r.output[-2000:]
    assert re.search(r"group tip: 1 points, 1 nodes \(-point_force\)", r.output), r.output[-2000:]
