"""Obstacles of any shape, per-node frames and moving obstacles (docs/method.md section 8)."""
import numpy as np
import pytest

from conftest import options_without_plane

TIGHT = ("-contact_tol", 1e-14, "-friction_snes_rtol", 1e-13, "-friction_coulomb_tol", 1e-11, "-output_every", 0)


@pytest.fixture
def disk_opts(tmp_path):
    """The frictional D1 disk without its plane, so that -obstacles can name the obstacles."""
    return options_without_plane("d1_friction", tmp_path)


def run_opts(mm, opts_path, *extra, **kw):
    return mm(opts_path, *extra, **kw)


def test_moving_floor_is_the_moving_body_seen_from_the_floor(mm, disk_opts):
    """Galilean invariance: the disk thrown at (-0.5, -1) onto a fixed floor, and the disk at rest hit
    by the floor moving at (0.5, 1), are the same relative motion. The moving floor must move every
    gap, and friction must act on the slip relative to it: the contact forces, the elastic energy
    and the method's contact and friction works agree to solver tolerance, while the moving floor's
    work goes to work_obstacle and the balance still closes."""
    floor = ("-obstacles", "floor", "-obstacle_floor_point", "0,0", "-obstacle_floor_normal", "0,1", *TIGHT)
    fixed = run_opts(mm, disk_opts, *floor, "-v0", "-0.5,-1", name="fixed")
    moving = run_opts(mm, disk_opts, *floor, "-v0", "0,0", "-obstacle_floor_velocity", "0.5,1", name="moving")
    a, b = fixed.history, moving.history
    fscale = np.abs(a["force_normal"]).max()
    assert a["active"].max() > 0 and a["slipping"].max() > 0  # it touches and slides
    for c in ["force_normal", "force_tangential", "force_floor_x", "force_floor_y"]:
        assert np.abs(a[c] - b[c]).max() <= 1e-9 * fscale, c
    escale = np.abs(a["total"]).max()
    for c in ["elastic", "work_contact", "work_friction"]:
        assert np.abs(a[c] - b[c]).max() <= 1e-10 * escale, c
    assert np.array_equal(a["active"], b["active"]) and np.array_equal(a["slipping"], b["slipping"])
    assert np.all(a["work_obstacle"] == 0) and b["work_obstacle"][-1] > 0.1 * escale
    assert b["balance_residual"].max() <= 1e-11
    assert b["max_penetration"].max() <= 1e-10 * 0.08
    # the force on the floor is the reaction's opposite: downward while the disk is on it
    assert b["force_floor_y"].min() < -0.5 * fscale and b["force_floor_y"].max() <= 1e-9 * fscale


@pytest.mark.parametrize("shape", [
    ("-obstacle_rail_type", "circle", "-obstacle_rail_center", "0,3", "-obstacle_rail_radius", 3, "-obstacle_rail_side", "inside"),
    ("-obstacle_rail_type", "circle", "-obstacle_rail_center", "0,-3", "-obstacle_rail_radius", 3),
])
def test_circle_inside_and_outside(mm, disk_opts, shape):
    """The disk on a circular rail from inside (the circle around it) and on a circular bump from
    outside: no penetration along each node's own normal, the balance closes, the Coulomb residual
    is at solver level, and the rail carries the disk's impact downward."""
    r = run_opts(mm, disk_opts, "-obstacles", "rail", *shape, *TIGHT, np_=2)
    h = r.history
    assert h["active"].max() >= 3
    assert h["max_penetration"].max() <= 1e-10 * 0.08
    assert h["balance_residual"].max() <= 1e-12
    assert h["coulomb_residual"].max() <= 1e-9
    assert h["force_rail_y"].min() < -0.5 * h["force_normal"].max()


# a rounded rectangle whose top face is the plane y = 0 left of x = -0.2, where its rounded corner
# (radius 0.5, centre (-0.2, -0.5)) begins: the disk lands on the rounding
BOX = ("-obstacle_block_type", "box", "-obstacle_block_center", "-1.2,-1", "-obstacle_block_half_sizes", "1.5,1", "-obstacle_block_radius", 0.5)


def test_disk_on_a_rounded_box_corner(mm, disk_opts):
    """The disk thrown onto the rounded corner of a box (type box, 2D: a rounded rectangle): no
    penetration along each node's own normal, the energy balance at round-off, the Coulomb residual at
    solver level; the rounding pushes the disk down and to the right (its normal leans to +x there),
    and 1 rank and 2 give the same history."""
    a = run_opts(mm, disk_opts, "-obstacles", "block", *BOX, *TIGHT, np_=1, name="one").history
    b = run_opts(mm, disk_opts, "-obstacles", "block", *BOX, *TIGHT, np_=2, name="two").history
    fscale = a["force_normal"].max()
    assert a["active"].max() >= 3 and a["slipping"].max() > 0
    assert a["max_penetration"].max() <= 1e-10 * 0.08
    assert a["balance_residual"].max() <= 1e-12
    escale = np.abs(a["total"]).max()
    works = a["work_ext"] + a["work_contact"] + a["work_friction"]
    assert np.abs(a["total"] - a["total"][0] - works).max() <= 1e-10 * escale
    assert a["coulomb_residual"].max() <= 1e-9
    assert a["force_block_y"].min() < -0.5 * fscale and a["force_block_x"].min() < -0.05 * fscale
    for c in ["kinetic", "elastic", "total", "work_contact", "work_friction"]:
        assert np.abs(a[c] - b[c]).max() <= 1e-8 * escale, c
    for c in ["force_normal", "force_tangential", "force_block_x", "force_block_y"]:
        assert np.abs(a[c] - b[c]).max() <= 1e-8 * fscale, c
    assert np.array_equal(a["active"], b["active"])


@pytest.mark.parametrize("extra,message", [
    (("-obstacles", "bowl", "-obstacle_bowl_type", "circle", "-obstacle_bowl_center", "0,3", "-obstacle_bowl_radius", 0), "-obstacle_bowl_radius 0. must be > 0"),
    (("-obstacles", "floor", "-obstacle_floor_point", "0,0", "-obstacle_floor_normal", "0,0"), "-obstacle_floor_normal is the zero vector"),
    (("-obstacles", "floor", "-obstacle_floor_type", "cone"), "-obstacle_floor_type cone is not a known obstacle type: use plane|sphere|circle|cylinder|box"),
    (("-obstacles", "ball", "-obstacle_ball_type", "sphere", "-obstacle_ball_center", "0,0", "-obstacle_ball_radius", 1), "Obstacle ball is a sphere, a 3D shape, but the mesh is 2D: use type circle"),
    (("-obstacles", "floor", "-obstacle_floor_point", "0,0", "-obstacle_floor_normal", "0,1", "-obstacle_floor_radius", 1), "-obstacle_floor_radius does not apply to an obstacle of type plane"),
    (("-obstacles", "rail", "-obstacle_rail_type", "circle", "-obstacle_rail_center", "0,0", "-obstacle_rail_radius", 0.5), "The initial state penetrates the obstacle \"rail\""),
    (("-obstacles", "rail", "-obstacle_rail_type", "circle", "-obstacle_rail_center", "0,1", "-obstacle_rail_radius", 3, "-obstacle_rail_side", "middle"), "-obstacle_rail_side middle: use outside or inside"),
    (("-obstacles", "block", *BOX[:-2], "-obstacle_block_radius", 2), "-obstacle_block_radius 2. is larger than the smallest of -obstacle_block_half_sizes (1.): the rounding must fit inside the box"),
    (("-obstacles", "block", *BOX, "-obstacle_block_side", "inside"), "-obstacle_block_side inside does not apply to an obstacle of type box"),
    (("-obstacles", "block", *BOX, "-obstacle_block_normal", "0,1"), "-obstacle_block_normal does not apply to an obstacle of type box"),
    (("-obstacles", "block", *BOX, "-obstacle_block_half_sizes", "1,0"), "-obstacle_block_half_sizes entry 1 is 0.: each must be > 0"),
    (("-obstacles", "block", *BOX[:4], *BOX[6:]), "Obstacle block (type box) needs -obstacle_block_half_sizes, 2 entries"),
])
def test_bad_obstacles_are_refused_by_name(mm, disk_opts, extra, message):
    r = run_opts(mm, disk_opts, *extra, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-1500:]


def test_named_and_legacy_plane_together_are_refused(mm):
    r = mm("d1_disk", "-obstacles", "floor", "-obstacle_floor_point", "0,0", "-obstacle_floor_normal", "0,1", np_=0, check=False)
    assert r.returncode != 0 and "-obstacle_point/-obstacle_normal were both given" in r.output
