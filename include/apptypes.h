/* Run options: everything the user sets (src/app/options.c), and the enums they choose from. */
#pragma once
#include "mmbase.h"
#include "obstacle.h"
#include "fem.h"
#include "ts.h"

PETSC_EXTERN const char *const MMInitialStates[];

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

/* Run options: everything the user sets. Filled in one place, src/app/options.c. */
typedef struct {
  char         mesh_file[PETSC_MAX_PATH_LEN];
  char         contact_name[256];
  PetscInt     n_dirichlet, n_traction;
  MMDirichlet *dirichlet;
  MMTraction  *traction;
  PetscInt      n_pressure, n_point_force; /* -pressure and -point_force (src/fem/loads_nodal.c) */
  MMPressure   *pressure;
  MMPointForce *point_force;
  PetscReal    E, nu, rho;
  PetscInt     n_bodies;            /* -bodies, 0 without it: one body, the whole mesh, of -E -nu -rho -v0 */
  MMBodyOptions *bodies;
  PetscReal    gravity[MM_MAX_DIM];
  MMAmplitudeOptions gravity_amplitude;
  PetscReal    u0_offset[MM_MAX_DIM], u0_gradient[MM_MAX_DIM * MM_MAX_DIM];
  PetscReal    v0[MM_MAX_DIM], omega[MM_MAX_DIM], omega_center[MM_MAX_DIM];
  MMInitialState initial_state;
  PetscReal    obstacle_point[MM_MAX_DIM], obstacle_normal[MM_MAX_DIM];
  PetscReal    mesh_rotation[MM_MAX_DIM], mesh_rotation_center[MM_MAX_DIM];
  PetscReal    contact_work_tol;
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
  PetscReal    mu_max;              /* the largest friction coefficient of the obstacles */
} MMOptions;
