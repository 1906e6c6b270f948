/* The condensed operator on a candidate set (docs/method.md section 3, "Candidate set").
 *
 * The step's contact VI needs the Delassus operator W = E^T K~^{-1} E only on the nodes that can
 * touch in the step. Its columns come from the factor of K~ when a node first enters the set and
 * are cached, on the owned condensed rows, until K~ is refactored (a new dt) or the cache exceeds
 * -contact_candidate_memory. The set's block W_SS is small and dense: it is gathered on every rank
 * and its VI solved there with LAPACK, identically, so no matrix of size (contact dofs)^2 exists.
 * A node outside the set that the recovered step would push into the obstacle joins it, and the
 * step is solved again: the answer is the full-set one. */
#include "condensedimpl.h"

static PetscBool NodeIsLocal(MMCandidates *c, MMContact ct, PetscInt g)
{
  return (PetscBool)(g >= c->node_start && g < c->node_start + ct->n_local);
}

/* The set's VI solver, created at set-up on a 1x1 placeholder so that its options (prefix contact_)
 * are read and checked before the first step; each new set gets its own (BuildSetOperator). */
static PetscErrorCode CreateSetSolver(MMContact ct)
{
  MMCandidates *c = &MMCondensedData(ct)->cand;
  Mat           W0;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, 1, 1, NULL, &W0));
  PetscCall(MatShift(W0, 1.0));
  PetscCall(MatAssemblyBegin(W0, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(W0, MAT_FINAL_ASSEMBLY));
  c->qp.A      = W0;
  c->qp.rtol_b = ct->tol;
  PetscCall(MMQPCreate(PETSC_COMM_SELF, "contact_", &c->qp, ct->ncomp > 1 ? ct->pb.mu_max : 0, &c->snes));
  PetscCall(MatDestroy(&W0));
  c->qp.A = NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode MMCandidatesSetUp(MMContact ct)
{
  MMCandidates *c = &MMCondensedData(ct)->cand;
  MPI_Comm     comm = PetscObjectComm((PetscObject)ct->dm);
  PetscMPIInt  size, nl;
  const PetscInt *in;
  PetscInt    *mine;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MPI_Scan(&ct->n_local, &c->node_start, 1, MPIU_INT, MPI_SUM, comm));
  c->node_start -= ct->n_local;
  c->nc_local   = ct->ncomp * ct->n_local;
  c->full_ok    = PETSC_TRUE;
  PetscCall(MatGetLocalSize(ct->qp.A, &c->n_local, NULL));
  PetscCall(MatGetSize(ct->qp.A, &c->N, NULL));
  c->margin     = ct->opt.candidate_margin;
  c->all        = ct->opt.candidate_all;
  c->memory_cap = ct->opt.candidate_memory * 1024.0 * 1024.0;
  c->memory_mib = ct->opt.candidate_memory;
  PetscCall(PetscMalloc2(size, &c->node_counts, size, &c->node_displs));
  PetscCall(PetscMPIIntCast(ct->n_local, &nl));
  PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, c->node_counts, 1, MPI_INT, comm));
  c->node_displs[0] = 0;
  for (PetscMPIInt r = 1; r < size; ++r) c->node_displs[r] = c->node_displs[r - 1] + c->node_counts[r - 1];
  PetscCall(PetscMalloc4(ct->n_global, &c->normal_dof, ct->n_global, &c->slot, ct->n_global, &c->in_set, ct->n_global, &c->set));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(PetscMalloc1(ct->n_local, &mine));
  for (PetscInt k = 0; k < ct->n_local; ++k) mine[k] = in[k];
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCallMPI(MPI_Allgatherv(mine, nl, MPIU_INT, c->normal_dof, c->node_counts, c->node_displs, MPIU_INT, comm));
  PetscCall(PetscFree(mine));
  for (PetscInt g = 0; g < ct->n_global; ++g) {
    c->slot[g]   = -1;
    c->in_set[g] = PETSC_FALSE;
  }
  PetscCall(PetscMalloc1(c->nc_local, &c->wc));
  {
    const PetscInt *ic;
    PetscInt        rstart;
    /* is_cond holds owned dofs only: array offsets, where VecGetSubVector would build a scatter each call */
    PetscCall(MatGetOwnershipRange(ct->qp.A, &rstart, NULL));
    PetscCall(PetscMalloc1(c->nc_local, &c->cond_row));
    PetscCall(ISGetIndices(ct->is_cond, &ic));
    for (PetscInt r = 0; r < c->nc_local; ++r) c->cond_row[r] = ic[r] - rstart;
    PetscCall(ISRestoreIndices(ct->is_cond, &ic));
  }
  PetscCall(CreateSetSolver(ct));
  PetscFunctionReturn(0);
}

/* K~ was refactored: every cached column is stale. */
PetscErrorCode MMCandidatesInvalidate(MMContact ct)
{
  MMCandidates *c = &MMCondensedData(ct)->cand;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n_cached; ++i) c->slot[c->slot_node[i]] = -1;
  c->n_cached = 0;
  c->full_ok  = PETSC_TRUE;
  for (PetscInt i = 0; i < c->n_set; ++i) c->in_set[c->set[i]] = PETSC_FALSE;
  c->n_set = 0;
  c->m     = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode UpdateCompliances(MMContact);

/* The cached columns swapped with other's (a kept factor's): the set is emptied, as after a
 * refactorization, and the slots and compliances follow the columns now in place. */
PetscErrorCode MMCandidatesSwapCache(MMContact ct, MMColumnCache *other)
{
  MMCandidates *c   = &MMCondensedData(ct)->cand;
  MMColumnCache mine = {c->cols, c->full, c->slot_node, c->n_cached, c->cap, c->full_ok};

  PetscFunctionBeginUser;
  PetscCall(MMCandidatesInvalidate(ct));
  c->cols      = other->cols;
  c->full      = other->full;
  c->slot_node = other->slot_node;
  c->n_cached  = other->n_cached;
  c->cap       = other->cap;
  c->full_ok   = other->cols ? other->full_ok : PETSC_TRUE;
  *other       = mine;
  for (PetscInt i = 0; i < c->n_cached; ++i) c->slot[c->slot_node[i]] = i;
  PetscCall(UpdateCompliances(ct));
  PetscFunctionReturn(0);
}

/* Keeps only the cached columns of the set's nodes, compacted to the front of the cache. */
static PetscErrorCode EvictOutsideSet(MMContact ct)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;
  PetscInt      nb = ct->ncomp * c->nc_local, kept = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n_cached; ++i) {
    const PetscInt g = c->slot_node[i];
    if (!c->in_set[g]) {
      c->slot[g] = -1;
      continue;
    }
    if (kept != i) PetscCall(PetscArraycpy(c->cols + kept * nb, c->cols + i * nb, nb));
    if (kept != i && c->full_ok) PetscCall(PetscArraycpy(c->full + (size_t)kept * ct->ncomp * c->n_local, c->full + (size_t)i * ct->ncomp * c->n_local, (size_t)ct->ncomp * c->n_local));
    c->slot_node[kept] = g;
    c->slot[g]         = kept++;
  }
  PetscCall(PetscInfo(NULL, "Candidate cache: kept %" PetscInt_FMT " of %" PetscInt_FMT " nodes\n", kept, c->n_cached));
  c->evicted += c->n_cached - kept;
  c->n_cached = kept;
  PetscFunctionReturn(0);
}

/* Room for n more cached nodes, within the memory cap: beyond it the nodes outside the set go,
 * then the full columns (the step is then recovered by a solve), and a set that alone does not
 * fit stops the run. */
static PetscErrorCode ReserveSlots(MMContact ct, PetscInt n)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;
  const PetscInt nr = ct->ncomp;
  const double  per_node = 8.0 * nr * nr * ct->n_global, per_node_full = 8.0 * nr * c->N; /* bytes over all ranks */

  PetscFunctionBeginUser;
  if ((c->n_cached + n) * (per_node + (c->full_ok ? per_node_full : 0)) > c->memory_cap) PetscCall(EvictOutsideSet(ct));
  if (c->full_ok && (c->n_cached + n) * (per_node + per_node_full) > c->memory_cap) {
    PetscCall(PetscInfo(NULL, "Candidate cache: full columns dropped; the step is recovered by a solve\n"));
    c->full_ok = PETSC_FALSE;
    PetscCall(PetscFree(c->full));
  }
  PetscCheck((c->n_cached + n) * per_node <= c->memory_cap, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_USER_INPUT,
             "The contact candidate set (%" PetscInt_FMT " nodes) needs %.3g MiB of K~^{-1} E columns, above -contact_candidate_memory %g MiB. Raise it, or use a contact formulation that needs no Delassus operator",
             c->n_cached + n, (c->n_cached + n) * per_node / 1048576.0, (double)ct->opt.candidate_memory);
  if (c->n_cached + n > c->cap || (c->full_ok && !c->full)) {
    /* doubling, but never allocating past the cap. The arrays are slot-major, so a larger one keeps
     * the cached slots where they are: realloc remaps a large block instead of copying it into
     * fresh pages, whose faults are slow (docs/scaling.md, "The figures behind the code's choices") */
    const PetscInt fit = (PetscInt)(c->memory_cap / (per_node + (c->full_ok ? per_node_full : 0)));
    const PetscInt cap = PetscMax(PetscMin(2 * c->cap, fit), c->n_cached + n);

    if (c->full_ok && !c->full) c->n_cached = 0; /* no full columns yet for the cached ones: start the cache again */
    PetscCall(PetscRealloc(sizeof(PetscScalar) * (size_t)cap * nr * c->nc_local, &c->cols));
    PetscCall(PetscRealloc(sizeof(PetscInt) * (size_t)cap, &c->slot_node));
    if (c->full_ok) PetscCall(PetscRealloc(sizeof(PetscScalar) * (size_t)cap * nr * c->n_local, &c->full));
    c->cap = cap;
  }
  PetscFunctionReturn(0);
}

/* Column i of the new ones (node todo[i / nr], component i % nr) into the cache, from its owned
 * rows xloc (xloc[0] is global row rstart); in order of i, so that a node's slot is taken by its
 * first component. */
static PetscErrorCode StoreColumn(MMContact ct, const PetscInt todo[], PetscInt i, const PetscInt ic[], PetscInt rstart, const PetscScalar xloc[])
{
  MMCandidates  *c  = &MMCondensedData(ct)->cand;
  const PetscInt nr = ct->ncomp, g = todo[i / nr], comp = i % nr;
  PetscScalar   *col;

  PetscFunctionBeginUser;
  if (comp == 0) {
    c->slot[g]                  = c->n_cached;
    c->slot_node[c->n_cached++] = g;
  }
  col = c->cols + ((size_t)c->slot[g] * nr + comp) * c->nc_local;
  for (PetscInt r = 0; r < c->nc_local; ++r) col[r] = xloc[ic[r] - rstart];
  if (c->full_ok) PetscCall(PetscArraycpy(c->full + ((size_t)c->slot[g] * nr + comp) * c->n_local, xloc, c->n_local));
  PetscFunctionReturn(0);
}

/* The global dof of new column i: component i % nr of node todo[i / nr] (its normal dof first). */
static inline PetscInt ColumnDof(const MMCandidates *c, const PetscInt todo[], PetscInt nr, PetscInt i)
{
  return c->normal_dof[todo[i / nr]] + i % nr;
}

/* The m new columns through a distributed factor (MUMPS), a block of right-hand sides at a time:
 * every rank takes part in every solve and keeps its rows. */
static PetscErrorCode SolveColumnsDistributed(MMContact ct, Mat F, const PetscInt todo[], PetscInt m, const PetscInt ic[])
{
  MMCandidates  *c  = &MMCondensedData(ct)->cand;
  MPI_Comm       comm = PetscObjectComm((PetscObject)ct->dm);
  const PetscInt nb_max = 96, nr = ct->ncomp;
  PetscInt       n, rstart, *rows = NULL;
  PetscScalar   *xb   = NULL;
  PetscMPIInt    rank;
  PetscBool      sparse;

  PetscFunctionBeginUser;
  {
    /* MUMPS: unit right-hand sides as a sparse B^T cut the column cost by a third, the same
     * columns to 1e-14 (docs/scaling.md, "The figures behind the code's choices"). MUMPS takes a sparse
     * right-hand side only centralized on its host, so B^T lives on rank 0 whole (a distributed
     * one fails with INFOG(1) = -27); every rank knows every contact node's normal dof. */
    MatSolverType type;
    PetscCall(MatFactorGetSolverType(F, &type));
    PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &sparse));
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MatGetLocalSize(ct->qp.A, &n, NULL));
  PetscCall(MatGetOwnershipRange(ct->qp.A, &rstart, NULL));
  /* the direct MUMPS path's buffers, one block's worth, for all the blocks */
  if (sparse) PetscCall(PetscMalloc2(nb_max, &rows, (size_t)PetscMax(n, 1) * PetscMin(nb_max, m), &xb));
  for (PetscInt i0 = 0; i0 < m; i0 += nb_max) {
    const PetscInt     nb = PetscMin(nb_max, m - i0);
    Mat                B, X;
    const PetscScalar *x;
    PetscInt           lda;

    if (sparse) {
      PetscBool done;

      for (PetscInt j = 0; j < nb; ++j) rows[j] = ColumnDof(c, todo, nr, i0 + j);
      PetscCall(MMMumpsColumnsSolve(&c->mumps, F, nb, rows, xb, n, &done));
      for (PetscInt j = 0; done && j < nb; ++j) PetscCall(StoreColumn(ct, todo, i0 + j, ic, rstart, xb + (size_t)j * n));
      if (done) continue;
    }
    PetscCall(MatCreateDense(comm, n, PETSC_DECIDE, PETSC_DETERMINE, nb, NULL, &X));
    if (sparse) {
      /* MUMPS takes the unit right-hand sides as a sparse B^T and prunes its forward elimination */
      PetscCall(MatCreateAIJ(comm, rank ? 0 : nb, rank ? 0 : c->N, nb, c->N, 1, NULL, 0, NULL, &B));
      for (PetscInt j = 0; !rank && j < nb; ++j) PetscCall(MatSetValue(B, j, ColumnDof(c, todo, nr, i0 + j), 1.0, INSERT_VALUES));
    } else {
      PetscCall(MatDuplicate(X, MAT_DO_NOT_COPY_VALUES, &B));
      for (PetscInt j = 0; j < nb; ++j)
        if (NodeIsLocal(c, ct, todo[(i0 + j) / nr])) PetscCall(MatSetValue(B, ColumnDof(c, todo, nr, i0 + j), j, 1.0, INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    if (sparse) PetscCall(MatMatTransposeSolve(F, B, X));
    else PetscCall(MatMatSolve(F, B, X));
    PetscCall(MatDenseGetLDA(X, &lda));
    PetscCall(MatDenseGetArrayRead(X, &x));
    for (PetscInt j = 0; j < nb; ++j) PetscCall(StoreColumn(ct, todo, i0 + j, ic, rstart, x + (size_t)j * lda));
    PetscCall(MatDenseRestoreArrayRead(X, &x));
    PetscCall(MatDestroy(&X));
    PetscCall(MatDestroy(&B));
  }
  PetscCall(PetscFree2(rows, xb));
  PetscFunctionReturn(0);
}

/* The m new columns through a redundant factor (2D on several ranks: every rank holds all of K~'s
 * factor, sequential): rank q solves the columns [m q / P, m (q + 1) / P) whole, and one
 * MPI_Alltoallv gives every rank its rows of all of them. Each rank solves 1/P of the columns. */
static PetscErrorCode SolveColumnsRedundant(MMContact ct, Mat F, const PetscInt todo[], PetscInt m, const PetscInt ic[])
{
  MMCandidates   *c  = &MMCondensedData(ct)->cand;
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);
  const PetscInt  nb_max = 96, nr = ct->ncomp, N = c->N;
  const PetscInt *ranges;
  PetscMPIInt     rank, size, *scount, *sdispl, *rcount, *rdispl;
  PetscInt        lo, hi, rstart, n;
  PetscScalar    *sbuf, *rbuf;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetOwnershipRanges(ct->qp.A, &ranges));
  PetscCall(MatGetOwnershipRange(ct->qp.A, &rstart, NULL));
  PetscCall(MatGetLocalSize(ct->qp.A, &n, NULL));
  lo = (m * rank) / size;
  hi = (m * (rank + 1)) / size;
  PetscCall(PetscMalloc4(size, &scount, size + 1, &sdispl, size, &rcount, size + 1, &rdispl));
  sdispl[0] = rdispl[0] = 0;
  for (PetscMPIInt q = 0; q < size; ++q) {
    const PetscInt lo_q = (m * q) / size, hi_q = (m * (q + 1)) / size;
    PetscCall(PetscMPIIntCast((hi - lo) * (ranges[q + 1] - ranges[q]), &scount[q]));
    PetscCall(PetscMPIIntCast((hi_q - lo_q) * n, &rcount[q]));
    PetscCall(PetscMPIIntCast((PetscInt)sdispl[q] + scount[q], &sdispl[q + 1]));
    PetscCall(PetscMPIIntCast((PetscInt)rdispl[q] + rcount[q], &rdispl[q + 1]));
  }
  PetscCall(PetscMalloc2(PetscMax(sdispl[size], 1), &sbuf, PetscMax(rdispl[size], 1), &rbuf));
  for (PetscInt i0 = lo; i0 < hi; i0 += nb_max) {
    const PetscInt     nb = PetscMin(nb_max, hi - i0);
    Mat                B, X;
    const PetscScalar *x;
    PetscInt           lda;

    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, N, nb, NULL, &X));
    PetscCall(MatDuplicate(X, MAT_DO_NOT_COPY_VALUES, &B));
    for (PetscInt j = 0; j < nb; ++j) PetscCall(MatSetValue(B, ColumnDof(c, todo, nr, i0 + j), j, 1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatMatSolve(F, B, X));
    PetscCall(MatDenseGetLDA(X, &lda));
    PetscCall(MatDenseGetArrayRead(X, &x));
    /* to rank q: rows [ranges[q], ranges[q+1]) of each column, column by column */
    for (PetscMPIInt q = 0; q < size; ++q) {
      const PetscInt nq = ranges[q + 1] - ranges[q];
      for (PetscInt j = 0; j < nb; ++j) PetscCall(PetscArraycpy(sbuf + sdispl[q] + (i0 - lo + j) * nq, x + ranges[q] + (size_t)j * lda, nq));
    }
    PetscCall(MatDenseRestoreArrayRead(X, &x));
    PetscCall(MatDestroy(&X));
    PetscCall(MatDestroy(&B));
  }
  PetscCallMPI(MPI_Alltoallv(sbuf, scount, sdispl, MPIU_SCALAR, rbuf, rcount, rdispl, MPIU_SCALAR, comm));
  /* rank q's columns arrive in q's order: all of them, in the order of i */
  for (PetscInt i = 0, q = 0; i < m; ++i) {
    while ((m * (q + 1)) / size <= i) ++q;
    PetscCall(StoreColumn(ct, todo, i, ic, rstart, rbuf + rdispl[q] + (i - (m * q) / size) * n));
  }
  PetscCall(PetscFree2(sbuf, rbuf));
  PetscCall(PetscFree4(scount, sdispl, rcount, rdispl));
  PetscFunctionReturn(0);
}

/* The m new columns through a PC that solves exactly but holds no factor matrix (schursplit, the 2D
 * default: on several ranks each solve is collective and costs each rank a sweep each way of its
 * part of K~'s factor, less than half of a whole factor's solve on every rank (docs/scaling.md, "The figures behind the code's choices"). */
static PetscErrorCode SolveColumnsByPC(MMContact ct, PC pc, const PetscInt todo[], PetscInt m, const PetscInt ic[])
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
  const PetscInt     nr = ct->ncomp;
  PetscInt           rstart, rend;
  Vec                e, x;
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(ct->qp.A, &x, &e));
  PetscCall(VecGetOwnershipRange(e, &rstart, &rend));
  PetscCall(VecZeroEntries(e));
  for (PetscInt i = 0; i < m; ++i) {
    const PetscInt row = ColumnDof(c, todo, nr, i);
    PetscScalar   *ea;
    /* every rank knows every contact node's dofs: the owner sets its unit entry, no assembly */
    PetscCall(VecGetArray(e, &ea));
    if (row >= rstart && row < rend) ea[row - rstart] = 1.0;
    PetscCall(VecRestoreArray(e, &ea));
    PetscCall(PCApply(pc, e, x));
    PetscCall(VecGetArray(e, &ea));
    if (row >= rstart && row < rend) ea[row - rstart] = 0.0;
    PetscCall(VecRestoreArray(e, &ea));
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(StoreColumn(ct, todo, i, ic, rstart, xa));
    PetscCall(VecRestoreArrayRead(x, &xa));
  }
  PetscCall(VecDestroy(&e));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* Columns of K~^{-1} E for the set's nodes not yet cached, kept on the owned condensed rows (and,
 * under the memory cap, on all owned rows for the recovery of w). */
static PetscErrorCode ComputeMissingColumns(MMContact ct)
{
  MMCandidates   *c  = &MMCondensedData(ct)->cand;
  PetscInt        nnew = 0, *todo;
  const PetscInt *ic;
  PC              pc;
  Mat             F;
  PetscBool       redundant, split;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(c->n_set, &todo));
  for (PetscInt i = 0; i < c->n_set; ++i)
    if (c->slot[c->set[i]] < 0) todo[nnew++] = c->set[i];
  if (!nnew) {
    PetscCall(PetscFree(todo));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(MMCONTACT_CandidateColumns, 0, 0, 0, 0));
  PetscCall(ReserveSlots(ct, nnew));
  PetscCall(MMKSPGetFactorPC(MMCondensedData(ct)->ksp_K, &pc, &redundant));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCSCHURSPLIT, &split));
  PetscCall(ISGetIndices(ct->is_cond, &ic));
  if (split) PetscCall(SolveColumnsByPC(ct, pc, todo, nnew * ct->ncomp, ic));
  else {
    PetscCall(PCFactorGetMatrix(pc, &F));
    if (redundant) PetscCall(SolveColumnsRedundant(ct, F, todo, nnew * ct->ncomp, ic));
    else PetscCall(SolveColumnsDistributed(ct, F, todo, nnew * ct->ncomp, ic));
  }
  PetscCall(ISRestoreIndices(ct->is_cond, &ic));
  c->columns += nnew * ct->ncomp;
  PetscCall(PetscFree(todo));
  PetscCall(PetscLogEventEnd(MMCONTACT_CandidateColumns, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* diag(W) of the owned cached nodes: the nodal compliances of the 3D return mapping. */
static PetscErrorCode UpdateCompliances(MMContact ct)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;
  const PetscInt nr = ct->ncomp;
  PetscScalar  *wd;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(MMCondensedData(ct)->Wdiag, &wd));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt s = c->slot[c->node_start + k];
    for (PetscInt p = 0; p < nr; ++p) wd[nr * k + p] = s < 0 ? 1.0 : c->cols[((size_t)s * nr + p) * c->nc_local + nr * k + p];
  }
  PetscCall(VecRestoreArray(MMCondensedData(ct)->Wdiag, &wd));
  PetscFunctionReturn(0);
}

/* The objects sized by the set, rebuilt whenever it changes. */
static PetscErrorCode DestroySetProblem(MMCandidates *c)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&c->W));
  PetscCall(VecDestroy(&c->x));
  PetscCall(VecDestroy(&c->lo));
  PetscCall(VecDestroy(&c->hi));
  PetscCall(VecDestroy(&c->q));
  PetscCall(VecDestroy(&c->f));
  PetscCall(VecScatterDestroy(&c->gather));
  PetscFunctionReturn(0);
}

/* The set's vectors, scatter and dense block W_SS: each rank contributes the rows it owns (the set
 * is sorted, so they are contiguous), every rank receives them all. W is symmetric; its two
 * triangles differ by the solves' round-off, so W_SS is their mean, and Cholesky applies. */
static PetscErrorCode BuildSetOperator(MMContact ct)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;
  MPI_Comm      comm = PetscObjectComm((PetscObject)ct->dm);
  const PetscInt nr = ct->ncomp;
  PetscMPIInt   size, *cnt, *dsp, mine;
  PetscInt      first = -1, nloc = 0, m;
  PetscScalar  *rows, *all, *w;
  IS            is;
  PetscInt     *idx;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_CandidateOperator, 0, 0, 0, 0));
  m = c->m = nr * c->n_set;
  PetscCall(DestroySetProblem(c));
  if (!m) {
    PetscCall(PetscLogEventEnd(MMCONTACT_CandidateOperator, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->n_set; ++i)
    if (NodeIsLocal(c, ct, c->set[i])) {
      if (first < 0) first = i;
      ++nloc;
    }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &cnt, size, &dsp));
  PetscCall(PetscMPIIntCast(nloc * nr * m, &mine));
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 1; r < size; ++r) dsp[r] = dsp[r - 1] + cnt[r - 1];
  PetscCall(PetscMalloc2((size_t)nloc * nr * m, &rows, (size_t)m * m, &all));
  for (PetscInt i = 0; i < nloc; ++i) {
    const PetscInt g = c->set[first + i], lr = nr * (g - c->node_start);
    for (PetscInt p = 0; p < nr; ++p)
      for (PetscInt j = 0; j < c->n_set; ++j)
        for (PetscInt q = 0; q < nr; ++q) rows[(size_t)(i * nr + p) * m + j * nr + q] = c->cols[((size_t)c->slot[c->set[j]] * nr + q) * c->nc_local + lr + p];
  }
  PetscCallMPI(MPI_Allgatherv(rows, mine, MPIU_SCALAR, all, cnt, dsp, MPIU_SCALAR, comm));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, m, m, NULL, &c->W));
  PetscCall(MatDenseGetArrayWrite(c->W, &w));
  for (PetscInt j = 0; j < m; ++j)
    for (PetscInt i = 0; i < m; ++i) w[i + (size_t)j * m] = 0.5 * (all[(size_t)i * m + j] + all[(size_t)j * m + i]);
  PetscCall(MatDenseRestoreArrayWrite(c->W, &w));
  PetscCall(MatAssemblyBegin(c->W, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(c->W, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(c->W, MAT_SPD, PETSC_TRUE));
  PetscCall(PetscFree2(rows, all));
  PetscCall(PetscFree2(cnt, dsp));

  PetscCall(MatCreateVecs(c->W, &c->x, &c->q));
  PetscCall(VecDuplicate(c->x, &c->lo));
  PetscCall(VecDuplicate(c->x, &c->hi));
  PetscCall(VecDuplicate(c->x, &c->f));
  PetscCall(PetscMalloc1(m, &idx));
  for (PetscInt i = 0; i < c->n_set; ++i)
    for (PetscInt p = 0; p < nr; ++p) idx[i * nr + p] = nr * c->set[i] + p;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, m, idx, PETSC_OWN_POINTER, &is));
  PetscCall(VecScatterCreate(ct->rho, is, c->x, NULL, &c->gather));
  PetscCall(ISDestroy(&is));
  c->qp.A      = c->W;
  c->qp.b      = c->q;
  c->qp.rtol_b = ct->tol;
  /* a new solver for the new size: SNESReset leaves the semismooth method's work vectors behind */
  PetscCall(SNESDestroy(&c->snes));
  PetscCall(MMQPCreate(PETSC_COMM_SELF, "contact_", &c->qp, nr > 1 ? ct->pb.mu_max : 0, &c->snes));
  PetscCall(SNESVISetVariableBounds(c->snes, c->lo, c->hi));
  PetscCall(PetscLogEventEnd(MMCONTACT_CandidateOperator, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Adds the listed nodes (owned here, increasing) of every rank to the set; returns how many. */
static PetscErrorCode AddToSet(MMContact ct, PetscInt nmine, const PetscInt mine[], PetscInt *added)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;
  MPI_Comm      comm = PetscObjectComm((PetscObject)ct->dm);
  PetscMPIInt   size, n, *cnt, *dsp;
  PetscInt     *news, total = 0, k = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &cnt, size, &dsp));
  PetscCall(PetscMPIIntCast(nmine, &n));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; ++r) {
    if (r) dsp[r] = dsp[r - 1] + cnt[r - 1];
    total += cnt[r];
  }
  PetscCall(PetscMalloc1(total + 1, &news));
  PetscCallMPI(MPI_Allgatherv(mine, n, MPIU_INT, news, cnt, dsp, MPIU_INT, comm));
  for (PetscInt i = 0; i < total; ++i) c->in_set[news[i]] = PETSC_TRUE;
  /* the set in increasing order, so that each rank's rows of W_SS are contiguous */
  for (PetscInt g = 0; g < ct->n_global; ++g)
    if (c->in_set[g]) c->set[k++] = g;
  c->n_set   = k;
  c->max_set = PetscMax(c->max_set, k);
  *added     = total;
  PetscCall(PetscFree(news));
  PetscCall(PetscFree2(cnt, dsp));
  PetscFunctionReturn(0);
}

static PetscErrorCode CompleteSet(MMContact ct)
{
  PetscFunctionBeginUser;
  PetscCall(ComputeMissingColumns(ct));
  PetscCall(UpdateCompliances(ct));
  PetscCall(BuildSetOperator(ct));
  PetscFunctionReturn(0);
}

/* The step's set, from q = z_c - offset (q_n = z_n - g: the contact-free predicted penetration):
 * the nodes predicted within margin * (deepest predicted penetration) of the obstacle, and those
 * carrying a reaction in the last solve. The reactions' displacement is largest at the nodes they
 * push and decays away from them (over about c_p dt), so a node farther out than the deepest
 * penetration they undo is not reached; rotations and bulging that do reach one are caught by
 * MMCandidatesGrow. */
PetscErrorCode MMCandidatesSelect(MMContact ct)
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
  const PetscInt     nr = ct->ncomp;
  const PetscScalar *qa, *ra, *q2 = NULL, *r2 = NULL;
  PetscReal          deepest = 0;
  PetscInt          *mine, n = 0, added;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n_set; ++i) c->in_set[c->set[i]] = PETSC_FALSE;
  c->n_set = 0;
  PetscCall(VecGetArrayRead(MMCondensedData(ct)->q, &qa));
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  /* a friction corner's second obstacle (zero elsewhere) can bring it into the set too */
  if (ct->fc_q) PetscCall(VecGetArrayRead(ct->fc_q, &q2));
  if (ct->fc_x) PetscCall(VecGetArrayRead(ct->fc_x, &r2));
  for (PetscInt k = 0; k < ct->n_local; ++k) deepest = PetscMax(deepest, PetscMax(PetscRealPart(qa[nr * k]), q2 ? PetscRealPart(q2[nr * k]) : 0.0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &deepest, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)ct->dm)));
  PetscCall(PetscMalloc1(ct->n_local, &mine));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscBool second = (PetscBool)(q2 && ct->fc_obstacle[k] >= 0 && (PetscRealPart(q2[nr * k]) >= -c->margin * deepest || PetscRealPart(r2[nr * k]) > 0));
    if (c->all || second || PetscRealPart(qa[nr * k]) >= -c->margin * deepest || PetscRealPart(ra[nr * k]) > 0) mine[n++] = c->node_start + k;
  }
  if (r2) PetscCall(VecRestoreArrayRead(ct->fc_x, &r2));
  if (q2) PetscCall(VecRestoreArrayRead(ct->fc_q, &q2));
  PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  PetscCall(VecRestoreArrayRead(MMCondensedData(ct)->q, &qa));
  PetscCall(AddToSet(ct, n, mine, &added));
  PetscCall(PetscFree(mine));
  PetscCall(CompleteSet(ct));
  PetscFunctionReturn(0);
}

/* After the set's VI: the nodes outside the set that its reactions push into the obstacle (beyond
 * 1e-10 h_c', the diagnostics' own "on the obstacle") join the set, and *grown says the VI must be
 * solved again. wc: the solution on the owned condensed dofs, exact on every contact node. */
PetscErrorCode MMCandidatesGrow(MMContact ct, const PetscScalar wc[], PetscBool *grown)
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
  const PetscScalar *ga;
  PetscInt          *mine, n = 0, added;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(PetscMalloc1(ct->n_local, &mine));
  for (PetscInt k = 0; k < ct->n_local; ++k)
    if (!c->in_set[c->node_start + k] && (PetscRealPart(wc[ct->ncomp * k] - ga[k]) > 1e-10 * ct->h_c || MMContactCornerCrosses(ct, ct->ncomp, k, wc, 1e-10 * ct->h_c))) mine[n++] = c->node_start + k;
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(AddToSet(ct, n, mine, &added));
  PetscCall(PetscFree(mine));
  *grown = (PetscBool)(added > 0);
  if (!*grown) PetscFunctionReturn(0);
  PetscCall(PetscInfo(NULL, "Candidate set grew by %" PetscInt_FMT " nodes to %" PetscInt_FMT ": the VI is solved again\n", added, c->n_set));
  ++c->resolves;
  PetscCall(CompleteSet(ct));
  PetscFunctionReturn(0);
}

/* y = W_{.,S} x on the owned condensed rows: the displacement of every contact dof owned here
 * under the set's reactions x (frame components). */
PetscErrorCode MMCandidatesMult(MMContact ct, Vec x, PetscScalar y[])
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
  const PetscInt     nr = ct->ncomp;
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(y, c->nc_local));
  if (!c->m) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt j = 0; j < c->n_set; ++j)
    for (PetscInt q = 0; q < nr; ++q) {
      const PetscScalar  xj  = xa[j * nr + q];
      const PetscScalar *col = c->cols + ((size_t)c->slot[c->set[j]] * nr + q) * c->nc_local;
      if (xj == 0) continue;
      for (PetscInt r = 0; r < c->nc_local; ++r) y[r] += col[r] * xj;
    }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(0);
}

/* w = z - K~^{-1} E_S x from the full columns: the step's solution without a solve. */
PetscErrorCode MMCandidatesRecover(MMContact ct, Vec w)
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
  const PetscInt     nr = ct->ncomp;
  const PetscScalar *xa;
  PetscScalar       *wa;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(ct->z, w));
  if (!c->m) PetscFunctionReturn(0);
  PetscCall(VecGetArray(w, &wa));
  PetscCall(VecGetArrayRead(c->x, &xa));
  {
    /* the columns of nonzero reactions, eight to a pass over w: the product is bound by the bytes it
     * moves, and w is read and written once per pass instead of once per column (the figures:
     * docs/scaling.md, "The figures behind the code's choices"). Each entry still subtracts the
     * columns one after the other, in the set's order: the same rounding. */
    const PetscScalar *col[8];
    PetscScalar        xs[8];
    PetscInt           k = 0;
    for (PetscInt j = 0; j <= c->n_set * nr; ++j) {
      if (j < c->n_set * nr && xa[j] != 0) {
        col[k]  = c->full + ((size_t)c->slot[c->set[j / nr]] * nr + j % nr) * c->n_local;
        xs[k++] = xa[j];
      }
      if (k == 8 || (j == c->n_set * nr && k)) {
        if (k == 8)
          for (PetscInt r = 0; r < c->n_local; ++r) {
            PetscScalar v = (((wa[r] - col[0][r] * xs[0]) - col[1][r] * xs[1]) - col[2][r] * xs[2]) - col[3][r] * xs[3];
            wa[r]         = (((v - col[4][r] * xs[4]) - col[5][r] * xs[5]) - col[6][r] * xs[6]) - col[7][r] * xs[7];
          }
        else
          for (PetscInt i = 0; i < k; ++i)
            for (PetscInt r = 0; r < c->n_local; ++r) wa[r] -= col[i][r] * xs[i];
        k = 0;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(c->x, &xa));
  PetscCall(VecRestoreArray(w, &wa));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCandidatesDestroy(MMCandidates *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(c->node_counts, c->node_displs));
  PetscCall(PetscFree4(c->normal_dof, c->slot, c->in_set, c->set));
  PetscCall(PetscFree(c->slot_node));
  PetscCall(PetscFree(c->cols));
  PetscCall(PetscFree(c->full));
  PetscCall(PetscFree(c->wc));
  PetscCall(PetscFree(c->cond_row));
  PetscCall(DestroySetProblem(c));
  PetscCall(SNESDestroy(&c->snes));
  PetscCall(MMMumpsColumnsDestroy(&c->mumps));
  PetscFunctionReturn(0);
}
