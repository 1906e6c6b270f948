/* The MPI environment the run needs, set before MPI starts. */
#include <stdlib.h>
#include "signals.h"

/* Open MPI's MPI-IO (ompio) opens every file with a shared-file-pointer component, sharedfp/sm,
 * that creates a POSIX semaphore named after the file's base name alone (/dev/shm/sem.OMPIO_NAME).
 * A run killed while it holds one (SIGKILL, a node failure) leaves it behind, and every later run
 * on the machine that opens a file of that name, checkpoint.h5.tmp in any directory, waits on it
 * forever; two runs writing such files at the same moment share it. HDF5 never uses shared file
 * pointers, so the component is turned off, unless the user chose otherwise. Must run before
 * MPI_Init, which reads the MCA parameters from the environment. */
PetscErrorCode MMMPIEnvironmentSet(void)
{
  if (setenv("OMPI_MCA_sharedfp", "^sm", 0)) return PETSC_ERR_SYS;
  return 0;
}
