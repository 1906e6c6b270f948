/* Internals of the contact module, shared by its files (src/contact*.c) and by no one else. */
#pragma once
#include "contact.h"

/* contact_qp.c: bound-constrained QPs as SNESVI solves; exact linear solves */
PETSC_EXTERN PetscErrorCode MMKSPCheckDirect(KSP);
PETSC_EXTERN PetscErrorCode MMQPCreate(MPI_Comm, const char[], MMBoundQP *, PetscReal, SNES *);
PETSC_EXTERN PetscErrorCode MMQPSetOperator(SNES, MMBoundQP *);
PETSC_EXTERN PetscErrorCode MMQPSolve(SNES, MMBoundQP *, Vec, PetscInt *);
PETSC_EXTERN PetscErrorCode MMKSPSetFactorSPD(KSP, PetscInt);

/* contact_kt.c: K~ without a Delassus operator, by a factorization or preconditioned CG */
PETSC_EXTERN PetscErrorCode MMKtCreate(MMCtx *);
PETSC_EXTERN PetscErrorCode MMKtSetOperator(MMCtx *, Mat);
PETSC_EXTERN PetscErrorCode MMKtSolveToTolerance(KSP, PetscReal, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMKtSolve(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMKtDestroy(MMStepSolver *);

/* contact_active_set.c: the primal-dual active-set formulation */
PETSC_EXTERN PetscErrorCode MMActiveSetSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMActiveSetSetOperator(MMCtx *);
PETSC_EXTERN PetscErrorCode MMActiveSetSetThresholds(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMActiveSetSolve(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMActiveSetDestroy(MMActiveSet *);

/* contact_condensed.c: the Delassus operator and the condensed VI */
PETSC_EXTERN PetscErrorCode MMCondensedFactor(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactCreateReactions(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCondensedCreateSolver(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCondensedSolveReactions(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedContactDofs(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedRecover(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedSolveCoulomb(MMCtx *, Vec, Vec, Vec, MMContactSetSolver, void *, PetscBool *);

/* contact_candidates.c: the candidate set, its cached columns of K~^{-1} E and its dense block */
PETSC_EXTERN PetscErrorCode MMCandidatesSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCandidatesInvalidate(MMContact *);
PETSC_EXTERN PetscErrorCode MMCandidatesSelect(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCandidatesGrow(MMCtx *, const PetscScalar[], PetscBool *);
PETSC_EXTERN PetscErrorCode MMCandidatesMult(MMContact *, Vec, PetscScalar[]);
PETSC_EXTERN PetscErrorCode MMCandidatesRecover(MMContact *, Vec);
PETSC_EXTERN PetscErrorCode MMCandidatesDestroy(MMCandidates *);
