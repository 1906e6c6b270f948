/* The contact component (src/contact/): the contact object MMContact, its life cycle, the step's
 * contact solve in the chosen formulation, and what the other components read of the contact set. */
#pragma once
#include "fem.h"
#include "obstacle.h"

/* The contact object: the contact set, gaps and the chosen formulation's state; its struct is
 * private (src/contact/contactimpl.h) */
typedef struct _p_MMContact *MMContact;

/* Life cycle */
PETSC_EXTERN PetscErrorCode MMContactInitializePackage(void);
PETSC_EXTERN PetscErrorCode MMContactCreate(MPI_Comm comm, MMContact *ct);
PETSC_EXTERN PetscErrorCode MMContactSetFromOptions(MMContact ct);
PETSC_EXTERN PetscErrorCode MMContactSetCoulombTolerance(MMContact ct, PetscReal tol);
PETSC_EXTERN PetscErrorCode MMContactGetTolerance(MMContact ct, PetscReal *tol);
PETSC_EXTERN PetscErrorCode MMContactStepIsIterative(MMContact ct, PetscBool *iterative);
/* What contact reads of the problem, given at set-up (src/app fills it from the options): the
 * obstacles (rigid ones first, then the contact pairs), the contact boundary's physical name, the
 * material's values its messages name, the single plane (-obstacle_point, -obstacle_normal) */
typedef struct {
  const MMObstacle *obstacles;
  PetscInt          n_obstacles, n_rigid;
  PetscReal         mu_max;           /* the largest friction coefficient: 0 frictionless */
  PetscReal         E, rho;
  const char       *contact_name;     /* -contact_boundary */
  PetscBool         contact_name_given; /* -contact_boundary was given (else contact_name is its default) */
  PetscBool         static_sliding;   /* -initial_state static_sliding: one fixed plane */
  PetscBool         quiet;
  PetscReal         obstacle_point[MM_MAX_DIM], obstacle_normal[MM_MAX_DIM];
  PetscReal         dt, steps;        /* the run's plan (-ts_dt, its steps): -contact_formulation auto's cost model */
} MMContactProblem;
/* Finds the contact nodes and builds Q, before fem assembles the operators; op and material are
 * borrowed (kept until destroy) */
PETSC_EXTERN PetscErrorCode MMContactSetUp(MMContact ct, MMOperators op, const MMMaterial *material, const MMContactProblem *pb);
/* The plane of the static sliding state (-initial_state static_sliding: the single obstacle's) */
PETSC_EXTERN PetscErrorCode MMContactGetPlane(MMContact ct, PetscReal point[], PetscReal normal[]);
PETSC_EXTERN PetscErrorCode MMContactView(MMContact ct, PetscViewer viewer);
/* -contact_view: the configuration once set up (src/contact/interface/view.c) */
PETSC_EXTERN PetscErrorCode MMContactSetUpView(MMContact ct, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMContactDestroy(MMContact *ct);
PETSC_EXTERN PetscErrorCode MMContactRegister(const char name[], PetscErrorCode (*create)(MMContact ct));
PETSC_EXTERN PetscErrorCode MMContactRegisterAll(void);
/* The contact frame (src/contact/frame/, docs/method.md section 2): contact's own w-frame K, load and
 * lift from fem's Cartesian ones (which stay Cartesian), and fem's M turned in place in op, which
 * must be the operators given to MMContactSetUp: Q^T A Q, M* for -mass, and the contact pairs'
 * N^T A N. */
PETSC_EXTERN PetscErrorCode MMContactSetUpFrame(MMContact ct, MMOperators op, const MMMaterial *material);
/* The w-frame operators (src/contact/frame/operators.c), contact's, as they are now: borrowed, and
 * rebuilt when the frames turn or the pairing changes, so ask for them when they are used rather
 * than keep them. K, Mstar: the stiffness and the mass in time stepping; load, lift: L and K_fD u_D
 * on the free dofs; mass_star, mass_star_inv: M*'s mass for rigid translations and its inverse
 * (dim x dim, zero without mass); massless: M*'s dofs without inertia, NULL if none. */
typedef struct {
  Mat              K, Mstar;
  Vec              load, lift;
  const PetscReal *mass_star, *mass_star_inv;
  IS               massless;
} MMContactOperators;
PETSC_EXTERN PetscErrorCode MMContactGetOperators(MMContact ct, MMContactOperators *ops);
/* The elastic energy of the w-frame state w, 1/2 w.K w + w.lift + the Dirichlet data's own
 * (src/contact/frame/energy.c); the start-up audit of it against fem's quadrature (stops the run when
 * they differ beyond round-off) */
PETSC_EXTERN PetscErrorCode MMContactElasticEnergy(MMContact ct, Vec w, PetscReal *energy);
PETSC_EXTERN PetscErrorCode MMContactCheckElasticEnergy(MMContact ct, const MMMaterial *mat, Vec w);
/* Whether M* has dofs without inertia (the contact normals under the modified mass) */
PETSC_EXTERN PetscBool MMContactHasMasslessDofs(MMContact ct);
/* A Cartesian P1 stiffness the caller assembles (the finite-strain tangent) into the w-frame as K is:
 * Begin gives the matrix Kc to assemble into (Kw itself, K's pattern, without contact pairs), End
 * turns it into Kw */
PETSC_EXTERN PetscErrorCode MMContactFrameMatrixBegin(MMContact ct, Mat Kw, Mat *Kc);
PETSC_EXTERN PetscErrorCode MMContactFrameMatrixEnd(MMContact ct, Mat Kc, Mat Kw);
/* The Rayleigh damping stiffness B of the linear law in the w-frame, its massless dofs is_massless
 * condensed cell by cell (docs/method.md section 12); B is new */
PETSC_EXTERN PetscErrorCode MMContactDampingStiffness(MMContact ct, const MMMaterial *material, IS is_massless, Mat *B);
/* The mass in time stepping (-mass, src/contact/frame/mass_star.c): the modified mass drops the
 * contact nodes' normal mass, the redistributed one gives it back to the other nodes. */
typedef enum {
  MM_MASS_MODIFIED,
  MM_MASS_STANDARD,
  MM_MASS_REDISTRIBUTED /* modified, its removed mass given to the other nodes (docs/method.md section 2) */
} MMMassType;
PETSC_EXTERN const char *const MMMassTypes[];
PETSC_EXTERN PetscErrorCode MMContactGetMassType(MMContact ct, MMMassType *type);
/* The mass's line of the reports: M's total, M*'s along each axis, and how well -mass redistributed
 * kept M's moments */
PETSC_EXTERN PetscErrorCode MMContactMassView(MMContact ct, PetscViewer viewer);

/* What the other components read of the contact set, as it is when asked (MMContactGetNodes): its
 * dofs, per owned contact row its frame, obstacle and mesh point; arrays and objects are the
 * contact object's, valid until it is destroyed. */
typedef struct {
  PetscBool        enabled;    /* -contact */
  PetscBool        moving;     /* some obstacle moves: gaps follow it every step */
  PetscInt         dim;        /* the mesh's */
  PetscInt         n_local, n_global; /* contact rows owned here / in total */
  PetscInt         ncomp;      /* reaction components per row: 1 (normal), or dim with friction */
  PetscInt         n_corners, n_fc; /* second rows; friction corners (over all ranks) */
  PetscReal        h_c;        /* h_c': the smallest diameter of the cells touching the contact boundary */
  PetscReal        h_min;      /* without contact: the smallest cell diameter; 0 with contact */
  PetscReal        dt;         /* the dt of the step matrix K~ */
  IS               is_normal, is_tangent, is_star, is_interior, is_massless; /* owned global dofs */
  Vec              gap;        /* g_i on the normal dofs, layout of is_normal */
  Vec              mu;         /* per row, the friction coefficient of its obstacle (layout of gap) */
  PetscReal        frame[MM_MAX_DIM][MM_MAX_DIM]; /* the single plane's frame (static sliding): rows nu, tau_1, tau_2 */
  const PetscReal *node_frame; /* per row its frame, 9 reals: rows nu, tau_1, tau_2 */
  const PetscInt  *obstacle;   /* per row, the obstacle it is constrained against */
  const PetscInt  *vertex;     /* per row, its mesh point */
  const PetscInt  *scalar_index; /* per row, its global index in the scalar vertex DM */
  const PetscBool *second;     /* per row: a corner node's second row (the row before is its first) */
  const PetscInt  *fc_obstacle; /* per row: a friction corner's second obstacle, or -1; NULL without friction */
  PetscBool        pairs_sliding; /* contact pairs with large sliding: a reaction may act on master dofs after a new pairing */
} MMContactNodes;
PETSC_EXTERN PetscErrorCode MMContactGetNodes(MMContact ct, MMContactNodes *nodes);
/* The step problem's right-hand side b, a vector of the contact object that the stepper fills */
PETSC_EXTERN PetscErrorCode MMContactGetRHS(MMContact ct, Vec *b);
/* The contact force on obstacle b at the last step (Cartesian, MM_MAX_DIM components) */
PETSC_EXTERN PetscErrorCode MMContactGetObstacleForce(MMContact ct, PetscInt b, PetscReal force[]);
/* For the start-up report: the formulation, why it was chosen ("" or " (auto...)"), how the CG
 * multiplies by K~ ("" without CG); pair p's slave nodes, those facing a master node and its facets */
PETSC_EXTERN PetscErrorCode MMContactGetSolverText(MMContact ct, const char **type, const char **choice, const char **products);
PETSC_EXTERN PetscErrorCode MMContactGetPairCounts(MMContact ct, PetscInt p, PetscInt *slave_nodes, PetscInt *node_to_node, PetscInt *master_facets);
/* Contact pairs with large sliding (-contact_pairs_sliding, docs/method.md section 11): at a step's start,
 * u = u^n, the pairing found again on the configuration of up (the step's predictor); when it changed, N,
 * K and M* are rebuilt, K~ with them at the next MMContactSetStepMatrix, and the w-frame vectors (contact's
 * and the held ones, MMContactFramesAddVec) carried to the new variables. changed: it did (the holder
 * drops what it built on N: the held matrices are not carried). */
PETSC_EXTERN PetscErrorCode MMContactSlidePairs(MMContact ct, Vec u, Vec up, PetscBool *changed);
PETSC_EXTERN PetscErrorCode MMContactPairsRefine(MMContact ct, Vec w, PetscBool *changed);
/* A checkpoint of large sliding (docs/method.md section 9): per owned contact row its pairing, MM_CONTACT_PAIR_RECORD
 * reals (the facet's reference centroid, the weights, the row's direction, the gap; *has: the row is a sliding
 * pair's), restored by -restart with N, K and M* rebuilt (*changed); the run's counters of new pairings */
#define MM_CONTACT_PAIR_RECORD (3 * MM_MAX_DIM + 1)
PETSC_EXTERN PetscErrorCode MMContactPairsGetRecord(MMContact ct, PetscInt k, PetscBool *has, PetscScalar rec[]);
PETSC_EXTERN PetscErrorCode MMContactPairsRestore(MMContact ct, const PetscScalar rec[], PetscBool *changed);
PETSC_EXTERN PetscErrorCode MMContactPairsGetCounters(MMContact ct, PetscReal c[3]);
PETSC_EXTERN PetscErrorCode MMContactPairsSetCounters(MMContact ct, const PetscReal c[3]);
/* The candidate set's size at the last step and its re-solves over the run (0 without one) */
PETSC_EXTERN PetscErrorCode MMContactGetCandidateCounts(MMContact ct, PetscInt *n_set, PetscInt *resolves);
PETSC_EXTERN PetscErrorCode MMContactSetCandidateResolves(MMContact ct, PetscInt resolves);

/* A contact row's state in a checkpoint (src/io/checkpoint.c): MM_CONTACT_NODE_STATE reals per mesh
 * vertex, 0: 1 (a contact node), 1: the friction threshold (the friction solver's), 2: slipping,
 * 3: last active, 4-5: slip direction, 6-8: reactions, 9-12: the formulation's warm start (the
 * active set's states, a friction corner's second reactions). A corner node's second row keeps its
 * states in slots its first row leaves free: owned[c] says which slots row k writes. */
#define MM_CONTACT_NODE_STATE 13
PETSC_EXTERN PetscErrorCode MMContactGetNodeState(MMContact ct, PetscInt k, PetscInt *vertex, PetscScalar state[], PetscBool owned[]);
PETSC_EXTERN PetscErrorCode MMContactSetNodeState(MMContact ct, PetscInt k, const PetscScalar state[], PetscBool *second);

/* The step */
PETSC_EXTERN PetscErrorCode MMContactSetTime(MMContact ct, PetscReal t, PetscReal dt);
/* The w-frame data other components keep (src/contact/interface/held.c, docs/developer.md "The
 * contact frame"): registered once by their addresses (the holder may replace the object behind
 * one; a NULL one is skipped), and turned or carried by contact, with its own, whenever its frames turn
 * or its pairing changes. The type says how a vector transforms and whether a checkpoint holds it:
 * the state's displacements (u, v, a) and forces (the reaction) are read from a restart's checkpoint
 * in its frames; a set-up force (a load part) is not. A held matrix (A <- R^T A R) turns with the
 * frames; a new pairing leaves it to its holder. The frame state counts the turns and new pairings:
 * what a holder builds on the frame instead (the momentum functionals) is stale when it changed. */
typedef enum {
  MM_FRAME_KINEMATIC,  /* a displacement or velocity of the state */
  MM_FRAME_FORCE,      /* a force of the state */
  MM_FRAME_SETUP_FORCE /* a force built at set-up, not in a checkpoint of frames */
} MMFrameVecType;
PETSC_EXTERN PetscErrorCode MMContactFramesAddVec(MMContact ct, MMFrameVecType type, Vec *x);
PETSC_EXTERN PetscErrorCode MMContactFramesAddMat(MMContact ct, Mat *A);
PETSC_EXTERN PetscErrorCode MMContactGetFrameState(MMContact ct, PetscObjectState *state);
/* -contact_frames follow (src/contact/interface/frames.c, docs/method.md section 8): at a step's
 * start, the frames of the nodes near a curved obstacle follow their position u + dt/2 v (w-frame)
 * at the step's predicted midpoint, t + dt/2; *turned: how many turned (all ranks). The w-frame K, M*, Q, loads and gaps are contact's
 * and turn with them, as do the held vectors and matrices (x <- R^T x, A <- R^T A R). */
PETSC_EXTERN PetscErrorCode MMContactFramesFollow(MMContact ct, PetscBool *follow);
/* the mass in free flight (src/contact/frame/mass_free.c) */
PETSC_EXTERN PetscErrorCode MMContactMassFreeFlight(MMContact ct, PetscBool *on, PetscBool *is_free);
PETSC_EXTERN PetscErrorCode MMContactMassSetFree(MMContact ct, PetscBool is_free);
PETSC_EXTERN PetscErrorCode MMContactMassReach(MMContact ct, Vec w, PetscReal t, PetscReal *slack, PetscReal *h_c);
PETSC_EXTERN PetscErrorCode MMContactMassFreeGetSwitches(MMContact ct, PetscInt switches[2]);
PETSC_EXTERN PetscErrorCode MMContactMassFreeRestore(MMContact ct, PetscBool is_free, const PetscInt switches[2]);
PETSC_EXTERN PetscErrorCode MMContactFramesUpdate(MMContact ct, Vec u, Vec midpoint, PetscReal t_mid, PetscInt *turned);
PETSC_EXTERN PetscErrorCode MMContactFramesRefine(MMContact ct, Vec w, PetscReal t, PetscInt *turned);
PETSC_EXTERN PetscErrorCode MMContactFramesSlid(MMContact ct, PetscInt k, PetscReal t, const PetscScalar w[], PetscReal *g);
/* Checkpoints of a run whose frames follow (frames.c): per following row its normal nu (MM_MAX_DIM)
 * and gap g_0, MM_CONTACT_FRAME_RECORD reals (*has: the row follows); the run's counters (updates,
 * frames turned, the largest turn); at -restart each row's frame and gap from its record, contact's
 * operators and the held set-up vectors and matrices turned with them (*turned: how many, all ranks),
 * not the state, read in these frames */
#define MM_CONTACT_FRAME_RECORD (MM_MAX_DIM + 1)
PETSC_EXTERN PetscErrorCode MMContactFramesGetRecord(MMContact ct, PetscInt k, PetscBool *has, PetscScalar rec[]);
PETSC_EXTERN PetscErrorCode MMContactFramesGetCounters(MMContact ct, PetscReal counters[3]);
PETSC_EXTERN PetscErrorCode MMContactFramesRestore(MMContact ct, const PetscScalar rec[], const PetscReal counters[3], PetscInt *turned);
/* K~ = ck K + cb B + cm M* for one dt, its coefficients computed by the stepper (src/ts/damping.c) */
typedef struct {
  PetscReal dt, ck, cb, cm;
  Mat       B; /* NULL when cb = 0; B == K allowed */
  Mat       K;       /* the stiffness in K~: NULL for fem's K; a finite-strain tangent (K's pattern) otherwise */
  PetscInt  version; /* K's version: K~ is rebuilt when it changes, even at the same dt */
} MMStepMatrix;
PETSC_EXTERN PetscErrorCode MMContactSetStepMatrix(MMContact ct, const MMStepMatrix *sm);
/* The time scheme's share of a step, which the stepper hands down with the step matrix (src/ts/scheme.c,
 * docs/developer.md "The step's data flow"): contact and friction never see u^n or v^n. offset: the
 * displacement at which w has zero velocity over the step, u^n + dt/2 v^n (w-frame, borrowed: the
 * stepper recomputes it in place at each try of a step), which the tangential bounds are taken from;
 * scale: the velocity per displacement, 2/dt; velocity: sigma = 2/dt (w - u^n) - v^n, the velocity of
 * w over the step (the slip velocity on the tangential contact dofs), computed by the stepper. */
typedef struct {
  Vec       offset;
  PetscReal scale;
  PetscErrorCode (*velocity)(void *ctx, Vec w, Vec sigma);
  void     *ctx;
} MMStepOffset;
PETSC_EXTERN PetscErrorCode MMContactSetStepOffset(MMContact ct, const MMStepOffset *so);
PETSC_EXTERN PetscErrorCode MMContactShiftBounds(MMContact ct, Vec origin, PetscBool shift);
PETSC_EXTERN PetscErrorCode MMContactGetStepOffset(MMContact ct, MMStepOffset *so);
PETSC_EXTERN PetscErrorCode MMContactStepVelocity(MMContact ct, Vec w, Vec sigma);
PETSC_EXTERN PetscErrorCode MMContactGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp);
PETSC_EXTERN PetscErrorCode MMContactSolve(MMContact ct, Vec b, Vec w, Vec react);
/* The step's certificate (src/contact/interface/step_residual.c): the residual of K~ w = b + f_c, and
 * the tolerance of the iterative solves, which the stepper tightens when a step needs it */
PETSC_EXTERN PetscErrorCode MMContactStepResidual(MMContact ct, Vec b, Vec w, Vec react, Vec r, Vec scale);
PETSC_EXTERN PetscErrorCode MMContactSetSolveTolerance(MMContact ct, PetscReal tol);
PETSC_EXTERN PetscErrorCode MMContactGetSolveTolerance(MMContact ct, PetscReal *tol, PetscReal *user);
PETSC_EXTERN PetscErrorCode MMContactSolveContactDofs(MMContact ct, Vec b, Vec w, Vec react);
PETSC_EXTERN PetscErrorCode MMContactRecover(MMContact ct, Vec b, Vec w, Vec react);
PETSC_EXTERN PetscErrorCode MMContactGetNormalReactions(MMContact ct, Vec s);
PETSC_EXTERN PetscErrorCode MMContactSetFrictionThresholds(MMContact ct, Vec s);
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
typedef PetscErrorCode (*MMContactSetSolver)(void *fctx, const MMContactSetProblem *problem, PetscScalar x[], PetscBool *ok);
PETSC_EXTERN PetscErrorCode MMContactHasDelassus(MMContact ct, PetscBool *has);
PETSC_EXTERN PetscErrorCode MMContactSolveCoulomb(MMContact ct, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok);
PETSC_EXTERN PetscErrorCode MMContactHasCoulombDofs(MMContact ct, PetscBool *has);
PETSC_EXTERN PetscErrorCode MMContactSolveCoulombDofs(MMContact ct, Vec b, Vec w, Vec react, Vec s, PetscReal rtol, PetscInt *its, PetscBool *ok);
PETSC_EXTERN PetscErrorCode MMContactProjectInitial(MMContact ct, Vec w);
PETSC_EXTERN PetscErrorCode MMContactProjectInitialCorrect(MMContact ct, Vec w, Vec res, PetscReal *change);
PETSC_EXTERN PetscErrorCode MMContactSolveStatic(MMContact ct, Vec u, Vec react);
PETSC_EXTERN PetscErrorCode MMContactSolveStaticStep(MMContact ct, Mat A, Vec b, Vec u, PetscBool seat, Vec dw, Vec react, PetscInt *its, PetscBool *failed);
/* The contact quantities of an accepted state (docs/method.md sections 5-6), for the history */
typedef struct {
  PetscInt  active, switched, slipping; /* contact rows in contact, that changed state, slipping */
  PetscReal force_normal, force_tangential, max_penetration, coulomb_residual;
  PetscInt  vi_its;                     /* Newton iterations of the last contact solve */
  PetscInt  candidates, resolves;       /* the step's candidate-set size; VI re-solves over the run */
} MMContactStats;
PETSC_EXTERN PetscErrorCode MMContactDiagnostics(MMContact ct, PetscReal t, Vec u, Vec react, Vec v, MMContactStats *st);
PETSC_EXTERN PetscErrorCode MMContactCoulomb(MMContact ct, PetscReal t, Vec w, Vec react, Vec sigma, PetscReal *coulomb, PetscInt *nslip, PetscInt *nstick);
PETSC_EXTERN PetscErrorCode MMContactAudit(MMContact ct, PetscInt step, PetscReal t, const MMContactStats *st);
/* The contact fields of a snapshot from the state (u, v, react): nodal pressure and gap (scalar vertex
 * vectors), tangential traction and slip velocity (Cartesian, on dm_out) */
PETSC_EXTERN PetscErrorCode MMContactBoundaryFields(MMContact ct, Vec u, Vec v, Vec react, DM dm_out, Vec pressure, Vec gap, Vec traction_t, Vec slip);
PETSC_EXTERN PetscErrorCode MMContactObstacleField(MMContact ct, Vec field);
/* The data check's first-contact estimate (interface/first_contact.c): the earliest time a contact
 * row closes at the nodes' initial velocity and acceleration, its node (reference position), its
 * obstacle (index in the options' obstacles, -1 if none closes before the end), its gap, approach
 * speed and acceleration at the start; and the rows touching at the start. */
typedef struct {
  PetscReal t, gap, speed, accel;
  PetscReal x[MM_MAX_DIM];
  PetscInt  obstacle, touching;
} MMFirstContact;
PETSC_EXTERN PetscErrorCode MMContactFirstContact(MMContact ct, Vec u, Vec v, Vec a, PetscReal t0, PetscReal t_end, MMFirstContact *fc);
PETSC_EXTERN PetscErrorCode MMContactObstacleGaps(MMContact ct, Vec u, PetscReal t, PetscInt count[], PetscReal gap[], PetscReal x[]);
PETSC_EXTERN PetscErrorCode MMContactCornersAccept(MMContact ct);
PETSC_EXTERN PetscErrorCode MMContactCornersWork(MMContact ct, PetscReal t0, PetscReal t1, Vec work, PetscReal *wc, PetscReal *wn, PetscReal *wt);

/* Linear solvers of K~ (interface/qp.c, pc_schursplit.c, pc_vifactor.c) */
PETSC_EXTERN PetscErrorCode MMKSPSetDirect(KSP ksp);
PETSC_EXTERN PetscErrorCode MMKSPSetExactCG(KSP ksp);
PETSC_EXTERN PetscErrorCode MMKSPCheckFactored(KSP ksp);
PETSC_EXTERN PetscErrorCode MMKSPSetFailureCheck(KSP ksp);
PETSC_EXTERN PetscErrorCode MMKSPSetDirectSPD(KSP ksp, PetscInt dim);
PETSC_EXTERN PetscErrorCode MMKSPGetFactorPC(KSP ksp, PC *fpc, PetscBool *redundant);
/* The exact solve of K~ split at the ranks' interface (src/contact/interface/pc_schursplit.c): the
 * default for K~ in 2D on 2 to 8 ranks, -contact_K_pc_type schursplit */
#define MMPCSCHURSPLIT "schursplit"
PETSC_EXTERN PetscErrorCode MMPCRegisterSchurSplit(void);
/* The full formulation's Newton solves by one factor of the whole K~, its active rows and columns
 * the identity's (src/contact/interface/pc_vifactor.c): the default, -contact_pc_type vifactor */
#define MMPCVIFACTOR "vifactor"
PETSC_EXTERN PetscErrorCode MMPCRegisterVIFactor(void);
PETSC_EXTERN PetscErrorCode MMPCVIFactorSetSNES(PC pc, SNES snes);
PETSC_EXTERN PetscErrorCode MMPCVIFactorAnalyse(PC pc, Mat A);
PETSC_EXTERN PetscErrorCode MMPCVIFactorGetFactor(PC pc, Mat *F, const char **solver);
PETSC_EXTERN PetscErrorCode MMFactorReadOptions(MPI_Comm comm, const char prefix[], MatSolverType solver, MatFactorType ftype);
