/* PC "schursplit": an exact solve of the SPD K~ on several ranks, split at the ranks' interface
 * (docs/scaling.md, "A 2D solve split between the ranks"). The default for K~ in 2D on several ranks.
 *
 * Rows are split by the parallel layout: the interface Gamma holds each rank's rows that couple to
 * a lower rank, the rest is each rank's interior I_r. Interiors of different ranks never couple
 * (a row coupling to a higher rank's row makes that row interface), so K~ = [A 0 ... B; ... ;
 * B^T ... K_GG] with A = blockdiag(A_r). Each rank factors its A_r = P^T G G^T P (PETSc's
 * Cholesky, nested dissection; G = U^T D^(1/2)) and keeps W_r = G^{-1} P K~(I_r, Gamma), sparse (the
 * nonzeros of a forward solve from a sparse column are its ancestors in the elimination tree).
 * The interface's Schur complement S = K_GG - sum_r W_r^T W_r is dense, small (a line of nodes in
 * 2D), summed over the ranks and factored on each. A solve is exact:
 *   z_r = G^{-1} P b_r;  S x_G = b_G - sum_r W_r^T z_r;  x_r = P^T G^{-T} (z_r - W_r x_G),
 * one forward sweep, one MPI_Allreduce of |Gamma| numbers and one backward sweep, ours
 * (BackwardSweep, faster than PETSc 3.18's MatBackwardSolve). So each rank sweeps its half-size
 * factor once each way, where PCREDUNDANT's whole factor costs each rank a full solve of twice the
 * size. Where the factor's layout is not the one the sweep expects, x_r = A_r^{-1} (b_r -
 * K~(I_r, Gamma) x_G) by the factor's MatSolve. The set-up pays one forward sweep per interface
 * column for W_r. The timings: docs/scaling.md, "The figures behind the code's choices". */
#include <petsc/private/pcimpl.h>
#include "../contactimpl.h"

typedef struct {
  PetscInt  nI, ng, ns, gstart; /* interior rows here; interface rows here; in all; our first in the interface numbering */
  PetscInt *iloc, *gloc;        /* local row numbers of the interior and interface rows here */
  Mat       A, F;               /* the interior block and its Cholesky factor */
  Mat       Wt;                 /* W_r^T: ns x nI, sparse */
  Mat       B;                  /* K~(I_r, Gamma): nI x ns, kept only for the MatSolve fallback */
  Mat       S;                  /* the interface's Schur complement, factored, on every rank */
  Vec       bI, z, v, xI, g, xg;
  PetscInt  nnzW;               /* nonzeros of W_r, for the view */
  /* The factor's backward sweep, our own (BackwardSweep): its arrays, borrowed from F */
  PetscBool          fast;      /* checked against MatBackwardSolve at set-up; else a full local solve */
  IS                 rperm;     /* the factor's ordering P */
  const PetscInt    *fi, *fj, *rp;
  PetscScalar       *fa;
  PetscReal         *sqd;       /* per row, the square root of the factor's 1/D */
  PetscScalar       *t;
} PC_SchurSplit;

/* The factor's arrays the backward sweep reads, given back; the ordering too unless keep_ordering
 * (a refactorization of the same pattern reuses it, PCSetUp_SchurSplit) */
static PetscErrorCode ReleaseFactorArrays(PC_SchurSplit *sp, PetscBool keep_ordering)
{
  PetscInt  n;
  PetscBool done;

  PetscFunctionBegin;
  if (sp->fa) PetscCall(MatSeqSBAIJRestoreArray(sp->F, &sp->fa));
  if (sp->fi) PetscCall(MatRestoreRowIJ(sp->F, 0, PETSC_FALSE, PETSC_FALSE, &n, &sp->fi, &sp->fj, &done));
  if (sp->rp) PetscCall(ISRestoreIndices(sp->rperm, &sp->rp));
  if (!keep_ordering) PetscCall(ISDestroy(&sp->rperm));
  PetscCall(PetscFree2(sp->sqd, sp->t));
  sp->fa   = NULL;
  sp->fi   = sp->fj = sp->rp = NULL;
  sp->fast = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* What depends on the operator's values: all but the interior block A, its factor F and ordering,
 * which a new operator of the same nonzero pattern refactors in place (keep) */
static PetscErrorCode ResetSplit(PC pc, PetscBool keep)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;

  PetscFunctionBegin;
  PetscCall(ReleaseFactorArrays(sp, keep));
  PetscCall(PetscFree2(sp->iloc, sp->gloc));
  if (!keep) {
    PetscCall(MatDestroy(&sp->A));
    PetscCall(MatDestroy(&sp->F));
  }
  PetscCall(MatDestroy(&sp->Wt));
  PetscCall(MatDestroy(&sp->B));
  PetscCall(MatDestroy(&sp->S));
  PetscCall(VecDestroy(&sp->bI));
  PetscCall(VecDestroy(&sp->z));
  PetscCall(VecDestroy(&sp->v));
  PetscCall(VecDestroy(&sp->xI));
  PetscCall(VecDestroy(&sp->g));
  PetscCall(VecDestroy(&sp->xg));
  sp->nI = sp->ng = sp->ns = sp->gstart = sp->nnzW = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCReset_SchurSplit(PC pc)
{
  PetscFunctionBegin;
  PetscCall(ResetSplit(pc, PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCDestroy_SchurSplit(PC pc)
{
  PetscFunctionBegin;
  PetscCall(PCReset_SchurSplit(pc));
  PetscCall(PetscFree(pc->data));
  PetscFunctionReturn(0);
}

/* Interface rows: those coupling to a lower rank's (a ghost column below rstart); the global list of
 * all of them, sorted, on every rank. */
static PetscErrorCode SplitRows(PC pc, Mat Ad, Mat Ao, const PetscInt colmap[], PetscInt rstart, PetscInt **gam_all, PetscInt **gpos)
{
  PC_SchurSplit  *sp   = (PC_SchurSplit *)pc->data;
  MPI_Comm        comm = PetscObjectComm((PetscObject)pc);
  PetscInt        n, *mine;
  PetscMPIInt     size, *counts, *displs, ngm;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(Ad, &n, NULL));
  PetscCall(PetscMalloc2(n, &sp->iloc, n, &sp->gloc));
  PetscCall(PetscMalloc1(n, gpos));
  sp->nI = sp->ng = 0;
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt        nc;
    const PetscInt *cols;
    PetscBool       lower = PETSC_FALSE;
    if (Ao) {
      PetscCall(MatGetRow(Ao, i, &nc, &cols, NULL));
      for (PetscInt k = 0; k < nc && !lower; ++k) lower = (PetscBool)(colmap[cols[k]] < rstart);
      PetscCall(MatRestoreRow(Ao, i, &nc, &cols, NULL));
    }
    (*gpos)[i] = lower ? sp->ng : -1;
    if (lower) sp->gloc[sp->ng++] = i;
    else sp->iloc[sp->nI++] = i;
  }
  PetscCallMPI(MPI_Scan(&sp->ng, &sp->gstart, 1, MPIU_INT, MPI_SUM, comm));
  sp->gstart -= sp->ng;
  PetscCall(MPIU_Allreduce(&sp->ng, &sp->ns, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(sp->ns, gam_all));
  PetscCall(PetscMalloc3(size, &counts, size, &displs, PetscMax(sp->ng, 1), &mine));
  for (PetscInt k = 0; k < sp->ng; ++k) mine[k] = rstart + sp->gloc[k];
  PetscCall(PetscMPIIntCast(sp->ng, &ngm));
  PetscCallMPI(MPI_Allgather(&ngm, 1, MPI_INT, counts, 1, MPI_INT, comm));
  displs[0] = 0;
  for (PetscMPIInt q = 1; q < size; ++q) displs[q] = displs[q - 1] + counts[q - 1];
  PetscCallMPI(MPI_Allgatherv(mine, ngm, MPIU_INT, *gam_all, counts, displs, MPIU_INT, comm));
  PetscCall(PetscFree3(counts, displs, mine));
  PetscFunctionReturn(0);
}

/* K~'s local rows as the split reads them: the diagonal and off-diagonal blocks, the ghost columns'
 * global numbers, the global interface rows (sorted, all ranks) and each local row's interface
 * position here (or -1). */
typedef struct {
  Mat             Ad, Ao;
  const PetscInt *colmap, *gam_all, *gpos;
} LocalRows;

/* The entries of local row i in interface columns: their interface numbers j[] and values v[] (at
 * most ns). An interior row must couple to no other rank's interior row: the matrix's structure
 * would not be symmetric. */
static PetscErrorCode InterfaceEntries(const PC_SchurSplit *sp, const LocalRows *lr, PetscInt i, PetscBool interior, PetscInt *n, PetscInt j[], PetscScalar v[])
{
  PetscInt           nc, g;
  const PetscInt    *cols;
  const PetscScalar *vals;

  PetscFunctionBegin;
  *n = 0;
  PetscCall(MatGetRow(lr->Ad, i, &nc, &cols, &vals));
  for (PetscInt k = 0; k < nc; ++k)
    if (lr->gpos[cols[k]] >= 0) {
      j[*n]     = sp->gstart + lr->gpos[cols[k]];
      v[(*n)++] = vals[k];
    }
  PetscCall(MatRestoreRow(lr->Ad, i, &nc, &cols, &vals));
  if (!lr->Ao) PetscFunctionReturn(0);
  PetscCall(MatGetRow(lr->Ao, i, &nc, &cols, &vals));
  for (PetscInt k = 0; k < nc; ++k) {
    PetscCall(PetscFindInt(lr->colmap[cols[k]], sp->ns, lr->gam_all, &g));
    PetscCheck(g >= 0 || !interior, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "-pc_type schursplit: row %" PetscInt_FMT " couples to row %" PetscInt_FMT " of another rank's interior: the matrix's structure is not symmetric", i, lr->colmap[cols[k]]);
    if (g < 0) continue;
    j[*n]     = g;
    v[(*n)++] = vals[k];
  }
  PetscCall(MatRestoreRow(lr->Ao, i, &nc, &cols, &vals));
  PetscFunctionReturn(0);
}

/* B = K~(I_r, Gamma), nI x ns. */
static PetscErrorCode BuildInteriorInterface(PC pc, const LocalRows *lr, Mat *B)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;
  PetscInt      *nnz, *j, n;
  PetscScalar   *v;

  PetscFunctionBegin;
  PetscCall(PetscMalloc3(sp->nI + 1, &nnz, sp->ns + 1, &j, sp->ns + 1, &v));
  for (PetscInt ii = 0; ii < sp->nI; ++ii) PetscCall(InterfaceEntries(sp, lr, sp->iloc[ii], PETSC_TRUE, &nnz[ii], j, v));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, sp->nI, sp->ns, 0, nnz, B));
  PetscCall(MatSetOption(*B, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (PetscInt ii = 0; ii < sp->nI; ++ii) {
    PetscCall(InterfaceEntries(sp, lr, sp->iloc[ii], PETSC_TRUE, &n, j, v));
    PetscCall(MatSetValues(*B, 1, &ii, n, j, v, INSERT_VALUES));
  }
  PetscCall(PetscFree3(nnz, j, v));
  PetscCall(MatAssemblyBegin(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The interior block's Cholesky factor; a failure is the PC's (PCGetFailedReason), as PCCHOLESKY's.
 * reuse: a new operator of the same nonzero pattern (the finite-strain tangent rebuilt,
 * src/ts/nonlinear.c): the block's values taken again into A and refactored in F, with the ordering
 * and the symbolic factorization of the first set-up; the same operations on the same pattern, so
 * the factor is the one a set-up from scratch would give, bit for bit. */
static PetscErrorCode FactorInterior(PC pc, Mat Ad, PetscBool reuse)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;
  IS             is, rperm, cperm;
  MatFactorInfo  info;
  MatFactorError err;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, sp->nI, sp->iloc, PETSC_USE_POINTER, &is));
  PetscCall(MatCreateSubMatrix(Ad, is, is, reuse ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &sp->A));
  PetscCall(ISDestroy(&is));
  PetscCall(MatFactorInfoInitialize(&info));
  if (!reuse) {
    PetscCall(MatGetFactor(sp->A, MATSOLVERPETSC, MAT_FACTOR_CHOLESKY, &sp->F));
    PetscCall(MatGetOrdering(sp->A, MATORDERINGND, &rperm, &cperm));
    PetscCall(MatCholeskyFactorSymbolic(sp->F, sp->A, rperm, &info));
    sp->rperm = rperm;
    PetscCall(ISDestroy(&cperm));
  }
  PetscCall(MatCholeskyFactorNumeric(sp->F, sp->A, &info));
  PetscCall(MatFactorGetError(sp->F, &err));
  if (err) pc->failedreason = (PCFailedReason)err;
  PetscFunctionReturn(0);
}

/* x = P^T G^{-T} b, the factor's backward sweep, as MatBackwardSolve computes it (PETSc's non-in-place
 * Cholesky layout: row k of U holds its off-diagonal entries, negated, then 1/D(k)), but with each
 * row's dot product read downwards, as the rows are, in four partial sums. PETSc 3.18's version
 * reads each row upwards while the rows go down, nearly three times the forward sweep's time
 * (docs/scaling.md, "The figures behind the code's choices"). The sum's order differs: round-off only. */
static PetscErrorCode BackwardSweep(PC_SchurSplit *sp, Vec b, Vec x)
{
  const PetscScalar *ba;
  PetscScalar       *xa, *t = sp->t;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayWrite(x, &xa));
  for (PetscInt k = sp->nI - 1; k >= 0; --k) {
    const PetscInt     beg = sp->fi[k];
    const PetscInt    *j   = sp->fj;
    const PetscScalar *a   = sp->fa;
    PetscScalar        s0 = ba[k] * sp->sqd[k], s1 = 0, s2 = 0, s3 = 0;
    PetscInt           p  = sp->fi[k + 1] - 2;

    for (; p - 3 >= beg; p -= 4) { /* downwards, as the rows go: one descending stream */
      s0 += a[p] * t[j[p]];
      s1 += a[p - 1] * t[j[p - 1]];
      s2 += a[p - 2] * t[j[p - 2]];
      s3 += a[p - 3] * t[j[p - 3]];
    }
    for (; p >= beg; --p) s0 += a[p] * t[j[p]];
    t[k]          = (s0 + s1) + (s2 + s3);
    xa[sp->rp[k]] = t[k];
  }
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(PetscLogFlops(2.0 * (sp->fi[sp->nI] - sp->nI)));
  PetscFunctionReturn(0);
}

/* Borrows the factor's arrays for BackwardSweep and checks it against MatBackwardSolve on one
 * vector; if the layout is not the one expected (another PETSc), the apply keeps a full local solve. */
static PetscErrorCode SetUpBackwardSweep(PC_SchurSplit *sp)
{
  PetscBool sbaij, done = PETSC_FALSE;
  PetscInt  n;
  Vec       y, x1, x2;
  PetscReal err, scale;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)sp->F, MATSEQSBAIJ, &sbaij));
  if (!sbaij || !sp->nI) PetscFunctionReturn(0);
  PetscCall(MatGetRowIJ(sp->F, 0, PETSC_FALSE, PETSC_FALSE, &n, &sp->fi, &sp->fj, &done));
  if (!done || n != sp->nI) {
    if (done) PetscCall(MatRestoreRowIJ(sp->F, 0, PETSC_FALSE, PETSC_FALSE, &n, &sp->fi, &sp->fj, &done));
    sp->fi = sp->fj = NULL;
    PetscFunctionReturn(0);
  }
  PetscCall(MatSeqSBAIJGetArray(sp->F, &sp->fa));
  PetscCall(ISGetIndices(sp->rperm, &sp->rp));
  PetscCall(PetscMalloc2(sp->nI, &sp->sqd, sp->nI, &sp->t));
  for (PetscInt k = 0; k < sp->nI; ++k) sp->sqd[k] = PetscSqrtReal(PetscMax(PetscRealPart(sp->fa[sp->fi[k + 1] - 1]), 0));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sp->nI, &y));
  PetscCall(VecDuplicate(y, &x1));
  PetscCall(VecDuplicate(y, &x2));
  {
    PetscScalar *ya;
    PetscCall(VecGetArrayWrite(y, &ya));
    for (PetscInt k = 0; k < sp->nI; ++k) ya[k] = PetscSinReal((PetscReal)(k + 1));
    PetscCall(VecRestoreArrayWrite(y, &ya));
  }
  {
    /* PETSc's Cholesky factors an indefinite matrix without complaint (its pivots need only be
     * nonzero), and its backward solve, which takes their square roots, is where a negative pivot
     * shows: K~ = K_t + 4/dt^2 M* is then not positive definite, which the finite-strain tangent
     * can make it (docs/reference.md, "Large rotations and finite strain"). Said in one line,
     * where PETSc's trace would name the square root (issue 48, item 6). */
    PetscErrorCode ierr;

    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = MatBackwardSolve(sp->F, y, x1);
    PetscCall(PetscPopErrorHandler());
    PetscCheck(ierr != PETSC_ERR_SUP, PETSC_COMM_SELF, MM_ERR_PHYSICS, "The step matrix K~ = K + 4/dt^2 M* is not positive definite: its Cholesky factor has a negative pivot. The finite-strain tangent K loses its definiteness under strong compression, or under contact pressure with a nearly incompressible -nu (lambda/mu large); lower -ts_dt (the mass term 4/dt^2 M* restores it) or -nu. The output up to the previous step is intact");
    PetscCall(ierr);
  }
  PetscCall(BackwardSweep(sp, y, x2));
  PetscCall(VecNorm(x1, NORM_INFINITY, &scale));
  PetscCall(VecAXPY(x2, -1.0, x1));
  PetscCall(VecNorm(x2, NORM_INFINITY, &err));
  sp->fast = (PetscBool)(err <= 1e-12 * scale);
  if (!sp->fast) PetscCall(PetscInfo(NULL, "schursplit: the factor's layout is not the one expected (backward sweep off by %g of %g): a full local solve instead\n", (double)err, (double)scale));
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&x1));
  PetscCall(VecDestroy(&x2));
  PetscFunctionReturn(0);
}

/* The forward sweep G^{-1} P b of a sparse b (nc entries at interior rows cols[], values vals[]),
 * as MatForwardSolve computes it (row k of the factor scatters x_k to its columns, then
 * x_k *= sqrt(1/D(k))), but only over the rows b reaches: the seeds' descendants in the factor's
 * graph (every edge goes from a row to a later one, so the reach in ascending order is an order of
 * the sweep). An interface column couples to a few interior rows next to the interface, and their
 * reach is a small part of the factor: the dense sweep per column was most of the 2D split's
 * set-up on 2 ranks. The same operations in the same order: the same values. x (zero on entry, zero
 * again on return) and the marks are work arrays of nI; the reach goes to reach[], its values to
 * w[] (in the factor's order), *n of them. */
static PetscErrorCode SparseForwardSweep(PC_SchurSplit *sp, PetscInt nc, const PetscInt cols[], const PetscScalar vals[], const PetscInt ip[], PetscScalar x[], PetscBool mark[], PetscInt stack[], PetscInt reach[], PetscScalar w[], PetscInt *n)
{
  PetscInt nr = 0;

  PetscFunctionBegin;
  for (PetscInt c = 0; c < nc; ++c) {
    const PetscInt seed = ip[cols[c]];
    PetscInt       top  = 0;
    x[seed] += vals[c];
    if (mark[seed]) continue;
    mark[seed]   = PETSC_TRUE;
    stack[top++] = seed;
    while (top) {
      const PetscInt k = stack[--top];
      reach[nr++]      = k;
      for (PetscInt p = sp->fi[k]; p < sp->fi[k + 1] - 1; ++p) {
        const PetscInt j = sp->fj[p];
        if (mark[j]) continue;
        mark[j]      = PETSC_TRUE;
        stack[top++] = j;
      }
    }
  }
  PetscCall(PetscSortInt(nr, reach));
  for (PetscInt r = 0; r < nr; ++r) {
    const PetscInt    k = reach[r], end = sp->fi[k + 1] - 1;
    const PetscScalar xk = x[k];
    for (PetscInt p = sp->fi[k]; p < end; ++p) x[sp->fj[p]] += sp->fa[p] * xk;
    x[k] = xk * sp->sqd[k];
  }
  for (PetscInt r = 0; r < nr; ++r) {
    w[r]            = x[reach[r]];
    x[reach[r]]     = 0;
    mark[reach[r]]  = PETSC_FALSE;
  }
  *n = nr;
  PetscFunctionReturn(0);
}

/* W_r^T, row j = G^{-1} P B(:, j), by one forward sweep per interface column that touches this
 * interior (sparse, SparseForwardSweep, when the factor's layout is the one checked; else PETSc's
 * dense MatForwardSolve); only its nonzeros are kept. */
static PetscErrorCode BuildW(PC pc, Mat B)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;
  Mat            Bt;
  Vec            bj = NULL, w = NULL;
  PetscInt      *ia, *ja, cap = 4 * sp->nI + 4, nnz = 0, *ip = NULL, *stack = NULL, *reach = NULL;
  PetscScalar   *a, *x = NULL, *wr = NULL;
  PetscBool     *mark = NULL;

  PetscFunctionBegin;
  PetscCall(MatTranspose(B, MAT_INITIAL_MATRIX, &Bt));
  if (sp->fast) {
    PetscCall(PetscMalloc3(sp->nI, &ip, sp->nI, &stack, sp->nI, &reach));
    PetscCall(PetscCalloc3(sp->nI, &x, sp->nI, &mark, sp->nI, &wr));
    for (PetscInt k = 0; k < sp->nI; ++k) ip[sp->rp[k]] = k;
  } else {
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, sp->nI, &bj));
    PetscCall(VecDuplicate(bj, &w));
  }
  PetscCall(PetscMalloc1(sp->ns + 1, &ia));
  PetscCall(PetscMalloc1(cap, &ja));
  PetscCall(PetscMalloc1(cap, &a));
  ia[0] = 0;
  for (PetscInt j = 0; j < sp->ns; ++j) {
    PetscInt           nc, nr = 0;
    const PetscInt    *cols, *ri = reach;
    const PetscScalar *vals, *wa = wr;
    PetscScalar       *ba;

    PetscCall(MatGetRow(Bt, j, &nc, &cols, &vals));
    if (nc && sp->fast) PetscCall(SparseForwardSweep(sp, nc, cols, vals, ip, x, mark, stack, reach, wr, &nr));
    else if (nc) {
      PetscCall(VecGetArray(bj, &ba));
      for (PetscInt k = 0; k < nc; ++k) ba[cols[k]] = vals[k];
      PetscCall(VecRestoreArray(bj, &ba));
      PetscCall(MatForwardSolve(sp->F, bj, w));
      PetscCall(VecGetArray(bj, &ba));
      for (PetscInt k = 0; k < nc; ++k) ba[cols[k]] = 0;
      PetscCall(VecRestoreArray(bj, &ba));
      PetscCall(VecGetArrayRead(w, &wa));
      nr = sp->nI;
      ri = NULL;
    }
    for (PetscInt r = 0; r < nr; ++r) {
      if (wa[r] == 0) continue;
      if (nnz == cap) {
        cap *= 2;
        PetscCall(PetscRealloc(cap * sizeof(PetscInt), &ja));
        PetscCall(PetscRealloc(cap * sizeof(PetscScalar), &a));
      }
      ja[nnz]  = ri ? ri[r] : r;
      a[nnz++] = wa[r];
    }
    if (nc && !sp->fast) PetscCall(VecRestoreArrayRead(w, &wa));
    PetscCall(MatRestoreRow(Bt, j, &nc, &cols, &vals));
    ia[j + 1] = nnz;
  }
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, sp->ns, sp->nI, 0, NULL, &sp->Wt));
  PetscCall(MatSeqAIJSetPreallocationCSR(sp->Wt, ia, ja, a));
  sp->nnzW = nnz;
  PetscCall(PetscFree(ia));
  PetscCall(PetscFree(ja));
  PetscCall(PetscFree(a));
  PetscCall(PetscFree3(ip, stack, reach));
  PetscCall(PetscFree3(x, mark, wr));
  PetscCall(VecDestroy(&bj));
  PetscCall(VecDestroy(&w));
  PetscCall(MatDestroy(&Bt));
  PetscFunctionReturn(0);
}

/* s -= W_r^T W_r, into the dense S (column-major, ns x ns): row by row of W_r (an interior row's
 * few interface couplings), each pair once and mirrored. PETSc's sparse MatMatTransposeMult built
 * a sparse matrix that is all but dense, half of the split's set-up (docs/scaling.md, "The figures behind the code's choices"). */
static PetscErrorCode SubtractWtW(PC_SchurSplit *sp, PetscScalar s[])
{
  Mat                W;
  const PetscInt    *wi, *wj;
  const PetscScalar *wa;
  PetscInt           n;
  PetscBool          done;
  PetscLogDouble     flops = 0;

  PetscFunctionBegin;
  PetscCall(MatTranspose(sp->Wt, MAT_INITIAL_MATRIX, &W));
  PetscCall(MatGetRowIJ(W, 0, PETSC_FALSE, PETSC_FALSE, &n, &wi, &wj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "schursplit: no row structure of W");
  PetscCall(MatSeqAIJGetArrayRead(W, &wa));
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt p = wi[i]; p < wi[i + 1]; ++p) {
      const PetscInt    ca = wj[p];
      const PetscScalar va = wa[p];
      s[ca + ca * sp->ns] -= va * va;
      flops += 2.0 + 3.0 * (wi[i + 1] - p - 1);
      for (PetscInt q = p + 1; q < wi[i + 1]; ++q) {
        const PetscScalar d = va * wa[q];
        s[ca + wj[q] * sp->ns] -= d;
        s[wj[q] + ca * sp->ns] -= d;
      }
    }
  PetscCall(PetscLogFlops(flops));
  PetscCall(MatSeqAIJRestoreArrayRead(W, &wa));
  PetscCall(MatRestoreRowIJ(W, 0, PETSC_FALSE, PETSC_FALSE, &n, &wi, &wj, &done));
  PetscCall(MatDestroy(&W));
  PetscFunctionReturn(0);
}

/* S = K_GG - sum_r W_r^T W_r, dense, summed over the ranks and Cholesky-factored on each. */
static PetscErrorCode BuildSchur(PC pc, const LocalRows *lr)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;
  PetscScalar   *s, *v;
  PetscInt      *j, n;
  PetscMPIInt    count;

  PetscFunctionBegin;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, sp->ns, sp->ns, NULL, &sp->S));
  PetscCall(MatDenseGetArray(sp->S, &s));
  PetscCall(PetscMalloc2(sp->ns + 1, &j, sp->ns + 1, &v));
  for (PetscInt k = 0; k < sp->ng; ++k) {
    PetscCall(InterfaceEntries(sp, lr, sp->gloc[k], PETSC_FALSE, &n, j, v));
    for (PetscInt c = 0; c < n; ++c) s[sp->gstart + k + j[c] * sp->ns] += v[c];
  }
  PetscCall(PetscFree2(j, v));
  PetscCall(SubtractWtW(sp, s));
  PetscCall(PetscMPIIntCast(sp->ns * sp->ns, &count));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, count, MPIU_SCALAR, MPIU_SUM, PetscObjectComm((PetscObject)pc)));
  PetscCall(MatDenseRestoreArray(sp->S, &s));
  if (sp->ns) PetscCall(MatCholeskyFactor(sp->S, NULL, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetUp_SchurSplit(PC pc)
{
  PC_SchurSplit  *sp = (PC_SchurSplit *)pc->data;
  LocalRows       lr;
  PetscInt        rstart, *gam_all, *gpos;
  PetscBool       reuse;

  PetscFunctionBegin;
  /* the same pattern as the last set-up, which succeeded: its split, ordering and symbolic factor hold */
  reuse = (PetscBool)(pc->setupcalled && pc->flag == SAME_NONZERO_PATTERN && sp->F && sp->A && sp->rperm && !pc->failedreason);
  PetscCall(ResetSplit(pc, reuse));
  PetscCall(MMKtGetLocalBlocks(pc->pmat, "-pc_type schursplit", &lr.Ad, &lr.Ao, &lr.colmap));
  PetscCall(MatGetOwnershipRange(pc->pmat, &rstart, NULL));
  PetscCall(SplitRows(pc, lr.Ad, lr.Ao, lr.colmap, rstart, &gam_all, &gpos));
  lr.gam_all = gam_all;
  lr.gpos    = gpos;
  PetscCall(FactorInterior(pc, lr.Ad, reuse));
  {
    PetscInt failed = (PetscInt)pc->failedreason; /* every rank stops building, or none */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &failed, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)pc)));
    if (failed && !pc->failedreason) pc->failedreason = PC_SUBPC_ERROR;
  }
  if (!pc->failedreason) {
    PetscCall(SetUpBackwardSweep(sp));
    PetscCall(BuildInteriorInterface(pc, &lr, &sp->B));
    PetscCall(BuildW(pc, sp->B));
    if (sp->fast) PetscCall(MatDestroy(&sp->B)); /* only the MatSolve fallback needs it */
    PetscCall(BuildSchur(pc, &lr));
  }
  PetscCall(PetscFree(gam_all));
  PetscCall(PetscFree(gpos));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sp->nI, &sp->bI));
  PetscCall(VecDuplicate(sp->bI, &sp->z));
  PetscCall(VecDuplicate(sp->bI, &sp->v));
  PetscCall(VecDuplicate(sp->bI, &sp->xI));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sp->ns, &sp->g));
  PetscCall(VecDuplicate(sp->g, &sp->xg));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApply_SchurSplit(PC pc, Vec b, Vec x)
{
  PC_SchurSplit     *sp = (PC_SchurSplit *)pc->data;
  const PetscScalar *ba, *xia, *xga;
  PetscScalar       *bia, *ra, *xa;
  PetscMPIInt        count;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayWrite(sp->bI, &bia));
  for (PetscInt i = 0; i < sp->nI; ++i) bia[i] = ba[sp->iloc[i]];
  PetscCall(VecRestoreArrayWrite(sp->bI, &bia));
  PetscCall(MatForwardSolve(sp->F, sp->bI, sp->z));
  if (sp->ns) {
    PetscCall(PetscLogEventBegin(MMCONTACT_SplitInterface, pc, 0, 0, 0));
    PetscCall(MatMult(sp->Wt, sp->z, sp->g));
    PetscCall(VecGetArray(sp->g, &ra));
    for (PetscInt i = 0; i < sp->ns; ++i) ra[i] = -ra[i];
    for (PetscInt k = 0; k < sp->ng; ++k) ra[sp->gstart + k] += ba[sp->gloc[k]];
    PetscCall(PetscMPIIntCast(sp->ns, &count));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ra, count, MPIU_SCALAR, MPIU_SUM, PetscObjectComm((PetscObject)pc)));
    PetscCall(VecRestoreArray(sp->g, &ra));
    PetscCall(MatSolve(sp->S, sp->g, sp->xg));
    PetscCall(PetscLogEventEnd(MMCONTACT_SplitInterface, pc, 0, 0, 0));
    if (sp->fast) {
      PetscCall(PetscLogEventBegin(MMCONTACT_SplitBackward, pc, 0, 0, 0));
      PetscCall(MatMultTranspose(sp->Wt, sp->xg, sp->v));
      PetscCall(VecAYPX(sp->v, -1.0, sp->z));
      PetscCall(BackwardSweep(sp, sp->v, sp->xI));
      PetscCall(PetscLogEventEnd(MMCONTACT_SplitBackward, pc, 0, 0, 0));
    } else {
      PetscCall(MatMult(sp->B, sp->xg, sp->v));
      PetscCall(VecAYPX(sp->v, -1.0, sp->bI));
      PetscCall(MatSolve(sp->F, sp->v, sp->xI));
    }
  } else if (sp->fast) {
    PetscCall(PetscLogEventBegin(MMCONTACT_SplitBackward, pc, 0, 0, 0));
    PetscCall(BackwardSweep(sp, sp->z, sp->xI));
    PetscCall(PetscLogEventEnd(MMCONTACT_SplitBackward, pc, 0, 0, 0));
  }
  else PetscCall(MatBackwardSolve(sp->F, sp->z, sp->xI));
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(VecGetArrayWrite(x, &xa));
  PetscCall(VecGetArrayRead(sp->xI, &xia));
  for (PetscInt i = 0; i < sp->nI; ++i) xa[sp->iloc[i]] = xia[i];
  PetscCall(VecRestoreArrayRead(sp->xI, &xia));
  if (sp->ns) {
    PetscCall(VecGetArrayRead(sp->xg, &xga));
    for (PetscInt k = 0; k < sp->ng; ++k) xa[sp->gloc[k]] = xga[sp->gstart + k];
    PetscCall(VecRestoreArrayRead(sp->xg, &xga));
  }
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCView_SchurSplit(PC pc, PetscViewer viewer)
{
  PC_SchurSplit *sp = (PC_SchurSplit *)pc->data;
  PetscBool      ascii;
  PetscInt       n[3] = {sp->nI, 0, sp->nnzW};
  PetscBool      fast = sp->fast;
  MatInfo        info;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  if (sp->F) {
    PetscCall(MatGetInfo(sp->F, MAT_LOCAL, &info));
    n[1] = (PetscInt)info.nz_used;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, n, 3, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)pc)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  split at the ranks' interface: %" PetscInt_FMT " interface rows (dense Schur complement on every rank); largest interior %" PetscInt_FMT " rows, its Cholesky factor (PETSc, nested dissection) %" PetscInt_FMT " nonzeros; largest W %" PetscInt_FMT " nonzeros\n", sp->ns, n[0], n[1], n[2]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fast, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)pc)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  interior solve: %s\n", fast ? "forward sweep, then mmcontact's backward sweep (checked against MatBackwardSolve at set-up)" : "forward sweep, then the factor's full MatSolve (its layout is not the one expected)"));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCCreate_SchurSplit(PC pc)
{
  PC_SchurSplit *sp;

  PetscFunctionBegin;
  PetscCall(PetscNew(&sp));
  pc->data         = (void *)sp;
  pc->ops->setup   = PCSetUp_SchurSplit;
  pc->ops->apply   = PCApply_SchurSplit;
  pc->ops->applytranspose = PCApply_SchurSplit; /* K~ is symmetric */
  pc->ops->reset   = PCReset_SchurSplit;
  pc->ops->destroy = PCDestroy_SchurSplit;
  pc->ops->view    = PCView_SchurSplit;
  PetscFunctionReturn(0);
}

/*@
  MMPCRegisterSchurSplit - Registers the PC type schursplit (MMPCSCHURSPLIT), once

  Not collective

  Level: developer

.seealso: `MMPCRegisterVIFactor()`
@*/
PetscErrorCode MMPCRegisterSchurSplit(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBegin;
  if (done) PetscFunctionReturn(0);
  PetscCall(PCRegister(MMPCSCHURSPLIT, PCCreate_SchurSplit));
  done = PETSC_TRUE;
  PetscFunctionReturn(0);
}
