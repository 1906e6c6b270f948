#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMCheckpointWrite(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMCheckpointMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode MMCheckpointDestroy(MMCheckpoint *);
PETSC_EXTERN PetscErrorCode MMCheckpointLoad(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMCheckpointRestoreHistory(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCheckpointSnapshots(MMCtx *, PetscInt *, PetscReal **);
PETSC_EXTERN PetscInt       MMCheckpointSnapshotCount(const MMCtx *);
