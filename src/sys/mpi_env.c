/* The MPI environment the run needs, set before MPI starts. */
#include <stdlib.h>
#include "sys.h"

/*@
  MMMPIEnvironmentSet - Sets the MCA parameters the run needs of Open MPI's MPI-IO in the
  environment, unless the user set them: ompio and sharedfp/sm left out

  Not collective

  Note:
  Open MPI's MPI-IO, and what the output needs of it (docs/full_disk.md). HDF5 never uses shared
  file pointers, yet Open MPI 4.1's own MPI-IO (ompio) opens every file with a shared-file-pointer
  component, and each of them can leave something behind or stop the job:
  - sharedfp/sm creates a POSIX semaphore named after the file's base name alone
    (/dev/shm/sem.OMPIO_NAME). A run killed while it holds one leaves it behind, and every later run
    on the machine that opens a file of that name waits on it forever;
  - sharedfp/lockedfile writes NAME-JOBID-PID.lock beside the file, on rank 0 only. On a full disk
    that write fails and rank 0 leaves the open before the barrier the other ranks wait in, then
    waits in the close's barrier on another communicator: every rank spins forever inside
    H5Fcreate (seen with gdb on an 8 KiB tmpfs, 2 ranks). A kill leaves the .lock file;
  - sharedfp/individual leaves NAME.data.RANK and NAME.metadata.RANK after a kill.
  ROMIO, Open MPI's other MPI-IO component, opens a file with its errors agreed on every rank and
  creates a shared-file-pointer file only when shared file pointers are used. So ompio is left out,
  unless the user chose otherwise; should ompio be chosen, sharedfp/sm still is not. Must run before
  MPI_Init, which reads the MCA parameters from the environment.

  Level: developer

.seealso: `MMThreadsSetDefault()`, `MMSignalsDieWithLauncher()`
@*/
PetscErrorCode MMMPIEnvironmentSet(void)
{
  if (setenv("OMPI_MCA_io", "^ompio", 0)) return PETSC_ERR_SYS;
  if (setenv("OMPI_MCA_sharedfp", "^sm", 0)) return PETSC_ERR_SYS;
  return 0;
}
