/* The problem as the user gives it (README "Options"): the mesh, the whole mesh's material, the
 * initial state, -mu and app's run controls, in app's block; then the objects that read their own
 * options, each in its own block: the bodies and the load groups (fem, src/fem/bodies.c,
 * src/fem/load_groups.c) and the obstacles (src/obstacle/interface/options.c). */
#include "appimpl.h"
#include "obstacle.h"
#include "sys.h"

const char *const MMInitialStates[] = {"given", "static_sliding", "static", "MMInitialState", "MM_INITIAL_", NULL};

/* What a vector option's length must be, once the dimension d is known. */
typedef enum {
  MM_LEN_DIM,     /* d entries */
  MM_LEN_TENSOR,  /* d*d entries */
  MM_LEN_ROTATION /* 1 entry in 2D (an angle), 3 in 3D (a vector) */
} MMVectorLength;

static const char *const VectorName[MM_V_NUM] = {"-u0_offset", "-u0_gradient", "-v0", "-omega", "-omega_center", "-obstacle_point", "-obstacle_normal", "-mesh_rotation", "-mesh_rotation_center", "-omega0"};
static const MMVectorLength VectorLength[MM_V_NUM] = {MM_LEN_DIM, MM_LEN_TENSOR, MM_LEN_DIM, MM_LEN_ROTATION, MM_LEN_DIM, MM_LEN_DIM, MM_LEN_DIM, MM_LEN_ROTATION, MM_LEN_DIM, MM_LEN_ROTATION};

/* The checked option readers of src/sys/option_values.c, under this file's short names. */
#define CheckFinite      MMOptionsCheckFinite
#define OptionsReal      MMOptionsReal
#define OptionsRealArray MMOptionsRealArray
#define OptionsInt       MMOptionsInt
#define OptionsBool      MMOptionsBool
#define OptionsString    MMOptionsString
#define OptionsEnum      MMOptionsEnum

/* A vector option; its length is checked against the dimension once the mesh is read. */
static PetscErrorCode OptionsVector(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, MMVectorOption which, const char help[], PetscReal v[])
{
  const PetscInt nmax = VectorLength[which] == MM_LEN_TENSOR ? MM_MAX_DIM * MM_MAX_DIM : MM_MAX_DIM;

  PetscFunctionBeginUser;
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, VectorName[which], help, nmax, v, &opt->vec_count[which]));
  PetscFunctionReturn(0);
}

/* -mu is the default of every obstacle's and pair's own _mu: given while each of them sets its own,
 * it would be read and used nowhere, and the user would believe it applies. Refused, naming them. */
static PetscErrorCode CheckMuUsed(MPI_Comm comm, const MMOptions *opt)
{
  PetscBool given, own = PETSC_TRUE;
  char      key[512], names[1024] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mu", &given));
  if (!given || !opt->n_obstacles || (!opt->obstacles_named && opt->n_rigid)) PetscFunctionReturn(0); /* the unnamed plane takes -mu */
  for (PetscInt b = 0; b < opt->n_obstacles && own; ++b) {
    const MMObstacle *ob = &opt->obstacles[b];
    PetscCall(PetscSNPrintf(key, sizeof(key), ob->pair ? "-contact_pair_%s_mu" : "-obstacle_%s_mu", ob->name));
    own = ob->mu_given;
    if (own) {
      if (names[0]) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
      PetscCall(PetscStrlcat(names, key, sizeof(names)));
    }
  }
  PetscCheck(!own, comm, PETSC_ERR_USER_INPUT, "-mu %.6g is used nowhere: it is the default friction coefficient of the obstacles and contact pairs, and each sets its own (%s). Drop -mu, or drop the _mu of those that should take it", (double)opt->mu, names);
  PetscFunctionReturn(0);
}

/* -obstacles NAME,... and -contact_pairs NAME,...: the lists, in app's block. */
static PetscErrorCode ReadObstacleLists(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt)
{
  char types[256], help[1024];

  PetscFunctionBeginUser;
  PetscCall(MMObstacleTypesList(types, sizeof(types)));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Comma-separated names of the rigid obstacles; each takes -obstacle_NAME_type %s and its parameters. Each contact node is constrained against the one nearest to it in the reference configuration (default: one plane, -obstacle_point and -obstacle_normal)", types));
  PetscCall(OptionsString(PetscOptionsObject, comm, "-obstacles", help, opt->obstacle_list, sizeof(opt->obstacle_list), NULL));
  PetscCall(OptionsString(PetscOptionsObject, comm, "-contact_pairs", "Comma-separated names of contact pairs between two surfaces of the mesh (two elastic bodies); each takes -contact_pair_NAME_slave, -contact_pair_NAME_master and -contact_pair_NAME_mu. Without -obstacles, a run with pairs has no rigid obstacle", opt->pair_list, sizeof(opt->pair_list), NULL));
  {
    PetscBool view; /* viewed in main.c once set up (MMObstacleView), as PETSc's -ksp_view */
    PetscCall(PetscOptionsName("-obstacle_view", "Print each obstacle and contact pair as set up, before the first step (shape, parameters, side, friction coefficient, motion): -obstacle_view, or -obstacle_view ascii:FILE to write it to FILE", "None", &view));
  }
  PetscFunctionReturn(0);
}

/* The obstacles of -obstacles, each reading its own options, or, without it, the single plane of
 * -obstacle_point and -obstacle_normal (completed once the dimension is known); then the contact
 * pairs, each reading its own. */
static PetscErrorCode CreateObstacles(MPI_Comm comm, MMOptions *opt)
{
  const char *list = opt->obstacle_list, *plist = opt->pair_list;
  char      **names, **pnames;
  PetscInt    n, np;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsSplitNames(comm, "-obstacles", list, &n, &names));
  opt->obstacles_named = (PetscBool)(n > 0);
  PetscCheck(!n || (opt->vec_count[MM_V_OBSTACLE_POINT] < 0 && opt->vec_count[MM_V_OBSTACLE_NORMAL] < 0), comm, PETSC_ERR_USER_INPUT, "-obstacles %s and -obstacle_point/-obstacle_normal were both given: give the plane as one of the named obstacles (-obstacle_NAME_type plane -obstacle_NAME_point ... -obstacle_NAME_normal ...)", list);
  PetscCall(MMOptionsSplitNames(comm, "-contact_pairs", plist, &np, &pnames));
  /* pairs alone: no default plane, unless one was given by -obstacle_point/-obstacle_normal */
  opt->n_rigid     = n ? n : (np && opt->vec_count[MM_V_OBSTACLE_POINT] < 0 && opt->vec_count[MM_V_OBSTACLE_NORMAL] < 0 ? 0 : 1);
  opt->n_obstacles = opt->n_rigid + np;
  PetscCall(PetscCalloc1(opt->n_obstacles, &opt->obstacles));
  for (PetscInt p = 0; p < np; ++p) {
    for (PetscInt b = 0; b < n; ++b) {
      PetscBool same;
      PetscCall(PetscStrcmp(names[b], pnames[p], &same));
      PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "-contact_pairs %s and -obstacles %s both name %s: each obstacle and pair has its own force columns (force_NAME_x ...), so give them different names", plist, list, pnames[p]);
    }
    PetscCall(MMObstacleSetPairFromOptions(&opt->obstacles[opt->n_rigid + p], comm, pnames[p], opt->mu));
  }
  PetscCall(PetscStrToArrayDestroy((int)np, pnames));
  for (PetscInt b = 0; b < opt->n_rigid; ++b) {
    if (n) PetscCall(MMObstacleSetFromOptions(&opt->obstacles[b], comm, names[b], opt->mu));
    else PetscCall(MMObstacleCreatePlane(&opt->obstacles[b], comm, "plane", opt->mu));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscCall(CheckMuUsed(comm, opt));
  PetscFunctionReturn(0);
}

/* -bodies: fem reads them, each body defaulting to the whole mesh's material and initial velocity. */
static PetscErrorCode ReadBodies(MPI_Comm comm, MMOptions *opt)
{
  MMBodyOptions whole;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&whole, sizeof(whole)));
  whole.E          = opt->E;
  whole.nu         = opt->nu;
  whole.rho        = opt->rho;
  whole.elasticity = opt->elasticity;
  whole.omega0_set = (PetscBool)(opt->vec_count[MM_V_OMEGA0] >= 0);
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    whole.v0[d]     = opt->v0[d];
    whole.omega0[d] = opt->omega0[d];
  }
  PetscCall(MMBodiesSetFromOptions(comm, &whole, &opt->n_bodies, &opt->bodies));
  PetscFunctionReturn(0);
}

/* The ranges of the scalar options, each refused with its range. */
static PetscErrorCode CheckRanges(MPI_Comm comm, const MMOptions *opt)
{
  PetscFunctionBeginUser;
  PetscCheck(opt->E > 0, comm, PETSC_ERR_USER_INPUT, "Young's modulus -E %g must be > 0", (double)opt->E);
  PetscCheck(opt->nu > -1.0, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -nu %.6g must lie in (-1, 0.5): nu <= -1 makes the shear modulus E / (2 (1 + nu)) infinite or negative, an unstable material", (double)opt->nu);
  PetscCheck(opt->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -nu %.6g must lie in (-1, 0.5): nu >= 0.5 is incompressible, which P1 elements cannot represent", (double)opt->nu);
  PetscCheck(opt->rho > 0, comm, PETSC_ERR_USER_INPUT, "Density -rho %g must be > 0", (double)opt->rho);
  if (!opt->n_bodies) PetscCall(MMMaterialCheckNearlyIncompressible(comm, "-nu", opt->nu, opt->elasticity));
  PetscCall(MMBodiesCheck(comm, opt->n_bodies, opt->bodies));
  PetscCheck(opt->mu >= 0, comm, PETSC_ERR_USER_INPUT, "Friction coefficient -mu %g must be >= 0", (double)opt->mu);
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsProcess(MPI_Comm comm, MMOptions *opt)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(opt, sizeof(*opt)));
  PetscOptionsBegin(comm, NULL, "mmcontact: modified-mass dynamic contact", "MMContact");
  opt->mesh_file[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-mesh", "gmsh mesh file (.msh, format 2.2 or 4.1) with named physical groups; first-order triangles give plane strain, first-order tetrahedra 3D", opt->mesh_file, sizeof(opt->mesh_file), NULL));
  PetscCall(PetscStrcpy(opt->contact_name, "contact"));
  PetscCall(OptionsString(PetscOptionsObject, comm, "-contact_boundary", "Physical name of the contact boundary (a Physical Curve in 2D, Surface in 3D)", opt->contact_name, sizeof(opt->contact_name), &opt->contact_name_given));

  opt->E = 1.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-E", "Young's modulus (Pa), > 0", &opt->E));
  opt->nu = 0.3;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-nu", "Poisson ratio, in (-1, 0.5): at most 0.4995 with -elasticity svk or neohookean, 0.49999995 with linear (P1 volumetric locking)", &opt->nu));
  opt->rho = 1.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-rho", "Mass density (kg/m^d), > 0", &opt->rho));
  opt->elasticity = MM_ELASTICITY_LINEAR;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-elasticity", "Elasticity law: linear (the small-strain model, rotations strain the body), svk (St. Venant-Kirchhoff) or neohookean (compressible neo-Hookean), both finite strain with the same E and nu, energy and momentum exact per step (docs/method.md section 13)", MMElasticityTypes, (PetscEnum *)&opt->elasticity));

  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_U0_OFFSET, "Initial displacement u0 = a + B x: the vector a, d entries", opt->u0_offset));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_U0_GRADIENT, "Initial displacement u0 = a + B x: the matrix B, row-major, d*d entries", opt->u0_gradient));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_V0, "Initial translation velocity vx,vy[,vz], d entries", opt->v0));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA, "Initial rigid angular velocity (rad/s): a scalar in 2D, a vector in 3D", opt->omega));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA_CENTER, "Centre of the initial rigid rotation, d entries", opt->omega_center));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA0, "Initial rigid angular velocity (rad/s) about the centre of mass, of each body with -bodies, added to -v0 and -omega: a scalar in 2D, a vector in 3D", opt->omega0));
  opt->initial_state = MM_INITIAL_GIVEN;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-initial_state", "Initial displacement: given (-u0_offset, -u0_gradient, contact dofs projected), static_sliding (the body sliding along the tangential part of -v0 on the obstacle under its loads, with friction -mu; the normal part of -v0 is dropped) or static (the static, frictionless contact problem K u0 = L(0) under the loads at t = 0, with -elasticity svk or neohookean f(u0) = L(0) by load steps and Newton, then the dynamics from u0 with -v0)", MMInitialStates, (PetscEnum *)&opt->initial_state));

  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OBSTACLE_POINT, "A point of the rigid obstacle plane, d entries", opt->obstacle_point));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OBSTACLE_NORMAL, "Unit normal of the obstacle plane, pointing out of the obstacle towards the body, d entries (default +y in 2D, +z in 3D)", opt->obstacle_normal));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_MESH_ROTATION, "Rigid rotation applied to the mesh when it is read: an angle (2D) or a rotation vector (3D), in radians", opt->mesh_rotation));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_MESH_ROTATION_CENTER, "Centre of the -mesh_rotation, d entries", opt->mesh_rotation_center));


  opt->mu = 0.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-mu", "Coulomb friction coefficient, >= 0 (0: frictionless, the friction loop is skipped); the default of each -obstacle_NAME_mu and -contact_pair_NAME_mu (refused when each of them is given: it would be used nowhere)", &opt->mu));
  PetscCall(ReadObstacleLists(PetscOptionsObject, comm, opt));
  opt->quiet = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-quiet", "Do not print the start-up report, progress lines and closing summary", &opt->quiet));
  /* a data check (abaqus datacheck, MOOSE --check-input): src/app/datacheck.c, README "Checking a case before a batch job" */
  opt->check_input = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-check_input", "Check the case and exit: read the options and the mesh, build everything a run builds and refuse what a run would refuse, print the start-up report with each physical group's node and element counts, the planned steps and output size and a first-contact estimate, then exit 0 without stepping or writing anything (no output directory). -quiet does not apply", &opt->check_input));
  if (opt->check_input) opt->quiet = PETSC_FALSE; /* the report is what the check is for */
  opt->debug = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-debug", "On an error, print PETSc's full trace on every rank (by default an error a user can act on prints its message alone; README \"Exit status\")", &opt->debug));
  opt->allow_unused = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-allow_unused_options", "Run even if an option is set that nothing reads (by default such an option, usually a typo, stops the run before the first step)", &opt->allow_unused));
  PetscOptionsEnd();
  PetscCall(ReadBodies(comm, opt));
  PetscCall(MMLoadGroupsSetFromOptions(comm, &opt->loads));
  PetscCall(CreateObstacles(comm, opt));
  PetscCall(CheckRanges(comm, opt));
  PetscFunctionReturn(0);
}

/* The length a vector option must have in dimension dim. */
static PetscInt ExpectedLength(MMVectorOption which, PetscInt dim)
{
  switch (VectorLength[which]) {
  case MM_LEN_TENSOR:
    return dim * dim;
  case MM_LEN_ROTATION:
    return dim == 2 ? 1 : 3;
  default:
    return dim;
  }
}

/* Checks what depends on the mesh dimension, once the mesh is read: every vector option has exactly
 * its length (a missing component would silently become 0), and the obstacle normal is a unit vector. */
PetscErrorCode MMOptionsCheckDimension(MPI_Comm comm, MMOptions *opt, PetscInt dim, PetscBool damped)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < MM_V_NUM; ++v) {
    const PetscInt n = ExpectedLength((MMVectorOption)v, dim);
    PetscCheck(opt->vec_count[v] < 0 || opt->vec_count[v] == n, comm, PETSC_ERR_USER_INPUT, "%s has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, VectorName[v], opt->vec_count[v], dim, n);
  }
  /* the default normal is +y in 2D, +z in 3D: only when none was given */
  if (opt->vec_count[MM_V_OBSTACLE_NORMAL] < 0) {
    PetscCall(PetscArrayzero(opt->obstacle_normal, MM_MAX_DIM));
    opt->obstacle_normal[dim - 1] = 1.0;
  }
  for (PetscInt d = 0; d < dim; ++d) nrm += PetscSqr(opt->obstacle_normal[d]);
  nrm = PetscSqrtReal(nrm);
  PetscCheck(PetscAbsReal(nrm - 1.0) < 1e-6, comm, PETSC_ERR_USER_INPUT, "-obstacle_normal must be a unit vector, its norm is %g", (double)nrm);
  for (PetscInt d = 0; d < dim; ++d) opt->obstacle_normal[d] /= nrm;
  if (!opt->obstacles_named && opt->n_rigid) PetscCall(MMObstacleSetPlane(&opt->obstacles[0], dim, opt->obstacle_point, opt->obstacle_normal));
  opt->mu_max = 0;
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) {
    if (b < opt->n_rigid) PetscCall(MMObstacleCheck(&opt->obstacles[b], comm, dim));
    opt->mu_max = PetscMax(opt->mu_max, opt->obstacles[b].mu);
  }
  PetscCall(MMLoadGroupsCheckDimension(comm, &opt->loads, dim, damped));
  PetscCall(MMBodiesCheckDimension(comm, opt->n_bodies, opt->bodies, dim));
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsDestroy(MMOptions *opt)
{
  PetscFunctionBeginUser;
  PetscCall(MMLoadGroupsDestroy(&opt->loads));
  PetscCall(MMBodiesDestroy(&opt->n_bodies, &opt->bodies));
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) PetscCall(MMObstacleDestroy(&opt->obstacles[b]));
  PetscCall(PetscFree(opt->obstacles));
  PetscFunctionReturn(0);
}
