/* The contact component's class and log events (-log_view), registered once, by MMContactCreate. */
#include "../contactimpl.h"

PetscClassId  MMCONTACT_CLASSID;
PetscLogEvent MMCONTACT_Assemble, MMCONTACT_Solve, MMCONTACT_Recover, MMCONTACT_KtReuse, MMCONTACT_KtSetUp, MMCONTACT_KtSolve;
PetscLogEvent MMCONTACT_CandidateColumns, MMCONTACT_CandidateOperator, MMCONTACT_ColumnsSolve, MMCONTACT_ColumnsMove;
PetscLogEvent MMCONTACT_SplitInterface, MMCONTACT_SplitBackward, MMCONTACT_ActiveSetIterate, MMCONTACT_ActiveSetCG, MMCONTACT_BlockOperator;
PetscLogEvent MMCONTACT_FrameSetUp, MMCONTACT_FrameRotate, MMCONTACT_MassRedistribute, MMCONTACT_FrameFollow, MMCONTACT_PairsSlide, MMCONTACT_MassFree;

static PetscBool MMContactPackageInitialized = PETSC_FALSE;

/*@
  MMContactInitializePackage - Registers the contact package's class and its logging events, once

  Not collective

  Level: developer

.seealso: `MMContactCreate()`, `MMFEInitializePackage()`
@*/
PetscErrorCode MMContactInitializePackage(void)
{
  PetscFunctionBeginUser;
  if (MMContactPackageInitialized) PetscFunctionReturn(0);
  MMContactPackageInitialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MMContact", &MMCONTACT_CLASSID));
  /* K~'s assembly for a new dt (the name -log_view has always shown) */
  PetscCall(PetscLogEventRegister("MMAssemble", MMCONTACT_CLASSID, &MMCONTACT_Assemble));
  PetscCall(PetscLogEventRegister("MMContactSolve", MMCONTACT_CLASSID, &MMCONTACT_Solve));
  PetscCall(PetscLogEventRegister("MMContactRecover", MMCONTACT_CLASSID, &MMCONTACT_Recover));
  PetscCall(PetscLogEventRegister("MMCandidateCols", MMCONTACT_CLASSID, &MMCONTACT_CandidateColumns));
  PetscCall(PetscLogEventRegister("MMColumnsSolve", MMCONTACT_CLASSID, &MMCONTACT_ColumnsSolve));
  PetscCall(PetscLogEventRegister("MMColumnsMove", MMCONTACT_CLASSID, &MMCONTACT_ColumnsMove));
  PetscCall(PetscLogEventRegister("MMSplitInterface", MMCONTACT_CLASSID, &MMCONTACT_SplitInterface));
  PetscCall(PetscLogEventRegister("MMSplitBackward", MMCONTACT_CLASSID, &MMCONTACT_SplitBackward));
  PetscCall(PetscLogEventRegister("MMBlockOperator", MMCONTACT_CLASSID, &MMCONTACT_BlockOperator));
  PetscCall(PetscLogEventRegister("MMCandidateOp", MMCONTACT_CLASSID, &MMCONTACT_CandidateOperator));
  PetscCall(PetscLogEventRegister("MMKtReuse", MMCONTACT_CLASSID, &MMCONTACT_KtReuse));
  PetscCall(PetscLogEventRegister("MMKtSetUp", MMCONTACT_CLASSID, &MMCONTACT_KtSetUp));
  PetscCall(PetscLogEventRegister("MMKtSolve", MMCONTACT_CLASSID, &MMCONTACT_KtSolve));
  PetscCall(PetscLogEventRegister("MMActiveSetIter", MMCONTACT_CLASSID, &MMCONTACT_ActiveSetIterate));
  PetscCall(PetscLogEventRegister("MMActiveSetCG", MMCONTACT_CLASSID, &MMCONTACT_ActiveSetCG));
  /* the frame's rotation of K and M, -mass redistributed's construction (the names fem registered) */
  PetscCall(PetscLogEventRegister("MMContactFrame", MMCONTACT_CLASSID, &MMCONTACT_FrameSetUp));
  PetscCall(PetscLogEventRegister("MMRotateKM", MMCONTACT_CLASSID, &MMCONTACT_FrameRotate));
  PetscCall(PetscLogEventRegister("MMFramesFollow", MMCONTACT_CLASSID, &MMCONTACT_FrameFollow));
  PetscCall(PetscLogEventRegister("MMMassFree", MMCONTACT_CLASSID, &MMCONTACT_MassFree));
  PetscCall(PetscLogEventRegister("MMMassRedist", MMCONTACT_CLASSID, &MMCONTACT_MassRedistribute));
  PetscCall(PetscLogEventRegister("MMPairsSlide", MMCONTACT_CLASSID, &MMCONTACT_PairsSlide));
  PetscFunctionReturn(0);
}
