/* The K~ solver of the paths that build no Delassus operator: the linear runs (-contact 0) and the
 * active-set formulation (docs/method.md section 3). K~ = K + 4/dt^2 M* is symmetric positive
 * definite, so besides a factorization it can be solved by CG with an algebraic multigrid PC (GAMG
 * with the rigid-body modes as near-null space, or hypre BoomerAMG), set up once per dt, prefix
 * contact_K_. The condensed formulation keeps its own factor (impls/condensed/). */
#include "../contactimpl.h"
#include "fem.h"

/* The rigid-body modes of the free dofs in the w-frame (rotated by Q^T at the contact nodes),
 * orthonormalized: GAMG's near-null space. */
static PetscErrorCode RigidBodyModes(MMContact ct, MatNullSpace *sp)
{
  const PetscInt nmodes = ct->dim == 2 ? 3 : 6;
  Vec            modes[6], ucart[6];

  PetscFunctionBeginUser;
  for (PetscInt m = 0; m < nmodes; ++m) {
    PetscCall(DMGetGlobalVector(ct->dm, &ucart[m]));
    PetscCall(VecDuplicate(ct->qp.b, &modes[m]));
  }
  PetscCall(MMFERigidModesCartesian(ct->op, (PetscReal[MM_MAX_DIM]){0, 0, 0}, 1.0, nmodes, ucart));
  for (PetscInt m = 0; m < nmodes; ++m) {
    PetscCall(MMFEFromCartesian(ct->op, ucart[m], modes[m]));
    PetscCall(DMRestoreGlobalVector(ct->dm, &ucart[m]));
  }
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
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)ct->dm), PETSC_FALSE, nmodes, modes, sp));
  for (PetscInt m = 0; m < nmodes; ++m) PetscCall(VecDestroy(&modes[m]));
  PetscFunctionReturn(0);
}

/* The CG's default PC for K~ (the active set's and the linear path's): on one rank the incomplete
 * Cholesky factor ICC(0) of K~, set up once per dt, on more Jacobi (ICC needs one rank's matrix;
 * -contact_K_pc_type bjacobi -contact_K_sub_pc_type icc gives ICC(0) per rank). On the 33k-dof D2 ball
 * it takes 0.27 to 0.29 of Jacobi's CG iterations (docs/benchmark_history.md, "Issue 50, the active
 * set's step"). */
PCType MMKtDefaultPC(MPI_Comm comm)
{
  PetscMPIInt size;

  return !MPI_Comm_size(comm, &size) && size == 1 ? PCICC : PCJACOBI;
}

/* The defaults, before the options: the linear runs keep the exact factorization they always had;
 * the iterative paths CG with the PC pc_default, whose choice each caller gives (MMKtDefaultPC). At the c_p dt / h_c' near 1 that
 * resolves the contact, K~ = K + 4/dt^2 M* is dominated by the mass, so a one-level PC needs few
 * iterations and beats GAMG's costly cycle; GAMG wins at much larger dt (docs/scaling.md, "The
 * figures behind the code's choices"). An incomplete Cholesky factor is taken in RCM order, which
 * took 6% fewer CG iterations than the natural one on the 33k-dof D2 ball (docs/benchmark_history.md,
 * "Issue 50, the active set's step"). */
static PetscErrorCode KtSetDefaults(KSP ksp, PetscBool iterative, PetscInt dim, PCType pc_default)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(MMKSPSetFactorSPD(ksp, dim));
  PetscCall(KSPSetTolerances(ksp, 1e-14, PETSC_DEFAULT, PETSC_DEFAULT, 5000));
  PetscCall(MMKSPSetFailureCheck(ksp));
  if (!iterative) PetscFunctionReturn(0);
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, pc_default));
  PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGRCM)); /* a no-op unless pc_default factors */
  PetscFunctionReturn(0);
}

/* Whether the PC is a complete factorization; an iterative one behind KSPPREONLY would be a single
 * cycle, not a solve, so it gets CG. */
static PetscErrorCode KtClassify(MMStepSolver *kt)
{
  PC        pc;
  PetscBool lu, cholesky, preonly;

  PetscFunctionBeginUser;
  PetscCall(MMKSPGetFactorPC(kt->ksp, &pc, NULL));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &cholesky, PCCHOLESKY, MMPCSCHURSPLIT, ""));
  PetscCall(PetscObjectTypeCompare((PetscObject)kt->ksp, KSPPREONLY, &preonly));
  kt->iterative = (PetscBool)!(lu || cholesky);
  if (kt->iterative && preonly) PetscCall(KSPSetType(kt->ksp, KSPCG));
  PetscFunctionReturn(0);
}

/* iterative: CG with the PC pc_default unless the options say otherwise, else a factorization. */
PetscErrorCode MMKtCreate(MMContact ct, PetscBool iterative, PCType pc_default)
{
  MMStepSolver *kt = &ct->kt;

  PetscFunctionBeginUser;
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)ct->dm), &kt->ksp));
  PetscCall(KSPSetOptionsPrefix(kt->ksp, "contact_K_"));
  PetscCall(KtSetDefaults(kt->ksp, iterative, ct->dim, pc_default));
  PetscCall(KSPSetFromOptions(kt->ksp));
  PetscCall(KtClassify(kt));
  if (!kt->iterative) PetscFunctionReturn(0);
  /* warm-started from the predictor, and tested on the true residual, ||K~ w - b|| <= contact_tol ||b|| (MMKtSolve) */
  PetscCall(KSPSetInitialGuessNonzero(kt->ksp, PETSC_TRUE));
  PetscCall(KSPSetNormType(kt->ksp, KSP_NORM_UNPRECONDITIONED));
  PetscFunctionReturn(0);
}

/* A new K~ (a new dt): the PC is set up here, once, and serves every solve until dt changes. */
PetscErrorCode MMKtSetOperator(MMContact ct, Mat Kt)
{
  MMStepSolver *kt = &ct->kt;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_KtSetUp, 0, 0, 0, 0));
  if (kt->iterative) {
    if (!kt->rigid) PetscCall(RigidBodyModes(ct, &kt->rigid));
    PetscCall(MatSetNearNullSpace(Kt, kt->rigid));
  }
  PetscCall(KSPSetOperators(kt->ksp, Kt, Kt));
  PetscCall(KSPSetUp(kt->ksp));
  PetscCall(MMKSPCheckFactored(kt->ksp));
  PetscCall(PetscLogEventEnd(MMCONTACT_KtSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* An iterative solve of ksp x = rhs for the step whose right-hand side is b: it stops at
 * ||r|| <= contact_tol ||b|| on the true residual, the accuracy the energy audit needs (README
 * "Large meshes"), or at the user's -..._ksp_atol if looser; the user's atol is restored after.
 * *atol_used (if not NULL): that absolute tolerance. */
PetscErrorCode MMKtSolveToTolerance(KSP ksp, PetscReal tol, Vec b, Vec rhs, Vec x, PetscReal *atol_used)
{
  PetscReal rtol, atol, bnorm;
  PetscInt  maxit;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, NULL, &maxit));
  if (atol_used) *atol_used = PetscMax(atol, tol * bnorm);
  PetscCall(KSPSetTolerances(ksp, rtol, PetscMax(atol, tol * bnorm), PETSC_DEFAULT, maxit));
  PetscCall(KSPSolve(ksp, rhs, x));
  PetscCall(KSPSetTolerances(ksp, rtol, atol, PETSC_DEFAULT, maxit));
  PetscFunctionReturn(0);
}

/* w = K~^{-1} b, w the initial guess on entry (the Newmark predictor) when the solve is iterative. */
PetscErrorCode MMKtSolve(MMContact ct, Vec b, Vec w)
{
  MMStepSolver *kt = &ct->kt;
  PetscInt      its;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_KtSolve, 0, 0, 0, 0));
  if (kt->iterative) PetscCall(MMKtSolveToTolerance(kt->ksp, ct->tol, b, b, w, NULL));
  else PetscCall(KSPSolve(kt->ksp, b, w));
  PetscCall(KSPGetIterationNumber(kt->ksp, &its));
  kt->its += its;
  PetscCall(PetscLogEventEnd(MMCONTACT_KtSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMKtDestroy(MMStepSolver *kt)
{
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&kt->ksp));
  PetscCall(MatNullSpaceDestroy(&kt->rigid));
  PetscFunctionReturn(0);
}

/* K~'s local diagonal and off-diagonal blocks (SeqAIJ) and the off-diagonal block's global columns,
 * for the code that reads K~'s arrays (schursplit, the active set's block copy); on one rank the
 * whole matrix and no off-diagonal block. who names the user of an AIJ-only path in the error. */
PetscErrorCode MMKtGetLocalBlocks(Mat K, const char who[], Mat *Ad, Mat *Ao, const PetscInt **colmap)
{
  PetscBool mpi, seq;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATMPIAIJ, &mpi));
  if (mpi) {
    PetscCall(MatMPIAIJGetSeqAIJ(K, Ad, Ao, colmap));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATSEQAIJ, &seq));
  PetscCheck(seq, PetscObjectComm((PetscObject)K), PETSC_ERR_SUP, "%s needs K~ as an AIJ matrix", who);
  *Ad     = K;
  *Ao     = NULL;
  *colmap = NULL;
  PetscFunctionReturn(0);
}
