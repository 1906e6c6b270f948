#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMMaterialSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMMaterialChecksum(MMCtx *, PetscReal[3]);
PETSC_EXTERN PetscErrorCode MMMaterialDestroy(MMMaterial *);
