/* Internals of the obstacle component: each shape's create function (registered in
 * interface/obstacle.c) and the checks the shapes share on their options. */
#pragma once
#include "obstacle.h"
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Plane(MMObstacle *ob);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Sphere(MMObstacle *ob);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Circle(MMObstacle *ob);
PETSC_EXTERN PetscErrorCode MMObstacleCreate_Cylinder(MMObstacle *ob);
PETSC_EXTERN PetscErrorCode MMObstacleRequireVector(const MMObstacle *ob, MPI_Comm comm, PetscInt dim, const char what[], PetscInt count, PetscReal v[], PetscBool direction);
PETSC_EXTERN PetscErrorCode MMObstacleRequireRadius(const MMObstacle *ob, MPI_Comm comm);
PETSC_EXTERN PetscErrorCode MMObstacleRefuseUnused(const MMObstacle *ob, MPI_Comm comm, PetscBool point, PetscBool normal, PetscBool center, PetscBool axis, PetscBool radius, PetscBool side);
