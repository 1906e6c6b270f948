"""Loads in time, moving Dirichlet boundaries and the support reactions (docs/method.md section 10,
README "Loads in time"): a slow ramp is quasi-static, a half-sine pulse is a wave of known speed and
amplitude, a table equal to a ramp is the ramp, a punch driven into a plane by its top boundary
balances the plane's force with its reaction; 1 and 2 ranks agree and a restart continues bit for
bit; bad amplitude input is refused by name."""
import os

import numpy as np
import pytest

from conftest import ROOT, run

F = 1e-3       # the traction of bar_ramp and bar_pulse (force per unit length of the end x = 1)
A = 1.0 / 80   # the bar's cross-section, the length of that end: the load's resultant is F A
L = 1.0        # the bar's length; E = rho = 1, nu = 0 (plane strain 1D): c = 1
ENERGIES = ("kinetic", "elastic", "total", "work_ext", "work_contact", "work_friction", "work_obstacle", "work_dirichlet")


def options_without_amplitude(tmp_path, case="bar_ramp"):
    """options/<case>.opts without its amplitude lines, for a test to give its own."""
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines() if "_amplitude" not in l]
    path = tmp_path / (case + "_constant.opts")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def end_displacement(r):
    """The snapshot times and the mean x-displacement of the nodes of the end x = L."""
    with r.fields() as f:
        x = f["geometry/vertices"][:]
        end = np.abs(x[:, 0] - L) < 1e-12
        return f["time"][:, 0], f["vertex_fields/displacement_displacement"][:, end, 0].mean(axis=1)


def test_slow_ramp_is_quasi_static(tmp_path):
    """bar_ramp: the traction ramped over T = 100, 25 times the first period 4 L / c. Each mode k of
    the clamped bar follows its static share times the ramp up to a ringing of at most its static
    share over omega_k T during the ramp and twice that after it (a single oscillator under a
    ramp); the shares are positive and sum to the static F L / (E A) times A, so the end displacement
    is within 2 / (omega_1 T) = 1.3% (omega_1 = pi c / 2 L) of the static one times the ramp, and
    the clamp's reaction, which differs from minus the load by the inertia force, likewise. A load
    applied at once instead would ring by 100%."""
    T = 100.0
    r = run("bar_ramp", tmp_path)
    h = r.history
    ramp = np.minimum(h["time"] / T, 1.0)
    bound = 2.0 / (np.pi / 2 * T)
    assert h["balance_residual"].max() <= 1e-10
    # the loads' resultant column is the ramped load, exactly
    assert np.abs(h["load_x"] - F * A * ramp).max() <= 1e-12 * F * A
    t, u = end_displacement(r)
    u_static = F * L  # F L / (E A) with the force F A
    assert len(t) == 25 and t[-1] == 120
    assert np.abs(u - u_static * np.minimum(t / T, 1.0)).max() <= bound * u_static
    assert abs(u[-1] - u_static) <= bound * u_static
    # the clamp holds the load: the x reaction is minus the applied resultant, y none (nu = 0)
    assert np.abs(h["reaction_left_x"] + F * A * ramp).max() <= bound * F * A
    assert np.abs(h["reaction_left_y"]).max() <= 1e-10 * F * A
    assert h["reaction_left_x"][-1] < -0.98 * F * A


def test_half_sine_pulse_travels_at_c(tmp_path):
    """bar_pulse: a half-sine pressure pulse of duration 0.2 (16 cells long) on the free end travels
    towards the clamp at c = sqrt(E / rho) = 1 with the particle velocity -sigma / (rho c). At
    x = 0.5 and x = 0.25 the velocity peaks at t = L - x + 0.1. P1 with the consistent mass at
    c dt / h = 1: the peak arrives within 1.5 h / c (a wave speed 5% off would be 3 h off at
    x = 0.25) and its height is within 5% (measured: 0.5% and 2.9%; the dispersion of the pulse's
    kinks grows with the distance). Behind the pulse the velocity falls back below 15% of the peak
    (a step load would keep it at 100%). The energy put in is sigma^2 A T / (2 rho c) to 2%."""
    Tp, h_mesh = 0.2, 1.0 / 80
    r = run("bar_pulse", tmp_path)
    hist = r.history
    assert hist["balance_residual"].max() <= 1e-10
    assert abs(hist["total"][-1] - F ** 2 * A * Tp / 2) <= 0.02 * F ** 2 * A * Tp / 2
    assert abs(hist["total"][-1] - hist["work_ext"][-1]) <= 1e-10 * hist["total"][-1]
    with r.fields() as f:
        x = f["geometry/vertices"][:]
        t = f["time"][:, 0]
        vel = f["vertex_fields/velocity_displacement"][:]
    v_wave = F / 1.0  # sigma / (rho c)
    for x0 in (0.5, 0.25):
        at = np.abs(x[:, 0] - x0) < 1e-12
        v = vel[:, at, 0].mean(axis=1)
        s = t - (L - x0)  # time since the pulse's front should have arrived
        k = np.argmin(v)
        assert abs(v[k] + v_wave) <= 0.05 * v_wave, (x0, v[k])
        assert abs(t[k] - (L - x0 + Tp / 2)) <= 1.5 * h_mesh, (x0, t[k])
        assert np.abs(v[s < -3 * h_mesh]).max() <= 0.02 * v_wave
        assert np.abs(v[s > Tp + 3 * h_mesh]).max() <= 0.15 * v_wave


def test_table_equals_ramp_and_interpolates(tmp_path):
    """A table (0, 0), (10, 1) gives the history of the ramp of T = 10, past its end too; a table with
    a plateau and a fall gives the load resultant interpolated linearly, constant beyond its ends."""
    opts = options_without_amplitude(tmp_path)
    ramp_csv = tmp_path / "ramp.csv"
    ramp_csv.write_text("time,factor\n0,0\n10,1\n")
    common = ("-ts_max_time", 20, "-output_every", 0)
    a = run(opts, tmp_path, *common, "-traction_right_amplitude", "ramp", "-traction_right_amplitude_time", 10, name="ramp").history
    b = run(opts, tmp_path, *common, "-traction_right_amplitude_table", ramp_csv, name="table").history
    escale = np.abs(a["total"]).max()
    assert escale > 0 and a["work_ext"][-1] > 0
    for c in ENERGIES:
        assert np.abs(a[c] - b[c]).max() <= 1e-12 * escale, c
    for c in ("load_x", "reaction_left_x"):
        assert np.abs(a[c] - b[c]).max() <= 1e-12 * F * A, c
    # a plateau: 0 -> 1 over [2, 5], 1 until 10, down to 0.5 at 15, then 0.5
    plateau = tmp_path / "plateau.csv"
    plateau.write_text("# t, factor\n2,0\n5,1\n10,1\n15,0.5\n")
    h = run(opts, tmp_path, *common, "-traction_right_amplitude", "table", "-traction_right_amplitude_table", plateau, name="plateau").history
    expect = np.interp(h["time"], [2, 5, 10, 15], [0, 1, 1, 0.5])
    assert np.abs(h["load_x"] - F * A * expect).max() <= 1e-12 * F * A
    assert h["balance_residual"].max() <= 1e-10


def test_gravity_amplitude(tmp_path):
    """The gravity's amplitude: a half-sine of T = 5 on the body force, with the traction off. The
    loads' resultant is the constant one times sin(pi t / T), then 0, and the balance closes."""
    opts = options_without_amplitude(tmp_path)
    h = run(opts, tmp_path, "-traction_right_value", "0,0", "-gravity", "1e-3,0", "-gravity_amplitude", "halfsine",
            "-gravity_amplitude_time", 5, "-ts_max_time", 8, "-output_every", 0).history
    a = np.where(h["time"] < 5, np.sin(np.pi * np.minimum(h["time"], 5) / 5), 0.0)
    k = np.argmax(a)
    g_res = h["load_x"][k] / a[k]
    assert 0.9 * 1e-3 * A < g_res <= 1e-3 * A  # the mass of the nodes that are not clamped, times g
    assert np.abs(h["load_x"] - g_res * a).max() <= 1e-12 * g_res
    assert h["balance_residual"].max() <= 1e-10 and h["work_ext"].max() > 0


def impulse(h, column):
    """The trapezoidal integral of a history column from the start to each step."""
    dt = np.diff(h["time"])
    return np.concatenate([[0.0], np.cumsum(0.5 * dt * (h[column][1:] + h[column][:-1]))])


def test_punch_reaction_balances_contact(tmp_path):
    """punch: the block's top driven down at v = 0.03 into the plane (lumped mass). The momentum of
    the free nodes changes by the trapezoidal impulse of the press's reaction and of the plane's
    force on the body, exactly (the press's nodes keep theirs); so over the run the reaction balances
    the contact force up to the block's change of momentum, 0.4% of the mean force here. The press's
    work is 1/2 (R^n + R^{n+1}) . (-v dt) per step, the energy balance closes with it, and the
    output shows the press's motion."""
    v = 0.03
    r = run("punch", tmp_path)
    h = r.history
    assert h["balance_residual"].max() <= 1e-10
    assert h["active"][-1] == 21  # the whole base is pressed
    force_on_body = -h["force_plane_y"]  # force_plane_y is the force on the plane
    R = h["reaction_top_y"]
    fscale = np.abs(force_on_body).max()
    assert fscale > 20 and R[-1] < -0.9 * fscale
    # the exact balance of momentum, and its meaning on average
    dP = h["P_y"] - h["P_y"][0]
    net = impulse(h, "reaction_top_y") + impulse(h, "force_normal")
    assert np.abs(net - dP).max() <= 1e-10 * fscale * h["time"][-1]
    assert abs(net[-1]) <= 0.01 * impulse(h, "force_normal")[-1]
    assert np.allclose(force_on_body, h["force_normal"], rtol=0, atol=1e-12 * fscale)
    # the press's work from its reaction, and the energy it put in
    w = np.concatenate([[0.0], np.cumsum(0.5 * (R[1:] + R[:-1]) * (-v) * np.diff(h["time"]))])
    escale = np.abs(h["total"]).max()
    assert np.abs(h["work_dirichlet"] - w).max() <= 1e-10 * escale
    assert np.abs(h["total"] - h["total"][0] - h["work_dirichlet"] - h["work_contact"] - h["work_ext"]).max() <= 1e-10 * escale
    assert h["work_dirichlet"][-1] > 0.9 * (h["total"][-1] - h["total"][0]) > 0
    with r.fields() as f:
        x = f["geometry/vertices"][:]
        top = np.abs(x[:, 1] - 0.5) < 1e-12
        t = f["time"][:, 0]
        u = f["vertex_fields/displacement_displacement"][:]
        vel = f["vertex_fields/velocity_displacement"][:]
    assert np.abs(u[:, top, 1] + v * t[:, None]).max() <= 1e-14 and np.abs(u[:, top, 0]).max() == 0
    assert np.abs(vel[:, top, 1] + v).max() <= 1e-14


def test_punch_consistent_mass_balances(tmp_path):
    """With the consistent mass the press's nodes move the free ones through M_fD too: their kinetic
    energy and the reaction's inertia term are in the balance, which closes."""
    h = run("punch", tmp_path, "-mass_lumped", 0, "-ts_max_time", 0.2, "-output_every", 0).history
    assert h["balance_residual"].max() <= 1e-10
    assert h["work_dirichlet"][-1] > 0.01


@pytest.mark.parametrize("case,extra", [("punch", ("-ts_max_time", 0.3)), ("bar_pulse", ("-output_every", 0))])
def test_one_and_two_ranks_agree(tmp_path, case, extra):
    h1 = run(case, tmp_path, *extra, np_=1, name="np1").history
    h2 = run(case, tmp_path, *extra, np_=2, name="np2").history
    escale = max(np.abs(h1[c]).max() for c in ENERGIES)
    assert len(h1) == len(h2) and escale > 0
    for c in ENERGIES:
        assert np.abs(h1[c] - h2[c]).max() <= 1e-10 * escale, c
    for c in [n for n in h1.dtype.names if n.startswith("reaction_") or n.startswith("load_")]:
        scale = np.abs(h1[c]).max() + np.abs(h1["force_normal"]).max() + F * A
        assert np.abs(h1[c] - h2[c]).max() <= 1e-10 * scale, c


def test_restart_continues_bitwise(tmp_path):
    """The punch stopped at step 150 (-ts_max_steps) and continued from its checkpoint: the history
    is the uninterrupted run's, bit for bit on 1 rank (the loads and the data are functions of time,
    the reactions are recomputed from the state, the press's work is checkpointed), and to 1e-10 of
    the scales on 2 ranks."""
    full = run("punch", tmp_path, "-output_every", 0, name="full").history
    run("punch", tmp_path, "-output_every", 0, "-ts_max_steps", 150, name="first")
    first = str(tmp_path / "first")
    again = run("punch", tmp_path, "-output_every", 0, "-restart", first, name="again").history
    assert len(again) == len(full) and full["step"][-1] > 300
    for c in full.dtype.names:
        assert np.array_equal(full[c], again[c]), c
    two = run("punch", tmp_path, "-output_every", 0, "-restart", first, np_=2, name="two").history
    escale = np.abs(full["total"]).max()
    for c in ENERGIES:
        assert np.abs(full[c] - two[c]).max() <= 1e-10 * escale, c
    assert np.abs(full["reaction_top_y"] - two["reaction_top_y"]).max() <= 1e-10 * np.abs(full["reaction_top_y"]).max()


BAD = [
    (("-traction_right_amplitude", "sine"), ["-traction_right_amplitude sine: unknown amplitude", "ramp or halfsine", "table"]),
    (("-traction_right_amplitude", "ramp"), ["-traction_right_amplitude ramp needs its time", "-traction_right_amplitude_time T"]),
    (("-gravity", "0,-1", "-gravity_amplitude", "halfsine", "-gravity_amplitude_time", 0), ["-gravity_amplitude_time 0", "must be > 0"]),
    (("-traction_right_amplitude", "table"), ["needs its file", "-traction_right_amplitude_table FILE.csv"]),
    (("-traction_right_amplitude_table", "/nonexistent/amp.csv"), ["-traction_right_amplitude_table /nonexistent/amp.csv", "cannot be read"]),
    (("-traction_right_amplitude_table", "unsorted.csv"), ["unsorted.csv", "line 3", "must increase strictly"]),
    (("-traction_right_amplitude_table", "one.csv"), ["one.csv", "has 1 row", "at least two"]),
    (("-traction_right_amplitude_table", "words.csv"), ["words.csv", "line 3", "is not two numbers"]),
    (("-traction_right_amplitude_table", "one.csv", "-traction_right_amplitude_time", 5), ["-traction_right_amplitude_time is given with a table amplitude", "drop it"]),
    (("-traction_rigth_amplitude_table", "one.csv"), ["-traction_rigth_amplitude_table", "\"rigth\" is not a traction boundary", "add it to -traction"]),
    (("-dirichlet_left_velocity", "0.1"), ["-dirichlet_left_velocity has 1 entries", "give one velocity per fixed component"]),
    (("-dirichlet_left_velocity", "0.1,0", "-damping_mass", 1), ["-dirichlet_left_velocity with Rayleigh damping", "Drop one of the two"]),
]


@pytest.mark.parametrize("extra,messages", BAD)
def test_bad_amplitude_input_is_named(tmp_path, extra, messages):
    (tmp_path / "unsorted.csv").write_text("0,0\n1,1\n0.5,2\n")
    (tmp_path / "one.csv").write_text("time,factor\n0,1\n")
    (tmp_path / "words.csv").write_text("0,0\n1,1\nten,2\n")
    extra = [str(tmp_path / e) if str(e).endswith(".csv") and not str(e).startswith("/") else e for e in extra]
    r = run(options_without_amplitude(tmp_path), tmp_path, "-ts_max_time", 1, *extra, np_=0, check=False)
    assert r.returncode != 0
    for m in messages:
        assert m in r.output, r.output[-1500:]


def test_3d_press_with_friction_and_gravity_ramp(tmp_path):
    """3D: the box's top driven down and sideways (-dirichlet_top_velocity 0.01,0,-0.02) onto the
    plane with friction mu = 0.3 under a ramped gravity. The balance with W_D closes on 1 and 2 ranks,
    which agree to 1e-10 of the energy scale; the press has done work and the base slips."""
    extra = ("-mesh", "meshes/box.msh", "-contact_boundary", "base", "-E", 100, "-nu", 0.3, "-rho", 1, "-dirichlet", "top",
             "-dirichlet_top_velocity", "0.01,0,-0.02", "-gravity", "0,0,-1", "-gravity_amplitude", "ramp",
             "-gravity_amplitude_time", 0.5, "-obstacle_point", "0,0,-0.001", "-obstacle_normal", "0,0,1", "-mu", 0.3,
             "-ts_dt", 0.01, "-ts_max_time", 1, "-output_every", 0, "-quiet")
    empty = tmp_path / "empty.opts"
    empty.write_text("# everything on the command line\n")
    h1 = run(str(empty), tmp_path, *extra, np_=1, name="np1").history
    h2 = run(str(empty), tmp_path, *extra, np_=2, name="np2").history
    escale = max(np.abs(h1[c]).max() for c in ENERGIES)
    for h in (h1, h2):
        assert h["balance_residual"].max() <= 1e-10
    assert h1["work_dirichlet"][-1] > 0.1 * escale and h1["slipping"][-1] > 0 and h1["work_friction"][-1] < 0
    for c in ENERGIES + ("reaction_top_x", "reaction_top_z"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-10 * max(escale, np.abs(h1["force_normal"]).max()), c


DIRICHLET_RAMP = ("-contact", 0, "-v0", "0,0", "-mass_lumped", "-dirichlet", "left,right", "-dirichlet_left_components", 0,
                  "-dirichlet_right_components", 0, "-dirichlet_right_value", 0.01, "-output_every", 0)


def test_dirichlet_value_ramp_stretches_the_bar_quasi_statically(tmp_path):
    """A bar (E = 1, nu = 0, 1 x 0.01) held at x = 0 whose end x = 1 is pulled to u = 0.01 by a slow ramp
    amplitude on the Dirichlet value (T = 50, 25 periods 2L/c of the held bar): at t = 60 the stress is
    E eps = 0.01, so each support carries sigma A = 1e-4, the left one -1e-4, within 2% (the rest is
    the vibration the ramp leaves, of order 1/(omega T)); the elastic energy is 1/2 sigma eps V =
    5e-7; the support's work W_D equals the energy the bar gained, and the balance closes."""
    r = run("b2_bar", tmp_path, *DIRICHLET_RAMP, "-dirichlet_right_amplitude", "ramp", "-dirichlet_right_amplitude_time", 50,
            "-ts_dt", 0.05, "-ts_max_time", 60, np_=2)
    h = r.history
    assert abs(h["reaction_right_x"][-1] - 1e-4) <= 0.02 * 1e-4
    assert abs(h["reaction_left_x"][-1] + 1e-4) <= 0.02 * 1e-4
    assert abs(h["elastic"][-1] - 5e-7) <= 0.02 * 5e-7
    assert abs(h["work_dirichlet"][-1] - (h["total"][-1] - h["total"][0])) <= 1e-10 * 5e-7
    assert h["balance_residual"].max() <= 1e-10


def test_dirichlet_value_pulse_balances_on_one_and_two_ranks(tmp_path):
    """A half-sine pulse of the end displacement (T = 0.5, a fraction of the bar's transit time 1):
    the energy identity with W_D closes at every step, and 1 and 2 ranks agree to 1e-10 of the energy
    scale; the pulse puts energy in and takes part of it out again (W_D > 0 at the end: a wave runs)."""
    extra = (*DIRICHLET_RAMP, "-dirichlet_right_amplitude", "halfsine", "-dirichlet_right_amplitude_time", 0.5,
             "-ts_dt", 0.01, "-ts_max_time", 2)
    one = run("b2_bar", tmp_path, *extra, np_=1, name="one").history
    two = run("b2_bar", tmp_path, *extra, np_=2, name="two").history
    escale = np.abs(one["total"]).max()
    assert escale > 0 and one["balance_residual"].max() <= 1e-10 and two["balance_residual"].max() <= 1e-10
    for c in ("kinetic", "elastic", "total", "work_dirichlet"):
        assert np.abs(one[c] - two[c]).max() <= 1e-10 * escale, c
    assert one["work_dirichlet"][-1] > 0.1 * escale


@pytest.mark.parametrize("extra,message", [
    (("-mass_lumped", 0), "-dirichlet_right_amplitude ramp needs -mass_lumped"),
    (("-damping_mass", 1), "-dirichlet_right_amplitude with Rayleigh damping is not supported"),
])
def test_dirichlet_amplitude_refusals(tmp_path, extra, message):
    """The consistent mass (the boundary's acceleration would drive the free dofs through M_fD) and
    damping (the moving boundary's damping force) are refused with a message that says why."""
    r = run("b2_bar", tmp_path, *DIRICHLET_RAMP, "-dirichlet_right_amplitude", "ramp", "-dirichlet_right_amplitude_time", 50,
            "-ts_max_steps", 2, *extra, np_=1, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-1500:]
