/* The active-set formulation (docs/method.md section 3, "Active-set formulation"): the step's
 * contact problem on the full dof vector by a primal-dual active-set (semismooth Newton) method,
 * with no factor and no Delassus operator, so that K~ can be solved by preconditioned CG.
 *
 * Per contact node, with rho = (lambda_n, -t) its reactions (K~ w = b - E rho) and c > 0 a scale:
 *   normal:  active (w_n = g) if lambda_n + c (w_n - g) > 0, else free with lambda_n = 0;
 *   Tresca (thresholds s, friction loop): with off_t = u_t^n + dt/2 v_t^n and the trial force
 *            tr = rho_t + c (w_t - off_t), stick (w_t = off_t) if |tr| <= s, else slip with the
 *            known load rho_t = s tr/|tr|.
 * In 3D the slip direction d = tr/|tr| is itself an unknown. Taking it from the last iterate alone
 * is a fixed point that crawls (rate s/(s + c |slip|): a node that barely slips barely moves), so a
 * slipping node gets the semismooth Newton step of the disk: rho_t.d = s along d, and across it, with
 * a = s/|tr| < 1 and e = d_perp, the linearized rho_t.e = kappa e.(w^{k+1} - w^k) - beta rho_t^k.e,
 * beta = a/(1-a), kappa = beta c: a spring on w.e, symmetric, added to the operator.
 * Each iteration fixes the dofs D of the active and sticking nodes at their values, loads the
 * slipping ones, and solves K~ on the free dofs F by CG with the operator P_F K~ P_F + P_D and the
 * PC P_F M^{-1} P_F + P_D, M^{-1} the contact_K_ PC set up once per dt (in 3D scaled for the disk's
 * springs, ScaleDiskTangent), warm-started from the last
 * iterate. It stops when the sets (and, in 3D, the slip directions) stop changing: the solution then
 * satisfies every condition exactly, up to the CG tolerance on the free dofs.
 * Coulomb (-friction_type newton): the thresholds follow the iterate, s = mu max(lambda_n, 0) after
 * each solve, so one iteration is one CG solve; the derivative of s in lambda_n is left out of the
 * operator, which keeps it symmetric (a full Newton step would couple each slipping node's
 * tangential rows to its normal row and need GMRES or BiCGStab), and the thresholds converge
 * linearly (docs/method.md section 3, "Coulomb in the active-set iteration"). */
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "active_setimpl.h"
#include "../cost_constants.h"

/* y += kappa_k e_k (e_k.x_t) at every slipping node in 3D, e_k = d_perp: the Newton tangent of the
 * Tresca disk across the slip direction (its tangential dofs are free). */
static PetscErrorCode AddDiskTangent(MMContact ct, Vec x, Vec y)
{
  MMActiveSet       *as = MMActiveSetData(ct);
  const PetscInt    *in;
  const PetscScalar *xa;
  PetscScalar       *ya;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  if (ct->ncomp != 3) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(x, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   i = in[k] - rstart;
    const PetscReal *d = &as->dir[2 * k], e[2] = {-d[1], d[0]};
    PetscReal        ex;
    if (as->kappa[k] == 0) continue;
    ex = e[0] * PetscRealPart(xa[i + 1]) + e[1] * PetscRealPart(xa[i + 2]);
    ya[i + 1] += as->kappa[k] * ex * e[0];
    ya[i + 2] += as->kappa[k] * ex * e[1];
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* y = P_F y + P_D x, P_F the 0/1 mask `free` and P_D = I - P_F: one pass over the vectors where a
 * product and two AXPYs took three, in a CG iteration whose other work is one MatMult and a few
 * vector operations. */
static PetscErrorCode KeepFreeElseCopy(Vec free, Vec x, Vec y)
{
  const PetscScalar *f, *xa;
  PetscScalar       *ya;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(y, &n));
  PetscCall(VecGetArrayRead(free, &f));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt i = 0; i < n; ++i)
    if (f[i] == 0) ya[i] = xa[i];
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(free, &f));
  PetscFunctionReturn(0);
}

/* y = P_F (K~ + S) P_F x + P_D x, with P_F the diagonal 0/1 mask `free` and S the disk tangent. */
static PetscErrorCode ProjectedOperator(Mat A, Vec x, Vec y)
{
  MMContact        ct;
  MMActiveSet *as;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &ct));
  as = MMActiveSetData(ct);
  PetscCall(VecPointwiseMult(as->t, as->free, x));
  PetscCall(MatMult(as->Kb ? as->Kb : ct->qp.A, as->t, y));
  PetscCall(AddDiskTangent(ct, as->t, y));
  PetscCall(KeepFreeElseCopy(as->free, x, y));
  PetscFunctionReturn(0);
}

/* v_t -= (1 - 1/sqrt(1 + beta_k)) e_k (e_k.v_t) at every slipping node in 3D: the square root of the
 * inverse of the disk tangent's stiffening, I + beta_k e_k e_k^T, on that node's tangential dofs.
 * Applied on both sides of the K~ PC it keeps the PC symmetric and, when that PC is diagonal with
 * the isotropic c of the spring, makes it the exact inverse of the node's tangential block
 * c (I + beta e e^T). Without it the springs (beta up to 1e6) are as many large, distinct eigenvalues
 * of the preconditioned operator as there are slipping nodes, and CG takes hundreds of iterations
 * per solve once a few thousand nodes slip (docs/method.md section 3). */
static PetscErrorCode ScaleDiskTangent(MMContact ct, Vec v)
{
  MMActiveSet    *as = MMActiveSetData(ct);
  const PetscInt *in;
  PetscScalar    *va;
  PetscInt        rstart;

  PetscFunctionBeginUser;
  if (ct->ncomp != 3) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(v, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArray(v, &va));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   i = in[k] - rstart;
    const PetscReal *d = &as->dir[2 * k], e[2] = {-d[1], d[0]};
    PetscReal        ev, f;
    if (as->kappa[k] == 0) continue;
    f  = 1.0 - 1.0 / PetscSqrtReal(1.0 + as->beta[k]);
    ev = e[0] * PetscRealPart(va[i + 1]) + e[1] * PetscRealPart(va[i + 2]);
    va[i + 1] -= f * ev * e[0];
    va[i + 2] -= f * ev * e[1];
  }
  PetscCall(VecRestoreArray(v, &va));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* y = P_F S^{-1/2} M^{-1} S^{-1/2} P_F x + P_D x: the K~ PC, blind to the fixed dofs, with the disk
 * tangent's stiffening S (ScaleDiskTangent) on both sides. */
static PetscErrorCode ProjectedPC(PC pc, Vec x, Vec y)
{
  MMContact        ct;
  MMActiveSet *as;
  PC           pcK;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &ct));
  as = MMActiveSetData(ct);
  PetscCall(KSPGetPC(ct->kt.ksp, &pcK));
  PetscCall(VecPointwiseMult(as->t, as->free, x));
  PetscCall(ScaleDiskTangent(ct, as->t));
  PetscCall(PCApply(pcK, as->t, y));
  PetscCall(ScaleDiskTangent(ct, y));
  PetscCall(KeepFreeElseCopy(as->free, x, y));
  PetscFunctionReturn(0);
}

/* The contact_K_ PC's default is MMKtDefaultPC's (interface/kt.c; docs/method.md section 3, "Active-set
 * formulation"): ICC(0) on one rank, Jacobi on more. With friction ICC takes 0.33 to 0.43 of Jacobi's CG
 * iterations on the D2 ball (the disk's springs, which ScaleDiskTangent makes exact for a diagonal PC,
 * are then only scaled). */
static PetscBool ActiveSetDefaultICC(MPI_Comm comm)
{
  PetscBool icc = PETSC_FALSE;

  return (PetscBool)(!PetscStrcmp(MMKtDefaultPC(comm), PCICC, &icc) && icc);
}

PetscErrorCode MMActiveSetSetUp(MMContact ct)
{
  MMActiveSet *as = MMActiveSetData(ct);
  MPI_Comm     comm = PetscObjectComm((PetscObject)ct->dm);
  PetscInt     n, N;
  PC           pc;

  PetscFunctionBeginUser;
  as->max_it  = ct->opt.active_set_max_it;
  as->inexact_rtol = ct->opt.active_set_inexact_rtol;
  as->inexact_coulomb_rtol = ct->opt.active_set_inexact_coulomb_rtol;
  as->monitor = ct->opt.active_set_monitor;
  as->block   = ct->opt.active_set_block;
  PetscCall(MMKtCreate(ct, PETSC_TRUE, MMKtDefaultPC(PetscObjectComm((PetscObject)ct->dm))));
  PetscCall(VecDuplicate(ct->qp.b, &as->free));
  PetscCall(VecDuplicate(ct->qp.b, &as->x0));
  PetscCall(VecDuplicate(ct->qp.b, &as->r));
  PetscCall(VecDuplicate(ct->qp.b, &as->dx));
  PetscCall(VecDuplicate(ct->qp.b, &as->t));
  PetscCall(VecDuplicate(ct->qp.b, &as->ct_diag));
  PetscCall(VecDuplicate(ct->gap, &as->s));
  PetscCall(VecZeroEntries(as->s));
  PetscCall(MMContactCreateReactions(ct));
  PetscCall(PetscCalloc3(ct->n_local, &as->active, ct->n_local, &as->stick, PetscMax(1, ct->n_local * (ct->dim - 1)), &as->dir));
  PetscCall(PetscCalloc3(ct->n_local, &as->kappa, ct->n_local, &as->beta, ct->n_local, &as->rperp));

  PetscCall(VecGetLocalSize(ct->qp.b, &n));
  PetscCall(VecGetSize(ct->qp.b, &N));
  PetscCall(MatCreateShell(comm, n, n, N, N, ct, &as->A));
  PetscCall(MatShellSetOperation(as->A, MATOP_MULT, (void (*)(void))ProjectedOperator));
  PetscCall(KSPCreate(comm, &as->ksp));
  PetscCall(KSPSetOptionsPrefix(as->ksp, "contact_as_"));
  PetscCall(KSPSetType(as->ksp, KSPCG));
  /* the test is on the true residual of the free dofs: ||r_F|| <= contact_tol ||b|| */
  PetscCall(KSPSetNormType(as->ksp, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetTolerances(as->ksp, 1e-14, PETSC_DEFAULT, PETSC_DEFAULT, 5000));
  /* a CG that fails (a residual grown 1e5-fold on an ill-conditioned K~ with the disk's stiff springs,
   * its iterations spent) fails the solve, which the friction solver turns into a smaller dt: SolveFree */
  PetscCall(KSPGetPC(as->ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, ct));
  PetscCall(PCShellSetApply(pc, ProjectedPC));
  PetscCall(PCShellSetName(pc, "P_F (contact_K_ PC) P_F + P_D"));
  PetscCall(KSPSetFromOptions(as->ksp));
  PetscFunctionReturn(0);
}

/* Kb made or refilled from the current K~ when K~ changed since (a new dt, or the kept one swapped
 * back); left NULL, and the products on K~'s AIJ, where K~'s pattern is not in whole blocks. */
static PetscErrorCode RefreshBlockOperator(MMContact ct)
{
  MMActiveSet     *as = MMActiveSetData(ct);
  PetscObjectState state;

  PetscFunctionBeginUser;
  if (!as->block) PetscFunctionReturn(0);
  PetscCall(PetscObjectStateGet((PetscObject)ct->qp.A, &state));
  if (as->Kb_of == ct->qp.A && as->Kb_state == state) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_BlockOperator, 0, 0, 0, 0));
  PetscCall(MMActiveSetBlockOperator(ct->qp.A, ct->dim, &as->Kb));
  PetscCall(PetscLogEventEnd(MMCONTACT_BlockOperator, 0, 0, 0, 0));
  as->block    = (PetscBool)(as->Kb != NULL);
  as->Kb_of    = ct->qp.A;
  as->Kb_state = state;
  PetscFunctionReturn(0);
}

/* A new K~ (a new dt): its PC, set up once, and the scale c = diag(K~) of the complementarity
 * functions, which keeps force and displacement in the same units. */
PetscErrorCode MMActiveSetSetOperator(MMContact ct)
{

  PetscFunctionBeginUser;
  PetscCall(MMKtSetOperator(ct, ct->qp.A));
  PetscCall(MatGetDiagonal(ct->qp.A, MMActiveSetData(ct)->ct_diag));
  PetscCall(RefreshBlockOperator(ct)); /* here too, so that the start-up header can tell */
  PetscCall(KSPSetOperators(MMActiveSetData(ct)->ksp, MMActiveSetData(ct)->A, MMActiveSetData(ct)->A));
  PetscFunctionReturn(0);
}

/* Tresca thresholds s, one per contact node, for the next solves; the bounds |rho_t| <= s are
 * also what the diagnostics compare the reactions with. */
PetscErrorCode MMActiveSetSetThresholds(MMContact ct, Vec s)
{

  PetscFunctionBeginUser;
  PetscCall(VecCopy(s, MMActiveSetData(ct)->s));
  for (PetscInt c = 1; c < ct->ncomp; ++c) {
    PetscCall(VecStrideScatter(s, c, ct->rho_hi, INSERT_VALUES));
    PetscCall(VecStrideScatter(s, c, ct->rho_lo, INSERT_VALUES));
    PetscCall(VecStrideScale(ct->rho_lo, c, -1.0));
  }
  PetscFunctionReturn(0);
}

/* What one iteration needs per node: the arrays of the state and of the step's data. */
typedef struct {
  PetscInt           dim, nt, ncomp, rstart;
  const PetscInt    *in;    /* normal dof of each contact node; its tangential dofs follow */
  const PetscScalar *g, *s, *off, *c; /* off: the step's offset u^n + dt/2 v^n (MMContactSetStepOffset) */
  const PetscReal   *slide;            /* per node and tangent: dt/2 times the obstacle's tangential velocity */
} NodeData;

static PetscErrorCode NodeDataGet(MMContact ct, NodeData *nd)
{

  PetscFunctionBeginUser;
  nd->dim     = ct->dim;
  nd->nt      = ct->ncomp > 1 ? nd->dim - 1 : 0; /* tangential dofs with friction */
  nd->ncomp   = ct->ncomp;
  nd->slide   = ct->slide_ref;
  PetscCall(VecGetOwnershipRange(ct->qp.b, &nd->rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &nd->in));
  PetscCall(VecGetArrayRead(ct->gap, &nd->g));
  PetscCall(VecGetArrayRead(MMActiveSetData(ct)->s, &nd->s));
  PetscCall(VecGetArrayRead(ct->step.offset, &nd->off));
  PetscCall(VecGetArrayRead(MMActiveSetData(ct)->ct_diag, &nd->c));
  PetscFunctionReturn(0);
}

static PetscErrorCode NodeDataRestore(MMContact ct, NodeData *nd)
{

  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(MMActiveSetData(ct)->ct_diag, &nd->c));
  PetscCall(VecRestoreArrayRead(ct->step.offset, &nd->off));
  PetscCall(VecRestoreArrayRead(MMActiveSetData(ct)->s, &nd->s));
  PetscCall(VecRestoreArrayRead(ct->gap, &nd->g));
  PetscCall(ISRestoreIndices(ct->is_normal, &nd->in));
  PetscFunctionReturn(0);
}

/* off_t = u_t^n + dt/2 (v_t^n + V_t), the step's offset plus the obstacle's sliding: w_t - off_t is
 * dt/2 times the slip velocity relative to the obstacle, V its velocity (impls/condensed/). */
static inline PetscReal Offset(const NodeData *nd, PetscInt k, PetscInt i, PetscInt j)
{
  return PetscRealPart(nd->off[i + 1 + j]) + nd->slide[k * (nd->dim - 1) + j];
}

/* The linear problem of the current sets: x0 = w with the fixed dofs at their values (g, off_t),
 * free = the mask of F, and r = P_F (b - E rho_slip - K~ x0), the free dofs' residual, rho_slip the
 * slipping nodes' load s d (3D: minus beta rperp e, the Newton step's part across d). */
static PetscErrorCode FixSets(MMContact ct, Vec b, Vec w)
{
  MMActiveSet *as = MMActiveSetData(ct);
  NodeData     nd;
  PetscScalar *x, *f, *r;
  const PetscScalar *rho;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(w, as->x0));
  PetscCall(VecSet(as->free, 1.0));
  PetscCall(VecCopy(b, as->t)); /* b - E rho_slip */
  PetscCall(NodeDataGet(ct, &nd));
  PetscCall(VecGetArray(as->x0, &x));
  PetscCall(VecGetArray(as->free, &f));
  PetscCall(VecGetArray(as->t, &r));
  PetscCall(VecGetArrayRead(ct->rho, &rho));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   i  = nd.in[k] - nd.rstart;
    const PetscReal  sk = nd.nt ? PetscRealPart(nd.s[k]) : 0;
    const PetscReal *d  = &as->dir[k * nd.nt];
    if (as->active[k]) {
      x[i] = nd.g[k];
      f[i] = 0;
    }
    as->rperp[k] = 0;
    /* the disk's spring belongs to slipping nodes only: a threshold that dropped to 0 removes it */
    if (sk <= 0 || as->stick[k]) as->kappa[k] = 0;
    if (sk <= 0) continue; /* no threshold: the tangential dofs are free and unloaded */
    for (PetscInt j = 0; j < nd.nt; ++j) {
      if (as->stick[k]) {
        x[i + 1 + j] = Offset(&nd, k, i, j);
        f[i + 1 + j] = 0;
      } else r[i + 1 + j] -= sk * d[j];
    }
    if (as->stick[k] || !as->kappa[k]) continue;
    {
      const PetscReal e[2] = {-d[1], d[0]};
      as->rperp[k] = e[0] * PetscRealPart(rho[k * 3 + 1]) + e[1] * PetscRealPart(rho[k * 3 + 2]);
      for (PetscInt j = 0; j < 2; ++j) r[i + 1 + j] += as->beta[k] * as->rperp[k] * e[j];
    }
  }
  PetscCall(VecRestoreArrayRead(ct->rho, &rho));
  PetscCall(VecRestoreArray(as->t, &r));
  PetscCall(VecRestoreArray(as->free, &f));
  PetscCall(VecRestoreArray(as->x0, &x));
  PetscCall(NodeDataRestore(ct, &nd));
  PetscCall(MatMult(as->Kb ? as->Kb : ct->qp.A, as->x0, as->r));
  PetscCall(VecAYPX(as->r, -1.0, as->t));
  PetscCall(VecPointwiseMult(as->r, as->free, as->r));
  PetscFunctionReturn(0);
}

/* The Newton tangent of the disk at a slipping node from its trial force tr, |tr| = trn > s: a = s/|tr|,
 * beta = a/(1-a), capped where the node barely slips (a -> 1: an infinitely stiff spring). The cap
 * is a few isolated large eigenvalues for CG; a cap of 1e2 left D2 with mu = 0.2 crawling at 0.99
 * per iteration at such a node, 1e6 converges in at most 5 iterations. */
static void DiskTangent(MMActiveSet *as, PetscInt k, PetscReal sk, PetscReal trn, PetscReal c)
{
  const PetscReal beta_max = 1e6, a = sk / trn;

  as->beta[k]  = a < beta_max / (1 + beta_max) ? a / (1 - a) : beta_max;
  as->kappa[k] = as->beta[k] * c;
}

/* w = x0 + dx, P_F K~ P_F dx = r by the projected CG from dx = 0 (x0 is the warm start). A loose
 * solve (eta > 0) stops once CG has reduced r by eta: its iterate only decides the next sets or
 * thresholds, which the solves to -contact_tol then confirm (MMActiveSetSolve). *tight: the solve
 * met -contact_tol (a loose one can, when its residual was small to begin with). */
static PetscErrorCode SolveFree(MMContact ct, Vec b, Vec w, PetscReal eta, PetscBool *tight, KSPConvergedReason *reason)
{
  MMActiveSet    *as    = MMActiveSetData(ct);
  const PetscBool loose = (PetscBool)(eta > 0);
  PetscInt        its, maxit;
  PetscReal       rtol, atol, dtol, rnorm, tight_atol;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_ActiveSetCG, 0, 0, 0, 0));
  PetscCall(VecZeroEntries(as->dx));
  PetscCall(KSPGetTolerances(as->ksp, &rtol, &atol, &dtol, &maxit));
  if (loose) PetscCall(KSPSetTolerances(as->ksp, PetscMax(rtol, eta), atol, dtol, maxit));
  PetscCall(MMKtSolveToTolerance(as->ksp, ct->tol, b, as->r, as->dx, &tight_atol));
  PetscCall(KSPSetTolerances(as->ksp, rtol, atol, dtol, maxit));
  PetscCall(KSPGetConvergedReason(as->ksp, reason));
  PetscCall(KSPGetIterationNumber(as->ksp, &its));
  as->lin_its += its;
  *tight = (PetscBool)!loose;
  if (loose) {
    PetscCall(KSPGetResidualNorm(as->ksp, &rnorm));
    *tight = (PetscBool)(rnorm <= tight_atol);
  }
  PetscCall(VecWAXPY(w, 1.0, as->x0, as->dx));
  PetscCall(PetscLogEventEnd(MMCONTACT_ActiveSetCG, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Tolerances of the set updates: a node changes set only when its condition is violated beyond
 * solver noise (a penetration of 1e-10 h_c', a tension or a Tresca excess of 1e-9 of the force
 * scale, as the Coulomb residual measures them, docs/method.md section 6); within them either set
 * is a solution, and switching back and forth on noise would never stop. */
typedef struct {
  PetscReal len, force, fscale;
} SetTolerances;

static PetscErrorCode GetSetTolerances(MMContact ct, SetTolerances *tol)
{
  PetscReal  rmax;

  PetscFunctionBeginUser;
  PetscCall(VecStrideMax(ct->rho, 0, NULL, &rmax));
  tol->fscale = PetscMax(rmax, 1e-3 * ct->material->E_max * PetscPowReal(ct->h_c, ct->dim - 1));
  tol->len    = 1e-10 * ct->h_c;
  tol->force  = 1e-9 * tol->fscale;
  PetscFunctionReturn(0);
}

/* b - K~ w on the contact dofs only, through K~'s contact rows (a few percent of its nonzeros, where
 * a whole product would cost as much as a CG iteration), extracted again whenever K~ changes. */
static PetscErrorCode ContactResidual(MMContact ct, Vec b, Vec w)
{
  MMActiveSet     *as = MMActiveSetData(ct);
  PetscObjectState state;
  Vec              bc;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)ct->qp.A, &state));
  if (!as->Kc || as->Kc_of != ct->qp.A || as->Kc_state != state) {
    PetscCall(MatDestroy(&as->Kc));
    PetscCall(VecDestroy(&as->rc));
    PetscCall(MatCreateSubMatrix(ct->qp.A, ct->is_cond, NULL, MAT_INITIAL_MATRIX, &as->Kc));
    PetscCall(MatCreateVecs(as->Kc, NULL, &as->rc));
    as->Kc_of    = ct->qp.A;
    as->Kc_state = state;
  }
  PetscCall(MatMult(as->Kc, w, as->rc));
  PetscCall(VecGetSubVector(b, ct->is_cond, &bc));
  PetscCall(VecAYPX(as->rc, -1.0, bc));
  PetscCall(VecRestoreSubVector(b, ct->is_cond, &bc));
  PetscFunctionReturn(0);
}

/* From the solution w of the current sets: the reactions rho (res = b - K~ w = E rho on the fixed
 * dofs, the loads on the slipping ones). */
static PetscErrorCode Reactions(MMContact ct, Vec b, Vec w)
{
  MMActiveSet       *as = MMActiveSetData(ct);
  NodeData           nd;
  const PetscScalar *res, *dx;
  PetscScalar       *rho;

  PetscFunctionBeginUser;
  PetscCall(ContactResidual(ct, b, w));
  PetscCall(NodeDataGet(ct, &nd));
  PetscCall(VecGetArrayRead(as->rc, &res));
  PetscCall(VecGetArrayRead(as->dx, &dx));
  PetscCall(VecGetArray(ct->rho, &rho));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   i  = nd.in[k] - nd.rstart, ic = k * nd.ncomp;
    const PetscReal  sk = nd.nt ? PetscRealPart(nd.s[k]) : 0;
    const PetscReal *d  = &as->dir[k * nd.nt];
    rho[k * nd.ncomp] = as->active[k] ? res[ic] : 0;
    for (PetscInt j = 0; j < nd.nt; ++j) rho[k * nd.ncomp + 1 + j] = sk <= 0 ? 0 : as->stick[k] ? res[ic + 1 + j] : sk * d[j];
    if (sk > 0 && !as->stick[k] && as->kappa[k]) {
      /* across d, the Newton step's reaction: the spring's force and the corrected one */
      const PetscReal e[2] = {-d[1], d[0]};
      const PetscReal rp   = as->kappa[k] * (e[0] * PetscRealPart(dx[i + 1]) + e[1] * PetscRealPart(dx[i + 2])) - as->beta[k] * as->rperp[k];
      for (PetscInt j = 0; j < 2; ++j) rho[k * 3 + 1 + j] += rp * e[j];
    }
  }
  PetscCall(VecRestoreArray(ct->rho, &rho));
  PetscCall(VecRestoreArrayRead(as->dx, &dx));
  PetscCall(VecRestoreArrayRead(as->rc, &res));
  PetscCall(NodeDataRestore(ct, &nd));
  PetscFunctionReturn(0);
}

/* Coulomb (docs/method.md section 3, "Coulomb in the active-set iteration"): the thresholds follow
 * the iterate, s = mu max(rho_n, 0), before the stick/slip sets are updated against them. Returns
 * the largest change of a threshold over the force scale: the iteration has converged only when it
 * vanishes with the set changes, and then s = mu rho_n, the Coulomb law, holds at every node. */
static PetscErrorCode CoulombThresholds(MMContact ct, PetscReal fscale, PetscReal *ds)
{
  const PetscScalar *rho, *mu;
  PetscScalar       *s;

  PetscFunctionBeginUser;
  *ds = 0;
  PetscCall(VecGetArrayRead(ct->rho, &rho));
  PetscCall(VecGetArrayRead(ct->mu, &mu));
  PetscCall(VecGetArray(MMActiveSetData(ct)->s, &s));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal s_new = PetscRealPart(mu[k]) * PetscMax(PetscRealPart(rho[k * ct->ncomp]), 0.0);
    *ds  = PetscMax(*ds, PetscAbsReal(s_new - PetscRealPart(s[k])) / fscale);
    s[k] = s_new;
  }
  PetscCall(VecRestoreArray(MMActiveSetData(ct)->s, &s));
  PetscCall(VecRestoreArrayRead(ct->mu, &mu));
  PetscCall(VecRestoreArrayRead(ct->rho, &rho));
  PetscFunctionReturn(0);
}

/* The new sets from w and its reactions rho. Counts the nodes that changed set and the largest
 * change of a slipping node's force over the force scale (its direction, and in 3D its part across
 * the direction). */
static PetscErrorCode NewSets(MMContact ct, Vec w, const SetTolerances *tol, PetscInt *nch_out, PetscReal *dmax_out)
{
  MMActiveSet       *as = MMActiveSetData(ct);
  NodeData           nd;
  const PetscScalar *wa;
  const PetscScalar *rho;
  PetscInt           nch = 0;
  PetscReal          dmax = 0;

  PetscFunctionBeginUser;
  PetscCall(NodeDataGet(ct, &nd));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ct->rho, &rho));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt  i  = nd.in[k] - nd.rstart;
    const PetscReal sk = nd.nt ? PetscRealPart(nd.s[k]) : 0;
    const PetscReal rn = PetscRealPart(rho[k * nd.ncomp]), gap = PetscRealPart(wa[i] - nd.g[k]);
    PetscReal       tr[MM_MAX_DIM] = {0, 0, 0}, trn = 0, ct_k = 0;
    PetscBool       stick;

    /* normal: the fixed one has w_n = g, the free one rho_n = 0, so only one term of the trial is live */
    if (as->active[k] ? rn < -tol->force : gap > tol->len) {
      as->active[k] = (PetscBool)!as->active[k];
      ++nch;
    }
    if (sk <= 0) continue;
    for (PetscInt j = 0; j < nd.nt; ++j) ct_k += PetscRealPart(nd.c[i + 1 + j]) / nd.nt; /* isotropic c: the disk stays a disk */
    for (PetscInt j = 0; j < nd.nt; ++j) {
      tr[j] = PetscRealPart(rho[k * nd.ncomp + 1 + j]) + ct_k * (PetscRealPart(wa[i + 1 + j]) - Offset(&nd, k, i, j));
      trn += tr[j] * tr[j];
    }
    trn   = PetscSqrtReal(trn);
    stick = as->stick[k] ? (PetscBool)(trn <= sk + tol->force) : (PetscBool)(trn < sk - ct_k * tol->len);
    if (stick != as->stick[k]) ++nch;
    as->stick[k]    = stick;
    ct->slipping[k] = (PetscBool)!stick;
    as->kappa[k]    = 0;
    if (stick) continue;
    {
      /* the change of the slip force s d, and in 3D its part across d: both vanish at the solution */
      PetscReal dd = 0, rp = 0;
      for (PetscInt j = 0; j < nd.nt; ++j) {
        const PetscReal d = tr[j] / trn;
        dd += PetscSqr(d - as->dir[k * nd.nt + j]);
        as->dir[k * nd.nt + j] = d;
      }
      if (nd.nt == 2) {
        rp = PetscAbsReal(-as->dir[2 * k + 1] * PetscRealPart(rho[3 * k + 1]) + as->dir[2 * k] * PetscRealPart(rho[3 * k + 2]));
        DiskTangent(as, k, sk, trn, ct_k);
      }
      dmax = PetscMax(dmax, PetscMax(sk * PetscSqrtReal(dd), rp) / tol->fscale);
    }
  }
  PetscCall(VecRestoreArrayRead(ct->rho, &rho));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(NodeDataRestore(ct, &nd));
  *nch_out  = nch;
  *dmax_out = dmax;
  PetscFunctionReturn(0);
}

/* One update from the solution w of the current sets: the reactions, with Coulomb the thresholds,
 * then the sets. Returns how many nodes changed set and the largest change of a slip force or a
 * threshold over the force scale. */
static PetscErrorCode UpdateSets(MMContact ct, Vec b, Vec w, PetscInt *changed, PetscReal *dchange)
{
  SetTolerances tol = {0, 0, 0};
  PetscInt      nch;
  PetscReal     dmax, ds = 0;

  PetscFunctionBeginUser;
  PetscCall(Reactions(ct, b, w));
  PetscCall(GetSetTolerances(ct, &tol));
  if (MMActiveSetData(ct)->coulomb) PetscCall(CoulombThresholds(ct, tol.fscale, &ds));
  PetscCall(NewSets(ct, w, &tol, &nch, &dmax));
  dmax = PetscMax(dmax, ds);
  PetscCall(MPIU_Allreduce(&nch, changed, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)w)));
  PetscCall(MPIU_Allreduce(&dmax, dchange, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)w)));
  PetscFunctionReturn(0);
}

/* The step's contact problem K~ w = b - E rho with the conditions above; w is the warm start on entry
 * (with the sets of the last solve) and the whole solution on return, ct->rho its reactions.
 * *converged is false when the sets still change after -active_set_max_it iterations. */
PetscErrorCode MMActiveSetSolve(MMContact ct, Vec b, Vec w, PetscBool *converged)
{
  MMActiveSet *as = MMActiveSetData(ct);
  MPI_Comm     comm = PetscObjectComm((PetscObject)w);
  /* with Coulomb the thresholds' change is the friction solver's own test (-friction_snes_rtol) */
  PetscReal    dtol = as->coulomb ? PetscMin(as->coulomb_rtol, 1e-2 * ct->opt.friction_coulomb_tol) : 1e-2 * ct->opt.friction_coulomb_tol;

  /* while nodes change set, a solve only has to tell the next sets apart: it is loose (reduces the
   * residual by -active_set_inexact_rtol). Once they hold, with Coulomb the slip directions and
   * thresholds still move, each iteration by about 1e-2 of the last move: a solve then only has to
   * be more exact than the next move, and stops at -active_set_inexact_coulomb_rtol of its residual
   * (an inexact Newton; a tight solve took 25 to 40 CG iterations there on the D2 ball at dt 8e-3,
   * for a move of 1e-4 of the force scale; docs/method.md section 3). The last solves are tight, and the last one, which
   * changes nothing, is the answer. */
  PetscReal    eta = as->inexact_rtol;

  PetscFunctionBeginUser;
  PetscCall(RefreshBlockOperator(ct));
  as->lin_its   = 0;
  as->cg_failed = KSP_CONVERGED_ITERATING;
  for (as->its = 1; as->its <= as->max_it; ++as->its) {
    PetscInt  changed;
    PetscReal dchange;
    PetscBool          tight = PETSC_FALSE;
    KSPConvergedReason reason;

    PetscCall(PetscLogEventBegin(MMCONTACT_ActiveSetIterate, 0, 0, 0, 0));
    PetscCall(FixSets(ct, b, w));
    PetscCall(SolveFree(ct, b, w, eta, &tight, &reason));
    if (reason < 0) { /* the CG failed: so does the solve (as->its past max_it says so) */
      PetscCall(PetscLogEventEnd(MMCONTACT_ActiveSetIterate, 0, 0, 0, 0));
      PetscCall(PetscInfo(NULL, "active set: its CG failed (%s) at iteration %" PetscInt_FMT "\n", KSPConvergedReasons[reason], as->its));
      as->cg_failed = reason;
      as->its       = as->max_it + 1;
      break;
    }
    PetscCall(UpdateSets(ct, b, w, &changed, &dchange));
    PetscCall(PetscLogEventEnd(MMCONTACT_ActiveSetIterate, 0, 0, 0, 0));
    if (as->monitor) PetscCall(PetscPrintf(comm, "    active set %2" PetscInt_FMT ": %" PetscInt_FMT " nodes changed set, slip forces%s changed by %.3e of the force scale, %" PetscInt_FMT " CG iterations so far%s\n", as->its, changed, as->coulomb ? " and thresholds" : "", (double)dchange, as->lin_its, tight ? "" : " (loose solve)"));
    if (!changed && dchange <= dtol && tight) break;
    eta = changed ? as->inexact_rtol : dchange > dtol && as->inexact_rtol > 0 ? as->inexact_coulomb_rtol : 0;
  }
  *converged = (PetscBool)(as->its <= as->max_it);
  as->its    = PetscMin(as->its, as->max_it);
  ct->vi_its = as->its;
  PetscFunctionReturn(0);
}

/* The frictionless or Tresca step: a solve that does not converge stops the run, as the other
 * formulations' VI does (the sets of a well-posed step settle in a few iterations). */
static PetscErrorCode ActiveSetSolveOrFail(MMContact ct, Vec b, Vec w)
{
  PetscBool converged;

  PetscFunctionBeginUser;
  PetscCall(MMActiveSetSolve(ct, b, w, &converged));
  PetscCheck(MMActiveSetData(ct)->cg_failed >= 0, PetscObjectComm((PetscObject)w), PETSC_ERR_NOT_CONVERGED, "The active-set contact solver's CG failed (%s): K~ on the free dofs is too ill-conditioned for it at this dt. Lower -ts_dt, or use -contact_formulation condensed (a factorization)", KSPConvergedReasons[MMActiveSetData(ct)->cg_failed]);
  PetscCheck(converged, PetscObjectComm((PetscObject)w), PETSC_ERR_NOT_CONVERGED, "The active-set contact solver did not converge in -active_set_max_it %" PetscInt_FMT " iterations: the contact or stick/slip sets keep changing. Run with -active_set_monitor to see how, and raise -active_set_max_it", MMActiveSetData(ct)->max_it);
  PetscFunctionReturn(0);
}

PetscErrorCode MMActiveSetDestroy(MMActiveSet *as)
{
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&as->ksp));
  PetscCall(MatDestroy(&as->A));
  PetscCall(VecDestroy(&as->free));
  PetscCall(VecDestroy(&as->x0));
  PetscCall(VecDestroy(&as->r));
  PetscCall(VecDestroy(&as->dx));
  PetscCall(VecDestroy(&as->t));
  PetscCall(MatDestroy(&as->Kc));
  PetscCall(VecDestroy(&as->rc));
  PetscCall(VecDestroy(&as->s));
  PetscCall(VecDestroy(&as->ct_diag));
  PetscCall(MatDestroy(&as->Kb));
  PetscCall(PetscFree3(as->active, as->stick, as->dir));
  PetscCall(PetscFree3(as->kappa, as->beta, as->rperp));
  PetscFunctionReturn(0);
}

/* ---- The formulation's ops ---- */

/* The contact force: -rho on the contact dofs, exactly. On its fixed dofs rho is K~ w - b's own
 * value; on its free contact dofs (a node off the obstacle, a slipping node's tangential dofs) rho is
 * the prescribed value and K~ w - b differs from it by the CG residual, which is left to the energy
 * audit, as on the interior dofs, instead of passing for a force. */
static PetscErrorCode ActiveSetContactForce(MMContact ct, Vec b, Vec w, Vec react)
{
  Vec        rc;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(react));
  PetscCall(VecGetSubVector(react, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(react, ct->is_cond, &rc));
  PetscFunctionReturn(0);
}

/* Every solve gives the whole w: the contact-dof solve is the solve. */
static PetscErrorCode ActiveSetSolveStep(MMContact ct, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(ActiveSetSolveOrFail(ct, b, w));
  PetscCall(ActiveSetContactForce(ct, b, w, react));
  PetscFunctionReturn(0);
}

/* The step's Coulomb problem on all dofs: the same iteration with the thresholds following the
 * iterate (CoulombThresholds), warm-started from s (the last step's thresholds), which it overwrites
 * with mu r_n of the answer; it stops when the thresholds change by at most rtol of the force
 * scale. A solve that does not converge reports it (*converged false): the friction solver rejects
 * the step, and it is retried with a smaller dt. */
static PetscErrorCode ActiveSetSolveCoulomb(MMContact ct, Vec b, Vec w, Vec react, Vec s, PetscReal rtol, PetscInt *its, PetscBool *converged)
{
  MMActiveSet *as = MMActiveSetData(ct);

  PetscFunctionBeginUser;
  PetscCall(VecCopy(s, as->s));
  as->coulomb      = PETSC_TRUE;
  as->coulomb_rtol = rtol;
  PetscCall(MMActiveSetSolve(ct, b, w, converged));
  as->coulomb = PETSC_FALSE;
  /* the bounds |rho_t| <= s of the diagnostics, at the thresholds of the answer */
  PetscCall(MMActiveSetSetThresholds(ct, as->s));
  PetscCall(VecCopy(as->s, s));
  PetscCall(ActiveSetContactForce(ct, b, w, react));
  *its = as->its;
  PetscFunctionReturn(0);
}

/* The CG on the free dofs (prefix contact_as_) applies the contact_K_ PC projected on them. */
static PetscErrorCode ActiveSetGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  *krylov = MMActiveSetData(ct)->ksp;
  *pc_ksp = ct->kt.ksp;
  PetscFunctionReturn(0);
}

/* The CG's products (block_operator.c), for the start-up report */
static PetscErrorCode ActiveSetGetProducts(MMContact ct, const char **products)
{
  MMActiveSet *as = MMActiveSetData(ct);

  PetscFunctionBeginUser;
  *products = "";
  if (as->ksp) *products = as->Kb ? "; CG products with K~ in symmetric block storage (SBAIJ)" : (ct->opt.active_set_block ? "; CG products with K~'s AIJ (its pattern is not in whole blocks)" : "");
  PetscFunctionReturn(0);
}

/* The warm start of row k: its normal state; on a first row its stick state and slip direction */
static PetscErrorCode ActiveSetGetNodeState(MMContact ct, PetscInt k, PetscBool second, PetscScalar state[])
{
  MMActiveSet *as = MMActiveSetData(ct);

  PetscFunctionBeginUser;
  if (!as->active) PetscFunctionReturn(0);
  if (second) {
    state[MM_CONTACT_STATE_SECOND_AS] = (PetscScalar)as->active[k];
    PetscFunctionReturn(0);
  }
  state[9]  = (PetscScalar)as->active[k];
  state[10] = (PetscScalar)as->stick[k];
  for (PetscInt j = 0; j < ct->dim - 1; ++j) state[11 + j] = as->dir[k * (ct->dim - 1) + j];
  PetscFunctionReturn(0);
}

static PetscErrorCode ActiveSetSetNodeState(MMContact ct, PetscInt k, PetscBool second, const PetscScalar state[])
{
  MMActiveSet *as = MMActiveSetData(ct);

  PetscFunctionBeginUser;
  if (!as->active) PetscFunctionReturn(0);
  if (second) {
    as->active[k] = (PetscBool)(PetscRealPart(state[MM_CONTACT_STATE_SECOND_AS]) != 0);
    PetscFunctionReturn(0);
  }
  as->active[k] = (PetscBool)(PetscRealPart(state[9]) != 0);
  as->stick[k]  = (PetscBool)(PetscRealPart(state[10]) != 0);
  for (PetscInt j = 0; j < ct->dim - 1; ++j) as->dir[k * (ct->dim - 1) + j] = PetscRealPart(state[11 + j]);
  PetscFunctionReturn(0);
}

static PetscErrorCode ActiveSetSetFromOptions(MMContact ct, PetscOptionItems *PetscOptionsObject)
{
  MPI_Comm          comm = ct->comm;
  MMContactOptions *o    = &ct->opt;

  PetscFunctionBeginUser;
  o->active_set_max_it = 100;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-active_set_max_it", "Active-set formulation: iterations per contact solve before the run stops (each is one projected CG solve)", &o->active_set_max_it));
  /* with ICC(0), the default PC on one rank, one CG iteration reduces the residual by 0.3: iterates
   * that rough let the D2 ball's stick/slip sets cycle (33k dofs, mu 0.2, dt 8e-3); 0.1 was chosen
   * over 0.01 to 0.3 there (docs/benchmark_history.md, "Issue 50, the active set's step") */
  o->active_set_inexact_rtol = ActiveSetDefaultICC(comm) ? 0.1 : 0.3;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-active_set_inexact_rtol", "Active-set formulation: while nodes still change set, CG reduces the residual by this factor only; the last solves, which confirm the sets, go to -contact_tol (0: every solve to -contact_tol). Default 0.1 on one rank (the K~ PC ICC(0)), 0.3 on more (Jacobi)", &o->active_set_inexact_rtol));
  o->active_set_inexact_coulomb_rtol = 3e-2;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-active_set_inexact_coulomb_rtol", "Active-set formulation with friction: once the sets hold but the slip directions and thresholds still move, CG reduces the residual by this factor only (an inexact Newton; the last solves go to -contact_tol; 0: every such solve to -contact_tol)", &o->active_set_inexact_coulomb_rtol));
  o->active_set_block = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-active_set_block_matrix", "Active-set formulation: the CG's products with K~ from a copy of it in symmetric block storage (SBAIJ, one block per pair of vertices, the upper triangle only: about 0.4 of the bytes an AIJ product reads, and the copy's memory, about 0.4 of K~'s); 0 keeps K~'s AIJ", &o->active_set_block));
  o->active_set_monitor = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-active_set_monitor", "Active-set formulation: print each iteration, the nodes that changed set and the CG iterations", &o->active_set_monitor));
  PetscCheck(o->active_set_inexact_coulomb_rtol >= 0 && o->active_set_inexact_coulomb_rtol < 1, comm, PETSC_ERR_USER_INPUT, "-active_set_inexact_coulomb_rtol %g must be in [0, 1): it is CG's relative residual reduction while the slip directions and thresholds move (0: every solve to -contact_tol)", (double)o->active_set_inexact_coulomb_rtol);
  PetscCheck(o->active_set_max_it >= 1, comm, PETSC_ERR_USER_INPUT, "-active_set_max_it %" PetscInt_FMT " must be >= 1", o->active_set_max_it);
  PetscCheck(o->active_set_inexact_rtol >= 0 && o->active_set_inexact_rtol < 1, comm, PETSC_ERR_USER_INPUT, "-active_set_inexact_rtol %g must be in [0, 1): it is CG's relative residual reduction while nodes change set (0: every solve to -contact_tol)", (double)o->active_set_inexact_rtol);
  PetscFunctionReturn(0);
}

static PetscErrorCode ActiveSetDestroy(MMContact ct)
{
  MMActiveSet *as = MMActiveSetData(ct);

  PetscFunctionBeginUser;
  PetscCall(MMActiveSetDestroy(as));
  PetscCall(VecDestroy(&as->kept_diag));
  PetscCall(PetscFree(ct->data));
  PetscFunctionReturn(0);
}

/* K~, its PC (a factor with -contact_K_pc_type lu) and diag(K~) swapped with the kept ones of the
 * previous dt: going back to it sets nothing up again. */
static PetscErrorCode ActiveSetSwapKept(MMContact ct, PetscReal dt, PetscBool *hit)
{
  Vec        diag = MMActiveSetData(ct)->ct_diag;

  PetscFunctionBeginUser;
  PetscCall(MMContactSwapKeptOperator(ct, &ct->kt.ksp));
  MMActiveSetData(ct)->ct_diag = MMActiveSetData(ct)->kept_diag;
  MMActiveSetData(ct)->kept_diag  = diag;
  /* a first swap: the buffers of the new dt are made here, as MMActiveSetSetUp made the first ones */
  if (!ct->kt.ksp) PetscCall(MMKtCreate(ct, PETSC_TRUE, MMKtDefaultPC(PetscObjectComm((PetscObject)ct->dm))));
  if (!MMActiveSetData(ct)->ct_diag) PetscCall(VecDuplicate(ct->qp.b, &MMActiveSetData(ct)->ct_diag));
  *hit = (PetscBool)(ct->qp.A && ct->Kt_dt == dt);
  PetscFunctionReturn(0);
}

/* -contact_formulation auto's model of this formulation (docs/scaling.md, "The formulation chosen by
 * cost"), fitted on 1 and 2 ranks over 1.3k to 115k dofs, the linear law and svk, steps accepted
 * by their certificate: no factorization; a step is CG iterations, whose number grows with
 * c_p dt / h_c' (the conditioning of K~ on the free dofs) and with the friction sets' changes. It cannot carry a friction corner's two Coulomb laws, nor contact pairs that slide
 * (-contact_pairs_sliding large keeps K~ on one pattern). */
static PetscErrorCode ActiveSetCost(MMContact ct, const MMCostInput *in, MMCost *cost)
{
  static const MMCostModel model[2] = {MM_COST_ACTIVE_SET_2D, MM_COST_ACTIVE_SET_3D}; /* scripts/cost_model_fit.py --write */

  PetscFunctionBeginUser;
  MMCostEvaluate(&model[in->dim == 3], in, cost);
  if ((in->friction && in->n_fc) || ct->opt.pairs_sliding == MM_PAIRS_SLIDING_LARGE) cost->setup = PETSC_INFINITY;
  PetscFunctionReturn(0);
}

static const MMContactOps ActiveSetOps = {
  .setfromoptions   = ActiveSetSetFromOptions,
  .setup            = MMActiveSetSetUp,
  .setoperator      = MMActiveSetSetOperator,
  .solve            = ActiveSetSolveStep,
  .solvecontactdofs = ActiveSetSolveStep,
  .recover          = ActiveSetContactForce,
  .setthresholds    = MMActiveSetSetThresholds,
  .solvecoulombdofs = ActiveSetSolveCoulomb,
  .getstepksp       = ActiveSetGetStepKSP,
  .swapkept         = ActiveSetSwapKept,
  .getnodestate     = ActiveSetGetNodeState,
  .setnodestate     = ActiveSetSetNodeState,
  .getproducts      = ActiveSetGetProducts,
  .cost             = ActiveSetCost,
  .destroy          = ActiveSetDestroy,
};

PetscErrorCode MMContactCreate_ActiveSet(MMContact ct)
{
  MMActiveSet *as;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&as));
  ct->data = as;
  ct->ops  = &ActiveSetOps;
  PetscFunctionReturn(0);
}
