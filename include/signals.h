#pragma once
#include "mmcontact.h"
#include "errors.h" /* MM_EXIT_RESTARTABLE: the exit status of a run stopped by SIGTERM or SIGINT */
PETSC_EXTERN PetscErrorCode MMSignalsSetUp(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMSignalsReport(MMCtx *);
PETSC_EXTERN PetscErrorCode MMSignalsDieWithLauncher(void);
PETSC_EXTERN PetscErrorCode MMMPIEnvironmentSet(void);
PETSC_EXTERN PetscErrorCode MMThreadsSetDefault(void);
