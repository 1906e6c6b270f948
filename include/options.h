#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMOptionsProcess(MPI_Comm, MMOptions *);
PETSC_EXTERN PetscErrorCode MMOptionsCheckDimension(MPI_Comm, MMOptions *, PetscInt);
PETSC_EXTERN PetscErrorCode MMOptionsDestroy(MMOptions *);
