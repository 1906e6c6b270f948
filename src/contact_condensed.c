/* The condensed formulation: K~ factored once per dt, the Delassus operator on the contact dofs, and
 * the step's contact VI on the reactions (docs/method.md section 3). */
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "contact_impl.h"

/* The condensed dofs are the normal dof of each contact node and, with friction, its tangential
 * dofs. With z = K~^{-1} b and the Delassus operator W = E^T K~^{-1} E on them, the step solution
 * is w = z - K~^{-1} E rho for contact reactions rho = (lambda_n, -t): lambda_n >= 0 the normal
 * reaction, t the tangential force on the body. The step problem is the box-constrained VI
 *   W rho - q  complementary to  lambda_n >= 0,  |rho_t| <= s,
 * with q_n = z_n - g (the gap left) and q_t = z_t - (u_t^n + dt/2 v_t^n), which makes the
 * tangential residual -dt/2 times the slip velocity: Tresca friction with thresholds s, exactly.
 * K~ is factored once per dt; a step costs two solves with that factor and a VI on the contact
 * dofs, whatever the contact set does. */

PetscErrorCode MMCondensedFactor(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (!ct->ksp_K) {
    PetscCall(MatCreateVecs(ct->qp.A, &ct->z, &ct->rhs_c));
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)ctx->op.dm), &ct->ksp_K));
    PetscCall(KSPSetOptionsPrefix(ct->ksp_K, "contact_K_"));
    PetscCall(MMKSPSetDirectSPD(ct->ksp_K, ctx->op.dim));
    PetscCall(KSPSetFromOptions(ct->ksp_K));
    /* now, not at the first solve: the Delassus operator is built from the factor before it */
    PetscCall(MMKSPCheckDirect(ct->ksp_K));
  }
  PetscCall(KSPSetOperators(ct->ksp_K, ct->qp.A, ct->qp.A));
  PetscCall(KSPSetUp(ct->ksp_K));
  PetscFunctionReturn(0);
}

/* Columns of K~^{-1} E, a block at a time through the factor, restricted to the condensed rows. */
PetscErrorCode MMCondensedAssembleDelassus(MMCtx *ctx)
{
  MMContact      *ct = &ctx->contact;
  MPI_Comm        comm = PetscObjectComm((PetscObject)ctx->op.dm);
  const PetscInt  nb_max = 64;
  PetscInt        n, rstart, cstart, lda, nc, N, *cols;
  const PetscInt *ic;
  PetscScalar    *vals;
  PC              pc;
  Mat             F;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ct->ksp_K, &pc));
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatGetLocalSize(ct->qp.A, &n, NULL));
  PetscCall(MatGetOwnershipRange(ct->qp.A, &rstart, NULL));
  PetscCall(ISGetLocalSize(ct->is_cond, &nc));
  PetscCall(ISGetSize(ct->is_cond, &N));
  PetscCall(MPI_Scan(&nc, &cstart, 1, MPIU_INT, MPI_SUM, comm));
  cstart -= nc;
  if (!ct->W) PetscCall(MatCreateAIJ(comm, nc, nc, N, N, nc, NULL, N - nc, NULL, &ct->W));
  PetscCall(MatZeroEntries(ct->W));
  PetscCall(ISGetIndices(ct->is_cond, &ic));
  PetscCall(PetscMalloc2(nb_max, &cols, nb_max, &vals));
  for (PetscInt j0 = 0; j0 < N; j0 += nb_max) {
    const PetscInt     nb = PetscMin(nb_max, N - j0);
    Mat                B, X;
    const PetscScalar *x;

    PetscCall(MatCreateDense(comm, n, PETSC_DECIDE, PETSC_DETERMINE, nb, NULL, &B));
    for (PetscInt k = 0; k < nc; ++k)
      if (cstart + k >= j0 && cstart + k < j0 + nb) PetscCall(MatSetValue(B, ic[k], cstart + k - j0, 1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatDuplicate(B, MAT_DO_NOT_COPY_VALUES, &X));
    PetscCall(MatMatSolve(F, B, X));
    PetscCall(MatDenseGetLDA(X, &lda));
    PetscCall(MatDenseGetArrayRead(X, &x));
    for (PetscInt j = 0; j < nb; ++j) cols[j] = j0 + j;
    for (PetscInt k = 0; k < nc; ++k) {
      const PetscInt row = cstart + k;
      for (PetscInt j = 0; j < nb; ++j) vals[j] = x[(ic[k] - rstart) + j * lda];
      PetscCall(MatSetValues(ct->W, 1, &row, nb, cols, vals, INSERT_VALUES));
    }
    PetscCall(MatDenseRestoreArrayRead(X, &x));
    PetscCall(MatDestroy(&X));
    PetscCall(MatDestroy(&B));
  }
  PetscCall(PetscFree2(cols, vals));
  PetscCall(ISRestoreIndices(ct->is_cond, &ic));
  PetscCall(MatAssemblyBegin(ct->W, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->W, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCondensedCreateSolver(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  ct->qpc.A      = ct->W;
  ct->qpc.rtol_b = ct->tol;
  PetscCall(MatCreateVecs(ct->W, &ct->rho, &ct->qpc.b));
  PetscCall(VecSetBlockSize(ct->rho, ct->ncomp));
  PetscCall(VecZeroEntries(ct->rho));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_lo));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_hi));
  PetscCall(VecDuplicate(ct->rho, &ct->offset));
  PetscCall(VecDuplicate(ct->rho, &ct->z_c));
  /* frictionless until thresholds are set: rho_t in [0, 0] */
  PetscCall(VecSet(ct->rho_lo, 0.0));
  PetscCall(VecSet(ct->rho_hi, 0.0));
  PetscCall(VecStrideSet(ct->rho_hi, 0, PETSC_INFINITY));
  PetscCall(MMQPCreate(PetscObjectComm((PetscObject)ctx->op.dm), "contact_", &ct->qpc, ct->ncomp > 1 ? ctx->opt.mu : 0, &ct->snes));
  PetscCall(SNESVISetVariableBounds(ct->snes, ct->rho_lo, ct->rho_hi));
  PetscFunctionReturn(0);
}

/* The normal reactions lambda_n of the last solve, one per contact node. */
PetscErrorCode MMContactGetNormalReactions(MMCtx *ctx, Vec lambda)
{
  PetscFunctionBeginUser;
  PetscCall(VecStrideGather(ctx->contact.rho, 0, lambda, INSERT_VALUES));
  PetscFunctionReturn(0);
}

/* q = z_c - offset: the gap on the normal dofs, u_t^n + dt/2 v_t^n on the tangential ones. */
static PetscErrorCode CondensedRHS(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;
  Vec        zc;

  PetscFunctionBeginUser;
  if (ct->ncomp > 1) {
    Vec ut, vt;
    PetscCall(VecGetSubVector(ctx->state.u_old, ct->is_cond, &ut));
    PetscCall(VecGetSubVector(ctx->state.v_old, ct->is_cond, &vt));
    PetscCall(VecWAXPY(ct->offset, 0.5 * ct->Kt_dt, vt, ut));
    PetscCall(VecRestoreSubVector(ctx->state.v_old, ct->is_cond, &vt));
    PetscCall(VecRestoreSubVector(ctx->state.u_old, ct->is_cond, &ut));
  }
  PetscCall(VecStrideScatter(ct->gap, 0, ct->offset, INSERT_VALUES));
  PetscCall(VecGetSubVector(ct->z, ct->is_cond, &zc));
  PetscCall(VecWAXPY(ct->qpc.b, -1.0, ct->offset, zc));
  PetscCall(VecRestoreSubVector(ct->z, ct->is_cond, &zc));
  PetscFunctionReturn(0);
}

/* RSLS holds a variable as active when it is within 1e-8 (absolute) of a bound with F pushing
 * outward, but leaves it where it is. Reactions can be far smaller than 1 (F1's are 1e-4), so put
 * those variables on their bounds exactly: the same active set, now satisfied to round-off. */
static PetscErrorCode SnapActiveToBounds(MMContact *ct, Mat A, Vec rho)
{
  const PetscScalar *lo, *hi, *f;
  PetscScalar       *x;
  PetscInt           n;
  Vec                F;

  PetscFunctionBeginUser;
  F = ct->z_c; /* scratch, free once the VI is solved */
  PetscCall(MatMult(A, rho, F));
  PetscCall(VecAXPY(F, -1.0, ct->qpc.b));
  PetscCall(VecGetLocalSize(rho, &n));
  PetscCall(VecGetArray(rho, &x));
  PetscCall(VecGetArrayRead(ct->rho_lo, &lo));
  PetscCall(VecGetArrayRead(ct->rho_hi, &hi));
  PetscCall(VecGetArrayRead(F, &f));
  for (PetscInt i = 0; i < n; ++i) {
    if (PetscRealPart(x[i]) <= PetscRealPart(lo[i]) + 1e-8 && PetscRealPart(f[i]) > 0) x[i] = lo[i];
    if (PetscRealPart(x[i]) >= PetscRealPart(hi[i]) - 1e-8 && PetscRealPart(f[i]) < 0) x[i] = hi[i];
  }
  PetscCall(VecRestoreArrayRead(F, &f));
  PetscCall(VecRestoreArrayRead(ct->rho_hi, &hi));
  PetscCall(VecRestoreArrayRead(ct->rho_lo, &lo));
  PetscCall(VecRestoreArray(rho, &x));
  PetscFunctionReturn(0);
}

/* The step's contact reactions rho: z = K~^{-1} b (once per step), then the VI on the condensed
 * dofs. No full-size solve: the friction loop calls this once per iteration. */
PetscErrorCode MMCondensedSolveReactions(MMCtx *ctx, Vec b)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  {
    PetscObjectState state;
    /* the friction loop solves one step's problem many times: z = K~^{-1} b is the same each time */
    PetscCall(PetscObjectStateGet((PetscObject)b, &state));
    if (b != ct->z_b || state != ct->z_b_state || ct->z_dt != ct->Kt_dt) {
      PetscCall(KSPSolve(ct->ksp_K, b, ct->z));
      ct->z_b       = b;
      ct->z_b_state = state;
      ct->z_dt      = ct->Kt_dt;
    }
  }
  ct->vi_its = 0;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(CondensedRHS(ctx));
  if (ct->ncomp == 3) {
    /* the VI in each node's (n, d, d_perp) basis: rho = P rho_r */
    if (!ct->rho_r) PetscCall(VecDuplicate(ct->rho, &ct->rho_r));
    PetscCall(VecCopy(ct->qpc.b, ct->z_c));
    PetscCall(MatMultTranspose(ct->P, ct->z_c, ct->qpc.b));
    PetscCall(MatMultTranspose(ct->P, ct->rho, ct->rho_r));
    ct->qpc.A = ct->Wr;
    PetscCall(MMQPSetOperator(ct->snes, &ct->qpc));
  }
  {
    Vec x = ct->ncomp == 3 ? ct->rho_r : ct->rho;
    /* a warm start must lie in the box of the current thresholds */
    PetscCall(VecPointwiseMax(x, x, ct->rho_lo));
    PetscCall(VecPointwiseMin(x, x, ct->rho_hi));
    PetscCall(MMQPSolve(ct->snes, &ct->qpc, x, &ct->vi_its));
    PetscCall(SnapActiveToBounds(ct, ct->qpc.A, x));
    if (ct->ncomp == 3) PetscCall(MatMult(ct->P, ct->rho_r, ct->rho));
  }
  PetscFunctionReturn(0);
}

/* The condensed dofs of the step's solution and of the contact force, exactly, from rho alone:
 * w_c = z_c - W rho and f_c = -rho (K~ w - b = -E rho). What the friction loop needs. */
PetscErrorCode MMCondensedContactDofs(MMCtx *ctx, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;
  Vec        wc, zc, rc;

  PetscFunctionBeginUser;
  PetscCall(MatMult(ct->W, ct->rho, ct->z_c)); /* z_c: scratch, free once the VI is solved */
  PetscCall(VecGetSubVector(w, ct->is_cond, &wc));
  PetscCall(VecGetSubVector(ct->z, ct->is_cond, &zc));
  PetscCall(VecWAXPY(wc, -1.0, ct->z_c, zc));
  PetscCall(VecRestoreSubVector(ct->z, ct->is_cond, &zc));
  PetscCall(VecRestoreSubVector(w, ct->is_cond, &wc));
  PetscCall(VecGetSubVector(react, ct->is_cond, &rc));
  PetscCall(VecAXPBY(rc, -1.0, 0.0, ct->rho));
  PetscCall(VecRestoreSubVector(react, ct->is_cond, &rc));
  PetscFunctionReturn(0);
}

/* The whole step solution from rho: w = z - K~^{-1} E rho, one full-size solve. */
PetscErrorCode MMCondensedRecover(MMCtx *ctx, Vec w)
{
  MMContact *ct = &ctx->contact;
  Vec        rc;

  PetscFunctionBeginUser;
  if (!ct->enabled) {
    PetscCall(VecCopy(ct->z, w));
    PetscFunctionReturn(0);
  }
  PetscCall(VecZeroEntries(ct->rhs_c));
  PetscCall(VecGetSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(KSPSolve(ct->ksp_K, ct->rhs_c, w));
  PetscCall(VecAXPY(w, 1.0, ct->z));
  PetscFunctionReturn(0);
}

