/* The contact set against a rigid plane: frames, gaps, bounds, and the exact per-step contact solve.
 *
 * Each step solves the bound-constrained QP  min 1/2 w.K~w - b.w  s.t.  w_c <= g  with SNESVI
 * (vinewtonrsls by default, prefix -contact_), condensed on the contact dofs by default. The friction
 * loop will wrap MMContactSolve: it only changes the right-hand side and the tangential bounds. */
#include <petscsf.h>
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "contact.h"
#include "mesh.h"

/* ---------------------------------------------------------------- a bound-constrained QP as a SNESVI */

/* LU with MUMPS: the default of every linear solver here, options still apply on top. */
static PetscErrorCode KSPSetDefaultLU(KSP ksp)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

/* What each exact solve is for, by options prefix, so that a refusal says which solve it is, and
 * whether its matrix is symmetric, so that Cholesky applies. */
typedef struct {
  const char *prefix, *purpose;
  PetscBool   symmetric;
} ExactSolve;

static ExactSolve ExactSolveInfo(const char prefix[])
{
  const ExactSolve known[] = {
    {"contact_K_", "K~ = K + 4/dt^2 M* is factored once per dt: the condensed contact builds its Delassus operator from the factor, and every step (also with -contact 0) solves with it", PETSC_TRUE},
    {"mass_",      "the initial acceleration solves M* a0 = L - K u0 + f_c0", PETSC_TRUE},
    {"sliding_",   "the static sliding state solves its (nonsymmetric) linear system", PETSC_FALSE},
  };
  const ExactSolve other = {prefix, "this solve", PETSC_FALSE};
  for (size_t i = 0; i < sizeof(known) / sizeof(known[0]); ++i) {
    PetscBool same;
    if (!PetscStrcmp(prefix, known[i].prefix, &same) && same) return known[i];
  }
  return other;
}

/* Solves the energy audit relies on, and the Delassus operator built from K~'s factor, must be
 * exact: only a complete factorization will do. An iterative or incomplete PC would fail late and
 * obscurely (no getfactoredmatrix method, an energy audit failure), or, for a0, not at all. */
static PetscErrorCode KSPCheckDirect(KSP ksp)
{
  PC          pc;
  PCType      type;
  PetscBool   lu, cholesky;
  const char *prefix;
  ExactSolve  info;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  info = ExactSolveInfo(prefix ? prefix : "");
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &cholesky));
  if (lu || (cholesky && info.symmetric)) PetscFunctionReturn(0);
  PetscCall(PCGetType(pc, &type));
  SETERRQ(PetscObjectComm((PetscObject)ksp), PETSC_ERR_USER_INPUT, "-%spc_type %s is not supported: %s, and this solve must be exact. Use -%spc_type lu (the default, with MUMPS)%s: iterative solvers and incomplete factorizations are not supported for it yet", info.prefix, type, info.purpose, info.prefix, info.symmetric ? " or cholesky" : "");
}

static PetscErrorCode KSPCheckDirectPreSolve(KSP ksp, Vec b, Vec x, void *ptr)
{
  PetscFunctionBeginUser;
  PetscCall(KSPCheckDirect(ksp));
  PetscFunctionReturn(0);
}

/* A solve that must be exact: LU with MUMPS by default, and any -PREFIX_pc_type that is not a
 * complete factorization refused when it solves (after KSPSetFromOptions). */
PetscErrorCode MMKSPSetDirect(KSP ksp)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetDefaultLU(ksp));
  PetscCall(KSPSetPreSolve(ksp, KSPCheckDirectPreSolve, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode QPResidual(SNES snes, Vec x, Vec f, void *ptr)
{
  MMBoundQP *qp = (MMBoundQP *)ptr;

  PetscFunctionBeginUser;
  PetscCall(MatMult(qp->A, x, f));
  PetscCall(VecAXPY(f, -1.0, qp->b));
  PetscFunctionReturn(0);
}

/* The matrix is constant: nothing to recompute, so the factorization is reused whenever SNES can.
 * Only a Jacobian that is a copy of A (see QPSetOperator) is refreshed from A. */
static PetscErrorCode QPJacobian(SNES snes, Vec x, Mat J, Mat P, void *ptr)
{
  MMBoundQP *qp = (MMBoundQP *)ptr;

  PetscFunctionBeginUser;
  if (J != qp->A) PetscCall(MatCopy(qp->A, J, SAME_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

/* The Jacobian SNES gets for A. vinewtonrsls only takes submatrices of it, so A itself will do.
 * vinewtonssls overwrites its Jacobian in place with the semismooth one, Da + Db J (row scaling
 * and diagonal shift): given A, it would corrupt the operator of the residual, iteration after
 * iteration, and never converge. It gets a copy of A instead, refreshed by QPJacobian. */
static PetscErrorCode QPSetOperator(SNES snes, MMBoundQP *qp)
{
  Mat         J;
  PetscObject source = NULL;
  PetscBool   ssls;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONSSLS, &ssls));
  PetscCall(SNESGetJacobian(snes, &J, NULL, NULL, NULL));
  if (!ssls) {
    if (J != qp->A) PetscCall(SNESSetJacobian(snes, qp->A, qp->A, QPJacobian, qp));
    PetscFunctionReturn(0);
  }
  if (J) PetscCall(PetscObjectQuery((PetscObject)J, "MMQPOperator", &source));
  if (J && source == (PetscObject)qp->A) PetscFunctionReturn(0);
  PetscCall(MatDuplicate(qp->A, MAT_COPY_VALUES, &J));
  PetscCall(PetscObjectCompose((PetscObject)J, "MMQPOperator", (PetscObject)qp->A));
  PetscCall(SNESSetJacobian(snes, J, J, QPJacobian, qp));
  PetscCall(MatDestroy(&J));
  PetscFunctionReturn(0);
}

/* Warm-started solves start near the answer, where a relative test cannot be met: also accept
 * ||F|| <= rtol_b ||b||, which is the solver's accuracy on this linear problem. */
static PetscErrorCode QPConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ptr)
{
  MMBoundQP *qp = (MMBoundQP *)ptr;

  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (*reason == SNES_CONVERGED_ITERATING && fnorm <= qp->rtol_b * qp->bnorm) *reason = SNES_CONVERGED_FNORM_ABS;
  PetscFunctionReturn(0);
}

/* Only the VI Newton methods honour bounds. vinewtonssls (Fischer-Burmeister) is refused with
 * friction: PETSc's semismooth Jacobian uses a fixed cut-off (|a|, |b| < 1e-6 gives the
 * derivative 1/2) which, at the weakly active tangential bounds of a stick/slip transition, turns
 * its convergence sublinear (D1 with -mu 0.2 does not converge in 3000 iterations). */
static PetscErrorCode CheckQPSolverType(SNES snes, PetscReal mu)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)snes);
  PetscBool   rsls, ssls;
  SNESType    type;
  const char *prefix;

  PetscFunctionBeginUser;
  PetscCall(SNESGetType(snes, &type));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONRSLS, &rsls));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONSSLS, &ssls));
  PetscCheck(rsls || ssls, comm, PETSC_ERR_USER_INPUT, "-%ssnes_type %s is not supported: the contact problem is a bound-constrained VI. Use -%ssnes_type vinewtonrsls (the default) or, without friction, vinewtonssls", prefix, type, prefix);
  PetscCheck(!ssls || mu == 0, comm, PETSC_ERR_USER_INPUT, "-%ssnes_type vinewtonssls is not supported with friction (-mu %g): at stick/slip transitions it converges too slowly to be usable. Use -%ssnes_type vinewtonrsls (the default)", prefix, (double)mu, prefix);
  PetscFunctionReturn(0);
}

/* mu: the friction coefficient of the problem, 0 when its bounds are on normal dofs only. */
static PetscErrorCode CreateQPSolver(MPI_Comm comm, const char prefix[], MMBoundQP *qp, PetscReal mu, SNES *snes)
{
  KSP            ksp;
  SNESLineSearch ls;
  Vec            r;

  PetscFunctionBeginUser;
  PetscCall(SNESCreate(comm, snes));
  PetscCall(SNESSetOptionsPrefix(*snes, prefix));
  PetscCall(SNESSetType(*snes, SNESVINEWTONRSLS));
  PetscCall(MatCreateVecs(qp->A, &r, NULL));
  PetscCall(SNESSetFunction(*snes, r, QPResidual, qp));
  PetscCall(VecDestroy(&r));
  PetscCall(SNESSetJacobian(*snes, qp->A, qp->A, QPJacobian, qp));
  PetscCall(SNESSetConvergenceTest(*snes, QPConverged, qp, NULL));
  PetscCall(SNESSetTolerances(*snes, PETSC_DEFAULT, 1e-12, 0.0, 100, PETSC_DEFAULT));
  /* a quadratic problem: the full projected Newton step is the right one */
  PetscCall(SNESGetLineSearch(*snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCall(SNESGetKSP(*snes, &ksp));
  /* the SNES checks its own residual: any linear solver that converges will do here */
  PetscCall(KSPSetDefaultLU(ksp));
  PetscCall(SNESSetFromOptions(*snes));
  PetscCall(CheckQPSolverType(*snes, mu));
  PetscCall(QPSetOperator(*snes, qp));
  PetscFunctionReturn(0);
}

/* Solves A x = b with the solver's bounds; x is the initial guess on entry. */
static PetscErrorCode SolveQP(SNES snes, MMBoundQP *qp, Vec x, PetscInt *its)
{
  SNESConvergedReason reason;
  const char         *prefix;

  PetscFunctionBeginUser;
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(VecNorm(qp->b, NORM_2, &qp->bnorm));
  qp->bnorm = PetscMax(qp->bnorm, PETSC_SMALL);
  PetscCall(SNESSolve(snes, NULL, x));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, its));
  PetscCheck(reason > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_NOT_CONVERGED, "The contact solver (%s) did not converge: %s after %" PetscInt_FMT " iterations. Run with -%ssnes_monitor -%ssnes_converged_reason to see why",
             prefix, SNESConvergedReasons[reason], *its, prefix, prefix);
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the condensed formulation
 * The condensed dofs are the normal dof of each contact node and, with friction, its tangential
 * dofs. With z = K~^{-1} b and the Delassus operator W = E^T K~^{-1} E on them, the step solution
 * is w = z - K~^{-1} E rho for contact reactions rho = (lambda_n, -t): lambda_n >= 0 the normal
 * reaction, t the tangential force on the body. The step problem is the box-constrained VI
 *   W rho - q  complementary to  lambda_n >= 0,  |rho_t| <= s,
 * with q_n = z_n - g (the gap left) and q_t = z_t - (u_t^n + dt/2 v_t^n), which makes the
 * tangential residual -dt/2 times the slip velocity: Tresca friction with thresholds s, exactly.
 * K~ is factored once per dt; a step costs two solves with that factor and a VI on the contact
 * dofs, whatever the contact set does. */

static PetscErrorCode FactorStepMatrix(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (!ct->ksp_K) {
    PetscCall(MatCreateVecs(ct->qp.A, &ct->z, &ct->rhs_c));
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)ctx->op.dm), &ct->ksp_K));
    PetscCall(KSPSetOptionsPrefix(ct->ksp_K, "contact_K_"));
    PetscCall(MMKSPSetDirect(ct->ksp_K));
    PetscCall(KSPSetFromOptions(ct->ksp_K));
    /* now, not at the first solve: the Delassus operator is built from the factor before it */
    PetscCall(KSPCheckDirect(ct->ksp_K));
  }
  PetscCall(KSPSetOperators(ct->ksp_K, ct->qp.A, ct->qp.A));
  PetscCall(KSPSetUp(ct->ksp_K));
  PetscFunctionReturn(0);
}

/* Columns of K~^{-1} E, a block at a time through the factor, restricted to the condensed rows. */
static PetscErrorCode AssembleDelassus(MMCtx *ctx)
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

static PetscErrorCode CreateCondensedSolver(MMCtx *ctx)
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
  PetscCall(CreateQPSolver(PetscObjectComm((PetscObject)ctx->op.dm), "contact_", &ct->qpc, ct->ncomp > 1 ? ctx->opt.mu : 0, &ct->snes));
  PetscCall(SNESVISetVariableBounds(ct->snes, ct->rho_lo, ct->rho_hi));
  PetscFunctionReturn(0);
}

/* 3D friction, the isotropic Coulomb disk |rho_t| <= s: each contact node sticks (rho_t free, so
 * the VI enforces zero slip) or slips (rho_t = s d fixed, d its slip direction); a node without
 * normal force carries no tangential force. The friction loop updates s, d and the states until
 * they stop changing (MMContactUpdateSlip), so the disk is exact, not a square. */
static PetscErrorCode SetDiskBounds(MMContact *ct, Vec s)
{
  const PetscScalar *sa;
  PetscScalar       *lo, *hi;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(s, &sa));
  PetscCall(VecGetArray(ct->rho_lo, &lo));
  PetscCall(VecGetArray(ct->rho_hi, &hi));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal sk = PetscRealPart(sa[k]);
    /* unknowns in the node's (d, d_perp) basis: a slipping node is a 1D Tresca box along d */
    if (sk <= 0) lo[3 * k + 1] = hi[3 * k + 1] = lo[3 * k + 2] = hi[3 * k + 2] = 0;
    else if (ct->slipping[k]) {
      lo[3 * k + 1] = -sk;
      hi[3 * k + 1] = sk;
      lo[3 * k + 2] = hi[3 * k + 2] = 0;
    } else {
      lo[3 * k + 1] = lo[3 * k + 2] = PETSC_NINFINITY;
      hi[3 * k + 1] = hi[3 * k + 2] = PETSC_INFINITY;
    }
  }
  PetscCall(VecRestoreArray(ct->rho_hi, &hi));
  PetscCall(VecRestoreArray(ct->rho_lo, &lo));
  PetscCall(VecRestoreArrayRead(s, &sa));
  PetscFunctionReturn(0);
}

/* P: the condensed dofs of each node from its (n, d, d_perp) basis to the frame's (n, t1, t2). */
static PetscErrorCode AssembleSlipRotation(MMContact *ct)
{
  PetscInt cstart;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(ct->W, &cstart, NULL));
  if (!ct->P) PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)ct->W), 3 * ct->n_local, 3 * ct->n_local, PETSC_DETERMINE, PETSC_DETERMINE, 2, NULL, 0, NULL, &ct->P));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt  r   = cstart + 3 * k;
    const PetscReal *d  = &ct->slip_dir[2 * k];
    const PetscReal dd  = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]);
    const PetscReal c   = dd > 0 ? d[0] / dd : 1, sn = dd > 0 ? d[1] / dd : 0;
    PetscCall(MatSetValue(ct->P, r, r, 1.0, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 1, r + 1, c, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 1, r + 2, -sn, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 2, r + 1, sn, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 2, r + 2, c, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(ct->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatPtAP(ct->W, ct->P, ct->Wr ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, 1.0, &ct->Wr));
  PetscFunctionReturn(0);
}

/* After a solve with thresholds s, the return mapping of each node: the trial force
 * rho_t + (dt/2) sigma_t / W_tt (its reaction plus its slip over its tangential compliance)
 * slips along itself when outside the disk, and sticks inside it. Returns the number of
 * stick/slip switches and the largest change of a slip direction. */
PetscErrorCode MMContactUpdateSlip(MMCtx *ctx, Vec s, Vec sigma, PetscInt *switches, PetscReal *dchange)
{
  MMContact         *ct = &ctx->contact;
  const PetscScalar *sa, *ra, *va, *wd;
  const PetscInt    *in;
  PetscInt           rstart, nsw = 0;
  PetscReal          dmax = 0;

  PetscFunctionBeginUser;
  *switches = 0;
  *dchange  = 0;
  if (ct->ncomp != 3) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(sigma, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(s, &sa));
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  PetscCall(VecGetArrayRead(sigma, &va));
  PetscCall(VecGetArrayRead(ct->Wdiag, &wd));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal sk = PetscRealPart(sa[k]);
    const PetscReal kt = 0.5 * ct->Kt_dt * 2.0 / (PetscRealPart(wd[3 * k + 1]) + PetscRealPart(wd[3 * k + 2]));
    const PetscReal tr[2] = {PetscRealPart(ra[3 * k + 1]) + kt * PetscRealPart(va[in[k] + 1 - rstart]), PetscRealPart(ra[3 * k + 2]) + kt * PetscRealPart(va[in[k] + 2 - rstart])};
    const PetscReal tn = PetscSqrtReal(tr[0] * tr[0] + tr[1] * tr[1]);
    const PetscBool slip = (PetscBool)(sk > 0 && tn > sk * (1 + 1e-10));
    PetscReal      *d = &ct->slip_dir[2 * k];

    if (sk <= 0) continue;
    if (slip != ct->slipping[k]) ++nsw;
    ct->slipping[k] = slip;
    if (slip) {
      if (d[0] != 0 || d[1] != 0) dmax = PetscMax(dmax, PetscSqrtReal(PetscSqr(tr[0] / tn - d[0]) + PetscSqr(tr[1] / tn - d[1])));
      d[0] = tr[0] / tn;
      d[1] = tr[1] / tn;
    }
  }
  PetscCall(VecRestoreArrayRead(ct->Wdiag, &wd));
  PetscCall(VecRestoreArrayRead(sigma, &va));
  PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  PetscCall(VecRestoreArrayRead(s, &sa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(&nsw, switches, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)sigma)));
  PetscCall(MPIU_Allreduce(&dmax, dchange, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)sigma)));
  PetscFunctionReturn(0);
}

/* Friction thresholds s (one per contact node): |rho_t| <= s in the next solves (2D: a box, exact;
 * 3D: the disk through the stick/slip states). */
PetscErrorCode MMContactSetThresholds(MMCtx *ctx, Vec s)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (ct->ncomp == 3) {
    PetscCall(AssembleSlipRotation(ct));
    PetscCall(SetDiskBounds(ct, s));
    PetscFunctionReturn(0);
  }
  for (PetscInt c = 1; c < ct->ncomp; ++c) {
    PetscCall(VecStrideScatter(s, c, ct->rho_hi, INSERT_VALUES));
    PetscCall(VecStrideScatter(s, c, ct->rho_lo, INSERT_VALUES));
    PetscCall(VecStrideScale(ct->rho_lo, c, -1.0));
  }
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

/* w = z - K~^{-1} E rho, with z = K~^{-1} b and rho from the VI, warm-started from the last solve. */
static PetscErrorCode SolveCondensed(MMCtx *ctx, Vec b, Vec w)
{
  MMContact *ct = &ctx->contact;
  Vec        rc;

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
  if (!ct->enabled) {
    PetscCall(VecCopy(ct->z, w));
    PetscFunctionReturn(0);
  }
  PetscCall(CondensedRHS(ctx));
  if (ct->ncomp == 3) {
    /* the VI in each node's (n, d, d_perp) basis: rho = P rho_r */
    if (!ct->rho_r) PetscCall(VecDuplicate(ct->rho, &ct->rho_r));
    PetscCall(VecCopy(ct->qpc.b, ct->z_c));
    PetscCall(MatMultTranspose(ct->P, ct->z_c, ct->qpc.b));
    PetscCall(MatMultTranspose(ct->P, ct->rho, ct->rho_r));
    ct->qpc.A = ct->Wr;
    PetscCall(QPSetOperator(ct->snes, &ct->qpc));
  }
  {
    Vec x = ct->ncomp == 3 ? ct->rho_r : ct->rho;
    /* a warm start must lie in the box of the current thresholds */
    PetscCall(VecPointwiseMax(x, x, ct->rho_lo));
    PetscCall(VecPointwiseMin(x, x, ct->rho_hi));
    PetscCall(SolveQP(ct->snes, &ct->qpc, x, &ct->vi_its));
    PetscCall(SnapActiveToBounds(ct, ct->qpc.A, x));
    if (ct->ncomp == 3) PetscCall(MatMult(ct->P, ct->rho_r, ct->rho));
  }
  PetscCall(VecZeroEntries(ct->rhs_c));
  PetscCall(VecGetSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(ct->rhs_c, ct->is_cond, &rc));
  PetscCall(KSPSolve(ct->ksp_K, ct->rhs_c, w));
  PetscCall(VecAXPY(w, 1.0, ct->z));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- contact set and frames */

/* Orthonormal frame (nu, tau_1[, tau_2]) with nu = -n the body's outward normal. */
static PetscErrorCode BuildFrame(MMCtx *ctx)
{
  PetscInt   dim = ctx->op.dim;
  PetscReal(*F)[MM_MAX_DIM] = ctx->contact.frame;
  const PetscReal *n = ctx->opt.obstacle_normal;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(ctx->contact.frame, sizeof(ctx->contact.frame)));
  for (PetscInt d = 0; d < dim; ++d) F[0][d] = -n[d];
  if (dim == 2) {
    F[1][0] = -F[0][1];
    F[1][1] = F[0][0];
  } else {
    /* tau_1 = e x nu / |e x nu| with e the axis least aligned with nu */
    PetscInt  k = 0;
    PetscReal e[3] = {0, 0, 0}, nrm;
    for (PetscInt d = 1; d < 3; ++d)
      if (PetscAbsReal(F[0][d]) < PetscAbsReal(F[0][k])) k = d;
    e[k]    = 1;
    F[1][0] = e[1] * F[0][2] - e[2] * F[0][1];
    F[1][1] = e[2] * F[0][0] - e[0] * F[0][2];
    F[1][2] = e[0] * F[0][1] - e[1] * F[0][0];
    nrm     = PetscSqrtReal(PetscSqr(F[1][0]) + PetscSqr(F[1][1]) + PetscSqr(F[1][2]));
    for (PetscInt d = 0; d < 3; ++d) F[1][d] /= nrm;
    F[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    F[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    F[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  }
  PetscFunctionReturn(0);
}

/* Marks the vertices of the contact faces, agreed over ranks through the point SF: a vertex can
 * sit on a rank that does not hold the face it belongs to. */
static PetscErrorCode MarkContactVertices(MMCtx *ctx, PetscInt **mark, Vec area)
{
  Vec          aloc;
  PetscScalar *aa;
  DM              dm = ctx->op.dm;
  DMLabel         label;
  IS              vis, pis;
  PetscInt        pStart, pEnd, vStart, vEnd, n, nv;
  const PetscInt *pts, *vals;
  PetscInt       *root;
  PetscSF         sf;

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, ctx->opt.contact_name, &label));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscCalloc1(pEnd - pStart, mark));
  PetscCall(PetscCalloc1(pEnd - pStart, &root));
  PetscCall(DMLabelGetValueIS(label, &vis));
  PetscCall(ISGetLocalSize(vis, &nv));
  PetscCall(ISGetIndices(vis, &vals));
  PetscCall(DMGetLocalVector(ctx->out.dm_scalar, &aloc));
  PetscCall(VecZeroEntries(aloc));
  PetscCall(VecGetArray(aloc, &aa));
  for (PetscInt i = 0; i < nv; ++i) {
    PetscCall(DMLabelGetStratumIS(label, vals[i], &pis));
    if (!pis) continue;
    PetscCall(ISGetLocalSize(pis, &n));
    PetscCall(ISGetIndices(pis, &pts));
    for (PetscInt j = 0; j < n; ++j) {
      PetscInt *closure = NULL, ncl, h;
      PetscCall(DMPlexGetPointHeight(dm, pts[j], &h));
      PetscCheck(h >= 1, PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "Contact boundary \"%s\" contains cells: it must be a Physical Curve (2D) or Physical Surface (3D)", ctx->opt.contact_name);
      PetscReal farea = 0;
      PetscInt  dim   = ctx->op.dim;
      if (h == 1) PetscCall(DMPlexComputeCellGeometryFVM(dm, pts[j], &farea, NULL, NULL));
      PetscCall(DMPlexGetTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &closure));
      for (PetscInt k = 0; k < ncl; ++k) {
        PetscInt off, end;
        (*mark)[closure[2 * k] - pStart] = 1;
        if (closure[2 * k] < vStart || closure[2 * k] >= vEnd) continue;
        PetscCall(DMPlexGetPointLocal(ctx->out.dm_scalar, closure[2 * k], &off, &end));
        aa[off] += farea / dim; /* int_F phi_i for P1 on a simplex face */
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &closure));
    }
    PetscCall(ISRestoreIndices(pis, &pts));
    PetscCall(ISDestroy(&pis));
  }
  PetscCall(ISRestoreIndices(vis, &vals));
  PetscCall(ISDestroy(&vis));
  PetscCall(VecRestoreArray(aloc, &aa));
  PetscCall(VecZeroEntries(area));
  PetscCall(DMLocalToGlobal(ctx->out.dm_scalar, aloc, ADD_VALUES, area));
  PetscCall(DMRestoreLocalVector(ctx->out.dm_scalar, &aloc));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscArraycpy(root, *mark, pEnd - pStart));
  PetscCall(PetscSFReduceBegin(sf, MPIU_INT, *mark, root, MPI_MAX));
  PetscCall(PetscSFReduceEnd(sf, MPIU_INT, *mark, root, MPI_MAX));
  PetscCall(PetscSFBcastBegin(sf, MPIU_INT, root, *mark, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_INT, root, *mark, MPI_REPLACE));
  PetscCall(PetscArraycpy(*mark, root, pEnd - pStart));
  PetscCall(PetscFree(root));
  PetscFunctionReturn(0);
}

/* h_c': the smallest diameter of the cells touching a contact node (Theorem 4.2). */
static PetscErrorCode ContactLayerDiameter(MMCtx *ctx, const PetscInt mark[])
{
  DM        dm = ctx->op.dm;
  PetscInt  cStart, cEnd, pStart, cdim;
  PetscReal hmin = PETSC_MAX_REAL;
  Vec       X;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscScalar *xc = NULL;
    PetscInt     nx, *closure = NULL, ncl;
    PetscBool    touches = PETSC_FALSE;
    PetscReal    diam    = 0;

    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &closure));
    for (PetscInt k = 0; k < ncl; ++k) {
      PetscInt dof;
      PetscCall(DMPlexGetPointDepth(dm, closure[2 * k], &dof));
      if (dof == 0 && mark[closure[2 * k] - pStart]) touches = PETSC_TRUE;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &closure));
    if (!touches) continue;
    PetscCall(DMPlexVecGetClosure(dm, NULL, X, c, &nx, &xc));
    for (PetscInt i = 0; i < nx / cdim; ++i)
      for (PetscInt j = i + 1; j < nx / cdim; ++j) {
        PetscReal d2 = 0;
        for (PetscInt d = 0; d < cdim; ++d) d2 += PetscSqr(PetscRealPart(xc[i * cdim + d] - xc[j * cdim + d]));
        diam = PetscMax(diam, PetscSqrtReal(d2));
      }
    PetscCall(DMPlexVecRestoreClosure(dm, NULL, X, c, &nx, &xc));
    hmin = PetscMin(hmin, diam);
  }
  PetscCall(MPIU_Allreduce(&hmin, &ctx->contact.h_c, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/* Index sets of the owned contact dofs, the gaps, and the rotation Q (identity off the contact set). */
static PetscErrorCode BuildContactDofs(MMCtx *ctx, const PetscInt mark[], Vec area)
{
  PetscInt           astart;
  const PetscScalar *av;
  PetscReal         *nodal_area;
  DM           dm = ctx->op.dm;
  MMContact   *ct = &ctx->contact;
  PetscSection gs, ls, cs;
  PetscInt     vStart, vEnd, pStart, dim = ctx->op.dim, n, rstart, rend, nc = 0, *in, *it, *is;
  PetscReal   *gap;
  Vec          X, g;
  const PetscScalar *x;
  PetscInt    *is_contact_dof; /* 0: other, 1: contact dof, 2: contact-normal dof */
  MPI_Comm     comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMCreateGlobalVector(dm, &g));
  PetscCall(VecGetLocalSize(g, &n));
  PetscCall(VecGetOwnershipRange(g, &rstart, &rend));
  PetscCall(VecDestroy(&g));
  PetscCall(PetscMalloc4(n, &in, n, &it, n, &is, n, &gap));
  PetscCall(PetscCalloc1(n, &is_contact_dof));
  PetscCall(PetscMalloc1(n, &ct->scalar_index));
  PetscCall(PetscMalloc1(n, &ct->vertex));
  PetscCall(PetscMalloc1(n, &nodal_area));
  PetscCall(VecGetOwnershipRange(area, &astart, NULL));
  PetscCall(VecGetArrayRead(area, &av));
  PetscCall(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, dim, NULL, 0, NULL, &ctx->op.Q));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, cdof, xoff;
    if (!mark[v - pStart]) continue;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    PetscCheck(cdof == 0, comm, PETSC_ERR_USER_INPUT, "A node of the contact boundary \"%s\" at (%g, %g) is also on a Dirichlet boundary. Contact dofs must be free: separate the two physical groups", ctx->opt.contact_name, (double)PetscRealPart(x[xoff]), (double)PetscRealPart(x[xoff + 1]));
    /* g_i = (x_i - p).n, the distance to the plane along nu = -n */
    gap[nc] = 0;
    for (PetscInt d = 0; d < dim; ++d) gap[nc] += (PetscRealPart(x[xoff + d]) - ctx->opt.obstacle_point[d]) * ctx->opt.obstacle_normal[d];
    in[nc] = goff;
    {
      PetscInt sstart, send;
      PetscCall(DMPlexGetPointGlobal(ctx->out.dm_scalar, v, &sstart, &send));
      ct->scalar_index[nc] = sstart;
      ct->vertex[nc]       = v;
      nodal_area[nc]       = PetscRealPart(av[sstart - astart]);
    }
    for (PetscInt d = 1; d < dim; ++d) it[nc * (dim - 1) + d - 1] = goff + d;
    for (PetscInt d = 0; d < dim; ++d) {
      is_contact_dof[goff - rstart + d] = 1;
      for (PetscInt e = 0; e < dim; ++e) PetscCall(MatSetValue(ctx->op.Q, goff + d, goff + e, ct->frame[e][d], INSERT_VALUES));
    }
    ++nc;
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecRestoreArrayRead(area, &av));
  {
    PetscInt ns = 0;
    for (PetscInt i = 0; i < n; ++i)
      if (!is_contact_dof[i]) PetscCall(MatSetValue(ctx->op.Q, rstart + i, rstart + i, 1.0, INSERT_VALUES));
    /* the star dofs: all but the contact-normal ones (tangential contact dofs keep their mass) */
    for (PetscInt k = 0; k < nc; ++k) is_contact_dof[in[k] - rstart] = 2;
    for (PetscInt i = 0; i < n; ++i)
      if (is_contact_dof[i] != 2) is[ns++] = rstart + i;
    PetscCall(ISCreateGeneral(comm, ns, is, PETSC_COPY_VALUES, &ct->is_star));
    ns = 0;
    for (PetscInt i = 0; i < n; ++i)
      if (!is_contact_dof[i]) is[ns++] = rstart + i;
    PetscCall(ISCreateGeneral(comm, ns, is, PETSC_COPY_VALUES, &ct->is_interior));
  }
  PetscCall(MatAssemblyBegin(ctx->op.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ctx->op.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(ISCreateGeneral(comm, nc, in, PETSC_COPY_VALUES, &ct->is_normal));
  PetscCall(ISCreateGeneral(comm, nc * (dim - 1), it, PETSC_COPY_VALUES, &ct->is_tangent));
  /* the condensed dofs, node by node: the normal one, and the tangential ones with friction */
  for (PetscInt k = 0; k < nc; ++k)
    for (PetscInt c = 0; c < ct->ncomp; ++c) is[k * ct->ncomp + c] = in[k] + c;
  PetscCall(ISCreateGeneral(comm, nc * ct->ncomp, is, PETSC_COPY_VALUES, &ct->is_cond));
  PetscCall(VecCreateMPI(comm, nc, PETSC_DETERMINE, &ct->gap));
  PetscCall(VecDuplicate(ct->gap, &ct->area));
  {
    PetscScalar *ga, *aa;
    PetscCall(VecGetArray(ct->gap, &ga));
    PetscCall(VecGetArray(ct->area, &aa));
    for (PetscInt k = 0; k < nc; ++k) {
      ga[k] = gap[k];
      aa[k] = nodal_area[k];
    }
    PetscCall(VecRestoreArray(ct->gap, &ga));
    PetscCall(VecRestoreArray(ct->area, &aa));
  }
  PetscCall(PetscFree(nodal_area));
  ct->n_local = nc;
  PetscCall(MPIU_Allreduce(&nc, &ct->n_global, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscCalloc1(nc, &ct->was_active));
  PetscCall(PetscCalloc2(nc, &ct->slipping, 2 * nc, &ct->slip_dir));
  PetscCall(PetscFree4(in, it, is, gap));
  PetscCall(PetscFree(is_contact_dof));
  PetscFunctionReturn(0);
}

/* Without contact: Q = I and every dof is a star dof. */
static PetscErrorCode BuildNoContact(MMCtx *ctx)
{
  Vec      g;
  PetscInt n, rstart;
  MPI_Comm comm = PetscObjectComm((PetscObject)ctx->op.dm);

  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(ctx->op.dm, &g));
  PetscCall(VecGetLocalSize(g, &n));
  PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
  PetscCall(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 1, NULL, 0, NULL, &ctx->op.Q));
  for (PetscInt i = rstart; i < rstart + n; ++i) PetscCall(MatSetValue(ctx->op.Q, i, i, 1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(ctx->op.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ctx->op.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ctx->contact.is_normal));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ctx->contact.is_tangent));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ctx->contact.is_cond));
  PetscCall(ISCreateStride(comm, n, rstart, 1, &ctx->contact.is_star));
  PetscCall(ISCreateStride(comm, n, rstart, 1, &ctx->contact.is_interior));
  PetscCall(VecCreateMPI(comm, 0, PETSC_DETERMINE, &ctx->contact.gap));
  PetscCall(VecDestroy(&g));
  ctx->contact.h_c = 0;
  PetscFunctionReturn(0);
}

/* Finds the contact nodes and builds Q; runs before the operators are assembled. */
PetscErrorCode MMContactSetUp(MMCtx *ctx)
{
  MMContact *ct = &ctx->contact;
  PetscInt  *mark;
  Vec        area;

  PetscFunctionBeginUser;
  ct->enabled     = ctx->opt.contact;
  ct->tol         = ctx->opt.contact_tol;
  ct->formulation = ctx->opt.contact_formulation;
  ct->ncomp       = ctx->opt.mu > 0 ? ctx->op.dim : 1;
  PetscCall(BuildFrame(ctx));
  if (!ct->enabled) {
    PetscCall(BuildNoContact(ctx));
    PetscFunctionReturn(0);
  }
  PetscCall(DMCreateGlobalVector(ctx->out.dm_scalar, &area));
  PetscCall(MarkContactVertices(ctx, &mark, area));
  PetscCall(BuildContactDofs(ctx, mark, area));
  PetscCall(ContactLayerDiameter(ctx, mark));
  PetscCall(PetscFree(mark));
  PetscCall(VecDestroy(&area));
  PetscCheck(ct->ncomp == 1 || ct->formulation == MM_CONTACT_CONDENSED, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_SUP, "Friction (-mu %g) needs -contact_formulation condensed", (double)ctx->opt.mu);
  PetscCheck(ct->n_global > 0, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_USER_INPUT, "The contact boundary \"%s\" has no nodes", ctx->opt.contact_name);
  PetscFunctionReturn(0);
}

/* Bounds on the whole w vector: w_c <= g on the normal dofs, free elsewhere. */
static PetscErrorCode SetBounds(MMContact *ct, Vec lower, Vec upper)
{
  Vec sub;

  PetscFunctionBeginUser;
  PetscCall(VecSet(lower, PETSC_NINFINITY));
  PetscCall(VecSet(upper, PETSC_INFINITY));
  PetscCall(VecGetSubVector(upper, ct->is_normal, &sub));
  PetscCall(VecCopy(ct->gap, sub));
  PetscCall(VecRestoreSubVector(upper, ct->is_normal, &sub));
  PetscFunctionReturn(0);
}

/* K~ = K + 4/dt^2 M*, assembled only when dt changes, with what the formulation builds on it: the
 * factor and the Delassus operator (condensed), or the bounds of the full VI. */
PetscErrorCode MMContactSetStepMatrix(MMCtx *ctx, PetscReal dt)
{
  MMContact *ct        = &ctx->contact;
  PetscBool  condensed = (PetscBool)(ct->formulation == MM_CONTACT_CONDENSED || !ct->enabled);

  PetscFunctionBeginUser;
  if (ct->qp.A && ct->Kt_dt == dt) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(ctx->log.assemble, 0, 0, 0, 0));
  if (!ct->qp.A) {
    PetscCall(MatDuplicate(ctx->op.K, MAT_COPY_VALUES, &ct->qp.A));
    PetscCall(MatCreateVecs(ct->qp.A, &ct->qp.b, NULL));
    ct->qp.rtol_b = ct->tol;
    if (!condensed) {
      PetscCall(VecDuplicate(ct->qp.b, &ct->lower));
      PetscCall(VecDuplicate(ct->qp.b, &ct->upper));
      PetscCall(CreateQPSolver(PetscObjectComm((PetscObject)ctx->op.dm), "contact_", &ct->qp, 0, &ct->snes));
      PetscCall(SetBounds(ct, ct->lower, ct->upper));
      PetscCall(SNESVISetVariableBounds(ct->snes, ct->lower, ct->upper));
    }
  } else PetscCall(MatCopy(ctx->op.K, ct->qp.A, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(ct->qp.A, 4.0 / (dt * dt), ctx->op.Mstar, SUBSET_NONZERO_PATTERN));
  ct->Kt_dt = dt;
  if (condensed) {
    PetscCall(FactorStepMatrix(ctx));
    if (ct->enabled) {
      PetscCall(AssembleDelassus(ctx));
      if (!ct->snes) PetscCall(CreateCondensedSolver(ctx));
      if (!ct->Wdiag) PetscCall(MatCreateVecs(ct->W, &ct->Wdiag, NULL));
      PetscCall(MatGetDiagonal(ct->W, ct->Wdiag));
    }
  }
  PetscCall(PetscLogEventEnd(ctx->log.assemble, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Solves the step problem K~ w = b + f_c with w_c <= g; w holds the initial guess on entry.
 * react returns f_c, the obstacle's force on the body (w-frame), on the contact dofs only,
 * recomputed from w whatever the formulation, so the energy audit checks the solve. */
PetscErrorCode MMContactSolve(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.contact_solve, 0, 0, 0, 0));
  if (ct->formulation == MM_CONTACT_CONDENSED || !ct->enabled) PetscCall(SolveCondensed(ctx, b, w));
  else {
    PetscCall(VecCopy(b, ct->qp.b));
    PetscCall(SolveQP(ct->snes, &ct->qp, w, &ct->vi_its));
  }
  PetscCall(MatMult(ct->qp.A, w, react));
  PetscCall(VecAXPY(react, -1.0, b));
  /* off the contact nodes the residual is solver noise, not a force */
  PetscCall(VecISSet(react, ct->is_interior, 0.0));
  if (ct->ncomp == 1) PetscCall(VecISSet(react, ct->is_tangent, 0.0));
  PetscCall(PetscLogEventEnd(ctx->log.contact_solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A given initial state that penetrates the obstacle is a wrong case (a plane on the wrong side, a
 * body placed inside it): projecting it would store elastic energy that launches the body. Refuse a
 * penetration deeper than -initial_penetration_tol h_c', naming the deepest node. */
static PetscErrorCode CheckInitialPenetration(MMCtx *ctx, Vec w)
{
  MMContact         *ct  = &ctx->contact;
  DM                 dm  = ctx->op.dm;
  PetscInt           dim = ctx->op.dim, rstart, deepest = -1;
  const PetscInt    *in;
  const PetscScalar *wa, *ga;
  struct {
    double depth;
    int    rank;
  } loc = {-PETSC_MAX_REAL, 0}, glob;
  PetscReal   x[MM_MAX_DIM] = {0, 0, 0};
  PetscMPIInt rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  loc.rank = rank;
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal depth = PetscRealPart(wa[in[k] - rstart] - ga[k]);
    if (depth > loc.depth) {
      loc.depth = depth;
      deepest   = k;
    }
  }
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  if (glob.depth <= ctx->opt.initial_penetration_tol * ct->h_c) PetscFunctionReturn(0);
  if (rank == glob.rank) {
    PetscSection cs;
    Vec          X;
    PetscInt     off;
    const PetscScalar *xa;
    PetscCall(DMGetCoordinateSection(dm, &cs));
    PetscCall(DMGetCoordinatesLocal(dm, &X));
    PetscCall(PetscSectionGetOffset(cs, ct->vertex[deepest], &off));
    PetscCall(VecGetArrayRead(X, &xa));
    for (PetscInt d = 0; d < dim; ++d) x[d] = PetscRealPart(xa[off + d]);
    PetscCall(VecRestoreArrayRead(X, &xa));
  }
  PetscCallMPI(MPI_Bcast(x, MM_MAX_DIM, MPIU_REAL, glob.rank, comm));
  /* C's formatting, not PETSc's, which writes 0 as "0." */
  char where[128];
  if (dim == 2) snprintf(where, sizeof(where), "(%g, %g)", (double)x[0], (double)x[1]);
  else snprintf(where, sizeof(where), "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]);
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "The initial state penetrates the obstacle: the deepest contact node, at %s, is %g inside it (-initial_penetration_tol %g h_c' = %g). Check -obstacle_point and the direction of -obstacle_normal (it points out of the obstacle, towards the body), and -u0_offset/-u0_gradient",
          where, glob.depth, (double)ctx->opt.initial_penetration_tol, (double)(ctx->opt.initial_penetration_tol * ct->h_c));
}

/* Consistent initial contact dofs (docs/method.md section 3, Initial state): with the other dofs fixed, the
 * massless normal dofs solve the quasi-static problem A_cc u_c = L_c - A_c* u*, u_c <= g. */
PetscErrorCode MMContactProjectInitial(MMCtx *ctx, Vec w)
{
  MMContact *ct = &ctx->contact;
  Vec        r, rc, wc;
  PetscInt   its;

  PetscFunctionBeginUser;
  if (ct->enabled) PetscCall(CheckInitialPenetration(ctx, w));
  if (!ct->enabled || ctx->opt.mass_type != MM_MASS_MODIFIED) PetscFunctionReturn(0);
  PetscCall(MatCreateSubMatrix(ctx->op.K, ct->is_normal, ct->is_normal, MAT_INITIAL_MATRIX, &ct->qp0.A));
  PetscCall(MatCreateVecs(ct->qp0.A, &ct->qp0.b, NULL));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->lower0));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->upper0));
  PetscCall(VecSet(ct->lower0, PETSC_NINFINITY));
  PetscCall(VecCopy(ct->gap, ct->upper0));
  ct->qp0.rtol_b = ct->tol;
  PetscCall(CreateQPSolver(PetscObjectComm((PetscObject)ctx->op.dm), "contact0_", &ct->qp0, 0, &ct->snes0));
  PetscCall(SNESVISetVariableBounds(ct->snes0, ct->lower0, ct->upper0));

  /* b0 = (L - lift - K w*)_c with the contact dofs zeroed in w* */
  PetscCall(VecDuplicate(w, &r));
  PetscCall(VecCopy(w, r));
  PetscCall(VecISSet(r, ct->is_normal, 0.0));
  PetscCall(VecDuplicate(w, &rc));
  PetscCall(MatMult(ctx->op.K, r, rc));
  PetscCall(VecAYPX(rc, -1.0, ctx->op.load));
  PetscCall(VecAXPY(rc, -1.0, ctx->op.lift));
  PetscCall(VecGetSubVector(rc, ct->is_normal, &wc));
  PetscCall(VecCopy(wc, ct->qp0.b));
  PetscCall(VecRestoreSubVector(rc, ct->is_normal, &wc));

  PetscCall(VecGetSubVector(w, ct->is_normal, &wc));
  PetscCall(VecPointwiseMin(wc, wc, ct->gap));
  PetscCall(SolveQP(ct->snes0, &ct->qp0, wc, &its));
  PetscCall(VecRestoreSubVector(w, ct->is_normal, &wc));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&rc));
  PetscFunctionReturn(0);
}

/* Per-node contact statistics of a state (w, react, sigma): sigma holds the velocity, whose
 * tangential components at a contact node are its slip velocity. */
typedef struct {
  PetscInt  active, switched, slipping, sticking;
  PetscReal force_normal, force_t[MM_MAX_DIM], max_penetration, coulomb;
} ContactStats;

static PetscErrorCode ContactStatistics(MMCtx *ctx, Vec w, Vec react, Vec sigma, PetscBool record_switches, ContactStats *st)
{
  MMContact         *ct = &ctx->contact;
  const PetscReal    mu = ctx->opt.mu, dt = ct->Kt_dt;
  /* slip is judged by the step's slip increment sigma dt/2 against h_c', like penetration */
  const PetscReal    vtol = 1e-9 * 2 * ct->h_c / dt;
  PetscInt           dim = ctx->op.dim, nc = ct->n_local, cnt[4] = {0, 0, 0, 0}, rstart;
  const PetscInt    *in;
  const PetscScalar *wa, *fa, *ga, *va, *ra = NULL, *rh = NULL;
  const PetscInt     nr = ct->ncomp;
  PetscReal          sums[1 + MM_MAX_DIM] = {0, 0, 0, 0}, loc[2] = {0, 0}, rmax = 0, fscale;
  MPI_Comm           comm = PetscObjectComm((PetscObject)ctx->op.dm);

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(st, sizeof(*st)));
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(react, &fa));
  PetscCall(VecGetArrayRead(sigma, &va));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  if (nr > 1) {
    PetscCall(VecGetArrayRead(ct->rho, &ra));
    PetscCall(VecGetArrayRead(ct->rho_hi, &rh));
  }
  for (PetscInt k = 0; k < nc; ++k) rmax = PetscMax(rmax, -PetscRealPart(fa[in[k] - rstart]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rmax, 1, MPIU_REAL, MPIU_MAX, comm));
  /* force scale of the normalized residuals: the largest reaction, but at least the nodal force of a
   * 1e-3 strain on the contact layer, so that solver noise on a free boundary is not normalized by itself */
  fscale = PetscMax(rmax, 1e-3 * ctx->opt.E * PetscPowReal(ct->h_c, dim - 1));
  for (PetscInt k = 0; k < nc; ++k) {
    const PetscInt  i = in[k] - rstart;
    const PetscReal un = PetscRealPart(wa[i]), g = PetscRealPart(ga[k]), r = -PetscRealPart(fa[i]);
    const PetscBool active = (PetscBool)(g - un <= 1e-10 * ct->h_c);
    PetscReal       tn = 0, vn = 0, res = 0;

    for (PetscInt d = 1; d < dim; ++d) {
      tn += PetscSqr(PetscRealPart(fa[i + d]));
      vn += PetscSqr(PetscRealPart(va[i + d]));
      sums[d] += PetscRealPart(fa[i + d]);
    }
    tn = PetscSqrtReal(tn);
    vn = PetscSqrtReal(vn);
    sums[0] += r;
    res = PetscMax(res, (un - g) / ct->h_c);                                 /* penetration */
    res = PetscMax(res, -r / fscale);                                        /* tension */
    res = PetscMax(res, PetscAbsReal(r * (un - g)) / (fscale * ct->h_c));    /* complementarity */
    res = PetscMax(res, (tn - mu * PetscMax(r, 0)) / fscale);                /* cone */
    /* the VI's own stick/slip split: a tangential reaction inside its bound sticks (RSLS holds a
     * variable within 1e-8, absolute, of its bound as active, hence the relative margin) */
    PetscBool at_bound = PETSC_FALSE;
    if (nr == 3) {
      PetscReal rt = PetscSqrtReal(PetscSqr(PetscRealPart(ra[k * nr + 1])) + PetscSqr(PetscRealPart(ra[k * nr + 2])));
      /* on the disk's rim: a slipping node whose reaction reached its threshold, or no threshold */
      at_bound = (PetscBool)((ct->slipping[k] || PetscRealPart(rh[k * nr + 1]) == 0) && rt >= PetscRealPart(rh[k * nr + 1]) - PetscMax(1e-6 * PetscRealPart(rh[k * nr + 1]), 2e-8));
    }
    else if (nr > 1) {
      PetscReal rt = 0;
      for (PetscInt d = 1; d < nr; ++d) rt += PetscSqr(PetscRealPart(ra[k * nr + d]));
      /* a zero threshold is a bound too: a node touching without force slides freely */
      at_bound = (PetscBool)(PetscSqrtReal(rt) >= PetscRealPart(rh[k * nr + 1]) - PetscMax(1e-6 * PetscRealPart(rh[k * nr + 1]), 2e-8));
    }
    /* inside the cone a node must not slip */
    if (active && nr > 1 && !at_bound) res = PetscMax(res, vn * dt / (2 * ct->h_c));
    if (active && at_bound && vn > vtol) {
      PetscReal slip = 0; /* |t + mu r sigma/|sigma|| */
      for (PetscInt d = 1; d < dim; ++d) slip += PetscSqr(PetscRealPart(fa[i + d]) + mu * r * PetscRealPart(va[i + d]) / vn);
      res = PetscMax(res, PetscSqrtReal(slip) / fscale);
      ++cnt[2];
    } else if (active && nr > 1) ++cnt[3];
    cnt[0] += active;
    if (record_switches) {
      cnt[1] += (active != ct->was_active[k]);
      ct->was_active[k] = active;
    }
    loc[0] = PetscMax(loc[0], res);
    loc[1] = PetscMax(loc[1], un - g);
  }
  if (nr > 1) {
    PetscCall(VecRestoreArrayRead(ct->rho, &ra));
    PetscCall(VecRestoreArrayRead(ct->rho_hi, &rh));
  }
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(sigma, &va));
  PetscCall(VecRestoreArrayRead(react, &fa));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 4, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 1 + MM_MAX_DIM, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 2, MPIU_REAL, MPIU_MAX, comm));
  st->active          = cnt[0];
  st->switched        = cnt[1];
  st->slipping        = cnt[2];
  st->sticking        = cnt[3];
  st->force_normal    = sums[0];
  for (PetscInt d = 1; d < dim; ++d) st->force_t[d - 1] = sums[d];
  st->coulomb         = PetscMax(loc[0], 0.0);
  st->max_penetration = PetscMax(loc[1], 0.0);
  PetscFunctionReturn(0);
}

/* The discrete Coulomb residual (docs/method.md section 6) of a state, and its slipping/sticking counts. */
PetscErrorCode MMContactCoulomb(MMCtx *ctx, Vec w, Vec react, Vec sigma, PetscReal *residual, PetscInt *nslip, PetscInt *nstick)
{
  ContactStats st;

  PetscFunctionBeginUser;
  PetscCall(ContactStatistics(ctx, w, react, sigma, PETSC_FALSE, &st));
  *residual = st.coulomb;
  *nslip    = st.slipping;
  *nstick   = st.sticking;
  PetscFunctionReturn(0);
}

/* Per-step contact quantities (docs/method.md sections 5-6) of the accepted state. */
PetscErrorCode MMContactDiagnostics(MMCtx *ctx, Vec w, Vec react, Vec v, MMHistory *h)
{
  ContactStats st;

  PetscFunctionBeginUser;
  PetscCall(ContactStatistics(ctx, w, react, v, PETSC_TRUE, &st));
  h->active           = st.active;
  h->switched         = st.switched;
  h->slipping         = st.slipping;
  h->force_normal     = st.force_normal;
  h->force_tangential = ctx->op.dim == 2 ? st.force_t[0] : PetscSqrtReal(PetscSqr(st.force_t[0]) + PetscSqr(st.force_t[1]));
  h->max_penetration  = st.max_penetration;
  h->coulomb_residual = st.coulomb;
  h->vi_its           = ctx->contact.vi_its;
  PetscFunctionReturn(0);
}

/* The contact fields of the output, zero off the contact boundary: nodal pressure r_i / int phi_i and
 * current gap g_i - u.nu (scalars), tangential traction and slip velocity (Cartesian vectors on dm_out,
 * the frame's tangential components mapped back). */
PetscErrorCode MMContactBoundaryFields(MMCtx *ctx, MMOutput *o)
{
  MMContact         *ct  = &ctx->contact;
  const PetscInt     dim = ctx->op.dim;
  Vec                out[] = {o->pressure, o->gap, o->traction_t, o->slip};
  const PetscInt    *in;
  const PetscScalar *wa, *fa, *va, *ga, *aa;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  for (size_t i = 0; i < sizeof(out) / sizeof(out[0]); ++i) PetscCall(VecZeroEntries(out[i]));
  if (ct->enabled) {
    PetscCall(VecGetOwnershipRange(ctx->state.u, &rstart, NULL));
    PetscCall(ISGetIndices(ct->is_normal, &in));
    PetscCall(VecGetArrayRead(ctx->state.u, &wa));
    PetscCall(VecGetArrayRead(ctx->state.react, &fa));
    PetscCall(VecGetArrayRead(ctx->state.v, &va));
    PetscCall(VecGetArrayRead(ct->gap, &ga));
    PetscCall(VecGetArrayRead(ct->area, &aa));
    for (PetscInt k = 0; k < ct->n_local; ++k) {
      const PetscInt i = in[k] - rstart;
      PetscInt       start, end;
      PetscScalar    tc[MM_MAX_DIM] = {0, 0, 0}, sc[MM_MAX_DIM] = {0, 0, 0};

      PetscCall(VecSetValue(o->pressure, ct->scalar_index[k], -fa[i] / aa[k], INSERT_VALUES));
      PetscCall(VecSetValue(o->gap, ct->scalar_index[k], ga[k] - wa[i], INSERT_VALUES));
      for (PetscInt d = 1; d < dim; ++d)
        for (PetscInt c = 0; c < dim; ++c) {
          tc[c] += fa[i + d] * ct->frame[d][c] / aa[k];
          sc[c] += va[i + d] * ct->frame[d][c];
        }
      PetscCall(DMPlexGetPointGlobal(o->dm_out, ct->vertex[k], &start, &end));
      for (PetscInt c = 0; c < dim; ++c) {
        PetscCall(VecSetValue(o->traction_t, start + c, tc[c], INSERT_VALUES));
        PetscCall(VecSetValue(o->slip, start + c, sc[c], INSERT_VALUES));
      }
    }
    PetscCall(VecRestoreArrayRead(ct->area, &aa));
    PetscCall(VecRestoreArrayRead(ct->gap, &ga));
    PetscCall(VecRestoreArrayRead(ctx->state.v, &va));
    PetscCall(VecRestoreArrayRead(ctx->state.react, &fa));
    PetscCall(VecRestoreArrayRead(ctx->state.u, &wa));
    PetscCall(ISRestoreIndices(ct->is_normal, &in));
  }
  for (size_t i = 0; i < sizeof(out) / sizeof(out[0]); ++i) {
    PetscCall(VecAssemblyBegin(out[i]));
    PetscCall(VecAssemblyEnd(out[i]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactDestroy(MMContact *ct)
{
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&ct->snes));
  PetscCall(SNESDestroy(&ct->snes0));
  PetscCall(KSPDestroy(&ct->ksp_K));
  PetscCall(MatDestroy(&ct->W));
  PetscCall(VecDestroy(&ct->qpc.b));
  PetscCall(VecDestroy(&ct->rho));
  PetscCall(VecDestroy(&ct->rho_lo));
  PetscCall(VecDestroy(&ct->rho_hi));
  PetscCall(VecDestroy(&ct->offset));
  PetscCall(VecDestroy(&ct->z_c));
  PetscCall(VecDestroy(&ct->rho_r));
  PetscCall(VecDestroy(&ct->Wdiag));
  PetscCall(MatDestroy(&ct->P));
  PetscCall(MatDestroy(&ct->Wr));
  PetscCall(ISDestroy(&ct->is_cond));
  PetscCall(VecDestroy(&ct->z));
  PetscCall(VecDestroy(&ct->rhs_c));
  PetscCall(MatDestroy(&ct->qp.A));
  PetscCall(VecDestroy(&ct->qp.b));
  PetscCall(MatDestroy(&ct->qp0.A));
  PetscCall(VecDestroy(&ct->qp0.b));
  PetscCall(VecDestroy(&ct->lower));
  PetscCall(VecDestroy(&ct->upper));
  PetscCall(VecDestroy(&ct->lower0));
  PetscCall(VecDestroy(&ct->upper0));
  PetscCall(VecDestroy(&ct->gap));
  PetscCall(VecDestroy(&ct->area));
  PetscCall(ISDestroy(&ct->is_normal));
  PetscCall(ISDestroy(&ct->is_tangent));
  PetscCall(ISDestroy(&ct->is_star));
  PetscCall(ISDestroy(&ct->is_interior));
  PetscCall(PetscFree(ct->was_active));
  PetscCall(PetscFree2(ct->slipping, ct->slip_dir));
  PetscCall(PetscFree(ct->scalar_index));
  PetscCall(PetscFree(ct->vertex));
  PetscFunctionReturn(0);
}
