/* The "none" contact formulation (-contact 0): no contact boundary, each step is one solve with
 * K~ (interface/kt.c: a factorization, or CG where the cost model predicts it faster). It has no state of its own
 * (data NULL) and lacks every capability the others add: friction, the Delassus operator, the kept
 * K~, a warm start to checkpoint. Adding a formulation is a folder like this one and one
 * MMContactRegister line (interface/contact.c). */
#include "../../contactimpl.h"

static PetscErrorCode NoneSetUp(MMContact ct)
{
  PetscFunctionBeginUser;
  /* CG where the cost model (or -iterative_dofs) prefers it to the factor: on large 3D problems its
   * solves are faster than the factor's triangular solves, with a fraction of its set-up (contact.c;
   * docs/scaling.md, "The linear path chosen by cost") */
  PetscCall(MMKtCreate(ct, ct->prefer_iterative, MMKtDefaultPC(ct->comm)));
  PetscFunctionReturn(0);
}

static PetscErrorCode NoneSetOperator(MMContact ct)
{
  PetscFunctionBeginUser;
  PetscCall(MMKtSetOperator(ct, ct->qp.A));
  PetscFunctionReturn(0);
}

static PetscErrorCode NoneSolve(MMContact ct, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(MMKtSolve(ct, b, w));
  PetscCall(MMContactForce(ct, b, w, react));
  PetscFunctionReturn(0);
}

static PetscErrorCode NoneGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  *krylov = *pc_ksp = ct->kt.ksp;
  PetscFunctionReturn(0);
}

static const MMContactOps NoneOps = {
  .setup       = NoneSetUp,
  .setoperator = NoneSetOperator,
  .solve       = NoneSolve,
  .getstepksp  = NoneGetStepKSP,
};

PetscErrorCode MMContactCreate_None(MMContact ct)
{
  PetscFunctionBeginUser;
  ct->ops = &NoneOps;
  PetscFunctionReturn(0);
}
