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
