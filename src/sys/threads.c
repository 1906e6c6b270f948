/* One thread per MPI rank. Debian's MUMPS is built with OpenMP, and libgomp starts as many
 * threads as there are cores in every process: on 2 ranks on 2 cores that is 4 threads on 2
 * cores, and the ranks' factorizations and triangular solves fight for them: 2 ranks are much slower
 * so, and one rank gains nothing from a second thread (the figures: docs/scaling.md, "The figures
 * behind the code's choices"). So unless the user sets OMP_NUM_THREADS, each rank keeps one
 * thread, for OpenMP (MUMPS) and for a threaded OpenBLAS alike.
 * libgomp reads OMP_NUM_THREADS when it is loaded, before main: the count is set through the
 * runtimes' own calls instead, looked up in the process so that a build without them links. */
#include <dlfcn.h>
#include <stdlib.h>
#include "sys.h"

/*@
  MMThreadsSetDefault - Gives OpenMP and a threaded OpenBLAS one thread per rank, unless
  OMP_NUM_THREADS is set

  Not collective

  Note:
  Called before MPI starts. Sets the counts through omp_set_num_threads() and
  openblas_set_num_threads(), looked up with dlsym() so that a build without them links; OpenBLAS
  keeps OPENBLAS_NUM_THREADS when that is set.

  Why one thread per rank: the comment at the head of this file (docs/scaling.md, "The figures
  behind the code's choices").

  Level: developer

.seealso: `MMMPIEnvironmentSet()`
@*/
PetscErrorCode MMThreadsSetDefault(void)
{
  void (*omp_set)(int)      = NULL;
  void (*openblas_set)(int) = NULL;

  if (getenv("OMP_NUM_THREADS")) return 0; /* the user's choice */
  *(void **)&omp_set      = dlsym(RTLD_DEFAULT, "omp_set_num_threads");
  *(void **)&openblas_set = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  if (omp_set) omp_set(1);
  if (openblas_set && !getenv("OPENBLAS_NUM_THREADS")) openblas_set(1);
  return 0;
}
