/* The time stepper (src/ts/): trapezoidal Newmark as the PETSc TS type "newmark", its context MMNewmark
 * that owns the state, the history row, the damping and the audits (energy, momenta, deformation),
 * and the TSAdapt "growback". Its public data structs are in tstypes.h. */
#pragma once
#include "mmcontact.h"
#include "contact.h"

/* Registers the TS type, the adaptor and ts's events; called once (MMNewmarkCreate calls it) */
PETSC_EXTERN PetscErrorCode MMTSInitializePackage(void);

/* The Newmark context: create, hand it the problem and the lower components, compute the initial
 * state, then the TS that steps it */
PETSC_EXTERN PetscErrorCode MMNewmarkCreate(MPI_Comm comm, MMNewmark *nm);
PETSC_EXTERN PetscErrorCode MMNewmarkSetFromOptions(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMNewmarkSetProblem(MMNewmark nm, const MMNewmarkProblem *pb);
PETSC_EXTERN PetscErrorCode MMNewmarkSetUp(MMNewmark nm, MMOperators *op, MMMaterial *material, MMLoads *loads, MMContact contact);
PETSC_EXTERN PetscErrorCode MMNewmarkSetFriction(MMNewmark nm, MMFriction friction);
PETSC_EXTERN PetscErrorCode MMNewmarkInitialState(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMNewmarkCreateTS(MMNewmark nm, TS *ts);
PETSC_EXTERN PetscErrorCode MMNewmarkSetDefaults(TS ts);
PETSC_EXTERN PetscErrorCode MMNewmarkGetState(MMNewmark nm, MMState **state);
PETSC_EXTERN PetscErrorCode MMNewmarkGetHistory(MMNewmark nm, MMHistory **hist);
PETSC_EXTERN PetscErrorCode MMNewmarkGetDamping(MMNewmark nm, MMDamping **damping);
PETSC_EXTERN PetscErrorCode MMNewmarkDestroy(MMNewmark *nm);
#define TSNEWMARK "newmark"

/* The audits (energy.c, deformation.c): on the initial state (restarted: it comes from a checkpoint),
 * then after every step by the stepper itself; the deformation audit's closing line */
PETSC_EXTERN PetscErrorCode MMEnergyInitial(MMNewmark nm, PetscBool restarted);
PETSC_EXTERN PetscErrorCode MMDeformationCheck(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMDeformationView(MMNewmark nm, PetscViewer viewer);

/* Rayleigh damping C = alpha M* + beta B in the trapezoidal scheme (damping.c) */
PETSC_EXTERN PetscBool      MMDampingOn(const MMDamping *d);
PETSC_EXTERN PetscErrorCode MMDampingGetStepMatrix(MMDamping *d, Mat K, PetscReal dt, MMStepMatrix *sm);
PETSC_EXTERN PetscErrorCode MMDampingAddForce(MMDamping *d, Vec v, PetscReal a, Vec r);
PETSC_EXTERN PetscErrorCode MMDampingDestroy(MMDamping *d);

/* TSAdapt "growback" (adapt_growback.c): the default adaptor of -ts_type newmark */
#define TSADAPTGROWBACK "growback"
#define MM_ADAPT_STATE  4
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackRejected(TS ts, PetscBool regime);
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackGetState(TS ts, PetscReal state[MM_ADAPT_STATE]);
PETSC_EXTERN PetscErrorCode MMAdaptGrowBackSetState(TS ts, const PetscReal state[MM_ADAPT_STATE]);
