/* io's log stage and events, registered once (like PETSc's XInitializePackage); HDF5's own error
 * printing off. */
#include <petscviewerhdf5.h>
#include "outputimpl.h"

MMIOLog MMIOEvents;

/*@
  MMIOInitializePackage - Registers io's log stage and events, once, and turns HDF5's own error
  printing off

  Not collective

  Level: developer

.seealso: `MMTSInitializePackage()`, `MMOutputSetFromOptions()`
@*/
PetscErrorCode MMIOInitializePackage(void)
{
  static PetscBool done = PETSC_FALSE;
  PetscClassId     id;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MMIO", &id));
  PetscCall(PetscLogStageRegister("MM output", &MMIOEvents.output));
  PetscCall(PetscLogEventRegister("MMOutputFlush", id, &MMIOEvents.flush));
  PetscCall(PetscLogEventRegister("MMOutputIndex", id, &MMIOEvents.index));
  PetscCall(PetscLogEventRegister("MMOutputCopy", id, &MMIOEvents.copy));
  PetscCall(PetscLogEventRegister("MMOutputSpace", id, &MMIOEvents.space));
  PetscCall(PetscLogEventRegister("MMCheckpoint", id, &MMIOEvents.checkpoint));
  PetscCall(PetscLogEventRegister("MMRestartOutput", id, &MMIOEvents.restart_output));
  /* every failed HDF5 call of ours is reported by us, naming the file, in one line (PetscCallHDF5,
   * MMOutputHDF5End): HDF5's stack dump (a hundred lines of HDF5-DIAG on a full disk) would come
   * first and bury it (docs/full_disk.md) */
  PetscCheck(H5Eset_auto2(H5E_DEFAULT, NULL, NULL) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "H5Eset_auto2 failed");
  PetscFunctionReturn(0);
}
