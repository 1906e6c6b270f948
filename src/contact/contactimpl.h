/* Internals of the contact component, shared by its files (src/contact/) and by no one else. */
#pragma once
#include "contact.h"
#include "sys.h"
#include "frame/frameimpl.h"

/* How each step's contact problem is solved, a contact formulation (impls/<type>/, chosen by
 * -contact_formulation from the registry MMContactRegister): condensed, full, active_set, or none
 * (no contact: one K~ solve per step). */
typedef struct _MMContactOps MMContactOps;

/* Slots of a contact row's checkpoint state (MMContactGetNodeState): a corner's second row
 * (frictionless) keeps its states in slots the friction law leaves free; a friction corner (condensed
 * formulation only) its second obstacle's reactions in the active set's slots */
#define MM_CONTACT_STATE_CORNER_R      9
#define MM_CONTACT_STATE_SECOND_ACTIVE 4
#define MM_CONTACT_STATE_SECOND_RHO    7
#define MM_CONTACT_STATE_SECOND_AS     11

/* A bound-constrained quadratic problem A x = b, x <= upper, as the SNESVI residual context. */
typedef struct {
  Mat       A;
  Vec       b;
  PetscReal bnorm; /* ||b||, the scale of the absolute convergence test */
  PetscReal rtol_b;
  PetscReal Anorm; /* ||A||_inf when > 0: a residual at the round-off of computing it also converges */
} MMBoundQP;

/* K~ and its factor (or PC) for the previous dt (-contact_K_keep); what the formulation built on it
 * (the condensed columns, the active set's diag(K~)) it keeps in its own data. */
typedef struct {
  Mat       A;
  KSP       ksp;
  PetscReal dt;
} MMKtKept;

/* The K~ solver of the paths that build no Delassus operator (-contact 0 and the active-set
 * formulation): a factorization, or CG with an algebraic multigrid PC, prefix contact_K_. Its PC is
 * set up once per dt. */
typedef struct {
  KSP          ksp;
  PetscBool    iterative; /* its PC is not a complete factorization */
  MatNullSpace rigid;     /* rigid-body modes in the w-frame: GAMG's near-null space */
  PetscInt     its;       /* linear iterations since the step began */
} MMStepSolver;

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
  /* large sliding (-contact_pairs_sliding large, docs/method.md section 11): the pairing found again at
   * each step's start on the current configuration */
  PetscBool  large;
  PetscInt  *facet;    /* per contact node, its master facet (index in its pair's gathered surface) */
  PetscReal *xs;       /* per contact node, MM_MAX_DIM: its reference position */
  PetscReal *nuc;      /* per contact node, MM_MAX_DIM: its constraint's direction, -(the current facet normal) */
  PetscBool *far;      /* per contact node: its row is a far one, along its frame's nu (pairs.c TakeRow) */
  PetscReal *far_d;    /* per contact node: a far row's distance at its step's start */
  Mat        Ky, My;   /* K and M* in the contact frame, before N: N^T K N and N^T M* N are rebuilt from them */
  Vec        y;        /* scratch, the layout of w: y = N w */
  Vec        um;       /* every master facet vertex's displacement, gathered on every rank */
  VecScatter to_um;
  PetscInt  *um_off;   /* per pair, its first entry in um */
  PetscInt   repairs;  /* steps whose pairing changed */
  PetscInt   facet_changes; /* slave nodes that moved to another facet, over the run */
  PetscReal  penetration; /* the deepest penetration of the current master surface at a step's start, over the run */
  PetscReal  depth;    /* -contact_pairs_depth (of h_c'): a step ending deeper inside the master is solved again */
  PetscInt   resolves; /* steps solved again with the pairing where they ended (MMContactPairsRefine) */
} MMContactPairs;
/* -contact_pairs_sliding */
typedef enum {
  MM_PAIRS_SLIDING_AUTO,
  MM_PAIRS_SLIDING_SMALL,
  MM_PAIRS_SLIDING_LARGE
} MMPairsSliding;
PETSC_INTERN const char *const MMPairsSlidings[];

/* -contact_frames: a contact node's frame and gap fixed at its reference position, or following its
 * contact point on a curved obstacle (interface/frames.c, docs/method.md section 8) */
typedef enum {
  MM_FRAMES_FIXED,
  MM_FRAMES_FOLLOW
} MMFramesType;
PETSC_INTERN const char *const MMFramesTypes[];

/* Frames that follow the contact point (interface/frames.c): at each step's start, a node near a
 * curved obstacle whose normal at its current position turned by more than -contact_frames_angle
 * gets the frame and the gap of that position; the w-frame operators turn with it by R. */
typedef struct {
  PetscBool  follow;          /* resolved at set-up: -contact_frames follow and some curved rigid obstacle */
  PetscReal  angle;           /* -contact_frames_angle (radians) */
  Mat        M;               /* the full w-frame mass M, turned with the frames: M* is rebuilt from it */
  Mat        R;               /* the last update's rotation, w_old = R w_new (block diagonal, identity off the turned nodes) */
  PetscReal *X;               /* per contact row, MM_MAX_DIM: its reference position */
  PetscReal *F_new;           /* per contact row, 9: the new frame of a node that turns */
  PetscBool *turn;            /* per contact row: its frame turns at this update */
  PetscReal  depth;           /* -contact_frames_depth (of h_c') */
  PetscInt  *refined;         /* per contact row, in this step: 0, 1 its bound was taken where a try ended, 2 then between two (frames.c) */
  PetscReal *prev;            /* per contact row, MM_MAX_DIM + 1: the bound before that, nu and g_0 */
  PetscInt   updates, turned; /* over the run: updates (steps with a turned frame), node frames turned */
  PetscInt   resolves;        /* over this run (not a restart's before it): steps solved again with frames at their end */
  PetscReal  angle_max;       /* the largest turn of one update */
} MMContactFrames;

/* The w-frame data other components keep, registered once (interface/held.c): the addresses of
 * their vectors and matrices, turned or carried by contact when its frames turn or its pairing
 * changes; state counts those changes (MMContactGetFrameState) */
typedef struct {
  PetscInt          nvec, nmat;
  Vec             **vec;
  MMFrameVecType   *type;
  Mat             **mat;
  PetscObjectState  state;
} MMContactHeld;

/* The contact options (MMContactSetFromOptions) */
typedef struct {
  PetscBool         contact;                 /* -contact */
  char              contact_formulation[MM_TYPE_LEN];
  PetscReal         contact_tol;
  PetscInt          iterative_dofs;
  PetscBool         keep_factor;             /* -contact_K_keep */
  PetscReal         candidate_margin, candidate_memory;
  PetscBool         candidate_all;
  PetscInt          active_set_max_it;
  PetscReal         active_set_inexact_rtol, active_set_inexact_coulomb_rtol;
  PetscBool         active_set_block, active_set_monitor;
  PetscReal         audit_penetration_tol, audit_coulomb_tol, initial_penetration_tol;
  PetscReal         friction_coulomb_tol; /* the friction solver's (MMContactSetCoulombTolerance) */
  MMFramesType      frames;                  /* -contact_frames */
  PetscBool         frames_set;              /* given: else follow for the finite-strain laws, fixed for linear */
  PetscReal         frames_angle;            /* -contact_frames_angle */
  PetscReal         frames_depth;            /* -contact_frames_depth */
  PetscReal         pairs_depth;             /* -contact_pairs_depth */
  MMPairsSliding    pairs_sliding;        /* -contact_pairs_sliding */
} MMContactOptions;

/* The contact object: the contact set, gaps, bounds and the step matrix, shared by every formulation;
 * the formulation's own state in data (impls/<type>/<type>impl.h). Friction wraps MMContactSolve. */
struct _p_MMContact {
  MPI_Comm   comm;
  PetscInt   dim;                 /* the mesh's (MMFEGetDimension) */
  MMContactOptions  opt;
  MMContactMass     mass;         /* -mass and what M*'s construction found (frame/mass_star.c) */
  MMContactProblem  pb;           /* the problem's data (MMContactSetUp): obstacles borrowed */
  MMOperators       op;           /* borrowed at set-up: fem's operators (its Cartesian K, M, load and lift; the frame's ops) */
  DM                dm;           /* fem's (MMFEGetDM), borrowed at set-up: the mesh and the layout of every vector */
  const MMMaterial *material;     /* borrowed: E_max, the force scale of the audits */
  MMStepOffset      step;         /* the step's offset and scale, the stepper's (MMContactSetStepOffset) */
  PetscBool  enabled;
  PetscBool  prefer_iterative; /* without contact: CG for K~ (by the cost model, or -iterative_dofs) */
  PetscBool  auto_type;        /* the formulation was chosen by -contact_formulation auto */
  char       auto_why[160];    /* auto's predicted whole runs, for the start-up report */
  PetscInt   n_local, n_global;   /* contact nodes owned here / in total */
  IS         is_normal;           /* global indices of the contact-normal dofs (owned) */
  IS         is_tangent;          /* global indices of the contact-tangential dofs (owned) */
  IS         is_star;             /* every other dof (owned) */
  IS         is_interior;         /* the dofs of the nodes off the contact boundary (owned) */
  Vec        gap;                 /* g_i on the normal dofs, layout of is_normal */
  Vec        lower, upper;        /* SNESVI bounds on the full w vector */
  MMBoundQP  qp;                  /* the step problem: K~ w = b, K~ = K + 4/dt^2 M* */
  Vec        Kt_rowabs;           /* sum_j |K~_ij| per row, the round-off scale of K~ w (step_residual.c) */
  PetscObjectState Kt_rowabs_state; /* K~'s state it was computed at */
  MMBoundQP  qp0;                 /* the initial projection of the contact dofs */
  Vec        lower0, upper0;
  PetscReal  Kt_dt;               /* dt for which Kt was assembled */
  PetscInt   Kt_version;          /* and the version of its stiffness (MMStepMatrix) */
  char       type[MM_TYPE_LEN]; /* the formulation, or "none" without contact */
  const MMContactOps *ops;        /* the formulation's operations */
  void      *data;                /* the formulation's state, freed by ops->destroy */
  MMKtKept   kept;                /* the previous dt's K~ and its KSP (-contact_K_keep) */
  PetscInt   ncomp;               /* condensed dofs per contact node: 1 (normal), or dim with friction */
  IS         is_cond;             /* the condensed dofs, node by node */
  Vec        rho, rho_lo, rho_hi; /* contact reactions (lambda_n, -t) per node and their bounds */
  Vec        z;                   /* the step's contact-free solution (condensed; friction corners read it) */
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
  Vec        gap_step;            /* the gaps at the step's time, kept while the bounds are of an increment (MMContactShiftBounds) */
  Vec        mu;                  /* per owned contact node, the friction coefficient of its obstacle */
  PetscReal *slide_ref;           /* per owned contact node and tangent, dt/2 V.tau_j: the obstacle's sliding */
  PetscBool  moving;              /* some obstacle moves: gaps follow it every step */
  PetscReal *force_obstacle;      /* per obstacle, MM_MAX_DIM: the contact force on it (Cartesian), last step */
  PetscReal  h_c;                 /* smallest diameter of cells touching the contact boundary */
  PetscReal  h_min;               /* without contact: the smallest cell diameter (the linear path's c_p dt / h) */
  PetscReal  penetration_free;    /* last accepted step: the deepest penetration of an obstacle a node has no row for */
  PetscReal  penetration_bound;   /* last accepted step: the deepest crossing of a node's own bound (frames that follow: the audit's) */
  PetscReal  slid[2];             /* last accepted step, fixed frames on a curved obstacle: the farthest held row from the true surface (MMContactFramesSlid), and its obstacle */
  PetscBool  slid_warned;         /* that warning was printed (once a run) */
  PetscReal  tol;                 /* -contact_tol */
  PetscBool *was_active;          /* per owned contact node, at the previous step */
  PetscBool *slipping;            /* friction: per owned contact node, slipping (on the rim of its disk) */
  PetscReal *slip_dir;            /* 3D friction: per owned contact node, its slip direction in the tangent plane (checkpointed) */
  PetscInt  *scalar_index;        /* per owned contact node, its global index in the scalar vertex DM */
  PetscInt  *vertex;              /* per owned contact node, its mesh point */
  PetscReal *all_gap0, *all_nu;   /* several obstacles: per owned contact node and obstacle b, the reference gap
                                     g_b(X) and normal nu_b (3 entries): every node is checked against every obstacle */
  Vec        area;                /* per owned contact node, int_Gc phi_i: force to pressure */
  PetscInt   vi_its;              /* Newton iterations of the last solve */
  MMStepSolver kt;                /* K~ solver without a Delassus operator (-contact 0, active set) */
  MMContactPairs pairs;           /* contact between two bodies of the mesh */
  MMContactFrames frames;         /* -contact_frames follow */
  MMContactHeld   held;           /* the w-frame data other components keep */
  Mat             K;               /* the w-frame stiffness, contact's (fem's stays Cartesian): Q^T K Q then N^T (.) N of fem's */
  Vec             load, lift;      /* the w-frame load and lift, contact's (fem's stay Cartesian): Q^T then N^T of fem's; the loads in time set them (MMLoadsSetUp) */
  MMContactTransform transform;    /* the frame: Q, N and N^{-1}, which fem reads through the ops installed by MMContactFrameInstall */
  Mat             frame_Kp, frame_KpN; /* MMContactFrameMatrixBegin/End with contact pairs: the P1 matrix, its N^T (.) N */
};


/* What -contact_formulation auto's cost model knows of the problem at set-up (interface/cost.c) */
typedef struct {
  PetscInt  dim;
  PetscReal dofs;     /* global, Dirichlet dofs excluded */
  PetscReal cfl;      /* c_p dt / h_c' at the plan's dt */
  PetscReal steps;    /* the plan's */
  PetscBool friction; /* some obstacle has mu > 0 */
  PetscInt  n_fc;     /* friction corners (nodes near two obstacles with friction) */
  PetscReal ranks;    /* the run's MPI ranks */
  PetscBool finite;   /* some body has a finite-strain law: a step is iterations of linear solves */
} MMCostInput;

/* A formulation's predicted times (s); setup PETSC_INFINITY: it cannot carry the problem. direct: its
 * step is a direct solve, exact by construction (the iterative ones are exact by the step's
 * certificate, at a cost that varies with the contact state, which the model does not see): within
 * MM_COST_DIRECT_MARGIN of the cheapest prediction, auto takes it (cost.c) */
typedef struct {
  PetscReal setup, step;
  PetscBool direct;
} MMCost;

/* A fitted model of one formulation in one dimension (docs/scaling.md, "The formulation chosen by
 * cost" and "Refitted with the ranks and the law"):
 *   ln step  = s[0] + s[1] ln dofs + s[2] ln(1 + cfl) + f (s[3] + s[4] ln(1 + cfl))
 *              + g (s[6] + s[7] ln dofs + s[10] ln(1 + cfl))
 *              + ln ranks (s[5] + s[8] ln dofs + s[9] ln(1 + cfl))
 *   ln setup = u[0] + u[1] ln dofs + ln ranks (u[2] + u[3] ln dofs)
 * f = 1 with friction, g = 1 with a finite-strain law; a second rank pays on large meshes and costs
 * on small ones, hence its terms in ln dofs; the active set's CG iterations grow with c_p dt / h_c'
 * faster on more ranks (Jacobi, not ICC(0)) and with a finite-strain law (its iterations), hence
 * theirs in ln(1 + cfl). The constants are written by scripts/cost_model_fit.py --write into
 * impls/cost_constants.h. */
typedef struct {
  PetscReal s[11], u[4];
} MMCostModel;
#define MM_MAX_FORMULATIONS 16 /* registered contact formulations auto compares */
PETSC_INTERN void MMCostEvaluate(const MMCostModel *m, const MMCostInput *in, MMCost *cost);
PETSC_INTERN PetscErrorCode MMContactChooseLinearPath(MMContact ct, PetscInt n_dofs);
PETSC_INTERN PCType MMKtDefaultPC(MPI_Comm comm);

/* A contact formulation's operations (docs/method.md section 3). A NULL entry is a capability the
 * formulation lacks: solvecontactdofs (a friction loop over it), setthresholds (Tresca solves with
 * given thresholds), solvecoulomb (the Delassus operator, for a contact-space Coulomb solver),
 * solvecoulombdofs (the formulation's own Coulomb solve on all dofs, for formulations without it). */
struct _MMContactOps {
  PetscErrorCode (*setfromoptions)(MMContact ct, PetscOptionItems *PetscOptionsObject); /* its own options */
  PetscErrorCode (*setup)(MMContact ct);                        /* its solvers, before the first K~ */
  PetscErrorCode (*setoperator)(MMContact ct);                  /* after K~ is assembled for a new dt */
  PetscErrorCode (*solve)(MMContact ct, Vec b, Vec w, Vec react); /* the step: b in; w (warm start in) and react out */
  PetscErrorCode (*solvecontactdofs)(MMContact ct, Vec b, Vec w, Vec react); /* at least the contact dofs of w and react */
  PetscErrorCode (*recover)(MMContact ct, Vec b, Vec w, Vec react); /* the whole w and react after solvecontactdofs */
  PetscErrorCode (*setthresholds)(MMContact ct, Vec s);         /* Tresca thresholds per contact node */
  PetscErrorCode (*solvecoulomb)(MMContact ct, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok);
  PetscErrorCode (*solvecoulombdofs)(MMContact ct, Vec b, Vec w, Vec react, Vec s, PetscReal rtol, PetscInt *its, PetscBool *ok); /* s: thresholds in and out */
  PetscErrorCode (*getstepksp)(MMContact ct, KSP *krylov, KSP *pc_ksp); /* the K~ solvers, for the start-up report */
  PetscErrorCode (*swapkept)(MMContact ct, PetscReal dt, PetscBool *hit); /* swap K~ and its factor with the kept ones; hit: those are for dt */
  PetscErrorCode (*getnodestate)(MMContact ct, PetscInt k, PetscBool second, PetscScalar state[]); /* row k's warm start, slots 9-12 (second: its slot) */
  PetscErrorCode (*setnodestate)(MMContact ct, PetscInt k, PetscBool second, const PetscScalar state[]);
  PetscErrorCode (*getcandidatecounts)(MMContact ct, PetscInt *n_set, PetscInt *resolves); /* NULL: no candidate set */
  PetscErrorCode (*setcandidateresolves)(MMContact ct, PetscInt resolves);
  PetscErrorCode (*getproducts)(MMContact ct, const char **products); /* how its CG multiplies by K~; NULL: no CG */
  PetscErrorCode (*view)(MMContact ct, PetscViewer viewer);     /* its lines of the closing summary */
  PetscErrorCode (*cost)(MMContact ct, const MMCostInput *in, MMCost *cost); /* its predicted set-up and step; NULL: auto never chooses it */
  PetscErrorCode (*destroy)(MMContact ct);                      /* frees data */
};

/* The component's class and log events (interface/package.c) */
PETSC_INTERN PetscClassId  MMCONTACT_CLASSID;
PETSC_INTERN PetscLogEvent MMCONTACT_Assemble, MMCONTACT_Solve, MMCONTACT_Recover, MMCONTACT_KtReuse, MMCONTACT_KtSetUp, MMCONTACT_KtSolve;
PETSC_INTERN PetscLogEvent MMCONTACT_CandidateColumns, MMCONTACT_CandidateOperator, MMCONTACT_ColumnsSolve, MMCONTACT_ColumnsMove;
PETSC_INTERN PetscLogEvent MMCONTACT_SplitInterface, MMCONTACT_SplitBackward, MMCONTACT_ActiveSetIterate, MMCONTACT_ActiveSetCG, MMCONTACT_BlockOperator;
PETSC_INTERN PetscLogEvent MMCONTACT_FrameSetUp, MMCONTACT_FrameRotate, MMCONTACT_MassRedistribute, MMCONTACT_FrameFollow, MMCONTACT_PairsSlide, MMCONTACT_MassFree;

/* The formulation of -contact_formulation (auto resolved by the cost model), or "none" (contact.c) */
PETSC_INTERN PetscErrorCode MMContactSetType(MMContact ct);
/* -contact_formulation auto: the registered formulation with the cheapest predicted run (cost.c) */
PETSC_INTERN PetscErrorCode MMContactChooseFormulation(MMContact ct, PetscInt n_dofs);
PETSC_INTERN PetscErrorCode MMContactPairsResolveSliding(MMContact ct);
/* The registry: each formulation's create function sets ct->ops. */
PETSC_INTERN PetscErrorCode MMContactCreate_Condensed(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactCreate_Full(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactCreate_ActiveSet(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactCreate_None(MMContact ct);
/* K~, its KSP and dt swapped with the kept ones (contact.c) */
PETSC_INTERN PetscErrorCode MMContactSwapKeptOperator(MMContact ct, KSP *ksp);
/* react = K~ w - b on the contact dofs (contact.c) */
PETSC_INTERN PetscErrorCode MMContactForce(MMContact ct, Vec b, Vec w, Vec react);

/* interface/set.c: the frame (nu, tau_1[, tau_2]) of an obstacle normal n, nu = -n */
PETSC_INTERN void MMContactFrameFromNormal(PetscInt dim, const PetscReal n[], PetscReal F[MM_MAX_DIM][MM_MAX_DIM]);
/* interface/held.c: the w-frame data other components keep, turned (x <- fn(x)) by one function */
typedef PetscErrorCode (*MMContactHeldFn)(MMContact ct, void *fctx, PetscBool force, Vec x);
PETSC_INTERN PetscErrorCode MMContactHeldTransform(MMContact ct, PetscBool state, MMContactHeldFn fn, void *fctx);
PETSC_INTERN PetscErrorCode MMContactHeldTurnMatrices(MMContact ct, Mat R);
PETSC_INTERN PetscErrorCode MMContactHeldInvalidate(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactHeldDestroy(MMContactHeld *h);
/* interface/frames.c: frames that follow the contact point (docs/method.md section 8) */
PETSC_INTERN PetscErrorCode MMContactFramesSetUp(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactFramesPenetration(MMContact ct, PetscInt k, PetscReal t, const PetscScalar w[], PetscReal *own, PetscReal *others);
PETSC_INTERN PetscErrorCode MMContactFramesView(MMContact ct, PetscViewer viewer);
PETSC_INTERN PetscErrorCode MMContactFramesDestroy(MMContactFrames *fr);

/* interface/corners.c: friction corners, a second obstacle's Coulomb law on a node's dofs */
PETSC_INTERN void           MMContactCornerT2(PetscInt dim, const PetscReal ab[2], PetscReal T[MM_MAX_DIM][MM_MAX_DIM]);
PETSC_INTERN void           MMContactCornerFrame2(PetscInt dim, const PetscReal F1[], const PetscReal ab[2], PetscReal F2[MM_MAX_DIM][MM_MAX_DIM]);
PETSC_INTERN void           MMContactCornerSplit(MMContact ct, PetscInt dim, PetscInt k, const PetscScalar rho[], PetscReal r1[], PetscReal r2[]);
PETSC_INTERN PetscBool      MMContactCornerCrosses(MMContact ct, PetscInt dim, PetscInt k, const PetscScalar wc[], PetscReal tol);
PETSC_INTERN PetscErrorCode MMContactCornersSetUpVecs(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactCornersRHS(MMContact ct, const PetscInt row[]);
PETSC_INTERN PetscErrorCode MMContactCornersExpand(PetscInt n, PetscInt nc, const PetscScalar W[], const PetscScalar q[], const PetscReal mu[], const PetscScalar x[], const PetscScalar geom[], const PetscScalar mu2[], const PetscScalar q2[], const PetscScalar x2[], PetscInt *ne, PetscInt **of, PetscScalar **We, PetscScalar **qe, PetscReal **mue, PetscScalar **xe);
PETSC_INTERN PetscErrorCode MMContactCornersContract(PetscInt n, PetscInt nc, PetscInt ne, const PetscInt of[], const PetscScalar geom[], const PetscScalar xe[], PetscScalar x[], PetscScalar x2[]);
PETSC_INTERN PetscErrorCode MMContactCornersStore(MMContact ct);

/* interface/pairs.c and pairs_sliding.c: contact pairs between two bodies, node to segment or facet */
PETSC_INTERN PetscErrorCode MMContactPairsSetUp(MMContact ct, const PetscInt mark[], PetscInt n_vertex_bound);
PETSC_INTERN PetscErrorCode MMContactPairsProject(MMContact ct, PetscInt p, PetscInt k, const PetscReal x[], PetscReal *gap, PetscReal n[]);
PETSC_INTERN PetscErrorCode MMContactPairsBuildTransform(MMContact ct);
/* One facet of a master surface, as gathered on every rank (pairs.c) */
#define MM_FACET_REALS 16 /* coordinates (dim x dim), outward normal (dim), centroid key (dim) */
PETSC_INTERN void           MMContactPairsFacetCross(PetscInt dim, const PetscReal x[], PetscReal n[]);
PETSC_INTERN PetscErrorCode MMContactPairsFacetNormal(DM dm, PetscInt dim, PetscInt cell, const PetscReal x[], PetscReal n[], PetscReal *length);
PETSC_INTERN PetscInt       MMContactPairsClosestFacet(PetscInt dim, PetscInt nf, const PetscReal xf_all[], const PetscReal x[], PetscReal phib[]);
PETSC_INTERN void           MMContactPairsSetPairing(MMContactPairs *pr, PetscInt dim, PetscInt p, PetscInt k, PetscInt fb, const PetscReal phib[]);
PETSC_INTERN PetscErrorCode MMContactPairsBuildN(MMContact ct);
PETSC_INTERN PetscErrorCode MMContactPairsTransformOperators(MMContact ct, MMOperators op);
PETSC_INTERN PetscErrorCode MMContactPairsDestroy(MMContactPairs *pr);
/* The direction of row k's normal reaction: its frame's nu, or under large sliding its facet's current one */
static inline const PetscReal *MMContactRowNormal(MMContact ct, PetscInt k)
{
  return ct->pairs.large && ct->obstacle[k] >= ct->pb.n_rigid && !ct->second[k] ? &ct->pairs.nuc[MM_MAX_DIM * k] : &ct->node_frame[9 * k];
}

/* interface/qp.c: bound-constrained QPs as SNESVI solves; exact linear solves */
PETSC_EXTERN PetscErrorCode MMKSPCheckDirect(KSP ksp);
PETSC_EXTERN PetscErrorCode MMQPCreate(MPI_Comm comm, const char prefix[], MMBoundQP *qp, PetscReal mu, SNES *snes);
PETSC_EXTERN PetscErrorCode MMQPSetFactorSPD(SNES snes);
PETSC_EXTERN PetscErrorCode MMQPSetOperator(SNES snes, MMBoundQP *qp);
PETSC_EXTERN PetscErrorCode MMQPSolve(SNES snes, MMBoundQP *qp, Vec x, PetscInt *its);
PETSC_EXTERN PetscErrorCode MMKSPSetFactorSPD(KSP ksp, PetscInt dim);
PETSC_EXTERN PetscErrorCode MMPCRegisterSchurSplit(void);

/* interface/kt.c: K~ without a Delassus operator, by a factorization or preconditioned CG */
PETSC_EXTERN PetscErrorCode MMKtCreate(MMContact ct, PetscBool iterative, PCType pc_default);
PETSC_EXTERN PetscErrorCode MMKtSetOperator(MMContact ct, Mat Kt);
PETSC_EXTERN PetscErrorCode MMKtSolveToTolerance(KSP ksp, PetscReal tol, Vec b, Vec rhs, Vec x, PetscReal *atol_used);
PETSC_EXTERN PetscErrorCode MMKtSolve(MMContact ct, Vec b, Vec w);
PETSC_EXTERN PetscErrorCode MMKtDestroy(MMStepSolver *kt);
PETSC_EXTERN PetscErrorCode MMKtGetLocalBlocks(Mat K, const char who[], Mat *Ad, Mat *Ao, const PetscInt **colmap);

/* interface/contact.c: the reactions rho and their bounds, one block of ncomp per contact node */
PETSC_EXTERN PetscErrorCode MMContactCreateReactions(MMContact ct);
