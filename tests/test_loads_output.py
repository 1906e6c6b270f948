"""Dirichlet data, tractions and gravity in the energy audit; the output files as ParaView reads them."""
import os
import xml.etree.ElementTree as ET

import numpy as np

from conftest import run

HEADER = ("step,time,dt,kinetic,elastic,total,work_ext,work_contact,work_friction,balance_residual,active,"
          "slipping,force_normal,force_tangential,max_penetration,coulomb_residual,vi_its,friction_its,cfl").split(",")


def test_nonzero_dirichlet_data_one_and_two_ranks(tmp_path):
    """B1 with the fixed end pulled to u_x = 0.1: the energy includes the Dirichlet data, balances,
    and 1 and 2 ranks agree, the rigid-body columns included."""
    extra = ("-dirichlet_right_value", 0.1, "-output_every", 40)
    h1 = run("b1_bar", tmp_path, *extra, np_=1, name="np1").history
    r2 = run("b1_bar", tmp_path, *extra, np_=2, name="np2")
    h2 = r2.history
    # 78 cells at strain -1/2 (the first is relaxed by the consistent start), the last at 7.5
    w = h = 1.0 / 80
    assert abs(h1["elastic"][0] - w * h * (78 * 0.125 + 0.5 * 7.5 ** 2)) <= 1e-12
    assert h1["balance_residual"].max() <= 1e-10
    for c in ("total", "work_contact", "force_normal", "ucm_x", "vcm_x", "vcm_y", "L_z"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-8 * max(1.0, np.abs(h1[c]).max()), c
    # output: the displacement carries the data, the velocity is zero there
    with r2.fields() as f:
        x = f["geometry/vertices"][:]
        end = np.abs(x[:, 0] - 1.0) < 1e-12
        assert np.allclose(f["vertex_fields/displacement_displacement"][-1][end, 0], 0.1)
        assert np.allclose(f["vertex_fields/velocity_displacement"][-1][end, 0], 0.0)


def test_traction_work_is_in_the_balance(tmp_path):
    """A traction (0, -20) on the upper half of the disk pushes it into the plane: W_ext balances it.
    With the standard mass the centre of mass accelerates at exactly F/m before impact, and
    F/m = 20 x arc length / area = 20 (to the polygon's approximation of the circle)."""
    h = run("d1_disk", tmp_path, "-traction", "upper", "-traction_upper_value", "0,-20", "-output_every", 0).history
    assert np.abs(h["work_ext"]).max() > 0.05
    assert h["balance_residual"].max() <= 1e-8
    hs = run("d1_disk", tmp_path, "-traction", "upper", "-traction_upper_value", "0,-20", "-mass", "standard",
             "-ts_max_time", 0.006, name="standard").history
    dv = np.diff(hs["vcm_y"][:4]) / hs["dt"][1]
    assert np.abs(dv - dv[0]).max() <= 1e-8 * 20
    assert abs(dv[0] + 20) <= 0.01 * 20, dv


def test_history_and_xdmf(tmp_path):
    r = run("d1_disk", tmp_path, "-ts_max_time", 0.05, "-output_every", 5, np_=2)
    with open(os.path.join(r.outdir, "history.csv")) as f:
        header = f.readline().strip().split(",")
    assert header[:len(HEADER)] == HEADER
    assert header[len(HEADER):] == ["ucm_x", "ucm_y", "vcm_x", "vcm_y", "L_z", "P_x", "P_y", "J_z", "load_x", "load_y", "switched", "contraction",
                                      "candidates", "candidate_resolves", "work_obstacle", "force_plane_x", "force_plane_y",
                                      "work_damping"]  # the default obstacle is "plane"; new columns go at the end
    h = r.history
    assert len(h) == 26 and h["step"][-1] == 25
    root = ET.parse(os.path.join(r.outdir, "solution.xmf")).getroot()
    grids = root.findall(".//Grid[@GridType='Uniform']")
    assert len(grids) == 6  # steps 0, 5, ..., 25
    with r.fields() as f:
        nv = f["geometry/vertices"].shape[0]
        for g in grids:
            for item in g.iter("DataItem"):
                if item.get("Format") == "HDF":
                    path = item.text.split(":")[1]
                    dims = tuple(int(d) for d in item.get("Dimensions").split())
                    assert f[path].shape == dims, (path, f[path].shape, dims)
        assert f["vertex_fields/displacement_displacement"].shape == (6, nv, 2)
        times = f["time"][:, 0]
        assert np.allclose(times, h["time"][::5])
        # the gap field is the gap: zero where a node touches, positive elsewhere on the contact boundary
        gap = f["vertex_fields/gap_nodal"][-1]
        p = f["vertex_fields/contact_pressure_nodal"][-1]
        assert gap.min() >= -1e-12 and (p > 1e-8 * p.max()).sum() == h["active"][-1]
        assert np.all(np.abs(gap[p > 1e-8 * p.max()]) <= 1e-12)
        # the obstacle of each contact node, written once: the one plane on the contact boundary
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
        assert owner.shape == (nv,) and set(np.unique(owner)) == {-1, 0}
        assert np.array_equal(owner == 0, f["vertex_fields/gap_nodal"][0] > 0)  # at t = 0 every contact node has a gap
