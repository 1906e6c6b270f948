/* io's log stage and events, registered once (like PETSc's XInitializePackage). */
#include "outputimpl.h"

MMIOLog MMIOEvents;

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
  PetscCall(PetscLogEventRegister("MMCheckpoint", id, &MMIOEvents.checkpoint));
  PetscCall(PetscLogEventRegister("MMRestartOutput", id, &MMIOEvents.restart_output));
  PetscFunctionReturn(0);
}
