#pragma once
#include "mmcontact.h"
#include "contact.h"
PETSC_EXTERN PetscErrorCode MMOptionsProcess(MPI_Comm comm, MMOptions *opt);
PETSC_EXTERN PetscErrorCode MMOptionsCheckDimension(MPI_Comm comm, MMOptions *opt, PetscInt dim, PetscBool damped);
PETSC_EXTERN PetscErrorCode MMOptionsDestroy(MMOptions *opt);
PETSC_EXTERN PetscErrorCode MMOptionsGetFEProblem(const MMOptions *opt, MMFEProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsGetContactProblem(const MMOptions *opt, MMContactProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsGetNewmarkProblem(const MMOptions *opt, MMNewmarkProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsGetIOProblem(const MMOptions *opt, MMIOProblem *pb);
PETSC_EXTERN PetscErrorCode MMOptionsHelpWithoutMesh(MPI_Comm comm, PetscBool *done);
PETSC_EXTERN PetscErrorCode MMOptionsCheckUnused(MPI_Comm comm, const MMOptions *opt, DM dm);
PETSC_EXTERN PetscErrorCode MMOptionsCheckValueless(MPI_Comm comm);
PETSC_EXTERN int            MMOptionsCheckFiles(int argc, char **argv);
