#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMFESetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFEAssembleOperators(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFEElasticEnergy(MMCtx *, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode MMFECheckElasticEnergy(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMFEToCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEFromCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEDestroy(MMOperators *);
