/* A cylinder (3D): a point on its axis, the axis direction and the radius; the body outside it (a
 * rail, a roller) or inside it (a pipe). */
#include "../../obstacleimpl.h"

typedef struct {
  MMObstacleValue point, axis, radius;
} Cylinder;

static const MMObstacleParameter CylinderParameters[] = {
  {"point",  MM_OBSTACLE_POINT,     "cylinder: a point on the axis, d entries",           offsetof(Cylinder, point) },
  {"axis",   MM_OBSTACLE_DIRECTION, "cylinder: the axis direction (normalized), 3 entries", offsetof(Cylinder, axis)  },
  {"radius", MM_OBSTACLE_LENGTH,    "cylinder: the radius, > 0",                          offsetof(Cylinder, radius)},
};

/* r = the part of x - p across the axis; g = |r| - R outside, R - |r| inside; n = +-r/|r|. */
static PetscErrorCode CylinderDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Cylinder  *cy = (const Cylinder *)ob->data;
  const PetscReal *p = cy->point.v, *a = cy->axis.v;
  PetscReal        r[3], along = 0, len = 0, s = ob->inside ? -1.0 : 1.0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; ++d) along += (x[d] - p[d]) * a[d];
  for (PetscInt d = 0; d < 3; ++d) {
    r[d] = x[d] - p[d] - along * a[d];
    len += PetscSqr(r[d]);
  }
  len = PetscSqrtReal(len);
  *g  = s * (len - cy->radius.v[0]);
  for (PetscInt d = 0; d < 3; ++d) n[d] = len > 0 ? s * r[d] / len : 0;
  PetscFunctionReturn(0);
}

static const MMObstacleOps CylinderOps = {
  .params   = CylinderParameters,
  .nparams  = PETSC_STATIC_ARRAY_LENGTH(CylinderParameters),
  .datasize = sizeof(Cylinder),
  .curved   = PETSC_TRUE,
  .sided    = PETSC_TRUE,
  .dim      = 3,
  .other    = "circle",
  .distance = CylinderDistance,
};

PetscErrorCode MMObstacleCreate_Cylinder(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &CylinderOps;
  PetscFunctionReturn(0);
}
