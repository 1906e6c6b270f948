/* A plane through a point with a unit normal pointing out of the obstacle, towards the body. */
#include "../../obstacleimpl.h"

typedef struct {
  MMObstacleValue point, normal;
} Plane;

static const MMObstacleParameter PlaneParameters[] = {
  {"point",  MM_OBSTACLE_POINT,     "plane: a point of the plane, d entries",                                          offsetof(Plane, point) },
  {"normal", MM_OBSTACLE_DIRECTION, "plane: normal pointing out of the obstacle, towards the body (normalized), d entries", offsetof(Plane, normal)},
};

static PetscErrorCode PlaneDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Plane *pl = (const Plane *)ob->data;

  PetscFunctionBeginUser;
  *g = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    *g += (x[d] - pl->point.v[d]) * pl->normal.v[d];
    n[d] = pl->normal.v[d];
  }
  PetscFunctionReturn(0);
}

static const MMObstacleOps PlaneOps = {
  .params   = PlaneParameters,
  .nparams  = PETSC_STATIC_ARRAY_LENGTH(PlaneParameters),
  .datasize = sizeof(Plane),
  .curved   = PETSC_FALSE,
  .sided    = PETSC_FALSE,
  .distance = PlaneDistance,
};

PetscErrorCode MMObstacleCreate_Plane(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &PlaneOps;
  PetscFunctionReturn(0);
}
