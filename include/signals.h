#pragma once
#include "mmcontact.h"
/* The exit status of a run stopped by SIGTERM or SIGINT after writing its checkpoint: EX_TEMPFAIL
 * of sysexits.h, "try again", so that a batch script can tell it from a finished or failed run. */
#define MM_EXIT_RESTARTABLE 75
PETSC_EXTERN PetscErrorCode MMSignalsSetUp(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMSignalsReport(MMCtx *);
