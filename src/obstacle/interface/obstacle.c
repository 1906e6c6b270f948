/* The registry of rigid obstacle shapes: each type sets the check of its parameters and its signed
 * distance (docs/method.md section 8). A new shape is one file and one line in MMObstacleRegisterAll. */
#include "../obstacleimpl.h"

static PetscFunctionList ObstacleList = NULL;

PetscErrorCode MMObstacleRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (ObstacleList) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListAdd(&ObstacleList, "plane", MMObstacleCreate_Plane));
  PetscCall(PetscFunctionListAdd(&ObstacleList, "sphere", MMObstacleCreate_Sphere));
  PetscCall(PetscFunctionListAdd(&ObstacleList, "circle", MMObstacleCreate_Circle));
  PetscCall(PetscFunctionListAdd(&ObstacleList, "cylinder", MMObstacleCreate_Cylinder));
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleFinalize(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&ObstacleList));
  PetscFunctionReturn(0);
}

/* "plane|sphere|circle|cylinder", for help strings and refusals. */
PetscErrorCode MMObstacleTypesList(char buf[], size_t len)
{
  const char *types[] = {"plane", "sphere", "circle", "cylinder"};

  PetscFunctionBeginUser;
  buf[0] = 0;
  for (size_t i = 0; i < sizeof(types) / sizeof(types[0]); ++i) {
    if (i) PetscCall(PetscStrlcat(buf, "|", len));
    PetscCall(PetscStrlcat(buf, types[i], len));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleSetType(MMObstacle *ob, MPI_Comm comm, const char type[])
{
  PetscErrorCode (*create)(MMObstacle *) = NULL;
  char types[128];

  PetscFunctionBeginUser;
  PetscCall(MMObstacleRegisterAll());
  PetscCall(PetscFunctionListFind(ObstacleList, type, &create));
  PetscCall(MMObstacleTypesList(types, sizeof(types)));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_type %s is not a known obstacle type: use %s", ob->name, type, types);
  PetscCall(PetscStrncpy(ob->type, type, sizeof(ob->type)));
  PetscCall((*create)(ob));
  PetscFunctionReturn(0);
}

/* The parameters common to every shape, then the shape's own. */
PetscErrorCode MMObstacleCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCheck(ob->nvelocity < 0 || ob->nvelocity == dim, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_velocity has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, ob->name, ob->nvelocity, dim, dim);
  PetscCheck(ob->mu >= 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_mu %g must be >= 0", ob->name, (double)ob->mu);
  PetscCheck(ob->start >= 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_start %g must be >= 0 (a time)", ob->name, (double)ob->start);
  PetscCheck(ob->stop > ob->start, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_stop %g must be after -obstacle_%s_start %g", ob->name, (double)ob->stop, ob->name, (double)ob->start);
  PetscCall((*ob->check)(ob, comm, dim));
  PetscFunctionReturn(0);
}

/* c(t) = V (min(t, t_stop) - t_start)^+: how far the obstacle has moved at time t. */
/* The obstacle's velocity at time t (the left limit at the start and stop times, as a step to t sees it). */
void MMObstacleVelocity(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal V[])
{
  const PetscBool on = (PetscBool)(t > ob->start && t <= ob->stop);
  for (PetscInt d = 0; d < dim; ++d) V[d] = on ? ob->velocity[d] : 0;
}

void MMObstacleDisplacement(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal c[])
{
  const PetscReal s = PetscMax(0.0, PetscMin(t, ob->stop) - ob->start);
  for (PetscInt d = 0; d < dim; ++d) c[d] = ob->velocity[d] * s;
}

/* A vector parameter -obstacle_NAME_<what> the shape needs: given, with dim entries, and, for a
 * direction, nonzero (then made unit). */
PetscErrorCode MMObstacleRequireVector(const MMObstacle *ob, MPI_Comm comm, PetscInt dim, const char what[], PetscInt count, PetscReal v[], PetscBool direction)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  PetscCheck(count >= 0, comm, PETSC_ERR_USER_INPUT, "Obstacle %s (type %s) needs -obstacle_%s_%s, %" PetscInt_FMT " entries", ob->name, ob->type, ob->name, what, dim);
  PetscCheck(count == dim, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, ob->name, what, count, dim, dim);
  if (!direction) PetscFunctionReturn(0);
  for (PetscInt d = 0; d < dim; ++d) nrm += PetscSqr(v[d]);
  nrm = PetscSqrtReal(nrm);
  PetscCheck(nrm > 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_%s is the zero vector: it must give a direction", ob->name, what);
  for (PetscInt d = 0; d < dim; ++d) v[d] /= nrm;
  PetscFunctionReturn(0);
}

/* A radius the shape needs: given and positive. */
PetscErrorCode MMObstacleRequireRadius(const MMObstacle *ob, MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCheck(ob->radius_set, comm, PETSC_ERR_USER_INPUT, "Obstacle %s (type %s) needs -obstacle_%s_radius", ob->name, ob->type, ob->name);
  PetscCheck(ob->radius > 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_radius %g must be > 0", ob->name, (double)ob->radius);
  PetscFunctionReturn(0);
}

/* Parameters a shape does not read are refused rather than ignored. */
PetscErrorCode MMObstacleRefuseUnused(const MMObstacle *ob, MPI_Comm comm, PetscBool point, PetscBool normal, PetscBool center, PetscBool axis, PetscBool radius, PetscBool side)
{
  PetscFunctionBeginUser;
  PetscCheck(point || ob->npoint < 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_point does not apply to an obstacle of type %s", ob->name, ob->type);
  PetscCheck(normal || ob->nnormal < 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_normal does not apply to an obstacle of type %s", ob->name, ob->type);
  PetscCheck(center || ob->ncenter < 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_center does not apply to an obstacle of type %s", ob->name, ob->type);
  PetscCheck(axis || ob->naxis < 0, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_axis does not apply to an obstacle of type %s", ob->name, ob->type);
  PetscCheck(radius || !ob->radius_set, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_radius does not apply to an obstacle of type %s", ob->name, ob->type);
  PetscCheck(side || !ob->inside, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_side inside does not apply to an obstacle of type %s: the body is on the side its normal points to", ob->name, ob->type);
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

/* -obstacle_view: one obstacle as set up (docs/reference.md, "Viewing the set-up"). Its parameters
 * are the ones given: each shape's check refuses the others and completes the single plane's, so
 * what is set is the shape's own. ASCII viewers only; printed once, by the viewer's first rank. */
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
  if (ob->npoint > 0 || ob->nnormal > 0) {
    PetscCall(VectorText(ob->point, ob->npoint, v[0], sizeof(v[0])));
    PetscCall(VectorText(ob->normal, ob->nnormal, v[1], sizeof(v[1])));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s%s%s%s\n", ob->npoint > 0 ? "point " : "", ob->npoint > 0 ? v[0] : "", ob->nnormal > 0 ? (ob->npoint > 0 ? ", normal " : "normal ") : "", ob->nnormal > 0 ? v[1] : ""));
  }
  if (ob->ncenter > 0) {
    PetscCall(VectorText(ob->center, ob->ncenter, v[0], sizeof(v[0])));
    PetscCall(PetscViewerASCIIPrintf(viewer, "center %s\n", v[0]));
  }
  if (ob->naxis > 0) {
    PetscCall(VectorText(ob->axis, ob->naxis, v[0], sizeof(v[0])));
    PetscCall(PetscViewerASCIIPrintf(viewer, "axis %s\n", v[0]));
  }
  if (ob->radius_set) PetscCall(PetscViewerASCIIPrintf(viewer, "radius %g\n", (double)ob->radius));
  if (ob->nvelocity > 0) {
    PetscCall(VectorText(ob->velocity, ob->nvelocity, v[2], sizeof(v[2])));
    if (ob->stop < PETSC_MAX_REAL) PetscCall(PetscViewerASCIIPrintf(viewer, "moves at velocity %s for %g < t <= %g\n", v[2], (double)ob->start, (double)ob->stop));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "moves at velocity %s from t = %g\n", v[2], (double)ob->start));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "fixed\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
