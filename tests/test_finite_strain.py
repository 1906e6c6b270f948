"""Finite strain (-elasticity svk, neohookean; docs/method.md section 13): the total Lagrangian P1 force,
the energy-momentum step, the Cauchy stress of the current configuration. Each tolerance is against the
case's physical scale: its energy, force, momentum, or the strain it is given."""
import os
import re

import numpy as np
import pytest

from conftest import ROOT, run, physical_scales

E, NU = 1000.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))  # plane strain
DISK_CENTRE = (0.0, 1.01)
MESH_DISK = os.path.join(ROOT, "meshes", "disk.msh")


def dead_pressure(law, s):
    """The dead pressure p (on the reference normals) that holds the disk at the uniform stretch F = s I
    (plane strain), P(F) = -p I, and the Cauchy stress then: in-plane -p / s, and sigma_zz."""
    if law == "svk":
        S, Szz = (LAM + MU) * (s * s - 1), LAM * (s * s - 1)
    elif law == "neohookean":
        S, Szz = MU * (1 - 1 / s ** 2) + LAM * 2 * np.log(s) / s ** 2, LAM * 2 * np.log(s)
    else:  # linear: sigma(eps), eps = (s - 1) I in the plane
        return -(2 * LAM + 2 * MU) * (s - 1), (2 * LAM + 2 * MU) * (s - 1), LAM * 2 * (s - 1)
    p = -s * S
    return p, S, Szz / s ** 2  # sigma = F S F^T / J, J = s^2


def disk(tmp_path, law, *extra, np_=1, name="out"):
    return run(os.path.join(ROOT, "options", "d1_disk.opts"), tmp_path, "-elasticity", law, *extra, np_=np_, name=name)


@pytest.mark.parametrize("law", ["svk", "neohookean", "linear"])
def test_homogeneous_compression_stays_and_its_stress_is_exact(tmp_path, law):
    """The disk compressed to F = 0.95 I and held there by the dead pressure P(F) = -p I that each law needs
    (a different p per law: the laws differ at 5% strain): a static solution, so after 20 steps every
    vertex is where it started and at rest, and the Cauchy stress is the law's at every vertex."""
    s = 0.95
    p, sig, szz = dead_pressure(law, s)
    B = s - 1
    r = disk(tmp_path, law, "-contact", 0, "-v0", "0,0", "-pressure", "contact,upper", "-pressure_contact_value", p,
             "-pressure_upper_value", p, "-u0_gradient", f"{B},0,0,{B}", "-u0_offset", f"{-B * DISK_CENTRE[0]},{-B * DISK_CENTRE[1]}",
             "-ts_max_steps", 20, "-ts_max_time", 1, "-output_every", 20)
    with r.fields() as f:
        X = f["geometry/vertices"][:]
        u = f["vertex_fields/displacement_displacement"][-1]
        v = f["vertex_fields/velocity_displacement"][-1]
        st = f["vertex_fields/stress_stress"][-1]
    u_exact = B * (X - np.array(DISK_CENTRE))
    c_p = np.sqrt((LAM + 2 * MU) / 1.0)
    assert np.abs(u - u_exact).max() <= 1e-10 * abs(B)          # of the imposed displacement (R = 1)
    assert np.abs(v).max() <= 1e-10 * abs(B) * c_p                # of the strain's wave velocity
    assert np.abs(st[:, 0] - sig).max() <= 1e-10 * abs(p) and np.abs(st[:, 3] - sig).max() <= 1e-10 * abs(p)
    assert np.abs(st[:, 1]).max() <= 1e-10 * abs(p) and np.abs(st[:, 5] - szz).max() <= 1e-10 * abs(p)
    if law != "linear":  # a compression of 5% is where the laws part: neither is the linear one
        p_lin = dead_pressure("linear", s)[0]
        assert abs(p - p_lin) > 0.05 * abs(p_lin)


@pytest.mark.parametrize("law", ["svk", "neohookean"])
def test_spinning_disk_keeps_energy_and_angular_momentum(tmp_path, law):
    """The disk (R = 1, E = 1000, rho = 1) spinning freely at omega = 1 about its centre of mass for two turns:
    the balance residual at most 1e-10 at every step, the angular momentum L_z constant to 1e-9, the
    momentum zero, and the largest (Green) strain the centrifugal stretch, at most 5e-3 (rho omega^2 R^2 / E
    = 1e-3). The linear model cannot turn: it keeps the velocity of an infinitesimal rotation and grows."""
    r = disk(tmp_path, law, "-contact", 0, "-v0", "0,0", "-omega0", 1, "-ts_dt", 0.05,
             "-ts_max_time", 4 * np.pi, "-output_every", 1000)
    h = r.history
    assert len(h) >= 250 and h["time"][-1] == pytest.approx(4 * np.pi, rel=1e-12)
    assert h["balance_residual"].max() <= 1e-10
    L = h["L_z"]
    assert L[0] > 1.5 and np.abs(L - L[0]).max() <= 1e-9 * L[0]
    scales = physical_scales(r.outdir, os.path.join(ROOT, "options", "d1_disk.opts"), h)
    assert np.abs(np.c_[h["P_x"], h["P_y"]]).max() <= 1e-10 * scales["momentum"]
    strain = float(r.output.split("largest strain ")[1].split()[0])
    assert 2e-4 <= strain <= 5e-3
    assert "finite strain:" in r.output
    # the linear model keeps the velocity of an infinitesimal rotation, whose strain is zero: the disk
    # grows to radius sqrt(1 + (omega t)^2) = 12.6 in two turns; the finite-strain disk stays within 2R
    lin = disk(tmp_path, "linear", "-contact", 0, "-v0", "0,0", "-omega0", 1, "-ts_dt", 0.05,
               "-ts_max_time", 4 * np.pi, "-output_every", 1000, name="linear")
    for out, lo, hi in ((r, 0, 2.01), (lin, 4 * np.pi - 0.1, 4 * np.pi + 0.1)):
        with out.fields() as f:
            u = f["vertex_fields/displacement_displacement"][-1]
        assert lo <= np.linalg.norm(u, axis=1).max() <= hi


@pytest.mark.parametrize("law", ["svk", "neohookean"])
def test_small_amplitude_limit_is_the_linear_model(tmp_path, law):
    """The disk resting on the plane (gap 0) thrown down with -v0 scaled by 1e-6: strains of 1e-7, where
    every law is the linear one, so its history (energies, contact force) equals the linear run's to
    1e-5 of the scales; the contact force is there, so the contact is active."""
    common = ("-obstacle_point", "0,0.01", "-v0", "0.5e-6,-1e-6", "-ts_max_time", 0.1, "-output_every", 0)
    lin = disk(tmp_path, "linear", *common, name="linear")
    fin = disk(tmp_path, law, *common, name=law)
    hl, hf = lin.history, fin.history
    scales = physical_scales(lin.outdir, os.path.join(ROOT, "options", "d1_disk.opts"), hl)
    assert len(hl) == len(hf) and hl["force_normal"].max() > 0
    for c in ("kinetic", "elastic", "total", "work_contact"):
        assert np.abs(hf[c] - hl[c]).max() <= 1e-5 * scales["energy"], c
    # the finite-strain step's contact force is its mean over the step (docs/method.md section 13), the
    # linear scheme's the end value of the trapezoidal pair: the mean of that pair is the same force
    for c in ("force_normal", "force_tangential"):
        assert np.abs(hf[c][1:] - 0.5 * (hl[c][1:] + hl[c][:-1])).max() <= 1e-5 * scales["force"], c
    assert np.abs(hf["vcm_y"] - hl["vcm_y"]).max() <= 1e-5 * scales["velocity"]


@pytest.fixture(scope="module")
def d1_friction(tmp_path_factory):
    """D1 with friction (options/d1_friction.opts) with svk on 1 and 2 ranks, and linear on 1"""
    tmp = tmp_path_factory.mktemp("d1f")
    runs = {n: run("d1_friction", tmp, "-elasticity", "svk", "-output_every", 15, np_=n, name=f"svk{n}") for n in (1, 2)}
    runs["linear"] = run("d1_friction", tmp, "-output_every", 0, name="linear")
    return runs


def test_d1_friction_svk_exact(d1_friction):
    """D1 with friction and svk: the balance at most 1e-10 at every step, no penetration beyond 1e-10 h_c',
    the Coulomb residual at solver level, the peak contact force within 15% of the linear run's."""
    h, hl = d1_friction[1].history, d1_friction["linear"].history
    out = d1_friction[1].output
    h_c = float(out.split("(h_c' ")[1].split(")")[0])
    assert h["balance_residual"].max() <= 1e-10
    assert h["max_penetration"].max() <= 1e-10 * h_c
    assert h["coulomb_residual"].max() <= 1e-8
    assert h["slipping"].max() > 0 and h["work_friction"][-1] < 0
    peak, peak_lin = h["force_normal"].max(), hl["force_normal"].max()
    assert abs(peak - peak_lin) <= 0.15 * peak_lin
    assert "finite strain:" in out


def test_active_set_svk_step_is_exact(tmp_path):
    """The D2 ball (H = 0.1) with friction mu 0.2, svk, on the active set: every step's balance within 5e-12 of the
    energy scale (3.2e-11 before its iterates solved for the increment and its audit saw the inner solve's residual:
    the CG's tolerance, relative to a right-hand side with 4/dt^2 M* u^n in it, set the step's floor), the same
    motion as the condensed formulation's to 1e-9 of the energy scale."""
    common = ("-mesh", "meshes/ball10.msh", "-ts_dt", 4e-3, "-ts_max_steps", 20, "-mu", 0.2, "-elasticity", "svk", "-output_every", 0)
    a = run("d2_ball", tmp_path, *common, "-contact_formulation", "active_set", name="as")
    c = run("d2_ball", tmp_path, *common, "-contact_formulation", "condensed", name="cond")
    ha, hc = a.history, c.history
    scale = physical_scales(c.outdir, "d2_ball", hc)["energy"]
    assert ha["balance_residual"].max() <= 5e-12
    assert ha["active"].max() > 0 and ha["slipping"].max() > 0
    for col in ("kinetic", "elastic", "work_friction"):
        assert np.abs(ha[col] - hc[col]).max() <= 1e-9 * scale, col


def test_active_set_svk_retry_starts_from_the_step_start(tmp_path):
    """The same ball at c_p dt / h_c' 5.9 (dt 0.016) rolling out of its impact: steps whose iteration
    diverges are rejected and retried. A retry must start from the step's start, not from the failed
    try's iterates: its tangent (rebuilt at a diverging iterate) and its friction thresholds (1e23 on the
    H 0.07 ball) were kept, the retries' right-hand sides were 1e10 times the forces, and a stalled
    iterate was accepted with a balance of 5e-4 (H 0.1) and 0.15 (H 0.07), stopping the run at the
    energy audit. Every accepted step within 5e-12 of the energy scale."""
    r = run("d2_ball", tmp_path, "-mesh", "meshes/ball10.msh", "-ts_dt", 0.016, "-ts_max_time", 0.32, "-mu", 0.2,
            "-elasticity", "svk", "-contact_formulation", "active_set", "-output_every", 0)
    assert "step rejected" in r.output  # the retry path is what is tested
    assert r.history["balance_residual"].max() <= 5e-12
    assert r.history["time"][-1] >= 0.32 - 1e-9
    # the first rejection, with the unclamped tangent, makes the run clamp it from then on
    assert re.search(r"finite strain: .*clamped from step \d+ \(a step with the unclamped tangent was rejected\)", r.output), r.output[-1500:]


def test_the_clamp_fallback_restarts_bit_for_bit(tmp_path):
    """The same run checkpointed at step 25, after its fallback to the clamped tangent (step 19), and
    continued by -restart: the checkpoint keeps the fallback (tangent_clamp_step), and the continued
    history is the uninterrupted run's, byte for byte."""
    common = ("-mesh", "meshes/ball10.msh", "-ts_dt", 0.016, "-ts_max_time", 0.32, "-mu", 0.2, "-elasticity", "svk",
              "-contact_formulation", "active_set", "-output_every", 0)
    whole = run("d2_ball", tmp_path, *common, name="whole")
    first = run("d2_ball", tmp_path, *common, "-checkpoint_every", 25, "-ts_max_steps", 25, name="first")
    assert "clamped from step" in first.output
    cont = run("d2_ball", tmp_path, *common, "-restart", first.outdir, "-output_dir", first.outdir, name="first")
    assert open(os.path.join(cont.outdir, "history.csv")).read() == open(os.path.join(whole.outdir, "history.csv")).read()


def test_d1_friction_svk_two_ranks_is_one(d1_friction):
    """1 and 2 ranks: every energy and work equal to 1e-8 of the energy scale, the contact force to 1e-8 of its scale"""
    h1, h2 = d1_friction[1].history, d1_friction[2].history
    scales = physical_scales(d1_friction[1].outdir, "d1_friction", h1)
    assert len(h1) == len(h2)
    for c in ("kinetic", "elastic", "total", "work_contact", "work_friction"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-8 * scales["energy"], c
    assert np.abs(h1["force_normal"] - h2["force_normal"]).max() <= 1e-8 * scales["force"]


def test_restart_across_rank_counts_svk(tmp_path, d1_friction):
    """svk checkpointed at step 75 on 1 rank and continued on 2: the history equals the straight 2-rank
    run's to 1e-8 of the energy and force scales"""
    first = run("d1_friction", tmp_path, "-elasticity", "svk", "-ts_max_time", 0.15, "-checkpoint_every", 75,
                "-output_every", 15, name="first")
    cont = run("d1_friction", tmp_path, "-elasticity", "svk", "-restart", first.outdir, "-output_dir", first.outdir,
               "-output_every", 15, np_=2, name="first")
    h, ref = cont.history, d1_friction[2].history
    scales = physical_scales(d1_friction[2].outdir, "d1_friction", ref)
    assert len(h) == len(ref)
    for c in ("kinetic", "elastic", "total", "work_friction"):
        assert np.abs(h[c] - ref[c]).max() <= 1e-8 * scales["energy"], c
    assert np.abs(h["force_normal"] - ref["force_normal"]).max() <= 1e-8 * scales["force"]


def test_finite_strain_refuses_what_it_does_not_support(tmp_path):
    """The static sliding start is linear-only: refused with the option named (64). The static start
    runs with the finite-strain laws (tests/test_static_finite.py), but the D1 disk above its plane has
    no static state: nothing holds it, and the run stops in one line saying so (65)"""
    bad = run(os.path.join(ROOT, "options", "d1_disk.opts"), tmp_path, "-elasticity", "svk", "-initial_state", "static_sliding",
              "-ts_max_steps", 1, name="sliding", np_=0, check=False)
    assert bad.returncode == 64 and "-initial_state static_sliding" in bad.output, bad.output[-1500:]
    bad = run(os.path.join(ROOT, "options", "d1_disk.opts"), tmp_path, "-elasticity", "svk", "-initial_state", "static",
              "-ts_max_steps", 1, name="static", np_=0, check=False)
    assert bad.returncode == 65 and "not well posed" in bad.output and "-initial_state" in bad.output, bad.output[-1500:]


@pytest.mark.parametrize("np_", [1, 2])
def test_two_balls_svk_contact_pairs(tmp_path, np_):
    """Two svk balls against each other through a contact pair (options/two_balls.opts, the tangent rebuilt every
    step so that the pairs' N^T K_t N path runs): the momentum stays zero to 1e-12 of the scale, the balance at
    1e-10, no penetration beyond 1e-10 h_c'; the master points are those of the reference mesh (small sliding)"""
    r = run("two_balls", tmp_path, "-elasticity", "svk", "-nonlinear_tangent", "step", "-ts_max_time", 0.2, "-output_every", 0, np_=np_)
    h = r.history
    h_c = float(r.output.split("(h_c' ")[1].split(")")[0])
    scales = physical_scales(r.outdir, "two_balls", h)
    assert h["force_normal"].max() > 0.1 * scales["force"]
    assert np.abs(np.c_[h["P_x"], h["P_y"], h["P_z"]]).max() <= 1e-12 * scales["momentum"]
    assert h["balance_residual"].max() <= 1e-10 and h["max_penetration"].max() <= 1e-10 * h_c


def test_support_reaction_of_a_stretched_bar_is_its_load(tmp_path):
    """A bar (nu = 0, E = 1) held by a roller at x = 0 and stretched by 10% (F = diag(1.1, 1)) under the dead
    traction that svk needs there, t = P_xx = s (s^2 - 1)/2 = 0.1155: a static state. It stays at rest, and
    the roller's reaction, from the svk force on the held dofs, balances the traction's resultant exactly
    (to 1e-10 of it); K_D u would give the linear 0.1 instead, 13% off"""
    s = 1.1
    t = s * (s * s - 1) / 2
    r = run("b2_bar", tmp_path, "-elasticity", "svk", "-contact", 0, "-v0", "0,0", "-E", 1, "-nu", 0, "-dirichlet", "left",
            "-dirichlet_left_components", 0, "-traction", "right", "-traction_right_value", f"{t},0",
            "-u0_gradient", f"{s - 1},0,0,0", "-ts_max_steps", 20, "-output_every", 0)
    h = r.history
    load = h["load_x"][0]
    assert load > 0 and np.abs(h["reaction_left_x"] + load).max() <= 1e-10 * load
    assert h["kinetic"].max() <= 1e-12 * h["elastic"][0]  # at rest: no motion beyond 1e-6 of the strain's wave velocity
