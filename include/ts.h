/* The time stepper (src/ts/): trapezoidal Newmark as the PETSc TS type "newmark", its context MMNewmark
 * that owns the state, the history row, the damping and the audits (energy, momenta, deformation),
 * and the TSAdapt "growback". The components above read the state, history row and damping through
 * MMNewmarkGetState, MMNewmarkGetHistory and MMNewmarkGetDamping. */
#pragma once
#include "mmbase.h"
#include "obstacle.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"

/* The trapezoidal Newmark stepper (src/ts/newmark.c): its context owns the state below. */
typedef struct _p_MMNewmark *MMNewmark;

typedef enum {
  MM_INITIAL_GIVEN,
  MM_INITIAL_STATIC_SLIDING,
  MM_INITIAL_STATIC /* the static contact problem under the loads at t = 0 (src/contact/interface/static.c) */
} MMInitialState;

/* The Newmark state and the per-step energy audit. */
typedef struct {
  Vec       u, v, a;           /* current state, w-frame */
  Vec       u_old, v_old, a_old;
  Vec       react, react_old;  /* contact reactions on the body (K~ w - b on contact dofs) */
  Vec       work;              /* scratch */
  Vec       u_next;            /* the TS solution vector */
  Vec       du;                /* the step's increment u^{n+1} - u^n as the linear step solves for it (-step_increments) */
  PetscBool has_du;            /* du holds the accepted step's increment (else it is formed as u^{n+1} - u^n) */
  PetscReal dt;
  PetscReal dt_user;           /* -ts_dt: after a rejected step, dt grows back to it */
  PetscReal work_contact;      /* W_c of the accepted step, computed once by the contact-work guard */
  PetscReal work_frame;        /* the kinetic energy the contact frames moved at this step's start (-contact_frames follow) */
} MMState;

/* One row of the history, and its running sums. */
typedef struct {
  PetscInt  step;
  PetscReal time, dt;
  PetscReal kinetic, elastic, total;
  PetscReal work_ext, work_contact, work_friction; /* running sums */
  PetscReal work_obstacle;     /* running sum: the work of the moving obstacles' contact forces */
  PetscReal work_damping;      /* running sum: the Rayleigh damping work W_d <= 0 (src/ts/damping.c) */
  PetscReal work_dirichlet;    /* running sum: the work of the moving Dirichlet boundaries' reactions */
  PetscReal work_frame;        /* running sum: 1/2 v.(M*_new - M*_old) v at the frames' updates (-contact_frames follow) */
  PetscReal balance_residual;
  PetscInt  active, slipping, switched;
  PetscReal force_normal, force_tangential, max_penetration, coulomb_residual;
  PetscInt  vi_its, friction_its;
  PetscInt  candidates, resolves; /* the step's candidate-set size; VI re-solves after the set grew, over the run */
  PetscReal cfl, contraction;
  PetscReal ucm[MM_MAX_DIM], vcm[MM_MAX_DIM], L[MM_MAX_DIM];
  PetscReal P[MM_MAX_DIM], J[3], load[MM_MAX_DIM]; /* the scheme's momenta and the loads' resultant */
  PetscReal max_balance, max_penetration_run; /* over the run, for the summary */
  PetscReal energy_scale;                     /* the largest |E| of the run so far */
} MMHistory;

/* Rayleigh damping C = alpha M* + beta B, B = K or its condensed form (src/ts/damping.c, docs/method.md section 3). */
typedef struct {
  PetscReal mass, stiffness, ratio, freq[2];       /* the options as given: -damping_mass, _stiffness, _ratio, _frequencies */
  PetscBool mass_set, stiffness_set, ratio_set;
  PetscInt  nfreq;       /* entries given to -damping_frequencies, -1 if not set */
  PetscReal alpha, beta; /* 1/s and s, from the options (MMNewmarkSetFromOptions); both 0: no damping, and nothing below exists */
  Vec       vC;          /* the trapezoidal velocity 2/dt (u^{n+1} - u^n) - vC^n, on all dofs */
  Mat       B;           /* the damping stiffness: K, or with massless dofs K with them condensed out cell by cell */
  Vec       work, x;     /* scratch */
  Mat       Mstar;       /* borrowed: contact's M* (MMContactGetOperators) */
} MMDamping;

/* What the stepper needs of the problem (filled by app from its options, MMOptionsGetNewmarkProblem):
 * the initial state, the obstacles whose work it audits, and the values its messages quote. */
typedef struct {
  MMInitialState    initial_state;
  PetscReal         u0_offset[MM_MAX_DIM], u0_gradient[MM_MAX_DIM * MM_MAX_DIM];
  PetscBool         u0_given; /* -u0_offset or -u0_gradient was given */
  PetscReal         v0[MM_MAX_DIM], omega[MM_MAX_DIM], omega_center[MM_MAX_DIM];
  const MMObstacle *obstacles;  /* the rigid obstacles, then the contact pairs (borrowed) */
  PetscReal         obstacle_normal[MM_MAX_DIM]; /* -initial_state static_sliding's plane */
  PetscReal         mu;
  PetscBool         dirichlet;         /* some Dirichlet boundary */
  PetscBool         dirichlet_nonzero; /* some Dirichlet value or velocity is nonzero */
  PetscReal         E, nu, rho;        /* as given: the messages quote them */
  PetscBool         quiet;
} MMNewmarkProblem;


/* Registers the TS type, the adaptor and ts's events; called once (MMNewmarkCreate calls it) */
PETSC_EXTERN PetscErrorCode MMTSInitializePackage(void);

/* The Newmark context: create, hand it the problem and the lower components, compute the initial
 * state, then the TS that steps it */
PETSC_EXTERN PetscErrorCode MMNewmarkCreate(MPI_Comm comm, MMNewmark *nm);
PETSC_EXTERN PetscErrorCode MMNewmarkSetFromOptions(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMNewmarkSetProblem(MMNewmark nm, const MMNewmarkProblem *pb);
PETSC_EXTERN PetscErrorCode MMNewmarkSetUp(MMNewmark nm, MMOperators op, MMMaterial *material, MMLoads *loads, MMContact contact);
PETSC_EXTERN PetscErrorCode MMNewmarkSetFriction(MMNewmark nm, MMFriction friction);
PETSC_EXTERN PetscErrorCode MMNewmarkInitialState(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMNewmarkCreateTS(MMNewmark nm, TS *ts);
PETSC_EXTERN PetscErrorCode MMNewmarkSetDefaults(TS ts);
PETSC_EXTERN PetscErrorCode MMNewmarkGetPlan(MMNewmark nm, PetscReal *dt, PetscReal *steps);
PETSC_EXTERN PetscErrorCode MMNewmarkGetState(MMNewmark nm, MMState **state);
PETSC_EXTERN PetscErrorCode MMNewmarkGetHistory(MMNewmark nm, MMHistory **hist);
PETSC_EXTERN PetscErrorCode MMNewmarkGetDamping(MMNewmark nm, MMDamping **damping);
PETSC_EXTERN PetscErrorCode MMNewmarkDestroy(MMNewmark *nm);
/* -restart of a run whose contact frames followed: the checkpoint's frames (MMCheckpointGetFrames) */
PETSC_EXTERN PetscErrorCode MMNewmarkRestoreFrames(MMNewmark nm, const PetscScalar rec[], const PetscReal counters[]);
/* The finite-strain iteration matrix's point (NULL: K itself), kept by a checkpoint and rebuilt by -restart
 * (docs/method.md section 9); the step matrix as the stepper has it; the stepper from its TS */
PETSC_EXTERN PetscErrorCode MMNewmarkGetTangentPoint(MMNewmark nm, Vec *at, PetscReal *t);
PETSC_EXTERN PetscErrorCode MMNewmarkRestoreTangent(MMNewmark nm, Vec at, PetscReal t);
PETSC_EXTERN PetscErrorCode MMNewmarkGetStepMatrix(MMNewmark nm, PetscReal dt, MMStepMatrix *sm);
/* The step of dt handed to contact: its matrix, and the scheme's offset and scale (scheme.c) */
PETSC_EXTERN PetscErrorCode MMNewmarkSetStep(MMNewmark nm, PetscReal dt);
PETSC_EXTERN PetscErrorCode MMNewmarkFromTS(TS ts, MMNewmark *nm);
/* Large sliding's checkpoint: the forces carried across pairings, and the pairing restored (docs/method.md section 9) */
PETSC_EXTERN PetscErrorCode MMNewmarkGetCarriedForces(MMNewmark nm, PetscInt *n, Vec f[]);
PETSC_EXTERN PetscInt       MMNewmarkCountCarriedForces(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMNewmarkRestorePairs(MMNewmark nm, const PetscScalar rec[], const char file[]);
#define TSNEWMARK "newmark"

/* The audits (energy.c, deformation.c): on the initial state (restarted: it comes from a checkpoint),
 * then after every step by the stepper itself; the deformation audit's closing line */
PETSC_EXTERN PetscErrorCode MMEnergyInitial(MMNewmark nm, PetscBool restarted);
PETSC_EXTERN PetscErrorCode MMDeformationCheck(MMNewmark nm);
PETSC_EXTERN PetscErrorCode MMDeformationView(MMNewmark nm, PetscViewer viewer);
/* The finite-strain step's closing line: its iterations per step and iteration-matrix rebuilds (nonlinear.c) */
PETSC_EXTERN PetscErrorCode MMNonlinearView(MMNewmark nm, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMCertificateView(MMNewmark nm, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMNewmarkGetCertificateResidual(MMNewmark nm, Vec *r);
/* The step from which a rejection made the finite-strain tangent clamped, 0: not (nonlinear.c; a checkpoint keeps it) */
PETSC_EXTERN PetscErrorCode MMNewmarkGetTangentClampStep(MMNewmark nm, PetscInt *step);
PETSC_EXTERN PetscErrorCode MMNewmarkSetTangentClampStep(MMNewmark nm, PetscInt step);

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
