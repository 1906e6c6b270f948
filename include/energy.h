#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMEnergyInitial(MMCtx *);
PETSC_EXTERN PetscErrorCode MMEnergyStep(MMCtx *);
PETSC_EXTERN PetscErrorCode MMEnergyContactWork(MMCtx *, Vec, PetscReal *);
