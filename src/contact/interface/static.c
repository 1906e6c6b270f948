/* -initial_state static: the static contact problem under the loads at t = 0 (docs/method.md
 * section 10, "The static start"),
 *   min 1/2 w.K w - b.w  subject to  w_n <= g on the contact-normal dofs,  b = L(0) - lift(0),
 * the step's problem of the full formulation with K in place of K~ = K + 4/dt^2 M*: a VI solved by
 * SNESVINEWTONRSLS, its Newton steps by the vifactor PC (one Cholesky of K with the active rows the
 * identity's). Frictionless: the tangential contact forces at t = 0 are zero.
 *
 * Without inertia K alone must hold the body: a rigid motion that neither a Dirichlet condition nor
 * the nodes in contact stop (a free body, one free to slide along a frictionless obstacle, loads
 * pulling it off) makes the factored matrix singular. MUMPS's null-pivot detection finds it, and the
 * run stops naming the case, where the factorization would otherwise fail or return garbage. */
#include <petscmat.h>
#include "../contactimpl.h"
#include "fem.h"

/* A pivot below this times ||K|| is a null pivot (MUMPS CNTL(3)): a rigid motion of K's free block
 * leaves a pivot of round-off size, while the smallest pivot of an SPD stiffness is at least its
 * smallest eigenvalue, of order E (h/L)^2 against ||K|| of order E: far above this on the meshes of
 * this program (a material contrast of 1e6 on a 1M-dof mesh would come near it). */
#define MM_STATIC_NULL_PIVOT 1e-11

/* After each Newton step's solve: a failed factorization stops the run (MMKSPCheckFactored), and so
 * does a MUMPS factor with null pivots. */
static PetscErrorCode StaticPostSolve(KSP ksp, Vec b, Vec x, void *ptr)
{
  PC          pc;
  Mat         F;
  const char *type;
  PetscInt    nnull = 0;
  PetscBool   mumps;

  PetscFunctionBeginUser;
  PetscCall(MMKSPCheckFactored(ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(MMPCVIFactorGetFactor(pc, &F, &type));
  if (!F || !type) PetscFunctionReturn(0);
  PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (!mumps) PetscFunctionReturn(0);
  PetscCall(MatMumpsGetInfog(F, 28, &nnull));
  PetscCheck(!nnull, PetscObjectComm((PetscObject)ksp), PETSC_ERR_USER_INPUT,
             "-initial_state static: the static problem at t = 0 is not well posed: %" PetscInt_FMT " rigid motion%s of the body %s held neither by a Dirichlet condition nor by the contact nodes in contact (a free body, one free to slide along a frictionless obstacle, or loads that pull it off its support: the static solve is frictionless). Hold it with -dirichlet, or start from -initial_state given",
             nnull, nnull > 1 ? "s" : "", nnull > 1 ? "are" : "is");
  PetscFunctionReturn(0);
}

/* The VI's solver: vifactor with MUMPS's null-pivot detection on its factor of K. */
static PetscErrorCode StaticSolverSetUp(SNES snes, Mat K)
{
  KSP         ksp;
  PC          pc;
  Mat         F;
  const char *type;
  PetscBool   mumps = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(MMQPSetFactorSPD(snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetPostSolve(ksp, StaticPostSolve, NULL));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(MMPCVIFactorAnalyse(pc, K));
  PetscCall(MMPCVIFactorGetFactor(pc, &F, &type));
  if (F && type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (mumps) {
    PetscCall(MatMumpsSetIcntl(F, 24, 1));
    PetscCall(MatMumpsSetCntl(F, 3, MM_STATIC_NULL_PIVOT));
  }
  PetscFunctionReturn(0);
}

/* The bounds of the whole w vector: w_n <= g on the contact-normal dofs, free elsewhere. */
static PetscErrorCode StaticBounds(MMContact ct, Vec lower, Vec upper)
{
  Vec        sub;

  PetscFunctionBeginUser;
  PetscCall(VecSet(lower, PETSC_NINFINITY));
  PetscCall(VecSet(upper, PETSC_INFINITY));
  if (!ct->enabled || !ct->is_normal) PetscFunctionReturn(0);
  PetscCall(VecGetSubVector(upper, ct->is_normal, &sub));
  PetscCall(VecCopy(ct->gap, sub));
  PetscCall(VecRestoreSubVector(upper, ct->is_normal, &sub));
  PetscFunctionReturn(0);
}

/*@
  MMContactSolveStatic - Solves the static contact problem with K, from rest, for the static state
  and its contact forces

  Collective

  Input Parameter:
. ct - the contact object

  Output Parameters:
+ w     - the static state
- react - K w - b on the contact-normal dofs, zero elsewhere

  Note:
  w: the static state; react: K w - b on the contact-normal dofs, the contact forces (zero
  elsewhere: the tangential ones of a frictionless solve, and the noise off the contact).

  Level: intermediate

.seealso: `MMContactGetPlane()`, `MMContactProjectInitial()`
@*/
PetscErrorCode MMContactSolveStatic(MMContact ct, Vec w, Vec react)
{
  MPI_Comm   comm = PetscObjectComm((PetscObject)ct->dm);
  MMBoundQP  qp;
  SNES       snes;
  Vec        lower, upper;
  PetscInt   its;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&qp, sizeof(qp)));
  qp.A      = ct->K;
  qp.rtol_b = ct->opt.contact_tol;
  /* K alone is as ill-conditioned as the part is slender: the test also accepts round-off (qp.c) */
  PetscCall(MatNorm(qp.A, NORM_INFINITY, &qp.Anorm));
  PetscCall(VecDuplicate(w, &qp.b));
  PetscCall(VecWAXPY(qp.b, -1.0, ct->lift, ct->load));
  PetscCall(MMQPCreate(comm, "static_", &qp, 0, &snes));
  PetscCall(StaticSolverSetUp(snes, qp.A));
  PetscCall(VecDuplicate(w, &lower));
  PetscCall(VecDuplicate(w, &upper));
  PetscCall(StaticBounds(ct, lower, upper));
  PetscCall(SNESVISetVariableBounds(snes, lower, upper));
  /* from rest: the nodes touching the obstacles at t = 0 start in the active set */
  PetscCall(VecZeroEntries(w));
  PetscCall(VecPointwiseMin(w, w, upper));
  PetscCall(MMQPSolve(snes, &qp, w, &its));
  PetscCall(MatMult(qp.A, w, react));
  PetscCall(VecAXPY(react, -1.0, qp.b));
  if (ct->enabled && ct->is_normal) {
    PetscCall(VecISSet(react, ct->is_interior, 0.0));
    PetscCall(VecISSet(react, ct->is_tangent, 0.0));
  } else PetscCall(VecZeroEntries(react));
  if (!ct->pb.quiet) PetscCall(PetscPrintf(comm, "mmcontact: -initial_state static: the static contact problem at t = 0 solved in %" PetscInt_FMT " VI iteration%s\n", its, its == 1 ? "" : "s"));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&lower));
  PetscCall(VecDestroy(&upper));
  PetscCall(VecDestroy(&qp.b));
  PetscFunctionReturn(0);
}
