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
 * K~ is factored once per dt; a step costs two solves with that factor and a VI on the candidate
 * set's dofs (contact_candidates.c), whatever the size of the contact boundary. */

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
  PetscCall(MMKSPCheckFactored(ct->ksp_K));
  if (ct->enabled) PetscCall(MMCandidatesInvalidate(ct));
  PetscFunctionReturn(0);
}

/* The reactions rho and their bounds, one block of ncomp per contact node: the layout the friction
 * loop and the diagnostics read, whatever the formulation. Frictionless until thresholds are set:
 * rho_t in [0, 0]. */
PetscErrorCode MMContactCreateReactions(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)ctx->op.dm), ct->ncomp * ct->n_local, PETSC_DETERMINE, &ct->rho));
  PetscCall(VecSetBlockSize(ct->rho, ct->ncomp));
  PetscCall(VecZeroEntries(ct->rho));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_lo));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_hi));
  PetscCall(VecSet(ct->rho_lo, 0.0));
  PetscCall(VecSet(ct->rho_hi, 0.0));
  PetscCall(VecStrideSet(ct->rho_hi, 0, PETSC_INFINITY));
  PetscFunctionReturn(0);
}

/* The condensed right-hand side on all contact nodes (global, ncomp per node), and the candidate
 * set that carries the VI. */
PetscErrorCode MMCondensedCreateSolver(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(MMContactCreateReactions(ctx));
  PetscCall(VecDuplicate(ct->rho, &ct->offset));
  PetscCall(VecDuplicate(ct->rho, &ct->q));
  PetscCall(VecDuplicate(ct->rho, &ct->Wdiag));
  PetscCall(VecSet(ct->Wdiag, 1.0));
  if (ct->ncomp == 3) PetscCall(VecDuplicate(ct->rho, &ct->rot));
  PetscCall(MMCandidatesSetUp(ctx));
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
  MMContact         *ct = &ctx->contact;
  const PetscInt    *row = ct->cand.cond_row, nr = ct->ncomp;
  const PetscScalar *za, *ua, *va, *ga;
  PetscScalar       *oa, *qa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ct->z, &za));
  PetscCall(VecGetArrayRead(ctx->state.u_old, &ua));
  PetscCall(VecGetArrayRead(ctx->state.v_old, &va));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(VecGetArray(ct->offset, &oa));
  PetscCall(VecGetArray(ct->q, &qa));
  for (PetscInt r = 0; r < ct->cand.nc_local; ++r) {
    /* tangential: relative to the obstacle's own velocity (slide_ref, contact_set.c) */
    oa[r] = r % nr ? ua[row[r]] + 0.5 * ct->Kt_dt * va[row[r]] + ct->slide_ref[(r / nr) * (nr - 1) + r % nr - 1] : ga[r / nr];
    qa[r] = za[row[r]] - oa[r];
  }
  PetscCall(VecRestoreArray(ct->q, &qa));
  PetscCall(VecRestoreArray(ct->offset, &oa));
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(ctx->state.v_old, &va));
  PetscCall(VecRestoreArrayRead(ctx->state.u_old, &ua));
  PetscCall(VecRestoreArrayRead(ct->z, &za));
  PetscFunctionReturn(0);
}

/* RSLS holds a variable as active when it is within 1e-8 (absolute) of a bound with F pushing
 * outward, but leaves it where it is. Reactions can be far smaller than 1 (F1's are 1e-4), so put
 * those variables on their bounds exactly: the same active set, now satisfied to round-off. */
static PetscErrorCode SnapActiveToBounds(MMCandidates *c)
{
  const PetscScalar *lo, *hi, *f;
  PetscScalar       *x;

  PetscFunctionBeginUser;
  PetscCall(MatMult(c->qp.A, c->x, c->f));
  PetscCall(VecAXPY(c->f, -1.0, c->q));
  PetscCall(VecGetArray(c->x, &x));
  PetscCall(VecGetArrayRead(c->lo, &lo));
  PetscCall(VecGetArrayRead(c->hi, &hi));
  PetscCall(VecGetArrayRead(c->f, &f));
  for (PetscInt i = 0; i < c->m; ++i) {
    if (PetscRealPart(x[i]) <= PetscRealPart(lo[i]) + 1e-8 && PetscRealPart(f[i]) > 0) x[i] = lo[i];
    if (PetscRealPart(x[i]) >= PetscRealPart(hi[i]) - 1e-8 && PetscRealPart(f[i]) < 0) x[i] = hi[i];
  }
  PetscCall(VecRestoreArrayRead(c->f, &f));
  PetscCall(VecRestoreArrayRead(c->hi, &hi));
  PetscCall(VecRestoreArrayRead(c->lo, &lo));
  PetscCall(VecRestoreArray(c->x, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode GatherToSet(MMCandidates *c, Vec from, Vec to)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(c->gather, from, to, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->gather, from, to, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

/* The set's VI: W_SS x - q complementary to the bounds of x; in 3D in each node's (n, d, d_perp)
 * basis, rotated blockwise (contact_slip.c). rho: x on the set, zero elsewhere. */
static PetscErrorCode SolveSetVI(MMCtx *ctx)
{
  MMContact    *ct = &ctx->contact;
  MMCandidates *c  = &ct->cand;

  PetscFunctionBeginUser;
  PetscCall(GatherToSet(c, ct->q, c->q));
  PetscCall(GatherToSet(c, ct->rho, c->x));
  PetscCall(GatherToSet(c, ct->rho_lo, c->lo));
  PetscCall(GatherToSet(c, ct->rho_hi, c->hi));
  if (ct->ncomp == 3) {
    PetscCall(GatherToSet(c, ct->rot, c->rot));
    PetscCall(MMSlipRotateSet(c));
  }
  /* a warm start must lie in the box of the current thresholds */
  PetscCall(VecPointwiseMax(c->x, c->x, c->lo));
  PetscCall(VecPointwiseMin(c->x, c->x, c->hi));
  PetscCall(MMQPSolve(c->snes, &c->qp, c->x, &ct->vi_its));
  PetscCall(SnapActiveToBounds(c));
  if (ct->ncomp == 3) PetscCall(MMSlipRotateBack(c, c->x));
  PetscCall(VecZeroEntries(ct->rho));
  PetscCall(VecScatterBegin(c->gather, c->x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->gather, c->x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* w_c = z_c - W_{.,S} rho_S on every owned contact dof: exact everywhere, the set's columns
 * carrying the rows of the whole contact boundary. */
static PetscErrorCode ContactDofValues(MMCtx *ctx)
{
  MMContact         *ct = &ctx->contact;
  MMCandidates      *c  = &ct->cand;
  const PetscScalar *za;

  PetscFunctionBeginUser;
  PetscCall(MMCandidatesMult(ct, c->x, c->wc));
  PetscCall(VecGetArrayRead(ct->z, &za));
  for (PetscInt r = 0; r < c->nc_local; ++r) c->wc[r] = za[c->cond_row[r]] - c->wc[r];
  PetscCall(VecRestoreArrayRead(ct->z, &za));
  PetscFunctionReturn(0);
}

/* The step's contact reactions rho: z = K~^{-1} b (once per step), then the VI on the candidate
 * set, chosen when z is new. No full-size solve: the friction loop calls this once per iteration. */
PetscErrorCode MMCondensedSolveReactions(MMCtx *ctx, Vec b)
{
  MMContact *ct    = &ctx->contact;
  PetscBool  fresh = PETSC_FALSE;

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
      fresh         = PETSC_TRUE;
    }
  }
  ct->vi_its = 0;
  if (!ct->enabled) PetscFunctionReturn(0);
  /* q and the set depend on z, u^n and v^n only: once per step, not per friction iteration */
  if (fresh) {
    PetscCall(CondensedRHS(ctx));
    PetscCall(MMCandidatesSelect(ctx));
  }
  /* the set grows, and its VI is solved again, until no node outside it penetrates: then its
   * reactions are the full-set ones (docs/method.md section 3, "Candidate set") */
  for (PetscBool grown = PETSC_TRUE; grown;) {
    if (ct->cand.m) PetscCall(SolveSetVI(ctx));
    else PetscCall(VecZeroEntries(ct->rho));
    PetscCall(ContactDofValues(ctx));
    PetscCall(MMCandidatesGrow(ctx, ct->cand.wc, &grown));
  }
  PetscFunctionReturn(0);
}

/* The condensed dofs of the step's solution and of the contact force, exactly, from rho alone:
 * w_c = z_c - W rho and f_c = -rho (K~ w - b = -E rho). What the friction loop needs. */
PetscErrorCode MMCondensedContactDofs(MMCtx *ctx, Vec w, Vec react)
{
  MMContact         *ct = &ctx->contact;
  const PetscInt    *row = ct->cand.cond_row;
  const PetscScalar *ra;
  PetscScalar       *wa, *fa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(w, &wa));
  PetscCall(VecGetArray(react, &fa));
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  for (PetscInt r = 0; r < ct->cand.nc_local; ++r) {
    wa[row[r]] = ct->cand.wc[r];
    fa[row[r]] = -ra[r];
  }
  PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  PetscCall(VecRestoreArray(react, &fa));
  PetscCall(VecRestoreArray(w, &wa));
  PetscFunctionReturn(0);
}

/* The whole step solution from rho: w = z - K~^{-1} E rho, from the set's full columns while
 * they fit in the cache (a product with the few columns of nonzero reactions), else by one
 * full-size solve. */
PetscErrorCode MMCondensedRecover(MMCtx *ctx, Vec w)
{
  MMContact *ct = &ctx->contact;
  Vec        rc;

  PetscFunctionBeginUser;
  if (!ct->enabled) {
    PetscCall(VecCopy(ct->z, w));
    PetscFunctionReturn(0);
  }
  if (ct->cand.full_ok) {
    PetscCall(MMCandidatesRecover(ct, w));
    PetscFunctionReturn(0);
  }
  ct->cand.recover_solves++;
  PetscCall(VecZeroEntries(ct->rhs_c));
  PetscCall(VecGetSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(KSPSolve(ct->ksp_K, ct->rhs_c, w));
  PetscCall(VecAXPY(w, 1.0, ct->z));
  PetscFunctionReturn(0);
}

