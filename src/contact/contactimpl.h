/* Internals of the contact component, shared by its files (src/contact/) and by no one else. */
#pragma once
#include "contact.h"

/* A contact formulation's operations (docs/method.md section 3). A NULL entry is a capability the
 * formulation lacks: solvecontactdofs (a friction loop over it), setthresholds (Tresca solves with
 * given thresholds), solvecoulomb (the Delassus operator, for a contact-space Coulomb solver),
 * solvecoulombdofs (the formulation's own Coulomb solve on all dofs, for formulations without it). */
struct _MMContactOps {
  PetscErrorCode (*setup)(MMCtx *);                         /* its solvers, before the first K~ */
  PetscErrorCode (*setoperator)(MMCtx *);                   /* after K~ is assembled for a new dt */
  PetscErrorCode (*solve)(MMCtx *, Vec, Vec, Vec);          /* the step: b in; w (warm start in) and react out */
  PetscErrorCode (*solvecontactdofs)(MMCtx *, Vec, Vec, Vec); /* at least the contact dofs of w and react */
  PetscErrorCode (*recover)(MMCtx *, Vec, Vec, Vec);        /* the whole w and react after solvecontactdofs */
  PetscErrorCode (*setthresholds)(MMCtx *, Vec);
  PetscErrorCode (*solvecoulomb)(MMCtx *, Vec, Vec, Vec, MMContactSetSolver, void *, PetscBool *);
  PetscErrorCode (*solvecoulombdofs)(MMCtx *, Vec, Vec, Vec, Vec, PetscReal, PetscInt *, PetscBool *); /* b, w, react, thresholds (in and out), rtol */
  PetscErrorCode (*getstepksp)(MMCtx *, KSP *, KSP *);      /* the K~ solvers, for the start-up report */
  PetscErrorCode (*swapkept)(MMCtx *, PetscReal, PetscBool *); /* swap K~ and its factor with the kept ones; true if those are for dt */
  PetscErrorCode (*summary)(MMCtx *);                       /* its lines of the closing summary */
};

/* The registry: each formulation's create function sets ct->ops. */
PETSC_INTERN PetscErrorCode MMContactCreate_Condensed(MMContact *);
PETSC_INTERN PetscErrorCode MMContactCreate_Full(MMContact *);
PETSC_INTERN PetscErrorCode MMContactCreate_ActiveSet(MMContact *);
PETSC_INTERN PetscErrorCode MMContactCreate_None(MMContact *);
/* K~, its KSP and dt swapped with the kept ones (contact.c) */
PETSC_INTERN PetscErrorCode MMContactSwapKeptOperator(MMContact *, KSP *);
/* react = K~ w - b on the contact dofs (contact.c) */
PETSC_INTERN PetscErrorCode MMContactForce(MMCtx *, Vec, Vec, Vec);

/* interface/corners.c: friction corners, a second obstacle's Coulomb law on a node's dofs */
PETSC_INTERN void           MMContactCornerT2(PetscInt, const PetscReal[2], PetscReal[MM_MAX_DIM][MM_MAX_DIM]);
PETSC_INTERN void           MMContactCornerFrame2(PetscInt, const PetscReal[], const PetscReal[2], PetscReal[MM_MAX_DIM][MM_MAX_DIM]);
PETSC_INTERN void           MMContactCornerSplit(const MMContact *, PetscInt, PetscInt, const PetscScalar[], PetscReal[], PetscReal[]);
PETSC_INTERN PetscBool      MMContactCornerCrosses(const MMContact *, PetscInt, PetscInt, const PetscScalar[], PetscReal);
PETSC_INTERN PetscErrorCode MMContactCornersSetUpVecs(MMCtx *);
PETSC_INTERN PetscErrorCode MMContactCornersRHS(MMCtx *, const PetscInt[]);
PETSC_INTERN PetscErrorCode MMContactCornersExpand(PetscInt, PetscInt, const PetscScalar[], const PetscScalar[], const PetscReal[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscInt *, PetscInt **, PetscScalar **, PetscScalar **, PetscReal **, PetscScalar **);
PETSC_INTERN PetscErrorCode MMContactCornersContract(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscScalar[], const PetscScalar[], PetscScalar[], PetscScalar[]);
PETSC_INTERN PetscErrorCode MMContactCornersStore(MMCtx *);

/* interface/pairs.c: contact pairs between two bodies, node to segment or facet */
PETSC_INTERN PetscErrorCode MMContactPairsSetUp(MMCtx *, const PetscInt[], PetscInt);
PETSC_INTERN PetscErrorCode MMContactPairsProject(MMCtx *, PetscInt, PetscInt, const PetscReal[], PetscReal *, PetscReal[]);
PETSC_INTERN PetscErrorCode MMContactPairsBuildTransform(MMCtx *);
PETSC_INTERN PetscErrorCode MMContactPairsDestroy(MMContactPairs *);

/* interface/qp.c: bound-constrained QPs as SNESVI solves; exact linear solves */
PETSC_EXTERN PetscErrorCode MMKSPCheckDirect(KSP);
PETSC_EXTERN PetscErrorCode MMQPCreate(MPI_Comm, const char[], MMBoundQP *, PetscReal, SNES *);
PETSC_EXTERN PetscErrorCode MMQPSetFactorSPD(SNES);
PETSC_EXTERN PetscErrorCode MMQPSetOperator(SNES, MMBoundQP *);
PETSC_EXTERN PetscErrorCode MMQPSolve(SNES, MMBoundQP *, Vec, PetscInt *);
PETSC_EXTERN PetscErrorCode MMKSPSetFactorSPD(KSP, PetscInt);
PETSC_EXTERN PetscErrorCode MMPCRegisterSchurSplit(void);

/* interface/kt.c: K~ without a Delassus operator, by a factorization or preconditioned CG */
PETSC_EXTERN PetscErrorCode MMKtCreate(MMCtx *, PetscBool);
PETSC_EXTERN PetscErrorCode MMKtSetOperator(MMCtx *, Mat);
PETSC_EXTERN PetscErrorCode MMKtSolveToTolerance(KSP, PetscReal, Vec, Vec, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode MMKtSolve(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMKtDestroy(MMStepSolver *);
PETSC_EXTERN PetscErrorCode MMKtGetLocalBlocks(Mat, const char[], Mat *, Mat *, const PetscInt **);

/* impls/active_set/: the primal-dual active-set formulation */
PETSC_EXTERN PetscErrorCode MMActiveSetSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMActiveSetSetOperator(MMCtx *);
PETSC_EXTERN PetscErrorCode MMActiveSetBlockOperator(Mat, PetscInt, Mat *);
PETSC_EXTERN PetscErrorCode MMActiveSetSetThresholds(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMActiveSetSolve(MMCtx *, Vec, Vec, PetscBool *);
PETSC_EXTERN PetscErrorCode MMActiveSetDestroy(MMActiveSet *);

/* impls/condensed/condensed.c: the Delassus operator and the condensed VI */
PETSC_EXTERN PetscErrorCode MMCondensedFactor(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactCreateReactions(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCondensedCreateSolver(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCondensedSolveReactions(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedContactDofs(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedRecover(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMCondensedSolveCoulomb(MMCtx *, Vec, Vec, Vec, MMContactSetSolver, void *, PetscBool *);

/* impls/condensed/candidates.c: the candidate set, its cached columns of K~^{-1} E and its dense block */
PETSC_EXTERN PetscErrorCode MMCandidatesSetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCandidatesInvalidate(MMContact *);
PETSC_EXTERN PetscErrorCode MMCandidatesSwapCache(MMContact *, MMColumnCache *);
PETSC_EXTERN PetscErrorCode MMCandidatesSelect(MMCtx *);
PETSC_EXTERN PetscErrorCode MMCandidatesGrow(MMCtx *, const PetscScalar[], PetscBool *);
PETSC_EXTERN PetscErrorCode MMCandidatesMult(MMContact *, Vec, PetscScalar[]);
PETSC_EXTERN PetscErrorCode MMCandidatesRecover(MMContact *, Vec);
PETSC_EXTERN PetscErrorCode MMCandidatesDestroy(MMCandidates *);
/* impls/condensed/mumps_columns.c: columns of K~^{-1} for unit right-hand sides on a MUMPS factor on
 * several ranks (done false: not such a factor, use MatMatTransposeSolve) */
PETSC_INTERN PetscErrorCode MMMumpsColumnsSolve(MMMumpsColumns *, Mat, PetscInt, const PetscInt[], PetscScalar[], PetscInt, PetscBool *);
PETSC_INTERN PetscErrorCode MMMumpsColumnsDestroy(MMMumpsColumns *);
