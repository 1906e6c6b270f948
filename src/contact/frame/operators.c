/* The w-frame operators as the other components read them (docs/developer.md, "The contact frame"):
 * contact's, as they are now. They are rebuilt when the frames turn or the pairing changes, so a
 * reader asks for them when it uses them (MMContactGetOperators) rather than keep them; and the one
 * w-frame operator the stepper needs built, the condensed damping stiffness. */
#include "../contactimpl.h"

PetscErrorCode MMContactGetOperators(MMContact ct, MMContactOperators *ops)
{
  const MMOperators *op = ct->op;

  PetscFunctionBeginUser;
  ops->K             = op->K;
  ops->Mstar         = ct->mass.Mstar;
  ops->load          = op->load;
  ops->lift          = op->lift;
  ops->mass_star     = ct->mass.mass_star;
  ops->mass_star_inv = ct->mass.mass_star_inv;
  ops->massless      = ct->mass.massless;
  PetscFunctionReturn(0);
}

PetscBool MMContactHasMasslessDofs(MMContact ct)
{
  return (PetscBool)(ct->mass.massless != NULL);
}

/* A Cartesian P1 stiffness the caller assembles (the finite-strain tangent), turned into the w-frame
 * as K is (docs/method.md sections 2 and 11). Begin: the matrix to assemble into, Kw itself (K's
 * pattern) without contact pairs, else contact's P1 one. End: Q^T Kc Q in place, and with pairs
 * N^T (.) N into Kw, the product kept so that later ones reuse its pattern (dropped at a new pairing,
 * pairs.c). */
PetscErrorCode MMContactFrameMatrixBegin(MMContact ct, Mat Kw, Mat *Kc)
{
  PetscFunctionBeginUser;
  if (!ct->op->N) *Kc = Kw;
  else {
    if (!ct->frame_Kp) PetscCall(MMFECreateMatrix(ct->op, ct->op->dm, &ct->frame_Kp));
    *Kc = ct->frame_Kp;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactFrameMatrixEnd(MMContact ct, Mat Kc, Mat Kw)
{
  const MMOperators *op = ct->op;

  PetscFunctionBeginUser;
  if (!op->N) {
    if (op->Q) PetscCall(MMRotateP1(op->Q, Kw, NULL)); /* into the contact nodes' frames, as K is */
  } else {
    PetscCall(MMRotateP1(op->Q, Kc, NULL));
    PetscCall(MatPtAP(Kc, op->N, ct->frame_KpN ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, 2.0, &ct->frame_KpN));
    PetscCall(MatCopy(ct->frame_KpN, Kw, SAME_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

/* B with the massless dofs (the contact normals and the friction corners' tau_1, docs/method.md
 * section 12) condensed cell by cell (MMAssembleP1DampingStiffness), in the w-frame of
 * K: the cells are rotated by Q there, and contact pairs transform it by N as K (N^T B N keeps the
 * slave-normal rows and columns zero: N's columns of those dofs are unit vectors). Its massless
 * rows and columns are then set to zero exactly, against the condensation's round-off. */
PetscErrorCode MMContactDampingStiffness(MMContact ct, const MMMaterial *material, IS is_massless, Mat *B)
{
  const MMOperators *op = ct->op;
  Vec                mark;

  PetscFunctionBeginUser;
  PetscCall(MMFECreateMatrix(op, op->dm, B));
  PetscCall(DMCreateGlobalVector(op->dm, &mark));
  PetscCall(VecZeroEntries(mark));
  PetscCall(VecISSet(mark, is_massless, 1.0));
  PetscCall(MMAssembleP1DampingStiffness(op->dm, material, op->Q, mark, *B));
  PetscCall(VecDestroy(&mark));
  if (op->N) {
    Mat BN;
    PetscCall(MatPtAP(*B, op->N, MAT_INITIAL_MATRIX, 2.0, &BN));
    PetscCall(MatDestroy(B));
    *B = BN;
  }
  PetscCall(MatZeroRowsColumnsIS(*B, is_massless, 0.0, NULL, NULL));
  PetscFunctionReturn(0);
}
