"""Issue 38, item 4: stiffness damping and the massless contact-normal dofs (docs/method.md section 3,
"Rayleigh damping of the massless dofs"). A cantilever falls onto a plane and is damped to rest
(options/cantilever_rest.opts, -damping_ratio 1 at 2 and 50 Hz). With beta K acting on the massless
dofs, their trapezoidal velocity carried an undamped (-1)^n mode and the contact force alternated
at rest between 0.2258 and 6e-7 (0.021 of the force scale per step), balancing the weight only as
the mean of two rows. With those dofs condensed out of the damping it is steady."""
import numpy as np
import pytest

from conftest import run

WEIGHT = 1.0 * 0.1 * 1.0 * 10  # rho H L g per unit thickness, the clamped nodes' share included


@pytest.mark.parametrize("np_", [1, 2])
def test_contact_force_at_rest_is_steady_and_balances_each_row(tmp_path, np_):
    h = run("cantilever_rest", tmp_path, np_=np_).history
    scale = np.abs(h["total"]).max()
    force = np.abs(h["force_normal"]).max()
    # damped to rest: the kinetic energy has fallen below 1e-20 of the energy scale (1e-24 here)
    assert h["kinetic"][-1] < 1e-20 * scale
    rest = h["time"] >= 1.5
    f = h["force_normal"][rest]
    # steady: step to step within 1e-8 of the force scale (the old scheme: 0.021)
    assert np.abs(np.diff(f)).max() < 1e-8 * force, np.abs(np.diff(f)).max() / force
    assert np.all(h["active"][rest] == h["active"][rest][0]) and h["active"][rest][0] > 0
    # in equilibrium row by row: the plane and the clamp carry the weight at every step
    balance = f + h["reaction_clamp_y"][rest] - WEIGHT
    assert np.abs(balance).max() < 1e-8 * force, np.abs(balance).max() / force
    assert 0.05 * WEIGHT < f[-1] < 0.2 * WEIGHT  # the plane carries part of it (0.1129)
    # the energy identity stays exact, and the damping only dissipates
    assert h["balance_residual"].max() < 1e-10
    assert np.diff(h["work_damping"]).max() <= 1e-14 * scale


def test_stiffness_damping_leaves_rigid_motion_alone(tmp_path):
    """The condensed damping stiffness is zero on rigid motions: the D1 disk in free flight, before it
    reaches the plane, keeps its velocity (0.5, -1) with -damping_stiffness alone, and its damping
    work is round-off."""
    h = run("d1_disk", tmp_path, "-damping_stiffness", 1e-2, "-ts_max_time", 0.008, "-output_every", 0, "-quiet", np_=1).history
    assert np.all(h["active"] == 0)
    assert np.abs(h["vcm_x"] - 0.5).max() < 1e-12 and np.abs(h["vcm_y"] + 1).max() < 1e-12
    assert np.abs(h["work_damping"]).max() < 1e-12 * np.abs(h["total"]).max()
