"""Issue 38, what users see of a run: every field in both of ParaView's XDMF readers, and the history
at the interval and places users choose (-history_every, -output_interval, -probes)."""
import os
import shutil
import subprocess

import h5py
import numpy as np
import pytest

from conftest import ROOT, physical_scales, run

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


def lumped_masses(f, rho):
    """Each vertex's lumped standard mass from solution.h5's mesh: rho |cell| / (dim + 1) from each cell."""
    X = f["geometry/vertices"][:]
    cells = f["viz/topology/cells"][:].astype(int)
    dim = X.shape[1]
    J = np.stack([X[cells[:, k + 1]] - X[cells[:, 0]] for k in range(dim)], axis=2)
    vol = np.abs(np.linalg.det(J)) / (2 if dim == 2 else 6)
    m = np.zeros(len(X))
    for k in range(dim + 1):
        np.add.at(m, cells[:, k], rho * vol / (dim + 1))
    return m


PROBE = ("-ts_max_steps", 20, "-output_every", 5, "-probes", "body,contact", "-mass", "standard")


@pytest.mark.parametrize("np_", [1, 2])
def test_probes_are_the_mass_weighted_means_of_their_groups(mm, np_):
    """The D1 disk (rho = 1, -mass standard: M* = M), probes on the whole body and on the contact
    boundary. The body's probe is its centre of mass: the ucm and vcm columns, to 1e-12 of the length
    and velocity scales. The contact boundary's (a sub-group) is the lumped-mass-weighted mean of its
    nodes' displacement and velocity in solution.h5 (the nodes with contact_obstacle >= 0) at every
    snapshot, to 1e-12 of the same scales."""
    r = mm("d1_disk", *PROBE, "-quiet", np_=np_)
    h = r.history
    s = physical_scales(r.outdir, "d1_disk", h)
    L, V = s["length"], s["velocity"]
    for c in "xy":
        assert np.abs(h[f"probe_body_u{c}"] - h[f"ucm_{c}"]).max() <= 1e-12 * L, c
        assert np.abs(h[f"probe_body_v{c}"] - h[f"vcm_{c}"]).max() <= 1e-12 * V, c
    assert np.abs(h["probe_body_vy"]).max() > 0.5  # thrown at (0.5, -1)
    with r.fields() as f:
        m = lumped_masses(f, 1.0)
        group = f["vertex_fields/contact_obstacle_nodal"][:] >= 0
        w = m[group] / m[group].sum()
        times = f["time"][:, 0]
        assert len(times) == 5
        for k, t in enumerate(times):
            row = np.flatnonzero(h["time"] == t)
            assert len(row) == 1, t
            u = w @ f["vertex_fields/displacement_displacement"][k][group]
            v = w @ f["vertex_fields/velocity_displacement"][k][group]
            for j, c in enumerate("xy"):
                assert abs(h[f"probe_contact_u{c}"][row[0]] - u[j]) <= 1e-12 * L, (t, c)
                assert abs(h[f"probe_contact_v{c}"][row[0]] - v[j]) <= 1e-12 * V, (t, c)
    assert np.abs(h["probe_contact_uy"]).max() > 1e-3  # it moved


def test_probes_of_two_ranks_are_those_of_one(mm):
    """The probe columns of a 2-rank run equal the 1-rank run's to 1e-12 of the length and velocity scales."""
    one = mm("d1_disk", *PROBE, "-quiet", name="one")
    two = mm("d1_disk", *PROBE, "-quiet", np_=2, name="two")
    h1, h2 = one.history, two.history
    s = physical_scales(one.outdir, "d1_disk", h1)
    assert np.array_equal(h1["step"], h2["step"])
    for name in h1.dtype.names:
        if name.startswith("probe_"):
            scale = s["length"] if name.split("_")[-1][0] == "u" else s["velocity"]
            assert np.abs(h1[name] - h2[name]).max() <= 1e-12 * scale, name


def snapshot_times(r):
    with r.fields() as f:
        return f["time"][:, 0]


def test_history_every_and_output_interval(mm):
    """The D1 disk, 20 steps of dt = 2e-3. With -history_every 1 -output_interval 0.01 (5 dt), the
    snapshots are at steps 0, 5, 10, 15, 20: t = k T to 1e-9 dt. With -history_every 3
    -output_interval 0.007 (not a multiple of dt): rows at steps 0, 3, ..., 18 and the last, 20,
    equal to the first run's rows (the same computation); snapshots at the first step at or past
    each k T, and the final state."""
    dt, T = 2e-3, 0.007
    a = mm("d1_disk", "-ts_max_steps", 20, "-history_every", 1, "-output_interval", 0.01, "-quiet", name="a")
    ha = a.history
    assert list(ha["step"]) == list(range(21))
    ta = snapshot_times(a)
    assert np.array_equal(ta, ha["time"][::5])
    assert np.abs(ta - 0.01 * np.arange(5)).max() <= 1e-9 * dt
    b = mm("d1_disk", "-ts_max_steps", 20, "-history_every", 3, "-output_interval", T, "-quiet", name="b")
    hb = b.history
    assert list(hb["step"]) == [0, 3, 6, 9, 12, 15, 18, 20]
    for name in hb.dtype.names:
        assert np.array_equal(hb[name], ha[name][hb["step"].astype(int)]), name
    want = [ha["time"][np.flatnonzero(ha["time"] >= k * T - 1e-9 * dt)[0]] for k in range(int(ha["time"][-1] / T) + 1)]
    if want[-1] != ha["time"][-1]:
        want.append(ha["time"][-1])  # the final state
    assert np.array_equal(snapshot_times(b), want), (snapshot_times(b), want)
    assert list(np.round(np.array(want) / dt).astype(int)) == [0, 4, 7, 11, 14, 18, 20]


def test_history_cadence_continues_after_a_restart(mm, tmp_path):
    """-history_every 3 with probes, stopped at step 10 (its checkpoint) and restarted to step 20 in
    the same directory: the rows are 0, 3, 6, 9, the first run's last (10), then 12, 15, 18 and 20,
    the uninterrupted run's rows at the same steps bit for bit (1 rank, README "Checkpoint and restart")."""
    opts = ("-history_every", 3, "-probes", "contact", "-quiet")
    full = mm("d1_disk", "-ts_max_steps", 20, *opts, name="full")
    mm("d1_disk", "-ts_max_steps", 10, *opts, name="cont")
    r = mm("d1_disk", "-ts_max_steps", 20, *opts, "-restart", str(tmp_path / "cont"), name="cont")
    h, hf = r.history, full.history
    assert list(h["step"]) == [0, 3, 6, 9, 10, 12, 15, 18, 20]
    keep = h["step"] != 10
    for name in h.dtype.names:
        assert np.array_equal(h[name][keep], hf[name]), name


def test_a_run_planning_over_a_million_steps_says_so_at_start(tmp_path):
    """-ts_max_time 2500 with dt = 2e-3 plans 1.25e6 steps (and about 1.1 GB of history): one
    'mmcontact warning:' line with the figures, before the first step; the run is then killed. A
    run of 20 steps says nothing."""
    from conftest import EXE, MPIEXEC, stop
    args = MPIEXEC + ["-n", "1", EXE, "-options_file", os.path.join(ROOT, "options", "d1_disk.opts"), "-ts_max_time", 2500,
                      "-output_every", 0, "-output_dir", str(tmp_path / "out"), "-quiet"]
    proc = subprocess.Popen(list(map(str, args)), cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        line = proc.stdout.readline()
    finally:
        stop(proc)
    assert line.startswith("mmcontact warning: this run plans 1.25e+06 steps, 1.1"), line
    assert "GB of history.csv (1.25e+06 rows)" in line and "-history_every" in line
    r = run("d1_disk", tmp_path, "-ts_max_steps", 20, name="short")
    assert "mmcontact warning: this run plans" not in r.output
