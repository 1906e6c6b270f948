"""Contact between two elastic bodies (contact pairs, node to segment and node to facet) and nodes
against two obstacles at once (issue 20). Exact answers: the 1D impact of two equal bars, the
symmetry of two equal balls against one ball on a rigid plane, the conservation of momentum."""
import os
import re

import numpy as np
import pytest

from conftest import run

W = 1.0 / 80     # the bars' width (meshes/two_bars.geo)
V0 = 0.01        # each bar's speed, c = 1
DT = 0.01


def contact_window(h):
    on = h["time"][h["active"] > 0]
    return on[0], on[-1]


@pytest.fixture(scope="module")
def bars(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bars")
    return {n: run("two_bars", tmp, *extra, np_=n, name=f"r{n}") for n, extra in ((1, ()), (2, ()))}


def test_two_bars_contact_stress_and_duration(bars):
    """Equal bars at +v and -v, non-matching meshes at the interface (80 against 100 cells, 3 end
    nodes against 4): the interface stays at rest while the waves cross each bar and back, so
    contact lasts 2L/c and carries the stress rho c v."""
    r = bars[1]
    assert "3 nodes (2 facing a master node" in r.output  # non-matching: one node on a segment
    h = r.history
    t0, t1 = contact_window(h)
    assert abs(t0 - 0.25) <= DT + 1e-12          # the gap 0.005 closes at 0.005 / (2 v)
    assert abs((t1 - t0) - 2.0) <= DT + 1e-12    # 2L/c, to one dt
    stress = h["force_p_x"][(h["time"] > t0 + 0.1) & (h["time"] < t1 - 0.1)] / W
    assert abs(np.median(stress) - 1.0 * 1.0 * V0) <= 0.02 * V0
    assert np.abs(stress - V0).max() <= 0.15 * V0  # no spurious oscillation of the contact stress
    # no penetration, the energy balance closed every step
    assert h["max_penetration"].max() <= 1e-12 * W
    assert np.abs(h["balance_residual"]).max() <= 1e-10


def test_two_bars_separate_with_velocities_swapped(bars):
    """After 2L/c the bars leave each other undeformed: the kinetic energy is back (the elastic one
    gone) and the momentum, zero, never moved. The momentum and energy scale is that of one bar."""
    h = bars[1].history
    scale_p = 1.0 * W * 1.0 * V0
    assert np.abs(h["P_x"] - h["P_x"][0]).max() <= 1e-10 * scale_p
    e0 = h["total"][0]
    after = h["time"] > 2.3
    assert np.abs(h["elastic"][after]).max() <= 0.02 * e0
    assert np.abs(h["kinetic"][after] - e0).max() <= 0.02 * e0


def test_two_bars_one_rank_against_two(bars):
    """The pair split across two ranks (METIS puts a bar on each) gives the same run."""
    a, b = bars[1].history, bars[2].history
    scale = np.abs(a["total"]).max()
    for c in ("total", "kinetic", "elastic", "work_contact"):
        assert np.abs(a[c] - b[c]).max() <= 1e-10 * scale, c
    assert np.abs(a["force_p_x"] - b["force_p_x"]).max() <= 1e-10 * W * V0


def test_conforming_bars_reduce_to_node_to_node(tmp_path):
    """Conforming meshes: every slave node faces a master node, its constraint couples it to that
    node alone (weight exactly 1), and the 1D answer holds as for the non-matching pair."""
    r = run("two_bars", tmp_path, "-mesh", "meshes/two_bars_conf.msh", "-ts_dt", "0.0125")
    m = re.search(r"slave a_right, (\d+) nodes \((\d+) facing a master node", r.output)
    assert m and m.group(1) == m.group(2) == "3", r.output[:2000]
    h = r.history
    t0, t1 = contact_window(h)
    assert abs((t1 - t0) - 2.0) <= 0.0125 + 1e-12
    stress = h["force_p_x"][(h["time"] > t0 + 0.1) & (h["time"] < t1 - 0.1)] / W
    assert abs(np.median(stress) - V0) <= 0.02 * V0


def impact(h, col):
    t0, t1 = contact_window(h)
    return t1 - t0, np.abs(h[col]).max()


@pytest.fixture(scope="module")
def balls(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("balls")
    return dict(two=run("two_balls", tmp, name="two"), two2=run("two_balls", tmp, np_=2, name="two2"),
                one=run("ball_plane_x", tmp, name="one"))


def test_two_balls_as_one_ball_on_a_plane(balls):
    """Two equal balls at +v and -v: by symmetry each hits the mid-plane as one ball hits a rigid
    plane. Contact time and peak force against the one-ball run on ball A's own mesh, to 3%."""
    d2, f2 = impact(balls["two"].history, "force_p_x")
    d1, f1 = impact(balls["one"].history, "force_mid_x")
    assert abs(d2 - d1) <= 0.03 * d1, (d2, d1)
    assert abs(f2 - f1) <= 0.03 * f1, (f2, f1)
    assert balls["two"].history["max_penetration"].max() <= 1e-12


def test_two_balls_momentum_and_ranks(balls):
    """No external force: the momentum of the two balls is conserved at every step (the contact
    forces on them are equal and opposite); 2 ranks give the 1-rank energies."""
    h, h2 = balls["two"].history, balls["two2"].history
    m_v = 2 * 4.18879 * 0.5  # the balls' momentum scale, 2 x (4/3 pi) rho v
    for c in ("P_x", "P_y", "P_z"):
        assert np.abs(h[c] - h[c][0]).max() <= 1e-12 * m_v, c
    scale = np.abs(h["total"]).max()
    for c in ("total", "kinetic", "elastic", "work_contact"):
        assert np.abs(h[c] - h2[c]).max() <= 1e-10 * scale, c


def test_two_balls_friction_momentum(tmp_path):
    """An oblique impact with Coulomb friction between the balls: the friction forces are equal and
    opposite too, so the momentum is still conserved to round-off, while friction does work."""
    r = run("two_balls", tmp_path, "-contact_pair_p_mu", "0.3", "-body_a_v0", "0.5,0.3,0",
            "-body_b_v0", "-0.5,-0.3,0", "-ts_max_time", "0.36", np_=2)
    h = r.history
    m_v = 2 * 4.18879 * 0.6
    for c in ("P_x", "P_y", "P_z"):
        assert np.abs(h[c] - h[c][0]).max() <= 1e-12 * m_v, c
    assert h["work_friction"][-1] < -1e-3 * h["total"][0]   # friction dissipates
    assert h["slipping"].max() > 0
    assert h["coulomb_residual"].max() <= 1e-6               # the Coulomb law on the relative slip
    assert np.abs(h["balance_residual"]).max() <= 1e-10
    assert h["max_penetration"].max() <= 1e-12


def test_ball_on_elastic_block(tmp_path):
    """A ball dropped on an elastic block whose base is held: no penetration, the energy balance
    closed, and the block's support takes the force the ball brings."""
    r = run("ball_block", tmp_path, "-ts_max_time", "0.15", np_=2)
    h = r.history
    assert h["active"].max() > 0
    assert h["max_penetration"].max() <= 1e-12
    assert np.abs(h["balance_residual"]).max() <= 1e-10


def test_cube_in_groove_touches_both_walls(tmp_path):
    """A cube dropped into a 90-degree V-groove, damped to rest: its lower edge is within h_c' of
    both walls, so its nodes carry a row for each. No node crosses either wall, the edge nodes end in
    contact with both, and the walls carry m g between them, equally by symmetry."""
    r = run("cube_groove", tmp_path, "-ts_max_time", "1.0", "-damping_mass", "30", np_=2)
    m = re.search(r"corners: (\d+) contact nodes .*? at the last step (\d+) in contact with both", r.output)
    assert m and int(m.group(1)) > 0 and int(m.group(2)) >= 4, r.output[-1500:]
    h = r.history
    assert h["max_penetration"].max() <= 1e-12
    mg = 0.125 * 10.0
    fl, fr = -h["force_left_z"][-1], -h["force_right_z"][-1]
    assert abs(fl + fr - mg) <= 1e-3 * mg
    assert abs(fl - fr) <= 0.02 * mg
    assert fl > 0.4 * mg and fr > 0.4 * mg


def test_pair_input_errors(tmp_path):
    """A pair without its master surface, and a master surface that is also a slave one."""
    r = run("two_bars", tmp_path, "-contact_pair_p_master", "", np_=0, check=False)
    assert r.returncode != 0
    r = run("two_bars", tmp_path, "-contact_pair_p_master", "a_right", np_=0, check=False, name="o2")
    assert r.returncode != 0 and "master node cannot carry a constraint" in r.output, r.output[-800:]
    r = run("two_bars", tmp_path, "-contact_pairs", "p,p", np_=0, check=False, name="o3")
    assert r.returncode != 0 and "-contact_pairs p,p names p twice" in r.output, r.output[-800:]
    r = run("two_bars", tmp_path, "-obstacles", "p", "-obstacle_p_point", "3,0", "-obstacle_p_normal", "-1,0",
            "-contact_boundary", "b_right", np_=0, check=False, name="o4")
    assert r.returncode != 0 and "both name p" in r.output, r.output[-800:]


@pytest.mark.parametrize("formulation,tol", [("full", 1e-9), ("active_set", 1e-5)])
def test_two_bars_every_formulation(bars, tmp_path, formulation, tol):
    """The relative variables make the pair a bound on one dof: the full VI and the active-set
    method solve the same steps as the condensed default (the active set to its CG tolerance)."""
    h = run("two_bars", tmp_path, "-contact_formulation", formulation).history
    ref = bars[1].history
    assert np.abs(h["total"] - ref["total"]).max() <= tol * ref["total"].max()
    assert np.abs(h["force_p_x"] - ref["force_p_x"]).max() <= tol * W * V0


@pytest.mark.parametrize("case,cut,end,np_a,np_b,force", [("two_bars", 1.2, 2.5, 1, 2, "force_p_x"),
                                                         ("cube_groove", 0.2, 0.4, 2, 1, "force_left_z")])
def test_restart_across_ranks(tmp_path, case, cut, end, np_a, np_b, force):
    """A pair's slave rows and a corner's second rows are checkpointed: a run stopped at t = cut and
    continued on another number of ranks ends as the uninterrupted run."""
    ref = run(case, tmp_path, "-ts_max_time", end, "-quiet", np_=np_a, name="ref").history
    run(case, tmp_path, "-ts_max_time", cut, "-quiet", np_=np_a, name="cut")
    h = run(case, tmp_path, "-restart", str(tmp_path / "cut"), "-ts_max_time", end, "-quiet", np_=np_b, name="cut").history
    assert list(h["step"]) == list(ref["step"])
    assert np.array_equal(h["active"], ref["active"]) and np.array_equal(h["switched"], ref["switched"])
    assert np.abs(h["total"] - ref["total"]).max() <= 1e-10 * np.abs(ref["total"]).max()
    assert np.abs(h[force] - ref[force]).max() <= 1e-10 * np.abs(ref[force]).max()
