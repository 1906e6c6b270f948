"""The condensed contact on a candidate set (docs/method.md section 3, "Candidate set") gives the
full-set answer: with the set started too small, it grows and re-solves until it does."""
import numpy as np
import pytest

# tight enough that the full-set reference, whose VI also carries every far-away node, is exact to 1e-10
TIGHT = ("-contact_tol", 1e-14, "-output_every", 0)
TIGHT_FRICTION = ("-friction_snes_rtol", 1e-13, "-friction_coulomb_tol", 1e-11)
COLUMNS = ["kinetic", "elastic", "total", "work_contact", "work_friction", "force_normal", "force_tangential"]


def same_history(ref, h, tol):
    assert len(ref) == len(h)
    scale = np.abs(ref["total"]).max()
    for c in COLUMNS + [n for n in ref.dtype.names if n.startswith(("vcm_", "L_"))]:
        assert np.abs(ref[c] - h[c]).max() <= tol * max(scale, np.abs(ref[c]).max()), c
    assert np.array_equal(ref["active"], h["active"])


@pytest.mark.parametrize("case,extra,np_", [
    ("d1_disk", ("-ts_max_time", 0.2), 1),
    ("d2_ball", ("-mu", 0.2, "-ts_max_time", 0.08, *TIGHT_FRICTION), 2),
])
def test_growth_gives_the_full_set_solution(mm, case, extra, np_):
    """-contact_candidate_margin -1 starts every step from the deepest predicted node alone: nodes
    outside the set must come into contact within the step, the set grows and the step's VI is
    solved again. The result is the full Delassus operator's (-contact_candidate_all) to 1e-10,
    with the same active nodes at every step."""
    full = mm(case, *extra, *TIGHT, "-contact_candidate_all", np_=np_, name="all")
    grow = mm(case, *extra, *TIGHT, "-contact_candidate_margin", -1, np_=np_, name="grow")
    h, ref = grow.history, full.history
    assert h["candidate_resolves"][-1] > 0  # the growth really happened
    assert ref["candidate_resolves"][-1] == 0
    same_history(ref, h, 1e-10)
    assert h["max_penetration"].max() <= 1e-10 * 0.08


def test_default_set_is_small_and_exact(mm):
    """The default margin: on the frictional D1 disk the set is a fraction of the 33 contact nodes,
    never needs to grow, and gives the full-set history."""
    full = mm("d1_friction", "-ts_max_time", 0.12, *TIGHT, *TIGHT_FRICTION, "-contact_candidate_all", np_=2, name="all")
    cand = mm("d1_friction", "-ts_max_time", 0.12, *TIGHT, *TIGHT_FRICTION, np_=2, name="cand")
    h = cand.history
    assert full.history["candidates"].max() == 33
    assert 0 < h["candidates"].max() <= 12
    same_history(full.history, h, 1e-10)
    assert "largest %d of 33 contact nodes" % h["candidates"].max() in cand.output


def test_memory_cap_evicts_and_stays_exact(mm):
    """The frictional disk rolling under gravity: its patch moves across 14 contact nodes while the
    set holds at most 11. A cap of 12 nodes' columns (1056 bytes each, without the whole columns)
    drops the whole columns, so every step is recovered by a solve, and drops cached nodes outside
    the set, whose columns are recomputed when they return. The history is the uncapped one."""
    case = ("-gravity", "0,-20", "-v0", "3,-1", "-ts_max_time", 0.6, *TIGHT, *TIGHT_FRICTION)
    ref = mm("d1_friction", *case, np_=0, name="uncapped")
    cap = mm("d1_friction", *case, "-contact_candidate_memory", 0.0125, np_=0, name="capped")
    assert "largest 11 of 33 contact nodes; 28 columns" in ref.output
    assert "contact candidate cache" not in ref.output
    evicted = int(cap.output.split("MiB: ")[1].split()[0])
    recomputed = int(cap.output.split("contact nodes; ")[1].split()[0]) - 28
    assert evicted > 0 and recomputed > 0
    assert int(cap.output.split("recomputed when needed; ")[1].split()[0]) > 0  # steps recovered by a solve
    same_history(ref.history, cap.history, 1e-10)


def test_memory_cap_too_small_is_refused(mm):
    """A cap the step's set alone exceeds stops the run, saying what it needs."""
    r = mm("d1_friction", "-contact_candidate_memory", 0.002, np_=0, check=False)
    assert r.returncode != 0
    assert "-contact_candidate_memory 0.002 MiB" in r.output and "Raise it" in r.output
    assert len(r.history) > 1  # the steps before it are on disk


@pytest.mark.parametrize("option,value,message", [
    ("-contact_candidate_margin", -2, "-contact_candidate_margin -2. must be >= -1"),
    ("-contact_candidate_memory", 0, "-contact_candidate_memory 0. must be > 0 (MiB)"),
])
def test_candidate_options_out_of_range_are_refused(mm, option, value, message):
    r = mm("d1_disk", option, value, np_=0, check=False)
    assert r.returncode != 0 and message in r.output, r.output[-1500:]


@pytest.mark.parametrize("keep", [1, 0])
def test_columns_on_two_ranks_through_refactorizations(mm, keep):
    """3D on 2 ranks the candidate columns come from MUMPS's solve on PETSc's factor with a solution
    map built once per factorization (src/contact/impls/condensed/mumps_columns.c); on 1 rank from
    MatMatTransposeSolve. The 3D box at mu = 10 with the fixed point held to 3 updates is rejected
    down to dt/64 and grown back: K~ is refactored at every change of dt (-contact_K_keep 0), or
    swapped with the kept factor and its columns (1), and all 98 contact nodes are in the set. Both
    rank counts give the same history to round-off: a column moved to the wrong rows, or one left
    from the previous factor, would change the forces at once."""
    case = ("-initial_state", "given", "-mu", 10, "-ts_max_steps", 25, "-output_every", 0, "-friction_type", "fixedpoint",
            "-friction_snes_max_it", 3, "-contact_K_keep", keep, "-contact_formulation", "condensed")
    one = mm("f1_box", *case, np_=1, name="one")
    two = mm("f1_box", *case, np_=2, name="two")
    h1, h2 = one.history, two.history
    assert len(h1) == len(h2) == 26
    assert np.array_equal(h1["dt"], h2["dt"]) and h1["dt"].max() / h1["dt"][1:].min() >= 64  # the refactorizations happened
    assert np.array_equal(h1["active"], h2["active"]) and h1["active"].max() == 98
    columns = [r.output.split("contact nodes; ")[1].split()[0] for r in (one, two)]
    assert columns[0] == columns[1] == ("1764" if keep else "2940")
    energy, force = h1["total"][0], np.abs(h1["force_normal"]).max()
    for c in ("total", "kinetic", "work_friction", "vcm_x", "vcm_y"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-10 * max(energy, np.abs(h1[c]).max()), c
    for c in ("force_normal", "force_tangential"):
        assert np.abs(h1[c] - h2[c]).max() <= 1e-9 * max(force, np.abs(h1[c]).max()), c
    assert h2["coulomb_residual"][1:].max() <= 1e-8 and h2["balance_residual"].max() <= 1e-8
