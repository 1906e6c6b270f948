/* sys: what every component may use, and nothing above it (src/sys/): the exit statuses and error
 * handler, SIGTERM/SIGINT, the process's threads and MPI environment, and the checked option readers. */
#pragma once
#include "mmbase.h"

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

/* errors.c: the error handler of the exit statuses, a clean-up for the MPI_Abort path, what a stopped
 * run still writes, and the names of the MPI-IO files written (for a failed write's message) */
PETSC_EXTERN PetscErrorCode MMErrorsSetUp(void);
PETSC_EXTERN PetscErrorCode MMErrorsAtAbort(void (*fn)(void));
PETSC_EXTERN PetscErrorCode MMErrorsAtStop(void (*fn)(void));
PETSC_EXTERN PetscErrorCode MMErrorsNameMPIIOFile(MPI_File fh, const char name[]);

/* signals.c: SIGTERM and SIGINT stop the run after the step; the report says how to continue */
PETSC_EXTERN PetscErrorCode MMSignalsSetUp(TS ts);
PETSC_EXTERN PetscErrorCode MMSignalsGetStop(int *signal_number);
PETSC_EXTERN PetscErrorCode MMSignalsReport(MPI_Comm comm, PetscInt step, PetscReal time, const char output_dir[]);
PETSC_EXTERN PetscErrorCode MMSignalsDieWithLauncher(void);

/* mpi_env.c and threads.c: before MPI starts */
PETSC_EXTERN PetscErrorCode MMMPIEnvironmentSet(void);
PETSC_EXTERN PetscErrorCode MMThreadsSetDefault(void);

/* option_values.c: option readers that check the value before PETSc parses it, for every
 * component's SetFromOptions (inside PetscOptionsBegin/End) */
typedef enum {
  MM_VALUE_REAL, /* comma-separated numbers */
  MM_VALUE_INT,  /* comma-separated integers */
  MM_VALUE_TEXT  /* any non-empty text: a name, a path, a choice */
} MMValueKind;
PETSC_EXTERN PetscErrorCode MMOptionsCheckValue(MPI_Comm comm, const char name[], MMValueKind kind);
PETSC_EXTERN PetscErrorCode MMOptionsCheckFinite(MPI_Comm comm, const char name[], const PetscReal v[], PetscInt n);
PETSC_EXTERN PetscErrorCode MMOptionsReal(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscReal *v);
PETSC_EXTERN PetscErrorCode MMOptionsRealArray(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscInt nmax, PetscReal v[], PetscInt *count);
PETSC_EXTERN PetscErrorCode MMOptionsInt(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscInt *v);
PETSC_EXTERN PetscErrorCode MMOptionsBool(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscBool *v);
PETSC_EXTERN PetscErrorCode MMOptionsString(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], char v[], size_t len, PetscBool *set);
PETSC_EXTERN PetscErrorCode MMOptionsEnum(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], const char *const list[], PetscEnum *v);
/* a named group's list, -obstacles NAME,NAME: the names, refused if one is empty, has a blank or comes twice */
PETSC_EXTERN PetscErrorCode MMOptionsSplitNames(MPI_Comm comm, const char option[], const char list[], PetscInt *n, char ***names);
/* option_order.c: which of two options was given later (PETSC_OPTIONS, the command line, options files in place) */
PETSC_EXTERN PetscErrorCode MMOptionsOrder(const char a[], const char b[], PetscInt *order);
