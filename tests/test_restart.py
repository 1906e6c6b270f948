"""Restart (docs/method.md section 9): a run killed in the middle and continued from its last
checkpoint, on another number of ranks, ends where the uninterrupted run ends, with the same
history.csv and the same snapshots; SIGTERM stops a run cleanly; a torn checkpoint leaves the last
good one usable; a checkpoint of another problem is refused with the difference named."""
import os
import shutil
import signal
import subprocess

import h5py
import numpy as np
import pytest
from conftest import EXE, MPIEXEC, ROOT, history_rows, run, signal_ranks

# The frictional disk: it lands sliding at step 5, friction drags it and it leaves spinning. 400
# steps; a checkpoint every 25, a snapshot every 5.
CASE = "d1_friction"
OPTS = ["-ts_max_time", 0.8, "-checkpoint_every", 25, "-output_every", 5, "-quiet"]
STEPS = 400
EXACT = ["step", "time", "dt", "active", "slipping", "switched", "cfl", "vi_its", "friction_its", "candidates", "candidate_resolves"]
ENERGY = ["kinetic", "elastic", "total", "work_ext", "work_contact", "work_friction", "work_obstacle"]
NOISE = ["balance_residual", "coulomb_residual", "max_penetration", "contraction"]


def ckpt_step(d):
    with h5py.File(os.path.join(d, "checkpoint.h5"), "r") as f:
        return int(f["run"][11])


def start(outdir, np_, *extra):
    args = MPIEXEC + ["-n", str(np_), EXE, "-options_file", os.path.join(ROOT, "options", CASE + ".opts"),
                      "-output_dir", outdir, *map(str, OPTS), *map(str, extra)]
    return subprocess.Popen(args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def signal_when(proc, ready, sig, np_):
    signal_ranks(proc, ready, sig, np_)
    out, _ = proc.communicate(timeout=60)
    return proc.returncode, out


def restart(tmp_path, outdir, np_, *extra, check=True):
    return run(CASE, tmp_path, *OPTS, "-restart", outdir, *extra, np_=np_, name=os.path.basename(outdir), check=check)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted run, on 1 and on 2 ranks."""
    base = tmp_path_factory.mktemp("reference")
    ref = {n: run(CASE, base, *OPTS, np_=n, name=f"np{n}") for n in (1, 2)}
    for r in ref.values():  # ended cleanly: solution.h5 is whole, the checkpoint's copy of it is gone
        assert not os.path.exists(os.path.join(r.outdir, "checkpoint_snapshots.h5"))
    return ref


def assert_same_history(ref, got):
    """No row missing or repeated, and the same numbers: energies and works to 1e-10 of the energy
    scale, forces of the force scale, every other quantity of its own scale; counts exactly. The
    audit residuals are rounding noise, compared with their bounds instead."""
    assert list(got["step"]) == list(range(STEPS + 1))
    escale = np.abs(ref["total"]).max()
    fscale = np.abs(ref["force_normal"]).max()
    assert escale > 1 and fscale > 10
    for c in ref.dtype.names:
        if c in NOISE:
            continue
        if c in EXACT:
            assert np.array_equal(ref[c], got[c]), c
            continue
        scale = escale if c in ENERGY else fscale if c.startswith("force") else max(np.abs(ref[c]).max(), 1e-300)
        assert np.abs(ref[c] - got[c]).max() <= 1e-10 * scale, (c, np.abs(ref[c] - got[c]).max(), scale)
    assert got["balance_residual"].max() < 1e-10 and got["max_penetration"].max() < 1e-9 * 0.0799


def by_serial(f, name):
    order = np.argsort(f["vertex_fields/serial_vertex_nodal"][:])
    return f["vertex_fields"][name][:][:, order]


def assert_same_snapshots(ref, got):
    """The same snapshot times, and every field vertex by vertex (matched by serial number: PETSc
    writes the vertices in the partition's order), to 1e-10 of the field's scale."""
    with ref.fields() as a, got.fields() as b:
        ta, tb = a["time"][:].ravel(), b["time"][:].ravel()
        assert len(ta) == STEPS // 5 + 1 and np.array_equal(ta, tb)
        for name in ("displacement_displacement", "velocity_displacement", "contact_pressure_nodal", "tangential_traction_displacement"):
            fa, fb = by_serial(a, name), by_serial(b, name)
            assert np.abs(fa - fb).max() <= 1e-10 * np.abs(fa).max(), name
    xmf = open(os.path.join(got.outdir, "solution.xmf")).read()
    assert xmf.count('<Grid Name="step') == STEPS // 5 + 1


def assert_same_end(ref, got):
    with h5py.File(os.path.join(ref.outdir, "checkpoint.h5"), "r") as a, h5py.File(os.path.join(got.outdir, "checkpoint.h5"), "r") as b:
        assert a["run"][11] == b["run"][11] == STEPS
        for k in ("u", "v"):
            assert np.abs(a[k][:] - b[k][:]).max() <= 1e-10 * np.abs(a[k][:]).max(), k


@pytest.mark.parametrize("before,after", [(2, 1), (1, 2)])
def test_killed_run_continues_on_other_ranks(tmp_path, reference, before, after):
    """SIGKILL after step 59 on `before` ranks, restart on `after` ranks from the checkpoint of
    step 50, while 5 nodes slide: the rows and snapshots written after it are dropped and computed
    again, and the run ends as the uninterrupted one does. HDF5 rewrites solution.h5's index in place
    as it grows, so a kill while a snapshot is written can leave the file unreadable (seen in CI:
    "addr overflow" reading /time): solution.h5 is cut to a third here, as such a kill leaves it, and
    the restart reads the earlier snapshots from the checkpoint's copy."""
    out = str(tmp_path / "run")
    hist = os.path.join(out, "history.csv")
    rc, _ = signal_when(start(out, before), lambda: history_rows(hist) >= 60, signal.SIGKILL, before)
    assert rc != 0
    k = ckpt_step(out)
    assert k == 50 and history_rows(hist) > k + 1  # rows past the checkpoint
    assert reference[before].history["slipping"][k] >= 3  # in contact, sliding
    sol = os.path.join(out, "solution.h5")
    os.truncate(sol, os.path.getsize(sol) // 3)
    with pytest.raises(OSError):
        h5py.File(sol, "r")["time"][:]
    r = restart(tmp_path, out, after)
    assert_same_history(reference[before].history, r.history)
    assert_same_snapshots(reference[before], r)
    assert_same_end(reference[before], r)


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_signal_checkpoints_and_restarts(tmp_path, reference, sig):
    """SIGTERM to the ranks, as a scheduler sends it (or SIGINT, Ctrl-C): the step is finished, the
    checkpoint is of that step, the output is closed, the message says how to continue and the exit
    status is 75; the restart ends as the uninterrupted run."""
    out = str(tmp_path / "run")
    hist = os.path.join(out, "history.csv")
    rc, text = signal_when(start(out, 2), lambda: history_rows(hist) >= 30, sig, 2)
    assert rc == 75, text[-2000:]
    assert f"stopped by {sig.name} after step" in text and f"-restart {out}" in text
    k = ckpt_step(out)
    assert 30 <= k < STEPS and history_rows(hist) == k + 1  # the checkpoint is of the last step
    assert not os.path.exists(os.path.join(out, "checkpoint.h5.tmp"))
    r = restart(tmp_path, out, 2)
    assert_same_history(reference[2].history, r.history)
    assert_same_snapshots(reference[2], r)


def test_torn_checkpoint_leaves_the_last_one_usable(tmp_path, reference):
    """A kill while a checkpoint is being written (every step, killed when the temporary file is
    there) leaves the last complete checkpoint, and the restart from the directory ends as the
    uninterrupted run. The temporary file, cut short, is refused if named."""
    out = str(tmp_path / "run")
    tmp = os.path.join(out, "checkpoint.h5.tmp")
    for attempt in range(5):
        shutil.rmtree(out, ignore_errors=True)
        rc, _ = signal_when(start(out, 2, "-checkpoint_every", 1), lambda: history_rows(os.path.join(out, "history.csv")) >= 40 and os.path.exists(tmp), signal.SIGKILL, 2)
        if os.path.exists(tmp):
            break
    assert os.path.exists(tmp), "no kill landed during a checkpoint write"
    k = ckpt_step(out)
    # the torn file: whatever the kill left, and a copy of the good one cut in half
    good = open(os.path.join(out, "checkpoint.h5"), "rb").read()
    cut = str(tmp_path / "cut.h5")
    open(cut, "wb").write(good[: len(good) // 2])
    bad = run(CASE, tmp_path, *OPTS, "-restart", cut, np_=0, name="run", check=False)
    assert bad.returncode != 0 and f"Could not open the checkpoint {cut}: it is not a complete HDF5 file" in bad.output
    assert ckpt_step(out) == k  # the refusal touched nothing
    r = restart(tmp_path, out, 2)
    assert_same_history(reference[2].history, r.history)
    assert not os.path.exists(tmp)


@pytest.fixture(scope="module")
def short_checkpoint(tmp_path_factory):
    base = tmp_path_factory.mktemp("short")
    return run(CASE, base, "-ts_max_steps", 10, "-quiet", np_=0, name="ck")


@pytest.mark.parametrize("extra,message", [
    (["-mu", 0.3], "was written with -mu 0.2, this run has -mu 0.3: its state would mean another problem. Restart with -mu 0.2"),
    (["-E", 2000], "was written with -E 1000, this run has -E 2000: its state would mean another problem"),
    (["-mesh_rotation", 0.001], "is of another mesh: it has as many vertices and cells as meshes/disk.msh, but other coordinates"),
    (["-mesh", "meshes/disk_rail.msh"], "is of another contact boundary: 33 contact nodes, this run has 64"),
    (["-contact", 0], "was written with -contact 1, this run has -contact 0"),
    (["-mass", "standard"], "was written with -mass redistributed, this run has -mass standard"),
    (["-damping_mass", 1], "was written with -damping_mass 0, this run has -damping_mass 1"),
])
def test_mismatched_restart_is_refused(tmp_path, short_checkpoint, extra, message):
    before = open(os.path.join(short_checkpoint.outdir, "history.csv")).read()
    r = run(CASE, tmp_path, "-restart", short_checkpoint.outdir, "-output_dir", short_checkpoint.outdir, *extra, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-3000:]
    assert open(os.path.join(short_checkpoint.outdir, "history.csv")).read() == before


def test_restart_on_another_mesh_is_refused(tmp_path, short_checkpoint):
    """The same disk meshed coarser (gmsh, H = 0.2)."""
    coarse = str(tmp_path / "disk_coarse.msh")
    subprocess.run(["gmsh", "-2", os.path.join(ROOT, "meshes", "disk.geo"), "-setnumber", "H", "0.2", "-o", coarse, "-v", "2"], check=True)
    r = run(CASE, tmp_path, "-restart", short_checkpoint.outdir, "-mesh", coarse, np_=0, check=False)
    assert r.returncode != 0 and f"is of another mesh: 423 vertices and 780 cells, this mesh {coarse} has" in r.output, r.output[-2000:]


def test_restart_of_another_dimension_is_refused(tmp_path, short_checkpoint):
    r = run("d2_ball", tmp_path, "-restart", short_checkpoint.outdir, np_=0, check=False)
    assert r.returncode != 0 and "is of a 2D problem, this mesh meshes/ball.msh is 3D: another dimension" in r.output


def test_restart_needs_the_history_of_its_run(tmp_path, short_checkpoint):
    """A checkpoint whose directory holds another run's history (here: cut short) is refused, and a
    missing checkpoint is named."""
    d = tmp_path / "copy"
    shutil.copytree(short_checkpoint.outdir, d)
    lines = open(d / "history.csv").read().splitlines(True)
    (d / "history.csv").write_text("".join(lines[:6]))
    r = run(CASE, tmp_path, "-restart", str(d), np_=0, name="copy", check=False)
    assert r.returncode != 0 and "has no row for step 5 (its rows in order end at step 4;" in r.output and "is at step 10" in r.output
    r = run(CASE, tmp_path, "-restart", str(tmp_path / "nowhere"), np_=0, check=False)
    assert r.returncode != 0 and f"-restart {tmp_path}/nowhere: {tmp_path}/nowhere does not exist" in r.output


@pytest.mark.parametrize("case,extra", [
    ("d1_friction", []),
    ("d1_friction", ["-contact_formulation", "active_set"]),
    # Rayleigh damping: its velocity vC (all dofs, also the massless normal ones) is in the checkpoint
    ("d1_friction", ["-damping_mass", 5, "-damping_stiffness", 1e-3]),
    # a friction corner: the second obstacle's reactions are in the checkpoint (docs/method.md section 12)
    ("block_push", []),
    # 3D: every node in the candidate set, so that the cached columns of K~^{-1} E are computed in
    # the same blocks as in the uninterrupted run (MUMPS's multi-column solves round by block)
    ("d2_ball", ["-mu", 0.3, "-contact_candidate_all"]),
    # rejected steps at 0, 6 and 17, the growback adaptor waiting 20 steps across the restart: its
    # state is in the checkpoint, or the restarted run would grow dt at step 28 instead of 37
    ("f1_block", ["-initial_state", "given", "-mu", 10, "-ts_dt", 6.73242e-4, "-friction_type", "fixedpoint",
                  "-friction_snes_max_it", 3]),
])
def test_restart_on_the_same_rank_is_bitwise(tmp_path, case, extra):
    """On one rank, where runs repeat bit for bit, a run stopped after step 23 and restarted writes
    the same history.csv, byte for byte, as the uninterrupted 40 steps, and the same final state:
    the checkpoint holds everything the steps read (2D friction in both formulations, a moving
    plate and two obstacles, 3D friction with its slip states)."""
    common = [*extra, "-quiet", "-checkpoint_every", 10]
    a = run(case, tmp_path, *common, "-ts_max_steps", 40, np_=0, name="a")
    run(case, tmp_path, *common, "-ts_max_steps", 23, np_=0, name="b")
    b = run(case, tmp_path, *common, "-ts_max_steps", 40, "-restart", str(tmp_path / "b"), np_=0, name="b")
    assert open(os.path.join(a.outdir, "history.csv"), "rb").read() == open(os.path.join(b.outdir, "history.csv"), "rb").read()
    assert len(a.history) == 41 and a.history["active"][23:].max() > 0  # in contact across the restart
    with h5py.File(os.path.join(a.outdir, "checkpoint.h5"), "r") as fa, h5py.File(os.path.join(b.outdir, "checkpoint.h5"), "r") as fb:
        for k in ("u", "v", "a", "react", "contact") + (("vC",) if "-damping_mass" in extra else ()):
            assert np.array_equal(fa[k][:], fb[k][:]), k
