#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMOutputCheckOptions(MPI_Comm, const MMOptions *);
PETSC_EXTERN PetscErrorCode MMOutputOpen(MMCtx *);
PETSC_EXTERN PetscErrorCode MMOutputMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode MMOutputClose(MMCtx *, PetscLogDouble, PetscLogDouble);
PETSC_EXTERN PetscErrorCode MMOutputLock(const char[]);
PETSC_EXTERN PetscErrorCode MMOutputUnlock(void);
PETSC_EXTERN PetscErrorCode MMOutputCheckHDF5Path(MPI_Comm, const char[], const char[], const char[]);
PETSC_EXTERN PetscErrorCode MMOutputSyncIndex(MMCtx *);
PETSC_EXTERN PetscErrorCode MMOutputCopySnapshots(MMCtx *);
/* -probes (src/io/probes.c): set up by the output, and by the data check, whose plan counts their
 * history columns and which refuses a group the mesh lacks as a run does */
PETSC_EXTERN PetscErrorCode MMProbesSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMProbesDestroy(MMProbes *);
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
PETSC_EXTERN PetscErrorCode MMOutputPlanMake(MMCtx *, TS, MMOutputPlan *);
