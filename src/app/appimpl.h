/* Private to the application (src/app/): the problem as the user gave it (MMOptions), the run's
 * context MMCtx that ties the components together, and app's own functions. No other component
 * includes this header: each reads its own options and takes its inputs explicitly. */
#pragma once
#include "mmbase.h"
#include "obstacle.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"
#include "ts.h"
#include "io.h"

PETSC_INTERN const char *const MMInitialStates[];

/* The vector options, whose lengths can only be checked once the mesh gives the dimension. */
typedef enum {
  MM_V_U0_OFFSET,
  MM_V_U0_GRADIENT,
  MM_V_V0,
  MM_V_OMEGA,
  MM_V_OMEGA_CENTER,
  MM_V_OBSTACLE_POINT,
  MM_V_OBSTACLE_NORMAL,
  MM_V_MESH_ROTATION,
  MM_V_MESH_ROTATION_CENTER,
  MM_V_OMEGA0,
  MM_V_NUM
} MMVectorOption;

/* The problem as the user gave it (src/app/options.c): mesh, bodies and material, boundary conditions,
 * loads, initial state, obstacles; and app's own run controls. Each component reads its own solver
 * and output options in its SetFromOptions. */
typedef struct {
  char         mesh_file[PETSC_MAX_PATH_LEN];
  char         contact_name[256];
  PetscBool    contact_name_given; /* -contact_boundary was given */
  MMLoadGroups loads;               /* -gravity, -dirichlet, -traction, -pressure, -point_force: fem's reader */
  PetscReal    E, nu, rho;
  MMElasticityType elasticity; /* -elasticity */
  PetscInt     n_bodies;            /* -bodies, 0 without it: one body, the whole mesh, of -E -nu -rho -v0 */
  MMBodyOptions *bodies;
  PetscReal    u0_offset[MM_MAX_DIM], u0_gradient[MM_MAX_DIM * MM_MAX_DIM];
  PetscReal    v0[MM_MAX_DIM], omega[MM_MAX_DIM], omega_center[MM_MAX_DIM];
  PetscReal    omega0[MM_MAX_DIM]; /* -omega0: a rigid rotation about each body's centre of mass */
  MMInitialState initial_state;
  PetscReal    obstacle_point[MM_MAX_DIM], obstacle_normal[MM_MAX_DIM];
  PetscReal    mesh_rotation[MM_MAX_DIM], mesh_rotation_center[MM_MAX_DIM];
  PetscReal    mu;
  PetscBool    quiet;
  PetscBool    check_input;         /* -check_input: set up, report and exit without stepping or writing */
  PetscBool    allow_unused;
  PetscBool    debug; /* -debug: full PETSc traces (read again by errors.c before the options) */
  PetscInt     vec_count[MM_V_NUM]; /* entries given to each vector option, -1 if not set */
  PetscInt     n_obstacles;         /* the rigid obstacles, then the contact pairs */
  PetscInt     n_rigid;             /* -obstacles, or the one plane of -obstacle_point/_normal (0 with pairs alone) */
  MMObstacle  *obstacles;
  PetscBool    obstacles_named;     /* -obstacles was given */
  char         obstacle_list[PETSC_MAX_PATH_LEN], pair_list[PETSC_MAX_PATH_LEN]; /* -obstacles, -contact_pairs */
  PetscReal    mu_max;              /* the largest friction coefficient of the obstacles */
} MMOptions;

/* The run's context: the problem as the user gave it, and each component's object or data, created,
 * set up and destroyed by main.c. */
typedef struct _MMCtx {
  MMOptions   opt;
  MMIOProblem iopb; /* the part of opt the output, checkpoint and progress read (MMOptionsGetIOProblem) */
  MMMaterial  material;
  DM          dm; /* the mesh, read and distributed by app (LoadMesh), handed to fem (MMFESetDM) */
  MMOperators op;
  MMLoads     loads;
  MMContact   contact;
  MMFriction  friction;
  MMNewmark   nm; /* the stepper (src/ts/): its state, history and damping through MMNewmarkGet* */
  MMProgress  progress;
  MMOutput    out;
  MMCheckpoint ckpt;
} MMCtx;

PETSC_INTERN PetscErrorCode MMOptionsProcess(MPI_Comm comm, MMOptions *opt);
PETSC_INTERN PetscErrorCode MMOptionsCheckDimension(MPI_Comm comm, MMOptions *opt, PetscInt dim, PetscBool damped);
PETSC_INTERN PetscErrorCode MMOptionsDestroy(MMOptions *opt);
PETSC_INTERN PetscErrorCode MMOptionsGetFEProblem(const MMOptions *opt, MMFEProblem *pb);
PETSC_INTERN PetscErrorCode MMOptionsGetContactProblem(const MMOptions *opt, MMContactProblem *pb);
PETSC_INTERN PetscErrorCode MMOptionsGetNewmarkProblem(const MMOptions *opt, MMNewmarkProblem *pb);
PETSC_INTERN PetscErrorCode MMOptionsGetIOProblem(const MMOptions *opt, MMIOProblem *pb);
PETSC_INTERN PetscErrorCode MMOptionsHelpWithoutMesh(MPI_Comm comm, PetscBool *done);
PETSC_INTERN PetscErrorCode MMOptionsCheckUnused(MPI_Comm comm, const MMOptions *opt, DM dm);
PETSC_INTERN PetscErrorCode MMOptionsCheckValueless(MPI_Comm comm);
PETSC_INTERN int            MMOptionsCheckFiles(int argc, char **argv);

/* -check_input: the data check's report and clean-up (src/app/datacheck.c) */
PETSC_INTERN PetscErrorCode MMDataCheckReport(MMCtx *ctx, TS ts);
PETSC_INTERN PetscErrorCode MMDataCheckDestroy(MMCtx *ctx);

/* app's own log stages and events (src/app/app_log.c): the set-up and the time loop, and each phase
 * of the set-up (main.c's MMPhase), so that -log_view accounts for all of it. */
typedef struct {
  PetscLogStage setup, solve;
  PetscLogEvent mesh_load, fe_setup, contact_setup, loads_setup, initial_state, friction_setup, step_matrix, energy_initial, deformation_check, output_open;
} MMAppLog;
PETSC_INTERN MMAppLog       MMAppEvents;
PETSC_INTERN PetscErrorCode MMAppInitializePackage(void);
