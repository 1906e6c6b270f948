/* What a run will write, before it writes anything: the size of its snapshots and history, for the
 * data check (-check_input, src/app/datacheck.c). The snapshot's fields come from the writer's own
 * table (MMOutputSnapshotFields), so the estimate follows the output when a field is added. */
#include "output.h"
#include "outputimpl.h"
#include "mesh.h"

/* The snapshots a run of `steps` steps from step0 writes: step 0's (a restart has its checkpoint's
 * already), every -output_every-th step, and the last if the cadence misses it (MMOutputMonitor,
 * MMOutputClose). */
static PetscReal SnapshotCount(PetscInt every, PetscReal step0, PetscReal steps, PetscBool restarted)
{
  const PetscReal last = step0 + steps;
  PetscReal       n    = restarted ? 0 : 1;

  if (every > 0) n += PetscFloorReal(last / every) - PetscFloorReal(step0 / every);
  if (steps > 0 && (every == 0 || PetscFmodReal(last, (PetscReal)every) != 0)) n += 1;
  return n;
}

PetscErrorCode MMOutputPlanSize(MMCtx *ctx, PetscReal step0, PetscReal steps, MMOutputPlan *plan)
{
  const PetscInt  dim = ctx->op.dim;
  MMOutput        stand_in;
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];
  MMLine          header;
  PetscInt        nc, nv, ncol = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(plan, sizeof(*plan)));
  PetscCall(MMMeshGetSizes(ctx->op.dm, &nc, &nv));
  /* the output's DMs exist only once it is open: any DM marks a vertex field in the table, NULL a
   * cell field */
  PetscCall(PetscMemzero(&stand_in, sizeof(stand_in)));
  stand_in.dm_out = stand_in.dm_scalar = stand_in.dm_stress = ctx->op.dm;
  MMOutputSnapshotFields(&stand_in, dim, f);
  plan->snapshot_bytes = sizeof(PetscReal); /* its time */
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) plan->snapshot_bytes += (PetscReal)(f[i].dm ? nv : nc) * f[i].ncomp * sizeof(PetscScalar);
  /* once: the coordinates, the cells, each vertex's obstacle and serial number (MMOutputWriteMesh,
   * MMOutputWriteStaticFields) */
  plan->mesh_bytes = (PetscReal)nv * dim * sizeof(PetscReal) + (PetscReal)nc * (dim + 1) * sizeof(PetscInt) + 2.0 * nv * sizeof(PetscScalar);
  /* and HDF5's own: object headers, chunk indices, groups. Measured 54 to 55 kB over the data for
   * the 15 datasets (the fields, time, the mesh's two, the two written once) of 2D and 3D files of 1
   * to 31 snapshots: 3.6 kB a dataset */
  plan->mesh_bytes += (MM_SNAPSHOT_FIELDS + 5) * 3.6e3;
  plan->snapshots  = SnapshotCount(ctx->opt.output_every, step0, steps, ctx->ckpt.restarted);
  /* the XDMF index: a grid per snapshot, as the writer words it (MMOutputIndexAddGrid) */
  {
    PetscReal t0 = 0;
    stand_in.nv    = nv;
    stand_in.nc    = nc;
    stand_in.times = &t0;
    PetscCall(MMOutputIndexAddGrid(&stand_in, dim, 0));
    plan->index_grid_bytes = (PetscReal)stand_in.index_len;
    PetscCall(PetscFree(stand_in.index));
  }
  /* a row per step, and step 0's; each value at most 24 characters with its comma (%.16e) */
  PetscCall(MMOutputCSVHeaderLine(ctx, &header));
  for (size_t i = 0; i < header.n; ++i) ncol += header.s[i] == ',';
  plan->rows         = steps + (ctx->ckpt.restarted ? 0 : 1);
  plan->row_bytes    = 24.0 * ncol;
  plan->header_bytes = (PetscReal)header.n;
  PetscFunctionReturn(0);
}
