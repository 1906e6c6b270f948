/* The bound-constrained quadratic problems of the contact module as SNESVI solves, and the exact
 * (factorization) linear solves they and the stepper rely on. */
#include "../contactimpl.h"

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

/* What each exact solve is for, by options prefix, so that a refusal says which solve it is; whether
 * its matrix is symmetric, so that Cholesky applies; and whether CG may solve it instead, and where. */
typedef struct {
  const char *prefix, *purpose;
  PetscBool   symmetric, cg;
  const char *iterative; /* where an iterative solve of this matrix is supported, if anywhere */
} ExactSolve;

static ExactSolve ExactSolveInfo(const char prefix[])
{
  const ExactSolve known[] = {
    {"contact_K_", "the condensed contact formulation builds its Delassus operator from K~'s factor", PETSC_TRUE, PETSC_FALSE,
     "Iterative solvers and incomplete factorizations cannot give it. Iterative K~ solves (-contact_K_ksp_type cg with -contact_K_pc_type gamg or hypre) are supported by -contact_formulation active_set and by -contact 0"},
    /* M* restricted to the dofs with inertia is SPD and well conditioned: CG to a tight tolerance is exact enough */
    {"mass_",      "the initial acceleration solves M* a0 = L - K u0 + f_c0", PETSC_TRUE, PETSC_TRUE, "CG is also accepted: -mass_ksp_type cg with, e.g., -mass_pc_type jacobi (default tolerance -mass_ksp_rtol 1e-13)"},
    {"sliding_",   "the static sliding state solves its (nonsymmetric) linear system", PETSC_FALSE, PETSC_FALSE, NULL},
  };
  const ExactSolve other = {prefix, "this solve", PETSC_FALSE, PETSC_FALSE, NULL};
  for (size_t i = 0; i < sizeof(known) / sizeof(known[0]); ++i) {
    PetscBool same;
    if (!PetscStrcmp(prefix, known[i].prefix, &same) && same) return known[i];
  }
  return other;
}

/* Solves the energy audit relies on, and the Delassus operator built from K~'s factor, must be
 * exact: a complete factorization, or CG to a tight tolerance where the matrix allows it (mass_).
 * An iterative or incomplete PC would fail late and obscurely (no getfactoredmatrix method, an
 * energy audit failure), or, for a0, not at all. */
PetscErrorCode MMKSPCheckDirect(KSP ksp)
{
  PC          pc;
  PCType      type;
  PetscBool   lu, cholesky, cg;
  const char *prefix;
  ExactSolve  info;

  PetscFunctionBeginUser;
  PetscCall(MMKSPGetFactorPC(ksp, &pc, NULL));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  info = ExactSolveInfo(prefix ? prefix : "");
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &cholesky, PCCHOLESKY, MMPCSCHURSPLIT, ""));
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPCG, &cg));
  if (lu || (cholesky && info.symmetric) || (cg && info.cg)) PetscFunctionReturn(0);
  PetscCall(PCGetType(pc, &type));
  SETERRQ(PetscObjectComm((PetscObject)ksp), PETSC_ERR_USER_INPUT, "-%spc_type %s is not supported here: %s, and this solve must be exact. Use -%spc_type lu%s. %s", info.prefix, type, info.purpose, info.prefix, info.symmetric ? " or cholesky" : "",
          info.iterative ? info.iterative : "Iterative solvers and incomplete factorizations are not supported for it");
}

static PetscErrorCode KSPCheckDirectPreSolve(KSP ksp, Vec b, Vec x, void *ptr)
{
  PetscFunctionBeginUser;
  PetscCall(MMKSPCheckDirect(ksp));
  PetscFunctionReturn(0);
}

/* What to do about a failed factorization, by its reason. */
static const char *FactorFailureHint(PCFailedReason reason)
{
  switch (reason) {
  case PC_FACTOR_OUTMEMORY:
    return "The direct factor does not fit in memory: use a coarser mesh, more ranks or memory, or the iterative path: -contact_formulation active_set with CG for K~ (README \"Large meshes\")";
  case PC_FACTOR_NUMERIC_ZEROPIVOT:
  case PC_FACTOR_STRUCT_ZEROPIVOT:
    return "The matrix is singular: check the mesh (inverted or degenerate cells) and the Dirichlet conditions";
  default:
    return "Run with -info to see the factorization package's own error (MUMPS: its INFOG(1); a limit set by -..._mat_mumps_icntl_14 or _23 too small gives one), and check the mesh (inverted or degenerate cells) and the Dirichlet conditions";
  }
}

/*@
  MMKSPCheckFactored - Stops the run when a KSP's factorization failed, naming the solve and why

  Collective

  Input Parameter:
. ksp - the KSP, set up

  Note:
  A factorization that failed (MUMPS out of memory, a zero pivot) does not stop KSPSetUp: its
  solves would return garbage or nothing. Stop here, on every rank, naming the solve and why. The
  reason is the factor's own: PCREDUNDANT reports only that its inner PC failed (SUBPC_ERROR).

  Level: developer

.seealso: `MMKSPGetFactorPC()`, `MMKSPSetFailureCheck()`
@*/
PetscErrorCode MMKSPCheckFactored(KSP ksp)
{
  PC             pc;
  PCFailedReason reason;
  PetscInt       r;
  const char    *prefix;

  PetscFunctionBeginUser;
  PetscCall(MMKSPGetFactorPC(ksp, &pc, NULL));
  PetscCall(PCGetFailedReasonRank(pc, &reason));
  r = (PetscInt)reason;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &r, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)ksp)));
  if (!r) PetscFunctionReturn(0);
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  SETERRQ(PetscObjectComm((PetscObject)ksp), PETSC_ERR_LIB, "The factorization for the solve -%s failed: %s. %s", prefix ? prefix : "", PCFailedReasons[r], FactorFailureHint((PCFailedReason)r));
}

static PetscErrorCode KSPCheckSolvedPostSolve(KSP ksp, Vec b, Vec x, void *ptr)
{
  KSPConvergedReason reason;
  const char        *prefix;

  PetscFunctionBeginUser;
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  if (reason >= 0) PetscFunctionReturn(0);
  PetscCall(MMKSPCheckFactored(ksp));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  SETERRQ(PetscObjectComm((PetscObject)ksp), PETSC_ERR_NOT_CONVERGED, "The solve -%s failed: %s. Run with -%sksp_converged_reason -%sksp_view to see why", prefix ? prefix : "", KSPConvergedReasons[reason], prefix ? prefix : "", prefix ? prefix : "");
}

/*@
  MMKSPSetFailureCheck - Makes a failed factorization or solve of a KSP stop the run with a message
  that names the solve

  Logically collective

  Input Parameter:
. ksp - the KSP

  Note:
  A failed factorization or solve stops the run with a message that names the solve (rather than
  KSPSetErrorIfNotConverged, which stops inside PCSetUp with the factorization package's own code).

  Level: developer

.seealso: `MMKSPCheckFactored()`, `MMKSPSetDirect()`
@*/
PetscErrorCode MMKSPSetFailureCheck(KSP ksp)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetPostSolve(ksp, KSPCheckSolvedPostSolve, NULL));
  PetscFunctionReturn(0);
}

/*@
  MMKSPSetDirect - Sets a KSP up for a solve that must be exact: LU with MUMPS by default, checked
  when it solves

  Logically collective

  Input Parameter:
. ksp - the KSP

  Note:
  A solve that must be exact: LU with MUMPS by default, and anything else MMKSPCheckDirect does not
  accept refused when it solves (after KSPSetFromOptions). A CG chosen by options, where accepted,
  stops at a tight relative residual; a failed factorization or solve stops the run.

  Level: developer

.seealso: `MMKSPSetExactCG()`, `MMKSPSetDirectSPD()`, `MMKSPSetFailureCheck()`
@*/
PetscErrorCode MMKSPSetDirect(KSP ksp)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetDefaultLU(ksp));
  PetscCall(KSPSetTolerances(ksp, 1e-13, PETSC_DEFAULT, PETSC_DEFAULT, 10000));
  PetscCall(KSPSetPreSolve(ksp, KSPCheckDirectPreSolve, NULL));
  PetscCall(MMKSPSetFailureCheck(ksp));
  PetscFunctionReturn(0);
}

/*@
  MMKSPSetExactCG - Sets a KSP up for an exact solve of a well-conditioned SPD matrix: CG with
  Jacobi to a tight tolerance by default

  Logically collective

  Input Parameter:
. ksp - the KSP

  Note:
  The exact solve of a well-conditioned SPD matrix (M* on the dofs with inertia: its condition number
  with the Jacobi PC does not grow with the mesh): CG with Jacobi to the tight tolerance, by default.
  A factorization by options (-mass_pc_type lu or cholesky with -mass_ksp_type preonly) is still
  accepted; anything MMKSPCheckDirect refuses stops the run when it solves. Cheaper to set up than the
  MUMPS LU it replaced (the figures: docs/scaling.md, "The figures behind the code's choices").

  Level: developer

.seealso: `MMKSPSetDirect()`
@*/
PetscErrorCode MMKSPSetExactCG(KSP ksp)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(MMKSPSetDirect(ksp));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCJACOBI));
  PetscFunctionReturn(0);
}

/* The default factorization of a symmetric positive definite matrix (K~), chosen by measurement
 * (README "Options"; the figures: docs/scaling.md, "The figures behind the code's choices").
 * - 2D: PETSc's own Cholesky with nested-dissection ordering, faster than MUMPS LU,
 *   - on up to 8 ranks split at the ranks' interface (schursplit, pc_schursplit.c: each rank
 *     factors its interior, the interface's Schur complement is dense on every rank); on one rank
 *     there is no interface, and it is that factor with a faster backward sweep than MatSolve;
 *   - on more ranks, where the dense interface grows with the ranks, held whole on every rank
 *     (PCREDUNDANT: PETSc's factorizations are serial, MUMPS's distributed solve is slower, and a
 *     2D factor is small, N log N).
 * - 3D, where that factorization and the Delassus columns cost more than MUMPS's: MUMPS's Cholesky
 *   (LDL^T), half the factor of its LU, ordered by MUMPS's automatic choice, SCOTCH with the MUMPS
 *   build the Makefile links.
 * Options still apply on top; nothing is checked here (kt.c also accepts iterative PCs). */
PetscErrorCode MMKSPSetFactorSPD(KSP ksp, PetscInt dim)
{
  PetscMPIInt size;
  PC          pc;

  PetscFunctionBeginUser;
  PetscCall(MMPCRegisterSchurSplit());
  PetscCall(KSPSetDefaultLU(ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  if (dim != 2) {
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ksp), &size));
  if (size <= 8) {
    PetscCall(PCSetType(pc, MMPCSCHURSPLIT));
    PetscFunctionReturn(0);
  }
  if (size > 1) {
    KSP inner;
    PetscCall(PCSetType(pc, PCREDUNDANT));
    PetscCall(PCRedundantGetKSP(pc, &inner));
    PetscCall(KSPSetType(inner, KSPPREONLY));
    PetscCall(KSPGetPC(inner, &pc));
  }
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERPETSC));
  PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGND));
  PetscFunctionReturn(0);
}

/*@
  MMKSPGetFactorPC - Gives the PC that holds a KSP's factorization

  Not collective

  Input Parameter:
. ksp - the KSP

  Output Parameters:
+ fpc       - the PC: the KSP's own, or PCREDUNDANT's inner one
- redundant - PETSC_TRUE for PCREDUNDANT's (or NULL)

  Note:
  The PC that holds a KSP's factorization: its own, or with PCREDUNDANT (2D on several ranks) the
  inner one, a sequential factor of the whole matrix on every rank (*redundant true).

  Level: developer

.seealso: `MMKSPCheckFactored()`
@*/
PetscErrorCode MMKSPGetFactorPC(KSP ksp, PC *fpc, PetscBool *redundant)
{
  PC        pc;
  PetscBool red;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCREDUNDANT, &red));
  if (red) {
    KSP inner;
    PetscCall(PCRedundantGetKSP(pc, &inner));
    PetscCall(KSPGetPC(inner, &pc));
  }
  *fpc = pc;
  if (redundant) *redundant = red;
  PetscFunctionReturn(0);
}

/*@
  MMKSPSetDirectSPD - Sets a KSP up for the exact solve of K~ the condensed formulation needs: a
  complete factorization, anything else refused

  Logically collective

  Input Parameters:
+ ksp - the KSP
- dim - the mesh's dimension

  Note:
  The exact solve of K~ the condensed formulation needs: the default factorization, and anything
  but a complete factorization refused.

  Level: developer

.seealso: `MMKSPSetDirect()`
@*/
PetscErrorCode MMKSPSetDirectSPD(KSP ksp, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCall(MMKSPSetDirect(ksp));
  PetscCall(MMKSPSetFactorSPD(ksp, dim));
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
PetscErrorCode MMQPSetOperator(SNES snes, MMBoundQP *qp)
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

/* The residual r = A x - b of an exact solve is round-off: each entry sums a row's products, so
 * |r| <= gamma (|A| |x| + |b|), and in norm ||r||_2 <= gamma (||A||_inf ||x||_2 + ||b||_2) (|A| is
 * symmetric). On a slender part A's condition number brings ||A|| ||x|| far above ||b||, and no
 * relative tolerance on ||b|| alone is reachable (docs/method.md section 10, "The static start"):
 * with qp->Anorm set, a residual below MM_QP_ROUNDOFF sqrt(N) eps (||A|| ||x|| + ||b||) has converged
 * too, N the unknowns: the product's rounding grows as sqrt(N) (N at worst), and the factor covers
 * the factorization's backward error beside it (the residuals measured on slender cantilevers:
 * docs/method.md section 10, "Convergence on a slender part"); a step that is not exact (a wrong
 * active set) leaves a residual of the size of the reactions it misses, orders of magnitude above. */
#define MM_QP_ROUNDOFF 4

/* Warm-started solves start near the answer, where a relative test cannot be met: also accept
 * ||F|| <= rtol_b ||b||, which is the solver's accuracy on this linear problem. */
static PetscErrorCode QPConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ptr)
{
  MMBoundQP *qp = (MMBoundQP *)ptr;
  Vec        x;
  PetscReal  x2;
  PetscInt   n;

  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (*reason == SNES_CONVERGED_ITERATING && fnorm <= qp->rtol_b * qp->bnorm) *reason = SNES_CONVERGED_FNORM_ABS;
  if (*reason != SNES_CONVERGED_ITERATING || qp->Anorm <= 0 || it == 0) PetscFunctionReturn(0);
  PetscCall(SNESGetSolution(snes, &x));
  PetscCall(VecNorm(x, NORM_2, &x2));
  PetscCall(VecGetSize(x, &n));
  if (fnorm <= MM_QP_ROUNDOFF * PetscSqrtReal((PetscReal)n) * PETSC_MACHINE_EPSILON * (qp->Anorm * x2 + qp->bnorm)) *reason = SNES_CONVERGED_FNORM_ABS;
  PetscCall(PetscInfo(snes, "residual %g: %g eps (||A|| ||x|| + ||b||)\n", (double)fnorm, (double)(fnorm / (PETSC_MACHINE_EPSILON * (qp->Anorm * x2 + qp->bnorm)))));
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

/* A dense operator (the candidate set's Delassus block) is factored by LAPACK: Cholesky, as W is
 * symmetric positive definite, unless the semismooth method's Jacobian (not symmetric) needs LU.
 * A -PREFIX_pc_type the user gave stays. */
static PetscErrorCode DenseFactorDefault(SNES snes, Mat A, const char prefix[])
{
  PetscBool dense, ssls, set;
  KSP       ksp;
  PC        pc;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQDENSE, &dense));
  if (!dense) PetscFunctionReturn(0);
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONSSLS, &ssls));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-pc_type", &set));
  if (!set) PetscCall(PCSetType(pc, ssls ? PCLU : PCCHOLESKY));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-pc_factor_mat_solver_type", &set));
  if (!set) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERPETSC));
  PetscFunctionReturn(0);
}

/*@
  MMFactorReadOptions - Reads the options of a factor package on a stand-in factor of a small matrix

  Collective

  Input Parameters:
+ comm   - the communicator
. prefix - the options prefix
. type   - the factor's package
- ftype  - the factor's kind

  Note:
  Reads the options of a factor of package type and kind ftype with options prefix prefix, on a
  stand-in factor of a small matrix: -PREFIX_mat_mumps_icntl_14 and the like are read by the
  factor only when it is created, which may come after the options audit (a factor made inside
  the VI's iterations), or never in a run whose help lists the options. The stand-in's analysis
  runs with the user's options, so it is a connected graph of a few dozen rows per rank, a 1D
  Laplacian: PORD (-..._mat_mumps_icntl_7 4) ends the process on a graph without edges ("no valid
  number of stages in multisector"), as a stand-in of unit rows was. A package that cannot factor
  this matrix type reads nothing (its solve is refused by the solve itself).

  Level: developer

.seealso: `MMKSPSetDirect()`
@*/
PetscErrorCode MMFactorReadOptions(MPI_Comm comm, const char prefix[], MatSolverType type, MatFactorType ftype)
{
  const PetscInt nlocal = 32;
  Mat            A, F;
  MatFactorInfo  info;
  PetscInt       rstart, rend, n;
  PetscBool      available;

  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(comm, nlocal, nlocal, PETSC_DETERMINE, PETSC_DETERMINE, 3, NULL, 1, NULL, &A));
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  PetscCall(MatGetSize(A, &n, NULL));
  for (PetscInt i = rstart; i < rend; ++i) {
    PetscCall(MatSetValue(A, i, i, 2.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatGetFactorAvailable(A, type, ftype, &available));
  if (available) {
    PetscCall(MatGetFactor(A, type, ftype, &F));
    PetscCall(MatSetOptionsPrefix(F, prefix));
    PetscCall(MatFactorInfoInitialize(&info));
    if (ftype == MAT_FACTOR_CHOLESKY) PetscCall(MatCholeskyFactorSymbolic(F, A, NULL, &info));
    else PetscCall(MatLUFactorSymbolic(F, A, NULL, NULL, &info));
    PetscCall(MatDestroy(&F));
  }
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

/* The VI's factor (full formulation) is created inside its iterations, or (vifactor) when K~ is
 * first set, after the options audit: its options are read now. */
static PetscErrorCode ReadDeferredFactorOptions(SNES snes)
{
  KSP           ksp;
  PC            pc;
  PetscBool     cholesky, lu, vifactor;
  MatSolverType type;
  const char   *prefix;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &cholesky));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCVIFACTOR, &vifactor));
  if (!cholesky && !lu && !vifactor) PetscFunctionReturn(0);
  if (vifactor) {
    Mat F;
    PetscCall(MMPCVIFactorGetFactor(pc, &F, &type));
    cholesky = PETSC_TRUE;
  } else PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(MMFactorReadOptions(PetscObjectComm((PetscObject)snes), prefix, type ? type : MATSOLVERPETSC, cholesky ? MAT_FACTOR_CHOLESKY : MAT_FACTOR_LU));
  PetscFunctionReturn(0);
}

/* A vifactor PC (default or -PREFIX_pc_type vifactor) learns its VI; it needs the reduced-space VI's
 * inactive sets. */
static PetscErrorCode SetUpVIFactor(SNES snes)
{
  KSP         ksp;
  PC          pc;
  PetscBool   is, rsls;
  const char *prefix;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCVIFACTOR, &is));
  if (!is) PetscFunctionReturn(0);
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONRSLS, &rsls));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCheck(rsls, PetscObjectComm((PetscObject)snes), PETSC_ERR_USER_INPUT, "-%spc_type %s solves the Newton steps of -%ssnes_type %s only (it needs their inactive sets): drop one of the two options", prefix ? prefix : "", MMPCVIFACTOR, prefix ? prefix : "", SNESVINEWTONRSLS);
  PetscCall(MMPCVIFactorSetSNES(pc, snes));
  PetscFunctionReturn(0);
}

/* The full formulation's VI (vinewtonrsls) factors K~ on the free dofs once per iteration, and the
 * free dofs change from step to step. As submatrices, each would be a new matrix whose ordering and
 * MUMPS analysis (sequential, on its host) ran every time (docs/scaling.md, "The full formulation's
 * factor"), which is why 2D used the approximate minimum fill ordering (ICNTL(7) = 2), cheap to
 * compute but with more fill. The default PC vifactor (pc_vifactor.c) factors the whole K~ with the
 * active rows the identity's: one pattern, ordered and analysed once, so MUMPS's automatic choice
 * (a nested dissection) pays for itself in 2D too (the orderings measured: docs/scaling.md, the same
 * section). K~'s block is SPD, so MUMPS's Cholesky, half the factor of its LU.
 * vinewtonssls's semismooth Jacobian is not symmetric and keeps LU; options given stay. */
PetscErrorCode MMQPSetFactorSPD(SNES snes)
{
  const char *prefix;
  PetscBool   ssls, set;
  KSP         ksp;
  PC          pc;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESVINEWTONSSLS, &ssls));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-pc_type", &set));
  if (!ssls && !set) {
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, MMPCVIFACTOR));
    PetscCall(SetUpVIFactor(snes));
  }
  PetscCall(ReadDeferredFactorOptions(snes));
  PetscFunctionReturn(0);
}

/* mu: the friction coefficient of the problem, 0 when its bounds are on normal dofs only. */
PetscErrorCode MMQPCreate(MPI_Comm comm, const char prefix[], MMBoundQP *qp, PetscReal mu, SNES *snes)
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
  PetscCall(MMPCRegisterVIFactor());
  PetscCall(SNESSetFromOptions(*snes));
  PetscCall(SetUpVIFactor(*snes));
  PetscCall(DenseFactorDefault(*snes, qp->A, prefix));
  PetscCall(CheckQPSolverType(*snes, mu));
  PetscCall(MMQPSetOperator(*snes, qp));
  PetscFunctionReturn(0);
}

/* Solves A x = b with the solver's bounds; x is the initial guess on entry. */
PetscErrorCode MMQPSolve(SNES snes, MMBoundQP *qp, Vec x, PetscInt *its)
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
  PetscCheck(reason > 0, PetscObjectComm((PetscObject)snes), PETSC_ERR_NOT_CONVERGED, "The contact solver (%s) did not converge: %s after %" PetscInt_FMT " iterations. Where the time step does not resolve the contact (c_p dt / h_c' well above 1 in the set-up's time line), a finite-strain step's matrix can be nearly singular there: lower -ts_dt towards h_c' / c_p. Else run with -%ssnes_monitor -%ssnes_converged_reason to see why",
             prefix, SNESConvergedReasons[reason], *its, prefix, prefix);
  PetscFunctionReturn(0);
}

