/* TSAdapt "growback", the default of -ts_type newmark (docs/method.md section 4, "Rejected steps").
 *
 * A step the stepper rejects (the friction solver did not converge, or a release would create
 * energy) is retried with dt times -ts_adapt_scale_solve_failed. Growing dt straight back on the
 * next accepted step hits the same difficulty and ping-pongs, refactoring K~ each way. Here dt grows
 * back (by the inverse factor, to the dt values whose factors are kept, up to -ts_dt) only after
 * -ts_adapt_growback_steps accepted steps at the reduced dt when the rejection was of a regime (the
 * friction solver: its difficulty lasts over steps); a grown dt rejected at once doubles the wait,
 * up to -ts_adapt_growback_max_steps. A rejection of an event (a contact release that dt does not
 * resolve, MMAdaptGrowBackRejected with regime false) is over once the step is past it: dt grows on
 * the next step accepted without one (waiting there multiplies the steps of a run whose contact
 * chatters, e.g. -mass standard, by 100). No error estimate is used: the scheme's energy identity
 * holds at every dt. */
#include <petsc/private/tsimpl.h>
#include "newmarkimpl.h"

typedef struct {
  PetscInt wait, wait0, wait_max; /* accepted steps before dt grows; its start and cap */
  PetscInt accepted;              /* accepted steps since dt last changed */
  PetscInt since_growth;          /* accepted steps since dt last grew */
  PetscInt regime_rejects;        /* rejections of a regime (the friction solver) */
  PetscInt regime_seen;           /* regime_rejects at the last choice */
  PetscInt rejects_seen;          /* ts->reject at the last choice */
  PetscBool event;                /* dt was last cut by an event: it grows on every clean step */
} TSAdapt_GrowBack;

static PetscErrorCode TSAdaptChoose_GrowBack(TSAdapt adapt, TS ts, PetscReal h, PetscInt *next_sc, PetscReal *next_h, PetscBool *accept, PetscReal *wlte, PetscReal *wltea, PetscReal *wlter)
{
  TSAdapt_GrowBack *gb       = (TSAdapt_GrowBack *)adapt->data;
  const PetscBool   rejected = (PetscBool)(ts->reject > gb->rejects_seen);
  const PetscBool   regime   = (PetscBool)(gb->regime_rejects > gb->regime_seen);

  PetscFunctionBeginUser;
  *accept       = PETSC_TRUE;
  *next_sc      = 0;
  *wlte         = -1;
  *wltea        = -1;
  *wlter        = -1;
  *next_h       = h;
  gb->rejects_seen = ts->reject;
  gb->regime_seen  = gb->regime_rejects;
  if (rejected && !regime) { /* an event: grow on every clean step from the next one */
    gb->event = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  if (rejected) {
    gb->event = PETSC_FALSE;
    /* the grown dt failed at once: wait longer before the next try */
    if (gb->since_growth == 0) gb->wait = PetscMin(2 * gb->wait, gb->wait_max);
    gb->accepted     = 0;
    gb->since_growth = PETSC_MAX_INT / 2;
    PetscFunctionReturn(0);
  }
  gb->accepted++;
  gb->since_growth++;
  if (h >= adapt->dt_max) gb->event = PETSC_FALSE;
  if (h < adapt->dt_max && (gb->event || gb->accepted >= gb->wait)) {
    *next_h          = PetscMin(adapt->dt_max, h / adapt->scale_solve_failed);
    gb->accepted     = 0;
    gb->since_growth = 0;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TSAdaptSetFromOptions_GrowBack(TSAdapt adapt, PetscOptionItems *PetscOptionsObject)
{
  TSAdapt_GrowBack *gb = (TSAdapt_GrowBack *)adapt->data;

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Grow-back adaptor options (-ts_type newmark)");
  PetscCall(PetscOptionsInt("-ts_adapt_growback_steps", "Accepted steps at a dt reduced by a rejection before dt grows back by 1/-ts_adapt_scale_solve_failed (>= 1)", NULL, gb->wait0, &gb->wait0, NULL));
  PetscCall(PetscOptionsInt("-ts_adapt_growback_max_steps", "The longest wait: each rejection soon after a growth doubles the wait, up to this", NULL, gb->wait_max, &gb->wait_max, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(gb->wait0 >= 1 && gb->wait_max >= gb->wait0, PetscObjectComm((PetscObject)adapt), PETSC_ERR_USER_INPUT, "-ts_adapt_growback_steps %" PetscInt_FMT " must be >= 1 and at most -ts_adapt_growback_max_steps %" PetscInt_FMT, gb->wait0, gb->wait_max);
  gb->wait = gb->wait0;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSAdaptView_GrowBack(TSAdapt adapt, PetscViewer viewer)
{
  TSAdapt_GrowBack *gb = (TSAdapt_GrowBack *)adapt->data;
  PetscBool         ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii) PetscCall(PetscViewerASCIIPrintf(viewer, "  grows back after %" PetscInt_FMT " accepted steps (now %" PetscInt_FMT ", at most %" PetscInt_FMT ")\n", gb->wait0, gb->wait, gb->wait_max));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSAdaptDestroy_GrowBack(TSAdapt adapt)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(adapt->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSAdaptCreate_GrowBack(TSAdapt adapt)
{
  TSAdapt_GrowBack *gb;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&gb));
  gb->wait0    = 5;
  gb->wait     = gb->wait0;
  gb->wait_max = 80;
  gb->since_growth        = PETSC_MAX_INT / 2;
  adapt->data             = gb;
  /* the final stretch as one shortened step (MatchFinalTime in newmark.c), not split in two halves
   * as TSAdapt does by default: each new dt is a factorization of K~ */
  adapt->matchstepfac[1]  = 0.0;
  adapt->ops->choose         = TSAdaptChoose_GrowBack;
  adapt->ops->setfromoptions = TSAdaptSetFromOptions_GrowBack;
  adapt->ops->view           = TSAdaptView_GrowBack;
  adapt->ops->destroy        = TSAdaptDestroy_GrowBack;
  PetscFunctionReturn(0);
}

/*@
  MMAdaptGrowBackRejected - Notes a rejected step for the TSAdapt growback: a regime or an event

  Logically collective

  Input Parameters:
+ ts     - the TS
- regime - PETSC_TRUE when the cause lasts over steps (a friction solve that does not converge at this dt), PETSC_FALSE for an event within the step (a release)

  Level: developer

.seealso: `MMAdaptGrowBackGetState()`
@*/
PetscErrorCode MMAdaptGrowBackRejected(TS ts, PetscBool regime)
{
  TSAdapt   adapt;
  PetscBool gb;

  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTGROWBACK, &gb));
  if (gb && regime) ((TSAdapt_GrowBack *)adapt->data)->regime_rejects++;
  PetscFunctionReturn(0);
}

PetscErrorCode MMAdaptGrowBackRegister(void)
{
  PetscFunctionBeginUser;
  PetscCall(TSAdaptRegister(TSADAPTGROWBACK, TSAdaptCreate_GrowBack));
  PetscFunctionReturn(0);
}

/*@
  MMAdaptGrowBackGetState - Gives the TSAdapt growback's state, for a checkpoint

  Not collective

  Input Parameter:
. ts - the TS

  Output Parameter:
. state - the wait, the accepted steps, the steps since the last growth and the event flag (0s for another adaptor)

  Note:
  The adaptor's state, for a checkpoint: the dt sequence after a restart continues as it would have
  (0s for another adaptor).

  Level: developer

.seealso: `MMAdaptGrowBackSetState()`, `MMCheckpointWrite()`
@*/
PetscErrorCode MMAdaptGrowBackGetState(TS ts, PetscReal state[MM_ADAPT_STATE])
{
  TSAdapt   adapt;
  PetscBool gb;

  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTGROWBACK, &gb));
  for (PetscInt i = 0; i < MM_ADAPT_STATE; ++i) state[i] = 0;
  if (!gb) PetscFunctionReturn(0);
  state[0] = ((TSAdapt_GrowBack *)adapt->data)->wait;
  state[1] = ((TSAdapt_GrowBack *)adapt->data)->accepted;
  state[2] = PetscMin(((TSAdapt_GrowBack *)adapt->data)->since_growth, 1e9);
  state[3] = ((TSAdapt_GrowBack *)adapt->data)->event;
  PetscFunctionReturn(0);
}

/*@
  MMAdaptGrowBackSetState - Restores the TSAdapt growback's state from a checkpoint, so that dt
  continues as it would have

  Logically collective

  Input Parameters:
+ ts    - the TS
- state - the state MMAdaptGrowBackGetState() gave

  Level: developer

.seealso: `MMAdaptGrowBackGetState()`, `MMCheckpointLoad()`
@*/
PetscErrorCode MMAdaptGrowBackSetState(TS ts, const PetscReal state[MM_ADAPT_STATE])
{
  TSAdapt           adapt;
  TSAdapt_GrowBack *g;
  PetscBool         gb;

  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTGROWBACK, &gb));
  if (!gb || state[0] < 1) PetscFunctionReturn(0);
  g               = (TSAdapt_GrowBack *)adapt->data;
  g->wait         = (PetscInt)state[0];
  g->accepted     = (PetscInt)state[1];
  g->since_growth = state[2] >= 1e9 ? PETSC_MAX_INT / 2 : (PetscInt)state[2];
  g->event        = (PetscBool)(state[3] != 0);
  g->rejects_seen = ts->reject;
  g->regime_seen  = g->regime_rejects;
  PetscFunctionReturn(0);
}
