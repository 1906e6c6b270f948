"""Coulomb friction: the friction solvers (-friction_type) on the exact cases and D1, D2."""
import numpy as np
import pytest

from conftest import run, stage_event_count


@pytest.fixture(scope="module")
def d1f(tmp_path_factory):
    return run("d1_friction", tmp_path_factory.mktemp("d1f"), "-output_every", 0, np_=2)


def test_d1_friction_energy_is_the_recorded_friction_work(d1f):
    h = d1f.history
    assert h["balance_residual"].max() <= 1e-8
    assert h["coulomb_residual"].max() <= 1e-8
    assert h["max_penetration"].max() <= 1e-9 * 0.08
    # friction dissipates: W_f <= 0 and never increases, and E - W_ext - W_c - W_f is conserved
    # friction only dissipates: each step's work is <= 0, up to round-off of the energy scale
    assert h["work_friction"][-1] < -0.05 and np.all(np.diff(h["work_friction"]) <= 1e-12 * np.abs(h["total"]).max())
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
    h1 = run("d1_friction", tmp_path, "-output_every", 0, np_=1).history
    h2 = d1f.history
    scale = h2["total"][0]
    for c in ("total", "work_friction", "work_contact", "force_normal", "force_tangential", "L_z", "vcm_x"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-8 * max(scale, np.abs(h2[c]).max()), c
    assert np.array_equal(h1["active"], h2["active"]) and np.array_equal(h1["slipping"], h2["slipping"])


MU, G, V0 = 0.25, 0.02, 0.05
# the exact cases stay exact with every friction solver
SOLVERS = ("newton", "fixedpoint")


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


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("E,dt", [(1, 0.05), (100, 0.01)])
def test_f1_sliding_block_is_exact(E, dt, solver, mm):
    check_sliding_exact(mm("f1_block", "-E", E, "-ts_dt", dt, "-output_every", 0, "-friction_type", solver).history, -MU * G)


@pytest.mark.parametrize("E,dt", [(1, 0.05), (100, 0.01)])
def test_f1_sliding_block_is_exact_with_active_set(E, dt, mm):
    """The active-set formulation's Coulomb iteration (no Delassus operator) on F1: exact. Its CG
    stops at -contact_tol of ||b||, which the inertia 4/dt^2 M* u dominates: over the 500 steps of
    dt = 0.01 the velocity drifts by 1.6e-8 of v0 at 1e-13 and 1.8e-9 at 1e-14 (a factorization of K~,
    -contact_K_pc_type lu, 3.4e-10), so the test runs at 1e-14."""
    check_sliding_exact(mm("f1_block", "-E", E, "-ts_dt", dt, "-output_every", 0, "-contact_formulation", "active_set",
                           "-contact_tol", "1e-14").history, -MU * G)


@pytest.mark.parametrize("solver", SOLVERS)
def test_f1_stop_and_stick(solver, mm):
    """gx = 0: the block stops at t = v0/(mu g) = 10 after sliding 0.25, then sticks."""
    h = mm("f1_block", "-E", 100, "-ts_dt", 0.02, "-ts_max_time", 12, "-output_every", 0, "-friction_type", solver).history
    t, x = h["time"], h["ucm_x"] - h["ucm_x"][0]
    assert abs(np.interp(11.0, t, x) - 0.25) <= 0.01 * 0.25
    assert np.abs(h["vcm_x"][t >= 10.1]).max() <= 1e-3
    assert h["slipping"][t >= 10.5].max() < 21
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8


@pytest.mark.parametrize("solver", SOLVERS)
def test_f1_supercritical_load_accelerates(solver, mm):
    """gx = 0.01 > mu g from rest: the block accelerates at gx - mu g = 0.005."""
    h = mm("f1_block", "-v0", "0,0", "-gravity", "0.01,-0.02", "-E", 100, "-ts_dt", 0.01, "-output_every", 0,
           "-friction_type", solver).history
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
    r = run("f1_block", tmp_path, "-v0", "0,0", "-gravity", "0.0025,-0.02", np_=0, check=False)
    assert r.returncode != 0 and "cannot overcome friction" in r.output


def test_f2_friction_iterations_grow_with_dt(mm):
    """F2: the same block, friction switched on suddenly (u = 0 under gravity, sliding at v0): the
    paper's fixed point needs more iterations, and contracts less, as c_p dt / h grows; every step
    ends with the Coulomb law satisfied."""
    c_p, h = 1.16024, 0.05
    its, rates = [], []
    for ratio in (0.5, 1, 4):
        hist = mm("f1_block", "-initial_state", "given", "-ts_dt", ratio * h / c_p, "-ts_max_steps", 15,
                  "-output_every", 0, "-friction_type", "fixedpoint", name="f2_%g" % ratio).history
        assert hist["coulomb_residual"][1:].max() <= 1e-8
        assert hist["balance_residual"].max() <= 1e-8
        its.append(hist["friction_its"][1:16].mean())
        rates.append(hist["contraction"].max())
    assert its[0] <= its[1] <= its[2], its
    assert rates[0] < rates[1] < rates[2] < 1, rates


def test_nonconvergent_friction_loop_retries_with_smaller_dt(mm):
    """mu = 10 at c_p dt / h_c' = 11, the paper's fixed point held to 3 threshold updates: it cannot
    converge in 3 at that dt; the step is retried with smaller dt (TSAdapt's
    -ts_adapt_scale_solve_failed), where it contracts faster, until it converges, and the run
    completes."""
    r = mm("f1_block", "-initial_state", "given", "-mu", 10, "-ts_dt", 16 * 0.05 / 1.16024, "-ts_max_steps", 5,
           "-output_every", 0, "-friction_type", "fixedpoint", "-friction_snes_max_it", 3)
    h = r.history
    assert "step rejected at t = 0" in r.output and "contraction factor" in r.output
    assert len(h) == 6 and h["dt"][1] < 0.02
    assert h["coulomb_residual"][1:].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8


@pytest.mark.parametrize("formulation,keep", [("condensed", 1), ("condensed", 0), ("active_set", 1)])
def test_rejection_then_growth_refactors_at_most_once(mm, formulation, keep):
    """The step at -ts_dt is rejected (the fixed point held to 3 updates cannot converge there) and
    retried at dt/4, which converges. The growback adaptor grows dt back after 5 accepted steps; the
    grown step is rejected again, and each such rejection doubles the wait (5, then 10): 3 rejections
    in 25 steps, not one every other step. With the kept factor, the whole run factors K~ once in its
    time steps (for dt/4: going back and forth to -ts_dt swaps factors, MMKtReuse); without it
    (-contact_K_keep 0), every change of dt refactors. The active-set formulation keeps K~ and its PC
    the same way."""
    dt = 6.73242e-4
    r = mm("f1_block", "-initial_state", "given", "-mu", 10, "-ts_dt", dt, "-ts_max_steps", 25, "-output_every", 0,
           "-friction_type", "fixedpoint", "-friction_snes_max_it", 3, "-contact_K_keep", keep, "-contact_formulation", formulation,
           "-log_view", name=f"{formulation}{keep}")
    h = r.history
    times = [float(l.split("t = ")[1].split(":")[0]) for l in r.output.splitlines() if "step rejected at t =" in l]
    steps = [int(np.argmin(np.abs(h["time"] - t))) for t in times]
    assert steps == [0, 6, 17], steps  # waits of 5 and 10 accepted steps before dt grows
    assert np.allclose(h["dt"][1:], dt / 4, rtol=1e-12)
    assert h["coulomb_residual"][1:].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8
    factors = stage_event_count(r.output, "MM time steps", "MMAssemble")
    if keep:
        assert factors == 1 and stage_event_count(r.output, "MM time steps", "MMKtReuse") == 5
    else:
        assert factors == 5


def test_nonconvergent_friction_loop_stops_at_the_dt_floor(tmp_path):
    """With the floor -ts_adapt_dt_min above the dt that would converge, the run stops with the
    time, the last dt, the contraction factor and c_p dt / h_c', and what it wrote stays readable."""
    r = run("f1_block", tmp_path, "-initial_state", "given", "-mu", 10, "-ts_dt", 16 * 0.05 / 1.16024,
            "-ts_adapt_dt_min", 0.1, "-output_every", 1, "-friction_type", "fixedpoint", "-friction_snes_max_it", 3,
            np_=0, check=False)
    assert r.returncode != 0
    for m in ("The friction loop does not converge at t = 0", "last dt = 0.172", "contraction factor", "c_p dt / h_c' = 2.8", "-ts_adapt_dt_min 0.1"):
        assert m in r.output, m
    h = r.history
    assert len(h) == 1 and h["step"][0] == 0 and h["total"][0] > 0
    with r.fields() as f:
        assert f["vertex_fields/displacement_displacement"].shape[0] == 1


@pytest.fixture(scope="module")
def d2f(tmp_path_factory):
    return run("d2_ball", tmp_path_factory.mktemp("d2f"), "-mu", 0.2, "-output_every", 0, np_=2)


def test_d2_friction_energy_spin_and_ranks(d2f, tmp_path):
    """3D: the isotropic Coulomb disk, solved by the default semismooth Newton solver."""
    h = d2f.history
    assert h["balance_residual"].max() <= 1e-8 and h["coulomb_residual"].max() <= 1e-8
    assert h["max_penetration"].max() <= 1e-9 * 0.24
    audit = h["total"] - h["work_ext"] - h["work_contact"] - h["work_friction"]
    assert np.abs(audit - audit[0]).max() <= 1e-10 * h["total"][0]
    assert h["work_friction"][-1] < -0.03 and h["slipping"].max() > 0
    # moving along +x, dragged back at its lowest point: it spins about +y, and leaves
    assert h["L_y"][-1] > 0.5 and abs(h["L_x"][-1]) < 0.05 * h["L_y"][-1] and h["active"][-1] == 0
    h1 = run("d2_ball", tmp_path, "-mu", 0.2, "-output_every", 0, np_=1).history
    for c in ("total", "work_friction", "force_tangential", "L_y"):
        assert np.abs(h1[c] - h[c]).max() <= 1e-8 * max(h["total"][0], np.abs(h[c]).max()), c


@pytest.mark.parametrize("solver", SOLVERS + ("active_set",))
def test_f1_box_3d_slides_along_its_velocity(solver, mm):
    """F1 in 3D: a box launched at 30 degrees to x slides along its velocity, whatever the mesh's
    axes, and decelerates at mu g: the isotropic disk, not a square. active_set: that formulation's
    own Coulomb iteration."""
    how = ("-contact_formulation", "active_set", "-contact_tol", "1e-13") if solver == "active_set" else ("-friction_type", solver)
    h = mm("f1_box", "-output_every", 0, *how, np_=2).history
    t = h["time"]
    direction = np.arctan2(h["vcm_y"], h["vcm_x"])
    assert np.abs(direction - np.pi / 6).max() <= 1e-6
    speed = np.hypot(h["vcm_x"], h["vcm_y"])
    assert np.abs(speed - (0.05 - MU * G * t)).max() <= 1e-6 * 0.05
    assert np.abs(h["force_tangential"] - MU * h["force_normal"]).max() <= 1e-8 * h["force_normal"][0]
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8
