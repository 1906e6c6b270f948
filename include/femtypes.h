/* The P1 discretization: the kernels' constants and the operators (src/fem/). */
#pragma once
#include "mmbase.h"
#include "insertmap.h"
#include "mesh.h"

/* The mass in time stepping (-mass, src/fem/fem_options.c): the modified mass drops the contact
 * nodes' normal mass, the redistributed one gives it back to the other nodes. */
typedef enum {
  MM_MASS_MODIFIED,
  MM_MASS_STANDARD,
  MM_MASS_REDISTRIBUTED /* modified, its removed mass given to the other nodes (docs/method.md section 2) */
} MMMassType;
PETSC_EXTERN const char *const MMMassTypes[];

/* How K and M are assembled: closed-form P1 element matrices in one pass over the cells, or the
 * PetscFE quadrature (DMPlexSNESComputeJacobianFEM), kept to cross-check the first. */
typedef enum {
  MM_ASSEMBLY_CLOSED_FORM,
  MM_ASSEMBLY_FE
} MMAssemblyType;
PETSC_EXTERN const char *const MMAssemblyTypes[];

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
  PetscReal   c_p, c_s;   /* its pressure and shear wave speeds */
  PetscReal   v0[MM_MAX_DIM];
  PetscInt    ncells;  /* over all ranks */
  PetscReal   volume, mass;
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
  PetscReal  c_p_max;     /* the largest pressure wave speed: the CFL number's */
  PetscReal  E_max;       /* the largest Young's modulus: the contact solvers' force scales */
} MMMaterial;

/* Finite element operators in the contact frame (w-dofs). */
typedef struct {
  DM        dm;
  DM        dm_scalar; /* one P1 scalar per vertex, no constraints: lumped masses, contact pressure and gap, von Mises */
  MMCells   cells;
  PetscInt  dim;
  Mat       K;      /* stiffness A */
  Mat       M;      /* standard mass (consistent or lumped): set-up only, NULL once M* is built */
  Mat       Mstar;  /* mass used in time stepping: M with the contact-normal rows/columns removed, or M */
  Mat       Q;      /* frame rotation, u_cart = Q w without contact pairs */
  Mat       N, Ninv; /* contact pairs: the slave nodes' relative variables, u_cart = Q N w (NULL without pairs) */
  Vec       pair_work; /* scratch for Q N w */
  Vec       load;   /* L: body force + traction (w-frame), constant in time */
  Vec       lift;   /* K_fD u_D: the Dirichlet data's elastic force on the free dofs (w-frame) */
  Vec       mass_lumped_cart; /* lumped standard mass per Cartesian dof */
  PetscReal mass_M;           /* total mass of M */
  PetscReal mass_star[MM_MAX_DIM * MM_MAX_DIM]; /* M*'s mass for rigid translations, dim x dim (m I for M) */
  PetscReal mass_star_inv[MM_MAX_DIM * MM_MAX_DIM]; /* its inverse (zero without mass), for ucm and vcm */
  PetscReal mass_correction;      /* -mass redistributed: the largest negative eigenvalue of a node's moment correction over its mass */
  PetscReal mass_moment_unreachable; /* 3D: |trace of G's translation-rotation block| left, / total mass (mass_redistribution.c) */
  PetscReal mass_moment_mismatch; /* -mass redistributed: max |rigid-mode Gram of M* - of M| / total mass */
  PetscBool mass_bounded;          /* -mass redistributed: the bounded correction (a coarse mesh: docs/method.md section 2) */
  PetscInt  mass_moments;          /* the moments matched: all (nr), or (dim) the masses and first moments alone */
  PetscReal mass_inertia_mismatch; /* then max |second moments of M* - of M| / total mass */
  MMMassType     mass_type;      /* -mass */
  PetscBool      lumped;         /* -mass_lumped */
  MMAssemblyType assembly;       /* -assembly */
  PetscBool      assembly_check; /* -assembly_check: assemble K and M both ways and stop if they differ */
  PetscReal c_p;    /* pressure wave speed */
  PetscReal energy_dirichlet; /* elastic energy of the Dirichlet data alone, 1/2 u_D.A_DD u_D */
  Vec       work;
} MMOperators;

/* The stress of a displacement (src/fem/stress.c, docs/method.md section 5, "Stress"): constant per
 * cell, and its lumped L2 projection per vertex, each with its von Mises value. */
typedef struct {
  DM         dm;                   /* 6 components per vertex: xx, xy, xz, yy, yz, zz (XDMF's Tensor6) */
  Vec        nodal, von_mises;     /* the nodal stress (dm) and its von Mises (MMOperators.dm_scalar) */
  Vec        weight;               /* each vertex's lumped weight sum_T |T| (dm_scalar) */
  Vec        cell, von_mises_cell; /* per local cell, in local order (no DM) */
  PetscReal *geom;                 /* per local cell its inverse edge matrix and volume, computed once */
} MMStress;

/* An amplitude in time (src/fem/loads.c): a(t) of a registered kind, docs/method.md section 10. */
typedef struct _MMAmplitude MMAmplitude;
struct _MMAmplitude {
  PetscReal (*value)(const MMAmplitude *, PetscReal);
  PetscReal  T;          /* ramp, halfsine */
  PetscInt   n;          /* table: rows, times t[] increasing, factors f[] */
  PetscReal *t, *f;
  PetscBool  constant;   /* a(t) = 1 */
};

/* Loads in time, moving Dirichlet data and the support reactions (src/fem/loads.c, docs/method.md
 * section 10). The load is a sum of parts, each a fixed vector times its amplitude,
 * L(t) = sum_k a_k(t) L_k: gravity is one part, each traction one. Nothing is reassembled per step. */
typedef struct {
  PetscInt     nparts;
  MMAmplitude *amp;        /* per part */
  Vec         *part;       /* per part: w-frame, free dofs */
  PetscBool    in_time;    /* some amplitude is not constant: op.load is set at each step's time */
  Vec          load_old;   /* L(t0), the step's start; op.load holds L(t1) */
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
