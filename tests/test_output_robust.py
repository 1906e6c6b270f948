"""The output survives what stops a run: kills leave consistent, readable files; write errors stop the
run with the file and the reason; a rerun keeps the earlier results in previous/."""
import os
import signal
import subprocess
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from conftest import EXE, MPIEXEC, ROOT, history_rows, run, signal_ranks, stop

FILES = ("history.csv", "solution.h5", "solution.xmf")
SHORT = ("-ts_max_time", 0.01, "-output_every", 1, "-quiet")  # D1, 6 steps


def opts(case):
    return os.path.join(ROOT, "options", case + ".opts")


def contents(d):
    return {n: open(os.path.join(d, n), "rb").read() for n in FILES}


def check_consistent(d, every=1):
    """What a reader of d finds: whole history rows; an index that parses and names only data that
    exist, at the history's times; every indexed snapshot really written. Returns (rows, snapshots)."""
    text = open(os.path.join(d, "history.csv")).read()
    assert text.endswith("\n"), repr(text[-200:])
    lines = text.splitlines()
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:]]
    assert all(len(r) == len(header) for r in rows), "a partial history row"
    hist = np.array(rows, dtype=float).reshape(len(rows), len(header))
    assert np.array_equal(hist[:, 0], np.arange(len(rows)))
    grids = ET.parse(os.path.join(d, "solution.xmf")).getroot().findall(".//Grid[@GridType='Uniform']")
    n = len(grids)
    assert n >= 1
    times = np.array([float(g.find("Time").get("Value")) for g in grids])
    assert n <= len(rows[::every]) and np.array_equal(times, hist[::every, 1][:n])
    with h5py.File(os.path.join(d, "solution.h5"), "r") as f:
        for g in grids:
            for item in g.iter("DataItem"):
                if item.get("Format") != "HDF":
                    continue
                name, path = item.text.strip().split(":")
                dims = tuple(int(x) for x in item.get("Dimensions").split())
                assert name == "solution.h5" and path in f, path
                shape = f[path].shape
                assert len(shape) == len(dims) and all(s >= k for s, k in zip(shape, dims)), (path, shape, dims)
        assert np.array_equal(f["time"][:n, 0], times)
        # written, not fill values: D1's velocity is nowhere zero at every instant
        v = f["vertex_fields/velocity_displacement"][:n]
        assert np.isfinite(v).all() and (np.abs(v).reshape(n, -1).max(axis=1) > 0).all()
    return len(rows), n


def run_file_limited(outdir, limit, *extra, case="b1_bar"):
    """Runs on 2 ranks, the ranks' files limited to `limit` bytes: past it writes fail with EFBIG, as on a
    full disk. The limit is set in the ranks only (mpiexec's own files must not be limited), with
    SIGXFSZ ignored so that the write fails instead of killing the process; Open MPI's shared-memory
    transport would hit the limit too, so the ranks talk over TCP."""
    wrap = ("import os, resource, signal, sys; n = int(sys.argv[1]); "
            "resource.setrlimit(resource.RLIMIT_FSIZE, (n, n)); signal.signal(signal.SIGXFSZ, signal.SIG_IGN); "
            "os.execv(sys.argv[2], sys.argv[2:])")
    args = MPIEXEC + ["-n", "2", "/usr/bin/python3", "-s", "-c", wrap, str(limit), EXE,
                      "-options_file", opts(case), "-output_dir", outdir, "-quiet", *map(str, extra)]
    env = dict(os.environ, OMPI_MCA_btl="self,tcp")
    proc = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=120, env=env)
    return proc.returncode, proc.stdout + proc.stderr


def test_empty_output_dir_is_refused(tmp_path):
    root_had = {n: os.path.exists("/" + n) for n in FILES}
    proc = subprocess.run([EXE, "-options_file", opts("d1_disk"), "-output_dir", "", "-quiet"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert proc.returncode != 0
    # PETSc stores an empty argument as no value: refused as an option given without one
    assert "-output_dir was given without a value" in proc.stderr.splitlines()[0], (proc.stdout + proc.stderr)[-1500:]
    for n in FILES:
        assert root_had[n] or not os.path.exists("/" + n), n


def test_bad_input_leaves_earlier_results_untouched(tmp_path):
    out = run("d1_disk", tmp_path, *SHORT).outdir
    before = contents(out)
    r = run("d1_disk", tmp_path, *SHORT, "-E", -1, np_=0, check=False)
    assert r.returncode != 0 and "Young's modulus" in r.output
    assert contents(out) == before
    assert not os.path.exists(os.path.join(out, "previous"))


def test_run_failing_at_step_1_keeps_earlier_results_in_previous(tmp_path):
    """The energy audit stops the new run at its first step: the last run's files are in previous/, whole."""
    out = run("d1_disk", tmp_path, *SHORT).outdir
    before = contents(out)
    r = run("d1_disk", tmp_path, *SHORT, "-audit_tol", 1e-30, np_=0, check=False)
    assert r.returncode != 0 and "Energy audit failed at step" in r.output
    prev = os.path.join(out, "previous")
    assert contents(prev) == before
    assert check_consistent(prev) == (6, 6)


def test_rerun_moves_earlier_results_to_previous(tmp_path):
    out = run("d1_disk", tmp_path, *SHORT).outdir
    first = contents(out)
    run("d1_disk", tmp_path, *SHORT, "-ts_max_time", 0.006)
    prev = os.path.join(out, "previous")
    assert contents(prev) == first
    assert check_consistent(prev) == (6, 6)
    assert check_consistent(out) == (4, 4)
    # a third run replaces the older set: previous/ holds the second run, not a mix
    second = contents(out)
    run("d1_disk", tmp_path, *SHORT)
    assert contents(prev) == second
    assert check_consistent(out) == (6, 6)


def test_history_write_error_stops_every_rank(tmp_path):
    """history.csv outgrows the file size limit first (-output_every 0 keeps solution.h5 small): both
    ranks stop, naming the file and the reason."""
    out = str(tmp_path / "out")
    rc, output = run_file_limited(out, 250000, "-output_every", 0, "-ts_max_time", 12)
    assert rc != 0
    assert f"Could not write {out}/history.csv: File too large" in output, output[-3000:]
    # the row the limit cut is cut away: the file ends on its last whole row
    data = open(os.path.join(out, "history.csv"), "rb").read()
    assert 250000 - 1000 < len(data) < 250000 and data.endswith(b"\n")
    assert len({len(r.split(b",")) for r in data.splitlines()}) == 1


def test_fields_write_error_names_the_file(tmp_path):
    out = str(tmp_path / "out")
    rc, output = run_file_limited(out, 150000, "-output_every", 1)
    assert rc != 0
    assert f"{out}/solution.h5: File too large" in output, output[-3000:]


def test_index_write_error_names_the_file(tmp_path):
    """The index is written beside solution.xmf and renamed over it: that file on a full device."""
    out = tmp_path / "out"
    out.mkdir()
    os.symlink("/dev/full", out / "solution.xmf.tmp")
    r = run("d1_disk", tmp_path, *SHORT, np_=2, check=False)
    assert r.returncode != 0
    assert f"Could not write {out}/solution.xmf.tmp: No space left on device" in r.output, r.output[-3000:]


def rows_reach(rows):
    """Kill trigger: the history has `rows` rows."""
    return lambda d: history_rows(os.path.join(d, "history.csv")) >= rows


def index_changes(rows):
    """Kill trigger: past `rows` rows, the index or the file it is being written to has just changed."""
    last = []

    def look(path):
        try:
            s = os.stat(path)
            return s.st_ino, s.st_size, s.st_mtime_ns
        except OSError:
            return None

    def ready(d):
        now = (look(os.path.join(d, "solution.xmf")), look(os.path.join(d, "solution.xmf.tmp")))
        changed = bool(last) and now != last[-1]
        last[:] = [now]
        return changed and history_rows(os.path.join(d, "history.csv")) >= rows
    return ready


def kill_d1(outdir, ready, delay, sig):
    """D1 on 2 ranks, every step written; once ready(outdir), waits `delay` s and sends `sig` to both
    ranks at once. Returns mpiexec once both ranks are dead: the files are then final (mpiexec itself
    takes a while longer to notice)."""
    args = MPIEXEC + ["-n", "2", EXE, "-options_file", opts("d1_disk"), "-output_dir", outdir,
                      "-output_every", "1", "-quiet"]
    proc = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    signal_ranks(proc, lambda: ready(outdir), sig, 2, delay)
    return proc


def test_killed_run_leaves_consistent_output(tmp_path):
    """Killed at different moments of D1 (151 snapshots), the files are always consistent and readable."""
    trials = [(rows_reach(2), 0.0, signal.SIGKILL), (rows_reach(30), 0.004, signal.SIGKILL),
              (index_changes(20), 0.0, signal.SIGKILL), (index_changes(60), 0.0, signal.SIGKILL),
              (rows_reach(45), 0.002, signal.SIGTERM)]
    procs = []
    try:
        for k, (ready, delay, sig) in enumerate(trials):
            out = str(tmp_path / f"kill{k}")
            procs.append(kill_d1(out, ready, delay, sig))
            nrows, n = check_consistent(out)
            assert nrows < 151, (k, nrows)
        for p in procs:
            assert p.wait(timeout=60) != 0
    finally:
        for p in procs:
            stop(p)
