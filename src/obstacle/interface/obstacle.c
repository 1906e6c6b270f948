/* The registry of rigid obstacle shapes (docs/method.md section 8) and what every shape shares: its
 * type, its motion, its parameters' checks once the dimension is known, its signed distance. A
 * shape declares its parameters and distance in its ops table (obstacleimpl.h); a new shape is one
 * folder impls/<type>/ and one line in MMObstacleRegisterAll. */
#include <string.h>
#include "../obstacleimpl.h"

static PetscFunctionList ObstacleList = NULL;

/*@
  MMObstacleRegister - Adds an obstacle shape to the registry, chosen by -obstacle_NAME_type

  Not collective

  Input Parameters:
+ type   - the shape's name
- create - the function that sets the shape's ops table (impls/<type>/)

  Level: developer

.seealso: `MMObstacleRegisterAll()`, `MMObstacleTypesList()`
@*/
PetscErrorCode MMObstacleRegister(const char type[], PetscErrorCode (*create)(MMObstacle *))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&ObstacleList, type, create));
  PetscFunctionReturn(0);
}

/* One shape: its create function (impls/<type>/) declared and registered, in one line. */
#define MM_OBSTACLE_REGISTER(type, create) \
  do { \
    PetscErrorCode create(MMObstacle *); \
    PetscCall(MMObstacleRegister(type, create)); \
  } while (0)

/*@
  MMObstacleRegisterAll - Registers the built-in shapes, plane, sphere, circle, cylinder and box,
  once

  Not collective

  Note:
  Does nothing while the registry holds shapes; MMObstacleFinalize() empties it.

  Level: developer

.seealso: `MMObstacleRegister()`, `MMObstacleFinalize()`
@*/
PetscErrorCode MMObstacleRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (ObstacleList) PetscFunctionReturn(0);
  MM_OBSTACLE_REGISTER("plane", MMObstacleCreate_Plane);
  MM_OBSTACLE_REGISTER("sphere", MMObstacleCreate_Sphere);
  MM_OBSTACLE_REGISTER("circle", MMObstacleCreate_Circle);
  MM_OBSTACLE_REGISTER("cylinder", MMObstacleCreate_Cylinder);
  MM_OBSTACLE_REGISTER("box", MMObstacleCreate_Box);
  MM_OBSTACLE_REGISTER("mesh", MMObstacleCreate_Mesh);
  PetscFunctionReturn(0);
}

/*@
  MMObstacleFinalize - Empties the registry of obstacle shapes

  Not collective

  Level: developer

.seealso: `MMObstacleRegisterAll()`
@*/
PetscErrorCode MMObstacleFinalize(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&ObstacleList));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleTypesList - Lists the registered shapes as "plane|sphere|circle|cylinder|box", for help
  strings and refusals

  Not collective

  Input Parameter:
. len - the size of buf

  Output Parameter:
. buf - the list, the names separated by |

  Note:
  Registers the built-in shapes first, if they are not yet.

  Level: developer

.seealso: `MMObstacleRegister()`, `MMObstacleSetFromOptions()`
@*/
PetscErrorCode MMObstacleTypesList(char buf[], size_t len)
{
  const char **types;
  int          n;

  PetscFunctionBeginUser;
  PetscCall(MMObstacleRegisterAll());
  PetscCall(PetscFunctionListGet(ObstacleList, &types, &n));
  buf[0] = 0;
  for (int i = 0; i < n; ++i) {
    if (!types[i] || !types[i][0]) continue;
    if (buf[0]) PetscCall(PetscStrlcat(buf, "|", len));
    PetscCall(PetscStrlcat(buf, types[i], len));
  }
  PetscCall(PetscFree(types));
  PetscFunctionReturn(0);
}

/* The shape's ops and its (zeroed) data, every parameter not set. */
PetscErrorCode MMObstacleSetType(MMObstacle *ob, MPI_Comm comm, const char type[])
{
  PetscErrorCode (*create)(MMObstacle *) = NULL;
  char types[256];

  PetscFunctionBeginUser;
  PetscCall(MMObstacleRegisterAll());
  PetscCall(PetscFunctionListFind(ObstacleList, type, &create));
  PetscCall(MMObstacleTypesList(types, sizeof(types)));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_type %s is not a known obstacle type: use %s", ob->name, type, types);
  PetscCall(PetscStrncpy(ob->type, type, sizeof(ob->type)));
  if (ob->ops && ob->ops->destroy && ob->data) PetscCall((*ob->ops->destroy)(ob));
  PetscCall(PetscFree(ob->data));
  PetscCall((*create)(ob));
  ob->curved  = ob->ops->curved;
  ob->faceted = ob->ops->faceted;
  PetscCall(PetscMalloc(ob->ops->datasize, &ob->data));
  PetscCall(PetscMemzero(ob->data, ob->ops->datasize));
  for (PetscInt i = 0; i < ob->ops->nparams; ++i) ((MMObstacleValue *)((char *)ob->data + ob->ops->params[i].offset))->n = -1;
  PetscFunctionReturn(0);
}

static MMObstacleValue *Value(const MMObstacle *ob, PetscInt i)
{
  return (MMObstacleValue *)((char *)ob->data + ob->ops->params[i].offset);
}

/* The index of parameter name in the shape's table, -1 if the shape has none of that name. */
static PetscInt FindParameter(const MMObstacleOps *ops, const char name[])
{
  for (PetscInt i = 0; ops && i < ops->nparams; ++i)
    if (!strcmp(ops->params[i].name, name)) return i;
  return -1;
}

/*@
  MMObstacleGetParameterNames - Gives the names of the shape's parameters, for a checkpoint's record
  of the physics

  Not collective

  Input Parameters:
+ ob  - the obstacle
- max - the most names names[] can hold

  Output Parameters:
+ n     - the number of parameters (0 without a shape)
- names - their names, the shape's own strings

  Note:
  A shape with more than max parameters is an error (PETSC_ERR_ARG_SIZ).

  Level: developer

.seealso: `MMObstacleGetParameter()`
@*/
PetscErrorCode MMObstacleGetParameterNames(const MMObstacle *ob, PetscInt max, PetscInt *n, const char *names[])
{
  PetscFunctionBeginUser;
  *n = ob->ops ? ob->ops->nparams : 0;
  PetscCheck(*n <= max, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Obstacle type %s has %" PetscInt_FMT " parameters, more than %" PetscInt_FMT, ob->type, *n, max);
  for (PetscInt i = 0; i < *n; ++i) names[i] = ob->ops->params[i].name;
  PetscFunctionReturn(0);
}

/*@
  MMObstacleGetParameter - Gives the first n values of a shape parameter, by its option suffix

  Not collective

  Input Parameters:
+ ob   - the obstacle
. name - the parameter's name, as in -obstacle_NAME_<name>
- n    - how many values

  Output Parameters:
+ v   - the n values; zeros if the shape has no parameter of that name
- has - whether it has one, or NULL

  Level: intermediate

.seealso: `MMObstacleGetParameterNames()`, `MMObstacleGetPlane()`
@*/
PetscErrorCode MMObstacleGetParameter(const MMObstacle *ob, const char name[], PetscInt n, PetscReal v[], PetscBool *has)
{
  const PetscInt i = FindParameter(ob->ops, name);

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < n; ++d) v[d] = i < 0 ? 0 : Value(ob, i)->v[d];
  if (has) *has = (PetscBool)(i >= 0);
  PetscFunctionReturn(0);
}

/*@
  MMObstacleCreatePlane - Makes the single plane of -obstacle_point and -obstacle_normal (without
  -obstacles), type plane

  Collective

  Input Parameters:
+ comm - the communicator
. name - the obstacle's name
- mu   - its friction coefficient

  Output Parameter:
. ob - the obstacle

  Note:
  Its point and normal are given by MMObstacleSetPlane() once the dimension is known.

  Level: intermediate

.seealso: `MMObstacleSetPlane()`, `MMObstacleSetFromOptions()`, `MMObstacleCheck()`
@*/
PetscErrorCode MMObstacleCreatePlane(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(ob->name, name, sizeof(ob->name)));
  ob->nvelocity = -1;
  ob->stop      = PETSC_MAX_REAL;
  ob->mu        = mu;
  PetscCall(MMObstacleSetType(ob, comm, "plane"));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleSetPlane - Sets a plane's point and normal

  Not collective

  Input Parameters:
+ ob     - the obstacle, a plane
. dim    - the number of entries given
. point  - a point of the plane, MM_MAX_DIM entries
- normal - its normal, MM_MAX_DIM entries

  Note:
  The values are checked, and the normal made unit, by MMObstacleCheck(). An obstacle that is not a
  plane is an error (PETSC_ERR_ARG_WRONG).

  Level: intermediate

.seealso: `MMObstacleCreatePlane()`, `MMObstacleGetPlane()`, `MMObstacleCheck()`
@*/
PetscErrorCode MMObstacleSetPlane(MMObstacle *ob, PetscInt dim, const PetscReal point[], const PetscReal normal[])
{
  const PetscInt ip = FindParameter(ob->ops, "point"), in = FindParameter(ob->ops, "normal");

  PetscFunctionBeginUser;
  PetscCheck(ip >= 0 && in >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Obstacle %s is not a plane", ob->name);
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    Value(ob, ip)->v[d] = point[d];
    Value(ob, in)->v[d] = normal[d];
  }
  Value(ob, ip)->n = Value(ob, in)->n = dim;
  PetscFunctionReturn(0);
}

/*@
  MMObstacleGetPlane - Gives a plane's point and normal; plane is false for another shape

  Not collective

  Input Parameter:
. ob - the obstacle

  Output Parameters:
+ point  - the plane's point, MM_MAX_DIM entries
. normal - its normal, MM_MAX_DIM entries
- plane  - whether the obstacle is a plane; point and normal are left untouched when it is not

  Note:
  A plane's point and normal (-initial_state static_sliding builds on one plane); *plane false for
  another shape.

  Level: intermediate

.seealso: `MMObstacleSetPlane()`, `MMObstacleGetParameter()`
@*/
PetscErrorCode MMObstacleGetPlane(const MMObstacle *ob, PetscReal point[], PetscReal normal[], PetscBool *plane)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrcmp(ob->type, "plane", plane));
  if (!*plane) PetscFunctionReturn(0);
  PetscCall(MMObstacleGetParameter(ob, "point", MM_MAX_DIM, point, NULL));
  PetscCall(MMObstacleGetParameter(ob, "normal", MM_MAX_DIM, normal, NULL));
  PetscFunctionReturn(0);
}

/* A parameter of the shape: given, with its entries, a direction nonzero (then made unit), a length > 0. */
static PetscErrorCode RequireParameter(const MMObstacle *ob, MPI_Comm comm, PetscInt dim, const MMObstacleParameter *p, MMObstacleValue *val)
{
  const char *what = p->name;
  PetscReal   nrm  = 0;

  PetscFunctionBeginUser;
  if (p->kind == MM_OBSTACLE_LENGTH) {
    PetscCheck(val->n >= 0, comm, PETSC_ERR_USER_INPUT, "Obstacle %s (type %s) needs -obstacle_%s_%s", ob->name, ob->type, ob->name, what);
    PetscCheck(val->v[0] > 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s %g must be > 0", ob->name, what, (double)val->v[0]);
    PetscFunctionReturn(0);
  }
  PetscCheck(val->n >= 0, comm, PETSC_ERR_USER_INPUT, "Obstacle %s (type %s) needs -obstacle_%s_%s, %" PetscInt_FMT " entries", ob->name, ob->type, ob->name, what, dim);
  PetscCheck(val->n == dim, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, ob->name, what, val->n, dim, dim);
  if (p->kind == MM_OBSTACLE_LENGTHS)
    for (PetscInt d = 0; d < dim; ++d) PetscCheck(val->v[d] > 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s entry %" PetscInt_FMT " is %g: each must be > 0", ob->name, what, d, (double)val->v[d]);
  if (p->kind != MM_OBSTACLE_DIRECTION) PetscFunctionReturn(0);
  for (PetscInt d = 0; d < dim; ++d) nrm += PetscSqr(val->v[d]);
  nrm = PetscSqrtReal(nrm);
  PetscCheck(nrm > 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s is the zero vector: it must give a direction", ob->name, what);
  for (PetscInt d = 0; d < dim; ++d) val->v[d] /= nrm;
  PetscFunctionReturn(0);
}

/* A parameter of another registered shape, given to this one, is refused rather than ignored; so
 * is the inside of a shape that has none. */
static PetscErrorCode RefuseOthers(const MMObstacle *ob, MPI_Comm comm)
{
  const char **types;
  int          n;

  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListGet(ObstacleList, &types, &n));
  for (int t = 0; t < n; ++t) {
    MMObstacle other;
    PetscErrorCode (*create)(MMObstacle *) = NULL;

    if (!types[t] || !types[t][0]) continue;
    PetscCall(PetscMemzero(&other, sizeof(other)));
    PetscCall(PetscFunctionListFind(ObstacleList, types[t], &create));
    PetscCall((*create)(&other));
    for (PetscInt i = 0; i < other.ops->nparams; ++i) {
      const char *what = other.ops->params[i].name;
      char        key[512];
      PetscBool   given;

      if (FindParameter(ob->ops, what) >= 0) continue;
      PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_%s", ob->name, what));
      PetscCall(PetscOptionsHasName(NULL, NULL, key, &given));
      PetscCheck(!given, comm, PETSC_ERR_USER_INPUT, "%s does not apply to an obstacle of type %s", key, ob->type);
    }
    for (PetscInt i = 0; other.ops->options && other.ops->options[i]; ++i) {
      const char *what = other.ops->options[i];
      char        key[512];
      PetscBool   given, own = PETSC_FALSE;

      for (PetscInt j = 0; ob->ops->options && ob->ops->options[j]; ++j) own = (PetscBool)(own || !strcmp(what, ob->ops->options[j]));
      if (own) continue;
      PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_%s", ob->name, what));
      PetscCall(PetscOptionsHasName(NULL, NULL, key, &given));
      PetscCheck(!given, comm, PETSC_ERR_USER_INPUT, "%s does not apply to an obstacle of type %s (it is an obstacle of type %s's)", key, ob->type, types[t]);
    }
  }
  PetscCall(PetscFree(types));
  PetscCheck(ob->ops->sided || !ob->inside, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_side inside does not apply to an obstacle of type %s: the body is on the side its normal points to", ob->name, ob->type);
  PetscFunctionReturn(0);
}

/*@
  MMObstacleCheck - Checks an obstacle once the dimension is known: its motion and mu, the shape's
  parameters required, another shape's refused

  Collective on comm

  Input Parameters:
+ ob   - the obstacle
. comm - the communicator a refusal is raised on
- dim  - the mesh's dimension

  Note:
  The parameters common to every shape, then the shape's own: its dimension, the others' refused,
  its own required.

  A direction parameter must be nonzero and is made unit; a length must be > 0. Another shape's
  parameters and an inside side the shape has not are refused only for an obstacle read under
  -obstacle_NAME_ (the plane of -obstacle_point reads no -obstacle_plane_*). Then the shape's own
  check, if it has one.

  Level: intermediate

.seealso: `MMObstacleSetFromOptions()`, `MMObstacleCreatePlane()`
@*/
PetscErrorCode MMObstacleCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  const MMObstacleOps *ops = ob->ops;

  PetscFunctionBeginUser;
  PetscCheck(ob->nvelocity < 0 || ob->nvelocity == dim, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_velocity has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, ob->name, ob->nvelocity, dim, dim);
  PetscCheck(ob->mu >= 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_mu %g must be >= 0", ob->name, (double)ob->mu);
  PetscCheck(ob->start >= 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_start %g must be >= 0 (a time)", ob->name, (double)ob->start);
  PetscCheck(ob->stop > ob->start, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_stop %g must be after -obstacle_%s_start %g", ob->name, (double)ob->stop, ob->name, (double)ob->start);
  PetscCheck(!ops->dim || dim == ops->dim, comm, PETSC_ERR_USER_INPUT, "Obstacle %s is a %s, a %" PetscInt_FMT "D shape, but the mesh is %" PetscInt_FMT "D: use type %s", ob->name, ob->type, ops->dim, dim, ops->other);
  if (ob->prefixed) PetscCall(RefuseOthers(ob, comm)); /* the plane of -obstacle_point reads no -obstacle_plane_* */
  for (PetscInt i = 0; i < ops->nparams; ++i) PetscCall(RequireParameter(ob, comm, dim, &ops->params[i], Value(ob, i)));
  if (ops->check) PetscCall((*ops->check)(ob, comm, dim));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleDistance - Computes the signed distance of a point to the obstacle and the outward
  normal there, by the shape's distance function

  Not collective

  Input Parameters:
+ ob  - the obstacle
. dim - the dimension
- x   - the point

  Output Parameters:
+ g - the signed distance
- n - its gradient, the obstacle's outward normal

  Note:
  The obstacle in its rest position: for a moving one, the caller subtracts
  MMObstacleDisplacement() from the point first.

  Level: intermediate

.seealso: `MMObstacleDisplacement()`, `MMObstacleCheck()`
@*/
PetscErrorCode MMObstacleDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscFunctionBeginUser;
  PetscCall((*ob->ops->distance)(ob, dim, x, g, n));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleVelocity - Gives the obstacle's velocity at time t

  Not collective

  Input Parameters:
+ ob  - the obstacle
. dim - the dimension
- t   - the time

  Output Parameter:
. V - the velocity: its velocity for start < t <= stop, else zero

  Note:
  Returns nothing (void).

  The obstacle's velocity at time t (the left limit at the start and stop times, as a step to t sees
  it).

  Level: intermediate

.seealso: `MMObstacleDisplacement()`
@*/
void MMObstacleVelocity(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal V[])
{
  const PetscBool on = (PetscBool)(t > ob->start && t <= ob->stop);
  for (PetscInt d = 0; d < dim; ++d) V[d] = on ? ob->velocity[d] : 0;
}

/*@
  MMObstacleDisplacement - Gives how far the obstacle has moved at time t

  Not collective

  Input Parameters:
+ ob  - the obstacle
. dim - the dimension
- t   - the time

  Output Parameter:
. c - the displacement

  Note:
  Returns nothing (void).

  c(t) = V (min(t, t_stop) - t_start)^+: how far the obstacle has moved at time t.

  Level: intermediate

.seealso: `MMObstacleVelocity()`, `MMObstacleDistance()`
@*/
void MMObstacleDisplacement(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal c[])
{
  const PetscReal s = PetscMax(0.0, PetscMin(t, ob->stop) - ob->start);
  for (PetscInt d = 0; d < dim; ++d) c[d] = ob->velocity[d] * s;
}

/*@
  MMObstacleDestroy - Frees the shape's data

  Not collective

  Input Parameter:
. ob - the obstacle

  Note:
  The MMObstacle struct itself is the caller's.

  Level: intermediate

.seealso: `MMObstacleSetFromOptions()`, `MMObstacleCreatePlane()`
@*/
PetscErrorCode MMObstacleDestroy(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  if (ob->ops && ob->ops->destroy && ob->data) PetscCall((*ob->ops->destroy)(ob));
  PetscCall(PetscFree(ob->data));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleDescribe - Gives the text by which a restart recognizes a shape's options that are not
  real parameters (a meshed obstacle's surface)

  Not collective

  Input Parameters:
+ ob  - the obstacle
- len - the size of text

  Output Parameter:
. text - the text, empty for a shape that has none

  Level: developer

.seealso: `MMObstacleView()`
@*/
PetscErrorCode MMObstacleDescribe(const MMObstacle *ob, char text[], size_t len)
{
  PetscFunctionBeginUser;
  text[0] = 0;
  if (ob->ops && ob->ops->describe) PetscCall((*ob->ops->describe)(ob, text, len));
  PetscFunctionReturn(0);
}

/* "(x, y[, z])" of n entries into buf. */
static PetscErrorCode VectorText(const PetscReal v[], PetscInt n, char buf[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buf, "(", len));
  for (PetscInt d = 0; d < n; ++d) {
    size_t used;
    PetscCall(PetscStrlen(buf, &used));
    PetscCall(PetscSNPrintf(buf + used, len - used, "%s%g", d ? ", " : "", (double)v[d]));
  }
  PetscCall(PetscStrlcat(buf, ")", len));
  PetscFunctionReturn(0);
}

/*@
  MMObstacleView - Prints one obstacle as set up (-obstacle_view): its shape, side, mu, the
  parameters given, its motion

  Collective on viewer

  Input Parameters:
+ ob     - the obstacle
- viewer - an ASCII viewer; another type prints nothing

  Note:
  -obstacle_view: one obstacle as set up (docs/reference.md, "Viewing the set-up"). Its parameters
  are the ones given: each shape's check refuses the others and completes the single plane's, so
  what is set is the shape's own. ASCII viewers only; printed once, by the viewer's first rank.

  A contact pair prints its slave and master surfaces and mu.

  Level: intermediate

.seealso: `MMObstacleCheck()`, `MMFrictionView()`
@*/
PetscErrorCode MMObstacleView(const MMObstacle *ob, PetscViewer viewer)
{
  PetscBool ascii;
  char      v[3][128];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  if (ob->pair) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "MMObstacle %s: contact pair, slave surface %s, master surface %s; friction coefficient %g\n", ob->name, ob->slave, ob->master, (double)ob->mu));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "MMObstacle %s: %s%s, the body %s; friction coefficient %g\n", ob->name, ob->type, ob->curved ? " (curved)" : "", ob->inside ? "inside" : "outside", (double)ob->mu));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  for (PetscInt i = 0; ob->ops && i < ob->ops->nparams; ++i) {
    const MMObstacleValue *val = Value(ob, i);
    if (val->n <= 0) continue;
    if (val->n == 1) PetscCall(PetscSNPrintf(v[0], sizeof(v[0]), "%g", (double)val->v[0]));
    else PetscCall(VectorText(val->v, val->n, v[0], sizeof(v[0])));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s %s\n", ob->ops->params[i].name, v[0]));
  }
  if (ob->ops && ob->ops->view) PetscCall((*ob->ops->view)(ob, viewer));
  if (ob->nvelocity > 0) {
    PetscCall(VectorText(ob->velocity, ob->nvelocity, v[2], sizeof(v[2])));
    if (ob->stop < PETSC_MAX_REAL) PetscCall(PetscViewerASCIIPrintf(viewer, "moves at velocity %s for %g < t <= %g\n", v[2], (double)ob->start, (double)ob->stop));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "moves at velocity %s from t = %g\n", v[2], (double)ob->start));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "fixed\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
