#pragma once
#include "mmcontact.h"
/* The registry of obstacle shapes (obstacle.c) and the shapes (obstacle_<type>.c). */
PETSC_EXTERN PetscErrorCode MMObstacleRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMObstacleSetType(MMObstacle *, MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode MMObstacleTypesList(char[], size_t);
PETSC_EXTERN PetscErrorCode MMObstacleCheck(MMObstacle *, MPI_Comm, PetscInt);
PETSC_EXTERN void           MMObstacleDisplacement(const MMObstacle *, PetscInt, PetscReal, PetscReal[]);
PETSC_EXTERN void           MMObstacleVelocity(const MMObstacle *, PetscInt, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode MMObstacleFinalize(void);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Plane(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Sphere(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Circle(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Cylinder(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleRequireVector(const MMObstacle *, MPI_Comm, PetscInt, const char[], PetscInt, PetscReal[], PetscBool);
PETSC_EXTERN PetscErrorCode MMObstacleRequireRadius(const MMObstacle *, MPI_Comm);
PETSC_EXTERN PetscErrorCode MMObstacleRefuseUnused(const MMObstacle *, MPI_Comm, PetscBool, PetscBool, PetscBool, PetscBool, PetscBool, PetscBool);
