"""A step accepted by its certificate (docs/method.md section 3, "A step accepted by its
certificate"): the residual of the step's equation does no work over the step and has no resultant
and no moment beyond the round-off of its terms, on every formulation. The active set's CG stops at
-contact_tol on the way; the accepted step is solved again, tighter, until its certificate holds.
Each test runs the active set (the formulation auto picks at these sizes, conftest forces condensed)
and checks an exact property of the scheme to the condensed formulation's round-off."""
import re

import numpy as np
import pytest

from conftest import ROOT, run

AS = ("-contact_formulation", "active_set")


def certificate_line(output):
    m = re.search(r"step certificate: .*?(\d+) solves again.*?(\d+) steps accepted at their residual's floor", output)
    assert m, output[-2000:]
    return int(m.group(1)), int(m.group(2))


@pytest.mark.parametrize("np_", [1, 2])
def test_disk_in_a_bowl_keeps_energy_and_its_angular_momentum_about_the_centre(mm, np_):
    """The disk thrown into a circular bowl, frictionless: every contact force points at the bowl's
    centre (0, 4), so J about it, J_z + 4 P_x, is conserved, and the energy balance holds. With the
    active set at its default -contact_tol the drift of J was 5.6e-9 of J and the balance 1.8e-9;
    the certified steps give 6e-12 and 5e-12, the condensed formulation's 3e-12 and 3e-12."""
    r = mm("disk_bowl", *AS, "-output_every", 0, "-ts_max_time", 0.6, np_=np_)
    h = r.history
    J = h["J_z"] + 4 * h["P_x"]
    assert h["active"].max() > 0  # it hits the wall
    assert np.abs(J - J[0]).max() <= 5e-11 * abs(J[0])
    assert h["balance_residual"].max() <= 5e-11
    resolves, floors = certificate_line(r.output)
    assert resolves >= 1, (resolves, floors)  # the certificate acted: -contact_tol alone was not enough


@pytest.mark.parametrize("dim", [2, 3])
def test_free_fall_is_exact_on_the_active_set(mm, dim):
    """Thrown under gravity above a plane it never reaches, on the active set: the redistributed
    mass's centre follows v0 t + g t^2 / 2 to 1e-10 of its scale, as on the condensed formulation
    (test_mass.py): CG's residual at -contact_tol gave 3.3e-8 (the issue's figure)."""
    G = 9.81
    geo = (("-mesh", "meshes/block.msh", "-contact_boundary", "base", "-obstacle_point", "0,-10", "-obstacle_normal", "0,1")
           if dim == 2 else ("-mesh", "meshes/box.msh", "-contact_boundary", "base", "-obstacle_point", "0,0,-10", "-obstacle_normal", "0,0,1"))
    v0 = (0.3, 0.2) if dim == 2 else (0.3, -0.1, 0.2)
    g = "0,%g" % -G if dim == 2 else "0,0,%g" % -G
    r = mm("d1_disk", *geo, *AS, "-E", 1e4, "-nu", 0.3, "-rho", 1, "-deformation_audit", 0, "-output_every", 0,
           "-gravity", g, "-v0", ",".join(map(str, v0)), "-mass", "redistributed", "-ts_dt", 1e-3, "-ts_max_time", 0.05)
    h = r.history
    t = h["time"]
    for d, a in enumerate("xyz"[:dim]):
        gd = -G if d == dim - 1 else 0.0
        scale = abs(v0[d]) + G * t[-1]
        assert np.abs(h["vcm_" + a] - (v0[d] + gd * t)).max() <= 1e-10 * scale, a
    P = h["P_" + "xyz"[dim - 1]]
    assert np.abs(np.diff(P, 2)).max() <= 1e-12 * np.abs(P).max()


def test_two_bars_exchange_momentum_exactly_on_the_active_set(mm):
    """Two bars impacting (options/two_bars.opts) on the active set: the pair's momentum P = sum M* v,
    zero, stays so to 1e-10 of one bar's momentum rho W L v0 = 1.25e-4 through the impact (2.8e-11
    certified; 8.2e-9 at -contact_tol alone; 3.5e-12 on the condensed formulation, test_two_bodies.py),
    and the energy balance holds."""
    h = mm("two_bars", *AS, "-output_every", 0).history
    assert np.abs(h["P_x"] - h["P_x"][0]).max() <= 1e-10 * 1.25e-4
    assert h["balance_residual"].max() <= 1e-11


def test_without_the_certificate_the_active_set_is_only_as_exact_as_its_tolerance(mm):
    """-step_certificate 0 stops every solve at -contact_tol: at -contact_tol 1e-8 the same bowl
    drifts by orders of magnitude more, which is what the certificate removes (the test above would
    fail). (At the default 1e-11 the uncertified increment's solve drifts 1.6e-11 of J: the
    tolerance applies to the increment's right-hand side, docs/method.md section 3.)"""
    h = mm("disk_bowl", *AS, "-output_every", 0, "-ts_max_time", 0.6, "-step_certificate", 0, "-contact_tol", 1e-8).history
    J = h["J_z"] + 4 * h["P_x"]
    assert np.abs(J - J[0]).max() > 1e-10 * abs(J[0])


def test_certificate_state_survives_a_restart(mm, tmp_path):
    """The certificate carries state from step to step (the last residual, the tightened
    -contact_tol): a checkpoint keeps it, so that an active-set run restarted gives the rows the
    uninterrupted run gave, bit for bit, on 1 rank."""
    full = mm("disk_bowl", *AS, "-output_every", 0, "-ts_max_time", 0.4, name="full").history
    part = mm("disk_bowl", *AS, "-output_every", 0, "-ts_max_time", 0.2, "-checkpoint_every", 50, name="part")
    again = mm("disk_bowl", *AS, "-output_every", 0, "-ts_max_time", 0.4, "-restart", part.outdir, name="part").history
    assert len(again) == len(full)
    for c in ("kinetic", "elastic", "J_z", "P_x", "force_normal"):
        assert np.array_equal(full[c], again[c]), c


def test_increment_removes_the_small_dt_floor(tmp_path):
    """The linear cube spinning onto its plane with -mass standard on the active set (2 ranks): the
    contact-work guard cuts dt to 9.8e-7, where the total displacement's equation cancels 4/dt^2 M* u
    in its residual. Solving for the increment (-step_increments, the default; docs/method.md section 3,
    "The step's unknown"), the balance is 1e-13 (measured 1.0e-13) and at most a step meets a floor;
    solving for u^{n+1}, 61 steps end at their floor and the balance is 1.8e-10."""
    opts = tmp_path / "cube.opts"
    opts.write_text("# the linear cube of tests/test_step_certificate.py\n")
    cube = ("-mesh", "meshes/cube_drop.msh", "-contact_boundary", "skin", "-obstacle_point", "0,0,0",
            "-obstacle_normal", "0,0,1", "-E", 1000, "-nu", 0.3, "-rho", 1, "-omega0", "1,4,0.5",
            "-v0", "0,0,-0.215", "-ts_dt", 1e-3, "-ts_max_time", 0.3, "-mass", "standard",
            "-contact_formulation", "active_set", "-output_every", 0, "-progress_every", 0)
    floors = {}
    for inc in (1, 0):
        r = run(str(opts), tmp_path, *cube, "-step_increments", inc, np_=2, name=f"inc{inc}")
        floors[inc] = int(r.output.split(" steps accepted at their residual's floor")[0].rsplit(" ", 1)[1])
        h = r.history
        assert h["dt"][1:].min() < 1e-5  # the guard's small steps, where the floor lies
        if inc:
            assert h["balance_residual"].max() <= 1e-12
    # how many steps meet a floor depends on the BLAS kernel's rounding (61 and 0 with OpenBLAS's
    # SkylakeX kernel, 39 and 1 with Haswell's): the increment removes nearly all of them
    assert floors[0] > 10 and floors[1] <= floors[0] / 10, floors
