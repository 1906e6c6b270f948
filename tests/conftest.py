"""Shared helpers: run mmcontact through mpiexec and read what it writes.

Every test runs the real executable on a real mesh and asserts numbers with tolerances."""
import contextlib
import os
import signal
import subprocess
import tempfile
import time

import h5py
import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "mmcontact")
MPIEXEC = ["mpiexec", "--allow-run-as-root", "--oversubscribe"]
UNUSED = "There are options you set that were not used"

# The suite's physics tests were written for the condensed formulation, exact to round-off, and
# assert it so (balances of 1e-10 of the energy, bitwise restarts, 1 rank against 2). Since issue 41,
# -contact_formulation auto chooses by a cost model, often the active-set formulation, exact to its
# CG tolerance (-contact_tol) instead; so every run of the suite defaults to condensed through PETSc's
# environment options, which any -contact_formulation given on the command line or in an options
# file overrides. auto's choice and the active-set path under it are tested in test_auto_formulation.py
# (with -contact_formulation auto given).
if "-contact_formulation" not in os.environ.get("PETSC_OPTIONS", ""):
    os.environ["PETSC_OPTIONS"] = (os.environ.get("PETSC_OPTIONS", "") + " -contact_formulation condensed").strip()


class Run:
    def __init__(self, proc, outdir):
        self.returncode = proc.returncode
        self.output = proc.stdout + proc.stderr
        self.outdir = outdir

    @property
    def history(self):
        return np.genfromtxt(os.path.join(self.outdir, "history.csv"), delimiter=",", names=True, ndmin=1)

    def fields(self):
        return h5py.File(os.path.join(self.outdir, "solution.h5"), "r")


def run(case, tmp_path, *extra, np_=1, name="out", check=True):
    """Runs options/<case>.opts with extra options on np_ ranks, output under tmp_path/name.
    np_=0 runs the executable without mpiexec (one rank): a refused input then costs 0.3 s, not
    the 1.4 s of MPI's abort path."""
    outdir = str(tmp_path / name)
    launcher = MPIEXEC + ["-n", str(np_)] if np_ > 0 else []
    opts = case if case.endswith(".opts") else os.path.join(ROOT, "options", case + ".opts")  # a case name or a file
    args = launcher + [EXE, "-options_file", opts,
                       "-output_dir", outdir, "-options_left", *map(str, extra)]
    proc = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=900)
    r = Run(proc, outdir)
    if check:
        assert r.returncode == 0, r.output[-3000:]
        # an option nobody used is a typo in a test or an options file
        assert UNUSED not in r.output, r.output[-2000:]
    return r


@pytest.fixture
def mm(tmp_path):
    return lambda case, *extra, **kw: run(case, tmp_path, *extra, **kw)


def options_without_plane(case, tmp_path):
    """options/<case>.opts without its single plane, so that -obstacles can name the obstacles."""
    drop = ("-obstacle_point", "-obstacle_normal", "-ts_monitor")
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines() if not l.split() or l.split()[0] not in drop]
    path = tmp_path / (case + "_no_plane.opts")
    path.write_text("\n".join(lines) + "\n")
    return str(path)


# Floating-point results are compared to the physical scale of their case (tests/README.md), never to
# their own round-off: a column that is physically zero (the angular momentum of a bar moving
# straight) holds round-off of 1e-16 on one machine and 1e-15 on another.
def physical_scales(outdir, case, history):
    """The scales of a case, from what its run wrote: the body's size D (diagonal of its bounding box)
    and mass M (rho, from the options file, times the volume of the mesh in solution.h5), the energy
    scale E (the largest energy or work of the run), and from them a velocity V = sqrt(2 E / M), a
    momentum M V, an angular momentum M V D and a force: the larger of E / D and the largest contact
    force of the run."""
    with h5py.File(os.path.join(outdir, "solution.h5"), "r") as f:
        X = f["geometry/vertices"][:]
        cells = f["viz/topology/cells"][:].astype(int)
    dim = X.shape[1]
    D = float(np.linalg.norm(X.max(axis=0) - X.min(axis=0)))
    J = np.stack([X[cells[:, k + 1]] - X[cells[:, 0]] for k in range(dim)], axis=2)
    volume = float(np.abs(np.linalg.det(J)).sum()) / (2 if dim == 2 else 6)
    rho = 1.0
    opts = case if case.endswith(".opts") else os.path.join(ROOT, "options", case + ".opts")
    for line in open(opts):
        words = line.split("#")[0].split()
        if len(words) == 2 and words[0] == "-rho":
            rho = float(words[1])
    M = rho * volume
    E = max(float(np.abs(history[c]).max()) for c in ("kinetic", "elastic", "total", "work_ext", "work_contact", "work_friction"))
    V = (2 * E / M) ** 0.5
    force = max(E / D, float(np.abs(history["force_normal"]).max()), float(np.abs(history["force_tangential"]).max()))
    return dict(length=D, mass=M, energy=E, velocity=V, momentum=M * V, angular_momentum=M * V * D, force=force)


def column_scale(column, scales):
    """The physical scale of a history column."""
    if column in ("kinetic", "elastic", "total") or column.startswith("work_"):
        return scales["energy"]
    if column.startswith("force_"):
        return scales["force"]
    if column.startswith("ucm_"):
        return scales["length"]
    if column.startswith("vcm_"):
        return scales["velocity"]
    if column.startswith("P_"):
        return scales["momentum"]
    if column.startswith(("L_", "J_")):
        return scales["angular_momentum"]
    raise KeyError(column)


def assert_close(got, ref, scale, rtol=1e-10, what=""):
    """|got - ref| <= rtol * scale, scale the quantity's physical scale (column_scale): the tolerance
    of tests/README.md. 1e-10 is 20 times the largest difference seen between two correct machines
    (5e-12 of the scale, over whole runs), and 1e4 times below an error of 1e-6."""
    got, ref = np.asarray(got, float), np.asarray(ref, float)
    assert got.shape == ref.shape, (what, got.shape, ref.shape)
    err = float(np.abs(got - ref).max(initial=0))
    assert err <= rtol * scale, f"{what}: differs by {err:.3e}, {err / scale:.2e} of its scale {scale:.3e}"


# Processes of a run, for the tests that kill one.
def children(pid):
    """The processes whose parent is pid (the ranks, for mpiexec)."""
    kids = []
    for p in os.listdir("/proc"):
        if p.isdigit():
            try:
                stat = open(f"/proc/{p}/stat").read()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                kids.append(int(p))
    return kids


def history_rows(path):
    try:
        with open(path, "rb") as f:
            return f.read().count(b"\n") - 1
    except OSError:
        return -1


def alive(pids):
    """Those of pids still running (not gone, not zombies)."""
    def state(pid):
        try:
            return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0]
        except OSError:
            return None
    return [p for p in pids if state(p) not in (None, "Z")]


def stop(proc):
    if proc.poll() is None:
        for p in children(proc.pid):
            os.kill(p, signal.SIGKILL)
        proc.kill()
        proc.wait()


def signal_ranks(proc, ready, sig, nranks, delay=0.0):
    """Once ready(), waits delay s and sends sig to the nranks ranks of the mpiexec proc at once (as
    a batch scheduler does), then waits until they are gone: their files are then final (mpiexec
    itself takes a while longer to notice). On any failure the job is killed."""
    try:
        t0, ranks = time.time(), []
        while len(ranks) < nranks:  # found first, so that the signal follows the trigger at once
            assert proc.poll() is None and time.time() - t0 < 60, "no ranks"
            ranks = children(proc.pid)
        while not ready():
            assert proc.poll() is None and time.time() - t0 < 60, "the run ended before the signal"
            time.sleep(0.0002)
        time.sleep(delay)
        for p in ranks:
            os.kill(p, sig)
        while alive(ranks):
            assert time.time() - t0 < 60, "the ranks outlived the signal"
            time.sleep(0.001)
    except BaseException:
        stop(proc)
        raise


def stage_event_count(output, stage, event):
    """How many times -log_view counted `event` in the log stage named `stage` (0 if not there)."""
    count, inside = 0, False
    for line in output.splitlines():
        if line.startswith("--- Event Stage"):
            inside = line.rstrip().endswith(stage)
        elif inside and line.split()[:1] == [event]:
            count += int(line.split()[1])
    return count


@contextlib.contextmanager
def small_fs(size):
    """A real full disk: a tmpfs of `size` (mount's syntax: 8k, 1m) on a fresh directory, unmounted
    however the test ends (root only; skipped where mount is not permitted)."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root")
    d = tempfile.mkdtemp(prefix="mm_fulldisk_")
    proc = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", d], capture_output=True, text=True)
    if proc.returncode != 0:
        os.rmdir(d)
        pytest.skip(f"mount -t tmpfs not permitted here: {proc.stderr.strip()}")
    try:
        yield d
    finally:
        if subprocess.run(["umount", d]).returncode != 0:
            subprocess.run(["umount", "-l", d])
        os.rmdir(d)
