/* The Coulomb friction solver (src/friction/, docs/method.md section 6): each step's Coulomb problem,
 * by a type chosen with -friction_type from a registry (MMFrictionRegister). It wraps the contact
 * object's solves. */
#pragma once
#include "contact.h"

/* The Coulomb friction solver: an opaque handle; its struct is private (src/friction/frictionimpl.h) */
typedef struct _p_MMFriction *MMFriction;

PETSC_EXTERN PetscFunctionList MMFrictionList;
PETSC_EXTERN PetscErrorCode MMFrictionInitializePackage(void);
PETSC_EXTERN PetscErrorCode MMFrictionRegister(const char name[], PetscErrorCode (*create)(MMFriction fr));
PETSC_EXTERN PetscErrorCode MMFrictionRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMFrictionCreate(MPI_Comm comm, MMFriction *fr);
PETSC_EXTERN PetscErrorCode MMFrictionSetFromOptions(MMFriction fr);
PETSC_EXTERN PetscErrorCode MMFrictionGetCoulombTolerance(MMFriction fr, PetscReal *tol);
PETSC_EXTERN PetscErrorCode MMFrictionSetUp(MMFriction fr, MMContact ct, PetscReal mu_max, PetscReal E_max, Vec react);
PETSC_EXTERN PetscErrorCode MMFrictionSolve(MMFriction fr, PetscInt step, PetscReal t, Vec b, Vec w, Vec react, PetscBool *ok);
PETSC_EXTERN PetscErrorCode MMFrictionGetType(MMFriction fr, const char **type);
PETSC_EXTERN PetscErrorCode MMFrictionGetConvergence(MMFriction fr, PetscInt *its, PetscInt *inner_its, PetscReal *contraction, PetscReal *contraction_max);
PETSC_EXTERN PetscErrorCode MMFrictionBeginStep(MMFriction);
PETSC_EXTERN PetscErrorCode MMFrictionRejectStep(MMFriction);
PETSC_EXTERN PetscErrorCode MMFrictionGetThresholds(MMFriction fr, Vec *s);
PETSC_EXTERN PetscErrorCode MMFrictionView(MMFriction fr, PetscViewer viewer); /* -friction_view */
PETSC_EXTERN PetscErrorCode MMFrictionDestroy(MMFriction *fr);
