/* Private to contact: the contact frame (src/contact/frame/, docs/method.md section 2). fem assembles
 * K, M, the load and the lift on the Cartesian dofs; the frame turns them into its own w-frame ones
 * (fem's MMOperators, which app hands it, hands over K and M and lends the load and lift: frame.c), builds M* for -mass (mass_star.c) and, for -mass
 * redistributed, gives the removed mass back (mass_redistribution.c). */
#pragma once
#include "contact.h"

/* The contact boundary as the mass sees it: the dofs M* drops, and each owned contact row's vertex
 * and frame, for -mass redistributed (filled from the contact set by mass_star.c). */
typedef struct {
  IS               massless;     /* the contact-normal dofs (w-frame), NULL without contact */
  PetscInt         n;            /* owned contact rows */
  const PetscInt  *vertex;       /* per row: its mesh point */
  const PetscInt  *scalar_index; /* per row: its vertex's global index on fem's scalar DM (MMFEGetScalarDM) */
  const PetscBool *second;       /* per row: a corner node's second row */
  const PetscReal *frame;        /* per row, 9 reals: its node's frame, rows nu, tau_1, tau_2 */
  const PetscInt  *fc_obstacle;  /* per row: a friction corner's second obstacle, or -1; NULL: none */
} MMMassBoundary;

/* The mass in time stepping: -mass, M* (w-frame) and its masses for the translations, which the stepper
 * reads through MMContactGetOperators, and what M*'s construction found, for its view (MMContactMassView). */
typedef struct {
  MMMassType type;                /* -mass */
  Mat        M;                   /* the w-frame standard mass, handed by fem (MMFEHandMatrices): set-up only, freed once M* and its moments are built */
  Mat        Mstar;               /* M with the massless dofs' rows and columns removed (and their mass given back, redistributed), or M */
  IS         massless;            /* the dofs without inertia in M* (the contact-normal ones), NULL if none (a reference) */
  PetscReal  mass_star[MM_MAX_DIM * MM_MAX_DIM];     /* M*'s mass for rigid translations, dim x dim (m I for M) */
  PetscReal  mass_star_inv[MM_MAX_DIM * MM_MAX_DIM]; /* its inverse (zero without mass), for ucm and vcm */
  PetscReal  total;               /* total mass of M */
  PetscReal  correction;          /* -mass redistributed: the largest negative eigenvalue of a node's moment correction over its mass */
  PetscReal  moment_unreachable;  /* 3D: |trace of G's translation-rotation block| left, / total mass (mass_redistribution.c) */
  PetscReal  moment_mismatch;     /* -mass redistributed: max |rigid-mode Gram of M* - of M| / total mass */
  PetscBool  bounded;             /* -mass redistributed: the bounded correction (a coarse mesh: docs/method.md section 2) */
  PetscInt   moments;             /* the moments matched: all (nr), or (dim) the masses and first moments alone */
  PetscReal  inertia_mismatch;    /* then max |second moments of M* - of M| / total mass */
  PetscBool  warned;              /* the warning of an M* short of M's mass was printed (once a run) */
  Mat        Q;                   /* borrowed: the frame's rotation (contact's), which turns the rigid modes into the w-frame */
  /* the mass in free flight (mass_free.c, docs/method.md section 2, "The mass in free flight") */
  PetscBool  free_flight;         /* -mass_free_flight */
  PetscBool  free_flight_set;     /* given: else on for the finite-strain laws where it applies */
  PetscBool  free_on;             /* resolved at set-up: M* switches between M and -mass's M* */
  PetscBool  is_free;             /* M* is M now: no contact node within reach of an obstacle */
  Mat        Mall;                /* the whole w-frame M, kept for the switches (shared with frames that follow) */
  PetscInt   switches[2];         /* over the run: switches to M (0) and back to -mass's M* (1) */
} MMContactMass;

/* The frame's transforms (docs/method.md sections 2 and 11): u_cart = Q N w, Q from the contact nodes'
 * frames (frame.c, turned by frames.c), N from the contact pairs (pairs.c). Contact's alone: fem reads
 * them through the ops table transform.c installs into its operators (MMFESetFrame). */
typedef struct {
  Mat Q;         /* frame rotation, u_cart = Q w without contact pairs */
  Mat N, Ninv;   /* contact pairs: the slave nodes' relative variables, u_cart = Q N w (NULL without pairs) */
  Vec pair_work; /* scratch for Q N w */
} MMContactTransform;

/* frame.c: Q from the contact nodes' frames (MMContactSetUp, before fem assembles) */
PETSC_INTERN PetscErrorCode MMContactFrameBuildRotation(MMContact ct, MMOperators op);
/* transform.c: the frame's transforms, installed into fem's operators; freed with contact */
PETSC_INTERN PetscErrorCode MMContactFrameInstall(MMContact ct, MMOperators op);
PETSC_INTERN PetscErrorCode MMContactTransformDestroy(MMContactTransform *xf);
/* mass_star.c: -mass, M* from M, its view */
PETSC_INTERN PetscErrorCode MMContactMassSetFromOptions(MPI_Comm comm, MMContactMass *mass);
PETSC_INTERN PetscErrorCode MMContactMassStar(MMContactMass *mass, MMOperators op, const MMMaterial *material, const MMMassBoundary *mb);
PETSC_INTERN PetscErrorCode MMContactMassRebuild(MMContactMass *mass, MMOperators op, Mat M, const MMMaterial *material, const MMMassBoundary *mb);
PETSC_INTERN void           MMContactMassBoundary(MMContact ct, MMMassBoundary *mb);
/* mass_redistribution.c: -mass redistributed, and the moments of M* */
PETSC_INTERN PetscErrorCode MMContactRedistributeMass(MMContactMass *mass, MMOperators op, const MMMaterial *material, const MMMassBoundary *mb);
PETSC_INTERN PetscErrorCode MMContactMassMoments(MMContactMass *mass, MMOperators op);
/* mass_free.c: the mass in free flight */
PETSC_INTERN PetscErrorCode MMContactMassFreeSetUp(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactMassFreeDestroy(MMContactMass *mass);
PETSC_INTERN PetscErrorCode MMContactMassFreeView(MMContact ct, PetscViewer viewer);
