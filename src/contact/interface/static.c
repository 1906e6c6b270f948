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
 * does a MUMPS factor with null pivots. With ptr (a PetscBool, the finite-strain Newton's solves),
 * either only fails the solve (an indefinite tangent, a Newton iterate that lifts the body off: the
 * load step is cut) */
static PetscErrorCode StaticPostSolve(KSP ksp, Vec b, Vec x, void *ptr)
{
  PC          pc;
  Mat         F;
  const char *type;
  PetscInt    nnull = 0;
  PetscBool   mumps;

  PetscFunctionBeginUser;
  if (!ptr) PetscCall(MMKSPCheckFactored(ksp));
  else {
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    if (reason < 0) *(PetscBool *)ptr = PETSC_TRUE;
  }
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(MMPCVIFactorGetFactor(pc, &F, &type));
  if (!F || !type) PetscFunctionReturn(0);
  PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (!mumps) PetscFunctionReturn(0);
  PetscCall(MatMumpsGetInfog(F, 28, &nnull));
  if (ptr && nnull) *(PetscBool *)ptr = PETSC_TRUE; /* an iterate far from the state may release the contact */
  PetscCheck(!nnull || ptr, PetscObjectComm((PetscObject)ksp), PETSC_ERR_USER_INPUT,
             "-initial_state static: the static problem at t = 0 is not well posed: %" PetscInt_FMT " rigid motion%s of the body %s held neither by a Dirichlet condition nor by the contact nodes in contact (a free body, one free to slide along a frictionless obstacle, or loads that pull it off its support: the static solve is frictionless). Hold it with -dirichlet, or start from -initial_state given",
             nnull, nnull > 1 ? "s" : "", nnull > 1 ? "are" : "is");
  PetscFunctionReturn(0);
}

/* The VI's solver: vifactor with MUMPS's null-pivot detection on its factor of K. */
static PetscErrorCode StaticSolverSetUp(SNES snes, Mat K, PetscBool *failed)
{
  KSP         ksp;
  PC          pc;
  Mat         F;
  const char *type;
  PetscBool   mumps = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(MMQPSetFactorSPD(snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetPostSolve(ksp, StaticPostSolve, failed));
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

/* The bounds of the whole w vector: w_n <= g on the contact-normal dofs, free elsewhere; about a
 * state u (not NULL), those of an increment dw: dw_n <= g - u_n. */
static PetscErrorCode StaticBounds(MMContact ct, Vec u, Vec lower, Vec upper)
{
  Vec        sub;

  PetscFunctionBeginUser;
  PetscCall(VecSet(lower, PETSC_NINFINITY));
  PetscCall(VecSet(upper, PETSC_INFINITY));
  if (!ct->enabled || !ct->is_normal) PetscFunctionReturn(0);
  PetscCall(VecGetSubVector(upper, ct->is_normal, &sub));
  PetscCall(VecCopy(ct->gap, sub));
  if (u) {
    Vec un;
    PetscCall(VecGetSubVector(u, ct->is_normal, &un));
    PetscCall(VecAXPY(sub, -1.0, un));
    PetscCall(VecRestoreSubVector(u, ct->is_normal, &un));
  }
  PetscCall(VecRestoreSubVector(upper, ct->is_normal, &sub));
  PetscFunctionReturn(0);
}

/* The static contact problem min 1/2 w.A w - b.w, (u +) w_n <= g, from the guess w, for w and the
 * contact forces react = A w - b on the contact-normal dofs. failed NULL: a solve that fails stops
 * the run; else it is said there. */
static PetscErrorCode StaticSolve(MMContact ct, const char prefix[], Mat A, Vec b, Vec u, Vec w, Vec react, PetscInt *its, PetscBool *failed)
{
  MPI_Comm   comm = PetscObjectComm((PetscObject)ct->dm);
  MMBoundQP  qp;
  SNES       snes;
  Vec        lower, upper;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&qp, sizeof(qp)));
  qp.A      = A;
  qp.b      = b;
  qp.rtol_b = ct->opt.contact_tol;
  /* K alone is as ill-conditioned as the part is slender: the test also accepts round-off (qp.c) */
  PetscCall(MatNorm(qp.A, NORM_INFINITY, &qp.Anorm));
  PetscCall(MMQPCreate(comm, prefix, &qp, 0, &snes));
  PetscCall(StaticSolverSetUp(snes, qp.A, failed));
  PetscCall(VecDuplicate(w, &lower));
  PetscCall(VecDuplicate(w, &upper));
  PetscCall(StaticBounds(ct, u, lower, upper));
  PetscCall(SNESVISetVariableBounds(snes, lower, upper));
  /* the nodes touching the obstacles start in the active set */
  PetscCall(VecPointwiseMin(w, w, upper));
  if (!failed) PetscCall(MMQPSolve(snes, &qp, w, its));
  else {
    SNESConvergedReason reason;
    PetscCall(VecNorm(qp.b, NORM_2, &qp.bnorm));
    qp.bnorm = PetscMax(qp.bnorm, PETSC_SMALL);
    PetscCall(SNESSolve(snes, NULL, w));
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, its));
    if (reason <= 0) *failed = PETSC_TRUE;
  }
  PetscCall(MatMult(qp.A, w, react));
  PetscCall(VecAXPY(react, -1.0, qp.b));
  if (ct->enabled && ct->is_normal) {
    PetscCall(VecISSet(react, ct->is_interior, 0.0));
    PetscCall(VecISSet(react, ct->is_tangent, 0.0));
  } else PetscCall(VecZeroEntries(react));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&lower));
  PetscCall(VecDestroy(&upper));
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

.seealso: `MMContactGetPlane()`, `MMContactProjectInitial()`, `MMContactSolveStaticStep()`
@*/
PetscErrorCode MMContactSolveStatic(MMContact ct, Vec w, Vec react)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)ct->dm);
  Vec      b;
  PetscInt its;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(w, &b));
  PetscCall(VecWAXPY(b, -1.0, ct->lift, ct->load));
  /* from rest */
  PetscCall(VecZeroEntries(w));
  PetscCall(StaticSolve(ct, "static_", ct->K, b, NULL, w, react, &its, NULL));
  if (!ct->pb.quiet) PetscCall(PetscPrintf(comm, "mmcontact: -initial_state static: the static contact problem at t = 0 solved in %" PetscInt_FMT " VI iteration%s\n", its, its == 1 ? "" : "s"));
  PetscCall(VecDestroy(&b));
  PetscFunctionReturn(0);
}

/* A push, of this times |b|_inf, into the obstacle on the unloaded rows of the touching nodes (Seat) */
#define MM_STATIC_SEAT 1e-8

/* A body that rests on its contact face with no load on the contact nodes themselves (a pressure on
 * its top) leaves them inactive in the VI's first iterate (its active set takes a node at its bound
 * only where the force pushes it on), and K alone is singular there. The first Newton step of a
 * nonlinear static start seats them: a small push into the obstacle on their unloaded rows of b, which
 * the next Newton step, from the true residual, takes back. */
static PetscErrorCode Seat(MMContact ct, Vec b, Vec u)
{
  Vec          bn, un;
  PetscScalar *ba;
  const PetscScalar *ga, *ua;
  PetscReal    bmax, push;
  PetscInt     n;

  PetscFunctionBeginUser;
  if (!ct->enabled || !ct->is_normal) PetscFunctionReturn(0);
  PetscCall(VecNorm(b, NORM_INFINITY, &bmax));
  push = MM_STATIC_SEAT * bmax;
  PetscCall(VecGetSubVector(b, ct->is_normal, &bn));
  PetscCall(VecGetSubVector(u, ct->is_normal, &un));
  PetscCall(VecGetLocalSize(bn, &n));
  PetscCall(VecGetArray(bn, &ba));
  PetscCall(VecGetArrayRead(un, &ua));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  for (PetscInt i = 0; i < n; ++i)
    if (PetscRealPart(ga[i] - ua[i]) <= 0 && PetscAbsScalar(ba[i]) <= push) ba[i] = push;
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(un, &ua));
  PetscCall(VecRestoreArray(bn, &ba));
  PetscCall(VecRestoreSubVector(u, ct->is_normal, &un));
  PetscCall(VecRestoreSubVector(b, ct->is_normal, &bn));
  PetscFunctionReturn(0);
}

/*@
  MMContactSolveStaticStep - Solves one Newton step of a nonlinear static contact problem: the
  frictionless contact problem of a given matrix for the increment of a state

  Collective

  Input Parameters:
+ ct - the contact object
. A  - the step's matrix (w-frame, K's layout): the tangent stiffness at u
. b    - the residual at u, the loads less the internal force (changed on the seated rows)
. u    - the state the increment starts from
- seat - whether the nodes touching at u with no load on them start pushed on their obstacle (the
         first step from rest)

  Output Parameters:
+ dw     - the increment: min 1/2 dw.A dw - b.dw subject to u_n + dw_n <= g (zero on entry: from u)
. react  - A dw - b on the contact-normal dofs, the contact forces at u + dw; zero elsewhere
. its    - the VI iterations
- failed - whether the solve failed (a failed factorization, an indefinite A, or no convergence)

  Note:
  The finite-strain static start (docs/method.md section 13, "The static start in finite strain"):
  the increment, not the state, is the unknown, so that the solve's relative tolerance shrinks with
  the Newton residual. A seated first step (seat) starts the nodes that touch with no load on them
  in the active set. A failed solve, null pivots included (a rigid motion nothing holds, which an
  iterate far from the state can give), is returned, for the caller to cut its load step.

  Level: developer

.seealso: `MMContactSolveStatic()`
@*/
PetscErrorCode MMContactSolveStaticStep(MMContact ct, Mat A, Vec b, Vec u, PetscBool seat, Vec dw, Vec react, PetscInt *its, PetscBool *failed)
{
  PetscFunctionBeginUser;
  *failed = PETSC_FALSE;
  if (seat) PetscCall(Seat(ct, b, u));
  PetscCall(StaticSolve(ct, "static_", A, b, u, dw, react, its, failed));
  PetscFunctionReturn(0);
}
