"""Runs that never lose or hide data, and errors a user can act on (README "Exit status" and
"What is checked before the run"): one run per output directory, options without a value, bodies
turned inside out, a file-size limit, output paths too long for MPI-IO, ranks orphaned by a killed
mpiexec, and the first line of stderr of a refused run."""
import os
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import EXE, MPIEXEC, ROOT, alive, children, history_rows, run, stop

USAGE, PHYSICS, LOCKED, IO = 64, 65, 73, 74


def opts(case):
    return os.path.join(ROOT, "options", case + ".opts")


def first_line(r):
    """The first line of stderr: conftest's Run merges the streams, so the tests that check it run
    the executable themselves."""
    return r.stderr.splitlines()[0] if r.stderr else ""


def direct(*args, env=None):
    """The executable on one rank, without mpiexec, stderr kept apart."""
    return subprocess.run([EXE, *map(str, args)], cwd=ROOT, capture_output=True, text=True, timeout=300, env=env)


def files(d):
    """The text files' bytes, and the HDF5 files' datasets (HDF5 files of equal content differ in
    their bytes: object headers carry times)."""
    import h5py
    got = {}
    for n in sorted(os.listdir(d)):
        path = os.path.join(d, n)
        if not os.path.isfile(path):
            continue
        if n.endswith(".h5"):
            with h5py.File(path, "r") as f:
                sets = {}
                f.visititems(lambda k, v: sets.__setitem__(k, v[()]) if isinstance(v, h5py.Dataset) else None)
            got[n] = sets
        else:
            got[n] = open(path, "rb").read()
    return got


def assert_same_files(a, b):
    """The same files; the same bytes for text, the same datasets for HDF5 (to 1e-12 of each
    dataset's own largest value: the same run on the same machine, computed twice)."""
    assert sorted(a) == sorted(b)
    for n in a:
        if not n.endswith(".h5"):
            assert a[n] == b[n], n
            continue
        assert sorted(a[n]) == sorted(b[n]), n
        for k, v in a[n].items():
            w = b[n][k]
            assert np.shape(v) == np.shape(w), (n, k)
            if np.issubdtype(np.asarray(v).dtype, np.number):
                scale = max(np.abs(v).max() if np.size(v) else 0, 1e-300)
                assert np.abs(np.asarray(v, float) - np.asarray(w, float)).max(initial=0) <= 1e-12 * scale, (n, k)
            else:
                assert np.array_equal(v, w), (n, k)


# 1. One run per output directory
def test_second_run_on_a_used_directory_is_refused_and_touches_nothing(tmp_path):
    """A run holds its -output_dir from set-up to exit. A second run on it, started while the first is
    frozen mid-run (SIGSTOP, so that the test does not depend on the machine's speed), is refused
    with exit 73 and a first line that names the directory and the holder's pid; it touches nothing:
    the first run, resumed, ends with files byte-identical to the same run in a directory of its own."""
    out, alone = tmp_path / "shared", tmp_path / "alone"
    args = ["-options_file", opts("d1_friction"), "-ts_dt", "1e-4", "-output_every", "100", "-quiet"]
    ref = subprocess.run(MPIEXEC + ["-n", "1", EXE, *args, "-output_dir", str(alone)], cwd=ROOT, capture_output=True, text=True)
    assert ref.returncode == 0, ref.stderr[-2000:]
    first = subprocess.Popen(MPIEXEC + ["-n", "1", EXE, *args, "-output_dir", str(out)], cwd=ROOT,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        t0 = time.time()
        while history_rows(str(out / "history.csv")) < 20:
            assert first.poll() is None and time.time() - t0 < 60, "the first run ended early"
            time.sleep(0.001)
        ranks = children(first.pid)
        for p in ranks:
            os.kill(p, signal.SIGSTOP)
        lock = (out / ".mmcontact.lock").read_text()
        assert f"pid {ranks[0]}" in lock, lock
        second = direct("-options_file", opts("d1_disk"), "-output_dir", out)
        assert second.returncode == LOCKED, second.stderr[-2000:]
        line = first_line(second)
        assert line.startswith("mmcontact error: The output directory") and str(out) in line and f"process {ranks[0]}" in line, line
        assert not (out / "previous").exists()
        for p in ranks:
            os.kill(p, signal.SIGCONT)
        assert first.wait(timeout=120) == 0, first.stderr.read()[-2000:]
    finally:
        stop(first)
    assert_same_files(files(str(out)), files(str(alone)))
    assert not (out / ".mmcontact.lock").exists()  # released at exit


def test_lock_of_a_killed_run_is_taken_over(tmp_path):
    """A run killed by SIGKILL leaves its lock file, but not its lock: the next run takes it."""
    out = tmp_path / "out"
    proc = subprocess.Popen(MPIEXEC + ["-n", "1", EXE, "-options_file", opts("d1_friction"), "-ts_dt", "1e-4", "-output_dir", str(out), "-quiet"],
                            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.time()
    while history_rows(str(out / "history.csv")) < 5:
        assert proc.poll() is None and time.time() - t0 < 60
        time.sleep(0.001)
    ranks = children(proc.pid)
    for p in ranks:
        os.kill(p, signal.SIGKILL)
    proc.wait(timeout=60)
    while alive(ranks):
        time.sleep(0.01)
    assert (out / ".mmcontact.lock").exists()
    r = run("d1_disk", tmp_path, "-ts_max_steps", 3, name="out")
    assert r.returncode == 0 and len(r.history) == 4
    assert not (out / ".mmcontact.lock").exists()


# 2. Options without a value
@pytest.mark.parametrize("extra,name", [
    (("-E",), "-E"),                             # last on the line: it would override the file's -E 1000
    (("-mu", "-v0", "0.5,-1"), "-mu"),           # followed by another option
    (("-v0",), "-v0"),
    (("-ts_dt",), "-ts_dt"),                     # the stepper's: found from the help text
    (("-contact_snes_rtol", "-quiet"), "-contact_snes_rtol"),
])
def test_option_without_value_is_refused_by_name(tmp_path, extra, name):
    r = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "out", *extra)
    assert r.returncode == USAGE, r.stderr[-2000:]
    assert first_line(r) == f'mmcontact error: {name} was given without a value: write "{name} VALUE", or leave the option out for its default' or \
        first_line(r).startswith(f"mmcontact error: {name} was given without a value"), first_line(r)
    assert not (tmp_path / "out" / "history.csv").exists()


def test_flag_without_value_still_runs(tmp_path):
    """Flags (-quiet, -ts_monitor) take no value: they are not refused."""
    r = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "out", "-ts_max_steps", 2, "-ts_monitor", "-quiet")
    assert r.returncode == 0, r.stderr[-2000:]


# 3. Bodies that turn inside out
def test_inverted_body_stops_the_run(tmp_path):
    """-v0 0.5,-200 on D1: cells turn inside out in the first step (the contact nodes stay on the
    plane, so the contact check alone saw nothing). The run stops with exit 65, naming the step, the
    cell and det F; history.csv holds the initial state only."""
    out = tmp_path / "out"
    r = direct("-options_file", opts("d1_disk"), "-output_dir", out, "-v0", "0.5,-200")
    assert r.returncode == PHYSICS, r.stderr[-2000:]
    line = first_line(r)
    assert line.startswith("mmcontact error: At step 1 (t = 0.002) the cell at (") and "has turned inside out (det F = -" in line, line
    h = np.genfromtxt(out / "history.csv", delimiter=",", names=True, ndmin=1)
    assert list(h["step"]) == [0]


def test_strain_warns_once_and_max_strain_stops(tmp_path):
    """D2 (the ball, strains up to about 0.2 at the impact) warns once above -strain_warn 0.1, with
    the step and the value; the summary gives the largest strain. -max_strain 0.15 stops the same run
    at the step where the warning's run crossed it."""
    ok = run("d2_ball", tmp_path, "-output_every", 0, name="ok")
    warnings = [l for l in ok.output.splitlines() if l.startswith("mmcontact warning:")]
    assert len(warnings) == 1 and "above -strain_warn 0.1" in warnings[0], warnings
    largest = float(ok.output.split("largest strain ")[1].split()[0])
    assert 0.15 < largest < 1
    r = direct("-options_file", opts("d2_ball"), "-output_dir", tmp_path / "stop", "-max_strain", 0.15)
    assert r.returncode == PHYSICS
    assert "above -max_strain 0.15: a small-strain model means nothing there" in first_line(r), first_line(r)


# 4. A file-size limit
def test_file_size_limit_stops_with_the_file_named_and_whole_rows(tmp_path):
    """Under a file-size limit (ulimit -f, set in the ranks only) the run is not killed by SIGXFSZ: it
    stops with exit 74 and a message naming history.csv and the system's reason, and history.csv ends
    on a whole row (every row has every column; no number cut short)."""
    out = tmp_path / "out"
    limit = 1_000_000  # history.csv of 3000 rows would be 2 MB; solution.h5 with two snapshots stays far below
    wrap = "import os, resource, sys; n = int(sys.argv[1]); resource.setrlimit(resource.RLIMIT_FSIZE, (n, n)); os.execv(sys.argv[2], sys.argv[2:])"
    args = MPIEXEC + ["-n", "2", "/usr/bin/python3", "-s", "-c", wrap, str(limit), EXE, "-options_file", opts("d1_disk"),
                      "-ts_dt", "1e-4", "-output_every", "0", "-output_dir", str(out), "-quiet"]
    env = dict(os.environ, OMPI_MCA_btl="self,tcp")  # shared memory would hit the limit too
    proc = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == IO, proc.stderr[-2000:]
    assert f"Could not write {out}/history.csv: File too large" in proc.stderr, proc.stderr[-2000:]
    data = (out / "history.csv").read_bytes()
    assert len(data) <= limit and data.endswith(b"\n")
    rows = data.decode().splitlines()
    ncol = len(rows[0].split(","))
    assert len(rows) > 100 and all(len(r.split(",")) == ncol for r in rows)
    h = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    assert np.array_equal(h["step"], np.arange(len(h)))


# 5. Long output paths
def test_output_dir_too_long_for_mpiio_is_refused_before_anything_moves(tmp_path):
    """An -output_dir whose HDF5 names would overflow Open MPI's file-open buffer (it aborted the
    process after previous/ had been made) is refused with the other options: the earlier files
    stay where they are."""
    long = tmp_path / ("d" * (230 - len(str(tmp_path)) - 1))
    assert len(str(long)) == 230
    long.mkdir()
    (long / "history.csv").write_text("step\n0\n")
    r = direct("-options_file", opts("d1_disk"), "-output_dir", long)
    assert r.returncode == USAGE
    assert first_line(r).startswith(f"mmcontact error: -output_dir {long} is 230 characters long"), first_line(r)
    assert os.listdir(long) == ["history.csv"] and (long / "history.csv").read_text() == "step\n0\n"


# 6. SIGKILL to mpiexec
def test_ranks_die_with_a_killed_mpiexec(tmp_path):
    """SIGKILL to mpiexec: its ranks die with it (they used to run on, writing, for a second or two),
    so history.csv does not grow after the kill."""
    out = tmp_path / "out"
    proc = subprocess.Popen(MPIEXEC + ["-n", "2", EXE, "-options_file", opts("d1_friction"), "-ts_dt", "1e-5",
                                       "-output_dir", str(out), "-quiet"], cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.time()
    ranks = []
    while len(ranks) < 2 or history_rows(str(out / "history.csv")) < 5:
        assert proc.poll() is None and time.time() - t0 < 60
        ranks = children(proc.pid)
        time.sleep(0.001)
    proc.kill()
    proc.wait()
    killed = time.time()
    while alive(ranks):
        assert time.time() - killed < 0.5, "the ranks outlived mpiexec"
        time.sleep(0.001)
    rows = history_rows(str(out / "history.csv"))
    time.sleep(0.3)
    assert history_rows(str(out / "history.csv")) == rows


# 7, 8. Errors a user can act on: one line, first, a documented status
@pytest.mark.parametrize("extra,status,line", [
    (("-E", "1e3Pa"), USAGE, 'mmcontact error: -E 1e3Pa: "1e3Pa" is not a number.'),
    (("-v0", "0.5,x"), USAGE, 'mmcontact error: -v0 0.5,x: "x" is not a number.'),
    (("-output_every", "5x"), USAGE, 'mmcontact error: -output_every 5x: "5x" is not an integer.'),
    (("-E", -1), USAGE, "mmcontact error: Young's modulus -E -1. must be > 0"),
    (("-ts_type", "nosuch"), USAGE, "mmcontact error: Unknown TS type: nosuch"),
    (("-mu_", 0.2), USAGE, "mmcontact error: 1 option is set but never read"),
    (("-audit_tol", 1e-30), PHYSICS, "mmcontact error: Energy audit failed at step 1"),
])
def test_user_errors_print_their_message_first(tmp_path, extra, status, line):
    """The message is the first line of stderr, not under PETSc's configure dump and traceback; no
    unused-option warning follows a refusal; the exit status is the documented one. On 2 ranks
    too: one message, from rank 0."""
    r = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "one", *extra)
    assert r.returncode == status and first_line(r).startswith(line), r.stderr[-2000:]
    assert "PETSC ERROR" not in r.stderr and "There are options you set that were not used" not in r.stdout + r.stderr
    two = subprocess.run(MPIEXEC + ["-n", "2", EXE, "-options_file", opts("d1_disk"), "-output_dir", str(tmp_path / "two"), *map(str, extra)],
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert two.returncode == status and first_line(two).startswith(line), two.stderr[-2000:]
    assert sum(l.startswith("mmcontact error") for l in two.stderr.splitlines()) == 1, two.stderr


def test_debug_keeps_petsc_trace(tmp_path):
    r = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "out", "-E", -1, "-debug")
    assert r.returncode != 0 and "PETSC ERROR" in r.stderr and "Young's modulus -E -1. must be > 0" in r.stderr


def test_audit_failure_far_above_the_solver_tolerance_points_to_units(tmp_path):
    """An energy residual orders of magnitude above -contact_tol is not a loose solve: the message says
    to check the units, not to tighten tolerances; one near it says to tighten them."""
    far = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "far", "-audit_tol", 1e-30, "-contact_tol", 1e-25)
    assert far.returncode == PHYSICS and "check that the units are consistent" in first_line(far) and "will not help" in first_line(far)
    near = direct("-options_file", opts("d1_disk"), "-output_dir", tmp_path / "near", "-audit_tol", 1e-30)
    assert near.returncode == PHYSICS and "tighten -contact_tol" in first_line(near)


def test_options_file_with_byte_order_mark_is_named(tmp_path):
    bom = tmp_path / "bom.opts"
    bom.write_bytes(b"\xef\xbb\xbf" + open(opts("d1_disk"), "rb").read())
    r = direct("-options_file", bom, "-output_dir", tmp_path / "out")
    assert r.returncode == USAGE and "starts with a UTF-8 byte order mark" in first_line(r), r.stderr[-2000:]
    missing = direct("-options_file", tmp_path / "none.opts")
    assert missing.returncode == USAGE and "none.opts cannot be read: No such file or directory" in first_line(missing)


@pytest.mark.parametrize("names", ["floor,,wall", "floor,", ",floor"])
def test_empty_obstacle_names_are_refused(tmp_path, names):
    from conftest import options_without_plane
    r = direct("-options_file", options_without_plane("d2_ball", tmp_path), "-output_dir", tmp_path / "out", "-obstacles", names)
    assert r.returncode == USAGE and first_line(r) == f"mmcontact error: -obstacles {names} has an empty name: give the names separated by single commas"


# 14. -help says what the program does today
def test_help_intro_describes_the_program():
    r = direct("-help")
    assert r.returncode == 0
    intro = r.stdout.split("\n\n")[0]
    for words in ("rigid obstacles", "planes, spheres/circles and cylinders", "Coulomb friction", "energy balance", "restart"):
        assert words in intro, intro
    assert "rigid plane" not in intro
