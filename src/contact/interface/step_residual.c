/* What the stepper's acceptance rule asks of contact (docs/method.md section 3, "A step accepted by
 * its certificate"): the residual of the step's equation K~ w = b + f_c at a solution, and how tight
 * the iterative solves beneath go. The stepper judges the residual against the round-off of the
 * terms it sums (src/ts/certificate.c) and, when the solve was not exact enough, tightens the
 * solves and asks again: the formulations keep their own inexact inner iterations. */
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet */
#include "../contactimpl.h"

/* sum_j |K~_ij| for each owned row i, once per K~ (a new dt or tangent, a kept one swapped back) */
static PetscErrorCode RowAbsSums(MMContact ct)
{
  Mat               A = ct->qp.A;
  PetscObjectState  state;
  PetscScalar      *ra;
  PetscInt          rstart, rend;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)A, &state));
  if (ct->Kt_rowabs && ct->Kt_rowabs_state == state) PetscFunctionReturn(0);
  if (!ct->Kt_rowabs) PetscCall(MatCreateVecs(A, NULL, &ct->Kt_rowabs));
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  PetscCall(VecGetArrayWrite(ct->Kt_rowabs, &ra));
  for (PetscInt i = rstart; i < rend; ++i) {
    const PetscScalar *v;
    PetscInt           nc;
    PetscReal          sum = 0;
    PetscCall(MatGetRow(A, i, &nc, NULL, &v));
    for (PetscInt j = 0; j < nc; ++j) sum += PetscAbsScalar(v[j]);
    PetscCall(MatRestoreRow(A, i, &nc, NULL, &v));
    ra[i - rstart] = sum;
  }
  PetscCall(VecRestoreArrayWrite(ct->Kt_rowabs, &ra));
  ct->Kt_rowabs_state = state;
  PetscFunctionReturn(0);
}

/*@
  MMContactStepResidual - The residual of the step's equation at a solution: r = b + f_c - K~ w

  Collective

  Input Parameters:
+ ct    - the contact object, its step matrix set (MMContactSetStepMatrix())
. b     - the step's right-hand side
. w     - the solution
- react - the contact (and friction) force f_c of the solution

  Output Parameters:
+ r     - the residual (w-frame)
- scale - per entry, the round-off scale of r's: |b_i| + |f_c,i| + sum_j |K~_ij| |w_i| (the last
          estimates (|K~| |w|)_i, the round-off of (K~ w)_i, by w's own entry: w varies little over a row)

  Level: developer

.seealso: `MMContactSolve()`, `MMContactSetSolveTolerance()`
@*/
PetscErrorCode MMContactStepResidual(MMContact ct, Vec b, Vec w, Vec react, Vec r, Vec scale)
{
  const PetscScalar *ba, *fa, *wa, *ka;
  PetscScalar       *ra, *sa;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCheck(ct->qp.A, ct->comm, PETSC_ERR_ORDER, "MMContactStepResidual needs the step matrix (MMContactSetStepMatrix)");
  PetscCall(RowAbsSums(ct));
  PetscCall(MatMult(ct->qp.A, w, r));
  PetscCall(VecGetLocalSize(w, &n));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayRead(react, &fa));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ct->Kt_rowabs, &ka));
  PetscCall(VecGetArray(r, &ra));
  PetscCall(VecGetArrayWrite(scale, &sa));
  for (PetscInt i = 0; i < n; ++i) {
    sa[i] = PetscAbsScalar(ba[i]) + PetscAbsScalar(fa[i]) + PetscRealPart(ka[i]) * PetscAbsScalar(wa[i]);
    ra[i] = ba[i] + fa[i] - ra[i];
  }
  PetscCall(VecRestoreArrayWrite(scale, &sa));
  PetscCall(VecRestoreArray(r, &ra));
  PetscCall(VecRestoreArrayRead(ct->Kt_rowabs, &ka));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(VecRestoreArrayRead(react, &fa));
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetSolveTolerance - Sets the relative tolerance the iterative contact solves stop at:
  ||K~ w - b - f_c|| <= tol ||b||

  Logically Collective

  Input Parameters:
+ ct  - the contact object
- tol - the tolerance, in (0, 1)

  Note:
  -contact_tol gives the first one. The stepper tightens it when a step's solve was not exact
  enough for the step's certificate (src/ts/certificate.c) and loosens it back towards
  -contact_tol while the steps' certificates hold with room to spare: the iterative solves then do
  no more work than the certificate needs. The factorizing solves are exact whatever it is.

  Level: developer

.seealso: `MMContactGetSolveTolerance()`, `MMContactStepResidual()`
@*/
PetscErrorCode MMContactSetSolveTolerance(MMContact ct, PetscReal tol)
{
  PetscFunctionBeginUser;
  ct->tol       = tol;
  ct->qp.rtol_b = tol;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetSolveTolerance - Gives the relative tolerance of the iterative contact solves

  Not Collective

  Input Parameter:
. ct - the contact object

  Output Parameters:
+ tol  - the tolerance in force now
- user - -contact_tol, the one the run started with

  Level: developer

.seealso: `MMContactSetSolveTolerance()`
@*/
PetscErrorCode MMContactGetSolveTolerance(MMContact ct, PetscReal *tol, PetscReal *user)
{
  PetscFunctionBeginUser;
  if (tol) *tol = ct->tol;
  if (user) *user = ct->opt.contact_tol;
  PetscFunctionReturn(0);
}
