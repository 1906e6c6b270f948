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
/* What a run will write (output_plan.c, for -check_input): its snapshots, the bytes of each and of
 * the mesh in solution.h5 and of each one's grid in solution.xmf, its history rows and the most
 * bytes a row takes in history.csv. */
typedef struct {
  PetscReal snapshots, snapshot_bytes, mesh_bytes, index_grid_bytes;
  PetscReal rows, row_bytes, header_bytes;
} MMOutputPlan;
PETSC_EXTERN PetscErrorCode MMOutputPlanSize(MMCtx *, PetscReal, PetscReal, MMOutputPlan *);
