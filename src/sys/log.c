/* Log stages and events, registered together so -log_view shows where time goes. */
#include "log.h"

PetscErrorCode MMLogRegister(MMLog *log)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("mmcontact", &id));
  PetscCall(PetscLogEventRegister("MMEnergy", id, &log->energy));
  PetscCall(PetscLogEventRegister("MMMomenta", id, &log->momenta));
  PetscFunctionReturn(0);
}
