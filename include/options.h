#pragma once
#include "mmcontact.h"
#include "contact.h"
PETSC_EXTERN PetscErrorCode MMOptionsProcess(MPI_Comm, MMOptions *);
PETSC_EXTERN PetscErrorCode MMOptionsCheckDimension(MPI_Comm comm, MMOptions *opt, PetscInt dim, PetscBool damped);
PETSC_EXTERN PetscErrorCode MMOptionsDestroy(MMOptions *);
PETSC_EXTERN PetscErrorCode MMOptionsGetFEProblem(const MMOptions *opt, MMFEProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsGetContactProblem(const MMOptions *opt, MMContactProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsGetNewmarkProblem(const MMOptions *opt, MMNewmarkProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsHelpWithoutMesh(MPI_Comm, PetscBool *);
PETSC_EXTERN PetscErrorCode MMOptionsCheckUnused(MPI_Comm, const MMOptions *, DM);
PETSC_EXTERN PetscErrorCode MMOptionsCheckValueless(MPI_Comm);
PETSC_EXTERN int            MMOptionsCheckFiles(int, char **);
