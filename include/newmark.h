#pragma once
#include "mmcontact.h"
#define TSNEWMARK "newmark"
PETSC_EXTERN PetscErrorCode MMNewmarkRegister(void);
PETSC_EXTERN PetscErrorCode MMNewmarkCreateTS(MMCtx *, TS *);
PETSC_EXTERN PetscErrorCode MMNewmarkSetDefaults(TS);
PETSC_EXTERN PetscErrorCode MMNewmarkInitialState(MMCtx *);
#define TSADAPTGROWBACK "growback"
#define MM_ADAPT_STATE  4
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackRegister(void);
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackRejected(TS, PetscBool);
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackGetState(TS, PetscReal[MM_ADAPT_STATE]);
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackSetState(TS, const PetscReal[MM_ADAPT_STATE]);
