/* The condensed formulation: K~ factored once per dt, the Delassus operator on the contact dofs, and
 * the step's contact VI on the reactions (docs/method.md section 3). */
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "../../contactimpl.h"

/* The condensed dofs are the normal dof of each contact node and, with friction, its tangential
 * dofs. With z = K~^{-1} b and the Delassus operator W = E^T K~^{-1} E on them, the step solution
 * is w = z - K~^{-1} E rho for contact reactions rho = (lambda_n, -t): lambda_n >= 0 the normal
 * reaction, t the tangential force on the body. The step problem is the box-constrained VI
 *   W rho - q  complementary to  lambda_n >= 0,  |rho_t| <= s,
 * with q_n = z_n - g (the gap left) and q_t = z_t - (u_t^n + dt/2 v_t^n), which makes the
 * tangential residual -dt/2 times the slip velocity: Tresca friction with thresholds s, exactly.
 * K~ is factored once per dt; a step costs two solves with that factor and a VI on the candidate
 * set's dofs (candidates.c), whatever the size of the contact boundary. */

PetscErrorCode MMCondensedFactor(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (!ct->z) PetscCall(MatCreateVecs(ct->qp.A, &ct->z, &ct->rhs_c));
  if (!ct->ksp_K) { /* the first, or a second one for the kept factor */
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
    /* tangential: relative to the obstacle's own velocity (slide_ref, interface/set.c) */
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

/* The set's VI: W_SS x - q complementary to the box bounds of x (frictionless: rho_t in [0, 0]). */
static PetscErrorCode SolveSetVI(MMCtx *ctx)
{
  MMContact    *ct = &ctx->contact;
  MMCandidates *c  = &ct->cand;

  PetscFunctionBeginUser;
  PetscCall(GatherToSet(c, ct->q, c->q));
  PetscCall(GatherToSet(c, ct->rho, c->x));
  PetscCall(GatherToSet(c, ct->rho_lo, c->lo));
  PetscCall(GatherToSet(c, ct->rho_hi, c->hi));
  /* a warm start must lie in the box of the current thresholds */
  PetscCall(VecPointwiseMax(c->x, c->x, c->lo));
  PetscCall(VecPointwiseMin(c->x, c->x, c->hi));
  PetscCall(MMQPSolve(c->snes, &c->qp, c->x, &ct->vi_its));
  PetscCall(SnapActiveToBounds(c));
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

/* z = K~^{-1} b, once per step: the friction solvers solve one step's problem many times. When z
 * is new, so are q and the candidate set (they depend on z, u^n and v^n only). */
static PetscErrorCode PrepareStep(MMCtx *ctx, Vec b)
{
  MMContact       *ct = &ctx->contact;
  PetscObjectState state;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)b, &state));
  if (b == ct->z_b && state == ct->z_b_state && ct->z_dt == ct->Kt_dt) PetscFunctionReturn(0);
  PetscCall(KSPSolve(ct->ksp_K, b, ct->z));
  ct->z_b       = b;
  ct->z_b_state = state;
  ct->z_dt      = ct->Kt_dt;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(CondensedRHS(ctx));
  PetscCall(MMContactCornersRHS(ctx, ct->cand.cond_row));
  PetscCall(MMCandidatesSelect(ctx));
  PetscFunctionReturn(0);
}

/* The set grows, and its problem is solved again, until no node outside it penetrates: then its
 * reactions are the full-set ones (docs/method.md section 3, "Candidate set"). solve() leaves the
 * set's reactions in c->x; *ok false stops the loop (a solver that did not converge). */
static PetscErrorCode SolveGrowingSet(MMCtx *ctx, PetscErrorCode (*solve)(MMCtx *, void *, PetscBool *), void *sctx, PetscBool *ok)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  for (PetscBool grown = PETSC_TRUE; grown;) {
    if (ct->cand.m) {
      PetscCall(solve(ctx, sctx, ok));
      PetscCall(VecZeroEntries(ct->rho));
      PetscCall(VecScatterBegin(ct->cand.gather, ct->cand.x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
      PetscCall(VecScatterEnd(ct->cand.gather, ct->cand.x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
    } else PetscCall(VecZeroEntries(ct->rho));
    if (!*ok) PetscFunctionReturn(0);
    PetscCall(ContactDofValues(ctx));
    PetscCall(MMCandidatesGrow(ctx, ct->cand.wc, &grown));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveSetBox(MMCtx *ctx, void *unused, PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(SolveSetVI(ctx));
  *ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The step's contact reactions rho with the box bounds of rho_lo/rho_hi (frictionless, or 2D
 * Tresca thresholds): z = K~^{-1} b once per step, then the VI on the candidate set. No full-size
 * solve. */
PetscErrorCode MMCondensedSolveReactions(MMCtx *ctx, Vec b)
{
  MMContact *ct = &ctx->contact;
  PetscBool  ok;

  PetscFunctionBeginUser;
  PetscCall(PrepareStep(ctx, b));
  ct->vi_its = 0;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(SolveGrowingSet(ctx, SolveSetBox, NULL, &ok));
  PetscFunctionReturn(0);
}

typedef struct {
  MMContactSetSolver fn;
  void              *fctx;
} CoulombSetCtx;

/* The set's problem with the friction corners' second nodes (docs/method.md section 12): extended,
 * solved by the friction solver, and contracted back to the nodes' reactions x; their r_2 into
 * ct->fc_x. */
static PetscErrorCode SolveSetCoulombCorners(MMCtx *ctx, const MMContactSetProblem *p, PetscScalar x[], CoulombSetCtx *cc, PetscBool *ok)
{
  MMContact          *ct = &ctx->contact;
  MMCandidates       *c  = &ct->cand;
  Vec                 sv[4], from[4] = {ct->fc_geom, ct->fc_mu, ct->fc_q, ct->fc_x};
  const PetscScalar  *geom, *mu2, *q2;
  PetscScalar        *x2, *We, *qe, *xe;
  PetscReal          *mue;
  PetscInt            ne, *of;
  MMContactSetProblem pe = *p;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4; ++i) {
    PetscCall(VecDuplicate(c->q, &sv[i]));
    PetscCall(GatherToSet(c, from[i], sv[i]));
  }
  PetscCall(VecGetArrayRead(sv[0], &geom));
  PetscCall(VecGetArrayRead(sv[1], &mu2));
  PetscCall(VecGetArrayRead(sv[2], &q2));
  PetscCall(VecGetArray(sv[3], &x2));
  PetscCall(MMContactCornersExpand(p->n, p->nc, p->W, p->q, p->mu, x, geom, mu2, q2, x2, &ne, &of, &We, &qe, &mue, &xe));
  pe.n         = ne;
  pe.W         = We;
  pe.q         = qe;
  pe.mu        = mue;
  pe.redundant = (PetscBool)(ne > p->n);
  PetscCall(cc->fn(cc->fctx, &pe, xe, ok));
  PetscCall(MMContactCornersContract(p->n, p->nc, ne, of, geom, xe, x, x2));
  PetscCall(PetscFree4(We, qe, mue, xe));
  PetscCall(PetscFree(of));
  PetscCall(VecRestoreArray(sv[3], &x2));
  PetscCall(VecRestoreArrayRead(sv[2], &q2));
  PetscCall(VecRestoreArrayRead(sv[1], &mu2));
  PetscCall(VecRestoreArrayRead(sv[0], &geom));
  PetscCall(VecZeroEntries(ct->fc_x));
  PetscCall(VecScatterBegin(c->gather, sv[3], ct->fc_x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->gather, sv[3], ct->fc_x, INSERT_VALUES, SCATTER_REVERSE));
  for (PetscInt i = 0; i < 4; ++i) PetscCall(VecDestroy(&sv[i]));
  PetscFunctionReturn(0);
}

/* The set's Coulomb problem handed to a friction solver: W_SS, q_S, mu per set node, and the warm
 * start (the last reactions) in c->x, all in the nodes' frames. */
static PetscErrorCode SolveSetCoulomb(MMCtx *ctx, void *sctx, PetscBool *ok)
{
  MMContact          *ct = &ctx->contact;
  MMCandidates       *c  = &ct->cand;
  CoulombSetCtx      *cc = (CoulombSetCtx *)sctx;
  MMContactSetProblem p;
  const PetscScalar  *w, *q, *mua;
  PetscScalar        *x;
  PetscReal          *mu;

  PetscFunctionBeginUser;
  if (!ct->mu_c) {
    PetscCall(VecDuplicate(ct->rho, &ct->mu_c));
    for (PetscInt d = 0; d < ct->ncomp; ++d) PetscCall(VecStrideScatter(ct->mu, d, ct->mu_c, INSERT_VALUES));
  }
  PetscCall(GatherToSet(c, ct->q, c->q));
  PetscCall(GatherToSet(c, ct->rho, c->x));
  PetscCall(GatherToSet(c, ct->mu_c, c->lo));
  PetscCall(PetscMalloc1(c->n_set, &mu));
  PetscCall(VecGetArrayRead(c->lo, &mua));
  for (PetscInt i = 0; i < c->n_set; ++i) mu[i] = PetscRealPart(mua[i * ct->ncomp]);
  PetscCall(VecRestoreArrayRead(c->lo, &mua));
  PetscCall(MatDenseGetArrayRead(c->W, &w));
  PetscCall(VecGetArrayRead(c->q, &q));
  PetscCall(VecGetArray(c->x, &x));
  p.n         = c->n_set;
  p.nc        = ct->ncomp;
  p.W         = w;
  p.q         = q;
  p.mu        = mu;
  p.redundant = PETSC_FALSE;
  if (ct->n_fc) PetscCall(SolveSetCoulombCorners(ctx, &p, x, cc, ok));
  else PetscCall(cc->fn(cc->fctx, &p, x, ok));
  PetscCall(VecRestoreArray(c->x, &x));
  PetscCall(VecRestoreArrayRead(c->q, &q));
  PetscCall(MatDenseRestoreArrayRead(c->W, &w));
  PetscCall(PetscFree(mu));
  PetscFunctionReturn(0);
}

/* The thresholds mu r_n of the solution as the reactions' bounds, and each node's state (slipping:
 * on the rim of its disk), so that the diagnostics read a Coulomb solution as they read a Tresca
 * one. */
static PetscErrorCode StoreCoulombBounds(MMCtx *ctx)
{
  MMContact         *ct = &ctx->contact;
  const PetscInt     nr = ct->ncomp;
  const PetscScalar *ra, *mua;
  PetscScalar       *lo, *hi;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  PetscCall(VecGetArrayRead(ct->mu, &mua));
  PetscCall(VecGetArray(ct->rho_lo, &lo));
  PetscCall(VecGetArray(ct->rho_hi, &hi));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    PetscReal r1[MM_MAX_DIM], r2[MM_MAX_DIM], s, rt = 0;
    /* a friction corner's own obstacle's reaction, without the second's (corners.c) */
    MMContactCornerSplit(ct, nr, k, &ra[nr * k], r1, r2);
    s = PetscRealPart(mua[k]) * PetscMax(r1[0], 0.0);
    for (PetscInt d = 1; d < nr; ++d) {
      lo[nr * k + d] = -s;
      hi[nr * k + d] = s;
      rt += PetscSqr(r1[d]);
    }
    ct->slipping[k] = (PetscBool)(s > 0 && PetscSqrtReal(rt) >= s * (1 - 1e-6));
  }
  PetscCall(VecRestoreArray(ct->rho_hi, &hi));
  PetscCall(VecRestoreArray(ct->rho_lo, &lo));
  PetscCall(VecRestoreArrayRead(ct->mu, &mua));
  PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  PetscFunctionReturn(0);
}

/* The step's Coulomb problem in contact space, solved on the candidate set by fn (a friction
 * solver): rho, and the contact dofs of w and react, exactly; MMContactRecover completes w. */
PetscErrorCode MMCondensedSolveCoulomb(MMCtx *ctx, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok)
{
  MMContact    *ct = &ctx->contact;
  CoulombSetCtx cc = {fn, fctx};

  PetscFunctionBeginUser;
  PetscCall(PrepareStep(ctx, b));
  ct->vi_its = 0;
  PetscCall(SolveGrowingSet(ctx, SolveSetCoulomb, &cc, ok));
  if (!*ok) PetscFunctionReturn(0);
  if (!ct->cand.m && ct->fc_x) PetscCall(VecZeroEntries(ct->fc_x)); /* no set, no second obstacle's reaction */
  PetscCall(MMContactCornersStore(ctx));
  PetscCall(StoreCoulombBounds(ctx));
  PetscCall(MMCondensedContactDofs(ctx, w, react));
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


/* ---- The formulation's ops ---- */

/* K~ for a new dt: its factor, and on the first one the VI solver on the reactions. */
static PetscErrorCode CondensedSetOperator(MMCtx *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedFactor(ctx));
  if (!ctx->contact.rho) PetscCall(MMCondensedCreateSolver(ctx));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSolve(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedSolveReactions(ctx, b));
  PetscCall(MMCondensedRecover(ctx, w));
  PetscCall(MMContactForce(ctx, b, w, react));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSolveContactDofs(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedSolveReactions(ctx, b));
  PetscCall(MMCondensedContactDofs(ctx, w, react));
  PetscFunctionReturn(0);
}

/* One full-size solve completes w once the friction loop has converged on the contact dofs. */
static PetscErrorCode CondensedRecoverAll(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedRecover(ctx, w));
  PetscCall(MMContactForce(ctx, b, w, react));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedGetStepKSP(MMCtx *ctx, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  *krylov = *pc_ksp = ctx->contact.ksp_K;
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSummary(MMCtx *ctx)
{
  const MMCandidates *c = &ctx->contact.cand;

  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  contact candidate set: largest %" PetscInt_FMT " of %" PetscInt_FMT " contact nodes; %" PetscInt_FMT " columns of K~^{-1} E computed; %" PetscInt_FMT " VI re-solves after the set grew\n", c->max_set, ctx->contact.n_global, c->columns, c->resolves));
  if (c->evicted || c->recover_solves)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  contact candidate cache at -contact_candidate_memory %g MiB: %" PetscInt_FMT " cached nodes dropped and their columns recomputed when needed; %" PetscInt_FMT " steps recovered by a solve, the whole columns being over the cap\n", (double)ctx->opt.candidate_memory, c->evicted, c->recover_solves));
  PetscFunctionReturn(0);
}

/* K~, its factor and its cached columns swapped with the kept ones (those of the previous dt): a
 * step that goes back to that dt, after a rejection, needs no factorization. */
static PetscErrorCode CondensedSwapKept(MMCtx *ctx, PetscReal dt, PetscBool *hit)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(MMContactSwapKeptOperator(ct, &ct->ksp_K));
  PetscCall(MMCandidatesSwapCache(ct, &ct->kept.cache));
  *hit = (PetscBool)(ct->qp.A && ct->Kt_dt == dt);
  PetscFunctionReturn(0);
}

static const MMContactOps CondensedOps = {
  .setoperator      = CondensedSetOperator,
  .solve            = CondensedSolve,
  .solvecontactdofs = CondensedSolveContactDofs,
  .recover          = CondensedRecoverAll,
  .solvecoulomb     = MMCondensedSolveCoulomb,
  .getstepksp       = CondensedGetStepKSP,
  .summary          = CondensedSummary,
  .swapkept         = CondensedSwapKept,
};

PetscErrorCode MMContactCreate_Condensed(MMContact *ct)
{
  PetscFunctionBeginUser;
  ct->ops = &CondensedOps;
  PetscFunctionReturn(0);
}
