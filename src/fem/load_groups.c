/* The loads and boundary conditions as the user gives them (README "Loads in time"): gravity and
 * each named group of -dirichlet, -traction, -pressure and -point_force with its value and amplitude
 * in time (docs/method.md section 10). The three load kinds are one reader: a kind differs only by its
 * option, its help strings, whether its value is a scalar, and its refusal when the value is missing.
 * The groups are checked against the mesh where the loads are built (loads.c, loads_nodal.c). */
#include "fem.h"
#include "sys.h"

/* A later amplitude replaces an earlier one, as a later value of one option replaces an earlier
 * value: -gravity_amplitude table on the command line over an options file's -gravity_amplitude
 * ramp and -gravity_amplitude_time 0.1 drops that time, which belonged to the ramp. Data given after
 * the kind, or with it in no order, stay and are checked against it (src/fem/loads.c). A table
 * given after the kind replaces the kind. */
static PetscErrorCode DropReplacedAmplitudeData(const char prefix[], PetscBool *kind_set, MMAmplitudeOptions *a)
{
  char      kind[512], time[512], table[512];
  PetscInt  table_vs_kind = 0, time_vs_kind = 0, time_vs_table = 0;
  PetscBool is_table, timed;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(kind, sizeof(kind), "%s_amplitude", prefix));
  PetscCall(PetscSNPrintf(time, sizeof(time), "%s_amplitude_time", prefix));
  PetscCall(PetscSNPrintf(table, sizeof(table), "%s_amplitude_table", prefix));
  if (*kind_set && a->table[0]) PetscCall(MMOptionsOrder(table, kind, &table_vs_kind));
  if (table_vs_kind > 0) *kind_set = PETSC_FALSE; /* the table came last: the table kind */
  PetscCall(PetscStrcmp(a->kind, "table", &is_table));
  if (*kind_set && !is_table && a->table[0] && table_vs_kind < 0) a->table[0] = 0; /* a table replaced by a later kind */
  timed = (PetscBool)(*kind_set && !is_table && strcmp(a->kind, "constant"));
  if (a->time_set && !timed) {
    if (*kind_set) PetscCall(MMOptionsOrder(time, kind, &time_vs_kind));
    else if (a->table[0]) PetscCall(MMOptionsOrder(time, table, &time_vs_table));
    if (time_vs_kind < 0 || time_vs_table < 0) a->time_set = PETSC_FALSE; /* the time of a replaced ramp or halfsine */
  }
  PetscFunctionReturn(0);
}

/*@
  MMAmplitudeOptionsRead - Reads a load's amplitude in time: PREFIX_amplitude, PREFIX_amplitude_time
  and PREFIX_amplitude_table

  Collective

  Input Parameters:
+ PetscOptionsObject - the options block being read
. comm               - the run's communicator
- prefix             - the load's option, e.g. -gravity

  Output Parameter:
. a - the amplitude as the user gave it

  Note:
  The amplitude in time of a load, PREFIX_amplitude KIND, PREFIX_amplitude_time T and
  PREFIX_amplitude_table FILE (docs/method.md section 10); the kinds and their data are checked in
  src/fem/loads.c, where they are registered. A table given alone means the table kind.

  Level: developer

.seealso: `MMLoadGroupsSetFromOptions()`, `MMAmplitudeValue()`
@*/
PetscErrorCode MMAmplitudeOptionsRead(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char prefix[], MMAmplitudeOptions *a)
{
  char      key[512];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(a->kind, "constant", sizeof(a->kind)));
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude", prefix));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, key, "Amplitude in time multiplying this load: constant (1, the default), ramp (0 at t = 0 to 1 at _amplitude_time, then 1), halfsine (sin(pi t/T) for t in [0, T], then 0) or table (_amplitude_table)", a->kind, sizeof(a->kind), &set));
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude_time", prefix));
  PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(key, "The time T of the ramp or halfsine amplitude, > 0", NULL, a->time, &a->time, &a->time_set));
  PetscCall(MMOptionsCheckFinite(comm, key, &a->time, 1));
  a->table[0] = 0;
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude_table", prefix));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, key, "Two-column CSV file of the table amplitude: time,factor per line, times increasing, interpolated linearly and constant beyond the ends", a->table, sizeof(a->table), NULL));
  PetscCall(DropReplacedAmplitudeData(prefix, &set, a));
  if (!set && a->table[0]) PetscCall(PetscStrncpy(a->kind, "table", sizeof(a->kind)));
  PetscFunctionReturn(0);
}

/* -dirichlet NAME,...: each boundary's fixed components, value, velocity and amplitude. */
static PetscErrorCode ReadDirichlet(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMLoadGroups *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsSplitNames(comm, "-dirichlet", list, &n, &names));
  opt->n_dirichlet = n;
  PetscCall(PetscCalloc1(n, &opt->dirichlet));
  for (PetscInt b = 0; b < n; ++b) {
    MMDirichlet *bc = &opt->dirichlet[b];
    char         key[512];
    PetscInt     nc = MM_MAX_DIM + 1, comps[MM_MAX_DIM + 1];
    PetscBool    set;

    PetscCall(PetscStrallocpy(names[b], &bc->name));
    /* default: a clamp, fixing every component to zero */
    bc->ncomp = -1;
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_components", bc->name));
    PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_INT));
    PetscCall(PetscOptionsIntArray(key, "Displacement components fixed on this Dirichlet boundary (0=x,1=y,2=z), each at most once; default all (a clamp)", NULL, comps, &nc, &set));
    if (set) {
      PetscCheck(nc <= MM_MAX_DIM, comm, PETSC_ERR_USER_INPUT, "%s lists %" PetscInt_FMT " or more components; a node has at most %d", key, nc, MM_MAX_DIM);
      bc->ncomp = nc;
      for (PetscInt c = 0; c < nc; ++c) {
        bc->comps[c] = comps[c];
        for (PetscInt e = 0; e < c; ++e) PetscCheck(comps[e] != comps[c], comm, PETSC_ERR_USER_INPUT, "%s lists component %" PetscInt_FMT " twice: give each fixed component once", key, comps[c]);
      }
    }
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_value", bc->name));
    PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, key, "Displacement value of each fixed component, in the order of _components, times its _amplitude (default constant); default 0", MM_MAX_DIM, bc->values, &bc->nvalues));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_velocity", bc->name));
    PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, key, "Constant velocity of each fixed component, in the order of _components: the boundary moves as value a(t) + velocity t; default 0", MM_MAX_DIM, bc->velocity, &bc->nvelocity));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s", bc->name));
    PetscCall(MMAmplitudeOptionsRead(PetscOptionsObject, comm, key, &bc->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* A kind of load group: -KIND NAME,... and each group's -KIND_NAME_value and amplitude. */
typedef struct {
  const char *option;     /* "-traction" */
  const char *list_help;  /* the list's help string */
  const char *value_help; /* -KIND_NAME_value's help string */
  PetscBool   scalar;     /* one value (a pressure) rather than d entries */
  const char *missing;    /* what to give when _value is missing; NULL: it may be omitted (default 0) */
} LoadKind;

static const LoadKind Traction = {"-traction", "Comma-separated physical names of traction (Neumann) boundaries, boundary faces only; each takes -traction_NAME_value and -traction_NAME_amplitude", "Traction vector (force per unit area) on this boundary, d entries, times its _amplitude", PETSC_FALSE, NULL};
static const LoadKind Pressure = {"-pressure", "Comma-separated physical names of boundary groups under a pressure (a Physical Curve in 2D, Surface in 3D); each takes -pressure_NAME_value p and -pressure_NAME_amplitude", "Pressure p on this boundary (force per unit area, Pa; per unit length in 2D): the traction -p n along the facets' outward normal n, p > 0 pushing in, times its _amplitude", PETSC_TRUE, "the pressure (force per unit area, > 0 pushing in)"};
static const LoadKind PointForce = {"-point_force", "Comma-separated physical names of Physical Point groups carrying a concentrated force on each of their nodes; each takes -point_force_NAME_value and -point_force_NAME_amplitude", "Force on each node of this Physical Point group (N; per unit thickness in 2D), d entries, times its _amplitude", PETSC_FALSE, "the force fx,fy[,fz] on each node of the group"};

/* One group's value: d entries, or one scalar read as PETSc reads a real (a list is refused by name). */
static PetscErrorCode ReadValue(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const LoadKind *kind, const char key[], MMLoadGroup *g)
{
  PetscBool set;

  PetscFunctionBeginUser;
  if (!kind->scalar) {
    PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, key, kind->value_help, MM_MAX_DIM, g->value, &g->nvalues));
    PetscFunctionReturn(0);
  }
  PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(key, kind->value_help, NULL, g->value[0], &g->value[0], &set));
  PetscCall(MMOptionsCheckFinite(comm, key, &g->value[0], 1));
  g->nvalues = set ? 1 : -1;
  PetscFunctionReturn(0);
}

/* -KIND NAME,...: each group's value and amplitude. */
static PetscErrorCode ReadGroups(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const LoadKind *kind, PetscInt *n, MMLoadGroup **groups)
{
  char     list[PETSC_MAX_PATH_LEN] = "", **names;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, kind->option, kind->list_help, list, sizeof(list), NULL));
  PetscCall(MMOptionsSplitNames(comm, kind->option, list, n, &names));
  PetscCall(PetscCalloc1(*n, groups));
  for (PetscInt b = 0; b < *n; ++b) {
    MMLoadGroup *g = &(*groups)[b];
    char         key[512];

    PetscCall(PetscStrallocpy(names[b], &g->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "%s_%s_value", kind->option, names[b]));
    PetscCall(ReadValue(PetscOptionsObject, comm, kind, key, g));
    PetscCheck(!kind->missing || g->nvalues >= 0, comm, PETSC_ERR_USER_INPUT, "%s lists %s but %s is not given: give %s, or drop %s from %s", kind->option, names[b], key, kind->missing, names[b], kind->option);
    PetscCall(PetscSNPrintf(key, sizeof(key), "%s_%s", kind->option, names[b]));
    PetscCall(MMAmplitudeOptionsRead(PetscOptionsObject, comm, key, &g->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)*n, names));
  PetscFunctionReturn(0);
}

/*@
  MMLoadGroupsSetFromOptions - Reads gravity, the Dirichlet boundaries and the load groups from
  their options, each group in its own options block

  Collective

  Input Parameter:
. comm - the run's communicator

  Output Parameter:
. lg - the loads and boundary conditions as the user gave them

  Note:
  Every group, in its own options block (its heading in -help).

  Level: intermediate

.seealso: `MMLoadGroupsCheckDimension()`, `MMLoadGroupsDestroy()`, `MMAmplitudeOptionsRead()`
@*/
PetscErrorCode MMLoadGroupsSetFromOptions(MPI_Comm comm, MMLoadGroups *lg)
{
  char list[PETSC_MAX_PATH_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(lg, sizeof(*lg)));
  PetscOptionsBegin(comm, NULL, "mmcontact: boundary conditions and loads", "MMLoadGroups");
  PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, "-gravity", "Body-force acceleration gx,gy[,gz] (m/s^2), d entries, times -gravity_amplitude", MM_MAX_DIM, lg->gravity, &lg->ngravity));
  PetscCall(MMAmplitudeOptionsRead(PetscOptionsObject, comm, "-gravity", &lg->gravity_amplitude));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-dirichlet", "Comma-separated physical names of Dirichlet boundaries; each takes -dirichlet_NAME_components, -dirichlet_NAME_value and -dirichlet_NAME_velocity", list, sizeof(list), NULL));
  PetscCall(ReadDirichlet(PetscOptionsObject, comm, lg, list));
  PetscCall(ReadGroups(PetscOptionsObject, comm, &Traction, &lg->n_traction, &lg->traction));
  PetscCall(ReadGroups(PetscOptionsObject, comm, &Pressure, &lg->n_pressure, &lg->pressure));
  PetscCall(ReadGroups(PetscOptionsObject, comm, &PointForce, &lg->n_point_force, &lg->point_force));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/*@
  MMLoadGroupsCheckDimension - Checks what depends on the mesh dimension and completes each
  Dirichlet boundary's components

  Collective

  Input Parameters:
+ comm   - the run's communicator
. opt    - the loads and boundary conditions, their default components set on return
. dim    - the mesh's dimension
- damped - Rayleigh damping is on (a moving Dirichlet boundary is then refused)

  Note:
  What depends on the mesh dimension: gravity and each vector load d entries; each Dirichlet
  boundary's components (default all: a clamp), its values and velocities one per component.

  Level: intermediate

.seealso: `MMLoadGroupsSetFromOptions()`
@*/
PetscErrorCode MMLoadGroupsCheckDimension(MPI_Comm comm, MMLoadGroups *opt, PetscInt dim, PetscBool damped)
{
  const struct {
    const char        *option;
    PetscInt           n;
    const MMLoadGroup *g;
  } vector[] = {
    {"-traction",    opt->n_traction,    opt->traction   },
    {"-point_force", opt->n_point_force, opt->point_force}
  };

  PetscFunctionBeginUser;
  PetscCheck(opt->ngravity < 0 || opt->ngravity == dim, comm, PETSC_ERR_USER_INPUT, "-gravity has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, opt->ngravity, dim, dim);
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) {
    MMDirichlet *bc = &opt->dirichlet[b];
    if (bc->ncomp < 0) {
      bc->ncomp = dim;
      for (PetscInt c = 0; c < dim; ++c) bc->comps[c] = c;
    }
    for (PetscInt c = 0; c < bc->ncomp; ++c) PetscCheck(bc->comps[c] >= 0 && bc->comps[c] < dim, comm, PETSC_ERR_USER_INPUT, "-dirichlet_%s_components: component %" PetscInt_FMT " is not in [0, %" PetscInt_FMT ")", bc->name, bc->comps[c], dim);
    PetscCheck(bc->nvalues < 0 || bc->nvalues == bc->ncomp, comm, PETSC_ERR_USER_INPUT, "-dirichlet_%s_value has %" PetscInt_FMT " entries but the boundary fixes %" PetscInt_FMT " components (-dirichlet_%s_components, default all %" PetscInt_FMT "): give one value per fixed component", bc->name, bc->nvalues, bc->ncomp, bc->name, dim);
    PetscCheck(bc->nvelocity < 0 || bc->nvelocity == bc->ncomp, comm, PETSC_ERR_USER_INPUT, "-dirichlet_%s_velocity has %" PetscInt_FMT " entries but the boundary fixes %" PetscInt_FMT " components (-dirichlet_%s_components, default all %" PetscInt_FMT "): give one velocity per fixed component", bc->name, bc->nvelocity, bc->ncomp, bc->name, dim);
    /* the damping force of the moving boundary's velocity on the free dofs, C_fD v_D, is not in the
     * scheme (docs/method.md section 10): refuse rather than let the energy audit stop the run */
    PetscCheck(bc->nvelocity < 0 || !damped, comm, PETSC_ERR_SUP, "-dirichlet_%s_velocity with Rayleigh damping (-damping_mass, -damping_stiffness or -damping_ratio) is not supported: the damping force of a moving boundary is not in the scheme. Drop one of the two", bc->name);
  }
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(vector); ++k)
    for (PetscInt b = 0; b < vector[k].n; ++b) {
      const MMLoadGroup *g = &vector[k].g[b];
      PetscCheck(g->nvalues < 0 || g->nvalues == dim, comm, PETSC_ERR_USER_INPUT, "%s_%s_value has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, vector[k].option, g->name, g->nvalues, dim, dim);
    }
  PetscFunctionReturn(0);
}

/*@
  MMLoadGroupsDestroy - Frees what MMLoadGroupsSetFromOptions() allocated

  Not collective

  Input Parameter:
. lg - the loads and boundary conditions

  Level: intermediate

.seealso: `MMLoadGroupsSetFromOptions()`
@*/
PetscErrorCode MMLoadGroupsDestroy(MMLoadGroups *lg)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < lg->n_dirichlet; ++b) PetscCall(PetscFree(lg->dirichlet[b].name));
  for (PetscInt b = 0; b < lg->n_traction; ++b) PetscCall(PetscFree(lg->traction[b].name));
  for (PetscInt b = 0; b < lg->n_pressure; ++b) PetscCall(PetscFree(lg->pressure[b].name));
  for (PetscInt b = 0; b < lg->n_point_force; ++b) PetscCall(PetscFree(lg->point_force[b].name));
  PetscCall(PetscFree(lg->dirichlet));
  PetscCall(PetscFree(lg->traction));
  PetscCall(PetscFree(lg->pressure));
  PetscCall(PetscFree(lg->point_force));
  PetscFunctionReturn(0);
}
