"""Iterative K~ solves: the active-set formulation (CG with GAMG on the free dofs, and with its default
PC, ICC(0) on 1 rank) gives the direct condensed history, with and without friction, in
2D and 3D, on 1 and 2 ranks; -contact 0 with CG
(GAMG, hypre) gives the direct history; the condensed formulation still refuses iterative K~.

Short runs (20 to 30 steps through the impact) with tight solver tolerances on both sides: the
condensed VI at its default -contact_tol leaves round-off of a few 1e-11 h_c' on a gap in 3D, which
can move a node across the 1e-10 h_c' line the active count uses."""
import numpy as np
import pytest

TIGHT = ("-contact_tol", "1e-13")
ITERATIVE = ("-contact_formulation", "active_set", "-contact_K_ksp_type", "cg", "-contact_K_pc_type", "gamg")


def assert_same_history(h1, h2, tol=1e-8):
    assert len(h1) == len(h2)
    scale = np.abs(h1["total"]).max()
    for c in ("kinetic", "elastic", "total"):
        assert np.abs(h1[c] - h2[c]).max() <= tol * scale, c
    assert np.array_equal(h1["active"], h2["active"])
    assert h1["active"].max() >= 3


CASES = {
    "d1": ("d1_disk", "-ts_max_time", 0.05),
    "d1_friction": ("d1_friction", "-ts_max_time", 0.05),
    "d2": ("d2_ball", "-ts_max_time", 0.08),
    "d2_friction": ("d2_ball", "-mu", 0.2, "-ts_max_time", 0.08),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_active_set_equals_condensed(case, mm):
    opts, *extra = CASES[case]
    direct = mm(opts, *extra, *TIGHT, "-output_every", 0, name="condensed").history
    it = mm(opts, *extra, *TIGHT, *ITERATIVE, "-output_every", 0, name="active_set")
    h = it.history
    assert_same_history(direct, h)
    assert h["balance_residual"].max() <= 1e-9
    if "friction" in case:
        # the Coulomb residual of every step, and real stick/slip
        assert h["coulomb_residual"].max() <= 1e-8
        assert h["slipping"].max() >= 2
        assert h["friction_its"].max() >= 2
    assert h["max_penetration"].max() == 0  # active nodes sit on the obstacle exactly


@pytest.mark.parametrize("case", ["d2", "d2_friction"])
def test_active_set_default_pc(case, mm):
    """The active set's default contact_K_ PC on 1 rank: ICC(0) of K~, which gives the condensed
    (direct) history with the balance at round-off, with and without friction (docs/method.md
    section 3); on 2 ranks Jacobi, ICC needing one rank's matrix."""
    opts, *extra = CASES[case]
    direct = mm(opts, *extra, *TIGHT, "-output_every", 0, name="condensed").history
    icc = mm(opts, *extra, *TIGHT, "-contact_formulation", "active_set", "-output_every", 0, name="icc")
    assert "K~ by cg + icc" in icc.output
    assert_same_history(direct, icc.history)
    assert icc.history["balance_residual"].max() <= 1e-12
    if "friction" in case:
        assert icc.history["coulomb_residual"].max() <= 1e-8
        assert icc.history["slipping"].max() >= 2
    two = mm(opts, *extra, "-ts_max_steps", 2, "-contact_formulation", "active_set", "-output_every", 0, np_=2, name="two")
    assert "K~ by cg + jacobi" in two.output


def test_active_set_two_ranks(mm):
    """2 ranks, and the default PC (Jacobi) against GAMG on 1 rank."""
    opts, *extra = CASES["d2_friction"]
    one = mm(opts, *extra, *TIGHT, *ITERATIVE, "-output_every", 0, name="one").history
    two = mm(opts, *extra, *TIGHT, "-contact_formulation", "active_set", "-output_every", 0, np_=2, name="two").history
    assert_same_history(one, two)
    assert two["coulomb_residual"].max() <= 1e-8


@pytest.mark.parametrize("pc", ["gamg", "hypre"])
def test_linear_run_iterative_equals_direct(pc, mm):
    """-contact 0: one K~ solve per step, by CG with AMG (and the initial acceleration by CG). A rigid
    motion under gravity is the Newmark predictor itself (CG would take no iteration): the ball starts
    strained, and vibrates."""
    short = ("-contact", 0, "-ts_max_time", 0.06, "-gravity", "0,0,-9.81", "-u0_gradient", "0.01,0,0,0,0.01,0,0,0,-0.02", "-output_every", 0)
    direct = mm("d2_ball", *short, name="direct").history
    cg = mm("d2_ball", *short, *TIGHT, "-contact_K_ksp_type", "cg", "-contact_K_pc_type", pc, "-mass_ksp_type", "cg", "-mass_pc_type", "jacobi", np_=2, name=pc).history
    assert len(direct) == len(cg)
    scale = np.abs(direct["total"]).max()
    for c in ("kinetic", "elastic", "total", "vcm_z"):
        assert np.abs(direct[c] - cg[c]).max() <= 1e-8 * max(scale, np.abs(direct[c]).max()), c
    assert cg["balance_residual"].max() <= 1e-9


def test_condensed_refuses_iterative_K(mm):
    r = mm("d1_disk", "-contact_K_ksp_type", "cg", "-contact_K_pc_type", "gamg", np_=0, check=False)
    assert r.returncode != 0
    assert "-contact_K_pc_type gamg is not supported" in r.output
    assert "-contact_formulation active_set" in r.output


def test_active_set_monitor_and_log_events(mm):
    r = mm("d1_disk", "-ts_max_time", 0.03, *ITERATIVE, "-active_set_monitor", "-log_view", "-output_every", 0, np_=0)
    assert "active set  1:" in r.output
    for ev in ("MMKtSetUp", "MMActiveSetIter", "MMActiveSetCG"):
        assert ev in r.output


def cg_iterations(output):
    """Total CG iterations of a run from -active_set_monitor: each contact solve prints its running
    count, restarting at "active set  1"."""
    total, last = 0, 0
    for line in output.splitlines():
        if "active set " not in line or "CG iterations so far" not in line:
            continue
        if "active set  1:" in line:
            total += last
        last = int(line.split("nodes changed set")[1].split(",")[-1].split()[0])
    return total + last


@pytest.mark.parametrize("case", ["d2", "d2_friction"])
def test_inexact_active_set_solves_give_the_exact_ones(case, mm):
    """While nodes change set the active-set CG solves are loose (-active_set_inexact_rtol): they only
    decide the next sets, which tight solves then confirm. The answer is the one of tight solves
    throughout, with the same contact and slip sets, in fewer CG iterations, on 2 ranks."""
    opts, *extra = CASES[case]
    common = (opts, *extra, "-contact_formulation", "active_set", "-active_set_monitor", "-output_every", 0)
    tight = mm(*common, "-active_set_inexact_rtol", 0, np_=2, name="tight")
    loose = mm(*common, np_=2, name="loose")
    assert_same_history(tight.history, loose.history)
    assert np.array_equal(tight.history["slipping"], loose.history["slipping"])
    assert "(loose solve)" in loose.output and "(loose solve)" not in tight.output
    assert loose.history["balance_residual"].max() <= 1e-9
    if "friction" in case:
        assert loose.history["coulomb_residual"].max() <= 1e-8 and loose.history["slipping"].max() >= 2
    assert cg_iterations(loose.output) < 0.9 * cg_iterations(tight.output)


def block_copies(output):
    """How many times -log_view says the active-set CG's block copy of K~ was made or refilled."""
    import re
    return sum(int(n) for n in re.findall(r"^MMBlockOperator\s+(\d+)", output, re.M))


@pytest.mark.parametrize("case, np_", [("d2_friction", 2), ("d1_friction", 1), ("punch", 2)])
def test_block_storage_products_equal_the_aij_ones(case, np_, mm):
    """The active-set CG multiplies by a copy of K~ in symmetric block storage (SBAIJ, one block per
    pair of vertices, the upper triangle only, src/contact/impls/active_set/block_operator.c), filled
    from K~'s AIJ a block row at a time. Its products only sum in another order, so the history equals the one with K~'s AIJ
    (-active_set_block_matrix 0) to 1e-10 of the energy, with the same contact and slip sets: in 3D
    on 2 ranks (blocks in both ranks' off-diagonal parts) and in 2D on 1 rank (2 x 2 blocks). A block
    put in the wrong place or transposed changes the answer by far more. The punch (2D, the press's
    vertices under Dirichlet conditions, so PETSc gives K~ block size 1 but whole blocks remain)
    takes the block copy too. -log_view shows the copy made (one dt: once) with the default, never
    with 0."""
    opts, *extra = CASES[case] if case in CASES else (case, "-ts_max_time", 0.06)
    common = (opts, *extra, *TIGHT, "-contact_formulation", "active_set", "-output_every", 0, "-log_view")
    aij = mm(*common, "-active_set_block_matrix", 0, np_=np_, name="aij")
    block = mm(*common, np_=np_, name="block")
    assert block_copies(aij.output) == 0 and block_copies(block.output) == 1, (block_copies(aij.output), block_copies(block.output))
    assert "CG products with K~ in symmetric block storage (SBAIJ)" in block.output and "block storage" not in aij.output
    assert_same_history(aij.history, block.history, tol=1e-10)
    assert np.array_equal(aij.history["slipping"], block.history["slipping"])
    assert block.history["balance_residual"].max() <= 1e-9
    if "friction" in case:
        assert block.history["slipping"].max() >= 2 and block.history["coulomb_residual"].max() <= 1e-8


def test_block_storage_falls_back_to_aij_where_blocks_are_broken(mm):
    """B1's bar holds only the axial component of its right end (-dirichlet_right_components 0): that
    end's vertices keep one of their two dofs, so K~ is not made of whole 2 x 2 blocks. The CG then
    multiplies by K~'s AIJ, the header says so, and the history is the AIJ one exactly."""
    common = ("b1_bar", "-contact_formulation", "active_set", "-ts_max_steps", 100, "-output_every", 0)
    default = mm(*common, name="default")
    aij = mm(*common, "-active_set_block_matrix", 0, name="aij")
    assert "CG products with K~'s AIJ (its pattern is not in whole blocks)" in default.output
    assert "block storage" not in default.output
    for c in ("kinetic", "elastic", "total", "active"):
        assert np.array_equal(default.history[c], aij.history[c]), c
    assert default.history["active"].max() >= 1
