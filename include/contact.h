#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMKSPSetDirect(KSP);
PETSC_EXTERN PetscErrorCode MMKSPSetExactCG(KSP);
PETSC_EXTERN PetscErrorCode MMKSPCheckFactored(KSP);
PETSC_EXTERN PetscErrorCode MMKSPSetFailureCheck(KSP);
PETSC_EXTERN PetscErrorCode MMKSPSetDirectSPD(KSP, PetscInt);
PETSC_EXTERN PetscErrorCode MMKSPGetFactorPC(KSP, PC *, PetscBool *);
/* The exact solve of K~ split at the ranks' interface (src/contact/interface/pc_schursplit.c): the
 * default for K~ in 2D on 2 to 8 ranks, -contact_K_pc_type schursplit */
#define MMPCSCHURSPLIT "schursplit"
PETSC_EXTERN PetscErrorCode MMPCRegisterSchurSplit(void);
/* The full formulation's Newton solves by one factor of the whole K~, its active rows and columns
 * the identity's (src/contact/interface/pc_vifactor.c): the default, -contact_pc_type vifactor */
#define MMPCVIFACTOR "vifactor"
PETSC_EXTERN PetscErrorCode MMPCRegisterVIFactor(void);
PETSC_EXTERN PetscErrorCode MMPCVIFactorSetSNES(PC, SNES);
PETSC_EXTERN PetscErrorCode MMPCVIFactorAnalyse(PC, Mat);
PETSC_EXTERN PetscErrorCode MMPCVIFactorGetFactor(PC, Mat *, const char **);
PETSC_EXTERN PetscErrorCode MMFactorReadOptions(MPI_Comm, const char[], MatSolverType, MatFactorType);
PETSC_EXTERN PetscErrorCode MMContactRegister(const char[], PetscErrorCode (*)(MMContact *));
PETSC_EXTERN PetscErrorCode MMContactRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMContactSetUp(MMCtx *);
/* mass_boundary.c: what fem needs of the contact boundary to build M* */
PETSC_EXTERN PetscErrorCode MMContactGetMassBoundary(const MMContact *ct, MMMassBoundary *mb);
PETSC_EXTERN PetscErrorCode MMContactSetType(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactSummary(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactSetTime(MMCtx *, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode MMContactSetStepMatrix(MMCtx *, PetscReal);
PETSC_EXTERN PetscErrorCode MMContactGetStepKSP(MMCtx *, KSP *, KSP *);
PETSC_EXTERN PetscErrorCode MMContactSolve(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactSolveContactDofs(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactRecover(MMCtx *, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactGetNormalReactions(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactSetFrictionThresholds(MMCtx *, Vec);
/* The step's contact problem in contact space, on the condensed formulation's candidate set, for a
 * friction solver: n nodes of nc components (normal, then the tangents of the node's frame); the
 * set's Delassus block W (column-major, symmetric), the right-hand side q with u = W r - q (u_n: the
 * gap left; u_t: -dt/2 times the slip velocity), each node's mu. The solver overwrites x (the warm
 * start) with the reactions r. */
typedef struct {
  PetscInt           n, nc;
  const PetscScalar *W, *q;
  const PetscReal   *mu;
  PetscBool          redundant; /* some nodes act on the same dofs (friction corners): W is singular */
} MMContactSetProblem;
typedef PetscErrorCode (*MMContactSetSolver)(void *, const MMContactSetProblem *, PetscScalar[], PetscBool *);
PETSC_EXTERN PetscErrorCode MMContactHasDelassus(MMCtx *, PetscBool *);
PETSC_EXTERN PetscErrorCode MMContactSolveCoulomb(MMCtx *, Vec, Vec, Vec, MMContactSetSolver, void *, PetscBool *);
PETSC_EXTERN PetscErrorCode MMContactHasCoulombDofs(MMCtx *, PetscBool *);
PETSC_EXTERN PetscErrorCode MMContactSolveCoulombDofs(MMCtx *, Vec, Vec, Vec, Vec, PetscReal, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode MMContactProjectInitial(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactSolveStatic(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMContactDiagnostics(MMCtx *, Vec, Vec, Vec, MMHistory *);
PETSC_EXTERN PetscErrorCode MMContactCoulomb(MMCtx *, Vec, Vec, Vec, PetscReal *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode MMContactAudit(MMCtx *, const MMHistory *);
PETSC_EXTERN PetscErrorCode MMContactBoundaryFields(MMCtx *, MMOutput *);
PETSC_EXTERN PetscErrorCode MMContactObstacleField(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMContactDestroy(MMContact *);
PETSC_EXTERN PetscErrorCode MMContactPairsTransformOperators(MMCtx *);
/* The data check's first-contact estimate (interface/first_contact.c): the earliest time a contact
 * row closes at the nodes' initial velocity and acceleration, its node (reference position), its
 * obstacle (index in the options' obstacles, -1 if none closes before the end), its gap, approach
 * speed and acceleration at the start; and the rows touching at the start. */
typedef struct {
  PetscReal t, gap, speed, accel;
  PetscReal x[MM_MAX_DIM];
  PetscInt  obstacle, touching;
} MMFirstContact;
PETSC_EXTERN PetscErrorCode MMContactFirstContact(MMCtx *, Vec, Vec, Vec, PetscReal, PetscReal, MMFirstContact *);
PETSC_EXTERN PetscErrorCode MMContactObstacleGaps(MMCtx *, Vec, PetscReal, PetscInt[], PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode MMContactCornersAccept(MMCtx *);
PETSC_EXTERN PetscErrorCode MMContactCornersWork(MMCtx *, PetscReal, PetscReal, Vec, PetscReal *, PetscReal *, PetscReal *);
