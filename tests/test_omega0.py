"""-omega0 and -body_NAME_omega0 (issue 40, README "Bodies"): an initial rigid rotation about each
body's own centre of mass, added to -v0 and -omega. Without contact (M* = M, the consistent mass)
the history's P and J are exact integrals of rho v and rho x x v for a P1 velocity, so at t = 0:
rotation about the centre of mass carries no momentum (-omega about the origin does), J about the
origin is sum_b omega_b I_b with I_b each body's polar moment about its own centre of mass, and
-omega0 w is -omega w -omega_center x_cm, x_cm computed here from the mesh. 1 and 2 ranks agree;
glued bodies and wrong lengths are refused by name.

meshes/side_bars.msh: bar_a [0, 1] x [0, 0.02] and bar_b [0, 1] x [0.04, 0.06], separate, plane
strain; meshes/cube_drop.msh: the unit cube centred at (0, 0, 0.55), 3D."""
import numpy as np
import pytest

from conftest import run

FREE = ("-contact", 0, "-E", 1, "-nu", 0, "-rho", 1, "-ts_dt", 0.02, "-ts_max_time", 0.06, "-output_every", 0, "-quiet")
BARS = ("-mesh", "meshes/side_bars.msh", *FREE)
CUBE = ("-mesh", "meshes/cube_drop.msh", *FREE)
TWO = ("-bodies", "A,B", "-body_A_group", "bar_a", "-body_B_group", "bar_b", "-body_B_rho", 2)
RHO_B = 2.0
COLUMNS_2D = ("kinetic", "P_x", "P_y", "J_z", "L_z", "vcm_x", "vcm_y")
COLUMNS_3D = ("kinetic", "P_x", "P_y", "P_z", "J_x", "J_y", "J_z", "L_x", "L_y", "L_z", "vcm_x", "vcm_y", "vcm_z")


def case(tmp_path, *extra, np_=1, name="out", check=True):
    """A run given by its options alone (as tests/test_bodies.py's two bars)."""
    opts = tmp_path / "empty.opts"
    opts.write_text("# tests/test_omega0.py: every option on the command line\n")
    return run(str(opts), tmp_path, *extra, np_=np_, name=name, check=check)


def bodies(r, rho=lambda c: np.ones(len(c))):
    """Per cell of the run's mesh: its vertices' coordinates, centroid, measure and density."""
    with r.fields() as f:
        X = f["geometry/vertices"][:]
        cells = f["viz/topology/cells"][:].astype(int)
    x = X[cells]
    dim = X.shape[1]
    J = np.stack([x[:, k + 1] - x[:, 0] for k in range(dim)], axis=2)
    vol = np.abs(np.linalg.det(J)) / (2 if dim == 2 else 6)
    c = x.mean(axis=1)
    return x, c, vol, rho(c)


def moments(x, c, vol, rho):
    """Mass, centre of mass (sum rho |T| x_T / sum rho |T|) and the second moment tensor about it,
    exact for P1: int_T y y^T = |T| / ((d+1)(d+2)) (sum_a y_a y_a^T + (sum_a y_a)(sum_a y_a)^T)."""
    d = x.shape[2]
    m = rho * vol
    xcm = (m[:, None] * c).sum(axis=0) / m.sum()
    y = x - xcm
    s = y.sum(axis=1)
    S = np.einsum("c,cai,caj->ij", m, y, y) + np.einsum("c,ci,cj->ij", m, s, s)
    return m.sum(), xcm, S / ((d + 1) * (d + 2)), float(np.linalg.norm(y, axis=2).max())


def test_rotation_about_the_centre_of_mass_carries_no_momentum(tmp_path):
    """The two bars as one body (centre of mass (0.5, 0.03)), omega = 0.1: with -omega0 P = 0 to
    1e-12 of m omega R and J_z = omega I_cm; -omega about the origin instead carries P = m omega x x_cm
    (P_y = 2e-3 here), to the same tolerance."""
    w = 0.1
    a = case(tmp_path, *BARS, "-omega0", w, name="omega0")
    o = case(tmp_path, *BARS, "-omega", w, name="omega")
    m, xcm, S, R = moments(*bodies(a))
    scale = m * w * R
    h, g = a.history, o.history
    assert abs(h["P_x"][0]) <= 1e-12 * scale and abs(h["P_y"][0]) <= 1e-12 * scale
    assert abs(h["J_z"][0] - w * np.trace(S)) <= 1e-12 * scale * R
    assert abs(g["P_x"][0] + m * w * xcm[1]) <= 1e-12 * scale and abs(g["P_y"][0] - m * w * xcm[0]) <= 1e-12 * scale
    assert abs(g["P_y"][0]) > 0.5 * scale  # the test can tell them apart


@pytest.mark.parametrize("mesh,w,columns", [(BARS, ("0.1",), COLUMNS_2D), (CUBE, ("0.1", "-0.2", "0.3"), COLUMNS_3D)], ids=["2d", "3d"])
def test_omega0_is_omega_about_the_centre_of_mass(tmp_path, mesh, w, columns):
    """-omega0 w gives the history of -omega w -omega_center x_cm, x_cm from the mesh, with -v0 added
    to both: each column at t = 0 and after 3 steps to 1e-12 of its scale (m |w| R, times R for J
    and L, m |w|^2 R^2 for the kinetic energy)."""
    wv = np.array([float(s) for s in w])
    v0 = ",".join(["0.01"] * (3 if len(w) == 3 else 2))
    a = case(tmp_path, *mesh, "-v0", v0, "-omega0", ",".join(w), name="omega0")
    m, xcm, S, R = moments(*bodies(a))
    b = case(tmp_path, *mesh, "-v0", v0, "-omega", ",".join(w), "-omega_center", ",".join(repr(float(x)) for x in xcm), name="omega")
    p = m * np.linalg.norm(wv) * R + m * 0.02
    scale = {"kinetic": p * p / m}
    for c in columns:
        s = scale.get(c, p * R if c[0] in "JL" else p if c[0] == "P" else p / m)
        assert np.abs(a.history[c] - b.history[c]).max() <= 1e-12 * s, c


@pytest.mark.parametrize("vb", [0.0, 0.01], ids=["spin", "spin_and_v0"])
def test_each_body_spins_about_its_own_centre(tmp_path, vb):
    """bar_a (rho 1) with -body_A_omega0 0.1, bar_b (rho 2) with -body_B_omega0 -0.2 and
    -body_B_v0 vb,0: P = m_b (vb, 0) (zero without it) and J_z about the origin = sum_b omega_b I_b
    + x_cm,b x P_b, each body's centre and moment from its own cells, to 1e-12 of m omega R."""
    wa, wb = 0.1, -0.2
    r = case(tmp_path, *BARS, *TWO, "-body_A_omega0", wa, "-body_B_omega0", wb, "-body_B_v0", f"{vb},0")
    x, c, vol, rho = bodies(r)
    in_b = c[:, 1] > 0.03
    ma, xa, Sa, Ra = moments(x[~in_b], c[~in_b], vol[~in_b], rho[~in_b])
    mb, xb, Sb, Rb = moments(x[in_b], c[in_b], vol[in_b], RHO_B * rho[in_b])
    scale = (ma + mb) * max(abs(wa), abs(wb)) * max(Ra, Rb)
    h = r.history
    assert abs(h["P_x"][0] - mb * vb) <= 1e-12 * scale and abs(h["P_y"][0]) <= 1e-12 * scale
    jz = wa * np.trace(Sa) + wb * np.trace(Sb) - xb[1] * mb * vb
    assert abs(h["J_z"][0] - jz) <= 1e-12 * scale * max(Ra, Rb)


def test_one_and_two_ranks_give_the_same_initial_state(tmp_path):
    """The two spinning bodies on 1 and 2 ranks (each body's centre summed over the ranks): every
    momentum and energy column equal to 1e-12 of its scale at t = 0, 1e-10 after 3 steps."""
    h = {n: case(tmp_path, *BARS, *TWO, "-body_A_omega0", 0.1, "-body_B_omega0", -0.2, np_=n, name=f"np{n}").history for n in (1, 2)}
    p = 0.06 * 0.2 * 0.5
    for c in COLUMNS_2D:
        s = p * p / 0.06 if c == "kinetic" else p * 0.5 if c[0] in "JL" else p
        assert abs(h[1][c][0] - h[2][c][0]) <= 1e-12 * s, c
        assert np.abs(h[1][c] - h[2][c]).max() <= 1e-10 * s, c


def test_glued_bodies_and_wrong_lengths_are_refused(tmp_path):
    """A vertex shared by two bodies rotating about two centres would tear at t = 0: refused naming
    -body_NAME_omega0 and the alternative; a 2D -body_NAME_omega0 of 2 entries and a nan -omega0
    are refused by name (exit 64)."""
    glued = ("-mesh", "meshes/bimaterial.msh", "-bodies", "l,r", "-body_l_group", "left_half", "-body_r_group", "right_half", *FREE)
    r = case(tmp_path, *glued, "-omega0", 0.1, np_=0, check=False)
    assert r.returncode == 64 and "-body_NAME_omega0" in r.output and "-omega_center" in r.output, r.output[-2000:]
    r = case(tmp_path, *BARS, *TWO, "-body_A_omega0", "1,2", np_=0, check=False)
    assert r.returncode == 64 and "-body_A_omega0 has 2 entries" in r.output, r.output[-2000:]
    r = case(tmp_path, *BARS, "-omega0", "nan", np_=0, check=False)
    assert r.returncode == 64 and "-omega0" in r.output and "NaN" in r.output, r.output[-2000:]
