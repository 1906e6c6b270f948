/* The w-frame operators as the other components read them (docs/developer.md, "The contact frame"):
 * contact's, as they are now. They are rebuilt when the frames turn or the pairing changes, so a
 * reader asks for them when it uses them (MMContactGetOperators) rather than keep them; and the one
 * w-frame operator the stepper needs built, the condensed damping stiffness. */
#include "../contactimpl.h"

/*@
  MMContactGetOperators - Gives the w-frame operators as they are now: K, M*, the load, the lift,
  M*'s rigid mass and its massless dofs

  Not collective

  Input Parameter:
. ct - the contact object, its frame set up

  Output Parameter:
. ops - the operators, borrowed: rebuilt when the frames turn or the pairing changes

  Level: intermediate

.seealso: `MMContactSetUpFrame()`, `MMContactHasMasslessDofs()`
@*/
PetscErrorCode MMContactGetOperators(MMContact ct, MMContactOperators *ops)
{
  PetscFunctionBeginUser;
  ops->K             = ct->K;
  ops->Mstar         = ct->mass.Mstar;
  ops->load          = ct->load;
  ops->lift          = ct->lift;
  ops->mass_star     = ct->mass.mass_star;
  ops->mass_star_inv = ct->mass.mass_star_inv;
  ops->massless      = ct->mass.massless;
  PetscFunctionReturn(0);
}

/*@
  MMContactHasMasslessDofs - Tells whether M* has dofs without inertia

  Not collective

  Input Parameter:
. ct - the contact object

  Level: intermediate

.seealso: `MMContactGetOperators()`, `MMContactGetMassType()`
@*/
PetscBool MMContactHasMasslessDofs(MMContact ct)
{
  return (PetscBool)(ct->mass.massless != NULL);
}

/*@
  MMContactFrameMatrixBegin - Gives the matrix into which a Cartesian P1 stiffness (the
  finite-strain tangent) is assembled before MMContactFrameMatrixEnd() turns it into the w-frame

  Collective

  Input Parameters:
+ ct - the contact object
- Kw - the w-frame matrix, of K's pattern

  Output Parameter:
. Kc - Kw itself without contact pairs, else contact's own Cartesian P1 matrix

  Note:
  A Cartesian P1 stiffness the caller assembles (the finite-strain tangent), turned into the w-frame
  as K is (docs/method.md sections 2 and 11). Begin: the matrix to assemble into, Kw itself (K's
  pattern) without contact pairs, else contact's P1 one. End: Q^T Kc Q in place, and with pairs
  N^T (.) N into Kw, the product kept so that later ones reuse its pattern (dropped at a new pairing,
  pairs.c).

  Level: intermediate

.seealso: `MMContactFrameMatrixEnd()`, `MMElasticityAssembleTangent()`
@*/
PetscErrorCode MMContactFrameMatrixBegin(MMContact ct, Mat Kw, Mat *Kc)
{
  PetscFunctionBeginUser;
  if (!ct->transform.N) *Kc = Kw;
  else {
    if (!ct->frame_Kp) PetscCall(MMFECreateMatrix(ct->op, ct->dm, &ct->frame_Kp));
    *Kc = ct->frame_Kp;
  }
  PetscFunctionReturn(0);
}

/*@
  MMContactFrameMatrixEnd - Turns the assembled Cartesian stiffness into the w-frame: Q^T Kc Q, and
  with contact pairs N^T (.) N into Kw

  Collective

  Input Parameters:
+ ct - the contact object
. Kc - the matrix MMContactFrameMatrixBegin() gave, assembled
- Kw - the w-frame matrix, set on return

  Level: intermediate

.seealso: `MMContactFrameMatrixBegin()`, `MMRotateP1()`
@*/
PetscErrorCode MMContactFrameMatrixEnd(MMContact ct, Mat Kc, Mat Kw)
{
  PetscFunctionBeginUser;
  if (!ct->transform.N) {
    if (ct->transform.Q) PetscCall(MMRotateP1(ct->transform.Q, Kw, NULL)); /* into the contact nodes' frames, as K is */
  } else {
    PetscCall(MMRotateP1(ct->transform.Q, Kc, NULL));
    PetscCall(MatPtAP(Kc, ct->transform.N, ct->frame_KpN ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, 2.0, &ct->frame_KpN));
    PetscCall(MatCopy(ct->frame_KpN, Kw, SAME_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

/*@
  MMContactDampingStiffness - Builds the Rayleigh damping stiffness B of the linear law in the
  w-frame, its massless dofs condensed cell by cell

  Collective

  Input Parameters:
+ ct          - the contact object, its frame set up
. material    - the bodies' material
- is_massless - the massless dofs to condense

  Output Parameter:
. B - the new matrix

  Note:
  B with the massless dofs (the contact normals and the friction corners' tau_1, docs/method.md
  section 12) condensed cell by cell (MMAssembleP1DampingStiffness), in the w-frame of
  K: the cells are rotated by Q there, and contact pairs transform it by N as K (N^T B N keeps the
  slave-normal rows and columns zero: N's columns of those dofs are unit vectors). Its massless
  rows and columns are then set to zero exactly, against the condensation's round-off.

  Level: intermediate

.seealso: `MMAssembleP1DampingStiffness()`, `MMContactGetOperators()`
@*/
PetscErrorCode MMContactDampingStiffness(MMContact ct, const MMMaterial *material, IS is_massless, Mat *B)
{
  MMOperators        op = ct->op;
  Vec                mark;

  PetscFunctionBeginUser;
  PetscCall(MMFECreateMatrix(op, ct->dm, B));
  PetscCall(DMCreateGlobalVector(ct->dm, &mark));
  PetscCall(VecZeroEntries(mark));
  PetscCall(VecISSet(mark, is_massless, 1.0));
  PetscCall(MMAssembleP1DampingStiffness(ct->dm, material, ct->transform.Q, mark, *B));
  PetscCall(VecDestroy(&mark));
  if (ct->transform.N) {
    Mat BN;
    PetscCall(MatPtAP(*B, ct->transform.N, MAT_INITIAL_MATRIX, 2.0, &BN));
    PetscCall(MatDestroy(B));
    *B = BN;
  }
  PetscCall(MatZeroRowsColumnsIS(*B, is_massless, 0.0, NULL, NULL));
  PetscFunctionReturn(0);
}
