/* The contact frame (docs/method.md section 2): the w-frame operators from fem's Cartesian ones.
 * Each contact node's dofs are rotated into its frame (nu, tau_1, tau_2) by Q, built here from the
 * frames the contact set chose (interface/set.c): K <- Q^T K Q and M <- Q^T M Q on the matrices fem
 * hands over (MMFEHandMatrices), contact's L = Q^T L (fem's load and lift stay Cartesian); then M*
 * for -mass (mass_star.c) and the contact pairs' relative variables, A <- N^T A N (interface/pairs.c,
 * docs/method.md section 11). The w-frame K, M, load and lift are contact's own, as are Q and N
 * (transform.c); the stepper, the output and the audits read them through contact (operators.c,
 * MMContactGetOperators). */
#include "../contactimpl.h"

/* Q, u_cart = Q w: per contact node the block of its frame, F^T (the columns nu, tau_1, tau_2), the
 * identity elsewhere; a corner's block is its first row's frame. Q is contact's (ct->transform), and
 * fem's frame transforms (MMFEToCartesian) reach it through the ops installed here (transform.c). */
PetscErrorCode MMContactFrameBuildRotation(MMContact ct, MMOperators op)
{
  const PetscInt  dim = ct->dim;
  PetscInt        n, rstart, nrow = 0;
  const PetscInt *in = NULL;
  PetscBool      *rotated;
  Vec             g;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(ct->dm, &g));
  PetscCall(VecGetLocalSize(g, &n));
  PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
  PetscCall(DMRestoreGlobalVector(ct->dm, &g));
  PetscCall(MatCreateAIJ(ct->comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, ct->enabled ? dim : 1, NULL, 0, NULL, &ct->transform.Q));
  PetscCall(PetscCalloc1(n, &rotated));
  if (ct->enabled) {
    PetscCall(ISGetLocalSize(ct->is_normal, &nrow));
    PetscCall(ISGetIndices(ct->is_normal, &in));
  }
  for (PetscInt k = 0; k < nrow; ++k) {
    const PetscReal *F = &ct->node_frame[9 * k];
    if (ct->second[k]) continue; /* in[k] is the node's dof 1: its block starts at the row before */
    for (PetscInt d = 0; d < dim; ++d) {
      rotated[in[k] - rstart + d] = PETSC_TRUE;
      for (PetscInt e = 0; e < dim; ++e) PetscCall(MatSetValue(ct->transform.Q, in[k] + d, in[k] + e, F[3 * e + d], INSERT_VALUES));
    }
  }
  if (ct->enabled) PetscCall(ISRestoreIndices(ct->is_normal, &in));
  for (PetscInt i = 0; i < n; ++i)
    if (!rotated[i]) PetscCall(MatSetValue(ct->transform.Q, rstart + i, rstart + i, 1.0, INSERT_VALUES));
  PetscCall(PetscFree(rotated));
  PetscCall(MatAssemblyBegin(ct->transform.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->transform.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MMContactFrameInstall(ct, op));
  PetscFunctionReturn(0);
}

/* K <- Q^T K Q and M <- Q^T M Q in place. Q is block diagonal by vertex, so the pattern stays:
 * MatPtAP would build new matrices, through a symbolic product that costs more than the closed-form
 * assembly (docs/scaling.md, "Assembly of K and M, measured"). A lumped M is m I at each node, which
 * the rotation leaves unchanged: it is not rotated, so that no round-off enters it. */
static PetscErrorCode RotateOperators(Mat Q, MMOperators op, Mat *K, Mat *M)
{
  PetscBool lumped;

  PetscFunctionBeginUser;
  PetscCall(MMFEIsMassLumped(op, &lumped));
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameRotate, 0, 0, 0, 0));
  /* fem hands its K and M over rather than keeping a Cartesian copy: one matrix of K's pattern less
   * for the whole run (at a million dofs, hundreds of MB; docs/scaling.md) */
  PetscCall(MMFEHandMatrices(op, K, M));
  PetscCall(MMRotateP1(Q, *K, lumped ? NULL : *M));
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameRotate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* w = Q^T cart for a force on the free dofs (the load, the lift): contact's w-frame copy, of cart's
 * layout and DM (VecDuplicate); fem's cart stays Cartesian. */
static PetscErrorCode RotateForce(Mat Q, Vec cart, Vec *w)
{
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(cart, w));
  PetscCall(MatMultTranspose(Q, cart, *w));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetUpFrame - Takes fem's K and M (MMFEHandMatrices) and turns them into contact's
  w-frame ones, and makes its own w-frame load and lift from fem's (which stay Cartesian): Q^T A Q,
  the mass M* of -mass, and the contact pairs' N^T A N

  Collective

  Input Parameters:
+ ct       - the contact object, set up
. op       - the operators given to MMContactSetUp(), assembled
- material - the bodies' material

  Note:
  Rotation first, then M* (its massless dofs are the frame's normal dofs, and its moments are taken
  in the contact frame), then the pairs' N^T A N, which leaves those moments unchanged
  (docs/method.md sections 2 and 11).

  Level: intermediate

.seealso: `MMContactSetUp()`, `MMFEAssembleOperators()`, `MMFEAssembleOperatorsEnd()`, `MMContactGetOperators()`
@*/
PetscErrorCode MMContactSetUpFrame(MMContact ct, MMOperators op, const MMMaterial *material)
{
  MMMassBoundary mb;
  Vec            load, lift;

  PetscFunctionBeginUser;
  PetscCheck(op == ct->op, ct->comm, PETSC_ERR_ARG_WRONG, "The contact frame rotates the operators given to MMContactSetUp, whose Q it built");
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameSetUp, 0, 0, 0, 0));
  PetscCall(RotateOperators(ct->transform.Q, op, &ct->K, &ct->mass.M));
  PetscCall(MMFEGetLoad(op, &load)); /* fem's load and lift stay Cartesian */
  PetscCall(MMFEGetLift(op, &lift));
  PetscCall(RotateForce(ct->transform.Q, load, &ct->load));
  PetscCall(RotateForce(ct->transform.Q, lift, &ct->lift));
  /* frames that follow the contact point rebuild M* from the whole w-frame M, turned with them */
  if (ct->frames.follow) PetscCall(MatDuplicate(ct->mass.M, MAT_COPY_VALUES, &ct->frames.M));
  PetscCall(MMContactMassFreeSetUp(ct)); /* the mass in free flight keeps it too (mass_free.c) */
  MMContactMassBoundary(ct, &mb);
  PetscCall(MMContactMassStar(&ct->mass, op, material, &mb));
  if (ct->transform.N) PetscCall(VecDuplicate(load, &ct->transform.pair_work));
  PetscCall(MMContactPairsTransformOperators(ct, op));
  /* M served only to build M* and to check M*'s moments against it: the steps, the audit and the
   * diagnostics use M*. Freed here, before any factorization, it leaves the run's peak memory: one
   * matrix of K's pattern (its size: docs/scaling.md, "The figures behind the code's choices") */
  PetscCall(MatDestroy(&ct->mass.M));
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
