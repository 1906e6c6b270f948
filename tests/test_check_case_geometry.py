"""Checking a case before it runs (mmcontact -check_input; scripts/check_case.py is its wrapper)
places the geometry as the run does: -mesh_rotation (about -mesh_rotation_center) and the initial
displacement -u0_offset/-u0_gradient. These were checks of the former Python check_case.py, which
computed the geometry itself; they now hold against mmcontact's own report."""
import os
import re
import subprocess

from conftest import EXE, ROOT, run


def check(opts, tmp_path, *extra):
    """mmcontact -check_input on an options file (a case name or a path): (status, stdout, stderr);
    it writes nothing, so its -output_dir must not exist afterwards."""
    path = opts if str(opts).endswith(".opts") else os.path.join(ROOT, "options", opts + ".opts")
    out = tmp_path / "check_out"
    p = subprocess.run([EXE, "-options_file", str(path), "-output_dir", str(out), "-check_input", *map(str, extra)],
                       cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert not os.path.exists(out)
    return p.returncode, p.stdout, p.stderr


def opts_with(tmp_path, case, extra):
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines()]
    path = tmp_path / f"{case}_moved.opts"
    path.write_text("\n".join(lines + [f"{k} {v}" for k, v in extra]) + "\n")
    return path


def obstacle_gaps(stdout):
    """-check_input's line per obstacle or pair: {name: (contact nodes, smallest gap)}."""
    return {m[1]: (int(m[2]), float(m[3])) for m in re.finditer(r"^  gap to (?:obstacle|pair) (\S+): (\d+) contact nodes, smallest (\S+)", stdout, re.M)}


def test_rotated_mesh_is_checked_where_mmcontact_puts_it(tmp_path):
    """D1 turned by 0.5 rad about (1, 0) sinks 0.593 into the plane y = 0: the run refuses it,
    naming the deepest node, and -check_input refuses it with the same status and message (the
    former script checked the unturned disk and found it clear)."""
    extra = [("-mesh_rotation", 0.5), ("-mesh_rotation_center", "1,0")]
    r = run("d1_disk", tmp_path, *[w for kv in extra for w in kv], np_=0, check=False)
    m = re.search(r"the deepest contact node, at \((\S+), (\S+)\), is (\S+) inside it", r.output)
    assert r.returncode == 64 and m, r.output[-1500:]
    assert abs(float(m[3]) - 0.593) <= 1e-3
    rc, out, err = check(opts_with(tmp_path, "d1_disk", extra), tmp_path)
    assert rc == 64 and err.splitlines()[0] in r.output and m[0] in err.splitlines()[0], err


def test_rotated_clear_case_and_its_assignment_agree(tmp_path):
    """The V-groove ball (two planes) turned by 0.3 rad about the y axis, through its centre, with
    both planes left in place: -check_input's count of contact nodes per plane is the count of the
    run's contact_obstacle field."""
    import h5py
    extra = [("-mesh_rotation", "0,0.3,0"), ("-mesh_rotation_center", "0,0,1.45")]
    r = run("ball_vgroove", tmp_path, *[w for kv in extra for w in kv], "-ts_max_steps", 1, np_=1)
    with h5py.File(os.path.join(r.outdir, "solution.h5"), "r") as f:
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
    rc, out, err = check(opts_with(tmp_path, "ball_vgroove", extra), tmp_path)
    assert rc == 0, out + err
    counts = [n for n, _ in obstacle_gaps(out).values()]
    assert len(counts) == 2 and counts == [int((owner == b).sum()) for b in range(2)], (counts, out)


def test_initial_displacement_moves_the_gaps(tmp_path):
    """B1 starts with u0 = 1/2 - x/2: its contact end is about 0.5 clear of the wall (0 at the
    reference position), and the smallest gap -check_input reports is the run's gap field at t = 0."""
    rc, out, err = check("b1_bar", tmp_path)
    assert rc == 0, out + err
    gap = obstacle_gaps(out)["plane"][1]
    r = run("b1_bar", tmp_path, "-ts_max_steps", 1, np_=0)
    with r.fields() as f:
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
        g0 = f["vertex_fields/gap_nodal"][0]
    assert abs(gap - g0[owner == 0].min()) <= 1e-9 and abs(gap - 0.5) <= 0.01, (gap, out)
