/* The condensed formulation: K~ factored once per dt, the Delassus operator on the contact dofs, and
 * the step's contact VI on the reactions (docs/method.md section 3). */
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "condensedimpl.h"
#include "../cost_constants.h"

/* The condensed dofs are the normal dof of each contact node and, with friction, its tangential
 * dofs. With z = K~^{-1} b and the Delassus operator W = E^T K~^{-1} E on them, the step solution
 * is w = z - K~^{-1} E rho for contact reactions rho = (lambda_n, -t): lambda_n >= 0 the normal
 * reaction, t the tangential force on the body. The step problem is the box-constrained VI
 *   W rho - q  complementary to  lambda_n >= 0,  |rho_t| <= s,
 * with q_n = z_n - g (the gap left) and q_t = z_t - (u_t^n + dt/2 v_t^n), the step's offset that
 * the stepper hands down (MMContactSetStepOffset), which makes the tangential residual -dt/2 times
 * the slip velocity: Tresca friction with thresholds s, exactly.
 * K~ is factored once per dt; a step costs two solves with that factor and a VI on the candidate
 * set's dofs (candidates.c), whatever the size of the contact boundary. */

PetscErrorCode MMCondensedFactor(MMContact ct)
{

  PetscFunctionBeginUser;
  if (!ct->z) PetscCall(MatCreateVecs(ct->qp.A, &ct->z, &MMCondensedData(ct)->rhs_c));
  if (!MMCondensedData(ct)->ksp_K) { /* the first, or a second one for the kept factor */
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)ct->dm), &MMCondensedData(ct)->ksp_K));
    PetscCall(KSPSetOptionsPrefix(MMCondensedData(ct)->ksp_K, "contact_K_"));
    PetscCall(MMKSPSetDirectSPD(MMCondensedData(ct)->ksp_K, ct->dim));
    PetscCall(KSPSetFromOptions(MMCondensedData(ct)->ksp_K));
    /* now, not at the first solve: the Delassus operator is built from the factor before it */
    PetscCall(MMKSPCheckDirect(MMCondensedData(ct)->ksp_K));
  }
  PetscCall(KSPSetOperators(MMCondensedData(ct)->ksp_K, ct->qp.A, ct->qp.A));
  PetscCall(KSPSetUp(MMCondensedData(ct)->ksp_K));
  PetscCall(MMKSPCheckFactored(MMCondensedData(ct)->ksp_K));
  if (ct->enabled) PetscCall(MMCandidatesInvalidate(ct));
  PetscFunctionReturn(0);
}

/* The condensed right-hand side on all contact nodes (global, ncomp per node), and the candidate
 * set that carries the VI. */
PetscErrorCode MMCondensedCreateSolver(MMContact ct)
{

  PetscFunctionBeginUser;
  PetscCall(MMContactCreateReactions(ct));
  PetscCall(VecDuplicate(ct->rho, &MMCondensedData(ct)->offset));
  PetscCall(VecDuplicate(ct->rho, &MMCondensedData(ct)->q));
  PetscCall(VecDuplicate(ct->rho, &MMCondensedData(ct)->Wdiag));
  PetscCall(VecSet(MMCondensedData(ct)->Wdiag, 1.0));
  PetscCall(MMCandidatesSetUp(ct));
  PetscFunctionReturn(0);
}

/* q = z_c - offset: the gap on the normal dofs, the step's offset u_t^n + dt/2 v_t^n (the stepper's,
 * MMContactSetStepOffset) on the tangential ones. */
static PetscErrorCode CondensedRHS(MMContact ct)
{
  const PetscInt    *row = MMCondensedData(ct)->cand.cond_row, nr = ct->ncomp;
  const PetscScalar *za, *sa, *ga;
  PetscScalar       *oa, *qa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ct->z, &za));
  PetscCall(VecGetArrayRead(ct->step.offset, &sa));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(VecGetArray(MMCondensedData(ct)->offset, &oa));
  PetscCall(VecGetArray(MMCondensedData(ct)->q, &qa));
  for (PetscInt r = 0; r < MMCondensedData(ct)->cand.nc_local; ++r) {
    /* tangential: relative to the obstacle's own velocity (slide_ref, interface/set.c) */
    oa[r] = r % nr ? sa[row[r]] + ct->slide_ref[(r / nr) * (nr - 1) + r % nr - 1] : ga[r / nr];
    qa[r] = za[row[r]] - oa[r];
  }
  PetscCall(VecRestoreArray(MMCondensedData(ct)->q, &qa));
  PetscCall(VecRestoreArray(MMCondensedData(ct)->offset, &oa));
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(ct->step.offset, &sa));
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
static PetscErrorCode SolveSetVI(MMContact ct)
{
  MMCandidates *c  = &MMCondensedData(ct)->cand;

  PetscFunctionBeginUser;
  PetscCall(GatherToSet(c, MMCondensedData(ct)->q, c->q));
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
static PetscErrorCode ContactDofValues(MMContact ct)
{
  MMCandidates      *c  = &MMCondensedData(ct)->cand;
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
static PetscErrorCode PrepareStep(MMContact ct, Vec b)
{
  PetscObjectState state;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)b, &state));
  if (b == MMCondensedData(ct)->z_b && state == MMCondensedData(ct)->z_b_state && MMCondensedData(ct)->z_dt == ct->Kt_dt) PetscFunctionReturn(0);
  PetscCall(KSPSolve(MMCondensedData(ct)->ksp_K, b, ct->z));
  MMCondensedData(ct)->z_b       = b;
  MMCondensedData(ct)->z_b_state = state;
  MMCondensedData(ct)->z_dt      = ct->Kt_dt;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(CondensedRHS(ct));
  PetscCall(MMContactCornersRHS(ct, MMCondensedData(ct)->cand.cond_row));
  PetscCall(MMCandidatesSelect(ct));
  PetscFunctionReturn(0);
}

/* The set grows, and its problem is solved again, until no node outside it penetrates: then its
 * reactions are the full-set ones (docs/method.md section 3, "Candidate set"). solve() leaves the
 * set's reactions in c->x; *ok false stops the loop (a solver that did not converge). */
static PetscErrorCode SolveGrowingSet(MMContact ct, PetscErrorCode (*solve)(MMContact, void *, PetscBool *), void *sctx, PetscBool *ok)
{

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  for (PetscBool grown = PETSC_TRUE; grown;) {
    if (MMCondensedData(ct)->cand.m) {
      PetscCall(solve(ct, sctx, ok));
      PetscCall(VecZeroEntries(ct->rho));
      PetscCall(VecScatterBegin(MMCondensedData(ct)->cand.gather, MMCondensedData(ct)->cand.x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
      PetscCall(VecScatterEnd(MMCondensedData(ct)->cand.gather, MMCondensedData(ct)->cand.x, ct->rho, INSERT_VALUES, SCATTER_REVERSE));
    } else PetscCall(VecZeroEntries(ct->rho));
    if (!*ok) PetscFunctionReturn(0);
    PetscCall(ContactDofValues(ct));
    PetscCall(MMCandidatesGrow(ct, MMCondensedData(ct)->cand.wc, &grown));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveSetBox(MMContact ct, void *unused, PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(SolveSetVI(ct));
  *ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The step's contact reactions rho with the box bounds of rho_lo/rho_hi (frictionless, or 2D
 * Tresca thresholds): z = K~^{-1} b once per step, then the VI on the candidate set. No full-size
 * solve. */
PetscErrorCode MMCondensedSolveReactions(MMContact ct, Vec b)
{
  PetscBool  ok;

  PetscFunctionBeginUser;
  PetscCall(PrepareStep(ct, b));
  ct->vi_its = 0;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(SolveGrowingSet(ct, SolveSetBox, NULL, &ok));
  PetscFunctionReturn(0);
}

typedef struct {
  MMContactSetSolver fn;
  void              *fctx;
} CoulombSetCtx;

/* The set's problem with the friction corners' second nodes (docs/method.md section 12): extended,
 * solved by the friction solver, and contracted back to the nodes' reactions x; their r_2 into
 * ct->fc_x. */
static PetscErrorCode SolveSetCoulombCorners(MMContact ct, const MMContactSetProblem *p, PetscScalar x[], CoulombSetCtx *cc, PetscBool *ok)
{
  MMCandidates       *c  = &MMCondensedData(ct)->cand;
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
static PetscErrorCode SolveSetCoulomb(MMContact ct, void *sctx, PetscBool *ok)
{
  MMCandidates       *c  = &MMCondensedData(ct)->cand;
  CoulombSetCtx      *cc = (CoulombSetCtx *)sctx;
  MMContactSetProblem p;
  const PetscScalar  *w, *q, *mua;
  PetscScalar        *x;
  PetscReal          *mu;

  PetscFunctionBeginUser;
  if (!MMCondensedData(ct)->mu_c) {
    PetscCall(VecDuplicate(ct->rho, &MMCondensedData(ct)->mu_c));
    for (PetscInt d = 0; d < ct->ncomp; ++d) PetscCall(VecStrideScatter(ct->mu, d, MMCondensedData(ct)->mu_c, INSERT_VALUES));
  }
  PetscCall(GatherToSet(c, MMCondensedData(ct)->q, c->q));
  PetscCall(GatherToSet(c, ct->rho, c->x));
  PetscCall(GatherToSet(c, MMCondensedData(ct)->mu_c, c->lo));
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
  if (ct->n_fc) PetscCall(SolveSetCoulombCorners(ct, &p, x, cc, ok));
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
static PetscErrorCode StoreCoulombBounds(MMContact ct)
{
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
PetscErrorCode MMCondensedSolveCoulomb(MMContact ct, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok)
{
  CoulombSetCtx cc = {fn, fctx};

  PetscFunctionBeginUser;
  PetscCall(PrepareStep(ct, b));
  ct->vi_its = 0;
  PetscCall(SolveGrowingSet(ct, SolveSetCoulomb, &cc, ok));
  if (!*ok) PetscFunctionReturn(0);
  if (!MMCondensedData(ct)->cand.m && ct->fc_x) PetscCall(VecZeroEntries(ct->fc_x)); /* no set, no second obstacle's reaction */
  PetscCall(MMContactCornersStore(ct));
  PetscCall(StoreCoulombBounds(ct));
  PetscCall(MMCondensedContactDofs(ct, w, react));
  PetscFunctionReturn(0);
}

/* The condensed dofs of the step's solution and of the contact force, exactly, from rho alone:
 * w_c = z_c - W rho and f_c = -rho (K~ w - b = -E rho). What the friction loop needs. */
PetscErrorCode MMCondensedContactDofs(MMContact ct, Vec w, Vec react)
{
  const PetscInt    *row = MMCondensedData(ct)->cand.cond_row;
  const PetscScalar *ra;
  PetscScalar       *wa, *fa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(w, &wa));
  PetscCall(VecGetArray(react, &fa));
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  for (PetscInt r = 0; r < MMCondensedData(ct)->cand.nc_local; ++r) {
    wa[row[r]] = MMCondensedData(ct)->cand.wc[r];
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
PetscErrorCode MMCondensedRecover(MMContact ct, Vec w)
{
  Vec        rc;

  PetscFunctionBeginUser;
  if (!ct->enabled) {
    PetscCall(VecCopy(ct->z, w));
    PetscFunctionReturn(0);
  }
  if (MMCondensedData(ct)->cand.full_ok) {
    PetscCall(MMCandidatesRecover(ct, w));
    PetscFunctionReturn(0);
  }
  MMCondensedData(ct)->cand.recover_solves++;
  PetscCall(VecZeroEntries(MMCondensedData(ct)->rhs_c));
  PetscCall(VecGetSubVector(MMCondensedData(ct)->rhs_c, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(MMCondensedData(ct)->rhs_c, ct->is_cond, &rc));
  PetscCall(KSPSolve(MMCondensedData(ct)->ksp_K, MMCondensedData(ct)->rhs_c, w));
  PetscCall(VecAXPY(w, 1.0, ct->z));
  PetscFunctionReturn(0);
}


/* ---- The formulation's ops ---- */

/* K~ for a new dt: its factor, and on the first one the VI solver on the reactions. */
static PetscErrorCode CondensedSetOperator(MMContact ct)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedFactor(ct));
  if (!ct->rho) PetscCall(MMCondensedCreateSolver(ct));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSolve(MMContact ct, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedSolveReactions(ct, b));
  PetscCall(MMCondensedRecover(ct, w));
  PetscCall(MMContactForce(ct, b, w, react));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSolveContactDofs(MMContact ct, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedSolveReactions(ct, b));
  PetscCall(MMCondensedContactDofs(ct, w, react));
  PetscFunctionReturn(0);
}

/* One full-size solve completes w once the friction loop has converged on the contact dofs. */
static PetscErrorCode CondensedRecoverAll(MMContact ct, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMCondensedRecover(ct, w));
  PetscCall(MMContactForce(ct, b, w, react));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  *krylov = *pc_ksp = MMCondensedData(ct)->ksp_K;
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedView(MMContact ct, PetscViewer viewer)
{
  const MMCandidates *c = &MMCondensedData(ct)->cand;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact candidate set: largest %" PetscInt_FMT " of %" PetscInt_FMT " contact nodes; %" PetscInt_FMT " columns of K~^{-1} E computed; %" PetscInt_FMT " VI re-solves after the set grew\n", c->max_set, ct->n_global, c->columns, c->resolves));
  if (c->evicted || c->recover_solves)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  contact candidate cache at -contact_candidate_memory %g MiB: %" PetscInt_FMT " cached nodes dropped and their columns recomputed when needed; %" PetscInt_FMT " steps recovered by a solve, the whole columns being over the cap\n", (double)c->memory_mib, c->evicted, c->recover_solves));
  PetscFunctionReturn(0);
}

/* A friction corner's second reactions in the slots the active set's warm start uses elsewhere */
static PetscErrorCode CondensedGetNodeState(MMContact ct, PetscInt k, PetscBool second, PetscScalar state[])
{
  const PetscInt dim = ct->dim;

  PetscFunctionBeginUser;
  if (!second && ct->fc_obstacle && ct->fc_obstacle[k] >= 0)
    for (PetscInt c = 0; c < dim; ++c) state[MM_CONTACT_STATE_CORNER_R + c] = ct->fc_r[dim * k + c];
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSetNodeState(MMContact ct, PetscInt k, PetscBool second, const PetscScalar state[])
{
  const PetscInt dim = ct->dim;

  PetscFunctionBeginUser;
  if (!second && ct->fc_obstacle && ct->fc_obstacle[k] >= 0)
    for (PetscInt c = 0; c < dim; ++c) ct->fc_r[dim * k + c] = PetscRealPart(state[MM_CONTACT_STATE_CORNER_R + c]);
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedGetCandidateCounts(MMContact ct, PetscInt *n_set, PetscInt *resolves)
{
  PetscFunctionBeginUser;
  *n_set    = MMCondensedData(ct)->cand.n_set;
  *resolves = MMCondensedData(ct)->cand.resolves;
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedSetCandidateResolves(MMContact ct, PetscInt resolves)
{
  PetscFunctionBeginUser;
  MMCondensedData(ct)->cand.resolves = resolves;
  PetscFunctionReturn(0);
}

/* The candidate set's options (impls/condensed/candidates.c) */
static PetscErrorCode CondensedSetFromOptions(MMContact ct, PetscOptionItems *PetscOptionsObject)
{
  MPI_Comm          comm = ct->comm;
  MMContactOptions *o    = &ct->opt;

  PetscFunctionBeginUser;
  o->candidate_margin = 1.0;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_candidate_margin", "Condensed formulation: a contact node joins the step's candidate set when its contact-free predicted gap is below this times the deepest predicted penetration (>= -1; negative values start from a set smaller than the contact, which the growth completes: the set grows and the step is re-solved whenever a node outside it would penetrate, so this changes the cost, not the answer)", &o->candidate_margin));
  o->candidate_all = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-contact_candidate_all", "Condensed formulation: every contact node in every step's candidate set (the full Delassus operator: the reference the candidate set is checked against)", &o->candidate_all));
  o->candidate_memory = 2048;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_candidate_memory", "Condensed formulation: MiB (over all ranks) of cached columns of K~^{-1} E; columns of nodes outside the step's set are dropped beyond it (> 0)", &o->candidate_memory));
  PetscCheck(o->candidate_margin >= -1, comm, PETSC_ERR_USER_INPUT, "-contact_candidate_margin %g must be >= -1: it is a multiple of the deepest predicted penetration (-1 starts each step from the deepest node alone)", (double)o->candidate_margin);
  PetscCheck(o->candidate_memory > 0, comm, PETSC_ERR_USER_INPUT, "-contact_candidate_memory %g must be > 0 (MiB)", (double)o->candidate_memory);
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedDestroy(MMContact ct)
{
  MMContact_Condensed *cd = MMCondensedData(ct);

  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&cd->ksp_K));
  PetscCall(MMCandidatesDestroy(&cd->cand));
  PetscCall(PetscFree(cd->kept_cache.cols));
  PetscCall(PetscFree(cd->kept_cache.full));
  PetscCall(PetscFree(cd->kept_cache.slot_node));
  PetscCall(VecDestroy(&cd->q));
  PetscCall(VecDestroy(&cd->mu_c));
  PetscCall(VecDestroy(&cd->offset));
  PetscCall(VecDestroy(&cd->Wdiag));
  PetscCall(VecDestroy(&cd->rhs_c));
  PetscCall(PetscFree(ct->data));
  PetscFunctionReturn(0);
}

/* K~, its factor and its cached columns swapped with the kept ones (those of the previous dt): a
 * step that goes back to that dt, after a rejection, needs no factorization. */
static PetscErrorCode CondensedSwapKept(MMContact ct, PetscReal dt, PetscBool *hit)
{

  PetscFunctionBeginUser;
  PetscCall(MMContactSwapKeptOperator(ct, &MMCondensedData(ct)->ksp_K));
  PetscCall(MMCandidatesSwapCache(ct, &MMCondensedData(ct)->kept_cache));
  *hit = (PetscBool)(ct->qp.A && ct->Kt_dt == dt);
  PetscFunctionReturn(0);
}

/* -contact_formulation auto's model of this formulation (docs/scaling.md, "The formulation chosen by
 * cost"), fitted on 1 and 2 ranks over 1.3k to 115k dofs, the linear law and svk: its set-up
 * holds K~'s factorization, its step a triangular solve and the candidate columns, which grow with
 * c_p dt / h_c' and friction (and with the finite-strain law's iterations). */
static PetscErrorCode CondensedCost(MMContact ct, const MMCostInput *in, MMCost *cost)
{
  static const MMCostModel model[2] = {MM_COST_CONDENSED_2D, MM_COST_CONDENSED_3D}; /* scripts/cost_model_fit.py --write */

  PetscFunctionBeginUser;
  (void)ct;
  MMCostEvaluate(&model[in->dim == 3], in, cost);
  cost->direct = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static const MMContactOps CondensedOps = {
  .setfromoptions   = CondensedSetFromOptions,
  .setoperator      = CondensedSetOperator,
  .solve            = CondensedSolve,
  .solvecontactdofs = CondensedSolveContactDofs,
  .recover          = CondensedRecoverAll,
  .solvecoulomb     = MMCondensedSolveCoulomb,
  .getstepksp           = CondensedGetStepKSP,
  .swapkept             = CondensedSwapKept,
  .getnodestate         = CondensedGetNodeState,
  .setnodestate         = CondensedSetNodeState,
  .getcandidatecounts   = CondensedGetCandidateCounts,
  .setcandidateresolves = CondensedSetCandidateResolves,
  .view                 = CondensedView,
  .cost                 = CondensedCost,
  .destroy              = CondensedDestroy,
};

PetscErrorCode MMContactCreate_Condensed(MMContact ct)
{
  MMContact_Condensed *cd;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&cd));
  ct->data = cd;
  ct->ops  = &CondensedOps;
  PetscFunctionReturn(0);
}
