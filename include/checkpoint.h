#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMCheckpointWrite(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMCheckpointMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode MMCheckpointDestroy(MMCheckpoint *);
