/* Private to the friction component (src/friction/): the solver context, its ops table, and the
 * contact-space Coulomb problem with its semismooth Newton kernel (docs/method.md section 6). */
#pragma once
#include "friction.h"
#include "contact.h"
#include "sys.h"

/* The friction loop's event (MMFrictionInitializePackage) */
PETSC_INTERN PetscLogEvent MMFRICTION_Loop;

/* The step's Coulomb problem on a set of n contact nodes, nc = dim components each (normal first,
 * then the tangents of the node's frame), in the condensed formulation's variables: with u = W r - q
 * (u_n the gap left, u_t = -dt/2 the slip velocity), per node
 *   r_n >= 0, u_n >= 0, r_n u_n = 0   and   r_t in D(R), -u_t in the normal cone of D(R) at r_t,
 * D(R) the disk (3D) or interval (2D) of radius R = mu r_n (Coulomb) or R = s given (Tresca). */
typedef struct {
  PetscInt           n, nc;
  const PetscScalar *W;  /* m x m, m = nc n, column-major, symmetric */
  const PetscScalar *q;
  const PetscReal   *mu; /* per node */
  const PetscReal   *s;  /* per node: the Tresca thresholds, or NULL for Coulomb */
  PetscBool          redundant; /* two nodes on one node's dofs (a friction corner, docs/method.md section 12):
                                 * W singular, the Newton step the least-norm one */
} MMCoulombProblem;

/* Work arrays of the kernel, grown to the largest set seen. */
typedef struct {
  PetscInt      cap;
  PetscReal    *rho, *u, *z, *F, *Fn, *d, *rt, *y, *J;
  PetscReal    *DP; /* 9 per node (nc x nc, row-major), whatever nc */
  PetscInt     *act;
  PetscBLASInt *ipiv;
} MMCoulombWork;

/* What a solve reports. */
typedef struct {
  PetscInt  its;         /* iterations of the solver's own loop (Newton steps or threshold updates) */
  PetscInt  inner_its;   /* Newton steps inside them (the fixed point's Tresca solves) */
  PetscReal residual;    /* |Phi|_inf over the force scale at exit */
  PetscReal contraction; /* fixed point: mean contraction rate of the threshold changes */
  PetscBool converged;
} MMCoulombResult;

PETSC_INTERN PetscErrorCode MMCoulombNewton(const MMCoulombProblem *p, MMCoulombWork *wk, PetscReal rtol, PetscInt maxit, PetscScalar r[], MMCoulombResult *res);
PETSC_INTERN PetscErrorCode MMCoulombWorkDestroy(MMCoulombWork *wk);

/* A friction solver's operations, a static const table per type (impls/<type>/): a NULL entry is a
 * capability the type lacks. */
typedef struct _MMFrictionOps MMFrictionOps;
struct _MMFrictionOps {
  /* the contact-space problem on the candidate set; NULL: the type needs no Delassus operator */
  PetscErrorCode (*solveset)(MMFriction fr, const MMCoulombProblem *p, PetscScalar r[], MMCoulombResult *res);
  /* the formulation's own Tresca solve inside a threshold loop (no Delassus operator); NULL: none */
  PetscErrorCode (*solvethresholds)(MMFriction fr, Vec b, Vec w, Vec react);
  /* the formulation's own Coulomb solve on all dofs (no Delassus operator); NULL: none */
  PetscErrorCode (*solvedofs)(MMFriction fr, Vec b, Vec w, Vec react);
  PetscReal   default_rtol; /* -friction_rtol's default */
  const char *rtol_meaning; /* what that tolerance measures, for its help */
};

struct _p_MMFriction {
  MPI_Comm           comm;
  char               type[MM_TYPE_LEN];
  const MMFrictionOps   *ops;
  MMContact          contact;  /* borrowed: the contact it wraps */
  PetscInt           step;     /* the last accepted step and its time: the audit's obstacles, the dump's names */
  PetscReal          time;
  /* options (MMFrictionSetFromOptions) */
  char               type_name[MM_TYPE_LEN]; /* -friction_type */
  PetscBool          type_set;
  char               dump[PETSC_MAX_PATH_LEN]; /* -friction_dump: directory for the step problems, empty: none */
  SNES               snes;     /* prefix friction_: a shell whose solve is the type's */
  Vec                s, s_new; /* thresholds mu r_n per contact node (the threshold loop) */
  Vec                s_start;  /* the thresholds at the step's start: a rejected step's retry starts from them */
  Vec                sigma;    /* velocity of the current iterate */
  Vec                b, w, react; /* the step problem being solved (borrowed) */
  MMCoulombWork      work;
  PetscReal          coulomb_tol, s_floor, rtol;
  PetscInt           maxit;
  PetscReal          contraction, contraction_max;
  PetscInt           its, inner_its; /* the last step's */
  PetscReal          coulomb;        /* the last step's Coulomb residual */
  PetscBool          monitor;
};

PETSC_INTERN PetscErrorCode MMFrictionCreate_Newton(MMFriction fr);
PETSC_INTERN PetscErrorCode MMFrictionCreate_FixedPoint(MMFriction fr);
PETSC_INTERN PetscErrorCode MMFrictionThresholdLoop(MMFriction fr, Vec b, Vec w, Vec react);
PETSC_INTERN PetscErrorCode MMFrictionSolveDofs(MMFriction fr, Vec b, Vec w, Vec react);
PETSC_INTERN PetscErrorCode MMFrictionDumpSetUp(MMFriction fr);
PETSC_INTERN PetscErrorCode MMFrictionDump(MMFriction fr, const MMCoulombProblem *p, const PetscScalar x0[], const PetscScalar x[], const MMCoulombResult *res, PetscLogDouble seconds);
PETSC_INTERN PetscErrorCode MMFrictionCoulombResidual(MMFriction fr, PetscReal *coulomb, PetscInt *nslip, PetscInt *nstick);
