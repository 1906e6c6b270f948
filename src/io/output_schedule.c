/* When the output is written (README "Output"): a history row every -history_every steps and at the
 * last step, the fields every -output_every steps or, with -output_interval T, at t = k T; and the
 * warning, at the start of the time loop, of a run whose planned output is very large. */
#include "io.h"
#include "outputimpl.h"

#define MM_PLAN_BYTES 1e9 /* 1 GB of history or of snapshots */
#define MM_PLAN_STEPS 1e6

/* Whether step has a history row (the last step gets one from MMOutputClose). The rule depends on the step
 * alone, so that a restarted run keeps the cadence of the run it continues. */
PetscBool MMOutputHistoryDue(const MMOutput *o, PetscInt step)
{
  return (PetscBool)(step % o->history_every == 0);
}

/* Whether the step from t - dt to t reached the next multiple of -output_interval T (or, without
 * one, step is a multiple of -output_every). The time is a sum of steps, so t_n = n dt only to
 * round-off: a multiple k T within 1e-9 dt of t counts as reached, so that T = 5 dt writes at
 * every 5th step, not at the 6th when n dt rounds below k T. Stateless, hence the same across a
 * restart. */
PetscBool MMOutputSnapshotDue(const MMOutput *o, PetscInt step, PetscReal t, PetscReal dt)
{
  if (o->interval > 0) {
    const PetscReal T = o->interval, eps = 1e-9 * dt;
    return (PetscBool)(PetscFloorReal((t + eps) / T) > PetscFloorReal((t - dt + eps) / T));
  }
  return (PetscBool)(o->every > 0 && step % o->every == 0);
}

/* One "mmcontact warning:" line, at the first step, when the run plans more than 1e6 steps, or more
 * than 1 GB of history or of snapshots: the figures, and the options that set them. The figures
 * are the data check's (MMOutputPlanMake, README "Output"). */
PetscErrorCode MMOutputPlanCheck(const MMOutput *o, TS ts)
{
  MMOutputPlan plan;
  PetscReal    snap_bytes;

  PetscFunctionBeginUser;
  PetscCall(MMOutputPlanMake(o, ts, &plan));
  snap_bytes = plan.snapshots * plan.snapshot_bytes;
  if (plan.steps <= MM_PLAN_STEPS && plan.csv_bytes <= MM_PLAN_BYTES && snap_bytes <= MM_PLAN_BYTES) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mmcontact warning: this run plans %.4g steps, %.3g GB of history.csv (%.4g rows) and %.3g GB of snapshots in solution.h5 (%.4g); above 1e6 steps or 1 GB, check -ts_dt and -ts_max_time, and thin the output with -history_every, -output_every or -output_interval\n", (double)plan.steps, (double)(plan.csv_bytes / 1e9), (double)plan.rows, (double)(snap_bytes / 1e9), (double)plan.snapshots));
  PetscFunctionReturn(0);
}
