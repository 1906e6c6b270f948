"""D1 (disk) and D2 (ball) thrown onto a rigid plane: the energy audit, exact contact, frame
invariance and rank independence."""
import numpy as np
import pytest

from conftest import run

COLUMNS = ["kinetic", "elastic", "total", "work_ext", "work_contact", "force_normal", "max_penetration"]


@pytest.fixture(scope="module")
def d1(tmp_path_factory):
    return run("d1_disk", tmp_path_factory.mktemp("d1"), np_=2)


@pytest.fixture(scope="module")
def d2(tmp_path_factory):
    return run("d2_ball", tmp_path_factory.mktemp("d2"), np_=2)


def check_energy_audit(h):
    # the discrete energy identity holds at every step
    assert h["balance_residual"].max() <= 1e-8, h["balance_residual"].max()
    # no penetration beyond solver tolerance
    assert h["max_penetration"].max() <= 1e-12
    assert h["coulomb_residual"].max() <= 1e-8
    # frictionless: E - W_ext changes only at steps where a contact node switches
    dE = np.diff(h["total"] - h["work_ext"])
    steady = h["switched"][1:] == 0
    assert steady.sum() > 0.5 * len(steady)
    assert np.abs(dE[steady]).max() <= 1e-10 * h["total"][0], np.abs(dE[steady]).max()
    assert np.abs(dE[~steady]).max() > 1e-8  # switching does cost energy: the test can see it
    # it bounced: contact happened, was released, and the body goes up
    assert h["active"].max() >= 3 and h["active"][-1] == 0
    vertical = "vcm_y" if "vcm_z" not in h.dtype.names else "vcm_z"
    assert h[vertical][-1] > 0.9


def test_d1_energy_and_contact(d1):
    check_energy_audit(d1.history)


def test_d2_energy_and_contact(d2):
    check_energy_audit(d2.history)


def test_d1_with_gravity_balances_external_work(mm):
    h = mm("d1_disk", "-gravity", "0,-9.81", "-output_every", 0).history
    assert np.abs(h["work_ext"]).max() > 0.01
    assert h["balance_residual"].max() <= 1e-8


def compare(h1, h2, tol=1e-8):
    assert len(h1) == len(h2)
    scale = np.abs(h1["total"]).max()
    for c in COLUMNS:
        assert np.abs(h1[c] - h2[c]).max() <= tol * max(scale, np.abs(h1[c]).max()), c
    assert np.array_equal(h1["active"], h2["active"])


def test_d1_one_rank_equals_two_ranks(d1, mm):
    compare(mm("d1_disk", np_=1, name="np1").history, d1.history)


def test_d2_one_rank_equals_two_ranks(d2, mm):
    compare(mm("d2_ball", np_=1, name="np1").history, d2.history)


def test_d1_tilted_obstacle_frame(d1, mm):
    """The same impact against a plane with a tilted normal: mesh, obstacle and velocity rotated
    together by 0.3 rad about the origin give the same energy history."""
    th = 0.3
    c, s = np.cos(th), np.sin(th)
    n = (-s, c)
    v = (c * 0.5 + s * 1.0, s * 0.5 - c * 1.0)
    h = mm("d1_disk", "-mesh_rotation", th, "-obstacle_normal", "%.17g,%.17g" % n, "-v0", "%.17g,%.17g" % v, np_=2, name="tilted").history
    compare(h, d1.history)
    # and it did not by accident run the axis-aligned case
    assert abs(h["vcm_x"][0] - v[0]) < 1e-12


def test_d2_tilted_obstacle_frame(d2, mm):
    """3D: mesh, plane and velocity rotated together by 0.3 rad about the x axis."""
    th = 0.3
    c, s = np.cos(th), np.sin(th)
    rot = lambda v: (v[0], c * v[1] - s * v[2], s * v[1] + c * v[2])
    fmt = lambda v: ",".join("%.17g" % x for x in v)
    h = mm("d2_ball", "-mesh_rotation", fmt((th, 0, 0)), "-obstacle_normal", fmt(rot((0, 0, 1))), "-v0", fmt(rot((0.5, 0, -1))),
           np_=2, name="tilted").history
    compare(h, d2.history)
    assert abs(h["vcm_y"][0] - rot((0.5, 0, -1))[1]) < 1e-12


@pytest.mark.parametrize("mass", ["standard", "redistributed"])
def test_initial_rigid_rotation(mm, mass):
    """-omega spins the disk about its centre: L_z = I omega with I = m R^2 / 2 (to the lumped
    mass's approximation of the polygon), and the centre of mass does not move. vcm is M*'s: with
    the standard mass, and with the redistributed one, whose moments are M's, a rotation about the
    centre of gravity carries no momentum (the modified mass's would: it lacks the contact nodes'
    normal masses, so its centre is not the disk's)."""
    h = mm("d1_disk", "-v0", "0,0", "-omega", 2.0, "-omega_center", "0,1.01", "-ts_max_steps", 2, "-output_every", 0, "-mass", mass, name=mass).history
    assert abs(h["L_z"][0] - 0.5 * np.pi * 2.0) <= 0.01 * np.pi
    assert abs(h["vcm_x"][0]) <= 1e-12 and abs(h["vcm_y"][0]) <= 1e-12


@pytest.mark.parametrize("case", ["d1_disk", "d2_ball"])
def test_condensed_equals_full_formulation(case, mm):
    """The condensed VI (Delassus operator, one factorization per dt) and the VI on all dofs are
    the same problem: the same history to solver tolerance."""
    hc = mm(case, "-output_every", 0, np_=2, name="condensed").history
    hf = mm(case, "-contact_formulation", "full", "-output_every", 0, np_=2, name="full").history
    compare(hc, hf, tol=1e-10)


def test_contact_disabled_is_linear_elastodynamics(mm):
    """-contact 0: the disk flies through the plane, energy exactly conserved, momentum unchanged."""
    h = mm("d1_disk", "-contact", 0, "-output_every", 0).history
    assert h["active"].max() == 0 and h["force_normal"].max() == 0
    assert np.abs(h["total"] - h["total"][0]).max() <= 1e-10 * h["total"][0]
    assert np.abs(h["vcm_y"] + 1).max() <= 1e-10 and h["ucm_y"][-1] < -0.29


def pulse_roughness(h):
    """Total variation of the contact force over twice its peak: exactly 1 for a single pulse."""
    f = h["force_normal"]
    return np.abs(np.diff(f)).sum() / (2 * f.max())


def test_d1_single_smooth_pressure_pulse(d1, mm):
    """The modified mass gives one smooth contact-force pulse; the standard mass chatters."""
    assert pulse_roughness(d1.history) <= 1.02
    assert pulse_roughness(mm("d1_disk", "-mass", "standard", "-output_every", 0, np_=2, name="standard").history) > 3
