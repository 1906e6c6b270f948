/* Internals of the obstacle component: each shape's create function (registered in
 * interface/obstacle.c) and the checks the shapes share on their options. */
#pragma once
#include "obstacle.h"
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Plane(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Sphere(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Circle(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Cylinder(MMObstacle *);
PETSC_EXTERN PetscErrorCode MMObstacleRequireVector(const MMObstacle *, MPI_Comm, PetscInt, const char[], PetscInt, PetscReal[], PetscBool);
PETSC_EXTERN PetscErrorCode MMObstacleRequireRadius(const MMObstacle *, MPI_Comm);
PETSC_EXTERN PetscErrorCode MMObstacleRefuseUnused(const MMObstacle *, MPI_Comm, PetscBool, PetscBool, PetscBool, PetscBool, PetscBool, PetscBool);
