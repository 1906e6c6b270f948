/* One thread per MPI rank. Debian's MUMPS is built with OpenMP, and libgomp starts as many
 * threads as there are cores in every process: on 2 ranks on 2 cores that is 4 threads on 2
 * cores, and the ranks' factorizations and triangular solves fight for them. Measured on the D2
 * ball (113k dofs, condensed, friction, 30 steps): 2 ranks took 0.87 s/step and 42 s of set-up
 * with OpenMP's default, 0.49 s/step and 26 s with one thread, while one rank gained nothing from
 * its second thread (0.525 against 0.528 s/step). So unless the user sets OMP_NUM_THREADS, each
 * rank keeps one thread, for OpenMP (MUMPS) and for a threaded OpenBLAS alike.
 * libgomp reads OMP_NUM_THREADS when it is loaded, before main: the count is set through the
 * runtimes' own calls instead, looked up in the process so that a build without them links. */
#include <dlfcn.h>
#include <stdlib.h>
#include "signals.h"

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
