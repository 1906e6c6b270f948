/* The contact frame (docs/method.md section 2): the w-frame operators from fem's Cartesian ones.
 * Each contact node's dofs are rotated into its frame (nu, tau_1, tau_2) by Q, built with the contact
 * set (interface/set.c): K <- Q^T K Q, M <- Q^T M Q, L <- Q^T L; then M* for -mass (mass_star.c) and
 * the contact pairs' relative variables, A <- N^T A N (interface/pairs.c, docs/method.md section 11).
 * The results stay in fem's MMOperators, which app hands in: the stepper, the output and the
 * audits read them there. */
#include "../contactimpl.h"

/* K <- Q^T K Q and M <- Q^T M Q in place. Q is block diagonal by vertex, so the pattern stays:
 * MatPtAP would build new matrices, through a symbolic product that costs more than the closed-form
 * assembly (docs/scaling.md, "Assembly of K and M, measured"). A lumped M is m I at each node, which
 * the rotation leaves unchanged: it is not rotated, so that no round-off enters it. */
static PetscErrorCode RotateOperators(MMOperators *op)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameRotate, 0, 0, 0, 0));
  PetscCall(MMRotateP1(op->Q, op->K, op->lumped ? NULL : op->M));
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameRotate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* v <- Q^T v for a force on the free dofs (the load, the lift): v keeps its layout and DM. */
static PetscErrorCode RotateForce(Mat Q, Vec v)
{
  Vec cart;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(v, &cart));
  PetscCall(VecCopy(v, cart));
  PetscCall(MatMultTranspose(Q, cart, v));
  PetscCall(VecDestroy(&cart));
  PetscFunctionReturn(0);
}

/* The contact boundary as M* sees it: without contact, no dof loses its mass. */
static void MassBoundary(MMContact ct, MMMassBoundary *mb)
{
  mb->massless     = ct->enabled ? ct->is_massless : NULL;
  mb->n            = ct->n_local;
  mb->vertex       = ct->vertex;
  mb->scalar_index = ct->scalar_index;
  mb->second       = ct->second;
  mb->frame        = ct->node_frame;
  mb->fc_obstacle  = ct->fc_obstacle;
}

PetscErrorCode MMContactSetUpFrame(MMContact ct, MMOperators *op, const MMMaterial *material)
{
  MMMassBoundary mb;

  PetscFunctionBeginUser;
  PetscCheck(op == ct->op, ct->comm, PETSC_ERR_ARG_WRONG, "The contact frame rotates the operators given to MMContactSetUp, whose Q it built");
  PetscCall(RotateOperators(op));
  PetscCall(RotateForce(op->Q, op->load));
  PetscCall(RotateForce(op->Q, op->lift));
  MassBoundary(ct, &mb);
  PetscCall(MMContactMassStar(&ct->mass, op, material, &mb));
  if (op->N) PetscCall(VecDuplicate(op->load, &op->pair_work));
  PetscCall(MMContactPairsTransformOperators(ct, op));
  PetscFunctionReturn(0);
}
