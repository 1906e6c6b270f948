/* The w-frame data other components keep (docs/developer.md, "The contact frame"): a holder (the
 * stepper) registers once the addresses of its w-frame vectors and matrices; when contact's frames
 * turn (-contact_frames follow, frames.c) or its pairing changes (large sliding, pairs_sliding.c), contact
 * turns or carries them all here, with its own load and lift, in one order: the kinematic vectors,
 * the state's forces, contact's load and lift, the set-up forces. What a holder builds on the frame
 * instead of turning (the momentum functionals) it rebuilds when MMContactGetFrameState() changes. */
#include "../contactimpl.h"
#include "fem.h"

/*@
  MMContactFramesAddVec - Registers a w-frame vector another component keeps, so that contact turns
  or carries it with its own

  Not collective

  Input Parameters:
+ ct   - the contact object
. type - how the vector transforms and whether a checkpoint holds it
- x    - the address of the holder's vector (the holder may replace the object behind it, a NULL one is skipped)

  Level: developer

.seealso: `MMContactFramesAddMat()`, `MMContactGetFrameState()`
@*/
PetscErrorCode MMContactFramesAddVec(MMContact ct, MMFrameVecType type, Vec *x)
{
  MMContactHeld *h = &ct->held;

  PetscFunctionBeginUser;
  PetscCall(PetscRealloc((h->nvec + 1) * sizeof(*h->vec), &h->vec));
  PetscCall(PetscRealloc((h->nvec + 1) * sizeof(*h->type), &h->type));
  h->vec[h->nvec]  = x;
  h->type[h->nvec] = type;
  h->nvec++;
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesAddMat - Registers a w-frame matrix another component keeps, so that it turns with
  the frames (A <- R^T A R)

  Not collective

  Input Parameters:
+ ct - the contact object
- A  - the address of the holder's matrix

  Level: developer

.seealso: `MMContactFramesAddVec()`, `MMContactGetFrameState()`
@*/
PetscErrorCode MMContactFramesAddMat(MMContact ct, Mat *A)
{
  MMContactHeld *h = &ct->held;

  PetscFunctionBeginUser;
  PetscCall(PetscRealloc((h->nmat + 1) * sizeof(*h->mat), &h->mat));
  h->mat[h->nmat++] = A;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetFrameState - Gives the frame state, which counts the frames' turns and new pairings

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. state - the frame state: what a holder built on the frames is stale when it changed

  Level: developer

.seealso: `MMContactFramesAddVec()`, `MMContactFramesAddMat()`
@*/
PetscErrorCode MMContactGetFrameState(MMContact ct, PetscObjectState *state)
{
  PetscFunctionBeginUser;
  *state = ct->held.state;
  PetscFunctionReturn(0);
}

/* The held vectors of one type through fn, in their registration order (NULL ones skipped) */
static PetscErrorCode TransformType(MMContact ct, MMFrameVecType type, MMContactHeldFn fn, void *fctx)
{
  MMContactHeld *h = &ct->held;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < h->nvec; ++i)
    if (h->type[i] == type && *h->vec[i]) PetscCall(fn(ct, fctx, (PetscBool)(type != MM_FRAME_KINEMATIC), *h->vec[i]));
  PetscFunctionReturn(0);
}

/* Every w-frame vector, contact's load and lift and the held ones, through fn (force: the vector is
 * force-like), in the one order of the file's head; state: also the state's vectors (a restore reads
 * them from its checkpoint, already in the new variables). The held matrices are the frames' alone
 * (MMContactHeldTurnMatrices). The frame state moves: what was built on the old frame is stale. */
PetscErrorCode MMContactHeldTransform(MMContact ct, PetscBool state, MMContactHeldFn fn, void *fctx)
{
  PetscFunctionBeginUser;
  if (state) {
    PetscCall(TransformType(ct, MM_FRAME_KINEMATIC, fn, fctx));
    PetscCall(TransformType(ct, MM_FRAME_FORCE, fn, fctx));
  }
  PetscCall(fn(ct, fctx, PETSC_TRUE, ct->load));
  PetscCall(fn(ct, fctx, PETSC_TRUE, ct->lift));
  PetscCall(TransformType(ct, MM_FRAME_SETUP_FORCE, fn, fctx));
  ct->held.state++;
  PetscFunctionReturn(0);
}

/* The held matrices A <- R^T A R (frames that follow; a new pairing leaves them to their holder,
 * whose pattern follows N) */
PetscErrorCode MMContactHeldTurnMatrices(MMContact ct, Mat R)
{
  MMContactHeld *h = &ct->held;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < h->nmat; ++i)
    if (*h->mat[i]) PetscCall(MMRotateP1(R, *h->mat[i], NULL));
  PetscFunctionReturn(0);
}

/* A new pairing restored from a checkpoint: nothing turns (the holders read their vectors from the
 * checkpoint in its variables), but what was built on the old pairing is stale */
PetscErrorCode MMContactHeldInvalidate(MMContact ct)
{
  PetscFunctionBeginUser;
  ct->held.state++;
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactHeldDestroy(MMContactHeld *h)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(h->vec));
  PetscCall(PetscFree(h->type));
  PetscCall(PetscFree(h->mat));
  h->nvec = h->nmat = 0;
  PetscFunctionReturn(0);
}
