#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMLoadsSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMLoadsSetTime(MMCtx *, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode MMLoadsReactions(MMCtx *);
PETSC_EXTERN PetscErrorCode MMLoadsStepWork(MMCtx *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode MMLoadsDirichletKinetic(MMCtx *, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode MMLoadsInsertDirichletVelocity(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMLoadsInsertBoundaryValues(MMCtx *, Vec, PetscReal);
PETSC_EXTERN PetscErrorCode MMLoadsDestroy(MMLoads *);
PETSC_EXTERN PetscReal      MMAmplitudeValue(const MMAmplitude *, PetscReal);
/* the pressures' and point forces' nodal forces (src/fem/loads_nodal.c) */
PETSC_EXTERN PetscErrorCode MMFEAddPressure(MMCtx *, PetscInt, Vec);
PETSC_EXTERN PetscErrorCode MMFEAddPointForce(MMCtx *, PetscInt, Vec);
