/* Every run option of mmcontact, declared in one place with its help string. */
#include "contact.h"
#include "appimpl.h"
#include <errno.h>
#include <stdlib.h>
#include <sys/stat.h>
#include "obstacle.h"
#include "sys.h"

const char *const MMInitialStates[] = {"given", "static_sliding", "static", "MMInitialState", "MM_INITIAL_", NULL};

/* What a vector option's length must be, once the dimension d is known. */
typedef enum {
  MM_LEN_DIM,     /* d entries */
  MM_LEN_TENSOR,  /* d*d entries */
  MM_LEN_ROTATION /* 1 entry in 2D (an angle), 3 in 3D (a vector) */
} MMVectorLength;

static const char *const VectorName[MM_V_NUM] = {"-gravity", "-u0_offset", "-u0_gradient", "-v0", "-omega", "-omega_center", "-obstacle_point", "-obstacle_normal", "-mesh_rotation", "-mesh_rotation_center", "-omega0"};
static const MMVectorLength VectorLength[MM_V_NUM] = {MM_LEN_DIM, MM_LEN_DIM, MM_LEN_TENSOR, MM_LEN_DIM, MM_LEN_ROTATION, MM_LEN_DIM, MM_LEN_DIM, MM_LEN_DIM, MM_LEN_ROTATION, MM_LEN_DIM, MM_LEN_ROTATION};

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

/* Splits a comma-separated list of physical names into a freshly allocated array. PetscStrToArray
 * would skip an empty name ("floor,,wall"), a typo that would drop an obstacle or a boundary. */
static PetscErrorCode SplitNames(MPI_Comm comm, const char option[], const char list[], PetscInt *n, char ***names)
{
  int    argc;
  size_t len = strlen(list);

  PetscFunctionBeginUser;
  *n     = 0;
  *names = NULL;
  if (!list[0]) PetscFunctionReturn(0);
  PetscCheck(list[0] != ',' && list[len - 1] != ',' && !strstr(list, ",,"), comm, PETSC_ERR_USER_INPUT, "%s %s has an empty name: give the names separated by single commas", option, list);
  for (const char *p = list; *p; ++p) PetscCheck(*p != ' ' && *p != '\t', comm, PETSC_ERR_USER_INPUT, "%s \"%s\" has a blank: give the names separated by commas, without blanks", option, list);
  PetscCall(PetscStrToArray(list, ',', &argc, names));
  *n = argc;
  /* a name given twice would make two objects of one name (two force columns, two bodies) */
  for (PetscInt b = 0; b < *n; ++b)
    for (PetscInt a = 0; a < b; ++a) {
      PetscBool same;
      PetscCall(PetscStrcmp((*names)[a], (*names)[b], &same));
      PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "%s %s names %s twice", option, list, (*names)[b]);
    }
  PetscFunctionReturn(0);
}

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

/* The amplitude in time of a load, PREFIX_amplitude KIND, PREFIX_amplitude_time T and
 * PREFIX_amplitude_table FILE (docs/method.md section 10); the kinds and their data are checked in
 * src/fem/loads.c, where they are registered. A table given alone means the table kind. */
static PetscErrorCode ProcessAmplitude(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char prefix[], MMAmplitudeOptions *a)
{
  char      key[512];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(a->kind, "constant", sizeof(a->kind)));
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude", prefix));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, "Amplitude in time multiplying this load: constant (1, the default), ramp (0 at t = 0 to 1 at _amplitude_time, then 1), halfsine (sin(pi t/T) for t in [0, T], then 0) or table (_amplitude_table)", a->kind, sizeof(a->kind), &set));
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude_time", prefix));
  PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(key, "The time T of the ramp or halfsine amplitude, > 0", NULL, a->time, &a->time, &a->time_set));
  PetscCall(CheckFinite(comm, key, &a->time, 1));
  a->table[0] = 0;
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_amplitude_table", prefix));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, "Two-column CSV file of the table amplitude: time,factor per line, times increasing, interpolated linearly and constant beyond the ends", a->table, sizeof(a->table), NULL));
  PetscCall(DropReplacedAmplitudeData(prefix, &set, a));
  if (!set && a->table[0]) PetscCall(PetscStrncpy(a->kind, "table", sizeof(a->kind)));
  PetscFunctionReturn(0);
}

static PetscErrorCode ProcessDirichlet(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(comm, "-dirichlet", list, &n, &names));
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
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "Displacement value of each fixed component, in the order of _components, times its _amplitude (default constant); default 0", MM_MAX_DIM, bc->values, &bc->nvalues));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s_velocity", bc->name));
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "Constant velocity of each fixed component, in the order of _components: the boundary moves as value a(t) + velocity t; default 0", MM_MAX_DIM, bc->velocity, &bc->nvelocity));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-dirichlet_%s", bc->name));
    PetscCall(ProcessAmplitude(PetscOptionsObject, comm, key, &bc->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

static PetscErrorCode ProcessTraction(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(comm, "-traction", list, &n, &names));
  opt->n_traction = n;
  PetscCall(PetscCalloc1(n, &opt->traction));
  for (PetscInt b = 0; b < n; ++b) {
    MMTraction *tr = &opt->traction[b];
    char        key[512];

    PetscCall(PetscStrallocpy(names[b], &tr->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-traction_%s_value", names[b]));
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "Traction vector (force per unit area) on this boundary, d entries, times its _amplitude", MM_MAX_DIM, tr->traction, &tr->nvalues));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-traction_%s", names[b]));
    PetscCall(ProcessAmplitude(PetscOptionsObject, comm, key, &tr->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* -pressure NAME,...: each a boundary group with its pressure and amplitude (src/fem/loads_nodal.c). */
static PetscErrorCode ProcessPressure(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(comm, "-pressure", list, &n, &names));
  opt->n_pressure = n;
  PetscCall(PetscCalloc1(n, &opt->pressure));
  for (PetscInt b = 0; b < n; ++b) {
    MMPressure *pr = &opt->pressure[b];
    char        key[512];

    PetscCall(PetscStrallocpy(names[b], &pr->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-pressure_%s_value", names[b]));
    PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
    PetscCall(PetscOptionsReal(key, "Pressure p on this boundary (force per unit area, Pa; per unit length in 2D): the traction -p n along the facets' outward normal n, p > 0 pushing in, times its _amplitude", NULL, pr->p, &pr->p, &pr->set));
    PetscCall(CheckFinite(comm, key, &pr->p, 1));
    PetscCheck(pr->set, comm, PETSC_ERR_USER_INPUT, "-pressure lists %s but %s is not given: give the pressure (force per unit area, > 0 pushing in), or drop %s from -pressure", names[b], key, names[b]);
    PetscCall(PetscSNPrintf(key, sizeof(key), "-pressure_%s", names[b]));
    PetscCall(ProcessAmplitude(PetscOptionsObject, comm, key, &pr->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* -point_force NAME,...: each a Physical Point group with its nodal force and amplitude. */
static PetscErrorCode ProcessPointForce(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, const char list[])
{
  char   **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(SplitNames(comm, "-point_force", list, &n, &names));
  opt->n_point_force = n;
  PetscCall(PetscCalloc1(n, &opt->point_force));
  for (PetscInt b = 0; b < n; ++b) {
    MMPointForce *pf = &opt->point_force[b];
    char          key[512];

    PetscCall(PetscStrallocpy(names[b], &pf->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-point_force_%s_value", names[b]));
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "Force on each node of this Physical Point group (N; per unit thickness in 2D), d entries, times its _amplitude", MM_MAX_DIM, pf->force, &pf->nvalues));
    PetscCheck(pf->nvalues >= 0, comm, PETSC_ERR_USER_INPUT, "-point_force lists %s but %s is not given: give the force fx,fy[,fz] on each node of the group, or drop %s from -point_force", names[b], key, names[b]);
    PetscCall(PetscSNPrintf(key, sizeof(key), "-point_force_%s", names[b]));
    PetscCall(ProcessAmplitude(PetscOptionsObject, comm, key, &pf->amplitude));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* One named obstacle of -obstacles: its type and every shape parameter (each type checks the ones
 * it needs, and refuses the others, in MMObstacleCheck once the dimension is known). */
static PetscErrorCode ProcessObstacle(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, MMObstacle *ob)
{
  char      key[512], type[32] = "plane", side[32] = "outside", types[128], help[256];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(MMObstacleTypesList(types, sizeof(types)));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_type", ob->name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Shape of this obstacle: %s (default plane)", types));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, help, type, sizeof(type), NULL));
  PetscCall(MMObstacleSetType(ob, comm, type));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_point", ob->name));
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "plane: a point of the plane; cylinder: a point on the axis; d entries", MM_MAX_DIM, ob->point, &ob->npoint));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_normal", ob->name));
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "plane: normal pointing out of the obstacle, towards the body (normalized), d entries", MM_MAX_DIM, ob->normal, &ob->nnormal));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_center", ob->name));
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "sphere, circle: the centre, d entries", MM_MAX_DIM, ob->center, &ob->ncenter));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_axis", ob->name));
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "cylinder: the axis direction (normalized), 3 entries", MM_MAX_DIM, ob->axis, &ob->naxis));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_radius", ob->name));
  PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(key, "sphere, circle, cylinder: the radius, > 0", NULL, ob->radius, &ob->radius, &ob->radius_set));
  PetscCall(CheckFinite(comm, key, &ob->radius, 1));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_side", ob->name));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, "sphere, circle, cylinder: outside (the body outside the shape: a bump) or inside (the body inside it: a bowl, a rail, a cavity)", side, sizeof(side), &set));
  {
    PetscBool out, in;
    PetscCall(PetscStrcmp(side, "outside", &out));
    PetscCall(PetscStrcmp(side, "inside", &in));
    PetscCheck(out || in, comm, PETSC_ERR_USER_INPUT, "%s %s: use outside or inside", key, side);
    ob->inside = in;
  }
  ob->mu = opt->mu;
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_mu", ob->name));
  PetscCall(OptionsReal(PetscOptionsObject, comm, key, "Coulomb friction coefficient against this obstacle, >= 0 (default -mu)", &ob->mu));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_velocity", ob->name));
  PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "Constant translation velocity of the obstacle between -obstacle_NAME_start and -obstacle_NAME_stop, d entries (default 0: fixed)", MM_MAX_DIM, ob->velocity, &ob->nvelocity));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_start", ob->name));
  PetscCall(OptionsReal(PetscOptionsObject, comm, key, "Time at which the obstacle starts moving, >= 0 (default 0)", &ob->start));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_stop", ob->name));
  PetscCall(OptionsReal(PetscOptionsObject, comm, key, "Time at which the obstacle stops, after -obstacle_NAME_start (default: never)", &ob->stop));
  PetscFunctionReturn(0);
}

/* Contact pair p of -contact_pairs, kept after the rigid obstacles in opt->obstacles so that each
 * contact node's constraint has one index, force column and mu (docs/method.md section 11): its
 * slave and master surfaces (physical names) and its friction coefficient. */
static PetscErrorCode ProcessPair(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt, char **names, PetscInt p)
{
  MMObstacle *ob = &opt->obstacles[opt->n_rigid + p];
  char        key[512];
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(ob->name, names[p], sizeof(ob->name)));
  PetscCall(PetscStrncpy(ob->type, "pair", sizeof(ob->type)));
  ob->pair = PETSC_TRUE;
  ob->stop = PETSC_MAX_REAL;
  ob->mu   = opt->mu;
  PetscCall(PetscSNPrintf(key, sizeof(key), "-contact_pair_%s_slave", ob->name));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, "Physical name of the pair's slave surface (a Physical Curve in 2D, Surface in 3D): its nodes carry the constraints and lose their normal mass", ob->slave, sizeof(ob->slave), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Contact pair %s has no slave surface: give -contact_pair_%s_slave NAME, a physical group of the mesh (the finer of the two surfaces)", ob->name, ob->name);
  PetscCall(PetscSNPrintf(key, sizeof(key), "-contact_pair_%s_master", ob->name));
  PetscCall(OptionsString(PetscOptionsObject, comm, key, "Physical name of the pair's master surface: the facets the slave nodes are projected on", ob->master, sizeof(ob->master), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Contact pair %s has no master surface: give -contact_pair_%s_master NAME, a physical group of the mesh on the other body", ob->name, ob->name);
  PetscCall(PetscSNPrintf(key, sizeof(key), "-contact_pair_%s_mu", ob->name));
  PetscCall(OptionsReal(PetscOptionsObject, comm, key, "Coulomb friction coefficient between the pair's surfaces, >= 0 (default -mu)", &ob->mu));
  PetscCheck(ob->mu >= 0, comm, PETSC_ERR_USER_INPUT, "-contact_pair_%s_mu %g: a friction coefficient is >= 0", ob->name, (double)ob->mu);
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
    PetscCall(PetscOptionsHasName(NULL, NULL, key, &own));
    if (own) {
      if (names[0]) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
      PetscCall(PetscStrlcat(names, key, sizeof(names)));
    }
  }
  PetscCheck(!own, comm, PETSC_ERR_USER_INPUT, "-mu %.6g is used nowhere: it is the default friction coefficient of the obstacles and contact pairs, and each sets its own (%s). Drop -mu, or drop the _mu of those that should take it", (double)opt->mu, names);
  PetscFunctionReturn(0);
}

/* -obstacles NAME,... or, without it, the single plane of -obstacle_point and -obstacle_normal
 * (completed once the dimension is known). */
static PetscErrorCode ProcessObstacles(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt)
{
  char     list[PETSC_MAX_PATH_LEN] = "", plist[PETSC_MAX_PATH_LEN] = "", **names, **pnames;
  PetscInt n, np;

  PetscFunctionBeginUser;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-obstacles", "Comma-separated names of the rigid obstacles; each takes -obstacle_NAME_type plane|sphere|circle|cylinder and its parameters. Each contact node is constrained against the one nearest to it in the reference configuration (default: one plane, -obstacle_point and -obstacle_normal)", list, sizeof(list), NULL));
  PetscCall(SplitNames(comm, "-obstacles", list, &n, &names));
  opt->obstacles_named = (PetscBool)(n > 0);
  PetscCheck(!n || (opt->vec_count[MM_V_OBSTACLE_POINT] < 0 && opt->vec_count[MM_V_OBSTACLE_NORMAL] < 0), comm, PETSC_ERR_USER_INPUT, "-obstacles %s and -obstacle_point/-obstacle_normal were both given: give the plane as one of the named obstacles (-obstacle_NAME_type plane -obstacle_NAME_point ... -obstacle_NAME_normal ...)", list);
  PetscCall(OptionsString(PetscOptionsObject, comm, "-contact_pairs", "Comma-separated names of contact pairs between two surfaces of the mesh (two elastic bodies); each takes -contact_pair_NAME_slave, -contact_pair_NAME_master and -contact_pair_NAME_mu. Without -obstacles, a run with pairs has no rigid obstacle", plist, sizeof(plist), NULL));
  PetscCall(SplitNames(comm, "-contact_pairs", plist, &np, &pnames));
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
    PetscCall(ProcessPair(PetscOptionsObject, comm, opt, pnames, p));
  }
  PetscCall(PetscStrToArrayDestroy((int)np, pnames));
  for (PetscInt b = 0; b < opt->n_rigid; ++b) {
    MMObstacle *ob = &opt->obstacles[b];
    ob->npoint = ob->nnormal = ob->ncenter = ob->naxis = ob->nvelocity = -1;
    ob->stop = PETSC_MAX_REAL;
    if (!n) {
      PetscCall(PetscStrncpy(ob->name, "plane", sizeof(ob->name)));
      PetscCall(MMObstacleSetType(ob, comm, "plane"));
      ob->mu = opt->mu;
      continue;
    }
    PetscCall(PetscStrncpy(ob->name, names[b], sizeof(ob->name)));
    PetscCall(ProcessObstacle(PetscOptionsObject, comm, opt, ob));
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscCall(CheckMuUsed(comm, opt));
  {
    PetscBool view; /* viewed in main.c once set up (MMObstacleView), as PETSc's -ksp_view */
    PetscCall(PetscOptionsName("-obstacle_view", "Print each obstacle and contact pair as set up, before the first step (shape, parameters, side, friction coefficient, motion): -obstacle_view, or -obstacle_view ascii:FILE to write it to FILE", "None", &view));
  }
  PetscFunctionReturn(0);
}

/* -bodies NAME,...: each body a physical group of cells with its own material and initial velocity,
 * each defaulting to the whole mesh's (so -E, -nu, -rho and -v0 must be read first). The cells and
 * the groups are checked against the mesh in src/fem/material.c. */
static PetscErrorCode ProcessBodies(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMOptions *opt)
{
  char     list[PETSC_MAX_PATH_LEN] = "", **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-bodies", "Comma-separated names of the bodies, each a physical group of cells (-body_NAME_group) with its own -body_NAME_E, _nu, _rho and _v0; every cell must be in exactly one body (default: one body, the whole mesh, of -E, -nu, -rho and -v0)", list, sizeof(list), NULL));
  PetscCall(SplitNames(comm, "-bodies", list, &n, &names));
  opt->n_bodies = n;
  PetscCall(PetscCalloc1(n, &opt->bodies));
  for (PetscInt b = 0; b < n; ++b) {
    MMBodyOptions *body = &opt->bodies[b];
    char           key[512];

    PetscCall(PetscStrallocpy(names[b], &body->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_group", body->name));
    PetscCall(OptionsString(PetscOptionsObject, comm, key, "Physical group of this body's cells: a Physical Surface (2D) or Physical Volume (3D) of the mesh; required", body->group, sizeof(body->group), &body->group_set));
    body->E   = opt->E;
    body->nu  = opt->nu;
    body->rho = opt->rho;
    body->elasticity = opt->elasticity;
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_elasticity", body->name));
    PetscCall(OptionsEnum(PetscOptionsObject, comm, key, "This body's elasticity law: linear, svk or neohookean (default -elasticity)", MMElasticityTypes, (PetscEnum *)&body->elasticity));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_E", body->name));
    PetscCall(OptionsReal(PetscOptionsObject, comm, key, "This body's Young's modulus (Pa), > 0 (default -E)", &body->E));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_nu", body->name));
    PetscCall(OptionsReal(PetscOptionsObject, comm, key, "This body's Poisson ratio, in (-1, 0.5), at most 0.4995 with a finite-strain law and 0.49999995 with linear (default -nu)", &body->nu));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_rho", body->name));
    PetscCall(OptionsReal(PetscOptionsObject, comm, key, "This body's mass density (kg/m^d), > 0 (default -rho)", &body->rho));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->v0[d] = opt->v0[d];
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_v0", body->name));
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "This body's initial translation velocity, d entries (default -v0); -omega adds the same rigid rotation to every body", MM_MAX_DIM, body->v0, &body->nv0));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->omega0[d] = opt->omega0[d];
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_omega0", body->name));
    PetscCall(OptionsRealArray(PetscOptionsObject, comm, key, "This body's initial rigid angular velocity (rad/s) about its own centre of mass, added to its _v0: a scalar in 2D, a vector in 3D (default -omega0)", MM_MAX_DIM, body->omega0, &body->nomega0));
    body->omega0_set = (PetscBool)(body->nomega0 >= 0 || opt->vec_count[MM_V_OMEGA0] >= 0);
  }
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* A nearly incompressible material (docs/reference.md, "Large rotations and finite strain", "Nearly
 * incompressible materials"): P1 elements lock volumetrically,
 * and K~ holds a volumetric stiffness lambda above the shear one mu, lambda/mu = 2 nu / (1 - 2 nu).
 * The linear law's energy balance then sums terms lambda/mu times larger than the energy it checks:
 * on the D1 disk its residual is 60 to 120 eps lambda/mu from lambda/mu = 5e4 to 5e7, and the audit
 * (-audit_tol 1e-6) stops the run at 5e8; nu <= 0.49999995 (lambda/mu <= 1e7) keeps the residual at
 * 2.6e-7 at most. The finite-strain laws fail earlier, not by round-off: under the pressures of an
 * impact (of order lambda times the locked volume change) the neo-Hookean tangent loses its
 * definiteness and K~'s Cholesky factor stops ("Diagonal must be real and nonnegative", D1 at
 * lambda/mu = 2.5e3), and the svk step's Newton iteration diverges (D1 at 1e4); both hold their
 * audits at lambda/mu = 999, nu = 0.4995 (tests/test_limits_and_advice.py). A harder impact can still
 * turn the tangent indefinite there: the run then stops naming -ts_dt (src/contact/interface/pc_schursplit.c). */
#define MM_NU_MAX_LINEAR 0.49999995
#define MM_NU_MAX_FINITE 0.4995

static PetscErrorCode CheckNearlyIncompressible(MPI_Comm comm, const char option[], PetscReal nu, MMElasticityType law)
{
  const PetscBool finite = (PetscBool)(law != MM_ELASTICITY_LINEAR);
  const PetscReal numax  = finite ? MM_NU_MAX_FINITE : MM_NU_MAX_LINEAR;

  PetscFunctionBeginUser;
  PetscCheck(nu <= numax, comm, PETSC_ERR_USER_INPUT, "Poisson ratio %s %.10g is too close to 0.5 for -elasticity %s: lambda/mu = 2 nu/(1 - 2 nu) = %.3g, P1 elements lock volumetrically and K~'s conditioning grows as lambda/mu, %s. The largest accepted value with -elasticity %s is %.10g (lambda/mu %.3g; docs/reference.md, \"Large rotations and finite strain\")", option, (double)nu, MMElasticityTypes[law], (double)(2 * nu / (1 - 2 * nu)),
             finite ? "and under contact pressures the finite-strain step's tangent turns indefinite or its Newton iteration diverges" : "and the energy audit's round-off (about 100 eps lambda/mu) reaches -audit_tol", MMElasticityTypes[law], (double)numax, (double)(2 * numax / (1 - 2 * numax)));
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
  if (!opt->n_bodies) PetscCall(CheckNearlyIncompressible(comm, "-nu", opt->nu, opt->elasticity));
  for (PetscInt b = 0; b < opt->n_bodies; ++b) {
    const MMBodyOptions *body = &opt->bodies[b];
    PetscCheck(body->group_set && body->group[0], comm, PETSC_ERR_USER_INPUT, "-bodies: body %s has no cells: give -body_%s_group GROUP, the physical group (a Physical %s) of its cells", body->name, body->name, "Surface in 2D, Volume in 3D");
    PetscCheck(body->E > 0, comm, PETSC_ERR_USER_INPUT, "Young's modulus -body_%s_E %g must be > 0", body->name, (double)body->E);
    PetscCheck(body->nu > -1.0, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -body_%s_nu %.6g must lie in (-1, 0.5): nu <= -1 makes the shear modulus E / (2 (1 + nu)) infinite or negative, an unstable material", body->name, (double)body->nu);
    PetscCheck(body->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -body_%s_nu %.6g must lie in (-1, 0.5): nu >= 0.5 is incompressible, which P1 elements cannot represent", body->name, (double)body->nu);
    PetscCheck(body->rho > 0, comm, PETSC_ERR_USER_INPUT, "Density -body_%s_rho %g must be > 0", body->name, (double)body->rho);
    {
      char key[512];

      PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_nu", body->name));
      PetscCall(CheckNearlyIncompressible(comm, key, body->nu, body->elasticity));
    }
  }
  PetscCheck(opt->mu >= 0, comm, PETSC_ERR_USER_INPUT, "Friction coefficient -mu %g must be >= 0", (double)opt->mu);
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsProcess(MPI_Comm comm, MMOptions *opt)
{
  char list[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(opt, sizeof(*opt)));
  PetscOptionsBegin(comm, NULL, "mmcontact: modified-mass dynamic contact", "MMContact");
  opt->mesh_file[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-mesh", "gmsh mesh file (.msh, format 2.2 or 4.1) with named physical groups; first-order triangles give plane strain, first-order tetrahedra 3D", opt->mesh_file, sizeof(opt->mesh_file), NULL));
  PetscCall(PetscStrcpy(opt->contact_name, "contact"));
  PetscCall(OptionsString(PetscOptionsObject, comm, "-contact_boundary", "Physical name of the contact boundary (a Physical Curve in 2D, Surface in 3D)", opt->contact_name, sizeof(opt->contact_name), NULL));
  list[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-dirichlet", "Comma-separated physical names of Dirichlet boundaries; each takes -dirichlet_NAME_components, -dirichlet_NAME_value and -dirichlet_NAME_velocity", list, sizeof(list), NULL));
  PetscCall(ProcessDirichlet(PetscOptionsObject, comm, opt, list));
  list[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-traction", "Comma-separated physical names of traction (Neumann) boundaries, boundary faces only; each takes -traction_NAME_value and -traction_NAME_amplitude", list, sizeof(list), NULL));
  PetscCall(ProcessTraction(PetscOptionsObject, comm, opt, list));
  list[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-pressure", "Comma-separated physical names of boundary groups under a pressure (a Physical Curve in 2D, Surface in 3D); each takes -pressure_NAME_value p and -pressure_NAME_amplitude", list, sizeof(list), NULL));
  PetscCall(ProcessPressure(PetscOptionsObject, comm, opt, list));
  list[0] = 0;
  PetscCall(OptionsString(PetscOptionsObject, comm, "-point_force", "Comma-separated physical names of Physical Point groups carrying a concentrated force on each of their nodes; each takes -point_force_NAME_value and -point_force_NAME_amplitude", list, sizeof(list), NULL));
  PetscCall(ProcessPointForce(PetscOptionsObject, comm, opt, list));

  opt->E = 1.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-E", "Young's modulus (Pa), > 0", &opt->E));
  opt->nu = 0.3;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-nu", "Poisson ratio, in (-1, 0.5): at most 0.4995 with -elasticity svk or neohookean, 0.49999995 with linear (P1 volumetric locking)", &opt->nu));
  opt->rho = 1.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-rho", "Mass density (kg/m^d), > 0", &opt->rho));
  opt->elasticity = MM_ELASTICITY_LINEAR;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-elasticity", "Elasticity law: linear (the small-strain model, rotations strain the body), svk (St. Venant-Kirchhoff) or neohookean (compressible neo-Hookean), both finite strain with the same E and nu, energy and momentum exact per step (docs/method.md section 13)", MMElasticityTypes, (PetscEnum *)&opt->elasticity));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_GRAVITY, "Body-force acceleration gx,gy[,gz] (m/s^2), d entries, times -gravity_amplitude", opt->gravity));
  PetscCall(ProcessAmplitude(PetscOptionsObject, comm, "-gravity", &opt->gravity_amplitude));

  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_U0_OFFSET, "Initial displacement u0 = a + B x: the vector a, d entries", opt->u0_offset));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_U0_GRADIENT, "Initial displacement u0 = a + B x: the matrix B, row-major, d*d entries", opt->u0_gradient));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_V0, "Initial translation velocity vx,vy[,vz], d entries", opt->v0));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA, "Initial rigid angular velocity (rad/s): a scalar in 2D, a vector in 3D", opt->omega));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA_CENTER, "Centre of the initial rigid rotation, d entries", opt->omega_center));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OMEGA0, "Initial rigid angular velocity (rad/s) about the centre of mass, of each body with -bodies, added to -v0 and -omega: a scalar in 2D, a vector in 3D", opt->omega0));
  opt->initial_state = MM_INITIAL_GIVEN;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-initial_state", "Initial displacement: given (-u0_offset, -u0_gradient, contact dofs projected), static_sliding (the body sliding along the tangential part of -v0 on the obstacle under its loads, with friction -mu; the normal part of -v0 is dropped) or static (the static, frictionless contact problem K u0 = L(0) under the loads at t = 0, then the dynamics from u0 with -v0)", MMInitialStates, (PetscEnum *)&opt->initial_state));
  PetscCall(ProcessBodies(PetscOptionsObject, comm, opt));

  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OBSTACLE_POINT, "A point of the rigid obstacle plane, d entries", opt->obstacle_point));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_OBSTACLE_NORMAL, "Unit normal of the obstacle plane, pointing out of the obstacle towards the body, d entries (default +y in 2D, +z in 3D)", opt->obstacle_normal));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_MESH_ROTATION, "Rigid rotation applied to the mesh when it is read: an angle (2D) or a rotation vector (3D), in radians", opt->mesh_rotation));
  PetscCall(OptionsVector(PetscOptionsObject, comm, opt, MM_V_MESH_ROTATION_CENTER, "Centre of the -mesh_rotation, d entries", opt->mesh_rotation_center));


  opt->mu = 0.0;
  PetscCall(OptionsReal(PetscOptionsObject, comm, "-mu", "Coulomb friction coefficient, >= 0 (0: frictionless, the friction loop is skipped); the default of each -obstacle_NAME_mu and -contact_pair_NAME_mu (refused when each of them is given: it would be used nowhere)", &opt->mu));
  PetscCall(ProcessObstacles(PetscOptionsObject, comm, opt));
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
  if (!opt->obstacles_named && opt->n_rigid) {
    MMObstacle *ob = &opt->obstacles[0];
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
      ob->point[d]  = opt->obstacle_point[d];
      ob->normal[d] = opt->obstacle_normal[d];
    }
    ob->npoint = ob->nnormal = dim;
  }
  opt->mu_max = 0;
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) {
    if (b < opt->n_rigid) PetscCall(MMObstacleCheck(&opt->obstacles[b], comm, dim));
    opt->mu_max = PetscMax(opt->mu_max, opt->obstacles[b].mu);
  }
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
  for (PetscInt b = 0; b < opt->n_bodies; ++b) {
    const MMBodyOptions *body = &opt->bodies[b];
    PetscCheck(body->nv0 < 0 || body->nv0 == dim, comm, PETSC_ERR_USER_INPUT, "-body_%s_v0 has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, body->name, body->nv0, dim, dim);
    PetscCheck(body->nomega0 < 0 || body->nomega0 == (dim == 2 ? 1 : 3), comm, PETSC_ERR_USER_INPUT, "-body_%s_omega0 has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %d (an angular velocity is a scalar in 2D, a vector in 3D)", body->name, body->nomega0, dim, dim == 2 ? 1 : 3);
  }
  for (PetscInt b = 0; b < opt->n_traction; ++b) {
    const MMTraction *tr = &opt->traction[b];
    PetscCheck(tr->nvalues < 0 || tr->nvalues == dim, comm, PETSC_ERR_USER_INPUT, "-traction_%s_value has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, tr->name, tr->nvalues, dim, dim);
  }
  for (PetscInt b = 0; b < opt->n_point_force; ++b) {
    const MMPointForce *pf = &opt->point_force[b];
    PetscCheck(pf->nvalues == dim, comm, PETSC_ERR_USER_INPUT, "-point_force_%s_value has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, pf->name, pf->nvalues, dim, dim);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsDestroy(MMOptions *opt)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) PetscCall(PetscFree(opt->dirichlet[b].name));
  for (PetscInt b = 0; b < opt->n_traction; ++b) PetscCall(PetscFree(opt->traction[b].name));
  for (PetscInt b = 0; b < opt->n_pressure; ++b) PetscCall(PetscFree(opt->pressure[b].name));
  for (PetscInt b = 0; b < opt->n_point_force; ++b) PetscCall(PetscFree(opt->point_force[b].name));
  PetscCall(PetscFree(opt->pressure));
  PetscCall(PetscFree(opt->point_force));
  for (PetscInt b = 0; b < opt->n_bodies; ++b) PetscCall(PetscFree(opt->bodies[b].name));
  PetscCall(PetscFree(opt->bodies));
  PetscCall(PetscFree(opt->dirichlet));
  PetscCall(PetscFree(opt->traction));
  PetscCall(PetscFree(opt->obstacles));
  PetscFunctionReturn(0);
}

/* Before PetscInitialize, which reads the options files and would stop with a traceback on their
 * first defect: a file that cannot be opened, or one that starts with a UTF-8 byte order mark (some
 * editors write one; PETSc takes it for the first option's name), or a directory. Plain C: PETSc is not up yet, so
 * the message is printed by the first rank alone (the launcher's rank variable), and every rank
 * exits with MM_EXIT_USAGE. Returns 0 when the files are fine. */
int MMOptionsCheckFiles(int argc, char **argv)
{
  const char *rank = getenv("OMPI_COMM_WORLD_RANK");
  const int   first = !rank || !strcmp(rank, "0");

  for (int i = 1; i < argc; ++i) {
    FILE         *f;
    struct stat   st;
    unsigned char head[3] = {0, 0, 0};
    const char   *name;
    size_t        n;

    if (strcmp(argv[i], "-options_file") && strcmp(argv[i], "-options_file_yaml")) continue;
    name = i + 1 < argc ? argv[i + 1] : NULL;
    if (!name || name[0] == '-' || !name[0]) {
      if (first) fprintf(stderr, "mmcontact error: %s was given without a file name: write \"%s FILE\"\n", argv[i], argv[i]);
      return MM_EXIT_USAGE;
    }
    if (!stat(name, &st) && S_ISDIR(st.st_mode)) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s is a directory: name a file of options in it, e.g. %s/case.opts\n", name, name);
      return MM_EXIT_USAGE;
    }
    if (!(f = fopen(name, "rb"))) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s cannot be read: %s\n", name, strerror(errno));
      return MM_EXIT_USAGE;
    }
    n = fread(head, 1, sizeof(head), f);
    fclose(f);
    if (n == 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s starts with a UTF-8 byte order mark (bytes EF BB BF), which PETSc reads as part of the first option: save it as UTF-8 without a byte order mark (or plain ASCII)\n", name);
      return MM_EXIT_USAGE;
    }
  }
  return 0;
}

/* The problem as fem reads it: plain data, the arrays borrowed from opt for the set-up. */
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
  pb->static_sliding = (PetscBool)(opt->initial_state == MM_INITIAL_STATIC_SLIDING);
  pb->quiet          = opt->quiet;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    pb->obstacle_point[d]  = opt->obstacle_point[d];
    pb->obstacle_normal[d] = opt->obstacle_normal[d];
  }
  PetscFunctionReturn(0);
}

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
  pb->gravity           = opt->gravity;
  pb->gravity_amplitude = &opt->gravity_amplitude;
  pb->n_dirichlet       = opt->n_dirichlet;
  pb->dirichlet         = opt->dirichlet;
  pb->n_traction        = opt->n_traction;
  pb->traction          = opt->traction;
  pb->n_pressure        = opt->n_pressure;
  pb->pressure          = opt->pressure;
  pb->n_point_force     = opt->n_point_force;
  pb->point_force       = opt->point_force;
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
  pb->n_dirichlet  = opt->n_dirichlet;
  pb->dirichlet    = opt->dirichlet;
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
  pb->dirichlet = (PetscBool)(opt->n_dirichlet > 0);
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) {
    for (PetscInt c = 0; c < opt->dirichlet[b].nvalues; ++c)
      if (opt->dirichlet[b].values[c] != 0) pb->dirichlet_nonzero = PETSC_TRUE;
    for (PetscInt c = 0; c < opt->dirichlet[b].nvelocity; ++c)
      if (opt->dirichlet[b].velocity[c] != 0) pb->dirichlet_nonzero = PETSC_TRUE;
  }
  pb->E                 = opt->E;
  pb->nu                = opt->nu;
  pb->rho               = opt->rho;
  pb->quiet             = opt->quiet;
  PetscFunctionReturn(0);
}
