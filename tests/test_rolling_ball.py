"""The rolling ball (issue 40's target; options/ball_roll.opts): an elastic ball (svk) thrown along a
rough plane (mu = 0.5, gravity 9.81) with backspin slides, spins up and then rolls without slipping,
its energy constant while it rolls; the linear model cannot roll it. Each tolerance is against the
case's physical scale: the initial energy, the rolling speed, the weight, h_c'.

Independent measures from solution.h5 (a snapshot every 10 steps): the ball's rotation angle about y
from its node positions (the rotation of the best rigid fit, unwrapped from snapshot to snapshot), and
its angular velocity from the velocity field (the rigid fit of the P1 consistent mass: I^-1 times the
angular momentum about the centre). The history's L_y is not used for omega: it is the scheme's, of
M*, whose inertia follows the ball's orientation (-mass redistributed matches M's moments in the
reference configuration only): measured on this run, L_y is 0.79 to 1.00 of I omega while it rolls."""
import os

import h5py
import numpy as np
import pytest

from conftest import ROOT, run

R = 1.0  # the ball's radius (meshes/ball_roll.geo)


def case_options():
    """-v0, -omega0, -mu, -gravity, -gravity_amplitude_time of options/ball_roll.opts"""
    opts = {}
    for line in open(os.path.join(ROOT, "options", "ball_roll.opts")):
        words = line.split("#")[0].split()
        if len(words) == 2:
            opts[words[0]] = [float(w) for w in words[1].split(",")] if words[1][0] in "-0123456789." else words[1]
    return dict(v0=opts["-v0"][0], w0=opts["-omega0"][1], mu=opts["-mu"][0], g=-opts["-gravity"][2],
                ramp=opts["-gravity_amplitude_time"][0])


def ball_motion(outdir):
    """Per snapshot: time, the rotation angle about y (unwrapped), the rigid angular velocity about y;
    and the ball's mass m and reference inertia I_yy (P1 consistent mass, rho = 1)."""
    with h5py.File(os.path.join(outdir, "solution.h5"), "r") as f:
        X = f["geometry/vertices"][:]
        cells = f["viz/topology/cells"][:].astype(int)
        t = f["time"][:].ravel()
        U = f["vertex_fields/displacement_displacement"][:]
        V = f["vertex_fields/velocity_displacement"][:]
    vol = np.abs(np.linalg.det(np.stack([X[cells[:, k + 1]] - X[cells[:, 0]] for k in range(3)], axis=2))) / 6
    m_node = np.zeros(len(X))
    np.add.at(m_node, cells.ravel(), np.repeat(vol / 4, 4))  # the row sums of the consistent mass
    m = vol.sum()

    def moments(x, v):
        """centre, inertia tensor and angular momentum about the centre of the consistent mass:
        int r r^T = |T|/20 (sum_a r_a r_a^T + (sum_a r_a)(sum_a r_a)^T), and so for r x v"""
        c = (m_node[:, None] * x).sum(0) / m
        r, w = x[cells] - c, v[cells] - (m_node[:, None] * v).sum(0) / m
        S = (np.einsum("c,cai,caj->ij", vol, r, r) + np.einsum("c,ci,cj->ij", vol, r.sum(1), r.sum(1))) / 20
        L = (np.einsum("c,cai->i", vol, np.cross(r, w)) + np.einsum("c,ci->i", vol, np.cross(r.sum(1), w.sum(1)))) / 20
        return c, np.trace(S) * np.eye(3) - S, L

    c0, I0, _ = moments(X, np.zeros_like(X))
    theta, omega, rot_prev = [0.0], [], np.eye(3)
    for k in range(len(t)):
        x = X + U[k]
        c, I, L = moments(x, V[k])
        omega.append(np.linalg.solve(I, L)[1])
        # the rotation of the best rigid fit x - c = Q (X - c0) (Kabsch), and its increment about y
        Us, _, Vt = np.linalg.svd(((X - c0) * m_node[:, None]).T @ (x - c))
        Q = Vt.T @ np.diag([1, 1, np.sign(np.linalg.det(Vt.T @ Us.T))]) @ Us.T
        if k:
            dQ = Q @ rot_prev.T
            theta.append(theta[-1] + np.arctan2(dQ[0, 2] - dQ[2, 0], dQ[0, 0] + dQ[2, 2]))
        rot_prev = Q
    return dict(t=t, theta=np.array(theta), omega=np.array(omega), m=m, I=I0[1, 1])


def rigid_sphere(p, m, I):
    """A rigid sphere of mass m and inertia I sliding at v0 with spin w0 under mu m g(t), g ramped up
    over T: the contact point slides at v - w R until v = (v0 + k w0 R) / (1 + k), k = I / (m R^2),
    when the friction impulse mu m (g (t - T / 2)) has taken m (v0 - v) (for t >= T)."""
    k = I / (m * R * R)
    v_roll = (p["v0"] + k * p["w0"] * R) / (1 + k)
    return p["ramp"] / 2 + (p["v0"] - v_roll) / (p["mu"] * p["g"]), v_roll


@pytest.fixture(scope="module")
def rolls(tmp_path_factory):
    """options/ball_roll.opts (svk), with what the test measures"""
    r = run("ball_roll", tmp_path_factory.mktemp("roll"), name="svk")
    p = case_options()
    motion = ball_motion(r.outdir)
    t_roll, v_roll = rigid_sphere(p, motion["m"], motion["I"])
    return dict(run=r, h=r.history, p=p, motion=motion, t_roll=t_roll, v_roll=v_roll,
                h_c=float(r.output.split("(h_c' ")[1].split(")")[0]))


def test_slides_then_rolls_as_a_rigid_sphere(rolls):
    """From its first contact the ball slides (tangential force mu times the normal force) until the time
    a rigid sphere of the mesh's mass and inertia would start rolling (0.393 here), within 8%, at its
    rolling speed (2.586), within 4%. Measured: 4.8% later and 2.4% slower. The elastic ball on its
    compliant contact differs: it bounces on the plane (its normal impulse is m g t + m v_z), and its
    contact point shears before it slips. Before its first contact (t = 0.064) the faceted ball turning
    backwards lifts its lowest vertex faster than the ramped gravity pulls it down. Coulomb's law holds
    at every step."""
    h, p = rolls["h"], rolls["p"]
    weight = rolls["motion"]["m"] * p["g"]
    Fn, Ft = h["force_normal"], h["force_tangential"]
    assert np.all(Ft <= p["mu"] * Fn + 1e-10 * weight)
    loaded = Fn > 1e-6 * weight
    sliding = loaded & (Ft >= (1 - 1e-3) * p["mu"] * Fn)
    first = np.argmax(loaded)
    assert h["time"][first] <= 0.1 and sliding[first]
    end = first + np.argmax(loaded[first:] & ~sliding[first:])  # the first loaded step that does not slide
    assert rolls["t_roll"] == pytest.approx(0.393, abs=1e-3) and rolls["v_roll"] == pytest.approx(2.586, abs=1e-3)
    assert h["time"][end] == pytest.approx(rolls["t_roll"], rel=0.08)
    assert h["vcm_x"][end] == pytest.approx(rolls["v_roll"], rel=0.04)


def test_rolls_without_slipping(rolls):
    """From 0.2 after the rigid sphere's rolling time to the end (t = 0.593 to 1.6, 51 snapshots) the
    centre moves by R times the angle the ball turns, within 1%: the mean centre velocity (ucm_x's change
    over the time, which is the mean of vcm_x: the scheme's u^{n+1} - u^n = dt (v^n + v^{n+1}) / 2)
    against omega R, omega the mean angular velocity from the snapshots' rotation (measured 0.41% low),
    and the slope of ucm_x against the rotation angle over every snapshot (0.47% low): the ball rolls on
    its flattened contact, its centre 0.017 below R. At each snapshot, vcm_x = omega R with the omega of
    the snapshot's velocity field within 12% of the rolling speed (measured 8.2%: the undamped elastic
    ball rocks on its contact since the slide ended). By the end it has turned by more than 3 radians."""
    h, mo = rolls["h"], rolls["motion"]
    t0 = rolls["t_roll"] + 0.2
    snap = mo["t"] >= t0
    t, theta = mo["t"][snap], mo["theta"][snap]
    x_c = np.interp(t, h["time"], h["ucm_x"])  # the snapshots are at steps: these are the history's values
    assert len(t) >= 50 and theta[-1] - theta[0] >= 2.5 and mo["theta"][-1] >= 3.0
    v_mean, omega_mean = (x_c[-1] - x_c[0]) / (t[-1] - t[0]), (theta[-1] - theta[0]) / (t[-1] - t[0])
    assert abs(v_mean - omega_mean * R) <= 0.01 * omega_mean * R
    assert abs(np.polyfit(theta, x_c, 1)[0] - R) <= 0.01 * R
    v_snap = np.interp(t, h["time"], h["vcm_x"])
    assert np.abs(v_snap - mo["omega"][snap] * R).max() <= 0.12 * v_mean


def test_energy_constant_while_rolling(rolls):
    """The exact balance at every step (residual at most 1e-10, the energies' identity total - W_ext -
    W_friction - W_contact constant to 1e-9 of the initial energy E0 over the run), no penetration beyond
    1e-10 h_c', the Coulomb residual at solver level, the plane doing no work it creates (W_contact never positive, within 2e-4 of
    E0). While it rolls, the energy (kinetic + elastic - the work of gravity) stays constant within 5e-3
    of E0 (measured 2.4e-3: the friction work of the trailing contact node's micro-slip as it leaves
    the plane), where the slide took 0.47 of E0, and the ball never leaves the plane."""
    h = rolls["h"]
    E0 = h["total"][0]
    assert h["balance_residual"].max() <= 1e-10
    identity = h["total"] - h["work_ext"] - h["work_friction"] - h["work_contact"]
    assert np.abs(identity - E0).max() <= 1e-9 * E0
    assert h["max_penetration"].max() <= 1e-10 * rolls["h_c"]
    assert h["coulomb_residual"].max() <= 1e-8
    # the plane's work: each node touching down as the ball rolls on (1 or 2 nodes bear it) meets the
    # plane over one step; measured 1.0e-4 of E0 at dt 2e-3 and 2.8e-5 at dt 1e-3: it goes with dt
    assert np.abs(h["work_contact"]).max() <= 2e-4 * E0
    assert h["work_contact"].max() <= 1e-10 * E0  # and it never creates energy
    rolling = h["time"] >= rolls["t_roll"] + 0.2
    energy = h["total"] - h["work_ext"]
    assert np.ptp(energy[rolling]) <= 5e-3 * E0
    assert energy[0] - energy[rolling][0] >= 0.4 * E0
    assert h["active"][rolling].min() >= 1


def test_linear_model_cannot_roll(tmp_path, rolls):
    """The same run with the linear model: its ball keeps the velocity of an infinitesimal rotation, which
    has no strain, so it grows instead of turning (its centre rises by 0.41 R) and it does not roll: over
    the window where svk holds its energy to 2.4e-3 of E0 the linear one loses 0.16 of E0 to friction,
    and it ends moving backwards (measured vcm_x -2.1 against svk's +2.5)."""
    lin = run("ball_roll", tmp_path, "-elasticity", "linear", "-output_every", 0, name="linear")
    h, E0 = lin.history, lin.history["total"][0]
    rolling = h["time"] >= rolls["t_roll"] + 0.2
    assert np.ptp((h["total"] - h["work_ext"])[rolling]) >= 0.05 * E0
    assert h["ucm_z"].max() >= 0.2 * R
    assert h["vcm_x"][-1] < 0 < rolls["h"]["vcm_x"][-1]
    assert h["balance_residual"].max() <= 1e-10  # exact, but of the wrong model
