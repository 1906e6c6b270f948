"""Issue 38, items 12 and 13: the loads users apply (a pressure on a boundary group, a concentrated
force on a Physical Point group; README "Loads in time") and the static start
(-initial_state static; README "Loads in time", "A static start", docs/method.md section 10).

Every number is compared to the physical scale of its case (tests/README.md): a resultant to the
load's own p x area, a momentum to the impulse of the force, energies to the run's energy scale."""
import os

import numpy as np
import pytest

from conftest import ROOT, run

ENERGIES = ("kinetic", "elastic", "total", "work_ext")


def plate_without_force(tmp_path):
    """options/plate_loads.opts without its point force, for a test to give its own loads."""
    lines = [l for l in open(os.path.join(ROOT, "options", "plate_loads.opts")).read().splitlines() if not l.startswith("-point_force")]
    path = tmp_path / "plate_free.opts"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def one_step(tmp_path, mesh, *extra, name="out"):
    """One step of a free body without contact: the history's load_* columns are the resultant of
    the nodal loads over the whole body (no Dirichlet node)."""
    return run(plate_without_force(tmp_path), tmp_path, "-mesh", mesh, "-ts_max_steps", 1, *extra, np_=0, name=name, check=False)


def test_pressure_resultant_on_closed_and_flat_surfaces(tmp_path):
    """A uniform pressure p on a closed surface has no resultant (sum of p n |F| over a closed
    polyhedron is zero exactly, up to round-off); on a flat face it is -p |F| n, n the outward normal
    (p > 0 pushes in). 2D: the plate's four sides (length 4), its right side x = 1 (length 1, per unit
    thickness); 3D: the box's six faces, its top z = 0.5 (area 1)."""
    p = 2e-3
    r = one_step(tmp_path, "meshes/plate.msh", "-pressure", "rim", "-pressure_rim_value", p, name="closed2d")
    assert r.returncode == 0, r.output[-2000:]
    h = r.history
    assert abs(h["load_x"][0]) <= 1e-12 * p * 4 and abs(h["load_y"][0]) <= 1e-12 * p * 4
    r = one_step(tmp_path, "meshes/plate.msh", "-pressure", "right,top", "-pressure_right_value", p, "-pressure_top_value", -3 * p, name="flat2d")
    assert r.returncode == 0, r.output[-2000:]
    h = r.history
    assert abs(h["load_x"][0] - (-p * 1.0)) <= 1e-12 * p     # pushes the right side in: -x
    assert abs(h["load_y"][0] - (3 * p * 1.0)) <= 1e-12 * p  # a negative pressure pulls the top out: +y
    r = one_step(tmp_path, "meshes/box.msh", "-pressure", "top,base,sides", "-pressure_top_value", p, "-pressure_base_value", p, "-pressure_sides_value", p, name="closed3d")
    assert r.returncode == 0, r.output[-2000:]
    h = r.history
    for c in ("load_x", "load_y", "load_z"):
        assert abs(h[c][0]) <= 1e-12 * p * 3, c  # the box's area is 3
    r = one_step(tmp_path, "meshes/box.msh", "-pressure", "top", "-pressure_top_value", p, name="flat3d")
    assert r.returncode == 0, r.output[-2000:]
    h = r.history
    assert abs(h["load_z"][0] + p * 1.0) <= 1e-12 * p
    assert abs(h["load_x"][0]) <= 1e-12 * p and abs(h["load_y"][0]) <= 1e-12 * p


def test_pressure_pulse_is_the_traction_pulse(tmp_path):
    """bar_pulse with its traction -1e-3,0 on the end x = 1 given as the pressure 1e-3 (outward normal
    +x), on 2 ranks: the same load, so the 1-rank traction run to 1e-10 of the energy scale, and the pulse carries the
    energy sigma^2 A T / (2 rho c) of the traction's test (tests/test_loads_time.py) to 2%; the
    energy balance, with the pressure's work in work_ext, closes to 1e-10."""
    F, A, Tp = 1e-3, 1.0 / 80, 0.2
    lines = [l for l in open(os.path.join(ROOT, "options", "bar_pulse.opts")).read().splitlines() if not l.startswith("-traction")]
    path = tmp_path / "bar_pulse_pressure.opts"
    path.write_text("\n".join(lines + ["-pressure right", "-pressure_right_value 1e-3", "-pressure_right_amplitude halfsine",
                                       "-pressure_right_amplitude_time 0.2"]) + "\n")
    pr = run(str(path), tmp_path, "-output_every", 0, name="pressure", np_=2).history
    tr = run("bar_pulse", tmp_path, "-output_every", 0, name="traction").history
    escale = np.abs(tr["total"]).max()
    for c in ENERGIES:
        assert np.abs(pr[c] - tr[c]).max() <= 1e-10 * escale, c
    assert np.abs(pr["load_x"] - tr["load_x"]).max() <= 1e-12 * F * A
    assert pr["balance_residual"].max() <= 1e-10
    assert abs(pr["total"][-1] - F ** 2 * A * Tp / 2) <= 0.02 * F ** 2 * A * Tp / 2
    assert abs(pr["work_ext"][-1] - pr["total"][-1]) <= 1e-10 * escale


def impulse(t, F, table):
    """int_0^t F a(s) ds for the piecewise linear amplitude a of the table rows (time, factor)."""
    tt, ff = np.array(table).T
    out = []
    for ti in t:
        grid = np.concatenate([tt[tt < ti], [ti]])
        vals = np.interp(grid, tt, ff)
        out.append(np.trapz(vals, grid) if len(grid) > 1 else 0.0)
    return np.outer(out, F)


@pytest.mark.parametrize("np_", [1, 2])
def test_point_force_momentum_is_its_impulse(tmp_path, np_):
    """options/plate_loads.opts: a free plate pushed at its corner (1,1) by a force whose amplitude is
    piecewise linear with its breaks on the steps, so the trapezoidal rule integrates it exactly. The
    scheme's momentum P changes over a step by dt times the mean of the resultant of the loads
    (docs/method.md section 4): P(t) = int_0^t F dt, and the angular momentum about the origin
    J_z(t) = int_0^t (x F_y - y F_x) dt, to 1e-10 of the momentum scale |F| T. The energy balance,
    with the force's work, closes to 1e-10; 2 ranks give 1 rank's history to 1e-10 of its scales."""
    F = np.array([1e-4, -2e-4])
    table = [(0, 0), (0.1, 1), (0.3, 1), (0.4, 0)]
    r = run("plate_loads", tmp_path, np_=np_)
    h = r.history
    P = impulse(h["time"], F, table)
    scale = np.abs(F).max() * 0.3
    assert np.abs(h["P_x"] - P[:, 0]).max() <= 1e-10 * scale
    assert np.abs(h["P_y"] - P[:, 1]).max() <= 1e-10 * scale
    assert np.abs(h["J_z"] - (P[:, 1] - P[:, 0])).max() <= 1e-10 * scale
    assert h["balance_residual"].max() <= 1e-10
    assert abs(h["work_ext"][-1] - h["total"][-1]) <= 1e-10 * np.abs(h["total"]).max()
    # the load column is the force times its amplitude, at every step
    assert np.abs(h["load_x"] - F[0] * np.interp(h["time"], *np.array(table).T)).max() <= 1e-12 * np.abs(F).max()
    if np_ == 2:
        one = run("plate_loads", tmp_path, name="one").history
        escale = np.abs(one["total"]).max()
        for c in ENERGIES:
            assert np.abs(h[c] - one[c]).max() <= 1e-10 * escale, c
        for c in ("P_x", "P_y", "J_z", "vcm_x", "vcm_y"):  # the plate's mass is 1: vcm's scale is P's
            assert np.abs(h[c] - one[c]).max() <= 1e-10 * scale, c


BAD = [
    (("-pressure", "body", "-pressure_body_value", 1), ["-pressure body", "holds cells, not boundary faces"]),
    (("-pressure", "tip", "-pressure_tip_value", 1), ["-pressure tip", "holds no faces"]),
    (("-pressure", "right"), ["-pressure lists right but -pressure_right_value is not given"]),
    (("-pressure", "right", "-pressure_right_value", 1, "-pressure_rigth_amplitude", "ramp"), ["\"rigth\" is not a pressure boundary"]),
    (("-pressure", "right", "-pressure_right_value", 1, "-pressure_right_amplitude", "ramp"), ["-pressure_right_amplitude ramp needs its time"]),
    (("-point_force", "right", "-point_force_right_value", "1,0"), ["-point_force right", "holds faces", "Give a Physical Point group"]),
    (("-point_force", "nowhere", "-point_force_nowhere_value", "1,0"), ["no physical group named \"nowhere\"", "\"tip\""]),
    (("-point_force", "tip", "-point_force_tip_value", "1,0,0"), ["-point_force_tip_value has 3 entries", "needs exactly 2"]),
    (("-point_force", "tip"), ["-point_force lists tip but -point_force_tip_value is not given"]),
]


@pytest.mark.parametrize("extra,messages", BAD)
def test_bad_load_input_is_named(tmp_path, extra, messages):
    r = run(plate_without_force(tmp_path), tmp_path, "-ts_max_steps", 1, *extra, np_=0, check=False)
    assert r.returncode != 0
    for m in messages:
        assert m in r.output, r.output[-1500:]
    assert "mmcontact error:" in r.output and "Traceback" not in r.output


# ---------------------------------------------------------------- item 13: -initial_state static

RHO_G, L_BAR, W_BAR = 1e-3, 1.0, 1.0 / 80  # options/bar_standing.opts: rho g, the bar's length and width


@pytest.mark.parametrize("np_,extra", [(1, ()), (2, ()), (1, ("-mu", 0.3))])
def test_static_start_stays_at_rest(tmp_path, np_, extra):
    """options/bar_standing.opts: the B1 strip standing on its end on the plane y = 0 under gravity,
    started static. The static state is an equilibrium of the scheme, so over the 100 steps the
    kinetic energy stays below 1e-10 of the elastic energy, every velocity below 1e-10 of the velocity
    scale sqrt(2 E / m), and the plane carries the weight rho g L W to 1e-10 at every step (measured:
    2e-34 of the energy, 1e-12 of the velocity, 3e-13 of the weight), on 1 and 2 ranks and with
    friction. The displacement is the 1D closed form u_y = -(rho g / E)(L y - y^2 / 2) up to the P1
    strip's O(h^2) error: within (h / L)^2 = 1.6e-4 of the top's -rho g L^2 / (2 E) (measured 9.5e-6;
    a start from u = 0 would be off by 100%)."""
    r = run("bar_standing", tmp_path, *extra, np_=np_)
    h = r.history
    weight = RHO_G * L_BAR * W_BAR
    E = h["elastic"].max()
    V = np.sqrt(2 * E / (L_BAR * W_BAR))
    assert "static contact problem at t = 0 solved" in r.output
    assert np.abs(h["kinetic"]).max() <= 1e-10 * E
    assert np.abs(h["force_normal"] - weight).max() <= 1e-10 * weight
    assert np.abs(h["elastic"] - h["elastic"][0]).max() <= 1e-10 * E
    assert h["balance_residual"].max() <= 1e-10
    assert np.abs(h["vcm_y"]).max() <= 1e-10 * V
    u_top = RHO_G * L_BAR ** 2 / 2
    with r.fields() as f:
        y = f["geometry/vertices"][:, 1]
        u = f["vertex_fields/displacement_displacement"][:]
        v = f["vertex_fields/velocity_displacement"][:]
    assert u.shape[0] == 6  # the initial state and every 20th step
    assert np.abs(v).max() <= 1e-10 * V
    exact = -RHO_G * (L_BAR * y - y ** 2 / 2)
    assert np.abs(u[:, :, 1] - exact).max() <= (1.0 / 80) ** 2 * u_top
    assert abs(u[0, :, 1].min() + u_top) <= (1.0 / 80) ** 2 * u_top


STATIC_BAD = [
    # no -dirichlet: the bar can slide along the frictionless plane
    (("-dirichlet", ""), ["-initial_state static: the static problem at t = 0 is not well posed", "1 rigid motion", "Hold it with -dirichlet"]),
    # gravity pulling it off the plane: nothing holds it along y
    (("-gravity", "0,1e-3"), ["not well posed", "rigid motions"]),
    (("-u0_offset", "0,0.1"), ["-initial_state static computes u0", "drop -u0_offset"]),
]


@pytest.mark.parametrize("extra,messages", STATIC_BAD)
def test_static_start_refuses_what_is_not_well_posed(tmp_path, extra, messages):
    lines = [l for l in open(os.path.join(ROOT, "options", "bar_standing.opts")).read().splitlines() if not (extra[0] == "-dirichlet" and l.startswith("-dirichlet"))]
    path = tmp_path / "bar.opts"
    path.write_text("\n".join(lines) + "\n")
    extra = extra if extra[0] != "-dirichlet" else ()
    r = run(str(path), tmp_path, *extra, np_=0, check=False)
    assert r.returncode == 64, r.output[-1500:]
    for m in messages:
        assert m in r.output, r.output[-1500:]
    assert "MUMPS" not in r.output and "Traceback" not in r.output
