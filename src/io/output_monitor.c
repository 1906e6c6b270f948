/* The output's glue to the rest of the run: the TS monitor and the end of the run gather each
 * snapshot's fields from the components that compute them (the stepper's u and v, fem's Cartesian
 * frame and stress, the loads' Dirichlet data, contact's boundary fields), then hand them to the
 * writer (output.c), which takes the output alone. The data path goes down once and comes back. */
#include "io.h"
#include "outputimpl.h"
#include "contact.h"
#include "fem.h"

/* The Cartesian displacement and velocity on every node, Dirichlet data included (the snapshot's, and
 * the row's for its probes), from the free dofs of the stepper's u and v; the velocity's data are
 * the moving boundaries' own. */
static PetscErrorCode WholeState(MMOutput *o)
{
  DM  dm   = o->dm;
  Vec w[2] = {o->state->u, o->state->v}, whole[2] = {o->disp_cart, o->vel_cart};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 2; ++i) {
    Vec g, l;
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(DMGetLocalVector(dm, &l));
    PetscCall(MMFEToCartesian(o->op, w[i], g));
    PetscCall(VecZeroEntries(l));
    PetscCall(DMGlobalToLocal(dm, g, INSERT_VALUES, l));
    /* the displacement's Dirichlet data; zero velocity there but the moving boundaries' (below) */
    if (i == 0) PetscCall(MMLoadsInsertBoundaryValues(o->loads, l, o->hist->time));
    PetscCall(MMInsertMapLocalToGlobal(o->dm_out, &o->to_out, l, whole[i]));
    PetscCall(DMRestoreLocalVector(dm, &l));
    PetscCall(DMRestoreGlobalVector(dm, &g));
  }
  PetscCall(MMLoadsInsertDirichletVelocity(o->loads, o->vel_cart));
  PetscFunctionReturn(0);
}

/* The history row and (snapshot) the fields of the current state: the stepper's state, fem's frames
 * and stress, contact's boundary fields. */
static PetscErrorCode Write(MMOutput *o, PetscBool row, PetscBool snapshot)
{
  PetscFunctionBeginUser;
  if (snapshot) PetscCall(PetscLogStagePush(MMIOEvents.output));
  if (snapshot || (row && o->probes.n)) PetscCall(WholeState(o));
  if (row) PetscCall(MMOutputWriteRow(o));
  if (!snapshot) PetscFunctionReturn(0);
  PetscCall(MMContactBoundaryFields(o->contact, o->state->u, o->state->v, o->state->react, o->dm_out, o->pressure, o->gap, o->traction_t, o->slip));
  PetscCall(MMStressCompute(&o->stress, o->op, o->material, o->dm_out, o->disp_cart, PETSC_TRUE));
  PetscCall(MMOutputWriteSnapshot(o, o->hist->time));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

/*@
  MMOutputSetUpProbes - Finds the nodes of the -probes groups and their lumped masses

  Collective

  Input Parameter:
. o - the output object, set up

  Note:
  The -probes groups, with their nodes' lumped masses from fem: also for the data check, whose plan
  counts their history columns and which refuses a group the mesh lacks as a run does.

  Level: developer

.seealso: `MMOutputOpen()`, `MMOutputPlanMake()`
@*/
PetscErrorCode MMOutputSetUpProbes(MMOutput *o)
{
  Vec mloc;

  PetscFunctionBeginUser;
  if (!o->probe_list[0]) PetscFunctionReturn(0);
  PetscCall(DMGetLocalVector(o->dm_scalar, &mloc));
  PetscCall(MMFEVertexMasses(o->op, o->material, mloc));
  PetscCall(MMProbesSetUp(o, mloc));
  PetscCall(DMRestoreLocalVector(o->dm_scalar, &mloc));
  PetscFunctionReturn(0);
}

/*@
  MMOutputOpen - Opens the output once all input is valid: the probes, the files, the fields fixed
  at set-up, and on -restart the earlier snapshots

  Collective

  Input Parameter:
. o - the output object, set up

  Note:
  Called last in set-up, once all input is valid: the probes (a group the mesh lacks is refused
  before any file is touched), the files, the fields fixed at set-up, and on -restart the earlier
  snapshots.

  Level: intermediate

.seealso: `MMOutputSetUp()`, `MMOutputSetUpProbes()`, `MMOutputClose()`, `MMOutputLock()`
@*/
PetscErrorCode MMOutputOpen(MMOutput *o)
{
  PetscFunctionBeginUser;
  PetscCall(MMOutputSetUpProbes(o));
  if (o->ckpt->restarted) PetscCall(PetscLogEventBegin(MMIOEvents.restart_output, 0, 0, 0, 0));
  PetscCall(MMOutputOpenFiles(o));
  PetscCall(MMStressCreate(o->op, &o->stress));
  PetscCall(MMContactObstacleField(o->contact, o->obstacle));
  if (o->ckpt->restarted) {
    PetscCall(MMOutputRestartFields(o));
    PetscCall(PetscLogEventEnd(MMIOEvents.restart_output, 0, 0, 0, 0));
  }
  PetscFunctionReturn(0);
}

/*@
  MMOutputMonitor - TS monitor that writes a history row and the fields at the cadence the options
  set

  Collective

  Input Parameters:
+ ts   - the time stepper
. step - the step just taken
. time - its time
. u    - the solution vector (unused: the state is the stepper's)
- ctx  - the output object (MMOutput *)

  Note:
  TS monitor: a history row every -history_every steps, the fields every -output_every steps or
  -output_interval (output_schedule.c).

  Level: intermediate

.seealso: `MMOutputWriteFinal()`, `TSMonitorSet()`, `MMCheckpointMonitor()`
@*/
PetscErrorCode MMOutputMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ptr)
{
  MMOutput *o = (MMOutput *)ptr;

  PetscFunctionBeginUser;
  if (!o->planned) {
    PetscCall(MMOutputPlanCheck(o, ts));
    o->planned = PETSC_TRUE;
  }
  /* -restart: the row and snapshot of the checkpoint's step are on disk already */
  if (o->ckpt->restarted && step == o->ckpt->restart_step) PetscFunctionReturn(0);
  PetscCall(Write(o, MMOutputHistoryDue(o, step), (PetscBool)(step == 0 || MMOutputSnapshotDue(o, step, time, o->hist->dt))));
  PetscFunctionReturn(0);
}

/*@
  MMOutputWriteFinal - Writes the last step's history row and snapshot if the cadence missed them

  Collective

  Input Parameter:
. o - the output object

  Note:
  The last step's row and snapshot, if the cadence missed them (a restart that made no step has them
  on disk).

  Level: intermediate

.seealso: `MMOutputMonitor()`, `MMOutputClose()`
@*/
PetscErrorCode MMOutputWriteFinal(MMOutput *o)
{
  const MMHistory *h = o->hist;

  PetscFunctionBeginUser;
  PetscCall(Write(o, (PetscBool)(!MMOutputHistoryDue(o, h->step) && !(o->ckpt->restarted && h->step == o->ckpt->restart_step)), (PetscBool)(o->n_written && o->times[o->n_written - 1] != h->time)));
  PetscFunctionReturn(0);
}
