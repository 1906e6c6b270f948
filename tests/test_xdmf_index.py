"""solution.xmf, the XDMF index of solution.h5 (README "Output"): rewritten whole and atomically,
but not after every snapshot (O(N^2) bytes over a run): when the snapshots have doubled, at
checkpoints and at the end. Readable at any moment, listing only complete snapshots."""
import math
import os
import re
import signal
import subprocess
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from conftest import EXE, MPIEXEC, ROOT, children, history_rows, run, stop


def grids(path):
    root = ET.parse(path).getroot()  # raises on a partial or malformed file
    return [g for g in root.iter("Grid") if g.get("GridType") == "Uniform"]


def test_index_is_rewritten_log_n_times_and_lists_every_snapshot_at_the_end(tmp_path):
    """D1 with a snapshot every step (151): the index is written 9 times (at 1, 2, 4, ..., 128
    snapshots and at the end), not 151; at the end it lists all 151, each at its time."""
    r = run("d1_disk", tmp_path, "-output_every", 1, "-log_view")
    counts = [int(c) for c in re.findall(r"^MMOutputIndex\s+(\d+)", r.output, re.M)]  # one line per log stage
    assert counts, r.output[-3000:]
    n = 151
    assert sum(counts) == math.floor(math.log2(n)) + 2, counts
    g = grids(os.path.join(r.outdir, "solution.xmf"))
    assert len(g) == n
    times = [float(x.find("Time").get("Value")) for x in g]
    with h5py.File(os.path.join(r.outdir, "solution.h5"), "r") as f:
        assert list(f["time"][:, 0]) == times


def frozen_look(proc, out):
    """With every rank stopped (SIGSTOP): the history's steps, the snapshots the index lists (it must
    parse, always) and those complete in solution.h5; None when solution.h5 is caught mid-flush."""
    ranks = children(proc.pid)
    for p in ranks:
        os.kill(p, signal.SIGSTOP)
    try:
        steps = history_rows(str(out / "history.csv")) - 1
        listed = len(grids(out / "solution.xmf"))
        try:
            with h5py.File(out / "solution.h5", "r") as f:
                complete = f["time"].shape[0]
        except OSError:
            return None
        return steps, listed, complete
    finally:
        for p in ranks:
            os.kill(p, signal.SIGCONT)


def test_index_is_readable_while_the_run_goes_on(tmp_path):
    """Frozen (SIGSTOP) at several moments of a 2-rank run: the index parses, lists at least half of
    the snapshots the history says were written and none that is not complete in solution.h5."""
    out = tmp_path / "out"
    args = MPIEXEC + ["-n", "2", EXE, "-options_file", os.path.join(ROOT, "options", "d1_friction.opts"), "-ts_dt", "2e-4",
                      "-output_every", "2", "-output_dir", str(out), "-quiet"]
    proc = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seen = []
    try:
        for rows in (30, 100, 250, 600, 1200):
            t0 = time.time()
            while history_rows(str(out / "history.csv")) < rows:
                assert proc.poll() is None and time.time() - t0 < 120, "the run ended early"
                time.sleep(0.001)
            # solution.h5 is not a journaled file: frozen inside HDF5's flush it may not open at all
            # (docs/reference.md, "A run that stops early": the index is what counts). Such a look
            # proves nothing about the index; it is let go and taken again a moment later.
            for attempt in range(50):
                look = frozen_look(proc, out)
                if look is not None:
                    break
                time.sleep(0.01)
            assert look is not None, "solution.h5 never opened in 50 looks"
            steps, listed, complete = look
            written = steps // 2 + 1  # snapshots at steps 0, 2, 4, ... up to the last row
            assert (written - 1) / 2 <= listed <= min(written, complete), (steps, written, listed, complete)
            seen.append(listed)
        assert proc.wait(timeout=300) == 0, proc.stderr.read()[-2000:]
    finally:
        stop(proc)
    assert len(set(seen)) > 2  # the index moved on between the looks
    assert len(grids(out / "solution.xmf")) == 751  # all of them at the end (1500 steps)


def test_snapshot_datasets_keep_petsc_vecview_layout(tmp_path):
    """solution.h5's fields come from mmcontact's own writer (src/io/output_dataset.c), which must keep
    the layout PETSc's VecView gives a time series, the one ParaView's XDMF reader and the restart
    read: time first and unlimited, one step per chunk, components last, the "timestepping"
    attribute; the static fields and the mesh untimed. 2 ranks, so that each dataset is written by
    both. Every dataset the index names exists with the index's dimensions."""
    r = run("d1_disk", tmp_path, "-ts_max_steps", 6, "-output_every", 2, np_=2)
    with h5py.File(os.path.join(r.outdir, "solution.h5"), "r") as f:
        nsnap = f["time"].shape[0]
        assert nsnap == 4 and f["time"].shape == (4, 1) and f["time"].chunks == (1, 1)
        assert list(f["time"][:, 0]) == pytest.approx([0, 4e-3, 8e-3, 1.2e-2], rel=1e-12, abs=1e-18)
        timed = 0
        for group in ("vertex_fields", "cell_fields"):
            for name, d in f[group].items():
                assert d.dtype == "float64", name
                if "timestepping" not in d.attrs:  # written once: contact_obstacle, serial_vertex
                    assert d.ndim == 1 and d.chunks == d.shape, (name, d.shape, d.chunks)
                    continue
                timed += 1
                assert bool(d.attrs["timestepping"]), name
                assert d.shape[0] == nsnap and d.maxshape[0] is None, (name, d.shape, d.maxshape)
                assert d.chunks == (1,) + d.shape[1:] and d.maxshape[1:] == d.shape[1:], (name, d.chunks)
                kind = d.attrs["vector_field_type"]
                kind = kind.decode() if isinstance(kind, bytes) else str(kind)
                assert kind == ("vector" if d.ndim == 3 else "scalar"), (name, kind, d.shape)
                assert np.all(np.isfinite(d[...])), name
        assert timed >= 9
        named = 0
        for g in grids(os.path.join(r.outdir, "solution.xmf")):
            for item in g.iter("DataItem"):
                if item.get("Format") != "HDF":
                    continue
                path = item.text.strip().split(":", 1)[1]
                dims = tuple(int(x) for x in item.get("Dimensions").split())
                assert dims == f[path].shape, (path, dims, f[path].shape)
                named += 1
        assert named >= nsnap * timed
