/* Checkpoints: the complete state of a run in one HDF5 file, OUTPUT_DIR/checkpoint.h5
 * (docs/method.md section 9). Every field is keyed by the serial mesh's vertex numbers, so the file
 * does not depend on the number of ranks that wrote it. */
#include <errno.h>
#include <string.h>
#include <petscviewerhdf5.h>
#include "checkpoint.h"

#define MM_CKPT_FILE "checkpoint.h5"
#define MM_CKPT_TMP  ".tmp" /* written whole, then renamed over the last good one */
#define MM_CKPT_NODE 9      /* per vertex: contact, s, slipping, was_active, slip_dir[2], rho[3] */

/* The scalars of a run, in the "run" vector of the file, in this order. */
typedef enum {
  MM_RUN_VERSION,
  MM_RUN_DIM,
  MM_RUN_VERTICES,
  MM_RUN_CELLS,
  MM_RUN_CONTACT_NODES,
  MM_RUN_COORDINATES, /* a checksum of the vertex coordinates */
  MM_RUN_MU,
  MM_RUN_RANKS,
  MM_RUN_TIME,
  MM_RUN_DT_NEXT,
  MM_RUN_DT_LAST,
  MM_RUN_STEP,
  MM_RUN_WORK_EXT,
  MM_RUN_WORK_CONTACT,
  MM_RUN_WORK_FRICTION,
  MM_RUN_WORK_OBSTACLE,
  MM_RUN_MAX_BALANCE,
  MM_RUN_MAX_PENETRATION,
  MM_RUN_ENERGY_SCALE,
  MM_RUN_RESOLVES,
  MM_RUN_SNAPSHOTS,
  MM_RUN_NUM
} MMRunEntry;

/* The free dofs of an owned vertex: global offset, and which of its dim components are free. */
static PetscErrorCode OwnedVertexDofs(MMCtx *ctx, PetscInt v, PetscInt *goff, PetscBool freedof[])
{
  PetscSection    gs, ls;
  PetscInt        cdof;
  const PetscInt *cind;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(ctx->op.dm, &gs));
  PetscCall(DMGetLocalSection(ctx->op.dm, &ls));
  PetscCall(PetscSectionGetOffset(gs, v, goff));
  PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
  PetscCall(PetscSectionGetConstraintIndices(ls, v, &cind));
  for (PetscInt d = 0; d < ctx->op.dim; ++d) freedof[d] = PETSC_TRUE;
  for (PetscInt c = 0; c < cdof; ++c) freedof[cind[c]] = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* w (the free dofs, in each node's frame) into packed, dim entries per serial-mesh vertex. The
 * frames are functions of the reference geometry, so frame components are the same on any
 * partition, and no rotation rounds them. */
static PetscErrorCode PackDofs(MMCtx *ctx, Vec w, Vec packed)
{
  const PetscInt     dim = ctx->op.dim;
  const PetscScalar *wa;
  PetscInt           vStart, vEnd, rstart;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(ctx->op.dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(VecGetArrayRead(w, &wa));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt  goff, j = 0;
    PetscBool freedof[MM_MAX_DIM];
    PetscCall(OwnedVertexDofs(ctx, v, &goff, freedof));
    if (goff < 0) continue;
    for (PetscInt d = 0; d < dim; ++d)
      if (freedof[d]) PetscCall(VecSetValue(packed, ctx->ckpt.vertex_orig[v - vStart] * dim + d, wa[goff - rstart + j++], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(VecAssemblyBegin(packed));
  PetscCall(VecAssemblyEnd(packed));
  PetscFunctionReturn(0);
}

/* The per-node contact state: the friction thresholds, the 3D stick/slip states and slip
 * directions, the last active set and the condensed reactions, which warm-start the next step. */
static PetscErrorCode PackContact(MMCtx *ctx, Vec packed)
{
  MMContact         *ct = &ctx->contact;
  const PetscScalar *sa = NULL, *ra = NULL;
  PetscInt           vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(ctx->op.dm, 0, &vStart, &vEnd));
  if (ct->enabled) {
    if (ctx->friction.s) PetscCall(VecGetArrayRead(ctx->friction.s, &sa));
    if (ct->rho) PetscCall(VecGetArrayRead(ct->rho, &ra));
    for (PetscInt k = 0; k < ct->n_local; ++k) {
      PetscScalar    rec[MM_CKPT_NODE] = {0};
      const PetscInt base = MM_CKPT_NODE * ctx->ckpt.vertex_orig[ct->vertex[k] - vStart];
      rec[0] = 1;
      rec[1] = sa ? sa[k] : 0;
      rec[2] = ct->slipping ? (PetscScalar)ct->slipping[k] : 0;
      rec[3] = (PetscScalar)ct->was_active[k];
      if (ct->slip_dir) {
        rec[4] = ct->slip_dir[2 * k];
        rec[5] = ct->slip_dir[2 * k + 1];
      }
      for (PetscInt c = 0; ra && c < ct->ncomp; ++c) rec[6 + c] = ra[k * ct->ncomp + c];
      for (PetscInt c = 0; c < MM_CKPT_NODE; ++c) PetscCall(VecSetValue(packed, base + c, rec[c], INSERT_VALUES));
    }
    if (ra) PetscCall(VecRestoreArrayRead(ct->rho, &ra));
    if (sa) PetscCall(VecRestoreArrayRead(ctx->friction.s, &sa));
  }
  PetscCall(VecAssemblyBegin(packed));
  PetscCall(VecAssemblyEnd(packed));
  PetscFunctionReturn(0);
}

/* A checksum of the geometry that does not depend on the partition (up to rounding). */
static PetscErrorCode CoordinateChecksum(MMCtx *ctx, PetscReal *sum)
{
  PetscSection       gs, cs;
  Vec                X;
  const PetscScalar *x;
  PetscInt           vStart, vEnd;

  PetscFunctionBeginUser;
  *sum = 0;
  PetscCall(DMGetGlobalSection(ctx->op.dm, &gs));
  PetscCall(DMGetCoordinateSection(ctx->op.dm, &cs));
  PetscCall(DMGetCoordinatesLocal(ctx->op.dm, &X));
  PetscCall(DMPlexGetDepthStratum(ctx->op.dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, xoff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    for (PetscInt d = 0; d < ctx->op.dim; ++d) *sum += (d + 1) * PetscRealPart(x[xoff + d]) * (1 + ctx->ckpt.vertex_orig[v - vStart] % 97);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ctx->op.dm)));
  PetscFunctionReturn(0);
}

static PetscErrorCode RunRecord(MMCtx *ctx, TS ts, PetscReal run[])
{
  const MMHistory *h = &ctx->hist;
  PetscMPIInt      size;
  PetscInt         cStart, cEnd, ncells;
  PetscReal        dt;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ctx->op.dm), &size));
  PetscCall(DMPlexGetHeightStratum(ctx->op.dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart; /* no overlap: every cell is on one rank */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ctx->op.dm)));
  PetscCall(TSGetTimeStep(ts, &dt));
  run[MM_RUN_VERSION]         = 1;
  run[MM_RUN_DIM]             = ctx->op.dim;
  run[MM_RUN_VERTICES]        = ctx->ckpt.nv_global;
  run[MM_RUN_CELLS]           = ncells;
  run[MM_RUN_CONTACT_NODES]   = ctx->contact.enabled ? ctx->contact.n_global : 0;
  PetscCall(CoordinateChecksum(ctx, &run[MM_RUN_COORDINATES]));
  run[MM_RUN_MU]              = ctx->opt.mu;
  run[MM_RUN_RANKS]           = size;
  run[MM_RUN_TIME]            = h->time;
  run[MM_RUN_DT_NEXT]         = dt;
  run[MM_RUN_DT_LAST]         = ctx->state.dt;
  run[MM_RUN_STEP]            = h->step;
  run[MM_RUN_WORK_EXT]        = h->work_ext;
  run[MM_RUN_WORK_CONTACT]    = h->work_contact;
  run[MM_RUN_WORK_FRICTION]   = h->work_friction;
  run[MM_RUN_WORK_OBSTACLE]   = h->work_obstacle;
  run[MM_RUN_MAX_BALANCE]     = h->max_balance;
  run[MM_RUN_MAX_PENETRATION] = h->max_penetration_run;
  run[MM_RUN_ENERGY_SCALE]    = h->energy_scale;
  run[MM_RUN_RESOLVES]        = h->resolves;
  run[MM_RUN_SNAPSHOTS]       = ctx->out.n_written;
  PetscFunctionReturn(0);
}

/* A vector held on rank 0, for the run's scalars and the snapshot times. */
static PetscErrorCode RootVector(MPI_Comm comm, const char name[], PetscInt n, const PetscReal vals[], Vec *v)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : n, n, v));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  if (!rank) {
    PetscScalar *a;
    PetscCall(VecGetArray(*v, &a));
    for (PetscInt i = 0; i < n; ++i) a[i] = vals[i];
    PetscCall(VecRestoreArray(*v, &a));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ViewPacked(MMCtx *ctx, PetscViewer viewer, const char name[], PetscInt bs, Vec src, PetscBool contact)
{
  Vec packed;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)ctx->op.dm), PETSC_DECIDE, bs * ctx->ckpt.nv_global, &packed));
  PetscCall(PetscObjectSetName((PetscObject)packed, name));
  PetscCall(VecZeroEntries(packed));
  if (contact) PetscCall(PackContact(ctx, packed));
  else PetscCall(PackDofs(ctx, src, packed));
  PetscCall(VecView(packed, viewer));
  PetscCall(VecDestroy(&packed));
  PetscFunctionReturn(0);
}

/* The vertices of the whole mesh, counted once. */
static PetscErrorCode CountVertices(MMCtx *ctx)
{
  PetscInt vStart, vEnd, n = 0;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(ctx->op.dm, 0, &vStart, &vEnd));
  for (PetscInt v = vStart; v < vEnd; ++v) n = PetscMax(n, ctx->ckpt.vertex_orig[v - vStart] + 1);
  PetscCall(MPIU_Allreduce(&n, &ctx->ckpt.nv_global, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)ctx->op.dm)));
  PetscFunctionReturn(0);
}

/* The state after the current step, to OUTPUT_DIR/checkpoint.h5: written whole to a temporary file
 * and renamed over the last one, so that a crash while writing leaves the last good checkpoint. */
PetscErrorCode MMCheckpointWrite(MMCtx *ctx, TS ts)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)ctx->op.dm);
  MMState    *s    = &ctx->state;
  PetscViewer viewer;
  PetscReal   run[MM_RUN_NUM];
  char        name[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  Vec         rv, tv;
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.checkpoint, 0, 0, 0, 0));
  if (!ctx->ckpt.nv_global) PetscCall(CountVertices(ctx));
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/%s", ctx->opt.output_dir, MM_CKPT_FILE));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", name, MM_CKPT_TMP));
  PetscCall(RunRecord(ctx, ts, run));
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &viewer));
  PetscCall(RootVector(comm, "run", MM_RUN_NUM, run, &rv));
  PetscCall(VecView(rv, viewer));
  PetscCall(VecDestroy(&rv));
  PetscCall(RootVector(comm, "snapshot_times", PetscMax(ctx->out.n_written, 1), ctx->out.n_written ? ctx->out.times : run, &tv));
  PetscCall(VecView(tv, viewer));
  PetscCall(VecDestroy(&tv));
  PetscCall(ViewPacked(ctx, viewer, "u", ctx->op.dim, s->u, PETSC_FALSE));
  PetscCall(ViewPacked(ctx, viewer, "v", ctx->op.dim, s->v, PETSC_FALSE));
  PetscCall(ViewPacked(ctx, viewer, "a", ctx->op.dim, s->a, PETSC_FALSE));
  PetscCall(ViewPacked(ctx, viewer, "react", ctx->op.dim, s->react, PETSC_FALSE));
  PetscCall(ViewPacked(ctx, viewer, "contact", MM_CKPT_NODE, NULL, PETSC_TRUE));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && rename(tmp, name)) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "Could not rename %s to %s: %s. The previous checkpoint, if any, is intact", tmp, name, strerror(err));
  ctx->ckpt.written++;
  ctx->ckpt.last_step = ctx->hist.step;
  PetscCall(PetscLogEventEnd(ctx->log.checkpoint, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* TS monitor: a checkpoint every -checkpoint_every steps (the final one is written by main). */
PetscErrorCode MMCheckpointMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ptr)
{
  MMCtx         *ctx   = (MMCtx *)ptr;
  const PetscInt every = ctx->opt.checkpoint_every;

  PetscFunctionBeginUser;
  if (every > 0 && step > 0 && step % every == 0) PetscCall(MMCheckpointWrite(ctx, ts));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCheckpointDestroy(MMCheckpoint *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c->vertex_orig));
  PetscFunctionReturn(0);
}
