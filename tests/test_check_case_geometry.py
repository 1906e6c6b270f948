"""scripts/check_case.py places the geometry as mmcontact does: -mesh_rotation (about
-mesh_rotation_center) and the initial displacement -u0_offset/-u0_gradient."""
import os
import re
import subprocess
import sys

from conftest import ROOT, run


def check_case(path):
    return subprocess.run([sys.executable, "-s", "scripts/check_case.py", str(path)], cwd=ROOT, capture_output=True, text=True)


def opts_with(tmp_path, case, extra):
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines()]
    path = tmp_path / f"{case}_moved.opts"
    path.write_text("\n".join(lines + [f"{k} {v}" for k, v in extra]) + "\n")
    return path


def test_rotated_mesh_is_checked_where_mmcontact_puts_it(tmp_path):
    """D1 turned by 0.5 rad about (1, 0) sinks 0.593 into the plane y = 0: mmcontact refuses it,
    naming the deepest node; check_case.py finds the same node at the same depth and exits 1 (it
    used to check the unturned disk and find it clear)."""
    extra = [("-mesh_rotation", 0.5), ("-mesh_rotation_center", "1,0")]
    r = run("d1_disk", tmp_path, *[w for kv in extra for w in kv], np_=0, check=False)
    m = re.search(r"the deepest contact node, at \((\S+), (\S+)\), is (\S+) inside it", r.output)
    assert r.returncode == 64 and m, r.output[-1500:]
    x, y, depth = map(float, m.groups())
    c = check_case(opts_with(tmp_path, "d1_disk", extra))
    assert c.returncode == 1, c.stdout
    assert "mesh turned by -mesh_rotation 0.5 about (1, 0)" in c.stdout
    m = re.search(r"ERROR: obstacle plane: contact vertex at \[(\S+)\s+(\S+)\] inside it \(signed distance (\S+)\)", c.stdout)
    assert m, c.stdout
    cx, cy, dist = map(float, m.groups())
    assert abs(cx - x) <= 1e-6 and abs(cy - y) <= 1e-6 and abs(-dist - depth) <= 1e-3 * depth


def test_rotated_clear_case_and_its_assignment_agree(tmp_path):
    """The V-groove ball (two planes) turned by 0.3 rad about the y axis, through its centre, with
    both planes left in place: check_case.py's count of contact vertices per plane is the count of
    mmcontact's contact_obstacle field."""
    import h5py
    extra = [("-mesh_rotation", "0,0.3,0"), ("-mesh_rotation_center", "0,0,1.45")]
    r = run("ball_vgroove", tmp_path, *[w for kv in extra for w in kv], "-ts_max_steps", 1, np_=1)
    with h5py.File(os.path.join(r.outdir, "solution.h5"), "r") as f:
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
    c = check_case(opts_with(tmp_path, "ball_vgroove", extra))
    assert c.returncode == 0, c.stdout + c.stderr
    counts = [int(n) for n in re.findall(r"obstacle \S+: (\d+) contact vertices", c.stdout)]
    assert len(counts) == 2 and counts == [int((owner == b).sum()) for b in range(2)], (counts, c.stdout)


def test_initial_displacement_moves_the_gaps(tmp_path):
    """B1 starts with u0 = 1/2 - x/2: its contact end is 0.5 clear of the wall (check_case.py used to
    report a gap of 0, the reference position)."""
    c = check_case(os.path.join(ROOT, "options", "b1_bar.opts"))
    assert c.returncode == 0 and "smallest gap 0.5 at (0.5, 0)" in c.stdout, c.stdout
