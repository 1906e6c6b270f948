"""Bodies of their own material and initial velocity (-bodies, README "Bodies", docs/method.md
section 2): a stress pulse crossing a material interface splits as the impedances say, two bars of
two materials and two velocities carry each its own momentum and energy, and hit a wall each with its
own contact stress and duration; one body covering the mesh is the run without -bodies; 1 and 2
ranks agree, a restart continues bit for bit, and bad input is refused by name.

The meshes (meshes/bimaterial.geo, meshes/side_bars.geo) are strips of plane strain with nu = 0, so
each bar is 1D: sigma = E eps, wave speed c = sqrt(E / rho), impedance Z = rho c."""
import os

import h5py
import numpy as np
import pytest

from conftest import ROOT, run

# options/bimaterial_pulse.opts: left_half [0, 0.5] and right_half [0.5, 1.5], width W
L1, L2, W = 0.5, 1.0, 0.5 / 40
E1, RHO1, E2, RHO2 = 1.0, 1.0, 8.0, 2.0
C1, C2 = (E1 / RHO1) ** 0.5, (E2 / RHO2) ** 0.5          # 1 and 2
Z1, Z2 = RHO1 * C1, RHO2 * C2                           # 1 and 4
R, T = (Z2 - Z1) / (Z2 + Z1), 2 * Z2 / (Z1 + Z2)        # stress: 0.6 reflected, 1.6 transmitted
SIGMA, TP, DT = 1e-3, 0.2, 0.0125                       # the pulse on x = 0: sigma sin(pi t / TP)

# options/two_bars_impact.opts: bar_a [0, 1] x [0, Wb], bar_b [0, 1] x [2 Wb, 3 Wb]
LB, WB, DTB = 1.0, 0.02, 0.02
EB, RHOB = 8.0, 2.0                                     # bar_b; bar_a has E = rho = 1
MA, MB = 1.0 * LB * WB, RHOB * LB * WB                  # the bars' masses
TWO_BARS = ("-mesh", "meshes/side_bars.msh", "-E", 1, "-nu", 0, "-rho", 1, "-bodies", "bar_a,bar_b",
            "-body_bar_a_group", "bar_a", "-body_bar_b_group", "bar_b", "-body_bar_b_E", EB, "-body_bar_b_rho", RHOB)


def pulse_options(tmp_path, drop, name):
    """options/bimaterial_pulse.opts without the lines of the options in drop (prefixes)."""
    lines = [l for l in open(os.path.join(ROOT, "options", "bimaterial_pulse.opts")).read().splitlines() if not l.startswith(drop)]
    path = tmp_path / (name + ".opts")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def energies_by_region(r, k, E, rho):
    """Kinetic plus elastic energy of snapshot k, per cell, from the fields alone: P1 strains and the
    consistent mass rho_T |T| (1 + delta_ab) / 12 of each cell with its own E and rho (nu = 0:
    lambda = 0, mu = E / 2). Their sum is the scheme's energy exactly when the scheme assembles each
    cell with its body's material."""
    with r.fields() as f:
        X = f["geometry/vertices"][:]
        cells = f["viz/topology/cells"][:].astype(int)
        u = f["vertex_fields/displacement_displacement"][k]
        v = f["vertex_fields/velocity_displacement"][k]
    x = X[cells]
    J = np.stack([x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]], axis=2)          # columns: the edges
    area = np.abs(np.linalg.det(J)) / 2
    du = np.stack([u[cells[:, 1]] - u[cells[:, 0]], u[cells[:, 2]] - u[cells[:, 0]]], axis=2)
    grad = du @ np.linalg.inv(J)
    eps = 0.5 * (grad + np.transpose(grad, (0, 2, 1)))
    mu = E(x.mean(axis=1)) / 2
    elastic = mu * np.sum(eps * eps, axis=(1, 2)) * area
    Mloc = (np.ones((3, 3)) + np.eye(3)) / 12
    vc = v[cells]                                                          # cell, vertex, component
    kinetic = 0.5 * rho(x.mean(axis=1)) * area * np.einsum("cai,ab,cbi->c", vc, Mloc, vc)
    return x.mean(axis=1), elastic + kinetic


@pytest.fixture(scope="module")
def pulse(tmp_path_factory):
    """The bimaterial pulse on 1 and on 2 ranks."""
    base = tmp_path_factory.mktemp("pulse")
    return {n: run("bimaterial_pulse", base, np_=n, name=f"np{n}") for n in (1, 2)}


def test_pulse_splits_at_the_interface(pulse):
    """The pulse enters the left half (Z1 = 1) and meets the right half (Z2 = 4) at t = 0.5. At
    t = 0.85 the reflected pulse is back in the left half, the transmitted one in the right half,
    neither has reached an end: the energy splits as R^2 = 0.36 and 1 - R^2 = 4 Z1 Z2 / (Z1 + Z2)^2
    = 0.64, to 1% (measured 1e-4). The particle velocity at x = 0.25 is sigma / Z1 going in and
    -R sigma / Z1 coming back; at x = 1 it is T sigma / Z2, at the free end x = 1.5 twice that,
    arriving at t = L1 / c1 + L2 / c2 + TP / 2 = 1.1; the right half's cell stress is -T sigma.
    Peak heights within 6% (P1 disperses the pulse's kinks: measured 0.8% to 5%), times within
    2 steps. A right half with its rho ignored (c = 2.8, Z = 2.8) would split the energy 0.22/0.78
    and arrive at x = 1.5 at t = 0.95, 12 steps early."""
    r = pulse[1]
    h = r.history
    assert h["balance_residual"].max() <= 1e-10
    # the start-up report: one line per body
    assert "material: 2 bodies (-bodies); the largest wave speed, c_p = 2, sets c_p dt / h_c'" in r.output
    assert "body left_half (group left_half): 160 cells; E = 1, nu = 0, rho = 1; waves c_p = 1, c_s = 0.7071; mass 0.00625" in r.output
    assert "body right_half (group right_half): 160 cells; E = 8, nu = 0, rho = 2; waves c_p = 2, c_s = 1.414; mass 0.025" in r.output
    with r.fields() as f:
        X = f["geometry/vertices"][:]
        t = f["time"][:, 0]
        vel = f["vertex_fields/velocity_displacement"][:]
        stress = f["cell_fields/stress_cell"][:]
        cells = f["viz/topology/cells"][:].astype(int)
    k = int(np.argmin(np.abs(t - 0.85)))
    assert abs(t[k] - 0.85) < 1e-9
    right = lambda x: x[:, 0] > L1
    xc, e = energies_by_region(r, k, lambda x: np.where(right(x), E2, E1), lambda x: np.where(right(x), RHO2, RHO1))
    row = int(np.argmin(np.abs(h["time"] - t[k])))
    scale = np.abs(h["total"]).max()
    # the scheme's energy is the sum of the cells' energies, each cell with its body's E and rho
    assert abs(e.sum() - h["total"][row]) <= 1e-10 * scale, (e.sum(), h["total"][row])
    share = e[right(xc)].sum() / e.sum()
    assert abs(share - (1 - R ** 2)) <= 0.01, share
    assert abs(e[~right(xc)].sum() / e.sum() - R ** 2) <= 0.01
    v_in = SIGMA / Z1

    def peak(x0, t0, t1):
        at = np.abs(X[:, 0] - x0) < 1e-9
        v = vel[:, at, 0].mean(axis=1)
        w = (t >= t0) & (t < t1)
        i = np.argmax(np.abs(v[w]))
        return t[w][i], v[w][i]

    tp, vp = peak(0.25, 0, 0.6)
    assert abs(vp - v_in) <= 0.06 * v_in and abs(tp - (0.25 / C1 + TP / 2)) <= 2 * DT, (tp, vp)
    tp, vp = peak(0.25, 0.6, 1.0)
    assert abs(vp + R * v_in) <= 0.06 * R * v_in and abs(tp - (0.5 + 0.25 / C1 + TP / 2)) <= 2 * DT, (tp, vp)
    tp, vp = peak(1.0, 0.6, 1.0)
    v_T = T * SIGMA / Z2
    assert abs(vp - v_T) <= 0.06 * v_T and abs(tp - (L1 / C1 + 0.5 / C2 + TP / 2)) <= 2 * DT, (tp, vp)
    tp, vp = peak(L1 + L2, 0.6, 1.25)
    assert abs(vp - 2 * v_T) <= 0.06 * 2 * v_T and abs(tp - (L1 / C1 + L2 / C2 + TP / 2)) <= 2 * DT, (tp, vp)
    # the cell stress of the right half, E2 times its strain: -T sigma (compression)
    s_right = stress[k][X[cells].mean(axis=1)[:, 0] > L1, 0]
    assert abs(s_right.min() + T * SIGMA) <= 0.06 * T * SIGMA, s_right.min()


def test_pulse_on_two_ranks(pulse):
    """The same run on 2 ranks: the energies and works to 1e-10 of the energy scale."""
    a, b = pulse[1].history, pulse[2].history
    scale = np.abs(a["total"]).max()
    assert list(a["step"]) == list(b["step"])
    for c in ("kinetic", "elastic", "total", "work_ext"):
        assert np.abs(a[c] - b[c]).max() <= 1e-10 * scale, c


def test_two_bars_carry_their_own_momentum_and_energy(tmp_path):
    """Two separate bars, no contact: bar_a (E = rho = 1) moving along x at 0.01, bar_b (E = 8,
    rho = 2) along -y at 0.02, both stretched by the strain eps_xx = 1e-3 (u0 = B x, the same for
    the whole mesh). At t = 0, exactly (to 1e-12 of each scale): P_x = m_a v_a and P_y = m_b v_b (so
    each body has its own v0 and its own mass), the kinetic energy 1/2 (m_a v_a^2 + m_b v_b^2) and the
    elastic energy 1/2 eps^2 (E_a |bar_a| + E_b |bar_b|). Then each bar rings in its own axial modes
    while the energy, and each momentum, stay constant (1e-10 of their scale) on 1 and 2 ranks."""
    va, vb, eps = 0.01, -0.02, 1e-3
    common = (*TWO_BARS, "-contact", 0, "-body_bar_a_v0", f"{va},0", "-body_bar_b_v0", f"0,{vb}",
              "-u0_gradient", f"{eps},0,0,0", "-ts_dt", DTB, "-ts_max_time", 1.0, "-output_every", 0)
    # the case is given by its options alone: run from an options file without any
    opts = tmp_path / "empty.opts"
    opts.write_text("# tests/test_bodies.py: two bars, every option on the command line\n")
    h = {n: run(str(opts), tmp_path, *common, np_=n, name=f"np{n}").history for n in (1, 2)}
    a = h[1]
    kinetic0 = 0.5 * (MA * va ** 2 + MB * vb ** 2)
    elastic0 = 0.5 * eps ** 2 * (1.0 * LB * WB + EB * LB * WB)
    escale, pscale = kinetic0 + elastic0, MA * abs(va) + MB * abs(vb)
    assert abs(a["P_x"][0] - MA * va) <= 1e-12 * pscale and abs(a["P_y"][0] - MB * vb) <= 1e-12 * pscale
    assert abs(a["kinetic"][0] - kinetic0) <= 1e-12 * escale
    assert abs(a["elastic"][0] - elastic0) <= 1e-12 * escale
    # the bars ring: strain energy goes to kinetic and back
    assert a["elastic"].min() < 0.2 * elastic0
    assert np.abs(a["total"] - a["total"][0]).max() <= 1e-10 * escale
    assert np.abs(a["P_x"] - MA * va).max() <= 1e-10 * pscale and np.abs(a["P_y"] - MB * vb).max() <= 1e-10 * pscale
    assert a["balance_residual"].max() <= 1e-10
    for c in ("kinetic", "elastic", "total"):
        assert np.abs(a[c] - h[2][c]).max() <= 1e-10 * escale, c


def test_two_bars_hit_a_wall(tmp_path):
    """B2 for two bodies at once (options/two_bars_impact.opts): bar_a (Z = 1, v0 = -0.01) touches
    the wall at t = 0.02 and presses with the stress Z v0 = 0.01 for 2 L / c_a = 2, bar_b (Z = 4,
    v0 = -0.005) touches at t = 0.04 and presses with 0.02 for 2 L / c_b = 1. The wall's force per
    unit width is 0.03 while both press and 0.01 once bar_b has left, within 2% (B2's bound), the
    releases within 2 steps of t = 1.04 and 2.02, and both bars leave at their speed reversed: the
    momentum, -(m_a 0.01 + m_b 0.005) but the contact nodes' normal mass, turns to its opposite
    (2%, the rebound of B2; measured 1.1%). A
    single material for both bars would give one plateau and one duration."""
    h = run("two_bars_impact", tmp_path).history
    t, s = h["time"], h["force_normal"] / WB
    both = (t >= 0.1) & (t <= 0.95)
    one = (t >= 1.15) & (t <= 1.9)
    assert np.all(np.abs(s[both] - 0.03) <= 0.02 * 0.03), (s[both].min(), s[both].max())
    assert np.all(np.abs(s[one] - 0.01) <= 0.02 * 0.01), (s[one].min(), s[one].max())
    nodes = h["active"]
    assert nodes[both].min() == nodes.max() == 6 and nodes[one].max() == 3 == nodes[one].min()
    last_b = t[nodes == 6][-1]
    last_a = t[nodes > 0][-1]
    assert abs(last_b - 1.04) <= 2 * DTB and abs(last_a - 2.02) <= 2 * DTB, (last_b, last_a)
    # the scheme's momentum M* v: the contact nodes' normal mass is not in it (the modified mass)
    p_in = h["P_x"][0]
    assert 0.97 * (MA * 0.01 + MB * 0.005) < -p_in < MA * 0.01 + MB * 0.005
    assert abs(h["P_x"][-1] + p_in) <= 0.02 * abs(p_in), (h["P_x"][-1], p_in)
    assert h["balance_residual"].max() <= 1e-10
    # the CFL number takes the larger wave speed, bar_b's c = 2, over h_c' (bar_a's cell diagonal)
    h_c = (0.02 ** 2 + 0.01 ** 2) ** 0.5
    assert np.abs(h["cfl"] - C2 * DTB / h_c).max() <= 1e-6, h["cfl"][0]  # written to 7 digits


def test_restart_with_bodies_is_bitwise(tmp_path):
    """The two bars hitting the wall, stopped at step 23 and restarted: the history byte for byte
    as the uninterrupted 40 steps (bodies in contact across the restart); a restart with another
    material for one body is refused, naming the bodies' options."""
    common = ["-quiet", "-checkpoint_every", 10]
    a = run("two_bars_impact", tmp_path, *common, "-ts_max_steps", 40, np_=0, name="a")
    run("two_bars_impact", tmp_path, *common, "-ts_max_steps", 23, np_=0, name="b")
    b = run("two_bars_impact", tmp_path, *common, "-ts_max_steps", 40, "-restart", str(tmp_path / "b"), np_=0, name="b")
    assert open(os.path.join(a.outdir, "history.csv"), "rb").read() == open(os.path.join(b.outdir, "history.csv"), "rb").read()
    assert a.history["active"][23:].min() == 6
    with h5py.File(os.path.join(a.outdir, "checkpoint.h5"), "r") as fa, h5py.File(os.path.join(b.outdir, "checkpoint.h5"), "r") as fb:
        for k in ("u", "v", "a", "react"):
            assert np.array_equal(fa[k][:], fb[k][:]), k
    for extra in (["-body_bar_b_E", 4], ["-body_bar_a_group", "bar_b", "-body_bar_b_group", "bar_a"]):
        r = run("two_bars_impact", tmp_path, *common, "-ts_max_steps", 40, "-restart", str(tmp_path / "a"), *extra, np_=0, name="c", check=False)
        assert r.returncode == 64 and f"this run has {extra[0]} {extra[1]}: its state would mean another problem" in r.output, r.output[-2000:]


def test_one_body_is_the_whole_mesh(tmp_path):
    """-bodies with one body whose group is the whole strip, or two bodies of the same material,
    give the history of the run without -bodies (to 1e-12 of the energy scale): the same material
    in every cell, the same v0."""
    opts = pulse_options(tmp_path, ("-bodies", "-body_"), "one_material")
    common = ("-ts_max_time", 0.5, "-output_every", 0, "-v0", "1e-3,0")
    ref = run(opts, tmp_path, *common, name="none").history
    scale = np.abs(ref["total"]).max()
    assert scale > 0
    for name, bodies in (("one", ("-bodies", "all", "-body_all_group", "strip")),
                         ("two", ("-bodies", "a,b", "-body_a_group", "left_half", "-body_b_group", "right_half", "-body_b_E", 1, "-body_b_v0", "1e-3,0"))):
        h = run(opts, tmp_path, *common, *bodies, name=name).history
        for c in ("kinetic", "elastic", "total", "work_ext", "P_x"):
            assert np.abs(h[c] - ref[c]).max() <= 1e-12 * (scale if c != "P_x" else np.abs(ref["P_x"]).max()), (name, c)


def test_glued_halves_with_dirichlet_data(tmp_path):
    """The two halves clamped at x = 0 and held at u_x = eps (L1 + L2) at x = 1.5, starting from the
    uniform strain eps: the elastic energy of the Dirichlet data and their force on the free dofs
    are computed cell by cell with each half's E when the bodies differ (the PetscFE quadrature holds
    one material). At t = 0 the elastic energy is 1/2 eps^2 (E1 |left| + E2 |right|) to 1e-10 (one
    material in those terms would be off by 60%); the
    uniform strain is no equilibrium (the stress jumps at the interface), so the halves move, and
    the balance closes every step."""
    eps = 1e-3
    opts = pulse_options(tmp_path, ("-traction",), "held")
    h = run(opts, tmp_path, "-dirichlet", "left,right", "-dirichlet_right_components", 0,
            "-dirichlet_right_value", eps * (L1 + L2), "-u0_gradient", f"{eps},0,0,0", "-ts_max_time", 0.5,
            "-output_every", 0).history
    elastic0 = 0.5 * eps ** 2 * (E1 * L1 * W + E2 * L2 * W)
    assert abs(h["elastic"][0] - elastic0) <= 1e-10 * elastic0, (h["elastic"][0], elastic0)
    assert h["kinetic"].max() > 1e-3 * elastic0
    assert h["balance_residual"].max() <= 1e-10


BAD = [
    (("-bodies", "a"), "-bodies: body a has no cells: give -body_a_group GROUP"),
    (("-bodies", "a", "-body_a_group", "nowhere"), 'The mesh has no physical group named "nowhere". Its physical names are:'),
    (("-bodies", "a", "-body_a_group", "left"), '-body_a_group left: the physical group "left" holds no cells; a body is a group of cells, a Physical Surface in 2D. The mesh\'s groups of cells are: "left_half" "'),
    (("-bodies", "a", "-body_a_group", "left_half"), "160 of the mesh's 320 cells are in no body's group (the first at ("),
    (("-bodies", "a,b", "-body_a_group", "strip", "-body_b_group", "right_half"), "160 cells of the mesh are in two bodies' groups, the first at ("),
    (("-bodies", "a,a", "-body_a_group", "strip"), "-bodies a,a names a twice"),
    (("-bodies", "a,b", "-body_a_group", "left_half", "-body_b_group", "right_half", "-body_c_E", 2), "-body_c_E 2: unknown; did you mean -body_a_E?"),
    (("-bodies", "a,b", "-body_a_group", "left_half", "-body_b_group", "right_half", "-body_b_v0", "1,0"), "is shared by cells of bodies with different initial velocities (-body_NAME_v0: x from 0. to 1., y from 0. to 0.)"),
    (("-bodies", "a", "-body_a_group", "strip", "-body_a_v0", "1,0,0"), "-body_a_v0 has 3 entries; the mesh is 2D, so it needs exactly 2"),
    (("-bodies", "a", "-body_a_group", "strip", "-body_a_E", -1), "Young's modulus -body_a_E -1. must be > 0"),
    (("-bodies", "a,b", "-body_a_group", "left_half", "-body_b_group", "right_half", "-body_b_E", 2, "-assembly", "fe"), "-assembly fe with bodies of different materials is not supported"),
]


@pytest.mark.parametrize("extra,message", BAD)
def test_bad_bodies_are_refused(tmp_path, extra, message):
    opts = pulse_options(tmp_path, ("-bodies", "-body_"), "plain")
    r = run(opts, tmp_path, *extra, "-ts_max_steps", 1, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-2000:]


def test_static_sliding_refuses_bodies(tmp_path):
    r = run("f1_block", tmp_path, "-bodies", "a", "-body_a_group", "body", "-ts_max_steps", 1, np_=0, check=False)
    assert r.returncode != 0 and "-initial_state static_sliding with -bodies is not supported" in r.output, r.output[-2000:]
