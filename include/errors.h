#pragma once
#include "mmcontact.h"
/* The exit status of a run (README "Exit status"), after sysexits.h where one fits, so that a batch
 * script can tell a refused input from a full disk, a stopped run from a finished one. */
#define MM_EXIT_USAGE       64 /* EX_USAGE: the input was refused (an option, the mesh, a checkpoint) */
#define MM_EXIT_PHYSICS     65 /* EX_DATAERR: a check of the result stopped the run (inverted cells, the energy audit, a solver that did not converge) */
#define MM_EXIT_LOCKED      73 /* EX_CANTCREAT: another run holds the output directory */
#define MM_EXIT_IO          74 /* EX_IOERR: an output file could not be written (full disk, file-size limit) */
#define MM_EXIT_RESTARTABLE 75 /* EX_TEMPFAIL: stopped by SIGTERM or SIGINT after a checkpoint: continue with -restart */
/* mmcontact's own error codes, beyond PETSc's: raise them with PetscCheck/SETERRQ like PETSc's */
#define MM_ERR_LOCKED  (PETSC_ERR_MAX_VALUE + 1) /* the output directory is another run's */
#define MM_ERR_PHYSICS (PETSC_ERR_MAX_VALUE + 2) /* the result is meaningless: a check of the physics failed */
PETSC_EXTERN PetscErrorCode MMErrorsSetUp(void);
PETSC_EXTERN PetscErrorCode MMErrorsAtAbort(void (*)(void));
