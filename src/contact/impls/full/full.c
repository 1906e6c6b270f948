/* The full formulation (docs/method.md section 3): the step's bound-constrained QP
 * min 1/2 w.K~w - b.w s.t. w_c <= g solved by SNESVI on the whole dof vector (prefix contact_),
 * whose Newton steps factor K~'s block on the free dofs. Frictionless: it cannot solve the contact
 * dofs alone, and has no Delassus operator. */
#include "fullimpl.h"

/* Bounds on the whole w vector: w_c <= g on the normal dofs, free elsewhere. */
static PetscErrorCode SetBounds(MMContact ct, Vec lower, Vec upper)
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

/* The VI's Newton steps factor K~ (pc_vifactor.c by default): a failed factorization stops the run
 * naming the factor's reason, where the VI alone would say only DIVERGED_LINEAR_SOLVE. */
static PetscErrorCode FullSetUp(MMContact ct)
{
  KSP        ksp;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(ct->qp.b, &ct->lower));
  PetscCall(VecDuplicate(ct->qp.b, &ct->upper));
  PetscCall(MMQPCreate(PetscObjectComm((PetscObject)ct->dm), "contact_", &ct->qp, 0, &MMFullData(ct)->snes));
  PetscCall(MMQPSetFactorSPD(MMFullData(ct)->snes));
  PetscCall(SNESGetKSP(MMFullData(ct)->snes, &ksp));
  PetscCall(MMKSPSetFailureCheck(ksp));
  PetscCall(SetBounds(ct, ct->lower, ct->upper));
  PetscCall(SNESVISetVariableBounds(MMFullData(ct)->snes, ct->lower, ct->upper));
  PetscFunctionReturn(0);
}

/* A new K~ (set-up, a new dt): a vifactor PC orders and analyses it now, once. */
static PetscErrorCode FullSetOperator(MMContact ct)
{
  KSP ksp;
  PC  pc;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(MMFullData(ct)->snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(MMPCVIFactorAnalyse(pc, ct->qp.A));
  PetscFunctionReturn(0);
}

/* The bounds are the step's: an increment's are g - u^n (MMContactShiftBounds, docs/method.md
 * section 3), a moving obstacle's move with it */
static PetscErrorCode FullSolve(MMContact ct, Vec b, Vec w, Vec react)
{
  Vec sub;

  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(ct->upper, ct->is_normal, &sub));
  PetscCall(VecCopy(ct->gap, sub));
  PetscCall(VecRestoreSubVector(ct->upper, ct->is_normal, &sub));
  PetscCall(VecCopy(b, ct->qp.b));
  PetscCall(MMQPSolve(MMFullData(ct)->snes, &ct->qp, w, &ct->vi_its));
  PetscCall(MMContactForce(ct, b, w, react));
  PetscFunctionReturn(0);
}

/* The VI factors K~'s free block in each iteration with its own linear solver (prefix contact_). */
static PetscErrorCode FullGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(MMFullData(ct)->snes, krylov));
  *pc_ksp = *krylov;
  PetscFunctionReturn(0);
}

static PetscErrorCode FullDestroy(MMContact ct)
{
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&MMFullData(ct)->snes));
  PetscCall(PetscFree(ct->data));
  PetscFunctionReturn(0);
}

static const MMContactOps FullOps = {
  .setup       = FullSetUp,
  .setoperator = FullSetOperator,
  .solve       = FullSolve,
  .getstepksp  = FullGetStepKSP,
  .destroy     = FullDestroy,
};

PetscErrorCode MMContactCreate_Full(MMContact ct)
{
  MMContact_Full *full;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&full));
  ct->data = full;
  ct->ops  = &FullOps;
  PetscFunctionReturn(0);
}
