"""Issue 38, what users see of a run: every field in both of ParaView's XDMF readers, and the history
at the interval and places users choose (-history_every, -output_interval, -probes)."""
import os
import shutil
import subprocess

import h5py
import numpy as np
import pytest

from conftest import ROOT

# The index's fields (README "Fields"): the dataset each one shows and its stored components
FIELDS = {
    "displacement": ("vertex_fields/displacement_displacement", "vector"),
    "velocity": ("vertex_fields/velocity_displacement", "vector"),
    "contact_pressure": ("vertex_fields/contact_pressure_nodal", "scalar"),
    "gap": ("vertex_fields/gap_nodal", "scalar"),
    "tangential_traction": ("vertex_fields/tangential_traction_displacement", "vector"),
    "slip_velocity": ("vertex_fields/slip_velocity_displacement", "vector"),
    "stress": ("vertex_fields/stress_stress", "tensor"),
    "von_mises": ("vertex_fields/von_mises_nodal", "scalar"),
    "contact_obstacle": ("vertex_fields/contact_obstacle_nodal", "static"),
    "stress_cell": ("cell_fields/stress_cell", "tensor"),
    "von_mises_cell": ("cell_fields/von_mises_cell", "scalar"),
}
READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
FULL_OF_SYMMETRIC = [0, 1, 2, 1, 3, 4, 2, 4, 5]  # xx xy xz / xy yy yz / xz yz zz from xx, xy, xz, yy, yz, zz


def shown(f, name, k):
    """What a reader must show of field `name` at snapshot k: a vector with 3 components (2D: z = 0),
    the stress as the full 3 x 3 tensor (9), a scalar as stored."""
    path, kind = FIELDS[name]
    d = f[path][...] if kind == "static" else f[path][k]
    if kind == "vector":
        return np.hstack([d, np.zeros((d.shape[0], 3 - d.shape[1]))])
    if kind == "tensor":
        return d[:, FULL_OF_SYMMETRIC]
    return d


def paraview_arrays(tmp_path, outdirs):
    """Every array ParaView's three XDMF readers give for each snapshot of each run's solution.xmf,
    read by pvbatch (tests/paraview_fields.py)."""
    pvbatch = shutil.which("pvbatch")
    assert pvbatch, "pvbatch not found: ParaView is needed by this test (make deps installs python3-paraview)"
    out = str(tmp_path / "paraview.npz")
    proc = subprocess.run([pvbatch, os.path.join(ROOT, "tests", "paraview_fields.py"), out] + [os.path.join(d, "solution.xmf") for d in outdirs],
                          cwd=str(tmp_path), capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    assert "Skipping" not in proc.stdout + proc.stderr, (proc.stdout + proc.stderr)[-3000:]
    return np.load(out)


def test_paraview_xdmf_readers_show_every_field(mm, tmp_path):
    """The D1 disk on 2 ranks (3 snapshots: the time series) and the 3D F1 box (1 snapshot, its
    static start: nonzero displacement, stress and pressure), opened with ParaView's legacy XDMF
    reader and both Xdmf3 readers: each shows all 11 fields (9 at the points, 2 on the cells) at
    every snapshot, vectors with 3 components, the stress with 9, and the values of solution.h5
    exactly (the same doubles, read from the same file)."""
    series = mm("d1_disk", "-ts_max_steps", 10, "-output_every", 5, "-quiet", np_=2, name="d1")
    single = mm("f1_box", "-ts_max_steps", 0, "-quiet", name="f1_box")
    z = paraview_arrays(tmp_path, [series.outdir, single.outdir])
    for i, (r, nsnap) in enumerate(((series, 3), (single, 1))):
        with r.fields() as f:
            assert f["time"].shape[0] == nsnap
            for reader in READERS:
                for k in range(nsnap):
                    key = f"{i}/{reader}/{k}"
                    assert float(z[key + "/time"]) == f["time"][k, 0], (reader, k)
                    names = {n.split("/")[-1] for n in z.files if n.startswith(key + "/point/")}
                    cells = {n.split("/")[-1] for n in z.files if n.startswith(key + "/cell/")}
                    assert names == {n for n, (p, _) in FIELDS.items() if p.startswith("vertex")}, (reader, names)
                    assert cells == {"stress_cell", "von_mises_cell"}, (reader, cells)
                    for name, (path, kind) in FIELDS.items():
                        got = z[f"{key}/{'point' if path.startswith('vertex') else 'cell'}/{name}"]
                        want = shown(f, name, k)
                        assert got.shape == want.shape, (reader, name, got.shape, want.shape)
                        assert np.array_equal(got, want), (reader, name, k)
            # not all zero: a field read as fill values would pass the comparison above
            last = nsnap - 1
            assert np.abs(f["vertex_fields/displacement_displacement"][last]).max() > 0
            assert np.abs(f["vertex_fields/stress_stress"][last]).max() > 0
