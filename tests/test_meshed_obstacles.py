"""Rigid obstacles from a mesh (-obstacle_NAME_type mesh, issue 51; docs/method.md section 8, "A meshed
obstacle"): a meshed plane gives the plane's run; the meshed rounded box converges to the box obstacle
at second order in its facets' size; the disk rolls off a meshed step and the ball rolls in a meshed
funnel with the balance exact, 1 rank equal to 2; bad surfaces and options are refused by name."""
import os
import shutil
import subprocess

import numpy as np
import pytest

from conftest import ROOT, assert_close, column_scale, options_without_plane, physical_scales, run

ENERGY = ["kinetic", "elastic", "total", "work_ext", "work_contact", "work_friction"]


def without(case, tmp_path, *prefixes):
    """options/<case>.opts without the lines whose option starts with one of prefixes."""
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines()
             if not l.split() or not l.split()[0].startswith(prefixes)]
    path = tmp_path / (case + "_without.opts")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def balance_and_works(h):
    """The largest |E - E_0 - (the works booked)| over the run, against the energy scale."""
    works = h["work_ext"] + h["work_contact"] + h["work_friction"] + h["work_obstacle"] + h["work_frame"]
    escale = max(np.abs(h[c]).max() for c in ENERGY)
    return np.abs(h["total"] - h["total"][0] - works).max() / escale


@pytest.mark.parametrize("case,plane,mesh,extra", [
    ("d1_friction", ("0,0", "0,1"), "plane_line", ()),
    ("d1_friction", ("0,0", "0,1"), "plane_line", ("-elasticity", "svk")),
    ("d1_friction", ("0,0", "0,1"), "plane_line", ("-obstacle_p_velocity", "0.3,0.2", "-obstacle_p_start", 0.02)),
    ("d2_ball", ("0,0,0", "0,0,1"), "plane_grid", ("-mesh", "meshes/ball10.msh", "-mu", 0.3, "-ts_max_time", 0.1)),
], ids=["2d-linear", "2d-svk", "2d-moving", "3d"])
def test_a_meshed_plane_is_the_plane(tmp_path, case, plane, mesh, extra):
    """The plane as segments (2D, 12 of them) or as an unstructured triangulation (3D, interior vertices
    where the facets meet flat), fixed or moving: every node's distance and normal are the plane's, so
    the run is the plane's, energies and forces to 1e-12 of their scales, the counts equal. A facet's normal comes from
    its vertices: a vertex that gmsh places 1e-11 off the line tilted the normal of a node above it by
    1e-9 until flat joints took the facets' normal (closest.c)."""
    opts = options_without_plane(case, tmp_path)
    common = ["-output_every", 0, "-ts_max_time", 0.2, *extra]
    a = run(opts, tmp_path, *common, "-obstacles", "p", "-obstacle_p_type", "plane", "-obstacle_p_point", plane[0], "-obstacle_p_normal", plane[1], name="plane")
    b = run(opts, tmp_path, *common, "-obstacles", "p", "-obstacle_p_type", "mesh", "-obstacle_p_mesh", f"meshes/{mesh}.msh", name="mesh")
    ha, hb = a.history, b.history
    assert len(ha) == len(hb) and ha["active"].max() > 0
    scales = physical_scales(a.outdir, opts, ha)
    for c in ENERGY + ["force_normal", "force_tangential"]:
        assert_close(hb[c], ha[c], column_scale(c, scales), rtol=1e-12, what=c)
    for c in ("active", "slipping"):
        assert np.array_equal(ha[c], hb[c]), c


@pytest.fixture(scope="module")
def box_runs(tmp_path_factory):
    """options/ball_box.opts with svk, against the box obstacle and against its surface meshed with
    triangles of 0.2 and 0.1 (meshes/box_rounded.geo), on 2 ranks."""
    base = tmp_path_factory.mktemp("box")
    opts = without("ball_box", base, "-obstacle_box_")
    common = ["-elasticity", "svk", "-output_every", 0]
    out = {"box": run(opts, base, *common, "-obstacle_box_type", "box", "-obstacle_box_center", "-0.6,-0.6,-1", "-obstacle_box_half_sizes", "1,1,1",
                      "-obstacle_box_radius", 0.5, np_=2, name="box")}
    for mesh in ("box_rounded_coarse", "box_rounded"):
        out[mesh] = run(opts, base, *common, "-obstacle_box_type", "mesh", "-obstacle_box_mesh", f"meshes/{mesh}.msh", np_=2, name=mesh)
    return out


def test_the_meshed_box_converges_to_the_box(box_runs):
    """The ball dropped on the rounded corner (ball_box) lands on facets that approach the box's sphere
    and cylinders as O(h^2): the centre's path differs from the box obstacle's by 0.0123 with facets of
    0.2 and 0.0035 with 0.1 (0.00076 with 0.05, not run here), 3.5 times less; each run exact on its
    own surface."""
    ref = box_runs["box"].history
    err = {}
    for mesh in ("box_rounded_coarse", "box_rounded"):
        h = box_runs[mesh].history
        assert len(h) == len(ref)
        assert h["balance_residual"].max() <= 1e-11
        assert balance_and_works(h) <= 1e-10
        err[mesh] = max(np.abs(h["ucm_" + x] - ref["ucm_" + x]).max() for x in "xyz")
    assert err["box_rounded"] <= 0.005  # of the ball's radius 1
    assert err["box_rounded_coarse"] >= 2.8 * err["box_rounded"], err


def test_the_meshed_box_is_not_crossed(box_runs):
    """The nodes that slide over the facets of the box's rounded corner stay outside them: 2.9e-7 =
    1.16e-6 h_c' measured, in one step where a node ends in a crease between two facets that gmsh made
    slightly concave (docs/method.md section 8), asserted at 1e-5 h_c': which rows a step solves again
    turns on a 1e-12 h_c' threshold, so another machine's rounding may take another path through that
    step. At round-off with the finer facets of 0.05 (3.7e-17), not run here."""
    h = box_runs["box_rounded"].history
    assert h["max_penetration"].max() <= 1e-5 * 0.2546


@pytest.fixture(scope="module")
def step_runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("step")
    return {np_: run("disk_step", base, "-output_every", 0, np_=np_, name=f"np{np_}") for np_ in (1, 2)}


def test_disk_rolls_off_the_meshed_step(step_runs):
    """options/disk_step.opts: the disk lands on the step's top, rolls over its rounded edge, whose
    normal turns from up to sideways, and drops to the floor 0.4 below: the step pushes it up and out
    (+x) until it leaves, the balance closes at every step with the frames' work booked, Coulomb
    holds, and no node is inside the step's facets beyond round-off (the history's penetration, with
    frames that follow, is measured on the true surface)."""
    h = step_runs[2].history
    assert "held by its bound" not in step_runs[2].output  # frames that follow: no small-sliding warning
    assert h["ucm_y"][-1] < -0.4  # it dropped off the step
    assert h["force_step_x"].min() < -0.2 * h["force_normal"].max()  # the edge pushed it out (+x): the step feels -x
    assert h["force_step_x"].max() <= 0.7 * h["force_normal"].max()
    assert h["balance_residual"].max() <= 1e-11
    assert balance_and_works(h) <= 1e-10
    assert h["max_penetration"].max() <= 1e-12 * 0.0799
    assert h["coulomb_residual"].max() <= 1e-8


def test_disk_step_one_rank_equals_two(step_runs):
    a, b = step_runs[1].history, step_runs[2].history
    scales = physical_scales(step_runs[1].outdir, "disk_step", a)
    for c in ENERGY + ["force_step_x", "force_step_y", "ucm_x", "ucm_y"]:
        assert_close(b[c], a[c], column_scale(c, scales), rtol=1e-8, what=c)


@pytest.fixture(scope="module")
def funnel_runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("funnel")
    return {np_: run("ball_funnel", base, "-output_every", 0, np_=np_, name=f"np{np_}") for np_ in (1, 2)}


def test_ball_rolls_in_the_meshed_funnel(funnel_runs):
    """options/ball_funnel.opts: the ball hits the funnel's wall and rolls around inside it: the funnel
    pushes it in (towards -x, where it hit) and up; exact balance with the frames' work booked; 1 rank
    equal to 2. The funnel's facets meet at concave edges: a node that ends a step in such a crease is
    held by one bound, not two, and sits 7.6e-6 = 3e-5 h_c' inside the other facet at worst (4.8e-5
    without solving such steps again; docs/method.md section 8): asserted at 1e-4 h_c'."""
    h, g = funnel_runs[2].history, funnel_runs[1].history
    assert h["force_funnel_x"].max() > 0.3 * h["force_normal"].max()  # the wall at +x pushes the ball back: the funnel feels +x
    assert h["force_funnel_z"].min() < -0.3 * h["force_normal"].max()  # and up
    assert h["balance_residual"].max() <= 1e-11
    assert balance_and_works(h) <= 1e-10
    assert h["coulomb_residual"].max() <= 1e-8
    assert h["max_penetration"].max() <= 1e-4 * 0.2546
    scales = physical_scales(funnel_runs[1].outdir, "ball_funnel", g)
    for c in ENERGY + ["force_funnel_x", "force_funnel_z"]:
        assert_close(h[c], g[c], column_scale(c, scales), rtol=1e-8, what=c)


def test_obstacle_view_names_the_surface(tmp_path):
    r = run("disk_step", tmp_path, "-ts_max_steps", 1, "-output_every", 0, "-obstacle_view", np_=0)
    assert "MMObstacle step: mesh (curved), the body outside" in r.output
    assert "mesh meshes/step2d.msh: 159 lines, 160 vertices; a search tree of" in r.output, r.output[-2000:]


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


LINES_41 = """$MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 3 1 3
1 1 0 3
1
2
3
3 0 0
0 0 0
-3 0 0
$EndNodes
$Elements
1 2 1 2
1 1 1 2
1 {a}
2 {b}
$EndElements
"""


@pytest.mark.parametrize("surface,extra,message", [
    (None, (), "Obstacle step is of type mesh but has no surface: give -obstacle_step_mesh FILE.msh"),
    ("missing.msh", (), "-obstacle_step_mesh missing.msh: it cannot be opened"),
    (("consistent.msh", LINES_41.format(a="1 2", b="2 3")), ("-obstacle_step_side", "inside"), "The initial state penetrates the obstacle \"step\""),
    (("flipped.msh", LINES_41.format(a="1 2", b="3 2")), (), "facets 1 and 2 face opposite sides"),
    (("binary.msh", "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n"), (), "it is a binary gmsh file: save it as ASCII"),
    (("points.msh", LINES_41.format(a="1 2", b="2 3").replace("1 1 1 2", "1 1 15 2")), (), "it has no 2-node line"),
    (("cut.msh", LINES_41.format(a="1 2", b="2 3").replace("$EndElements\n", "")), (), "it has no $EndElements line where its section ends: the file is cut short"),
    (("lifted.msh", LINES_41.format(a="1 2", b="2 3").replace("0 0 0", "0 0 0.5")), (), "its node 2 is at z = 0.5: a 2D obstacle's lines lie in the plane z = 0"),
])
def test_bad_surfaces_are_refused_by_name(tmp_path, surface, extra, message):
    opts = without("disk_step", tmp_path, "-obstacle_step_mesh")
    args = ["-ts_max_steps", 1]
    if isinstance(surface, tuple):
        args += ["-obstacle_step_mesh", write(tmp_path, *surface)]
    elif surface:
        args += ["-obstacle_step_mesh", surface]
    r = run(opts, tmp_path, *args, *extra, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-1500:]


@pytest.mark.parametrize("extra,message", [
    (("-obstacle_step_radius", 1), "-obstacle_step_radius does not apply to an obstacle of type mesh"),
    (("-obstacle_step_type", "circle", "-obstacle_step_center", "0,-4", "-obstacle_step_radius", 4), "-obstacle_step_mesh does not apply to an obstacle of type circle"),
])
def test_other_shapes_options_are_refused(tmp_path, extra, message):
    r = run("disk_step", tmp_path, "-ts_max_steps", 1, *extra, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-1500:]


def test_restart_with_another_surface_is_refused(tmp_path):
    """The checkpoint keeps the surface's counts and a hash of its coordinates, not its file's name: the
    same name with a moved step is another problem."""
    moved = tmp_path / "step.msh"
    subprocess.run(["gmsh", "-1", os.path.join(ROOT, "meshes", "step2d.geo"), "-setnumber", "X", "0.35", "-o", str(moved), "-v", "2"], check=True)
    same = tmp_path / "same.msh"
    shutil.copy(os.path.join(ROOT, "meshes", "step2d.msh"), same)
    first = run("disk_step", tmp_path, "-ts_max_steps", 10, "-checkpoint_every", 5, "-output_every", 0, "-quiet", np_=0, name="ck")
    ok = run("disk_step", tmp_path, "-restart", first.outdir, "-obstacle_step_mesh", str(same), "-ts_max_steps", 12, "-quiet", np_=0, name="ck")
    assert ok.returncode == 0
    r = run("disk_step", tmp_path, "-restart", first.outdir, "-obstacle_step_mesh", str(moved), "-quiet", np_=0, name="ck2", check=False)
    assert r.returncode != 0 and "-obstacle_step_mesh" in r.output and "its state would mean another problem" in r.output, r.output[-2000:]


def test_fixed_frames_that_slid_off_are_reported(tmp_path):
    """With the linear law the frames are fixed: each node's bound is the tangent plane of its reference
    contact point. On disk_step the disk then rolls on the top's plane past the rounded edge, held
    above the falling surface, where svk's frames follow the edge down (test_disk_rolls_off_the_meshed_step):
    the run says so once, naming the obstacle and the fix, instead of a silent float."""
    r = run("disk_step", tmp_path, "-elasticity", "linear", "-output_every", 0, np_=2)
    said = "a contact node held by its bound is"
    assert r.output.count(said) == 1 and "off the true surface of obstacle step" in r.output and "-elasticity svk or neohookean" in r.output, r.output[-2000:]
    assert r.history["ucm_y"][-1] > -0.2  # it did not drop: the small-sliding bound held it up
