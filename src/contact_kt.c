/* The K~ solver of the paths that build no Delassus operator: the linear runs (-contact 0) and the
 * active-set formulation (docs/method.md section 3). K~ = K + 4/dt^2 M* is symmetric positive
 * definite, so besides a factorization it can be solved by CG with an algebraic multigrid PC (GAMG
 * with the rigid-body modes as near-null space, or hypre BoomerAMG), set up once per dt, prefix
 * contact_K_. The condensed formulation keeps its own factor (contact_condensed.c). */
#include "contact_impl.h"

/* The rigid-body mode `mode` at x: translations e_0..e_{d-1}, then rotations (2D: one, 3D: three),
 * about the origin (the modes are orthonormalized afterwards, so the centre does not matter). */
static PetscErrorCode RigidMode(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ptr)
{
  const PetscInt mode = *(const PetscInt *)ptr;

  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0;
  if (mode < dim) {
    u[mode] = 1;
    return 0;
  }
  if (dim == 2) {
    u[0] = -x[1];
    u[1] = x[0];
    return 0;
  }
  {
    const PetscInt k = mode - dim, i = (k + 1) % 3, j = (k + 2) % 3;
    /* e_k x x */
    u[i] = -x[j];
    u[j] = x[i];
  }
  return 0;
}

/* The rigid-body modes of the free dofs in the w-frame: projected on the DM's global vectors (which
 * drop the Dirichlet-constrained dofs), rotated by Q^T at the contact nodes, orthonormalized. */
static PetscErrorCode RigidBodyModes(MMCtx *ctx, MatNullSpace *sp)
{
  const PetscInt dim = ctx->op.dim, nmodes = dim == 2 ? 3 : 6;
  Vec            modes[6], ucart;
  PetscInt       mode;
  void          *fctx = &mode;
  PetscErrorCode (*f[1])(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar *, void *) = {RigidMode};

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(ctx->op.dm, &ucart));
  for (mode = 0; mode < nmodes; ++mode) {
    PetscCall(DMProjectFunction(ctx->op.dm, 0.0, f, &fctx, INSERT_VALUES, ucart));
    PetscCall(VecDuplicate(ctx->contact.qp.b, &modes[mode]));
    PetscCall(MatMultTranspose(ctx->op.Q, ucart, modes[mode]));
  }
  PetscCall(DMRestoreGlobalVector(ctx->op.dm, &ucart));
  /* modified Gram-Schmidt; a mode the Dirichlet data remove entirely is still harmless to GAMG */
  for (PetscInt i = 0; i < nmodes; ++i) {
    PetscReal nrm;
    for (PetscInt j = 0; j < i; ++j) {
      PetscScalar dot;
      PetscCall(VecDot(modes[i], modes[j], &dot));
      PetscCall(VecAXPY(modes[i], -dot, modes[j]));
    }
    PetscCall(VecNormalize(modes[i], &nrm));
  }
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)ctx->op.dm), PETSC_FALSE, nmodes, modes, sp));
  for (PetscInt i = 0; i < nmodes; ++i) PetscCall(VecDestroy(&modes[i]));
  PetscFunctionReturn(0);
}

/* The defaults, before the options: the linear runs keep the exact factorization they always had;
 * the active-set formulation, made for large meshes, CG with GAMG (README "Solvers", measured). */
static PetscErrorCode KtSetDefaults(KSP ksp, PetscBool iterative, PetscInt dim)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(MMKSPSetFactorSPD(ksp, dim));
  PetscCall(KSPSetTolerances(ksp, 1e-14, PETSC_DEFAULT, PETSC_DEFAULT, 5000));
  PetscCall(KSPSetErrorIfNotConverged(ksp, PETSC_TRUE));
  if (!iterative) PetscFunctionReturn(0);
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscFunctionReturn(0);
}

/* Whether the PC is a complete factorization; an iterative one behind KSPPREONLY would be a single
 * cycle, not a solve, so it gets CG. */
static PetscErrorCode KtClassify(MMStepSolver *kt)
{
  PC        pc;
  PetscBool lu, cholesky, preonly;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(kt->ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &cholesky));
  PetscCall(PetscObjectTypeCompare((PetscObject)kt->ksp, KSPPREONLY, &preonly));
  kt->iterative = (PetscBool)!(lu || cholesky);
  if (kt->iterative && preonly) PetscCall(KSPSetType(kt->ksp, KSPCG));
  PetscFunctionReturn(0);
}

PetscErrorCode MMKtCreate(MMCtx *ctx)
{
  MMStepSolver *kt = &ctx->contact.kt;

  PetscFunctionBeginUser;
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)ctx->op.dm), &kt->ksp));
  PetscCall(KSPSetOptionsPrefix(kt->ksp, "contact_K_"));
  PetscCall(KtSetDefaults(kt->ksp, (PetscBool)(ctx->contact.enabled && ctx->contact.formulation == MM_CONTACT_ACTIVE_SET), ctx->op.dim));
  PetscCall(KSPSetFromOptions(kt->ksp));
  PetscCall(KtClassify(kt));
  if (!kt->iterative) PetscFunctionReturn(0);
  /* warm-started from the predictor, and tested on the true residual, ||K~ w - b|| <= contact_tol ||b|| (MMKtSolve) */
  PetscCall(KSPSetInitialGuessNonzero(kt->ksp, PETSC_TRUE));
  PetscCall(KSPSetNormType(kt->ksp, KSP_NORM_UNPRECONDITIONED));
  PetscFunctionReturn(0);
}

/* A new K~ (a new dt): the PC is set up here, once, and serves every solve until dt changes. */
PetscErrorCode MMKtSetOperator(MMCtx *ctx, Mat Kt)
{
  MMStepSolver *kt = &ctx->contact.kt;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.kt_setup, 0, 0, 0, 0));
  if (kt->iterative) {
    if (!kt->rigid) PetscCall(RigidBodyModes(ctx, &kt->rigid));
    PetscCall(MatSetNearNullSpace(Kt, kt->rigid));
  }
  PetscCall(KSPSetOperators(kt->ksp, Kt, Kt));
  PetscCall(KSPSetUp(kt->ksp));
  PetscCall(PetscLogEventEnd(ctx->log.kt_setup, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The convergence test of every iterative K~ solve: ||r|| <= contact_tol ||b||, the accuracy the
 * energy audit needs (README "Solvers"), or the user's -contact_K_ksp_atol if looser. */
PetscErrorCode MMKtSetTolerance(KSP ksp, PetscReal tol, Vec b)
{
  PetscReal rtol, atol, bnorm;
  PetscInt  maxit;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, NULL, &maxit));
  PetscCall(KSPSetTolerances(ksp, rtol, PetscMax(atol, tol * bnorm), PETSC_DEFAULT, maxit));
  PetscFunctionReturn(0);
}

/* w = K~^{-1} b, w the initial guess on entry (the Newmark predictor) when the solve is iterative. */
PetscErrorCode MMKtSolve(MMCtx *ctx, Vec b, Vec w)
{
  MMStepSolver *kt = &ctx->contact.kt;
  PetscInt      its;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.kt_solve, 0, 0, 0, 0));
  if (kt->iterative) {
    PetscReal rtol, atol;
    PetscInt  maxit;
    /* the user's atol, restored after: the test scales with this step's b */
    PetscCall(KSPGetTolerances(kt->ksp, &rtol, &atol, NULL, &maxit));
    PetscCall(MMKtSetTolerance(kt->ksp, ctx->contact.tol, b));
    PetscCall(KSPSolve(kt->ksp, b, w));
    PetscCall(KSPSetTolerances(kt->ksp, rtol, atol, PETSC_DEFAULT, maxit));
  } else PetscCall(KSPSolve(kt->ksp, b, w));
  PetscCall(KSPGetIterationNumber(kt->ksp, &its));
  kt->its += its;
  PetscCall(PetscLogEventEnd(ctx->log.kt_solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMKtDestroy(MMStepSolver *kt)
{
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&kt->ksp));
  PetscCall(MatNullSpaceDestroy(&kt->rigid));
  PetscFunctionReturn(0);
}
