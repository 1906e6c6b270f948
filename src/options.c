/* Every run option of mmcontact, declared in one place with its help string. */
#include "options.h"

const char *const MMMassTypes[] = {"modified", "standard", "MMMassType", "MM_MASS_", NULL};
const char *const MMInitialStates[] = {"given", "static_sliding", "MMInitialState", "MM_INITIAL_", NULL};
const char *const MMContactFormulations[] = {"condensed", "full", "MMContactFormulation", "MM_CONTACT_", NULL};

/* Reads a real vector option of up to MM_MAX_DIM entries; *n returns how many were given. */
static PetscErrorCode OptionsVector(PetscOptionItems *PetscOptionsObject, const char name[], const char help[], PetscReal v[], PetscInt *n)
{
  PetscInt  nmax = MM_MAX_DIM;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsRealArray(name, help, NULL, v, &nmax, &set));
  if (n) *n = set ? nmax : -1;
  PetscFunctionReturn(0);
}

/* Splits a comma-separated list of physical names into a freshly allocated array. */
static PetscErrorCode SplitNames(const char list[], PetscInt *n, char ***names)
{
  int argc;

  PetscFunctionBeginUser;
  *n     = 0;
  *names = NULL;
  if (!list[0]) PetscFunctionReturn(0);
  PetscCall(PetscStrToArray(list, ',', &argc, names));
  *n = argc;
  PetscFunctionReturn(0);
}

static PetscErrorCode ProcessDirichlet(PetscOptionItems *PetscOptionsObject, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(list, &n, &names));
  opt->n_dirichlet = n;
  PetscCall(PetscCalloc1(n, &opt->dirichlet));
  for (PetscInt b = 0; b < n; ++b) {
    MMDirichlet *bc = &opt->dirichlet[b];
    char         key[512];
    PetscInt     nc = MM_MAX_DIM, nv = MM_MAX_DIM;
    PetscBool    set;

    PetscCall(PetscStrallocpy(names[b], &bc->name));
    /* default: a clamp, fixing every component to zero */
    for (PetscInt c = 0; c < MM_MAX_DIM; ++c) bc->comps[c] = c;
    bc->ncomp = -1;
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_components", bc->name));
    PetscCall(PetscOptionsIntArray(key, "Displacement components fixed on this Dirichlet boundary (0=x,1=y,2=z); default all (a clamp)", NULL, bc->comps, &nc, &set));
    if (set) bc->ncomp = nc;
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_value", bc->name));
    PetscCall(PetscOptionsRealArray(key, "Constant displacement value of each fixed component, in the order of _components; default 0", NULL, bc->values, &nv, &set));
    PetscCheck(!set || bc->ncomp < 0 || nv == bc->ncomp, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-dirichlet_%s_value has %" PetscInt_FMT " entries but -dirichlet_%s_components has %" PetscInt_FMT ": give one value per fixed component", bc->name, nv, bc->name, bc->ncomp);
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

static PetscErrorCode ProcessTraction(PetscOptionItems *PetscOptionsObject, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(list, &n, &names));
  opt->n_traction = n;
  PetscCall(PetscCalloc1(n, &opt->traction));
  for (PetscInt b = 0; b < n; ++b) {
    char     key[512];
    PetscInt nv = MM_MAX_DIM;

    PetscCall(PetscStrallocpy(names[b], &opt->traction[b].name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-traction_%s_value", names[b]));
    PetscCall(PetscOptionsRealArray(key, "Constant traction vector (force per unit area) on this boundary", NULL, opt->traction[b].traction, &nv, NULL));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsProcess(MPI_Comm comm, MMOptions *opt)
{
  char      list[PETSC_MAX_PATH_LEN];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(opt, sizeof(*opt)));
  PetscOptionsBegin(comm, NULL, "mmcontact: modified-mass dynamic contact", "MMContact");
  opt->mesh_file[0] = 0;
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file (.msh) with named physical groups; triangles give plane strain, tetrahedra 3D", NULL, opt->mesh_file, opt->mesh_file, sizeof(opt->mesh_file), NULL));
  PetscCall(PetscStrcpy(opt->contact_name, "contact"));
  PetscCall(PetscOptionsString("-contact_boundary", "Physical name of the contact boundary", NULL, opt->contact_name, opt->contact_name, sizeof(opt->contact_name), NULL));
  list[0] = 0;
  PetscCall(PetscOptionsString("-dirichlet", "Comma-separated physical names of Dirichlet boundaries; each takes -dirichlet_NAME_components and -dirichlet_NAME_value", NULL, list, list, sizeof(list), NULL));
  PetscCall(ProcessDirichlet(PetscOptionsObject, opt, list));
  list[0] = 0;
  PetscCall(PetscOptionsString("-traction", "Comma-separated physical names of traction (Neumann) boundaries; each takes -traction_NAME_value", NULL, list, list, sizeof(list), NULL));
  PetscCall(ProcessTraction(PetscOptionsObject, opt, list));

  opt->E = 1.0;
  PetscCall(PetscOptionsReal("-E", "Young's modulus (Pa), > 0", NULL, opt->E, &opt->E, NULL));
  opt->nu = 0.3;
  PetscCall(PetscOptionsReal("-nu", "Poisson ratio, in (-1, 0.5)", NULL, opt->nu, &opt->nu, NULL));
  opt->rho = 1.0;
  PetscCall(PetscOptionsReal("-rho", "Mass density (kg/m^d), > 0", NULL, opt->rho, &opt->rho, NULL));
  PetscCall(OptionsVector(PetscOptionsObject, "-gravity", "Body-force acceleration gx,gy[,gz] (m/s^2)", opt->gravity, NULL));

  PetscCall(OptionsVector(PetscOptionsObject, "-u0_offset", "Initial displacement u0 = a + B x: the vector a", opt->u0_offset, NULL));
  {
    PetscInt n = MM_MAX_DIM * MM_MAX_DIM;
    PetscCall(PetscOptionsRealArray("-u0_gradient", "Initial displacement u0 = a + B x: the matrix B, row-major (d*d entries)", NULL, opt->u0_gradient, &n, &set));
    PetscCheck(!set || n == 4 || n == 9, comm, PETSC_ERR_USER_INPUT, "-u0_gradient needs d*d entries (4 in 2D, 9 in 3D), got %" PetscInt_FMT, n);
  }
  PetscCall(OptionsVector(PetscOptionsObject, "-v0", "Initial translation velocity vx,vy[,vz]", opt->v0, NULL));
  PetscCall(OptionsVector(PetscOptionsObject, "-omega", "Initial rigid angular velocity (rad/s): a scalar in 2D, a vector in 3D", opt->omega, NULL));
  PetscCall(OptionsVector(PetscOptionsObject, "-omega_center", "Centre of the initial rigid rotation", opt->omega_center, NULL));
  opt->initial_state = MM_INITIAL_GIVEN;
  PetscCall(PetscOptionsEnum("-initial_state", "Initial displacement: given (-u0_offset, -u0_gradient, contact dofs projected) or static_sliding (the body sliding along -v0 on the obstacle under its loads, with friction -mu)", NULL, MMInitialStates, (PetscEnum)opt->initial_state, (PetscEnum *)&opt->initial_state, NULL));

  PetscCall(OptionsVector(PetscOptionsObject, "-obstacle_point", "A point of the rigid obstacle plane", opt->obstacle_point, NULL));
  opt->obstacle_normal[1] = 1.0;
  PetscCall(OptionsVector(PetscOptionsObject, "-obstacle_normal", "Unit normal of the obstacle plane, pointing out of the obstacle towards the body (default +y in 2D, +z in 3D)", opt->obstacle_normal, NULL));
  PetscCall(OptionsVector(PetscOptionsObject, "-mesh_rotation", "Rigid rotation applied to the mesh when it is read: an angle (2D) or a rotation vector (3D), in radians", opt->mesh_rotation, NULL));
  PetscCall(OptionsVector(PetscOptionsObject, "-mesh_rotation_center", "Centre of the -mesh_rotation", opt->mesh_rotation_center, NULL));

  opt->mass_type = MM_MASS_MODIFIED;
  PetscCall(PetscOptionsEnum("-mass", "Mass matrix in time stepping: modified (normal mass of contact nodes removed) or standard", NULL, MMMassTypes, (PetscEnum)opt->mass_type, (PetscEnum *)&opt->mass_type, NULL));
  opt->lumped = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-mass_lumped", "Use the row-sum lumped mass instead of the consistent mass", NULL, opt->lumped, &opt->lumped, NULL));
  opt->contact = PETSC_TRUE;
  PetscCall(PetscOptionsBool("-contact", "Enforce unilateral contact; 0 gives linear elastodynamics on the same mesh (the contact boundary is then unused)", NULL, opt->contact, &opt->contact, NULL));

  opt->mu = 0.0;
  PetscCall(PetscOptionsReal("-mu", "Coulomb friction coefficient, >= 0 (0: frictionless, the friction loop is skipped)", NULL, opt->mu, &opt->mu, NULL));
  opt->friction_coulomb_tol = 1e-8;
  PetscCall(PetscOptionsReal("-friction_coulomb_tol", "The friction loop converges when the thresholds change less than -friction_snes_rtol (default 1e-10) and the discrete Coulomb residual is below this", NULL, opt->friction_coulomb_tol, &opt->friction_coulomb_tol, NULL));
  opt->friction_monitor = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-friction_monitor", "Print each friction iteration: threshold change, Coulomb residual, contraction factor, slipping and sticking node counts", NULL, opt->friction_monitor, &opt->friction_monitor, NULL));
  opt->contact_formulation = MM_CONTACT_CONDENSED;
  PetscCall(PetscOptionsEnum("-contact_formulation", "Contact VI on the contact dofs through the Delassus operator (condensed: K~ factored once per dt) or on all dofs (full: a factorization per VI iteration)", NULL, MMContactFormulations, (PetscEnum)opt->contact_formulation, (PetscEnum *)&opt->contact_formulation, NULL));
  opt->contact_tol = 1e-11;
  PetscCall(PetscOptionsReal("-contact_tol", "Contact solves stop when ||K~ w - b - f_c|| <= contact_tol ||b|| (on top of -contact_snes_rtol/atol)", NULL, opt->contact_tol, &opt->contact_tol, NULL));
  opt->audit_tol = 1e-6;
  PetscCall(PetscOptionsReal("-audit_tol", "Stop the run when a step's relative energy-balance residual exceeds this: the scheme's identity no longer holds", NULL, opt->audit_tol, &opt->audit_tol, NULL));
  PetscCall(PetscStrcpy(opt->output_dir, "output"));
  PetscCall(PetscOptionsString("-output_dir", "Directory for history.csv, solution.h5 and solution.xmf (created if missing)", NULL, opt->output_dir, opt->output_dir, sizeof(opt->output_dir), NULL));
  opt->output_every = 10;
  PetscCall(PetscOptionsInt("-output_every", "Write the HDF5 fields every k steps (0: only the initial and final state)", NULL, opt->output_every, &opt->output_every, NULL));
  opt->quiet = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-quiet", "Do not print the start-up report and closing summary", NULL, opt->quiet, &opt->quiet, NULL));
  PetscOptionsEnd();

  PetscCheck(opt->E > 0, comm, PETSC_ERR_USER_INPUT, "Young's modulus -E %g must be > 0", (double)opt->E);
  PetscCheck(opt->nu > -1.0 && opt->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -nu %g must lie in (-1, 0.5); nu >= 0.5 is incompressible, which P1 elements cannot represent", (double)opt->nu);
  PetscCheck(opt->rho > 0, comm, PETSC_ERR_USER_INPUT, "Density -rho %g must be > 0", (double)opt->rho);
  PetscCheck(opt->mu >= 0, comm, PETSC_ERR_USER_INPUT, "Friction coefficient -mu %g must be >= 0", (double)opt->mu);
  PetscCheck(opt->output_every >= 0, comm, PETSC_ERR_USER_INPUT, "-output_every %" PetscInt_FMT " must be >= 0", opt->output_every);
  PetscFunctionReturn(0);
}

/* Checks what depends on the mesh dimension, once the mesh is read. */
PetscErrorCode MMOptionsCheckDimension(MPI_Comm comm, MMOptions *opt, PetscInt dim)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  if (dim == 3 && opt->obstacle_normal[0] == 0 && opt->obstacle_normal[1] == 1 && opt->obstacle_normal[2] == 0) {
    opt->obstacle_normal[1] = 0;
    opt->obstacle_normal[2] = 1;
  }
  for (PetscInt d = 0; d < dim; ++d) nrm += PetscSqr(opt->obstacle_normal[d]);
  nrm = PetscSqrtReal(nrm);
  PetscCheck(PetscAbsReal(nrm - 1.0) < 1e-6, comm, PETSC_ERR_USER_INPUT, "-obstacle_normal must be a unit vector, its norm is %g", (double)nrm);
  for (PetscInt d = 0; d < dim; ++d) opt->obstacle_normal[d] /= nrm;
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) {
    MMDirichlet *bc = &opt->dirichlet[b];
    if (bc->ncomp < 0) bc->ncomp = dim;
    for (PetscInt c = 0; c < bc->ncomp; ++c) PetscCheck(bc->comps[c] >= 0 && bc->comps[c] < dim, comm, PETSC_ERR_USER_INPUT, "-dirichlet_%s_components: component %" PetscInt_FMT " is not in [0, %" PetscInt_FMT ")", bc->name, bc->comps[c], dim);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsDestroy(MMOptions *opt)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) PetscCall(PetscFree(opt->dirichlet[b].name));
  for (PetscInt b = 0; b < opt->n_traction; ++b) PetscCall(PetscFree(opt->traction[b].name));
  PetscCall(PetscFree(opt->dirichlet));
  PetscCall(PetscFree(opt->traction));
  PetscFunctionReturn(0);
}
