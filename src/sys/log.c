/* Log stages and events, registered together so -log_view shows where time goes. */
#include "log.h"

PetscLogEvent MM_ColumnsSolve, MM_ColumnsMove, MM_SplitInterface, MM_SplitBackward, MM_BlockOperator;

PetscErrorCode MMLogRegister(MMLog *log)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("mmcontact", &id));
  PetscCall(PetscLogStageRegister("MM setup", &log->setup));
  PetscCall(PetscLogStageRegister("MM time steps", &log->solve));
  PetscCall(PetscLogStageRegister("MM output", &log->output));
  PetscCall(PetscLogEventRegister("MMAssemble", id, &log->assemble));
  PetscCall(PetscLogEventRegister("MMContactSolve", id, &log->contact_solve));
  PetscCall(PetscLogEventRegister("MMContactRecover", id, &log->contact_recover));
  PetscCall(PetscLogEventRegister("MMFrictionLoop", id, &log->friction));
  PetscCall(PetscLogEventRegister("MMCandidateCols", id, &log->candidate_columns));
  PetscCall(PetscLogEventRegister("MMColumnsSolve", id, &MM_ColumnsSolve));
  PetscCall(PetscLogEventRegister("MMColumnsMove", id, &MM_ColumnsMove));
  PetscCall(PetscLogEventRegister("MMSplitInterface", id, &MM_SplitInterface));
  PetscCall(PetscLogEventRegister("MMSplitBackward", id, &MM_SplitBackward));
  PetscCall(PetscLogEventRegister("MMBlockOperator", id, &MM_BlockOperator));
  PetscCall(PetscLogEventRegister("MMCandidateOp", id, &log->candidate_operator));
  PetscCall(PetscLogEventRegister("MMEnergy", id, &log->energy));
  PetscCall(PetscLogEventRegister("MMMomenta", id, &log->momenta));
  PetscCall(PetscLogEventRegister("MMCheckpoint", id, &log->checkpoint));
  PetscCall(PetscLogEventRegister("MMRestartOutput", id, &log->restart_output));
  PetscCall(PetscLogEventRegister("MMKtReuse", id, &log->kt_reuse));
  PetscCall(PetscLogEventRegister("MMKtSetUp", id, &log->kt_setup));
  PetscCall(PetscLogEventRegister("MMKtSolve", id, &log->kt_solve));
  PetscCall(PetscLogEventRegister("MMActiveSetIter", id, &log->as_iterate));
  PetscCall(PetscLogEventRegister("MMActiveSetCG", id, &log->as_linear));
  PetscCall(PetscLogEventRegister("MMMeshLoad", id, &log->mesh_load));
  PetscCall(PetscLogEventRegister("MMFESetUp", id, &log->fe_setup));
  PetscCall(PetscLogEventRegister("MMContactSetUp", id, &log->contact_setup));
  PetscCall(PetscLogEventRegister("MMLoadsSetUp", id, &log->loads_setup));
  PetscCall(PetscLogEventRegister("MMInitialState", id, &log->initial_state));
  PetscCall(PetscLogEventRegister("MMFrictionSetUp", id, &log->friction_setup));
  PetscCall(PetscLogEventRegister("MMStepMatrix", id, &log->step_matrix));
  PetscCall(PetscLogEventRegister("MMEnergyInitial", id, &log->energy_initial));
  PetscCall(PetscLogEventRegister("MMDeformCheck", id, &log->deformation_check));
  PetscCall(PetscLogEventRegister("MMOutputOpen", id, &log->output_open));
  PetscFunctionReturn(0);
}
