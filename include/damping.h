/* Rayleigh damping C = alpha M* + beta B in the trapezoidal scheme (src/ts/damping.c). */
#pragma once
#include "contact.h"
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMDampingCheckOptions(MPI_Comm, const MMOptions *);
PETSC_EXTERN PetscErrorCode MMDampingCoefficients(const MMOptions *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscBool      MMDampingOn(const MMCtx *);
PETSC_EXTERN PetscErrorCode MMDampingSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMDampingDestroy(MMDamping *);
PETSC_EXTERN PetscErrorCode MMDampingGetStepMatrix(MMDamping *d, Mat K, PetscReal dt, MMStepMatrix *sm);
PETSC_EXTERN PetscErrorCode MMDampingAddForce(MMCtx *, Vec, PetscReal, Vec);
PETSC_EXTERN PetscErrorCode MMDampingAddStepRHS(MMCtx *, PetscReal, Vec);
PETSC_EXTERN PetscErrorCode MMDampingUpdateVelocity(MMCtx *, PetscReal);
PETSC_EXTERN PetscErrorCode MMDampingWork(MMCtx *, Vec, PetscReal, PetscReal *);
