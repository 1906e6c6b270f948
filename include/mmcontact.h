/* Shared context types of mmcontact: one struct per concern.
 *
 * Frames. Global vectors hold the free (non-Dirichlet) dofs. At every contact node the d dofs are
 * expressed in the obstacle frame (nu, tau_1[, tau_2]), nu the body's outward normal (pointing into
 * the obstacle): component 0 is the normal displacement u.nu, so u.nu <= g is a bound on one
 * unknown. All other nodes keep Cartesian dofs. Q maps frame dofs to Cartesian: u_cart = Q w.
 */
#pragma once
#include <petscdmplex.h>
#include <petscds.h>
#include <petscfe.h>
#include <petscsnes.h>
#include <petscts.h>

#define MM_MAX_DIM 3

typedef enum {
  MM_INITIAL_GIVEN,
  MM_INITIAL_STATIC_SLIDING
} MMInitialState;
PETSC_EXTERN const char *const MMInitialStates[];

typedef enum {
  MM_MASS_MODIFIED,
  MM_MASS_STANDARD
} MMMassType;
PETSC_EXTERN const char *const MMMassTypes[];

/* How each step's contact problem is solved: SNESVI condensed on the contact dofs through the
 * Delassus operator W = E^T K~^{-1} E (K~ factored once per dt), SNESVI on the full dof vector, or
 * a primal-dual active-set method on the full dof vector whose linear solves are preconditioned CG
 * (docs/method.md section 3, "Active-set formulation"): no factor, no Delassus operator. */
typedef enum {
  MM_CONTACT_CONDENSED,
  MM_CONTACT_FULL,
  MM_CONTACT_ACTIVE_SET
} MMContactFormulation;
PETSC_EXTERN const char *const MMContactFormulations[];

/* How K and M are assembled: closed-form P1 element matrices in one pass over the cells, or the
 * PetscFE quadrature (DMPlexSNESComputeJacobianFEM), kept to cross-check the first. */
typedef enum {
  MM_ASSEMBLY_CLOSED_FORM,
  MM_ASSEMBLY_FE
} MMAssemblyType;
PETSC_EXTERN const char *const MMAssemblyTypes[];

/* A Dirichlet boundary: fixes the listed components to constant values. */
typedef struct {
  char      *name;
  PetscInt   ncomp;   /* -1 until the dimension is known: then all components (a clamp) */
  PetscInt   comps[MM_MAX_DIM];
  PetscReal  values[MM_MAX_DIM];
  PetscInt   nvalues; /* entries given to -dirichlet_NAME_value, -1 if not set */
} MMDirichlet;

/* A Neumann boundary carrying a constant traction (force per unit area). */
typedef struct {
  char     *name;
  PetscReal traction[MM_MAX_DIM];
  PetscInt  nvalues; /* entries given to -traction_NAME_value, -1 if not set */
} MMTraction;

/* A rigid obstacle (docs/method.md section 8): a shape from the registry (src/obstacle*.c) that
 * gives the signed distance of a point and its gradient, the outward normal of the obstacle; it
 * may translate at a constant velocity between a start and a stop time. */
typedef struct _MMObstacle MMObstacle;
struct _MMObstacle {
  char      name[64], type[32];
  PetscReal point[MM_MAX_DIM], normal[MM_MAX_DIM], center[MM_MAX_DIM], axis[MM_MAX_DIM], radius;
  PetscInt  npoint, nnormal, ncenter, naxis, nvelocity; /* entries given, -1 if not set */
  PetscBool radius_set;
  PetscBool inside;                  /* the body is inside the sphere, circle or cylinder */
  PetscReal mu;                      /* friction coefficient against this obstacle */
  PetscReal velocity[MM_MAX_DIM], start, stop; /* moves at velocity for start < t <= stop */
  /* checks the parameters the shape needs, once the dimension is known */
  PetscErrorCode (*check)(MMObstacle *, MPI_Comm, PetscInt);
  /* signed distance g of x (positive outside the obstacle) and n = grad g, in the obstacle's
   * position at time 0 */
  PetscErrorCode (*distance)(const MMObstacle *, PetscInt, const PetscReal[], PetscReal *, PetscReal[]);
};

/* The vector options, whose lengths can only be checked once the mesh gives the dimension. */
typedef enum {
  MM_V_GRAVITY,
  MM_V_U0_OFFSET,
  MM_V_U0_GRADIENT,
  MM_V_V0,
  MM_V_OMEGA,
  MM_V_OMEGA_CENTER,
  MM_V_OBSTACLE_POINT,
  MM_V_OBSTACLE_NORMAL,
  MM_V_MESH_ROTATION,
  MM_V_MESH_ROTATION_CENTER,
  MM_V_NUM
} MMVectorOption;

/* Run options: everything the user sets. Filled in one place, src/options.c. */
typedef struct {
  char         mesh_file[PETSC_MAX_PATH_LEN];
  char         contact_name[256];
  PetscInt     n_dirichlet, n_traction;
  MMDirichlet *dirichlet;
  MMTraction  *traction;
  PetscReal    E, nu, rho;
  PetscReal    gravity[MM_MAX_DIM];
  PetscReal    u0_offset[MM_MAX_DIM], u0_gradient[MM_MAX_DIM * MM_MAX_DIM];
  PetscReal    v0[MM_MAX_DIM], omega[MM_MAX_DIM], omega_center[MM_MAX_DIM];
  MMInitialState initial_state;
  PetscReal    obstacle_point[MM_MAX_DIM], obstacle_normal[MM_MAX_DIM];
  PetscReal    mesh_rotation[MM_MAX_DIM], mesh_rotation_center[MM_MAX_DIM];
  MMMassType   mass_type;
  PetscBool    lumped;
  MMAssemblyType assembly;
  PetscBool    assembly_check; /* assemble K and M both ways and stop if they differ */
  PetscBool    contact;
  MMContactFormulation contact_formulation;
  PetscReal    contact_tol;
  PetscReal    candidate_margin;  /* candidate set: predicted gap within this times the deepest predicted penetration */
  PetscReal    candidate_memory;  /* candidate set: MiB of cached operator columns, over all ranks */
  PetscBool    candidate_all;     /* candidate set: every contact node, every step (the reference) */
  PetscInt     active_set_max_it;   /* active-set iterations per contact solve */
  PetscBool    active_set_monitor;
  PetscReal    audit_tol;
  PetscReal    contact_work_tol;
  PetscReal    initial_penetration_tol;
  PetscReal    mu;
  PetscReal    friction_coulomb_tol;
  char         friction_type[64];   /* -friction_type: a name registered in src/friction/ */
  PetscBool    friction_type_set;
  PetscBool    friction_monitor;
  char         output_dir[PETSC_MAX_PATH_LEN];
  PetscInt     output_every;
  PetscInt     checkpoint_every; /* steps between checkpoints, 0: only at the end */
  char         restart[PETSC_MAX_PATH_LEN]; /* -restart: the checkpoint, or its directory, to continue; empty: none */
  PetscBool    quiet;
  PetscReal    progress_every;      /* seconds of wall time between progress lines, 0: none */
  PetscBool    allow_unused;
  PetscBool    deformation_audit;       /* the deformation audit (deformation.c) and its thresholds */
  PetscReal    strain_warn, max_strain;
  PetscBool    debug; /* -debug: full PETSc traces (read again by errors.c before the options) */
  PetscInt     vec_count[MM_V_NUM]; /* entries given to each vector option, -1 if not set */
  PetscInt     n_obstacles;         /* -obstacles, or the one plane of -obstacle_point/_normal */
  MMObstacle  *obstacles;
  PetscBool    obstacles_named;     /* -obstacles was given */
  PetscReal    mu_max;              /* the largest friction coefficient of the obstacles */
} MMOptions;

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

/* Finite element operators in the contact frame (w-dofs). */
typedef struct {
  DM        dm;
  PetscInt  dim;
  Mat       K;      /* stiffness A */
  Mat       M;      /* standard mass (consistent or lumped) */
  Mat       Mstar;  /* mass used in time stepping: M with the contact-normal rows/columns removed, or M */
  Mat       Q;      /* frame rotation, u_cart = Q w */
  Vec       load;   /* L: body force + traction (w-frame), constant in time */
  Vec       lift;   /* K_fD u_D: the Dirichlet data's elastic force on the free dofs (w-frame) */
  Vec       mass_lumped_cart; /* lumped standard mass per Cartesian dof, for rigid-body diagnostics */
  PetscReal c_p;    /* pressure wave speed */
  PetscReal energy_dirichlet; /* elastic energy of the Dirichlet data alone, 1/2 u_D.A_DD u_D */
  Vec       work;
} MMOperators;

/* A bound-constrained quadratic problem A x = b, x <= upper, as the SNESVI residual context. */
typedef struct {
  Mat       A;
  Vec       b;
  PetscReal bnorm; /* ||b||, the scale of the absolute convergence test */
  PetscReal rtol_b;
} MMBoundQP;

/* The candidate set of the condensed formulation (docs/method.md section 3, "Candidate set"): the
 * contact nodes that can touch in the step, with the columns of K~^{-1} E computed when a node
 * first enters the set and kept, under a memory cap, until K~ is refactored. The step's VI on the
 * set is small and dense: it is replicated on every rank and solved with LAPACK. */
typedef struct {
  PetscInt     node_start;          /* global number of the first contact node owned here */
  PetscMPIInt *node_counts, *node_displs; /* contact nodes per rank, for the set's gathers */
  PetscInt    *normal_dof;          /* per contact node (all ranks): global index of its normal dof */
  PetscInt    *slot;                /* per contact node (all ranks): its column block in the cache, or -1 */
  PetscInt    *slot_node;           /* per cached block: its contact node */
  PetscInt     n_cached, cap;       /* cached nodes; blocks allocated */
  PetscScalar *cols;                /* cached columns of K~^{-1} E on the owned condensed rows (lda nc_local) */
  PetscInt     nc_local;            /* owned condensed dofs: ncomp n_local */
  PetscInt    *cond_row;            /* per owned condensed dof, its local row in the full vectors */
  PetscScalar *full;                /* the same columns on all owned dofs (lda n_local), while they fit */
  PetscInt     n_local, N;          /* owned and global dofs */
  PetscBool    full_ok;             /* full columns kept: the step is recovered from them, without a solve */
  PetscBool   *in_set;              /* per contact node (all ranks): in the step's set */
  PetscInt     n_set, *set;         /* the step's set: contact nodes in increasing order, on every rank */
  PetscInt     m;                   /* its condensed dofs: ncomp n_set */
  Mat          W;                   /* the set's Delassus block (seqdense, symmetrized) */
  Vec          x, lo, hi, q, f;     /* the set's reactions, bounds, right-hand side, residual */
  VecScatter   gather;              /* global condensed vectors -> the set */
  SNES         snes;                /* the VI on the set, prefix contact_ */
  MMBoundQP    qp;
  PetscReal    margin;              /* -contact_candidate_margin */
  PetscBool    all;                 /* -contact_candidate_all */
  PetscReal    memory_cap;          /* -contact_candidate_memory, bytes over all ranks */
  PetscScalar *wc;                  /* the step's solution on the owned condensed dofs, from the set's reactions */
  PetscInt     resolves;            /* VI re-solves after the set grew, over the run */
  PetscInt     columns;             /* columns computed in the run */
  PetscInt     evicted;             /* cached nodes dropped under the memory cap, over the run */
  PetscInt     recover_solves;      /* steps recovered by a solve, the full columns being over the cap */
  PetscInt     max_set;             /* the largest set of the run */
} MMCandidates;
/* The K~ solver of the paths that build no Delassus operator (-contact 0 and the active-set
 * formulation): a factorization, or CG with an algebraic multigrid PC, prefix contact_K_. Its PC is
 * set up once per dt. */
typedef struct {
  KSP          ksp;
  PetscBool    iterative; /* its PC is not a complete factorization */
  MatNullSpace rigid;     /* rigid-body modes in the w-frame: GAMG's near-null space */
  PetscInt     its;       /* linear iterations since the step began */
} MMStepSolver;

/* The active-set contact solver (contact_active_set.c): per owned contact node its normal state and,
 * with friction, its stick/slip state and slip direction; the projected CG on the free dofs. */
typedef struct {
  KSP        ksp;       /* prefix contact_as_: CG on the free dofs, PC the projected contact_K_ PC */
  Mat        A;         /* shell operator P_F K~ P_F + P_D */
  Vec        free;      /* 1 on the dofs free in this iteration, 0 on the fixed ones (D) */
  Vec        x0, r, dx, t; /* the iterate with its fixed values, residuals, correction, scratch */
  Vec        s;         /* Tresca thresholds per contact node (0 without friction) */
  Vec        ct_diag;   /* diag(K~): the scale c of the complementarity functions, per dof */
  PetscBool *active;    /* normal: w_n = g (else rho_n = 0) */
  PetscBool *stick;     /* tangential: w_t = off_t (else rho_t = s d) */
  PetscReal *dir;       /* slip direction d per node, dim-1 components in the tangent frame */
  PetscReal *kappa, *beta, *rperp; /* 3D slip: Newton tangent of the disk across d (a spring kappa on
                                    * w.d_perp), and the reaction across d it corrects (beta rperp) */
  PetscInt   max_it, its, lin_its;
  PetscBool  monitor;
} MMActiveSet;

/* Contact set, gaps, bounds and the per-step contact solver. Friction wraps ContactSolve. */
typedef struct {
  PetscBool  enabled;
  PetscInt   n_local, n_global;   /* contact nodes owned here / in total */
  IS         is_normal;           /* global indices of the contact-normal dofs (owned) */
  IS         is_tangent;          /* global indices of the contact-tangential dofs (owned) */
  IS         is_star;             /* every other dof (owned) */
  IS         is_interior;         /* the dofs of the nodes off the contact boundary (owned) */
  Vec        gap;                 /* g_i on the normal dofs, layout of is_normal */
  Vec        lower, upper;        /* SNESVI bounds on the full w vector */
  MMBoundQP  qp;                  /* the step problem: K~ w = b, K~ = K + 4/dt^2 M* */
  MMBoundQP  qp0;                 /* the initial projection of the contact dofs */
  Vec        lower0, upper0;
  PetscReal  Kt_dt;               /* dt for which Kt was assembled */
  MMContactFormulation formulation;
  SNES       snes;                /* the VI solver, prefix contact_: on w (full) or on lambda (condensed) */
  KSP        ksp_K;               /* K~ factored once per dt, prefix contact_K_ (condensed) */
  MMCandidates cand;              /* the condensed VI on the candidate set: W rho - q complementary to the box of rho */
  Vec        q;                   /* the condensed right-hand side on all contact nodes: z_c - offset */
  PetscInt   ncomp;               /* condensed dofs per contact node: 1 (normal), or dim with friction */
  IS         is_cond;             /* the condensed dofs, node by node */
  Vec        rho, rho_lo, rho_hi; /* contact reactions (lambda_n, -t) per node and their bounds */
  Vec        offset, z, rhs_c;    /* q = z_c - offset; the step's contact-free solution; E rho */
  Vec        zc_loc;              /* scratch on the condensed dofs */
  Vec        z_b;                 /* the right-hand side z was solved for (not owned), its state and dt */
  PetscObjectState z_b_state;
  PetscReal  z_dt;
  SNES       snes0;               /* quasi-static projection of the contact dofs, prefix contact0_ */
  PetscReal  frame[MM_MAX_DIM][MM_MAX_DIM]; /* the single plane's frame (static sliding); rows: nu, tau_1, tau_2 */
  PetscReal *node_frame;          /* per owned contact node its frame, 9 reals: rows nu, tau_1, tau_2 */
  PetscInt  *obstacle;            /* per owned contact node, the obstacle it is constrained against */
  Vec        gap0;                /* g_i at time 0, layout of gap */
  Vec        mu;                  /* per owned contact node, the friction coefficient of its obstacle */
  PetscReal *slide_ref;           /* per owned contact node and tangent, dt/2 V.tau_j: the obstacle's sliding */
  PetscBool  moving;              /* some obstacle moves: gaps follow it every step */
  PetscReal *force_obstacle;      /* per obstacle, MM_MAX_DIM: the contact force on it (Cartesian), last step */
  PetscReal  h_c;                 /* smallest diameter of cells touching the contact boundary */
  PetscReal  tol;                 /* -contact_tol */
  PetscBool *was_active;          /* per owned contact node, at the previous step */
  PetscBool *slipping;            /* friction: per owned contact node, slipping (on the rim of its disk) */
  PetscReal *slip_dir;            /* 3D friction: per owned contact node, its slip direction in the tangent plane (checkpointed) */
  Vec        mu_c;                /* mu of each contact node in each of its condensed dofs (layout of rho) */
  Vec        Wdiag;               /* diag(W) on the cached nodes, the nodal compliances (1 elsewhere) */
  PetscInt  *scalar_index;        /* per owned contact node, its global index in the scalar vertex DM */
  PetscInt  *vertex;              /* per owned contact node, its mesh point */
  Vec        area;                /* per owned contact node, int_Gc phi_i: force to pressure */
  PetscInt   vi_its;              /* Newton iterations of the last solve */
  MMStepSolver kt;                /* K~ solver without a Delassus operator (-contact 0, active set) */
  MMActiveSet  as;                /* the active-set formulation */
} MMContact;

/* The Newmark state and the per-step energy audit. */
typedef struct {
  Vec       u, v, a;           /* current state, w-frame */
  Vec       u_old, v_old, a_old;
  Vec       react, react_old;  /* contact reactions on the body (K~ w - b on contact dofs) */
  Vec       work;              /* scratch */
  Vec       u_next;            /* the TS solution vector */
  PetscReal dt;
  PetscReal dt_user;           /* -ts_dt: after a rejected step, dt grows back to it */
  PetscReal work_contact;      /* W_c of the accepted step, computed once by the contact-work guard */
} MMState;

/* The Coulomb friction solver: an opaque handle, owned by the friction component (include/friction.h,
 * src/friction/). */
typedef struct _p_MMFriction *MMFriction;

/* One row of the history, and its running sums. */
typedef struct {
  PetscInt  step;
  PetscReal time, dt;
  PetscReal kinetic, elastic, total;
  PetscReal work_ext, work_contact, work_friction; /* running sums */
  PetscReal work_obstacle;     /* running sum: the work of the moving obstacles' contact forces */
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

/* The progress line (progress.c): what it keeps between two lines. The references are taken at the
 * first monitor call, the start of TSSolve, so that the rates are those of this run's time loop. */
typedef struct {
  PetscBool      started;
  PetscLogDouble wall_start, wall_last; /* wall time at the start of the time loop and at the last line */
  PetscReal      t_start;               /* simulated time at the start of the time loop */
  PetscInt       step_start, step_last; /* the step then, and the last step counted */
  PetscInt       friction_its, steps;   /* friction iterations and steps since the last line */
} MMProgress;

/* Output files. Rank 0 alone writes history.csv and solution.xmf; solution.h5 is written by all. */
typedef struct {
  int           csv_fd;                /* history.csv, on rank 0 (-1 elsewhere and once closed) */
  char          csv_name[PETSC_MAX_PATH_LEN], h5_name[PETSC_MAX_PATH_LEN], xmf_name[PETSC_MAX_PATH_LEN];
  PetscViewer   h5;                    /* solution.h5, open from MMOutputOpen to MMOutputClose */
  PetscInt      n_written;             /* snapshots on disk and flushed */
  PetscInt      n_indexed;             /* the ones the XDMF index on disk lists */
  PetscReal    *times;                 /* time of each snapshot */
  PetscInt      nv, nc;                /* global vertex and cell counts, for the XDMF index */
  char         *index;                 /* rank 0: the index's grids, written out at every snapshot */
  size_t        index_len, index_cap;
  PetscLogEvent ev_flush, ev_index, ev_copy; /* HDF5 flush, XDMF rewrite, the checkpoint's copy of solution.h5 */
  DM            dm_out;                /* the displacement field without constraints: output of whole fields */
  Vec           disp_cart, vel_cart;   /* Cartesian output fields on dm_out */
  DM            dm_scalar;             /* one scalar per vertex: pressure, gap */
  Vec           pressure, gap;
  Vec           obstacle;              /* each contact node's obstacle (index in -obstacles), -1 elsewhere: written once */
  Vec           serial;                /* each vertex's number in the serial mesh: written once */
  PetscBool     static_written;        /* obstacle and serial are in solution.h5 */
  Vec           traction_t, slip;      /* tangential traction and slip velocity on the contact boundary (dm_out) */
} MMOutput;

typedef struct {
  PetscLogStage setup, solve, output;
  PetscLogEvent assemble, contact_solve, contact_recover, friction, energy, checkpoint;
  PetscLogEvent restart_output; /* -restart: the history cut and the earlier snapshots copied */
  PetscLogEvent candidate_columns, candidate_operator; /* K~^{-1} E columns of new candidates; the set's dense block */
  PetscLogEvent kt_setup, kt_solve, as_iterate, as_linear; /* K~ PC set-up and solves; active-set iterations and their CG */
} MMLog;

/* Checkpoints (checkpoint.c, docs/method.md section 9): the state keyed by the serial mesh's vertex
 * numbers, so that a run can continue on any number of ranks. */
typedef struct {
  PetscInt *vertex_orig; /* per local vertex (from vStart), its number in the serial mesh */
  PetscInt *vertex_file; /* per serial-mesh vertex, its position among the mesh file's nodes (mesh_file.c) */
  PetscInt  nv_global;   /* vertices of the whole mesh */
  PetscInt  every;       /* -checkpoint_every: steps between checkpoints, 0 only at the end */
  PetscInt  written;     /* checkpoints written by this run */
  PetscInt  last_step;   /* step of the last one written */
  /* -restart */
  PetscBool    restarted;
  PetscInt     restart_step;                   /* the step the run continues from */
  char         file[PETSC_MAX_PATH_LEN];       /* the checkpoint read */
  char         source_dir[PETSC_MAX_PATH_LEN]; /* its directory: the history and snapshots to continue */
  PetscReal    run[32];                        /* its run record */
  PetscScalar *node;                           /* its per-node records of the owned contact nodes */
  PetscReal   *snapshot_times;                 /* the times of its snapshots, until the output takes them */
  int          stop_signal;                    /* the signal that stopped the run (signals.c), 0: none */
} MMCheckpoint;

/* The deformation audit (deformation.c): the largest strain of the run and where it was. */
typedef struct {
  PetscReal     max_strain;                /* over the run: the largest principal strain magnitude */
  PetscReal     where[MM_MAX_DIM];         /* the reference centroid of the cell that had it */
  PetscInt      step;                      /* the step at which it was reached */
  PetscBool     warned;                    /* the -strain_warn warning was printed */
  PetscLogEvent ev;                        /* MMDeformation, in -log_view */
  PetscInt      ncells;                    /* this rank's cells, and for each its dim+1 vertices' */
  PetscInt     *cell_u, *cell_x;           /* offsets in the local displacement and coordinate vectors */
} MMDeformation;

/* Everything the stepper needs; the TS type "newmark" holds a pointer to it. */
typedef struct {
  MMOptions   opt;
  PetscReal   constants[MM_C_NUM];
  MMOperators op;
  MMContact   contact;
  MMFriction  friction;
  MMState     state;
  MMHistory   hist;
  MMProgress  progress;
  MMOutput    out;
  MMCheckpoint ckpt;
  MMDeformation deform;
  MMLog       log;
} MMCtx;
