#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMDeformationCheck(MMCtx *);
PETSC_EXTERN PetscErrorCode MMDeformationSummary(MMCtx *);
PETSC_EXTERN PetscErrorCode MMDeformationDestroy(MMDeformation *);
