#pragma once
#include "mmcontact.h"
#define TSNEWMARK "newmark"
PETSC_EXTERN PetscErrorCode MMNewmarkRegister(void);
PETSC_EXTERN PetscErrorCode MMNewmarkCreateTS(MMCtx *, TS *);
PETSC_EXTERN PetscErrorCode MMNewmarkSetDefaults(TS);
PETSC_EXTERN PetscErrorCode MMNewmarkInitialState(MMCtx *);
