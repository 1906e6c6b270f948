/* The problem as each component is handed it: the plain structs of include/ filled from MMOptions
 * (docs/developer.md, "Components"), so that no component includes app's header. */
#include "appimpl.h"

/* The problem as contact reads it: plain data, the arrays borrowed from opt for the set-up. */
PetscErrorCode MMOptionsGetContactProblem(const MMOptions *opt, MMContactProblem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->obstacles      = opt->obstacles;
  pb->n_obstacles    = opt->n_obstacles;
  pb->n_rigid        = opt->n_rigid;
  pb->mu_max         = opt->mu_max;
  pb->E              = opt->E;
  pb->rho            = opt->rho;
  pb->contact_name   = opt->contact_name;
  pb->contact_name_given = opt->contact_name_given;
  pb->static_sliding = (PetscBool)(opt->initial_state == MM_INITIAL_STATIC_SLIDING);
  pb->quiet          = opt->quiet;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    pb->obstacle_point[d]  = opt->obstacle_point[d];
    pb->obstacle_normal[d] = opt->obstacle_normal[d];
  }
  PetscFunctionReturn(0);
}

/* The problem as fem reads it: the material, bodies, loads and initial velocity, borrowed from opt. */
PetscErrorCode MMOptionsGetFEProblem(const MMOptions *opt, MMFEProblem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->E                 = opt->E;
  pb->nu                = opt->nu;
  pb->rho               = opt->rho;
  pb->elasticity        = opt->elasticity;
  pb->v0                = opt->v0;
  pb->n_bodies          = opt->n_bodies;
  pb->bodies            = opt->bodies;
  pb->omega0            = opt->omega0;
  pb->omega0_set        = (PetscBool)(opt->vec_count[MM_V_OMEGA0] >= 0);
  pb->gravity           = opt->loads.gravity;
  pb->gravity_amplitude = &opt->loads.gravity_amplitude;
  pb->n_dirichlet       = opt->loads.n_dirichlet;
  pb->dirichlet         = opt->loads.dirichlet;
  pb->n_traction        = opt->loads.n_traction;
  pb->traction          = opt->loads.traction;
  pb->n_pressure        = opt->loads.n_pressure;
  pb->pressure          = opt->loads.pressure;
  pb->n_point_force     = opt->loads.n_point_force;
  pb->point_force       = opt->loads.point_force;
  pb->static_sliding    = (PetscBool)(opt->initial_state == MM_INITIAL_STATIC_SLIDING);
  PetscFunctionReturn(0);
}

/* The problem as io reads it: the names its columns and report quote, a checkpoint's fingerprint. */
PetscErrorCode MMOptionsGetIOProblem(const MMOptions *opt, MMIOProblem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->mesh_file    = opt->mesh_file;
  pb->contact_name = opt->contact_name;
  pb->E            = opt->E;
  pb->nu           = opt->nu;
  pb->rho          = opt->rho;
  pb->mu           = opt->mu;
  pb->mu_max       = opt->mu_max;
  pb->n_obstacles  = opt->n_obstacles;
  pb->n_rigid      = opt->n_rigid;
  pb->obstacles    = opt->obstacles;
  pb->obstacles_named = opt->obstacles_named;
  pb->n_dirichlet  = opt->loads.n_dirichlet;
  pb->dirichlet    = opt->loads.dirichlet;
  PetscFunctionReturn(0);
}

/* The problem as the stepper reads it: the initial state, the obstacles (borrowed from opt), the
 * audits' thresholds and the values its messages quote. */
PetscErrorCode MMOptionsGetNewmarkProblem(const MMOptions *opt, MMNewmarkProblem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->initial_state = opt->initial_state;
  pb->u0_given      = (PetscBool)(opt->vec_count[MM_V_U0_OFFSET] >= 0 || opt->vec_count[MM_V_U0_GRADIENT] >= 0);
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    pb->u0_offset[d]       = opt->u0_offset[d];
    pb->v0[d]              = opt->v0[d];
    pb->omega[d]           = opt->omega[d];
    pb->omega_center[d]    = opt->omega_center[d];
    pb->obstacle_normal[d] = opt->obstacle_normal[d];
  }
  for (PetscInt d = 0; d < MM_MAX_DIM * MM_MAX_DIM; ++d) pb->u0_gradient[d] = opt->u0_gradient[d];
  pb->obstacles = opt->obstacles;
  pb->mu        = opt->mu;
  pb->dirichlet = (PetscBool)(opt->loads.n_dirichlet > 0);
  for (PetscInt b = 0; b < opt->loads.n_dirichlet; ++b) {
    for (PetscInt c = 0; c < opt->loads.dirichlet[b].nvalues; ++c)
      if (opt->loads.dirichlet[b].values[c] != 0) pb->dirichlet_nonzero = PETSC_TRUE;
    for (PetscInt c = 0; c < opt->loads.dirichlet[b].nvelocity; ++c)
      if (opt->loads.dirichlet[b].velocity[c] != 0) pb->dirichlet_nonzero = PETSC_TRUE;
  }
  pb->E                 = opt->E;
  pb->nu                = opt->nu;
  pb->rho               = opt->rho;
  pb->quiet             = opt->quiet;
  PetscFunctionReturn(0);
}
