/* A sphere (3D) or a circle (2D): centre and radius, the body outside it (a bump) or inside it (a
 * bowl, a rail, a cavity). Along the radial line through a point the distance is exactly linear,
 * so the bound along a node's own normal is exact for motion along that normal. */
#include "../../obstacleimpl.h"

typedef struct {
  MMObstacleValue center, radius;
} Round;

static const MMObstacleParameter RoundParameters[] = {
  {"center", MM_OBSTACLE_POINT,  "sphere, circle: the centre, d entries", offsetof(Round, center)},
  {"radius", MM_OBSTACLE_LENGTH, "sphere, circle: the radius, > 0",       offsetof(Round, radius)},
};

/* g = |x - c| - R outside, R - |x - c| inside; n = +-(x - c)/|x - c|. At the centre the normal is
 * undefined: the caller refuses a contact node there. */
static PetscErrorCode RoundDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Round    *rd = (const Round *)ob->data;
  const PetscReal *c = rd->center.v;
  PetscReal       r = 0, s = ob->inside ? -1.0 : 1.0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; ++d) r += PetscSqr(x[d] - c[d]);
  r  = PetscSqrtReal(r);
  *g = s * (r - rd->radius.v[0]);
  for (PetscInt d = 0; d < dim; ++d) n[d] = r > 0 ? s * (x[d] - c[d]) / r : 0;
  PetscFunctionReturn(0);
}

static const MMObstacleOps SphereOps = {
  .params   = RoundParameters,
  .nparams  = PETSC_STATIC_ARRAY_LENGTH(RoundParameters),
  .datasize = sizeof(Round),
  .curved   = PETSC_TRUE,
  .sided    = PETSC_TRUE,
  .dim      = 3,
  .other    = "circle",
  .distance = RoundDistance,
};

static const MMObstacleOps CircleOps = {
  .params   = RoundParameters,
  .nparams  = PETSC_STATIC_ARRAY_LENGTH(RoundParameters),
  .datasize = sizeof(Round),
  .curved   = PETSC_TRUE,
  .sided    = PETSC_TRUE,
  .dim      = 2,
  .other    = "sphere",
  .distance = RoundDistance,
};

PetscErrorCode MMObstacleCreate_Sphere(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &SphereOps;
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleCreate_Circle(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &CircleOps;
  PetscFunctionReturn(0);
}
