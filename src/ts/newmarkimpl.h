/* The Newmark context's struct (include/ts.h): private to src/ts/. */
#pragma once
#include "ts.h"

/* The deformation audit (deformation.c): the largest strain of the run and where it was. */
typedef struct {
  PetscReal max_strain;        /* over the run: the largest principal strain magnitude */
  PetscReal where[MM_MAX_DIM]; /* the reference centroid of the cell that had it */
  PetscInt  step;              /* the step at which it was reached */
  PetscBool warned;            /* the -strain_warn warning was printed */
  PetscBool warned_rotation;   /* the linear law's rotation warning was printed */
  PetscInt  ncells;            /* this rank's cells, and for each its dim+1 vertices' */
  PetscInt *cell_u, *cell_x;   /* offsets in the local displacement and coordinate vectors */
} MMDeformation;

/* The momentum audit's fixed data (momenta.c), built on the first diagnostics and again after the
 * contact frames turned or the pairing changed: each linear momentum functional as one w-frame
 * vector, and the vertices of the angular momentum. */
typedef struct {
  PetscInt  ng, nJ;             /* ng = 2 dim + nJ functionals; nJ: J's components, 3 in 3D, 1 (z) in 2D */
  Vec       g[3 * MM_MAX_DIM];  /* g.x: the sums behind ucm or vcm (dim), P (dim) and J (nJ) for x = u or v */
  Vec       sel[MM_MAX_DIM];    /* Cartesian: 1 at component d of the vertices with no Dirichlet dof */
  PetscInt  nv;                 /* this rank's owned vertices with no Dirichlet dof */
  PetscInt *vert_u, *vert_x;    /* their offsets in the owned part of a global vector and in the local coordinates */
  PetscObjectState frames;      /* contact's frame state they were built in (MMContactGetFrameState): stale once it moves */
} MMMomenta;

/* The finite-strain step (nonlinear.c, docs/method.md section 13): a modified Newton iteration on the
 * algorithmic internal force, each iterate one contact (and friction) solve of the step matrix
 * K_s + 4/dt^2 M*, K_s the reference stiffness or a tangent rebuilt when it stops paying. */
typedef enum {
  MM_TANGENT_AUTO,      /* K_s kept while the iteration contracts fast, rebuilt at the iterate when not */
  MM_TANGENT_REFERENCE, /* K_s = K, the reference stiffness, all run: one factor */
  MM_TANGENT_STEP       /* K_s rebuilt at u^n every step */
} MMTangentPolicy;
PETSC_INTERN const char *const MMTangentPolicies[];
/* Anderson acceleration of the step's fixed point on the force correction (anderson.c) */
#define MM_ANDERSON_MAX 16
typedef struct {
  PetscInt  m, n;       /* depth, stored differences (oldest first) */
  PetscBool first;      /* no previous iterate yet */
  Vec      *dF, *dH;    /* differences of the residuals f = H - c and of the maps H */
  Vec       f, f_prev, H_prev;
} MMAnderson;
PETSC_INTERN PetscErrorCode MMAndersonSetUp(MMAnderson *aa, PetscInt m, Vec tmpl);
PETSC_INTERN PetscErrorCode MMAndersonReset(MMAnderson *aa);
PETSC_INTERN PetscErrorCode MMAndersonUpdate(MMAnderson *aa, Vec c, Vec H);
PETSC_INTERN PetscErrorCode MMAndersonDestroy(MMAnderson *aa);
PETSC_INTERN PetscErrorCode MMNewmarkCheckStepCount(MPI_Comm comm);
typedef struct {
  MMElasticity    el;
  MMAnderson      aa;          /* -nonlinear_anderson m */
  MMTangentPolicy policy;      /* -nonlinear_tangent */
  PetscReal       rtol;        /* -nonlinear_rtol: the force residual, relative to the internal force */
  PetscReal       rtol_audit;  /* -nonlinear_audit_rtol: below it, a residual the audits cannot see also ends the step */
  PetscReal       size;        /* the mesh's bounding-box diagonal: the angular momentum's length scale */
  PetscInt        max_it;      /* -nonlinear_max_it */
  PetscInt        anderson;    /* -nonlinear_anderson: its depth */
  PetscReal       refresh;     /* -nonlinear_refresh_ratio: auto rebuilds K_s when an iteration contracts less */
  Mat             Ks;          /* the iteration stiffness when not K (w-frame, K's pattern) */
  PetscInt        version;     /* counts the rebuilds of Ks: contact rebuilds K~ when it changes */
  PetscBool       use_tangent; /* Ks, not K, is in K~ */
  PetscBool       clamp;       /* the tangent's compressed cells clamped semi-definite: -nonlinear_tangent_clamp, or since a step with the unclamped one was rejected */
  PetscInt        clamp_step;  /* the step from which it is clamped by that fallback, 0: not */
  Vec             Ks_at;       /* the Cartesian displacement Ks is the tangent at, and its time (the Dirichlet data's): */
  PetscReal       Ks_time;     /* a checkpoint keeps them, so that a restart builds the same Ks (docs/method.md section 9) */
  Vec             bnl, f, c, c_prev; /* the step's fixed right-hand side; 2 f_alg; K_s w - 2 f_alg at this iterate and the last */
  Vec             c_scale;     /* the round-off scale of 2 f_alg (a stalled iterate's certificate) */
  Mat             Kabs;        /* |K|, for that scale, built on first use */
  PetscInt        its, its_total, rebuilds, steps; /* the last step's iterations; over the run, and the solved steps */
  PetscReal       residual;    /* the last step's final relative residual */
  PetscBool       friction_failed; /* the last step's iteration stopped at a friction solve that did not converge (at iteration its) */
  PetscInt        static_steps;  /* -static_load_steps: the static start's first load increment is 1/this */
  PetscInt        static_max_it; /* -static_max_it: Newton iterations per load level before the increment is halved */
} MMNonlinear;

/* The step's certificate (certificate.c, docs/method.md section 3): the defects of a step's solution,
 * the residual's work over the step, its resultant and its moment, and the round-off of each one's
 * terms; ratio: the largest defect in round-offs (<= 1: met). */
typedef struct {
  PetscReal energy, energy_tol, force, force_tol, torque, torque_tol, ratio;
  PetscReal size; /* an iterate's (MMCertificateOfIterate): ||r|| in round-offs of its terms, eps ||scale|| */
} MMStepCertificate;
/* The round-offs of its terms a step's defect may be (certificate.c), and those of an iteration
 * that stopped falling: its floor, accepted there */
#define MM_CERT_ROUNDOFFS       4.0
#define MM_SOLVE_TOL_MIN        1e-15 /* the tightest relative tolerance the finite-strain step asks of an iterative solve */
#define MM_CERT_FLOOR_ROUNDOFFS 1e3
#define MM_CERT_MAX_SOLVES      4 /* solves of one linear step at most */
typedef struct {
  PetscBool         on;          /* -step_certificate, with the linear law */
  Vec               r, scale, r_old; /* the residual and its entries' round-off scale; the last accepted step's residual */
  PetscReal         radius;      /* the mesh's farthest extent from the origin: the moments' lever */
  PetscReal         ratio_prev;  /* the last solve's ratio, this step */
  PetscReal         ratio_max;   /* over the run, of the steps that met it */
  PetscInt          resolves;    /* solves again with a tighter tolerance, over the run */
  PetscInt          floor_steps; /* steps accepted at their residual's round-off floor */
  PetscReal         floor_max;   /* their largest ratio */
} MMCertificateData;
/* A step accepted at its residual's round-off floor, counted for the run's report */
static inline void MMCertificateAtFloor(MMCertificateData *cd, PetscReal ratio)
{
  cd->floor_steps++;
  cd->floor_max = PetscMax(cd->floor_max, ratio);
}
PETSC_INTERN PetscErrorCode MMCertificateSetUp(MMNewmark nm);
PETSC_INTERN PetscErrorCode MMCertificateCheck(MMNewmark nm, Vec b, Vec w, PetscInt tries, PetscBool *again);
PETSC_INTERN PetscErrorCode MMCertificateDestroy(MMCertificateData *cd);
PETSC_INTERN PetscErrorCode MMCertificateOfIterate(MMNewmark nm, Vec bH, Vec w, Vec force_scale, MMStepCertificate *c);
PETSC_INTERN PetscErrorCode MMCertificateResidualOfIterate(MMNewmark nm, Vec bH, Vec w, Vec *r);
PETSC_INTERN PetscErrorCode MMCertificateOfResidual(MMNewmark nm, Vec r, Vec scale, Vec w, MMStepCertificate *c);

/* Why a step is rejected and retried with a smaller dt. */
typedef enum {
  MM_REJECT_FRICTION,     /* the friction loop did not converge (Theorem 4.2's condition fails) */
  MM_REJECT_CONTACT_WORK, /* a release the step does not resolve creates energy */
  MM_REJECT_NONLINEAR     /* the finite-strain step's iteration did not converge */
} MMRejectReason;

/* The step's law (step_laws.c): what the linear and the finite-strain steps do differently in
 * TSStep_Newmark's one skeleton. begin: before the step's start is saved (NULL: nothing);
 * stepmatrix: K~'s coefficients for dt; solve: w = u^{n+1} from the predictor in w and contact's
 * right-hand side b (*solved: converged); failure: why a step whose solve failed is rejected. */
typedef struct {
  PetscErrorCode (*begin)(MMNewmark nm, PetscReal t, PetscReal dt);
  PetscErrorCode (*stepmatrix)(MMNewmark nm, PetscReal dt, MMStepMatrix *sm);
  PetscErrorCode (*solve)(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, PetscBool *solved);
  /* after a solved step (NULL: none): *again, the step is to be solved again from its start (the
   * frames of the nodes that ended inside their obstacle turned to where they ended) */
  PetscErrorCode (*refine)(MMNewmark nm, PetscReal t0, PetscReal dt, Vec w, PetscInt tries, PetscBool *again);
  MMRejectReason failure;
  PetscBool      certified; /* the step is accepted by the certificate of K~ w = b + f_c (certificate.c) */
} MMStepLawOps;
PETSC_INTERN const MMStepLawOps *MMStepLawGetOps(const MMMaterial *material);
PETSC_INTERN PetscErrorCode      MMNonlinearRefineStep(MMNewmark nm, PetscReal t0, PetscReal dt, Vec w, PetscInt tries, PetscBool *again);

struct _p_MMNewmark {
  MPI_Comm         comm;
  MMNewmarkProblem pb;
  /* the lower components, borrowed (MMNewmarkSetUp) */
  MMOperators  op;
  DM           dm;  /* fem's (MMFEGetDM): the mesh and the layout of every vector */
  PetscInt     dim; /* the mesh's (MMFEGetDimension) */
  MMMaterial  *material;
  MMLoads     *loads;
  MMContact    contact;
  MMFriction   friction; /* set once friction is set up (MMNewmarkSetFriction) */
  /* the audits' options (MMNewmarkSetFromOptions) */
  PetscReal audit_tol;         /* -audit_tol: the energy audit's */
  PetscReal contact_work_tol;  /* -contact_work_tol: a step whose contact work creates more energy is rejected */
  PetscBool deformation_audit; /* -deformation_audit, -strain_warn, -max_strain */
  PetscReal strain_warn, max_strain;
  /* owned */
  MMState       state;
  MMHistory     hist;
  MMDamping     damping;
  MMDeformation deform;
  MMMomenta     momenta;
  MMNonlinear   nl;     /* the finite-strain laws' step (material->finite) */
  MMStepOffset  scheme; /* the step's offset and scale, handed to contact (scheme.c) */
  PetscBool     increments; /* -step_increments, resolved at set-up: the linear step solves for du (scheme.c) */
  PetscBool     scheme_origin_zero; /* the step's offset and velocity are of du, during the increment's solve */
  MMCertificateData cert; /* the step's acceptance rule (certificate.c) */
  const MMStepLawOps *law; /* the step's law: linear or finite strain (step_laws.c) */
};

/* The dofs without inertia: the contact-normal dofs under the modified mass, none otherwise. */
static inline PetscBool MMNewmarkHasMasslessDofs(MMNewmark nm)
{
  return MMContactHasMasslessDofs(nm->contact);
}

/* ts's events (MMTSInitializePackage) */
PETSC_INTERN PetscLogEvent MM_TS_Energy, MM_TS_Momenta, MM_TS_Deformation, MM_TS_Certificate, MM_TS_StaticFinite;

/* The parts of the stepper, each in its file */
PETSC_INTERN PetscErrorCode MMEnergyContactWork(MMNewmark nm, Vec w, PetscReal *w_c);
PETSC_INTERN PetscErrorCode MMEnergyStep(MMNewmark nm);
PETSC_INTERN PetscErrorCode MMRigidBodyDiagnostics(MMNewmark nm, MMHistory *h);
PETSC_INTERN PetscErrorCode MMMomentaOfForce(MMNewmark nm, Vec u, Vec f, PetscReal F[3], PetscReal T[3]);
PETSC_INTERN PetscErrorCode MMMomentaDestroy(MMMomenta *mo);
PETSC_INTERN PetscErrorCode MMDeformationDestroy(MMDeformation *d);
PETSC_INTERN PetscErrorCode MMInitialStaticSliding(MMNewmark nm, Vec w, Vec react);
PETSC_INTERN PetscErrorCode MMDampingSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMDamping *d);
PETSC_INTERN PetscErrorCode MMDampingSetUp(MMDamping *d, MMContact ct, MMMaterial *material, IS is_massless, Vec v0);
PETSC_INTERN PetscErrorCode MMDampingAddStepRHS(MMDamping *d, Vec u, PetscReal dt, Vec b);
PETSC_INTERN PetscErrorCode MMNewmarkSchemeIncrement(MMNewmark nm, PetscReal dt, PetscBool on);
PETSC_INTERN PetscErrorCode MMNewmarkStepIncrement(MMNewmark nm, Vec w, Vec du);
PETSC_INTERN PetscErrorCode MMNewmarkPredictEnd(MMNewmark nm, PetscReal dt, Vec w);
PETSC_INTERN PetscErrorCode MMDampingUpdateVelocity(MMDamping *d, Vec du, PetscReal dt);
PETSC_INTERN PetscErrorCode MMDampingAddStepRHSIncrement(MMDamping *d, Vec b);
PETSC_INTERN PetscErrorCode MMDampingWork(MMDamping *d, Vec du, PetscReal dt, PetscReal *w);
PETSC_INTERN PetscErrorCode MMNewmarkRegister(void);
PETSC_INTERN PetscErrorCode MMNewmarkView(MMNewmark nm, PetscReal dt, PetscViewer viewer);
PETSC_INTERN PetscErrorCode MMNonlinearSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMNonlinear *nl);
PETSC_INTERN PetscErrorCode MMNonlinearSetUp(MMNewmark nm);
PETSC_INTERN PetscErrorCode MMNonlinearStepMatrix(MMNewmark nm, PetscReal dt, MMStepMatrix *sm);
PETSC_INTERN PetscErrorCode MMNonlinearSlidePairs(MMNewmark nm, PetscReal dt);
PETSC_INTERN PetscErrorCode MMNonlinearSolve(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, PetscBool *solved);
/* free_flight.c: the mass in free flight */
PETSC_INTERN PetscErrorCode MMNonlinearFreeFlight(MMNewmark nm, PetscReal t, PetscReal dt);
PETSC_INTERN PetscErrorCode MMNonlinearFreeFlightTouched(MMNewmark nm, Vec w, PetscReal t, PetscBool *touched);
PETSC_INTERN PetscErrorCode MMNonlinearElasticEnergy(MMNewmark nm, Vec u, PetscReal t, PetscReal *energy);
PETSC_INTERN PetscErrorCode MMNonlinearDestroy(MMNonlinear *nl);
PETSC_INTERN PetscErrorCode MMNonlinearDampingWork(MMNewmark nm, Vec du, PetscReal t1, PetscReal dt, PetscReal *w);
PETSC_INTERN PetscErrorCode MMNonlinearFollowFrames(MMNewmark nm, PetscReal t, PetscReal dt, Vec midpoint);
PETSC_INTERN PetscErrorCode MMNonlinearBuildTangent(MMNewmark nm, Vec l, PetscReal t);
PETSC_INTERN PetscErrorCode MMNewmarkStaticFinite(MMNewmark nm, Vec u, Vec react);
PETSC_INTERN PetscErrorCode MMAdaptGrowBackRegister(void);
PETSC_INTERN PetscErrorCode MMNewmarkSchemeSetUp(MMNewmark nm);
PETSC_INTERN PetscErrorCode MMNewmarkPredictMidpoint(MMNewmark nm, PetscReal dt, Vec *midpoint);
PETSC_INTERN PetscErrorCode MMNewmarkSchemeDestroy(MMNewmark nm);
