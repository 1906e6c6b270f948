/* The contact component's context (src/contact/): the contact set and the formulations' state. */
#pragma once
#include "mmbase.h"

/* How each step's contact problem is solved, a contact formulation (src/contact/impls/<type>/,
 * chosen by -contact_formulation from the registry MMContactRegister): condensed (SNESVI on the
 * contact dofs through the Delassus operator, K~ factored once per dt), full (SNESVI on all dofs)
 * or active_set (a primal-dual active-set method with CG on all dofs). Its ops table is private to
 * the contact component (src/contact/contactimpl.h). */
typedef struct _MMContactOps MMContactOps;

/* A bound-constrained quadratic problem A x = b, x <= upper, as the SNESVI residual context. */
typedef struct {
  Mat       A;
  Vec       b;
  PetscReal bnorm; /* ||b||, the scale of the absolute convergence test */
  PetscReal rtol_b;
} MMBoundQP;

/* The cached columns of K~^{-1} E of one factor of K~, which a kept factor keeps with it. */
typedef struct {
  PetscScalar *cols, *full;  /* on the owned condensed dofs; on all owned dofs (MMCandidates) */
  PetscInt    *slot_node;    /* per cached block: its contact node */
  PetscInt     n_cached, cap;
  PetscBool    full_ok;
} MMColumnCache;

/* The map from the solution rows of a MUMPS factor of K~ on several ranks to PETSc's rows, for the
 * candidate columns (src/contact/impls/condensed/mumps_columns.c): MUMPS keeps the same rows on each
 * rank for every solve with one factorization, so the map is built once per factorization. */
typedef struct {
  Mat          F;               /* the factor whose solution rows sf maps */
  PetscSF      sf;              /* MUMPS's solution rows here (leaves) -> PETSc's owned rows (roots) */
  int         *isol, *isol_map; /* MUMPS_INT, from 1: the rows of the last solve here; those sf maps */
  PetscScalar *sol;             /* the last solve's block on those rows, lsol x nb_cap */
  PetscInt     lsol, nb_cap;
} MMMumpsColumns;

/* K~ and its factor (or PC) for the previous dt, with what the formulation built on it
 * (-contact_K_keep): the condensed formulation's columns, the active-set formulation's diag(K~). */
typedef struct {
  Mat           A;
  KSP           ksp;
  PetscReal     dt;
  MMColumnCache cache;
  Vec           diag;
} MMKtKept;

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
  MMMumpsColumns mumps;             /* the columns' solves on a MUMPS factor on several ranks */
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

/* The active-set contact solver (src/contact/impls/active_set/): per owned contact node its normal state and,
 * with friction, its stick/slip state and slip direction; the projected CG on the free dofs. */
typedef struct {
  KSP        ksp;       /* prefix contact_as_: CG on the free dofs, PC the projected contact_K_ PC */
  Mat        A;         /* shell operator P_F K~ P_F + P_D */
  Vec        free;      /* 1 on the dofs free in this iteration, 0 on the fixed ones (D) */
  Vec        x0, r, dx, t; /* the iterate with its fixed values, residuals, correction, scratch */
  Mat        Kc;        /* K~'s contact rows (is_cond), for the reactions: built from Kc_of at state Kc_state */
  Mat        Kc_of;
  PetscObjectState Kc_state;
  Vec        rc;        /* b - K~ w on the contact dofs */
  Vec        s;         /* Tresca thresholds per contact node (0 without friction) */
  Vec        ct_diag;   /* diag(K~): the scale c of the complementarity functions, per dof */
  PetscBool  block;     /* the CG's products with K~ through Kb, its block (BAIJ) copy */
  Mat        Kb, Kb_of; /* that copy, made from Kb_of at state Kb_state (block_operator.c) */
  PetscObjectState Kb_state;
  PetscBool *active;    /* normal: w_n = g (else rho_n = 0) */
  PetscBool *stick;     /* tangential: w_t = off_t (else rho_t = s d) */
  PetscReal *dir;       /* slip direction d per node, dim-1 components in the tangent frame */
  PetscReal *kappa, *beta, *rperp; /* 3D slip: Newton tangent of the disk across d (a spring kappa on
                                    * w.d_perp), and the reaction across d it corrects (beta rperp) */
  PetscInt   max_it, its, lin_its;
  PetscReal  inexact_rtol; /* CG's relative tolerance while nodes change set (0: always tight) */
  PetscBool  monitor;
  PetscBool  coulomb;   /* the thresholds follow the iterate, s = mu rho_n (a Coulomb solve) */
  PetscReal  coulomb_rtol; /* its test: the thresholds' change over the force scale */
} MMActiveSet;

/* The contact pairs between surfaces of the mesh (src/contact/interface/pairs.c): each pair's master
 * surface gathered on every rank, and per owned contact node the master vertices' first global dofs
 * (-1: held or absent) and weights of its constraint. */
typedef struct {
  PetscInt   n;        /* pairs */
  PetscInt  *nf;       /* per pair: master facets */
  PetscReal **xf;      /* per pair and facet: vertex coordinates, outward normal, centroid */
  PetscInt  **df;      /* per pair and facet: each vertex's first global dof, -1 if held */
  PetscReal *phi;      /* per contact node, MM_MAX_DIM: weights phi_j of its master vertices */
  PetscInt  *mdof;     /* per contact node, MM_MAX_DIM: their first global dofs */
  PetscInt  *count;    /* per pair, 2: its slave nodes, and those facing a master node (node to node) */
} MMContactPairs;

/* Contact set, gaps, bounds and the per-step contact solver. Friction wraps ContactSolve. */
typedef struct {
  PetscBool  enabled;
  PetscBool  prefer_iterative; /* 3D with at least -iterative_dofs dofs: active_set and CG for K~ by default */
  PetscBool  auto_type;        /* the formulation was chosen by -contact_formulation auto */
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
  char       type[MM_TYPE_LEN]; /* the formulation, or "none" without contact */
  const MMContactOps *ops;        /* the formulation's operations (contactimpl.h) */
  SNES       snes;                /* the VI solver, prefix contact_: on w (full) or on lambda (condensed) */
  KSP        ksp_K;               /* K~ factored once per dt, prefix contact_K_ (condensed) */
  MMCandidates cand;
  MMKtKept     kept;              /* the previous dt's K~, factor and columns (condensed, -contact_K_keep) */              /* the condensed VI on the candidate set: W rho - q complementary to the box of rho */
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
  PetscBool *second;              /* per row: a corner node's second row, on its dof 1 (the row before is its first) */
  PetscReal *corner_ab;           /* per row, 2: a second row's nu_2 = a nu_1 + b tau_1 in its node's frame */
  PetscInt   n_corners;           /* second rows over all ranks */
  /* Friction corners (docs/method.md section 12): with friction, a node within h_c' of a second
   * obstacle keeps one row, its tau_1 in the plane of both normals, and carries the second
   * obstacle's own Coulomb law on the same dofs; NULL without friction. Per row: */
  PetscInt  *fc_obstacle;         /* the second obstacle, or -1 */
  PetscReal *fc_ab;               /* 2: nu_2 = a nu_1 + b tau_1 (b > 0) */
  PetscReal *fc_gap0, *fc_gap;    /* g_2 at the reference position, and at the step's time */
  PetscReal *fc_slide;            /* dim - 1: dt/2 V_2.tau'_j, the second obstacle's sliding */
  PetscReal *fc_r, *fc_r_old;     /* dim: the second obstacle's reactions (normal, tangents of its frame), the
                                     last solve's and the last accepted step's */
  PetscInt   n_fc;                /* friction corners over all ranks */
  Vec        fc_geom, fc_mu, fc_q, fc_x; /* layout of rho, for the candidate set's gathers: (b, a), mu_2, the second
                                     row's q and reactions (zero off the friction corners) */
  IS         is_massless;         /* the dofs M* drops: the normal dofs and the friction corners' tau_1 */
  Vec        gap0;                /* g_i at time 0, layout of gap */
  Vec        mu;                  /* per owned contact node, the friction coefficient of its obstacle */
  PetscReal *slide_ref;           /* per owned contact node and tangent, dt/2 V.tau_j: the obstacle's sliding */
  PetscBool  moving;              /* some obstacle moves: gaps follow it every step */
  PetscReal *force_obstacle;      /* per obstacle, MM_MAX_DIM: the contact force on it (Cartesian), last step */
  PetscReal  h_c;                 /* smallest diameter of cells touching the contact boundary */
  PetscReal  penetration_free;    /* last accepted step: the deepest penetration of an obstacle a node has no row for */
  PetscReal  tol;                 /* -contact_tol */
  PetscBool *was_active;          /* per owned contact node, at the previous step */
  PetscBool *slipping;            /* friction: per owned contact node, slipping (on the rim of its disk) */
  PetscReal *slip_dir;            /* 3D friction: per owned contact node, its slip direction in the tangent plane (checkpointed) */
  Vec        mu_c;                /* mu of each contact node in each of its condensed dofs (layout of rho) */
  Vec        Wdiag;               /* diag(W) on the cached nodes, the nodal compliances (1 elsewhere) */
  PetscInt  *scalar_index;        /* per owned contact node, its global index in the scalar vertex DM */
  PetscInt  *vertex;              /* per owned contact node, its mesh point */
  PetscReal *all_gap0, *all_nu;   /* several obstacles: per owned contact node and obstacle b, the reference gap
                                     g_b(X) and normal nu_b (3 entries): every node is checked against every obstacle */
  Vec        area;                /* per owned contact node, int_Gc phi_i: force to pressure */
  PetscInt   vi_its;              /* Newton iterations of the last solve */
  MMStepSolver kt;                /* K~ solver without a Delassus operator (-contact 0, active set) */
  MMActiveSet  as;                /* the active-set formulation */
  MMContactPairs pairs;           /* contact between two bodies of the mesh */
} MMContact;
