#pragma once
#include "mmcontact.h"
/* The registry of obstacle shapes (src/obstacle/interface/) and what the rest of the program asks of
 * an obstacle; each shape is src/obstacle/impls/<type>/, its private helpers in obstacleimpl.h. */
PETSC_EXTERN PetscErrorCode MMObstacleRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMObstacleSetType(MMObstacle *, MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode MMObstacleTypesList(char[], size_t);
PETSC_EXTERN PetscErrorCode MMObstacleCheck(MMObstacle *, MPI_Comm, PetscInt);
PETSC_EXTERN void           MMObstacleDisplacement(const MMObstacle *, PetscInt, PetscReal, PetscReal[]);
PETSC_EXTERN void           MMObstacleVelocity(const MMObstacle *, PetscInt, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode MMObstacleFinalize(void);
