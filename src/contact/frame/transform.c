/* The frame's transforms, contact's own, and the ops table that hands them to fem's operators
 * (docs/developer.md, "The contact frame"; docs/method.md sections 2 and 11). */
#include "../contactimpl.h"
#include "fem.h"

/* Displacements and velocities: u = Q N w, w = N^{-1} Q^T u (N = I without contact pairs or corners,
 * Q orthogonal). Forces, their duals: f = Q N^{-T} f_w, f_w = N^T Q^T f (docs/method.md section 11).
 * One pass of each: to Cartesian, N (or N^{-T}) then Q; from it, Q^T then N^{-1} (or N^T). */
static PetscErrorCode FrameTransform(const MMContactTransform *xf, PetscBool to_cartesian, Mat Nmat, PetscBool n_transpose, Vec x, Vec y)
{
  Vec t = xf->pair_work;

  PetscFunctionBeginUser;
  if (!xf->N) {
    if (to_cartesian) PetscCall(MatMult(xf->Q, x, y));
    else PetscCall(MatMultTranspose(xf->Q, x, y));
    PetscFunctionReturn(0);
  }
  if (to_cartesian) {
    if (n_transpose) PetscCall(MatMultTranspose(Nmat, x, t));
    else PetscCall(MatMult(Nmat, x, t));
    PetscCall(MatMult(xf->Q, t, y));
  } else {
    PetscCall(MatMultTranspose(xf->Q, x, t));
    if (n_transpose) PetscCall(MatMultTranspose(Nmat, t, y));
    else PetscCall(MatMult(Nmat, t, y));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ToCartesian(void *ctx, Vec w, Vec ucart)
{
  const MMContactTransform *xf = &((MMContact)ctx)->transform;

  PetscFunctionBeginUser;
  PetscCall(FrameTransform(xf, PETSC_TRUE, xf->N, PETSC_FALSE, w, ucart));
  PetscFunctionReturn(0);
}

static PetscErrorCode FromCartesian(void *ctx, Vec ucart, Vec w)
{
  const MMContactTransform *xf = &((MMContact)ctx)->transform;

  PetscFunctionBeginUser;
  PetscCall(FrameTransform(xf, PETSC_FALSE, xf->Ninv, PETSC_FALSE, ucart, w));
  PetscFunctionReturn(0);
}

static PetscErrorCode ForceToCartesian(void *ctx, Vec fw, Vec fcart)
{
  const MMContactTransform *xf = &((MMContact)ctx)->transform;

  PetscFunctionBeginUser;
  PetscCall(FrameTransform(xf, PETSC_TRUE, xf->Ninv, PETSC_TRUE, fw, fcart));
  PetscFunctionReturn(0);
}

static PetscErrorCode ForceFromCartesian(void *ctx, Vec fcart, Vec fw)
{
  const MMContactTransform *xf = &((MMContact)ctx)->transform;

  PetscFunctionBeginUser;
  PetscCall(FrameTransform(xf, PETSC_FALSE, xf->N, PETSC_TRUE, fcart, fw));
  PetscFunctionReturn(0);
}

/* Hands fem's operators the frame: its transforms read Q and N through ct when called, so a frame
 * that turns or a new pairing needs no second install. */
PetscErrorCode MMContactFrameInstall(MMContact ct, MMOperators op)
{
  static const MMFrameOps ops = {ToCartesian, FromCartesian, ForceToCartesian, ForceFromCartesian};

  PetscFunctionBeginUser;
  PetscCall(MMFESetFrame(op, &ops, ct));
  ct->mass.Q = ct->transform.Q;
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactTransformDestroy(MMContactTransform *xf)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&xf->Q));
  PetscCall(MatDestroy(&xf->N));
  PetscCall(MatDestroy(&xf->Ninv));
  PetscCall(VecDestroy(&xf->pair_work));
  PetscFunctionReturn(0);
}
