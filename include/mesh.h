#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMMeshLoad(MPI_Comm, MMOptions *, DM *, PetscInt **);
PETSC_EXTERN PetscErrorCode MMMeshGetLabel(DM, const char[], DMLabel *);
PETSC_EXTERN PetscErrorCode MMMeshGetSizes(DM, PetscInt *, PetscInt *);
