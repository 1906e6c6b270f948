/* When the output is written (README "Output"): a history row every -history_every steps and at the
 * last step, the fields every -output_every steps or, with -output_interval T, at t = k T; and the
 * warning, at the start of the time loop, of a run whose planned output is very large. */
#include "outputimpl.h"

#define MM_PLAN_BYTES 1e9 /* 1 GB of history or of snapshots */
#define MM_PLAN_STEPS 1e6

/* Whether step has a history row (the last step gets one from MMOutputClose). The rule depends on the step
 * alone, so that a restarted run keeps the cadence of the run it continues. */
PetscBool MMOutputHistoryDue(const MMOptions *opt, PetscInt step)
{
  return (PetscBool)(step % opt->history_every == 0);
}

/* Whether the step from t - dt to t reached the next multiple of -output_interval T (or, without
 * one, step is a multiple of -output_every). The time is a sum of steps, so t_n = n dt only to
 * round-off: a multiple k T within 1e-9 dt of t counts as reached, so that T = 5 dt writes at
 * every 5th step, not at the 6th when n dt rounds below k T. Stateless, hence the same across a
 * restart. */
PetscBool MMOutputSnapshotDue(const MMOptions *opt, PetscInt step, PetscReal t, PetscReal dt)
{
  if (opt->output_interval > 0) {
    const PetscReal T = opt->output_interval, eps = 1e-9 * dt;
    return (PetscBool)(PetscFloorReal((t + eps) / T) > PetscFloorReal((t - dt + eps) / T));
  }
  return (PetscBool)(opt->output_every > 0 && step % opt->output_every == 0);
}

/* The bytes of one snapshot: every field's values (doubles) and its view's header (about 1 kB). */
static PetscErrorCode SnapshotBytes(MMOutput *o, PetscInt dim, PetscReal *bytes)
{
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];

  PetscFunctionBeginUser;
  MMOutputSnapshotFields(o, dim, f);
  *bytes = 8;
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) {
    PetscInt N;
    PetscCall(VecGetSize(f[i].vec, &N));
    *bytes += 8.0 * N + 1024;
  }
  PetscFunctionReturn(0);
}

/* One "mmcontact warning:" line, at the first step, when the run plans more than 1e6 steps, or more
 * than 1 GB of history or of snapshots: the figures, and the options that set them. A row of the
 * history is about 24 bytes per column (a value is printed with 17 digits). */
PetscErrorCode MMOutputPlanCheck(MMCtx *ctx, TS ts, const MMLine *header)
{
  const MMOptions *opt = &ctx->opt;
  PetscReal        t, t_end, dt, steps, rows, snaps, hist_bytes, snap_bytes;
  PetscInt         step, max_steps, columns = 1;

  PetscFunctionBeginUser;
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(TSGetMaxSteps(ts, &max_steps));
  steps = PetscCeilReal(PetscMax(t_end - t, 0) / dt - 1e-9);
  if (max_steps < PETSC_MAX_INT) steps = PetscMin(steps, (PetscReal)PetscMax(max_steps - step, 0));
  for (size_t i = 0; i < header->n; ++i) columns += header->s[i] == ',';
  rows       = steps / opt->history_every + 1;
  hist_bytes = rows * 24.0 * columns;
  if (opt->output_interval > 0) snaps = PetscMin(PetscFloorReal(steps * dt / opt->output_interval), steps) + 1;
  else snaps = opt->output_every > 0 ? PetscFloorReal(steps / opt->output_every) + 1 : 1;
  PetscCall(SnapshotBytes(&ctx->out, ctx->op.dim, &snap_bytes));
  snap_bytes *= snaps;
  if (steps <= MM_PLAN_STEPS && hist_bytes <= MM_PLAN_BYTES && snap_bytes <= MM_PLAN_BYTES) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mmcontact warning: this run plans %.4g steps, %.3g GB of history.csv (%.4g rows) and %.3g GB of snapshots in solution.h5 (%.4g); above 1e6 steps or 1 GB, check -ts_dt and -ts_max_time, and thin the output with -history_every, -output_every or -output_interval\n", (double)steps, (double)(hist_bytes / 1e9), (double)rows, (double)(snap_bytes / 1e9), (double)snaps));
  PetscFunctionReturn(0);
}
