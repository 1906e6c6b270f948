/* app's log stages and events, registered once (like PETSc's XInitializePackage). */
#include "appimpl.h"

MMAppLog MMAppEvents;

PetscErrorCode MMAppInitializePackage(void)
{
  static PetscBool done = PETSC_FALSE;
  PetscClassId     id;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MMApp", &id));
  PetscCall(PetscLogStageRegister("MM setup", &MMAppEvents.setup));
  PetscCall(PetscLogStageRegister("MM time steps", &MMAppEvents.solve));
  PetscCall(PetscLogEventRegister("MMMeshLoad", id, &MMAppEvents.mesh_load));
  PetscCall(PetscLogEventRegister("MMFESetUp", id, &MMAppEvents.fe_setup));
  PetscCall(PetscLogEventRegister("MMContactSetUp", id, &MMAppEvents.contact_setup));
  PetscCall(PetscLogEventRegister("MMLoadsSetUp", id, &MMAppEvents.loads_setup));
  PetscCall(PetscLogEventRegister("MMInitialState", id, &MMAppEvents.initial_state));
  PetscCall(PetscLogEventRegister("MMFrictionSetUp", id, &MMAppEvents.friction_setup));
  PetscCall(PetscLogEventRegister("MMStepMatrix", id, &MMAppEvents.step_matrix));
  PetscCall(PetscLogEventRegister("MMEnergyInitial", id, &MMAppEvents.energy_initial));
  PetscCall(PetscLogEventRegister("MMDeformCheck", id, &MMAppEvents.deformation_check));
  PetscCall(PetscLogEventRegister("MMOutputOpen", id, &MMAppEvents.output_open));
  PetscFunctionReturn(0);
}
