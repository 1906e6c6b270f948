/* Log stages and events, registered together so -log_view shows where time goes. */
#include "log.h"

PetscLogEvent MM_ColumnsSolve, MM_ColumnsMove, MM_SplitInterface, MM_SplitBackward, MM_BlockOperator;

PetscErrorCode MMLogRegister(MMLog *log)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("mmcontact", &id));
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
  PetscCall(PetscLogEventRegister("MMKtReuse", id, &log->kt_reuse));
  PetscCall(PetscLogEventRegister("MMKtSetUp", id, &log->kt_setup));
  PetscCall(PetscLogEventRegister("MMKtSolve", id, &log->kt_solve));
  PetscCall(PetscLogEventRegister("MMActiveSetIter", id, &log->as_iterate));
  PetscCall(PetscLogEventRegister("MMActiveSetCG", id, &log->as_linear));
  PetscFunctionReturn(0);
}
