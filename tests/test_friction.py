"""Coulomb friction: the shell friction loop around the exact contact VI."""
import numpy as np
import pytest

from conftest import run


@pytest.fixture(scope="module")
def d1f(tmp_path_factory):
    return run("d1_disk", tmp_path_factory.mktemp("d1f"), "-mu", 0.2, "-output_every", 0, np_=2)


def test_d1_friction_energy_is_the_recorded_friction_work(d1f):
    h = d1f.history
    assert h["balance_residual"].max() <= 1e-8
    assert h["coulomb_residual"].max() <= 1e-8
    assert h["max_penetration"].max() <= 1e-9 * 0.08
    # friction dissipates: W_f <= 0 and never increases, and E - W_ext - W_c - W_f is conserved
    assert h["work_friction"][-1] < -0.05 and np.all(np.diff(h["work_friction"]) <= 1e-14)
    audit = h["total"] - h["work_ext"] - h["work_contact"] - h["work_friction"]
    assert np.abs(audit - audit[0]).max() <= 1e-10 * h["total"][0]
    # where contact persists (no node switches) the energy changes by exactly the friction work
    dE, dWf = np.diff(h["total"]), np.diff(h["work_friction"])
    steady = (h["switched"][1:] == 0) & (h["active"][1:] > 0)
    assert steady.sum() > 50
    assert np.abs(dE[steady] - dWf[steady]).max() <= 1e-10 * h["total"][0]
    assert h["slipping"].max() > 0 and h["friction_its"].max() > 1


def test_d1_friction_spins_the_disk(d1f):
    """Moving in +x, the disk is dragged back at its lowest point: it leaves spinning clockwise
    (L_z < 0), slower, and bouncing."""
    h = d1f.history
    assert h["active"][-1] == 0 and h["vcm_y"][-1] > 0.9
    assert h["L_z"][0] == pytest.approx(0, abs=1e-12) and h["L_z"][-1] < -0.5
    assert 0 < h["vcm_x"][-1] < 0.45


def test_d1_friction_one_rank_equals_two(d1f, tmp_path):
    h1 = run("d1_disk", tmp_path, "-mu", 0.2, "-output_every", 0, np_=1).history
    h2 = d1f.history
    scale = h2["total"][0]
    for c in ("total", "work_friction", "work_contact", "force_normal", "force_tangential", "L_z", "vcm_x"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-8 * max(scale, np.abs(h2[c]).max()), c
    assert np.array_equal(h1["active"], h2["active"]) and np.array_equal(h1["slipping"], h2["slipping"])


MU, G, V0 = 0.25, 0.02, 0.05


def check_sliding_exact(h, a, v0=V0):
    """u = u_qs + (v0 t + a t^2/2) e_x while sliding, constant reactions, E + D = E0."""
    t = h["time"]
    sliding = v0 + a * t > 0
    x = h["ucm_x"] - h["ucm_x"][0]
    exact = v0 * t + a * t ** 2 / 2
    assert np.abs(x - exact)[sliding].max() <= 1e-8 * np.abs(exact[sliding]).max()
    assert np.abs(h["vcm_x"] - (v0 + a * t))[sliding].max() <= 1e-8 * max(v0, abs(a) * t[-1])
    fn, ft = h["force_normal"][sliding], h["force_tangential"][sliding]
    assert np.abs(fn - fn[0]).max() <= 1e-6 * fn[0] and abs(fn[0] - 0.5 * G) <= 1e-10
    assert np.abs(ft - ft[0]).max() <= 1e-6 * abs(ft[0]) and abs(ft[0] + MU * fn[0]) <= 1e-10
    energy = h["total"] - h["work_ext"] - h["work_friction"]
    scale = max(np.abs(h["total"]).max(), np.abs(h["work_ext"]).max())
    assert np.abs(energy - energy[0]).max() <= 1e-8 * scale
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8
    assert h["slipping"][1:].min() == 21


@pytest.mark.parametrize("E,dt", [(1, 0.05), (100, 0.01)])
def test_f1_sliding_block_is_exact(E, dt, mm):
    check_sliding_exact(mm("f1_block", "-E", E, "-ts_dt", dt, "-output_every", 0).history, -MU * G)


def test_f1_stop_and_stick(mm):
    """gx = 0: the block stops at t = v0/(mu g) = 10 after sliding 0.25, then sticks."""
    h = mm("f1_block", "-E", 100, "-ts_dt", 0.02, "-ts_max_time", 12, "-output_every", 0).history
    t, x = h["time"], h["ucm_x"] - h["ucm_x"][0]
    assert abs(np.interp(11.0, t, x) - 0.25) <= 0.01 * 0.25
    assert np.abs(h["vcm_x"][t >= 10.1]).max() <= 1e-3
    assert h["slipping"][t >= 10.5].max() < 21
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8


def test_f1_supercritical_load_accelerates(mm):
    """gx = 0.01 > mu g from rest: the block accelerates at gx - mu g = 0.005."""
    h = mm("f1_block", "-v0", "0,0", "-gravity", "0.01,-0.02", "-E", 100, "-ts_dt", 0.01, "-output_every", 0).history
    a = h["vcm_x"][-1] / h["time"][-1]
    assert abs(a - 0.005) <= 1e-6 * 0.005
    check_sliding_exact(h, 0.005, v0=0.0)


def test_f1_subcritical_load_does_not_slide(mm):
    """gx = 0.0025 < mu g from rest (loads applied suddenly): the block does not slide; with the
    supercritical load above it has moved 0.06 by the same time."""
    h = mm("f1_block", "-initial_state", "given", "-v0", "0,0", "-gravity", "0.0025,-0.02", "-E", 100, "-ts_dt", 0.01,
           "-output_every", 0).history
    assert abs(h["ucm_x"][-1]) <= 1e-3 and abs(h["vcm_x"][-1]) <= 1e-4
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8


def test_static_sliding_from_rest_needs_a_load_that_overcomes_friction(tmp_path):
    r = run("f1_block", tmp_path, "-v0", "0,0", "-gravity", "0.0025,-0.02", check=False)
    assert r.returncode != 0 and "cannot overcome friction" in r.output
