/* What a run will write, before it writes anything: its steps, and the size of its snapshots, index
 * and history. One plan for the data check (-check_input, src/app/datacheck.c) and for the run's
 * large-output warning (MMOutputPlanCheck, output_schedule.c), so the two cannot disagree. Each part
 * comes from the writer's own code where it can: the snapshot's fields from its table
 * (MMOutputSnapshotFields), their views measured by output_views.c's own code, the index's grids by
 * MMOutputIndexAddGrid, the history's columns from its header, and the steps that write a row or a
 * snapshot from the rules the run applies (MMOutputHistoryDue, MMOutputSnapshotDue). */
#include "io.h"
#include "outputimpl.h"
#include "mesh.h"

/* Above this many steps the schedule is walked over the first ones only and scaled (about a second
 * of walking; a run of 1e8 steps is far past the warning's 1e6 anyway) */
#define MM_PLAN_WALK_MAX 1e8

/* The steps the run will take from where it starts (t0, step0: a restart's checkpoint): to
 * -ts_max_time, the last one shortened onto it (matchstep) or taken whole (stepover), unless
 * -ts_max_steps ends the run first. A time within 1e-10 of the final time is the final time, as the
 * stepper has it (src/ts/newmark.c, FinalTimeTolerance). */
static PetscErrorCode PlanSteps(TS ts, MMOutputPlan *plan)
{
  PetscReal              t_end;
  PetscInt               max_steps, s0;
  TSExactFinalTimeOption eft;

  PetscFunctionBeginUser;
  PetscCall(TSGetTime(ts, &plan->t0));
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetTimeStep(ts, &plan->dt));
  PetscCall(TSGetMaxSteps(ts, &max_steps));
  PetscCall(TSGetStepNumber(ts, &s0));
  PetscCall(TSGetExactFinalTime(ts, &eft));
  plan->step0    = (PetscReal)s0;
  plan->steps    = PetscMax(0, PetscCeilReal((t_end - 1e-10 * t_end - plan->t0) / plan->dt));
  plan->by_steps = (PetscBool)(max_steps < PETSC_MAX_INT && (PetscReal)(max_steps - s0) < plan->steps);
  if (plan->by_steps) plan->steps = PetscMax(0, (PetscReal)(max_steps - s0));
  plan->t_last = plan->by_steps || eft == TS_EXACTFINALTIME_STEPOVER ? plan->t0 + plan->steps * plan->dt : t_end;
  PetscFunctionReturn(0);
}

/* The history rows and snapshots this run writes: step 0's (a restart has its checkpoint's already),
 * each step's that the run's rules make due (output_schedule.c), and the last step's if they miss it
 * (MMOutputClose). The steps' times are summed as the stepper sums them, the step that would pass
 * -ts_max_time shortened onto it under matchstep and a time within 1e-10 of it snapped to it
 * (src/ts/newmark.c, MatchFinalTime and TSStep_Newmark), so that -output_interval's snapshots fall on
 * the run's steps. dt is taken constant: steps a run rejects and retries are not foreseen. */
static PetscErrorCode PlanSchedule(const MMOutput *o, TS ts, MMOutputPlan *plan)
{
  const PetscReal        walk = PetscMin(plan->steps, MM_PLAN_WALK_MAX);
  PetscReal              t = plan->t0, t_end, tol, rows = 0, snaps = 0;
  PetscBool              row_due = PETSC_TRUE, snap_due = PETSC_TRUE;
  TSExactFinalTimeOption eft;

  PetscFunctionBeginUser;
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetExactFinalTime(ts, &eft));
  tol = 1e-10 * t_end;
  for (PetscInt s = 1; s <= (PetscInt)walk; ++s) {
    const PetscInt step = (PetscInt)plan->step0 + s;
    PetscReal      h    = plan->dt;
    if (eft == TS_EXACTFINALTIME_MATCHSTEP && t + h > t_end + tol) h = t_end - t;
    t += h;
    if (PetscAbsReal(t - t_end) <= tol) t = t_end;
    row_due  = MMOutputHistoryDue(o, step);
    snap_due = MMOutputSnapshotDue(o, step, t, h);
    rows += row_due;
    snaps += snap_due;
  }
  if (walk < plan->steps) { /* the rest at the walked steps' rate */
    rows *= plan->steps / walk;
    snaps *= plan->steps / walk;
  }
  plan->rows      = rows + (o->ckpt->restarted ? 0 : 1) + (plan->steps > 0 && !row_due ? 1 : 0);
  plan->snapshots = snaps + (o->ckpt->restarted ? 0 : 1) + (plan->steps > 0 && !snap_due ? 1 : 0);
  PetscFunctionReturn(0);
}

/* The bytes of one snapshot in solution.h5: its time, every field's values, and its views
 * (output_views.c). o is a stand-in whose DMs mark the vertex fields. */
static PetscErrorCode SnapshotBytes(MMOutput *o, PetscInt dim, PetscInt k0, PetscReal *bytes)
{
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];
  PetscReal       views;

  PetscFunctionBeginUser;
  MMOutputSnapshotFields(o, dim, f);
  *bytes = sizeof(PetscReal);
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) *bytes += (PetscReal)(f[i].dm ? o->nv : o->nc) * f[i].ncomp * sizeof(PetscScalar);
  PetscCall(MMOutputViewBytes(f, o->nv, o->nc, k0, &views));
  *bytes += views;
  PetscFunctionReturn(0);
}

/* The bytes of grid k of the index, as MMOutputIndexAddGrid writes it. */
static PetscErrorCode GridBytes(MMOutput *o, PetscInt dim, PetscInt k, PetscReal t, PetscReal *bytes)
{
  PetscFunctionBeginUser;
  o->index_len = 0;
  PetscCall(MMOutputIndexAddGrid(o, dim, k, t));
  *bytes = (PetscReal)o->index_len;
  PetscFunctionReturn(0);
}

/* The bytes of solution.xmf with the grids of snapshots k0 .. k0 + n - 1: its frame and each grid. A
 * grid's text differs from another's only by the digits of its number (its name and its views'
 * paths; every time has the same width in %.16e), so one grid per count of digits is measured. */
static PetscErrorCode IndexBytes(MMOutput *o, PetscInt dim, PetscReal k0, PetscReal n, PetscReal t, PetscReal *bytes)
{
  PetscFunctionBeginUser;
  *bytes = (PetscReal)MMOutputIndexFrameBytes();
  for (PetscReal lo = 0, hi = 10; lo < k0 + n; lo = hi, hi *= 10) {
    const PetscReal from = PetscMax(lo, k0), to = PetscMin(hi, k0 + n);
    PetscReal       grid = 0;
    if (from >= to) continue;
    PetscCall(GridBytes(o, dim, (PetscInt)from, t, &grid));
    *bytes += (to - from) * grid;
  }
  PetscCall(PetscFree(o->index));
  o->index_cap = 0;
  PetscFunctionReturn(0);
}

/* The bytes of history.csv: its header, and each row at most 24 characters a value with its comma
 * (%.16e, the widest format of a row), the probes' columns included (MMOutputCSVHeaderLine names
 * them once -probes is set up). */
static PetscErrorCode HistoryBytes(const MMOutput *o, MMOutputPlan *plan)
{
  MMLine   header;
  PetscInt ncol = 1;

  PetscFunctionBeginUser;
  PetscCall(MMOutputCSVHeaderLine(o, &header));
  for (size_t i = 0; i < header.n; ++i) ncol += header.s[i] == ',';
  plan->header_bytes = (PetscReal)header.n;
  plan->row_bytes    = 24.0 * ncol;
  plan->csv_bytes    = plan->header_bytes + plan->rows * plan->row_bytes;
  PetscFunctionReturn(0);
}

/* The output's DMs exist only once it is open: any DM marks a vertex field in the table, NULL a
 * cell field. Collective (the mesh's sizes). */
static PetscErrorCode StandIn(const MMOutput *o, MMOutput *stand_in)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(stand_in, sizeof(*stand_in)));
  stand_in->dm_out = stand_in->dm_scalar = stand_in->stress.dm = o->dm;
  PetscCall(MMMeshGetSizes(o->dm, &stand_in->nc, &stand_in->nv));
  PetscFunctionReturn(0);
}

/* The bytes of solution.h5's mesh (with what is written once) and of one snapshot from k0 on */
static PetscErrorCode WriteBytes(MMOutput *stand_in, PetscInt dim, PetscInt k0, PetscReal *mesh, PetscReal *snapshot)
{
  PetscFunctionBeginUser;
  PetscCall(SnapshotBytes(stand_in, dim, k0, snapshot));
  /* once: the coordinates, the cells, each vertex's obstacle and serial number (MMOutputWriteMesh,
   * MMOutputWriteStaticFields) */
  *mesh = (PetscReal)stand_in->nv * dim * sizeof(PetscReal) + (PetscReal)stand_in->nc * (dim + 1) * sizeof(PetscInt) + 2.0 * stand_in->nv * sizeof(PetscScalar);
  /* and HDF5's own: object headers, chunk indices, groups. Measured 54 to 55 kB over the data for
   * the 15 datasets (the fields, time, the mesh's two, the two written once) of 2D and 3D files of 1
   * to 31 snapshots: 3.6 kB a dataset */
  *mesh += (MM_SNAPSHOT_FIELDS + 5) * 3.6e3;
  PetscFunctionReturn(0);
}

/* The bytes the writes of solution.h5 take, for the check of the free space before each
 * (MMOutputCheckSpace): its creation with the mesh, and each snapshot. Collective. */
PetscErrorCode MMOutputPlanWrites(MMOutput *o)
{
  MMOutput stand_in;

  PetscFunctionBeginUser;
  PetscCall(StandIn(o, &stand_in));
  PetscCall(WriteBytes(&stand_in, o->dim, MMCheckpointSnapshotCount(o->ckpt), &o->mesh_bytes, &o->snapshot_bytes));
  PetscFunctionReturn(0);
}

/*@
  MMOutputPlanMake - Plans the output of the run about to start: steps, snapshots, history rows and
  their sizes

  Collective

  Input Parameters:
+ o  - the output object, set up
- ts - the time stepper, at the run's first step

  Output Parameter:
. plan - the plan

  Level: intermediate

.seealso: `MMOutputSetUpProbes()`, `MMCheckpointSnapshotCount()`
@*/
PetscErrorCode MMOutputPlanMake(const MMOutput *o, TS ts, MMOutputPlan *plan)
{
  const PetscInt dim = o->dim;
  const PetscInt k0  = MMCheckpointSnapshotCount(o->ckpt); /* this run's first snapshot's number */
  MMOutput       stand_in;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(plan, sizeof(*plan)));
  PetscCall(PlanSteps(ts, plan));
  PetscCall(PlanSchedule(o, ts, plan));
  PetscCall(StandIn(o, &stand_in));
  PetscCall(WriteBytes(&stand_in, dim, k0, &plan->mesh_bytes, &plan->snapshot_bytes));
  plan->h5_bytes = plan->mesh_bytes + plan->snapshots * plan->snapshot_bytes;
  PetscCall(IndexBytes(&stand_in, dim, (PetscReal)k0, plan->snapshots, plan->t0, &plan->xmf_bytes));
  PetscCall(HistoryBytes(o, plan));
  PetscFunctionReturn(0);
}
