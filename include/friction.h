#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMFrictionSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFrictionSolve(MMCtx *, Vec, Vec, Vec, PetscBool *);
PETSC_EXTERN PetscErrorCode MMFrictionDestroy(MMFriction *);
