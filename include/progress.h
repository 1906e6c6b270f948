#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMProgressHeader(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMProgressMassLine(MMCtx *);
PETSC_EXTERN PetscErrorCode MMProgressSetUp(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMProgressMonitor(TS, PetscInt, PetscReal, Vec, void *);
