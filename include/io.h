/* io: the run's output (history.csv, solution.h5 and its XDMF index), checkpoints and restart, and the
 * progress lines (src/io/). Their structs are in iotypes.h, part of the run's context. */
#pragma once
#include "mmcontact.h"

/* iopackage.c: io's log stage and events, registered once */
PETSC_EXTERN PetscErrorCode MMIOInitializePackage(void);

/* output.c: the files of a run, from set-up to close */
PETSC_EXTERN PetscErrorCode MMOutputSetFromOptions(MPI_Comm comm, MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputSetUp(MMOutput *o, const MMOptions *opt, const MMOperators *op, const MMMaterial *material, const MMHistory *hist, const MMState *state, const MMContact *contact, MMLoads *loads, MMCheckpoint *ckpt);
/* output_monitor.c: the glue that gathers each snapshot's fields from the components below */
PETSC_EXTERN PetscErrorCode MMOutputOpen(MMCtx *ctx);
PETSC_EXTERN PetscErrorCode MMOutputSetUpProbes(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
PETSC_EXTERN PetscErrorCode MMOutputWriteFinal(MMCtx *ctx);
PETSC_EXTERN PetscErrorCode MMOutputClose(MMOutput *o, const MMCheckpoint *c, PetscInt step);
PETSC_EXTERN PetscErrorCode MMOutputView(const MMOutput *o, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMOutputDestroy(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputCheckHDF5Path(MPI_Comm comm, const char option[], const char path[], const char longest[]);
PETSC_EXTERN PetscErrorCode MMOutputSyncIndex(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputCopySnapshots(MMOutput *o);
/* output_lock.c: one run per output directory */
PETSC_EXTERN PetscErrorCode MMOutputLock(const char dir[]);
PETSC_EXTERN PetscErrorCode MMOutputUnlock(void);
PETSC_EXTERN PetscErrorCode MMProbesDestroy(MMProbes *probes);
/* What a run will write (src/io/output_plan.c, for -check_input and the large-output warning): its
 * steps from step0 at t0, each dt, to t_last (by_steps: -ts_max_steps ends it before -ts_max_time);
 * its snapshots, the bytes of each (with its views) and of the mesh, and solution.h5's and
 * solution.xmf's bytes; its history rows, the most bytes a row takes, the header's, and at most
 * history.csv's bytes. */
typedef struct {
  PetscReal step0, steps, t0, dt, t_last;
  PetscBool by_steps;
  PetscReal snapshots, snapshot_bytes, mesh_bytes, h5_bytes, xmf_bytes;
  PetscReal rows, row_bytes, header_bytes, csv_bytes;
} MMOutputPlan;
PETSC_EXTERN PetscErrorCode MMOutputPlanMake(const MMOutput *o, TS ts, MMOutputPlan *plan);

/* checkpoint.c: checkpoints and -restart (docs/method.md section 9) */
PETSC_EXTERN PetscErrorCode MMCheckpointSetFromOptions(MPI_Comm comm, MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointSetUp(MMCheckpoint *c, const MMOptions *opt, const MMOperators *op, const MMMaterial *material, MMHistory *hist, MMState *state, MMDamping *damping, MMContact *contact, MMFriction friction, MMOutput *out);
PETSC_EXTERN PetscErrorCode MMCheckpointWrite(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
PETSC_EXTERN PetscErrorCode MMCheckpointDestroy(MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointLoad(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointGetRestart(const MMCheckpoint *c, PetscBool *restarted, PetscInt *step, PetscReal *time);
PETSC_EXTERN PetscErrorCode MMCheckpointWriteFinal(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointView(const MMCheckpoint *c, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMCheckpointRestoreHistory(MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointSnapshots(MMCheckpoint *c, PetscInt *n, PetscReal **times);
PETSC_EXTERN PetscInt       MMCheckpointSnapshotCount(const MMCheckpoint *c);

/* progress.c: the start-up report and the progress lines */
PETSC_EXTERN PetscErrorCode MMProgressSetFromOptions(MPI_Comm comm, MMProgress *p);
PETSC_EXTERN PetscErrorCode MMProgressSetUp(MMProgress *p, const MMOptions *opt, const MMOperators *op, const MMMaterial *material, const MMHistory *hist, const MMState *state, const MMContact *contact, const MMDamping *damping);
PETSC_EXTERN PetscErrorCode MMProgressHeader(MMProgress *p, TS ts, KSP krylov, KSP pc_ksp);
PETSC_EXTERN PetscErrorCode MMProgressMassLine(const MMProgress *p);
PETSC_EXTERN PetscErrorCode MMProgressMonitorSet(MMProgress *p, TS ts);
PETSC_EXTERN PetscErrorCode MMProgressMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
