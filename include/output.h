#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMOutputCheckOptions(MPI_Comm, const MMOptions *);
PETSC_EXTERN PetscErrorCode MMOutputOpen(MMCtx *);
PETSC_EXTERN PetscErrorCode MMOutputMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode MMOutputClose(MMCtx *, PetscLogDouble, PetscLogDouble);
PETSC_EXTERN PetscErrorCode MMOutputLock(const char[]);
PETSC_EXTERN PetscErrorCode MMOutputUnlock(void);
PETSC_EXTERN PetscErrorCode MMOutputCheckHDF5Path(MPI_Comm, const char[], const char[], const char[]);
PETSC_EXTERN PetscErrorCode MMOutputSyncIndex(MMCtx *);
PETSC_EXTERN PetscErrorCode MMOutputCopySnapshots(MMCtx *);
