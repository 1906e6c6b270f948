"""Checkpoints (docs/method.md section 9): the complete state in OUTPUT_DIR/checkpoint.h5, keyed by
the serial mesh's vertex numbers so that it does not depend on the number of ranks."""
import os

import h5py
import numpy as np


def state(run):
    with h5py.File(os.path.join(run.outdir, "checkpoint.h5"), "r") as f:
        return {k: f[k][:] for k in f.keys()}


RUN = {"time": 8, "dt_next": 9, "step": 11, "work_ext": 12, "work_contact": 13, "work_friction": 14, "snapshots": 20}


def test_checkpoint_is_the_same_on_one_and_two_ranks(mm):
    """The frictional disk written by 1 and by 2 ranks: the same state vertex by vertex (to rounding),
    the same contact set and friction states, and the run record of the last history row."""
    a = mm("d1_friction", "-ts_max_time", 0.2, np_=1, name="one")
    b = mm("d1_friction", "-ts_max_time", 0.2, np_=2, name="two")
    sa, sb = state(a), state(b)
    assert not os.path.exists(os.path.join(b.outdir, "checkpoint.h5.tmp"))
    for k in ("u", "v", "react"):
        scale = np.abs(sa[k]).max()
        assert scale > 0 and np.abs(sa[k] - sb[k]).max() <= 1e-10 * scale, k
    assert np.abs(sa["a"] - sb["a"]).max() <= 1e-9 * np.abs(sa["a"]).max()
    ca, cb = sa["contact"].reshape(-1, 13), sb["contact"].reshape(-1, 13)
    assert np.array_equal(ca[:, 0], cb[:, 0]) and ca[:, 0].sum() > 10  # the contact set
    assert np.array_equal(ca[:, 3], cb[:, 3])  # the active set of the last step
    assert np.abs(ca[:, 1] - cb[:, 1]).max() <= 1e-9 * max(np.abs(ca[:, 1]).max(), 1e-300)  # friction thresholds
    h = a.history
    run = sa["run"]
    assert run[RUN["step"]] == h["step"][-1] and run[RUN["time"]] == h["time"][-1]
    for c in ("work_ext", "work_contact", "work_friction"):
        assert run[RUN[c]] == h[c][-1], c
    assert run[RUN["snapshots"]] == len(sa["snapshot_times"]) and np.isclose(sa["snapshot_times"][-1], h["time"][-1])


def test_checkpoint_every_k_steps_replaces_the_last(mm):
    """-checkpoint_every 7 on a 25-step run: the file holds the final state (the end always writes
    one), and no temporary file is left behind."""
    r = mm("d1_disk", "-ts_max_steps", 25, "-checkpoint_every", 7, np_=2)
    s = state(r)
    assert s["run"][RUN["step"]] == 25
    assert sorted(os.listdir(r.outdir)) == ["checkpoint.h5", "history.csv", "solution.h5", "solution.xmf"]


def test_negative_checkpoint_every_is_refused(mm):
    r = mm("d1_disk", "-checkpoint_every", -1, np_=0, check=False)
    assert r.returncode != 0 and "-checkpoint_every -1 must be >= 0" in r.output
