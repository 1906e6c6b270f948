"""-initial_state static with the finite-strain laws (issue 50; docs/method.md section 13, "The static
start in finite strain"): the static equilibrium under the loads at t = 0 by load steps and Newton
with the consistent tangent, the contact exact at every Newton iterate, then the dynamics from it.
A slender cantilever against the elastica and against the rest state of the damped dynamic run, 1
rank against 2; a neo-Hookean block pressed on a plane by a pressure: the plane carries the load,
nothing penetrates, the struck run's balance holds and the unstruck block stays at rest; what is
refused and how a start that cannot be reached stops."""
import re

import numpy as np
import pytest

from test_slender_cantilever import elastica_tip

E, L = 1e5, 1.0
ALPHA = 3  # P L^2 / EI


def tip_traction(t):
    """The end traction (force per unit area, spread over the tip's section) of P L^2 / EI = ALPHA."""
    return ALPHA * E * t**3 / 12 / L**2 / t


def static_cantilever(mm, mesh, t, *extra, np_=1, name="out"):
    """options/slender_cantilever.opts started static under its end load held constant (no ramp)."""
    return mm("slender_cantilever", "-mesh", f"meshes/{mesh}.msh", "-traction_tip_value", f"0,{-tip_traction(t)}",
              "-traction_tip_amplitude", "constant", "-initial_state", "static", "-output_every", 0, *extra, np_=np_, name=name)


def load_steps(output):
    m = re.search(r"-initial_state static \(finite strain\): (\d+) load steps \((\d+) cut\), (\d+) Newton iterations \(per load step: ([\d ]+)\), final residual (\S+) round-offs", output)
    assert m, output[-2000:]
    return int(m.group(1)), [int(k) for k in m.group(4).split()], float(m.group(5))


@pytest.mark.parametrize("mesh,t", [("slender_cantilever_t05", 0.05), ("slender_cantilever", 0.02)])
def test_static_tip_is_the_elastica(mm, mesh, t):
    """t/L 0.05 (160 x 8 cells) and 0.02 (400 x 8), svk, the tip section's mean displacement of the static
    state within 2% of the elastica's tip at P L^2/EI = 3 (-1.7% and -1.9% measured: 8 P1 triangles
    through the thickness bend a little stiffly, as the damped dynamic run's test found); Newton ends
    each load step within the round-off of its terms (at most 9 iterations measured); on 2 ranks the
    state is the 1-rank one to round-off of the tip deflection (1e-15 measured)."""
    tip = []
    for np_ in (1, 2):
        r = static_cantilever(mm, mesh, t, "-ts_max_time", 0.01, np_=np_, name=f"np{np_}")
        levels, its, ratio = load_steps(r.output)
        assert ratio <= 1 and max(its) <= 15, r.output[-1500:]
        h = r.history
        assert h["time"][0] == 0
        tip.append((h["probe_tip_ux"][0], h["probe_tip_uy"][0]))
    dv, dh, _ = elastica_tip(ALPHA)
    assert -tip[0][1] == pytest.approx(dv, rel=0.02), (tip[0], dv)
    assert -tip[0][0] == pytest.approx(dh, rel=0.05), (tip[0], dh)
    assert np.abs(np.subtract(*tip)).max() <= 1e-12 * abs(tip[0][1]), tip


def test_static_is_the_damped_rest_state(mm):
    """t/L 0.05: the static tip against the rest state of options/slender_cantilever.opts's damped run
    (the load ramped over 3 s, held to t = 5): within 1e-6 of the deflection (8e-10 measured; 1.3e-9
    at t = 6, 1.7e-7 at 4.5; t/L 0.02's run, 5 times longer, is at 4e-8 at t = 6)."""
    t = 0.05
    s = static_cantilever(mm, "slender_cantilever_t05", t, "-ts_max_time", 0.01).history
    d = mm("slender_cantilever", "-mesh", "meshes/slender_cantilever_t05.msh", "-traction_tip_value", f"0,{-tip_traction(t)}", "-ts_max_time", 5, "-output_every", 0, name="damped").history
    assert d["time"][-1] == pytest.approx(5.0)
    uy = s["probe_tip_uy"][0]
    assert abs(d["probe_tip_uy"][-1] - uy) <= 1e-6 * abs(uy), (d["probe_tip_uy"][-1], uy)
    assert abs(d["probe_tip_ux"][-1] - s["probe_tip_ux"][0]) <= 1e-6 * abs(uy)


def test_static_cantilever_stays_at_rest(mm):
    """Undamped, started static with v0 = 0: over 0.2 s the tip moves by no more than 1e-8 of its
    deflection (7e-10 measured: the slender beam's force, a small difference of large element forces,
    is in equilibrium to their round-off, which its stiffness maps to that much displacement), the
    kinetic energy stays below 1e-15 of the elastic one (3e-19), and the balance holds."""
    h = static_cantilever(mm, "slender_cantilever_t05", 0.05, "-damping_ratio", 0, "-ts_max_time", 0.2).history
    uy = h["probe_tip_uy"]
    assert np.abs(uy - uy[0]).max() <= 1e-8 * abs(uy[0]), np.abs(uy - uy[0]).max()
    assert h["kinetic"].max() <= 1e-15 * h["elastic"][0]
    assert h["balance_residual"].max() <= 1e-12


def test_static_contact_is_the_damped_rest_state(mm):
    """options/cantilever_rest.opts with svk: the clamped strip sags under its weight onto the plane
    0.005 below its tip half; the static start finds the contact (one node) and its state is the
    damped dynamic run's at t = 1: the plane's force within 1e-6 of itself (3e-8 measured, the run
    still settling), the centre of mass within 1e-9 of its fall (1e-12)."""
    s = mm("cantilever_rest", "-elasticity", "svk", "-initial_state", "static", "-ts_max_time", 0.01, "-output_every", 0, name="static").history
    d = mm("cantilever_rest", "-elasticity", "svk", "-ts_max_time", 1, "-output_every", 0, name="damped").history
    assert s["active"][0] == 1 and d["active"][-1] == 1
    assert abs(d["force_normal"][-1] - s["force_normal"][0]) <= 1e-6 * s["force_normal"][0]
    assert abs(d["ucm_y"][-1] - s["ucm_y"][0]) <= 1e-9 * abs(s["ucm_y"][0])
    assert s["max_penetration"][0] <= 1e-14 * 0.005


P, W, H, RHO = 2e5, 1.0, 0.5, 1000.0  # options/rubber_block_press.opts


def test_block_pressed_static_then_struck(mm):
    """options/rubber_block_press.opts: at t = 0 the plane carries the pressure's resultant p W to
    round-off of that force (1.5e-16 measured), the whole base in contact (seated by the first Newton
    step: no load acts on the contact nodes themselves) with no penetration; struck down at 0.5, the
    run's balance holds to round-off of its energy (1.2e-13 measured) and nothing penetrates."""
    r = mm("rubber_block_press", "-output_every", 0)
    levels, its, ratio = load_steps(r.output)
    assert ratio <= 1
    h = r.history
    F = P * W
    assert abs(h["force_normal"][0] - F) <= 1e-12 * F, (h["force_normal"][0], F)
    assert h["active"][0] == 17  # the whole base in contact
    assert h["max_penetration"][0] <= 1e-14 * H
    assert h["time"][-1] == pytest.approx(0.02)
    assert h["balance_residual"].max() <= 1e-11
    assert h["max_penetration"].max() <= 1e-12 * H
    assert h["force_normal"].max() > 1.1 * F  # struck: the plane pushes back harder


def test_block_pressed_stays_at_rest(mm):
    """Without -v0 the pressed block stays in its static state: its centre-of-mass velocity below
    1e-10 of p / (rho c_p), the particle velocity of a pressure wave of amplitude p (5e-13 measured),
    the contact force steady to 1e-12 of itself, on 1 rank and on 2."""
    c_p = 61.59
    for np_ in (1, 2):
        h = mm("rubber_block_press", "-v0", "0,0", "-output_every", 0, np_=np_, name=f"rest{np_}").history
        assert np.abs(h["vcm_y"]).max() <= 1e-10 * P / (RHO * c_p), np.abs(h["vcm_y"]).max()
        F = h["force_normal"]
        assert np.abs(F - F[0]).max() <= 1e-12 * F[0]


def test_static_sliding_refused_in_finite_strain(mm):
    """static_sliding stays linear: with a finite-strain law it is refused in one line, pointing to static."""
    r = mm("rubber_block_press", "-initial_state", "static_sliding", np_=0, check=False)
    err = [l for l in r.output.splitlines() if l.strip()]
    assert r.returncode == 64 and "-initial_state static_sliding solves a linear sliding state" in err[0], r.output[-1500:]


def test_unreachable_static_state_stops_in_one_line(mm):
    """St. Venant-Kirchhoff softens in compression and has a largest compressive force: pressed by
    0.5 E it has no static state, the load steps are cut down to 1e-6, and the run stops with one line
    naming the load factor reached (0.48 measured), exit status 65 like the other solver failures. Held
    in y instead of x at its pin, the block is free to slide along the frictionless plane: no load
    level converges, and the line says the problem is not well posed."""
    r = mm("rubber_block_press", "-elasticity", "svk", "-pressure_top_value", 5e5, np_=0, check=False)
    lines = [l for l in r.output.splitlines() if l.strip()]
    assert r.returncode == 65, r.output[-1500:]
    assert len(lines) == 1 and "did not converge beyond load factor 0.4" in lines[0], r.output[-1500:]
    assert "PETSc" not in r.output
    r = mm("rubber_block_press", "-dirichlet_pin_components", 1, np_=0, check=False, name="free")
    lines = [l for l in r.output.splitlines() if l.strip()]
    assert r.returncode == 65 and len(lines) == 1 and "did not converge at any load level" in lines[0] and "not well posed" in lines[0], r.output[-1500:]


@pytest.mark.parametrize("alpha,load,mesh,t,np_", [
    (1, "traction", "slender_cantilever_t05", 0.05, 1),
    (10, "traction", "slender_cantilever_t05", 0.05, 2),
    (1, "point", "slender_cantilever_t05", 0.05, 2),
    (10, "point", "slender_cantilever", 0.02, 1),
])
def test_static_tip_over_the_load_range(mm, alpha, load, mesh, t, np_):
    """The issue's range of the cantilever, P L^2/EI = 1 and 10, under the end traction and under a
    point force of the same resultant at the tip's corner (tip_point), default options: the tip
    section's mean vertical displacement against the elastica's, each load step within the round-off
    of its terms. 8 P1 cells through the thickness bend stiffly: at a small load (P L^2/EI = 0.01) this
    mesh's tip is 4.3% short of the elastica (4.5% at t/L 0.02), the P1 bending error, which the
    geometric stiffening of larger deflections hides: measured -3.6% (traction) and -4.9% (point force,
    whose corner adds its local flattening) at 1, -1.7% at 3, within 2% at 10. So 5% at 1, 2% at 10;
    the horizontal, of second order in the deflection, twice that (-7.2% and -10.0% at 1)."""
    P = alpha * E * t**3 / 12 / L**2  # the resultant, per unit depth
    if load == "traction":
        loading = ("-traction_tip_value", f"0,{-P / t}", "-traction_tip_amplitude", "constant")
    else:
        loading = ("-traction_tip_value", "0,0", "-point_force", "tip_point", "-point_force_tip_point_value", f"0,{-P}")
    r = mm("slender_cantilever", "-mesh", f"meshes/{mesh}.msh", *loading, "-initial_state", "static",
           "-output_every", 0, "-ts_max_time", 0.01, np_=np_)
    levels, its, ratio = load_steps(r.output)
    assert ratio <= 1, r.output[-1500:]
    h = r.history
    dv, dh, _ = elastica_tip(alpha)
    assert -h["probe_tip_uy"][0] == pytest.approx(dv, rel=0.05 if alpha < 3 else 0.02), (h["probe_tip_uy"][0], dv)
    assert -h["probe_tip_ux"][0] == pytest.approx(dh, rel=0.12 if alpha < 3 else 0.05), (h["probe_tip_ux"][0], dh)
