"""The start-up header and the progress line (README "Progress"): what they print is checked against
the run's own history and output files, not against a copy of the text."""
import os
import re
import subprocess

import numpy as np

from conftest import EXE, ROOT, run

LINE = re.compile(r"^  t = (?P<t>\S+) of (?P<t_end>\S+)(?: \((?P<pct>\S+)%\))?, step (?P<step>\d+)(?: of (?P<max_steps>\d+) \((?P<pct_steps>\S+)%\))?"
                  r" \| wall (?P<wall>.+?), ETA (?P<eta>.+?) \| energy (?P<energy>\S+), balance (?P<balance>\S+)"
                  r" \| active (?P<active>\d+), slipping (?P<slipping>\d+)(?:, friction its (?P<friction>\S+))?$", re.M)
MESH = re.compile(r"^mmcontact: case (?P<case>.+); mesh (?P<mesh>\S+), (?P<dim>\d)D: (?P<cells>\d+) cells, (?P<vertices>\d+) vertices, "
                  r"(?P<dofs>\d+) dofs(?: \(and (?P<fixed>\d+) fixed by -dirichlet\))?; (?P<ranks>\d+) ranks?$", re.M)


def seconds(text):
    """A duration as the line prints it: "12.3 s", "4m05s" or "2h07m"."""
    m = re.fullmatch(r"([\d.]+) s|(\d+)m(\d+)s|(\d+)h(\d+)m", text)
    assert m, text
    if m.group(1):
        return float(m.group(1))
    if m.group(2):
        return 60 * int(m.group(2)) + int(m.group(3))
    return 3600 * int(m.group(4)) + 60 * int(m.group(5))


def progress_lines(output):
    lines = []
    for m in LINE.finditer(output):
        d = m.groupdict()
        lines.append(dict(t=float(d["t"]), t_end=float(d["t_end"]), pct=float(d["pct"] or d["pct_steps"]), step=int(d["step"]),
                          wall=seconds(d["wall"]), eta=seconds(d["eta"]), energy=float(d["energy"]), balance=float(d["balance"]),
                          active=int(d["active"]), slipping=int(d["slipping"]),
                          friction=float(d["friction"]) if d["friction"] else None))
    return lines


def test_progress_lines_follow_the_run(mm, monkeypatch):
    """The frictional D1 disk with 3000 steps and a line every 0.2 s, on a clock that advances 1 ms per
    step (MMCONTACT_TEST_CLOCK, tests/README.md), so that what is checked does not depend on the
    speed of the machine: the lines come at that interval of the clock, not every step; time,
    percentage and step advance; the ETA is the elapsed time scaled by the simulated time left over
    the time done, and it falls at every line; energy, balance residual and contact counts are those
    of history.csv at that step, and the friction iterations their mean over the steps since the
    previous line."""
    per_step, every = 0.001, 0.2
    monkeypatch.setenv("MMCONTACT_TEST_CLOCK", str(per_step))
    r = mm("d1_friction", "-ts_dt", 1e-4, "-progress_every", every, "-output_every", 0)
    lines = progress_lines(r.output)
    h = r.history
    # the steps that print: the rule of progress.c, in the same floating-point arithmetic
    expected, last = [], 0.0
    for s in h["step"][1:]:
        if per_step * int(s) - last >= every:
            expected.append(int(s))
            last = per_step * int(s)
    assert len(expected) >= 10 and [p["step"] for p in lines] == expected, (expected, r.output[-3000:])
    row = {int(s): i for i, s in enumerate(h["step"])}
    t_end = 0.3
    prev_step = 0
    for k, p in enumerate(lines):
        assert p["t_end"] == t_end
        assert 0 < p["pct"] <= 100 and abs(p["pct"] - 100 * p["t"] / t_end) <= 0.051
        i = row[p["step"]]
        wall = per_step * p["step"]
        assert abs(p["wall"] - wall) <= 0.051  # printed to 0.1 s
        # the ETA: the elapsed (clock) time times the simulated time left over the time done
        eta = wall * (t_end - h["time"][i]) / h["time"][i]
        assert abs(p["eta"] - eta) <= 0.051 + 1e-3 * eta, (p, eta)
        assert abs(p["t"] - h["time"][i]) <= 1e-5 * t_end
        assert abs(p["energy"] - h["total"][i]) <= 1e-9 * abs(h["total"]).max()
        assert abs(p["balance"] - h["balance_residual"][i]) <= 6e-3 * h["balance_residual"][i] + 1e-300
        assert (p["active"], p["slipping"]) == (h["active"][i], h["slipping"][i])
        # the mean over the steps since the previous line
        since = (h["step"] > prev_step) & (h["step"] <= p["step"])
        assert abs(p["friction"] - h["friction_its"][since].mean()) <= 0.051
        prev_step = p["step"]
        if k:
            q = lines[k - 1]
            assert p["t"] > q["t"] and p["step"] > q["step"] and p["pct"] >= q["pct"]
            assert p["eta"] < q["eta"], (q, p)  # steady steps on this clock: the ETA falls at every line
    assert max(p["active"] for p in lines) > 0 and max(p["friction"] for p in lines) > 1


def test_progress_every_zero_negative_quiet_and_ts_monitor(tmp_path):
    """-progress_every 0 prints no line where a tiny interval prints one per step; a negative value
    is refused naming the option; -quiet prints neither header nor lines; -ts_monitor still prints
    its own line per step beside the progress lines; with -ts_max_steps the percentage counts
    steps."""
    steps = ("-ts_max_steps", 20, "-output_every", 0)
    every_step = run("d1_disk", tmp_path, *steps, "-progress_every", 1e-9, np_=0, name="every")
    lines = progress_lines(every_step.output)
    assert [p["step"] for p in lines] == list(range(1, 21))
    assert [p["pct"] for p in lines] == [5.0 * (s + 1) for s in range(20)]
    assert all(p["friction"] is None for p in lines)  # frictionless: no friction column
    off = run("d1_disk", tmp_path, *steps, "-progress_every", 0, np_=0, name="off")
    assert MESH.search(off.output) and "no progress lines" in off.output
    assert not progress_lines(off.output)
    quiet = run("d1_disk", tmp_path, *steps, "-progress_every", 1e-9, "-quiet", np_=0, name="quiet")
    assert not progress_lines(quiet.output) and not MESH.search(quiet.output)
    monitor = run("d1_disk", tmp_path, *steps, "-progress_every", 1e-9, "-ts_monitor", np_=0, name="monitor")
    assert len(re.findall(r"^\d+ TS dt 0\.002 time ", monitor.output, re.M)) == 21
    assert len(progress_lines(monitor.output)) == 20
    bad = run("d1_disk", tmp_path, "-progress_every", -1, np_=0, name="bad", check=False)
    assert bad.returncode != 0
    assert "-progress_every -1 must be >= 0" in bad.output, bad.output[-2000:]


def header(output):
    m = MESH.search(output)
    assert m, output[-3000:]
    return m.groupdict()


def test_header_counts_the_mesh_and_names_the_solvers(tmp_path):
    """The header's cells, vertices and dofs are those of the mesh written to solution.h5 (dofs = d x
    vertices, less the Dirichlet ones), its ranks the ranks, its case the options file (or the
    command line), and its K~ solver the one the objects have in 2D: PETSc's Cholesky, on 2 ranks
    of each rank's interior, with the interface's Schur complement (schursplit)."""
    opts = os.path.join(ROOT, "options", "d1_disk.opts")
    r = run("d1_disk", tmp_path, "-ts_max_steps", 2, np_=2, name="disk")
    m = header(r.output)
    with r.fields() as f:
        nv, dim = f["geometry/vertices"].shape
        nc = f["viz/topology/cells"].shape[0]
    assert (m["case"], m["mesh"], int(m["dim"]), int(m["ranks"])) == (opts, "meshes/disk.msh", 2, 2)
    assert (int(m["cells"]), int(m["vertices"]), int(m["dofs"]), m["fixed"]) == (nc, nv, dim * nv, None)
    assert "K~ by preonly + schursplit (each rank's interior by PETSc's Cholesky, the ranks' interface by its dense Schur complement), prefix contact_K_" in r.output
    assert "33 contact nodes against 1 obstacle: plane (plane)" in r.output and "frictionless" in r.output
    assert "c_p dt / h_c' = 0.919" in r.output

    bar = run("b1_bar", tmp_path, "-ts_max_steps", 2, np_=0, name="bar")
    m = header(bar.output)
    with bar.fields() as f:
        nv, dim = f["geometry/vertices"].shape
    assert int(m["ranks"]) == 1 and int(m["vertices"]) == nv
    assert int(m["fixed"]) > 0 and int(m["dofs"]) + int(m["fixed"]) == dim * nv
    assert "K~ by preonly + schursplit (PETSc's Cholesky; one rank, no interface), prefix contact_K_" in bar.output

    # the same case given on the command line
    args = [w for line in open(opts) for w in line.split("#")[0].split()]
    proc = subprocess.run([EXE, *args, "-ts_max_steps", "1", "-output_dir", str(tmp_path / "cmdline")], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert header(proc.stdout)["case"] == "command line"


def test_header_names_the_3d_factor_ordering_scotch_by_default(tmp_path):
    """K~'s 3D factor is MUMPS's Cholesky with the SCOTCH ordering, through the SCOTCH-enabled MUMPS
    linked ahead of PETSc's (Makefile, MUMPS_SCOTCH_LIB): the header names the ordering MUMPS
    reports (INFOG(7)), so a build that lost that library, where MUMPS falls back to PORD and fills
    a third more, shows it. The ordering changes the round-off only: PORD, asked for, gives the
    same frictional D2 history (12k dofs, 2 ranks) to 1e-10 of the energy scale, the same sets."""
    common = ("-mesh", "meshes/ball10.msh", "-contact_formulation", "condensed", "-mu", 0.2, "-ts_max_steps", 15)
    scotch = run("d2_ball", tmp_path, *common, np_=2, name="scotch")
    pord = run("d2_ball", tmp_path, *common, "-contact_K_mat_mumps_icntl_7", 4, np_=2, name="pord")
    # a PETSc other than Debian's keeps its own MUMPS (Makefile): then only the history is checked
    libs = subprocess.run(["ldd", EXE], capture_output=True, text=True).stdout
    linked = "libdmumps_ptscotch-5.5.so" in libs
    assert linked or "libdmumps-5.5.so" not in libs, "Debian's PORD-only MUMPS without the SCOTCH build linked ahead of it"
    if linked:
        assert "K~ by preonly + cholesky (mumps, SCOTCH ordering), prefix contact_K_" in scotch.output
    assert "K~ by preonly + cholesky (mumps, PORD ordering), prefix contact_K_" in pord.output
    # -log_view is read only at the end, so the options audit replays the help, which reads
    # K~'s MUMPS options on a stand-in factor: with PORD on one rank that ended the process
    one = run("d2_ball", tmp_path, *common[:-2], "-ts_max_steps", 2, "-contact_K_mat_mumps_icntl_7", 4, "-log_view", np_=1, name="pord_1rank")
    assert "mmcontact summary:" in one.output and "MatCholFctrNum" in one.output
    a, b = scotch.history, pord.history
    assert a["active"].max() > 0 and a["slipping"].max() > 0
    assert np.array_equal(a["active"], b["active"]) and np.array_equal(a["slipping"], b["slipping"])
    scale = np.abs(a["total"]).max()
    for k in ("kinetic", "elastic", "work_contact", "work_friction"):
        assert np.abs(a[k] - b[k]).max() <= 1e-10 * scale, k
