"""Stress output (src/fem/stress.c, docs/method.md section 5): the nodal stress (stored as 6 components xx, xy,
xz, yy, yz, zz) and von Mises of every snapshot. A uniform strain gives the exact stress at every
vertex, in 3D and in 2D plane strain; a run on 2 ranks writes the stress of 1 rank."""
import numpy as np
import pytest

from conftest import run

E, NU = 1000.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))


def exact_stress(B):
    """sigma = lambda tr(eps) I + 2 mu eps for u = B x (2D: plane strain, padded to 3D), as Tensor6 and
    its von Mises value."""
    G = np.zeros((3, 3))
    d = B.shape[0]
    G[:d, :d] = B
    e = 0.5 * (G + G.T)
    S = LAM * np.trace(e) * np.eye(3) + 2 * MU * e
    vm = np.sqrt(0.5 * ((S[0, 0] - S[1, 1]) ** 2 + (S[1, 1] - S[2, 2]) ** 2 + (S[2, 2] - S[0, 0]) ** 2)
                 + 3 * (S[0, 1] ** 2 + S[0, 2] ** 2 + S[1, 2] ** 2))
    return np.array([S[0, 0], S[0, 1], S[0, 2], S[1, 1], S[1, 2], S[2, 2]]), vm


@pytest.mark.parametrize("case,B", [
    ("d2_ball", np.array([[1e-3, 2e-3, 0], [0, -1e-3, 0], [4e-4, 0, 5e-4]])),
    ("d1_disk", np.array([[1e-3, 2e-3], [-5e-4, -1e-3]])),
])
@pytest.mark.parametrize("np_", [1, 2])
def test_uniform_strain_gives_the_exact_stress(tmp_path, case, B, np_):
    """A free body (no contact, no Dirichlet) given u0 = B x: at t = 0 every vertex carries the exact
    stress of the strain sym(B), and its von Mises value, to round-off of the stress scale."""
    r = run(case, tmp_path, "-contact", 0, "-u0_gradient", ",".join(map(str, B.ravel())), "-ts_max_steps", 1,
            "-output_every", 1, np_=np_)
    ex, vm = exact_stress(B)
    with r.fields() as f:
        s, v = f["vertex_fields/stress_stress"][0], f["vertex_fields/von_mises_nodal"][0]
    assert s.shape[1] == 6 and np.abs(s - ex).max() <= 1e-12 * np.abs(ex).max()
    assert np.abs(v - vm).max() <= 1e-12 * vm
    if case == "d1_disk":  # plane strain: sigma_zz = lambda (eps_xx + eps_yy), no out-of-plane shear
        assert abs(ex[5] - LAM * (B[0, 0] + B[1, 1])) <= 1e-15 * abs(ex).max() and ex[2] == ex[4] == 0


def test_stress_of_two_ranks_is_that_of_one(tmp_path):
    """The frictional disk through its impact: the nodal stress and von Mises of every snapshot on 2
    ranks equal those of 1 rank vertex by vertex (matched by serial number), to 1e-10 of their scale;
    the contact zone is the most stressed, and the index lists the stress as a tensor."""
    runs = [run("d1_friction", tmp_path, "-ts_max_time", 0.06, "-output_every", 5, np_=n, name=f"np{n}") for n in (1, 2)]
    fields = []
    for r in runs:
        with r.fields() as f:
            order = np.argsort(f["vertex_fields/serial_vertex_nodal"][:].ravel())
            fields.append((f["vertex_fields/stress_stress"][:][:, order], f["vertex_fields/von_mises_nodal"][:][:, order]))
    (s1, v1), (s2, v2) = fields
    assert s1.shape == s2.shape and s1.shape[0] >= 6
    scale = np.abs(s1).max()
    assert scale > 0 and np.abs(s1 - s2).max() <= 1e-10 * scale and np.abs(v1 - v2).max() <= 1e-10 * scale
    with runs[0].fields() as f:
        pressure = f["vertex_fields/contact_pressure_nodal"][-1]
    assert v1[-1][pressure > 0].max() > 0.5 * v1[-1].max()
    xmf = open(runs[0].outdir + "/solution.xmf").read()
    assert 'Name="stress" AttributeType="Tensor"' in xmf and 'Name="von_mises" AttributeType="Scalar"' in xmf


def cell_centroids(f):
    """Each cell's centroid, from the XDMF topology and geometry, in the cells' written order."""
    x, cells = f["geometry/vertices"][:], f["viz/topology/cells"][:].astype(int)
    return x[cells].mean(axis=1)


@pytest.mark.parametrize("np_", [1, 2])
def test_bar_under_traction_has_the_traction_in_every_cell(tmp_path, np_):
    """A bar (nu = 0, plane strain) held by a roller at x = 0 and pulled by the traction t at x = 1,
    started from its static state u = (t/E) x: it stays there, and every cell's stress is
    sigma_xx = t, the others 0 (exact for P1), at every snapshot; von Mises is |t| (sigma_zz =
    lambda tr eps = 0 with nu = 0). Written as cell fields, with Center="Cell" in the index."""
    t, E = 0.01, 1.0
    r = run("b2_bar", tmp_path, "-contact", 0, "-v0", "0,0", "-E", E, "-dirichlet", "left", "-dirichlet_left_components", 0,
            "-traction", "right", "-traction_right_value", f"{t},0", "-u0_gradient", f"{t / E},0,0,0",
            "-ts_max_steps", 20, "-output_every", 10, np_=np_)
    with r.fields() as f:
        s, vm = f["cell_fields/stress_cell"][:], f["cell_fields/von_mises_cell"][:]
        ncells = f["viz/topology/cells"].shape[0]
    assert s.shape == (3, ncells, 6) and vm.shape == (3, ncells)
    exact = np.array([t, 0, 0, 0, 0, 0])
    assert np.abs(s - exact).max() <= 1e-9 * t, np.abs(s - exact).max()
    assert np.abs(vm - t).max() <= 1e-9 * t
    xmf = open(r.outdir + "/solution.xmf").read()
    assert 'Name="stress_cell" AttributeType="Tensor" Center="Cell"' in xmf
    assert 'Name="von_mises_cell" AttributeType="Scalar" Center="Cell"' in xmf


def test_cell_stress_of_two_ranks_is_that_of_one(tmp_path):
    """Through the frictional disk's impact, the cell stress of 2 ranks equals that of 1 cell by cell
    (matched by centroid, as the two runs order the cells differently), to 1e-10 of its scale; the
    cell and nodal von Mises agree where the field is smooth (their largest values within 25%)."""
    runs = [run("d1_friction", tmp_path, "-ts_max_time", 0.06, "-output_every", 5, np_=n, name=f"np{n}") for n in (1, 2)]
    fields = []
    for r in runs:
        with r.fields() as f:
            c = cell_centroids(f)
            order = np.lexsort((c[:, 1], c[:, 0]))
            fields.append((f["cell_fields/stress_cell"][:][:, order], f["cell_fields/von_mises_cell"][:][:, order],
                           f["vertex_fields/von_mises_nodal"][:]))
    (s1, v1, n1), (s2, v2, _) = fields
    assert s1.shape == s2.shape and s1.shape[0] >= 6
    scale = np.abs(s1).max()
    assert scale > 0 and np.abs(s1 - s2).max() <= 1e-10 * scale and np.abs(v1 - v2).max() <= 1e-10 * scale
    assert abs(v1[-1].max() - n1[-1].max()) <= 0.25 * v1[-1].max()


def test_each_field_is_written_once(tmp_path):
    """solution.h5 holds each field once, under /vertex_fields or /cell_fields: no /fields copy."""
    r = run("d1_disk", tmp_path, "-ts_max_steps", 4, "-output_every", 2)
    with r.fields() as f:
        assert "fields" not in f and "vertex_fields" in f and "cell_fields" in f
        assert f["time"].shape[0] == 3 and f["vertex_fields/displacement_displacement"].shape[0] == 3
