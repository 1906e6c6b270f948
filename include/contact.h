#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMKSPSetDirect(KSP);
PETSC_EXTERN PetscErrorCode MMKSPCheckFactored(KSP);
PETSC_EXTERN PetscErrorCode MMKSPSetFailureCheck(KSP);
PETSC_EXTERN PetscErrorCode MMKSPSetDirectSPD(KSP, PetscInt);
PETSC_EXTERN PetscErrorCode MMContactSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactSetTime(MMCtx *, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode MMContactSetStepMatrix(MMCtx *, PetscReal);
PETSC_EXTERN PetscErrorCode MMContactGetStepKSP(MMCtx *, KSP *, KSP *);
PETSC_EXTERN PetscErrorCode MMContactSolve(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactSolveContactDofs(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactRecover(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactSetThresholds(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactGetNormalReactions(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactUpdateSlip(MMCtx *, Vec, Vec, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode MMContactSetFrictionThresholds(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactUpdateFrictionStates(MMCtx *, Vec, Vec, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode MMContactProjectInitial(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactDiagnostics(MMCtx *, Vec, Vec, Vec, MMHistory *);
PETSC_EXTERN PetscErrorCode MMContactCoulomb(MMCtx *, Vec, Vec, Vec, PetscReal *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode MMContactBoundaryFields(MMCtx *, MMOutput *);
PETSC_EXTERN PetscErrorCode MMContactObstacleField(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactDestroy(MMContact *);
