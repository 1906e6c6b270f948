/* How a run that stops says why (README "Exit status").
 *
 * PETSc's default handler prints, on every rank, the message under its configure line, a traceback
 * and the list of options not yet read: right for a bug, noise for a user who mistyped an option.
 * Here the errors a user can act on (a refused input, an output file that cannot be written, a run
 * stopped by a check of its physics) print their message alone, once, as the first line of stderr,
 * and the run exits with a documented status. Any other error is a bug of ours or of a library: it
 * keeps PETSc's full trace, and so does every error under -debug. */
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "sys.h"

static PetscBool debug_trace = PETSC_FALSE;
static void (*at_abort)(void) = NULL; /* what exit() would run through atexit, on the MPI_Abort path */
static void (*at_stop)(void)  = NULL; /* what a run stopped by an error still writes (the output's index) */

/* Our own sources are compiled as "src/...", PETSc's as "./src/...": an unsupported combination of
 * options is the user's to fix when we raise it, a bug when PETSc does. */
static PetscBool OurCode(const char file[])
{
  return (PetscBool)(file && !strncmp(file, "src/", 4));
}

/* The exit status of an error a user can act on, 0 for any other (a bug: full trace). */
static int ExitStatus(PetscErrorCode n, const char fun[], const char file[])
{
  switch (n) {
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_FILE_OPEN:
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_UNEXPECTED:
    return MM_EXIT_USAGE;
  case PETSC_ERR_SUP:
    return OurCode(file) ? MM_EXIT_USAGE : 0;
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
    /* PETSc's reading of its own options: "-ts_type foo", "-ts_dt 1e-3s" */
    return fun && (!strncmp(fun, "PetscOptions", 12) || strstr(fun, "SetType") || strstr(fun, "SetFromOptions")) ? MM_EXIT_USAGE : 0;
  case PETSC_ERR_FILE_WRITE:
    return MM_EXIT_IO;
  case MM_ERR_LOCKED:
    return MM_EXIT_LOCKED;
  case MM_ERR_PHYSICS:
  case PETSC_ERR_NOT_CONVERGED:
  case PETSC_ERR_FP:
    return OurCode(file) ? MM_EXIT_PHYSICS : 0;
  default:
    return 0;
  }
}

/* A copy of MPI_COMM_WORLD for the end of a run that stops on an error, so that its barrier never
 * meets another collective in flight. */
static MPI_Comm end_comm = MPI_COMM_NULL;

/* Whether every rank has reached the end within about `seconds`: then the job can end cleanly. */
static PetscBool AllRanksEnding(double seconds)
{
  MPI_Request req;
  int         done = 0;

  if (end_comm == MPI_COMM_NULL || MPI_Ibarrier(end_comm, &req) != MPI_SUCCESS) return PETSC_FALSE;
  for (int i = 0; i < (int)(seconds / 0.005) && !done; ++i) {
    if (MPI_Test(&req, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) return PETSC_FALSE;
    if (!done) (void)usleep(5000);
  }
  return (PetscBool)done;
}

static void Print(const char mess[], int rank)
{
  if (rank >= 0) (void)fprintf(stderr, "mmcontact error (rank %d): %s\n", rank, mess);
  else (void)fprintf(stderr, "mmcontact error: %s\n", mess);
  (void)fflush(stderr);
}

/* After a failed write the ranks stop at different points of HDF5's calls, with its files open:
 * MPI_Finalize would have HDF5 close them, collectively, from those different points, and the ranks
 * wait for each other forever (under a full disk, one rank in H5AC_flush's barrier, the other in
 * H5FD_truncate's broadcast, called from H5F_term_package; docs/full_disk.md); on 1 rank the close
 * of a file whose creation failed crashed (SIGSEGV). What is on disk is what a kill leaves,
 * consistent by design: the job ends without closing the files, and without atexit's handlers,
 * HDF5's among them. */
static void EndWithFilesOpen(int status)
{
  (void)fflush(stdout);
  (void)fflush(stderr);
  if (at_abort) at_abort();
  _exit(status);
}

/* Prints the message and ends every rank with the status, the job ending normally when every rank
 * stops together: an error raised on all ranks (PetscCheck on a collective condition, or PETSc's
 * own check of an option, which each rank raises alone on PETSC_COMM_SELF) is printed once, by rank
 * 0. An error of one rank alone is printed by that rank, which ends the job with MPI_Abort (its
 * banner follows the message). */
static void PrintAndExit(MPI_Comm comm, const char mess[], int status)
{
  PetscMPIInt size = 1, rank = 0, wsize = 1, wrank = 0;
  PetscBool   together;

  (void)MPI_Comm_size(comm, &size);
  (void)MPI_Comm_rank(comm, &rank);
  (void)MPI_Comm_size(MPI_COMM_WORLD, &wsize);
  (void)MPI_Comm_rank(MPI_COMM_WORLD, &wrank);
  (void)fflush(stdout);
  if (at_stop) at_stop();
  if (wsize == 1) {
    Print(mess, -1);
    if (status == MM_EXIT_IO) EndWithFilesOpen(status);
    (void)MPI_Finalize();
    exit(status);
  }
  if (size == wsize) { /* collective: every rank is here, or about to be */
    if (rank == 0) Print(mess, -1);
    together = AllRanksEnding(10);
  } else { /* raised on fewer ranks: are the others stopping too? */
    together = AllRanksEnding(2);
    if (together && wrank == 0) Print(mess, -1);
    if (!together) Print(mess, wrank);
  }
  if (together && status == MM_EXIT_IO) EndWithFilesOpen(status);
  if (together) {
    /* rank 0's clean-up (the output directory's lock) before any rank ends: mpiexec kills the job's
     * other processes as soon as one exits with an error status, and an atexit handler of rank 0
     * could then never run (a refused -restart on 2 ranks left its lock file, under load) */
    if (at_abort) at_abort();
    (void)MPI_Barrier(MPI_COMM_WORLD);
    (void)MPI_Finalize();
    exit(status);
  }
  if (at_abort) at_abort();
  (void)MPI_Abort(MPI_COMM_WORLD, status);
  exit(status);
}

/* MPI-IO files being written, by handle, so that a failed write can name its file: registered by
 * the writer once HDF5 has opened the file; `opening` names the file being created, whose first
 * writes come before its handle is known. */
#define MM_MPIIO_FILES 4
static struct {
  MPI_File fh;
  char     name[PETSC_MAX_PATH_LEN];
} mpiio_files[MM_MPIIO_FILES];
static char mpiio_opening[PETSC_MAX_PATH_LEN];

/* The system's reason for a failed MPI-IO call: ROMIO keeps errno's meaning in the error class for a
 * full disk and a quota, and leaves errno set by the write that failed otherwise. */
static void MPIIOReason(int code, int err, char reason[], int len)
{
  int cls = MPI_ERR_OTHER, n = 0;

  (void)MPI_Error_class(code, &cls);
  if (cls == MPI_ERR_NO_SPACE) err = ENOSPC;
  else if (cls == MPI_ERR_QUOTA) err = EDQUOT;
  if (err) {
    (void)snprintf(reason, (size_t)len, "%s", strerror(err));
    return;
  }
  if (MPI_Error_string(code, reason, &n) != MPI_SUCCESS) (void)snprintf(reason, (size_t)len, "MPI-IO error %d", code);
}

/* A failed MPI-IO call on an open file ends the job at once, from inside the call: the collective
 * HDF5 call it came from would go on along a different path on each rank (one rank in H5AC's
 * barrier, another in H5FD_truncate's broadcast, for ever: docs/full_disk.md), at whatever size
 * the disk fills. HDF5 never sees the error, so no rank can leave the collective call unmatched.
 * A failed open returns as before: ROMIO's open agrees on its outcome across the ranks, and the
 * caller reports it collectively. */
static void MPIIOFailed(MPI_File *fh, int *code, ...)
{
  const int err = errno;
  char      reason[MPI_MAX_ERROR_STRING], mess[2 * PETSC_MAX_PATH_LEN + MPI_MAX_ERROR_STRING];
  const char *name = mpiio_opening[0] ? mpiio_opening : NULL;

  if (*fh == MPI_FILE_NULL) return;
  for (int i = 0; i < MM_MPIIO_FILES; ++i)
    if (mpiio_files[i].name[0] && mpiio_files[i].fh == *fh) name = mpiio_files[i].name;
  MPIIOReason(*code, err, reason, (int)sizeof(reason));
  /* a file not named by the writer is one being read (a checkpoint, on -restart) */
  if (name) (void)snprintf(mess, sizeof(mess), "Could not write %s: %s", name, reason);
  else (void)snprintf(mess, sizeof(mess), "Could not read an HDF5 file through MPI-IO: %s", reason);
  PrintAndExit(MPI_COMM_SELF, mess, MM_EXIT_IO);
}

/*@
  MMErrorsNameMPIIOFile - Names the MPI-IO file a writer is about to create or has open, so that a
  failed write's message names it

  Not collective

  Input Parameters:
+ fh   - the file's handle, or MPI_FILE_NULL for a file about to be created
- name - the file's name, or NULL to forget the handle once the file is closed

  Note:
  The writer names the file it is about to create (MPI_FILE_NULL) or has open (its handle); NULL
  forgets the handle once the file is closed.

  At most MM_MPIIO_FILES files may be named at a time; one more is an error (PETSC_ERR_PLIB).

  Level: developer

.seealso: `MMErrorsSetUp()`
@*/
PetscErrorCode MMErrorsNameMPIIOFile(MPI_File fh, const char name[])
{
  PetscFunctionBeginUser;
  if (fh == MPI_FILE_NULL) {
    PetscCall(PetscStrncpy(mpiio_opening, name ? name : "", sizeof(mpiio_opening)));
    PetscFunctionReturn(0);
  }
  for (int i = 0; i < MM_MPIIO_FILES; ++i)
    if (mpiio_files[i].name[0] && mpiio_files[i].fh == fh) mpiio_files[i].name[0] = 0;
  if (!name) PetscFunctionReturn(0);
  for (int i = 0; i < MM_MPIIO_FILES; ++i) {
    if (mpiio_files[i].name[0]) continue;
    mpiio_files[i].fh = fh;
    PetscCall(PetscStrncpy(mpiio_files[i].name, name, sizeof(mpiio_files[i].name)));
    PetscFunctionReturn(0);
  }
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_PLIB, "More than %d MPI-IO files open for writing", MM_MPIIO_FILES);
}

static PetscErrorCode MMErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  const int status = p == PETSC_ERROR_INITIAL && mess && mess[0] ? ExitStatus(n, fun, file) : 0;

  if (!status || debug_trace) return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
  PrintAndExit(comm, mess, status);
  return n;
}

/*@
  MMErrorsAtAbort - Sets the clean-up that runs also when the job ends by MPI_Abort()

  Not collective

  Input Parameter:
. fn - the clean-up, replacing any set before

  Note:
  A clean-up that must run also when the job ends by MPI_Abort (atexit handlers do not).

  Level: developer

.seealso: `MMErrorsAtStop()`, `MMErrorsSetUp()`
@*/
PetscErrorCode MMErrorsAtAbort(void (*fn)(void))
{
  PetscFunctionBeginUser;
  at_abort = fn;
  PetscFunctionReturn(0);
}

/*@
  MMErrorsAtStop - Sets what every rank runs when an error a user can act on stops the run

  Not collective

  Input Parameter:
. fn - the function, replacing any set before

  Note:
  What every rank runs when an error a user can act on stops the run, before the job ends (no MPI,
  no PETSc error handling in it: it runs inside the handler, on the ranks that raised the error).

  Level: developer

.seealso: `MMErrorsAtAbort()`, `MMErrorsSetUp()`
@*/
PetscErrorCode MMErrorsAtStop(void (*fn)(void))
{
  PetscFunctionBeginUser;
  at_stop = fn;
  PetscFunctionReturn(0);
}

/*@
  MMErrorsSetUp - Installs the error handler that ends a run with the exit statuses MM_EXIT_*, and
  the MPI-IO file error handler

  Not collective

  Note:
  Right after PetscInitialize: -debug is read here, before any option can fail. A write beyond the
  file-size limit (ulimit -f) raises SIGXFSZ, which kills the process without a word and can leave a
  row of history.csv cut mid-number: ignored, the write fails with EFBIG instead and the run stops
  naming the file (exit status MM_EXIT_IO).

  Also duplicates MPI_COMM_WORLD for the handler's own use, and sets an MPI-IO error handler on
  MPI_FILE_NULL, so that every file opened from then on reports a failed read or write (named by
  MMErrorsNameMPIIOFile()) and exits with MM_EXIT_IO.

  Level: developer

.seealso: `MMErrorsAtAbort()`, `MMErrorsAtStop()`, `MMErrorsNameMPIIOFile()`
@*/
PetscErrorCode MMErrorsSetUp(void)
{
  PetscFunctionBeginUser;
  PetscCheck(signal(SIGXFSZ, SIG_IGN) != SIG_ERR, PETSC_COMM_SELF, PETSC_ERR_SYS, "Could not ignore SIGXFSZ");
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-debug", &debug_trace, NULL));
  PetscCallMPI(MPI_Comm_dup(MPI_COMM_WORLD, &end_comm));
  PetscCall(PetscPushErrorHandler(MMErrorHandler, NULL));
  {
    /* every file MPI-IO opens from now on takes it (MPI_FILE_NULL's handler is the default) */
    MPI_Errhandler eh;
    PetscCallMPI(MPI_File_create_errhandler(MPIIOFailed, &eh));
    PetscCallMPI(MPI_File_set_errhandler(MPI_FILE_NULL, eh));
    PetscCallMPI(MPI_Errhandler_free(&eh));
  }
  PetscFunctionReturn(0);
}
