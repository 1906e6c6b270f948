/* A cylinder (3D): a point on its axis, the axis direction and the radius; the body outside it (a
 * rail, a roller) or inside it (a pipe). */
#include "../../obstacleimpl.h"

static PetscErrorCode CylinderCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCheck(dim == 3, comm, PETSC_ERR_USER_INPUT, "Obstacle %s is a cylinder, a 3D shape, but the mesh is 2D: use type circle", ob->name);
  PetscCall(MMObstacleRefuseUnused(ob, comm, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE));
  PetscCall(MMObstacleRequireVector(ob, comm, dim, "point", ob->npoint, ob->point, PETSC_FALSE));
  PetscCall(MMObstacleRequireVector(ob, comm, dim, "axis", ob->naxis, ob->axis, PETSC_TRUE));
  PetscCall(MMObstacleRequireRadius(ob, comm));
  PetscFunctionReturn(0);
}

/* r = the part of x - p across the axis; g = |r| - R outside, R - |r| inside; n = +-r/|r|. */
static PetscErrorCode CylinderDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscReal r[3], along = 0, len = 0, s = ob->inside ? -1.0 : 1.0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; ++d) along += (x[d] - ob->point[d]) * ob->axis[d];
  for (PetscInt d = 0; d < 3; ++d) {
    r[d] = x[d] - ob->point[d] - along * ob->axis[d];
    len += PetscSqr(r[d]);
  }
  len = PetscSqrtReal(len);
  *g  = s * (len - ob->radius);
  for (PetscInt d = 0; d < 3; ++d) n[d] = len > 0 ? s * r[d] / len : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleCreate_Cylinder(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->curved   = PETSC_TRUE;
  ob->check    = CylinderCheck;
  ob->distance = CylinderDistance;
  PetscFunctionReturn(0);
}
