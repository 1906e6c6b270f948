"""Rayleigh damping C = alpha M* + beta B, B = K or K with the massless dofs condensed out (docs/method.md sections 3 and 4): the decay rate of a free
bar's first mode, the energy balance with the damping work on the contact and friction paths, the
ratio option, the refusals, and 1 rank against 2."""
import math
import os
import re

import h5py
import numpy as np
import pytest

from conftest import run

# A free bar, [0,1] x [0,0.05] in 80 cells along x (meshes/bar80.msh), plane strain with nu = 0 and
# E = rho = 1: a 1D bar with c = 1, free at both ends, whose first mode is cos(pi x) with omega = pi.
# The initial strain u_x = 0.01 (x - 1/2), at rest and without rigid motion, is
# -0.04/pi^2 sum_{k odd} cos(k pi x)/k^2: mostly the first mode, with modes 3, 5, ... carrying
# 1/9, 1/25, ... of its energy. c dt / h = 1; 10 periods are 1600 steps (under a second).
BAR = ["-mesh", "meshes/bar80.msh", "-E", 1, "-nu", 0, "-rho", 1, "-contact", 0,
       "-u0_offset", "-0.005,0", "-u0_gradient", "0.01,0,0,0", "-ts_dt", 0.0125]
OMEGA = math.pi   # the exact first mode of the continuous bar
PERIODS = 10
ZETA = 0.01       # 1% of critical: the first mode's amplitude falls to exp(-2 pi 0.1) = 0.53 in 10 periods


def bar_options(tmp_path):
    path = tmp_path / "bar.opts"
    path.write_text("".join(f"{BAR[i]} {BAR[i + 1]}\n" for i in range(0, len(BAR), 2)))
    return str(path)


def first_mode(outdir, omega):
    """The first mode's coordinate q and its rate p, by projection of the snapshots on cos(pi x) with the
    trapezoidal weights (the lumped mass of the uniform bar), and its amplitude sqrt(q^2 + (p/omega)^2).
    The discrete modes are orthogonal in that mass, up to O(h^2), so modes 3, 5, ..., which decay at
    other Rayleigh rates (slower with mass damping, faster with stiffness damping), drop out of q: the
    energy or the end displacement would mix their rates in."""
    with h5py.File(os.path.join(outdir, "solution.h5"), "r") as f:
        x = f["geometry/vertices"][:, 0]
        u = f["vertex_fields/displacement_displacement"][:, :, 0]
        v = f["vertex_fields/velocity_displacement"][:, :, 0]
        t = f["time"][:, 0]
    w = np.where((x < 1e-9) | (x > 1 - 1e-9), 0.5, 1.0)
    phi = np.cos(np.pi * x)
    q = (u * w * phi).sum(1) / (w * phi * phi).sum()
    p = (v * w * phi).sum(1) / (w * phi * phi).sum()
    return t, q, p, np.sqrt(q * q + (p / omega) ** 2)


@pytest.fixture(scope="module")
def omega_discrete(tmp_path_factory):
    """The first mode's angular frequency of the discrete (undamped) bar, from the zero crossings of q
    over two periods; it is pi to 2e-4 (P1 and the trapezoidal rule err by O((pi h)^2))."""
    base = tmp_path_factory.mktemp("undamped")
    r = run(bar_options(base), base, "-ts_max_time", 4.0, "-output_every", 2, "-quiet", np_=0)
    t, q, p, _ = first_mode(r.outdir, OMEGA)
    i = np.nonzero(np.sign(q[1:]) != np.sign(q[:-1]))[0]
    zeros = t[i] - q[i] * (t[i + 1] - t[i]) / (q[i + 1] - q[i])
    omega = math.pi / np.diff(zeros).mean()  # half a period between crossings
    assert len(zeros) == 4 and abs(omega / OMEGA - 1) < 1e-3, zeros
    return omega


def decay_rate(tmp_path, omega, *damping):
    """zeta measured: the slope of log(amplitude) at the 11 snapshots t = 0, T, ..., 10 T over omega.
    Sampled a whole period apart, the amplitude's O(zeta) ripple within a period is at the same phase
    in every sample and drops out of the slope."""
    r = run(bar_options(tmp_path), tmp_path, *damping, "-ts_max_time", PERIODS * 2.0, "-output_every", 160, "-quiet", np_=0)
    t, q, p, a = first_mode(r.outdir, omega)
    assert len(t) == PERIODS + 1
    return -np.polyfit(t, np.log(a), 1)[0] / omega, r


@pytest.mark.parametrize("kind", ["mass", "stiffness", "ratio"])
def test_free_bar_decays_at_the_rayleigh_rate(tmp_path, omega_discrete, kind):
    """The first mode decays at zeta = alpha/(2 omega) + beta omega/2, to 2% over 10 periods: mass
    damping alone, stiffness damping alone, and both from -damping_ratio 0.01 at 0.25 and 1 Hz, which
    give 0.008 at the bar's 0.5 Hz (below the ratio between the two frequencies)."""
    w = omega_discrete
    if kind == "mass":
        alpha, beta, opts = 2 * ZETA * OMEGA, 0.0, ["-damping_mass", 2 * ZETA * OMEGA]
    elif kind == "stiffness":
        alpha, beta, opts = 0.0, 2 * ZETA / OMEGA, ["-damping_stiffness", 2 * ZETA / OMEGA]
    else:
        w1, w2 = 2 * math.pi * 0.25, 2 * math.pi * 1.0
        alpha, beta = 2 * ZETA * w1 * w2 / (w1 + w2), 2 * ZETA / (w1 + w2)
        opts = ["-damping_ratio", ZETA, "-damping_frequencies", "0.25,1"]
    predicted = alpha / (2 * w) + beta * w / 2
    measured, r = decay_rate(tmp_path, w, *opts)
    assert abs(measured / predicted - 1) < 0.02, (measured, predicted)
    h = r.history
    assert h["balance_residual"].max() < 1e-10
    # W_d = -(1/dt) du.C du <= 0 at every step, to round-off of the energy scale (a step with no
    # motion gives +-1e-18)
    assert np.diff(h["work_damping"]).max() <= 1e-14 * np.abs(h["total"]).max() and h["work_damping"][-1] < -0.5 * h["total"][0]


def test_undamped_bar_does_not_decay(tmp_path, omega_discrete):
    """The trapezoidal rule dissipates nothing: the same measurement without damping gives zeta ~ 0, so
    the damped rates above are the damping's."""
    measured, r = decay_rate(tmp_path, omega_discrete)
    assert abs(measured) < 2e-4 * ZETA * 10, measured
    assert np.all(r.history["work_damping"] == 0)


@pytest.mark.parametrize("case,np_,extra", [
    ("d1_disk", 1, ["-damping_mass", 5, "-damping_stiffness", 1e-3]),
    ("d1_friction", 2, ["-damping_stiffness", 1e-3]),
    ("d1_friction", 2, ["-damping_mass", 5, "-damping_stiffness", 1e-3, "-contact_formulation", "active_set"]),
    ("f1_block", 2, ["-damping_ratio", 0.05, "-damping_frequencies", "1,10"]),
])
def test_energy_balance_closes_with_damping(tmp_path, case, np_, extra):
    """With contact (condensed and active set), friction (Newton and the active set's fixed point) and
    the static sliding block: every step's balance E^{n+1} - E^n = W_ext + W_c + W_f + W_d holds at
    solver level, and the running sums of the history add up to the energy change. The active set
    solves K~ by CG (to its tolerance: 2.6e-10 per step on undamped D1 with friction), the condensed
    formulation by a factorization (1e-13)."""
    r = run(case, tmp_path, *extra, "-output_every", 0, "-quiet", np_=np_)
    h = r.history
    scale = np.abs(h["total"]).max()
    tol = 1e-9 if "active_set" in extra else 1e-10
    assert h["balance_residual"].max() < tol
    works = h["work_ext"] + h["work_contact"] + h["work_friction"] + h["work_obstacle"] + h["work_damping"]
    assert np.abs(h["total"] - h["total"][0] - works).max() < 10 * tol * scale
    # W_d = -(1/dt) du.C du <= 0 at every step, to round-off of the energy scale (a step with no
    # motion gives +-1e-18)
    assert np.diff(h["work_damping"]).max() <= 1e-14 * scale
    assert h["work_damping"][-1] < -0.05 * h["total"][0]  # the damping did dissipate
    assert h["active"].max() > 0
    if "-mu" in open(os.path.join("options", case + ".opts")).read() or case == "f1_block":
        assert h["work_friction"][-1] < -0.01 * h["total"][0]


def test_damped_one_and_two_ranks_agree(tmp_path):
    """The damped D1 impact on 1 and 2 ranks: the same energies and works to 1e-10 of the energy scale."""
    extra = ["-damping_mass", 5, "-damping_stiffness", 1e-3, "-output_every", 0, "-quiet"]
    a = run("d1_disk", tmp_path, *extra, np_=1, name="one").history
    b = run("d1_disk", tmp_path, *extra, np_=2, name="two").history
    scale = np.abs(a["total"]).max()
    for c in ("kinetic", "elastic", "total", "work_damping", "work_contact", "force_normal"):
        s = scale if c != "force_normal" else np.abs(a[c]).max()
        assert np.abs(a[c] - b[c]).max() <= 1e-10 * s, c
    assert np.array_equal(a["active"], b["active"])


def test_damping_ratio_gives_alpha_and_beta(tmp_path):
    """-damping_ratio 0.03 at 2 and 7 Hz: the header prints, and the checkpoint's run record holds (the
    values the run used), alpha = 2 zeta w1 w2/(w1 + w2) and beta = 2 zeta/(w1 + w2)."""
    r = run(bar_options(tmp_path), tmp_path, "-damping_ratio", 0.03, "-damping_frequencies", "2,7",
            "-ts_max_steps", 2, np_=0)
    w1, w2 = 2 * math.pi * 2, 2 * math.pi * 7
    alpha, beta = 2 * 0.03 * w1 * w2 / (w1 + w2), 2 * 0.03 / (w1 + w2)
    m = re.search(r"damping: Rayleigh C = alpha M\* \+ beta (?:K|B \(K without the massless contact-normal dofs\)), alpha = (\S+) 1/s, beta = (\S+) s \(-damping_ratio 0.03 at 2 and 7 Hz\)", r.output)
    assert m, r.output[-2000:]
    assert abs(float(m.group(1)) / alpha - 1) < 1e-9 and abs(float(m.group(2)) / beta - 1) < 1e-9
    with h5py.File(os.path.join(r.outdir, "checkpoint.h5"), "r") as f:
        rec = f["run"][:]
    assert abs(rec[27] / alpha - 1) < 1e-14 and abs(rec[28] / beta - 1) < 1e-14
    # the rate these give at 2 and 7 Hz is the ratio
    for w in (w1, w2):
        assert abs(alpha / (2 * w) + beta * w / 2 - 0.03) < 1e-12


def test_no_damping_prints_nothing_and_adds_a_zero_column(tmp_path):
    r = run(bar_options(tmp_path), tmp_path, "-ts_max_steps", 3, np_=0)
    assert "damping:" not in r.output
    assert np.all(r.history["work_damping"] == 0)


@pytest.mark.parametrize("extra,message", [
    (["-damping_ratio", 0.02, "-damping_mass", 1, "-damping_frequencies", "1,2"], "-damping_ratio was given together with -damping_mass or -damping_stiffness: the ratio sets both alpha and beta"),
    (["-damping_ratio", 0.02, "-damping_stiffness", 1e-3, "-damping_frequencies", "1,2"], "-damping_ratio was given together with -damping_mass or -damping_stiffness"),
    (["-damping_ratio", 0.02], "-damping_ratio needs the two frequencies (Hz) at which it holds: give -damping_frequencies f1,f2 (it is missing)"),
    (["-damping_ratio", 0.02, "-damping_frequencies", "1"], "give -damping_frequencies f1,f2 (it needs exactly 2 entries)"),
    (["-damping_ratio", 0.02, "-damping_frequencies", "0,2"], "-damping_frequencies 0,2: both frequencies must be > 0 (Hz)"),
    (["-damping_ratio", 0.02, "-damping_frequencies", "1,-2"], "both frequencies must be > 0 (Hz)"),
    (["-damping_ratio", -0.02, "-damping_frequencies", "1,2"], "-damping_ratio -0.02 must be >= 0"),
    (["-damping_mass", -1], "-damping_mass -1 must be >= 0"),
    (["-damping_stiffness", -1e-3], "-damping_stiffness -0.001 must be >= 0"),
    (["-damping_frequencies", "1,2"], "-damping_frequencies is only read with -damping_ratio: give -damping_ratio zeta too"),
    (["-damping_mass", "nan"], "-damping_mass: entry 0 is NaN"),
])
def test_bad_damping_input_is_refused(tmp_path, extra, message):
    r = run(bar_options(tmp_path), tmp_path, *extra, "-ts_max_steps", 1, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-2000:]
