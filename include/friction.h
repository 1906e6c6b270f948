/* The Coulomb friction solver (src/friction/, docs/method.md section 6): each step's Coulomb problem,
 * by a type chosen with -friction_type from a registry (MMFrictionRegister). */
#pragma once
#include "mmcontact.h"

PETSC_EXTERN PetscFunctionList MMFrictionList;
PETSC_EXTERN PetscErrorCode MMFrictionRegister(const char[], PetscErrorCode (*)(MMFriction));
PETSC_EXTERN PetscErrorCode MMFrictionRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMFrictionSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFrictionSolve(MMCtx *, Vec, Vec, Vec, PetscBool *);
PETSC_EXTERN PetscErrorCode MMFrictionGetType(MMFriction, const char **);
PETSC_EXTERN PetscErrorCode MMFrictionGetConvergence(MMFriction, PetscInt *, PetscInt *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode MMFrictionGetThresholds(MMFriction, Vec *);
PETSC_EXTERN PetscErrorCode MMFrictionDestroy(MMFriction *);
