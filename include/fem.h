/* fem: P1 elasticity on the mesh (src/fem/): the material of each cell, the operators K, M and the
 * loads (Cartesian: contact's frame rotates them), the loads in time and the support reactions, the stress. What the
 * user describes (the bodies, boundary conditions and loads) comes in as plain data (MMFEProblem). */
#pragma once
#include "mmbase.h"
#include "mesh.h"

/* insertmap.c: DMLocalToGlobal(dm, l, INSERT_VALUES, g) as a list of (local, global) dof pairs built once per
 * DM (src/fem/insertmap.c). */
typedef struct {
  DM        dm;         /* the DM the map was built for (not referenced) */
  PetscBool transform;  /* the DM has a basis transform: PETSc's own DMLocalToGlobal */
  PetscInt  n;
  PetscInt *loc, *glob; /* local offset, global offset from this rank's first */
} MMInsertMap;

PETSC_EXTERN PetscErrorCode MMInsertMapLocalToGlobal(DM dm, MMInsertMap *map, Vec l, Vec g);
PETSC_EXTERN PetscErrorCode MMInsertMapDestroy(MMInsertMap *map);

/* How K and M are assembled: closed-form P1 element matrices in one pass over the cells, or the
 * PetscFE quadrature (DMPlexSNESComputeJacobianFEM), kept to cross-check the first. */
typedef enum {
  MM_ASSEMBLY_CLOSED_FORM,
  MM_ASSEMBLY_FE
} MMAssemblyType;
PETSC_EXTERN const char *const MMAssemblyTypes[];

/* An amplitude in time as the user gave it (-traction_NAME_amplitude..., -gravity_amplitude...): its
 * kind, a name registered in src/fem/loads.c, and its data; checked there. */
typedef struct {
  char      kind[MM_TYPE_LEN];         /* "constant" (the default), "ramp", "halfsine", "table" */
  PetscReal time;                      /* T of ramp and halfsine */
  PetscBool time_set;
  char      table[PETSC_MAX_PATH_LEN]; /* the two-column CSV of table, empty if not given */
} MMAmplitudeOptions;

/* A Dirichlet boundary: fixes the listed components to value a(t) + velocity t, a its amplitude. */
typedef struct {
  char      *name;
  PetscInt   ncomp;   /* -1 until the dimension is known: then all components (a clamp) */
  PetscInt   comps[MM_MAX_DIM];
  PetscReal  values[MM_MAX_DIM];
  PetscInt   nvalues; /* entries given to -dirichlet_NAME_value, -1 if not set */
  PetscReal  velocity[MM_MAX_DIM];
  PetscInt   nvelocity; /* entries given to -dirichlet_NAME_velocity, -1 if not set */
  MMAmplitudeOptions amplitude;     /* -dirichlet_NAME_amplitude... of the value */
  const struct _MMAmplitude *amp;   /* its a(t), set by src/fem/loads.c; NULL: constant */
} MMDirichlet;

/* A load group (src/fem/load_groups.c): a physical group carrying a value times an amplitude in
 * time. A traction (-traction): a force per unit area on the group's boundary faces, d entries. A
 * pressure (-pressure, README "Loads in time"): value[0] = p, the traction -p n along each facet's
 * outward normal n of the reference configuration (p > 0 pushes in; per unit length in 2D). A point
 * force (-point_force): the force on each node of a Physical Point group, d entries (per unit
 * thickness in 2D). */
typedef struct {
  char     *name;
  PetscReal value[MM_MAX_DIM];
  PetscInt  nvalues; /* entries given to -KIND_NAME_value, -1 if not set */
  MMAmplitudeOptions amplitude;
} MMLoadGroup;
typedef MMLoadGroup MMTraction, MMPressure, MMPointForce;

/* The loads and boundary conditions as the user gives them (-gravity, -dirichlet, -traction,
 * -pressure, -point_force), read by MMLoadGroupsSetFromOptions (src/fem/load_groups.c). */
typedef struct {
  PetscReal          gravity[MM_MAX_DIM];
  PetscInt           ngravity; /* entries given to -gravity, -1 if not set */
  MMAmplitudeOptions gravity_amplitude;
  PetscInt     n_dirichlet, n_traction, n_pressure, n_point_force;
  MMDirichlet *dirichlet;
  MMLoadGroup *traction, *pressure, *point_force;
} MMLoadGroups;

/* The elasticity law (-elasticity, -body_NAME_elasticity; src/fem/elasticity_laws.c, docs/method.md
 * section 13): the paper's linear small-strain model, or a finite-strain hyperelastic law with the
 * same E and nu in the small-strain limit. */
typedef enum {
  MM_ELASTICITY_LINEAR,
  MM_ELASTICITY_SVK,       /* St. Venant-Kirchhoff */
  MM_ELASTICITY_NEOHOOKEAN /* compressible neo-Hookean */
} MMElasticityType;
PETSC_EXTERN const char *const MMElasticityTypes[];

/* A body of -bodies (docs/method.md section 2, "Bodies"): a physical group of cells with its own
 * material and initial velocity, each defaulting to the whole mesh's -E, -nu, -rho and -v0. */
typedef struct {
  char     *name;
  char      group[256]; /* -body_NAME_group: a Physical Surface (2D) or Volume (3D) */
  PetscBool group_set;
  PetscReal omega0[MM_MAX_DIM]; /* -body_NAME_omega0 (default -omega0): a rigid rotation about its centre of mass */
  PetscInt  nomega0;            /* entries given to -body_NAME_omega0, -1 if not set */
  PetscBool omega0_set;         /* it or -omega0 was given: without it nothing is added */
  PetscReal E, nu, rho;
  PetscReal v0[MM_MAX_DIM];
  PetscInt  nv0; /* entries given to -body_NAME_v0, -1 if not set */
  MMElasticityType elasticity; /* -body_NAME_elasticity (default -elasticity) */
} MMBodyOptions;

/* The problem fem discretizes, as the user described it (app's MMOptions, borrowed for the set-up):
 * the bodies' material, gravity, the boundary conditions and the loads (docs/method.md sections 2, 10). */
typedef struct {
  PetscReal            E, nu, rho;    /* the whole mesh's material without -bodies */
  MMElasticityType     elasticity;    /* -elasticity: the whole mesh's law without -bodies */
  const PetscReal     *v0;            /* MM_MAX_DIM: its initial velocity */
  PetscInt             n_bodies;      /* -bodies, 0 without it */
  const MMBodyOptions *bodies;
  const PetscReal     *omega0;        /* MM_MAX_DIM: -omega0 of the whole mesh without -bodies */
  PetscBool            omega0_set;    /* -omega0 was given */
  const PetscReal     *gravity;       /* MM_MAX_DIM */
  const MMAmplitudeOptions *gravity_amplitude;
  PetscInt             n_dirichlet, n_traction, n_pressure, n_point_force;
  MMDirichlet         *dirichlet;     /* the loads set each one's amplitude (MMDirichlet.amp) */
  const MMTraction    *traction;
  const MMPressure    *pressure;
  const MMPointForce  *point_force;
  PetscBool            static_sliding; /* -initial_state static_sliding: one body and constant loads */
  PetscBool            damped;         /* Rayleigh damping is on: a Dirichlet value's amplitude is refused */
} MMFEProblem;

/* Physical parameters, also passed to the pointwise kernels as constants[]. */
typedef enum {
  MM_C_LAMBDA,
  MM_C_MU,
  MM_C_RHO,
  MM_C_WEIGHT_K, /* weights of the stiffness and mass kernels in an assembly */
  MM_C_WEIGHT_M,
  MM_C_GRAVITY,  /* MM_MAX_DIM entries */
  MM_C_NUM = MM_C_GRAVITY + MM_MAX_DIM
} MMConstantIndex;

/* One body's material and initial velocity (src/fem/material.c, docs/method.md section 2 "Bodies"). */
typedef struct {
  const char *name;    /* the -bodies name; "body" for the whole mesh without -bodies */
  const char *group;   /* its physical group of cells; NULL: the whole mesh */
  PetscReal   E, nu, rho;
  PetscReal   lambda, mu; /* Lame parameters (plane strain in 2D) */
  MMElasticityType elasticity;
  PetscReal   c_p, c_s;   /* its pressure and shear wave speeds */
  PetscReal   v0[MM_MAX_DIM];
  PetscInt    ncells;  /* over all ranks */
  PetscReal   volume, mass;
  PetscReal   omega0[MM_MAX_DIM]; /* -omega0: its rigid rotation about x_cm, only when omega0_set */
  PetscBool   omega0_set;
  PetscReal   x_cm[MM_MAX_DIM];   /* its centre of mass, computed only when omega0_set */
} MMBody;

/* The material of each cell, built once at set-up: one body (the whole mesh, -E -nu -rho -v0)
 * without -bodies, or the bodies of -bodies, every cell in exactly one. The per-cell arrays are
 * indexed by the local cell number c - cStart of the mesh (and of its clones, which share it). */
typedef struct {
  PetscInt   n_bodies;
  MMBody    *body;
  PetscBool  named;       /* -bodies was given */
  PetscBool  uniform;     /* every cell has the same E, nu, rho: the PetscDS constants hold it */
  PetscInt   cStart, ncells; /* local cells */
  PetscInt  *cell_body;   /* per local cell, its body */
  PetscReal *lambda, *mu, *rho; /* per local cell */
  PetscReal *vertex_v0;   /* -bodies: per local vertex (dim entries), the v0 of the body of its cells */
  PetscReal *vertex_omega0; /* -omega0: per local vertex (dim entries), omega0 x (x - x_cm) of its body; NULL without */
  PetscBool  spin;        /* some body has an -omega0 */
  PetscReal  c_p_max;     /* the largest pressure wave speed: the CFL number's */
  PetscReal  E_max;       /* the largest Young's modulus: the contact solvers' force scales */
  PetscBool  finite;      /* some body has a finite-strain law (-elasticity svk or neohookean) */
} MMMaterial;

/* The contact frame's transforms (docs/method.md sections 2 and 11), an ops table contact installs into
 * fem's operators at set-up (MMFESetFrame): the frame, Q and N, is contact's (docs/developer.md, "The
 * contact frame"); fem's MMFEToCartesian family calls these. ctx is contact's. */
typedef struct {
  PetscErrorCode (*tocartesian)(void *ctx, Vec w, Vec ucart);        /* u = Q N w */
  PetscErrorCode (*fromcartesian)(void *ctx, Vec ucart, Vec w);      /* w = N^{-1} Q^T u */
  PetscErrorCode (*forcetocartesian)(void *ctx, Vec fw, Vec fcart);  /* f = Q N^{-T} f_w */
  PetscErrorCode (*forcefromcartesian)(void *ctx, Vec fcart, Vec fw); /* f_w = N^T Q^T f */
} MMFrameOps;

/* The finite element operators (src/fem/femimpl.h, private to fem): the mesh's DM and its scalar
 * vertex DM, the cells, the Cartesian K, M, load and lift fem assembles (MMFEAssembleOperators) and
 * hands to contact (MMFEHandMatrices, MMFEGetLoad, MMFEGetLift), whose frame turns them into its own
 * w-frame ones; the frame's transforms are contact's, installed by MMFESetFrame (docs/developer.md,
 * "The contact frame"). Another component reads them through functions (MMFEGetDM, ...). */
typedef struct _p_MMOperators *MMOperators;

/* The stress of a displacement (src/fem/stress.c, docs/method.md section 5, "Stress"): constant per
 * cell, and its lumped L2 projection per vertex, each with its von Mises value. */
typedef struct {
  DM         dm;                   /* 6 components per vertex: xx, xy, xz, yy, yz, zz (XDMF's Tensor6) */
  Vec        nodal, von_mises;     /* the nodal stress (dm) and its von Mises (fem's scalar DM, MMFEGetScalarDM) */
  Vec        weight;               /* each vertex's lumped weight sum_T |T| (dm_scalar) */
  Vec        cell, von_mises_cell; /* per local cell, in local order (no DM) */
  PetscReal *geom;                 /* per local cell its inverse edge matrix and volume, computed once */
} MMStress;

/* An amplitude in time (src/fem/loads.c): a(t) of a registered kind, docs/method.md section 10. */
typedef struct _MMAmplitude MMAmplitude;
struct _MMAmplitude {
  PetscReal (*value)(const MMAmplitude *a, PetscReal t);
  PetscReal  T;          /* ramp, halfsine */
  PetscInt   n;          /* table: rows, times t[] increasing, factors f[] */
  PetscReal *t, *f;
  PetscBool  constant;   /* a(t) = 1 */
};

/* Loads in time, moving Dirichlet data and the support reactions (src/fem/loads.c, docs/method.md
 * section 10). The load is a sum of parts, each a fixed vector times its amplitude,
 * L(t) = sum_k a_k(t) L_k: gravity is one part, each traction one. Nothing is reassembled per step. */
typedef struct {
  MMOperators        op;       /* borrowed at MMLoadsSetUp: the operators the loads are set on */
  struct _MMElasticity *el;     /* the finite-strain laws' force for the reactions (MMLoadsSetElasticity), or NULL: K_D */
  const MMMaterial  *material; /* borrowed at MMLoadsSetUp */
  IS           massless;   /* borrowed at MMLoadsSetUp: M*'s dofs without inertia (contact's), NULL if none */
  Vec          load, lift; /* borrowed at MMLoadsSetUp: the w-frame load and lift (contact's), which the loads in time set */
  PetscInt     nparts;
  MMAmplitude *amp;        /* per part */
  Vec         *part;       /* per part: w-frame, free dofs */
  PetscBool    in_time;    /* some amplitude is not constant: load is set at each step's time */
  Vec          load_old;   /* L(t0), the step's start; load holds L(t1) */
  PetscReal    t0, t1;     /* the times of the step being taken (both the current time between steps) */
  /* the constrained dofs (all Dirichlet boundaries): rows of the Cartesian K and M on a copy of the
   * mesh without constraints, and the load parts there */
  DM           dm_full;
  MMInsertMap  to_full, to_free; /* DMLocalToGlobal(INSERT) on dm_full and on the constrained DM, as maps */
  IS           isD;        /* the owned constrained dofs in dm_full's global numbering */
  PetscInt     nD;         /* how many (this rank) */
  PetscInt    *Dbc;        /* per owned constrained dof: the boundary whose reaction it counts in */
  PetscInt    *Dcomp;      /* and its Cartesian component */
  Mat          KD, MD;     /* rows D of the Cartesian stiffness and mass (M*: a is zero on the massless dofs) */
  Vec         *partD;      /* per part: its values on D */
  Vec          full, full2, rD, rD0, uD0, uD1, vD; /* scratch on dm_full and D; vD the boundary velocity */
  PetscBool    moving;     /* some -dirichlet_NAME_velocity is nonzero, or some value has an amplitude */
  PetscBool    dirichlet_amplitude; /* some value has an amplitude: u_D is not affine in t (lumped mass only) */
  MMAmplitude *bc_amp;     /* per Dirichlet boundary (n_bc of them), its value's amplitude */
  PetscInt     n_bc;
  PetscReal    vMv_DD;     /* vD . M_DD vD */
  PetscReal   *reaction;   /* per boundary, MM_MAX_DIM Cartesian components of the support's force on the body */
  /* the Dirichlet data of dm's local vectors, u_D(t) = bv0 + t bv1 at local dofs bv_idx, when no value
   * has an amplitude (MMLoadsInsertBoundaryValues); bv_n < 0: not tabulated */
  PetscInt     bv_n;
  PetscInt    *bv_idx;
  PetscReal   *bv0, *bv1;
} MMLoads;

/* fem.c and fem_options.c: the discretization, the Cartesian operators, the frame transforms (contact's ops, MMFESetFrame) */
PETSC_EXTERN PetscErrorCode MMFEInitializePackage(void);
PETSC_EXTERN PetscErrorCode MMFESetFromOptions(MMOperators op);
PETSC_EXTERN PetscErrorCode MMFESetUp(MMOperators op, MMMaterial *mat, const MMFEProblem *pb);
PETSC_EXTERN PetscErrorCode MMFEAssembleOperators(MMOperators op, const MMMaterial *mat, const MMFEProblem *pb);
PETSC_EXTERN PetscErrorCode MMFEAssembleOperatorsEnd(MMOperators op);
PETSC_EXTERN PetscErrorCode MMFECreateMatrix(MMOperators op, DM dm, Mat *A);
PETSC_EXTERN PetscErrorCode MMFEInterpolate(MMOperators op, PetscErrorCode (*f)(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt nc, PetscScalar *u, void *fctx), void *fctx, Vec u);
/* 1/2 int sigma(u):eps(u) of a Cartesian global vector ucart with the Dirichlet data of t = 0 inserted */
PETSC_EXTERN PetscErrorCode MMFEElasticEnergyIntegral(MMOperators op, const MMMaterial *mat, Vec ucart, PetscReal *energy);
PETSC_EXTERN PetscErrorCode MMFESetFrame(MMOperators op, const MMFrameOps *ops, void *ctx);
PETSC_EXTERN PetscErrorCode MMFEHandMatrices(MMOperators op, Mat *K, Mat *M);
PETSC_EXTERN PetscErrorCode MMFEToCartesian(MMOperators op, Vec w, Vec ucart);
PETSC_EXTERN PetscErrorCode MMFEFromCartesian(MMOperators op, Vec ucart, Vec w);
PETSC_EXTERN PetscErrorCode MMFEForceToCartesian(MMOperators op, Vec fw, Vec fcart);
PETSC_EXTERN PetscErrorCode MMFEForceFromCartesian(MMOperators op, Vec fcart, Vec fw);
PETSC_EXTERN PetscErrorCode MMFEVertexMasses(MMOperators op, const MMMaterial *mat, Vec mloc);
PETSC_EXTERN PetscErrorCode MMFEAddTraction(MMOperators op, const MMTraction *tr, Vec floc);
PETSC_EXTERN PetscErrorCode MMFEDestroy(MMOperators *op);
/* fem_object.c: the object, the mesh app hands it, and what the other components read of it */
PETSC_EXTERN PetscErrorCode MMFECreate(MPI_Comm comm, MMOperators *op);
PETSC_EXTERN PetscErrorCode MMFESetDM(MMOperators op, DM dm);
PETSC_EXTERN PetscErrorCode MMFEGetDM(MMOperators op, DM *dm);
PETSC_EXTERN PetscErrorCode MMFEGetScalarDM(MMOperators op, DM *dm);
PETSC_EXTERN PetscErrorCode MMFEGetDimension(MMOperators op, PetscInt *dim);
PETSC_EXTERN PetscErrorCode MMFEGetCells(MMOperators op, const MMCells **cells);
PETSC_EXTERN PetscErrorCode MMFEGetLoad(MMOperators op, Vec *load);
PETSC_EXTERN PetscErrorCode MMFEGetLift(MMOperators op, Vec *lift);
PETSC_EXTERN PetscErrorCode MMFEGetLumpedMass(MMOperators op, Vec *m);
PETSC_EXTERN PetscErrorCode MMFEIsMassLumped(MMOperators op, PetscBool *lumped);
PETSC_EXTERN PetscErrorCode MMFEGetDirichletEnergy(MMOperators op, PetscReal *energy);
/* assembly_p1.c: the damping stiffness with the dofs marked in qmark (w-frame) condensed cell by cell */
PETSC_EXTERN PetscErrorCode MMAssembleP1DampingStiffness(DM dm, const MMMaterial *mat, Mat Q, Vec qmark, Mat B);
/* assembly_p1.c: K <- Q^T K Q and M <- Q^T M Q in place on the P1 pattern, Q block diagonal by vertex (M
 * may be NULL); the contact frame's rotation (src/contact/frame/frame.c) */
PETSC_EXTERN PetscErrorCode MMRotateP1(Mat Q, Mat K, Mat M);
/* rigid_modes.c: the rigid-body modes, translations then rotations */
#define MM_MAX_RIGID 6
static inline PetscInt MMFENumRigidModes(PetscInt dim)
{
  return dim == 2 ? 3 : 6;
}
PETSC_EXTERN void           MMFERigidModeMatrix(PetscInt dim, const PetscReal x[], PetscReal T[MM_MAX_DIM][MM_MAX_RIGID]);
PETSC_EXTERN PetscErrorCode MMFERigidModesCartesian(MMOperators op, const PetscReal x0[], PetscReal ell, PetscInt nmodes, Vec modes[]);
/* stress.c: the stress of a displacement, for the output */
PETSC_EXTERN PetscErrorCode MMStressCreate(MMOperators op, MMStress *st);
PETSC_EXTERN PetscErrorCode MMStressCompute(MMStress *st, MMOperators op, const MMMaterial *mat, DM dm_u, Vec u, PetscBool nodal);
PETSC_EXTERN PetscErrorCode MMStressDestroy(MMStress *st);
/* loads.c: the loads in time, moving Dirichlet data and the reactions (after MMLoadsSetUp) */
PETSC_EXTERN PetscErrorCode MMLoadsSetUp(MMLoads *ld, MMOperators op, const MMMaterial *mat, const MMFEProblem *pb, IS massless, Vec load, Vec lift);
PETSC_EXTERN PetscErrorCode MMLoadsSetTime(MMLoads *ld, PetscReal t0, PetscReal t1);
PETSC_EXTERN PetscErrorCode MMLoadsReactions(MMLoads *ld, Vec u, Vec a);
PETSC_EXTERN PetscErrorCode MMLoadsStepWork(MMLoads *ld, Vec u, Vec a, Vec u_old, Vec a_old, PetscReal *w_ext_D, PetscReal *w_D);
PETSC_EXTERN PetscErrorCode MMLoadsDirichletKinetic(MMLoads *ld, Vec v, PetscReal *ek);
PETSC_EXTERN PetscErrorCode MMLoadsInsertDirichletVelocity(MMLoads *ld, Vec whole);
PETSC_EXTERN PetscErrorCode MMLoadsInsertBoundaryValues(MMLoads *ld, Vec l, PetscReal t);
PETSC_EXTERN PetscErrorCode MMLoadsScaleBoundaryValues(MMLoads *ld, Vec l, PetscReal s);
PETSC_EXTERN PetscErrorCode MMLoadsDestroy(MMLoads *ld);
PETSC_EXTERN PetscReal      MMAmplitudeValue(const MMAmplitude *a, PetscReal t);
/* bodies.c: the bodies read from their options (whole: the whole mesh's material, their defaults) */
PETSC_EXTERN PetscErrorCode MMBodiesSetFromOptions(MPI_Comm comm, const MMBodyOptions *whole, PetscInt *n, MMBodyOptions **bodies);
PETSC_EXTERN PetscErrorCode MMBodiesCheck(MPI_Comm comm, PetscInt n, const MMBodyOptions bodies[]);
PETSC_EXTERN PetscErrorCode MMBodiesCheckDimension(MPI_Comm comm, PetscInt n, const MMBodyOptions bodies[], PetscInt dim);
PETSC_EXTERN PetscErrorCode MMBodiesDestroy(PetscInt *n, MMBodyOptions **bodies);
PETSC_EXTERN PetscErrorCode MMMaterialCheckNearlyIncompressible(MPI_Comm comm, const char option[], PetscReal nu, MMElasticityType law);
/* load_groups.c: the boundary conditions and load groups read from their options */
PETSC_EXTERN PetscErrorCode MMLoadGroupsSetFromOptions(MPI_Comm comm, MMLoadGroups *lg);
PETSC_EXTERN PetscErrorCode MMLoadGroupsCheckDimension(MPI_Comm comm, MMLoadGroups *lg, PetscInt dim, PetscBool damped);
PETSC_EXTERN PetscErrorCode MMLoadGroupsDestroy(MMLoadGroups *lg);
PETSC_EXTERN PetscErrorCode MMAmplitudeOptionsRead(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char prefix[], MMAmplitudeOptions *a);
/* loads_nodal.c: the pressures' and point forces' nodal forces */
PETSC_EXTERN PetscErrorCode MMFEAddPressure(MMOperators op, const MMPressure *pr, Vec floc);
PETSC_EXTERN PetscErrorCode MMFEAddPointForce(MMOperators op, const MMPointForce *pf, Vec floc);
/* material.c: each cell's material */
PETSC_EXTERN PetscErrorCode MMMaterialSetUp(MMMaterial *mat, MMOperators op, const MMFEProblem *pb);
PETSC_EXTERN PetscErrorCode MMMaterialChecksum(const MMMaterial *mat, MMOperators op, PetscReal sum[3]);
PETSC_EXTERN PetscErrorCode MMMaterialDestroy(MMMaterial *mat);

/* elasticity.c: the total Lagrangian P1 internal force of the finite-strain laws (docs/method.md
 * section 13), on local Cartesian vectors of fem's DM (MMFEGetDM) with their Dirichlet data inserted */
typedef struct _MMElasticity {
  Vec       l0, l1, lf; /* local scratch */
  Vec       g;          /* global Cartesian scratch */
  PetscReal *G0;        /* per local cell, grad u at the step's start (MMElasticitySetStepStart) */
  PetscInt *cell_off;   /* per local cell, its dim + 1 vertices' offsets in the local vectors */
  PetscReal *cell_geom; /* per local cell, its P1 gradients (dim + 1 by dim) and volume */
  PetscReal  visc;      /* beta/dt: the step's viscous stress beta D : dE/dt (Rayleigh's stiffness part), 0 undamped */
  PetscBool  consistent; /* the tangent dP/dF itself, its geometric term everywhere (the static start's Newton) */
  PetscBool  clamp;      /* a compressed cell's tangent made semi-definite (unless consistent): the iteration matrix's choice */
} MMElasticity;
#define MM_ELASTICITY_GEOM ((MM_MAX_DIM + 1) * MM_MAX_DIM + 1)
PETSC_EXTERN PetscErrorCode MMElasticitySetUp(MMElasticity *el, MMOperators op);
/* l: the Cartesian local vector of the w-frame w with the Dirichlet data of time t */
PETSC_EXTERN PetscErrorCode MMElasticityLocal(MMElasticity *el, MMOperators op, MMLoads *ld, Vec w, PetscReal t, Vec l);
/* the step's start l0 (its grad u kept per cell), then fw (w-frame, free dofs) = the algorithmic internal
 * force of the step from l0 to l1 */
PETSC_EXTERN PetscErrorCode MMElasticitySetStepStart(MMElasticity *el, MMOperators op, Vec l0);
PETSC_EXTERN PetscErrorCode MMElasticityForce(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l1, Vec fw);
/* el->lf (local, Cartesian, unassembled: the constrained dofs' rows too) = the internal force P(F) at l */
PETSC_EXTERN PetscErrorCode MMElasticityForceLocal(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l);
PETSC_EXTERN PetscErrorCode MMElasticityForceMagnitude(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, Vec sw);
/* the reactions of the Dirichlet supports from the finite-strain force instead of K_D (el borrowed) */
PETSC_EXTERN PetscErrorCode MMLoadsSetElasticity(MMLoads *ld, MMElasticity *el);
PETSC_EXTERN PetscErrorCode MMElasticityEnergy(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, PetscReal *energy);
/* sum over the cells of |T| dE : D : dE for the step from the start set by MMElasticitySetStepStart to l1 */
PETSC_EXTERN PetscErrorCode MMElasticityDissipation(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l1, PetscReal *d);
/* Kc (a P1 matrix of the pattern of fem's DM) = the tangent dP/dF at l on the Cartesian dofs (contact turns it
 * into the w-frame: MMContactFrameMatrixBegin/End) */
PETSC_EXTERN PetscErrorCode MMElasticityAssembleTangent(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, Mat Kc);
/* the Cauchy stress of cell c (local) at the displacement gradient G */
PETSC_EXTERN PetscErrorCode MMElasticityCauchy(const MMMaterial *mat, PetscInt c, PetscInt dim, const PetscReal G[MM_MAX_DIM][MM_MAX_DIM], PetscReal sigma[MM_MAX_DIM][MM_MAX_DIM]);
PETSC_EXTERN PetscErrorCode MMElasticityDestroy(MMElasticity *el);
