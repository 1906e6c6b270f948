/* A plane through a point with a unit normal pointing out of the obstacle, towards the body. */
#include "../../obstacleimpl.h"

static PetscErrorCode PlaneCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCall(MMObstacleRefuseUnused(ob, comm, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE));
  PetscCall(MMObstacleRequireVector(ob, comm, dim, "point", ob->npoint, ob->point, PETSC_FALSE));
  PetscCall(MMObstacleRequireVector(ob, comm, dim, "normal", ob->nnormal, ob->normal, PETSC_TRUE));
  PetscFunctionReturn(0);
}

static PetscErrorCode PlaneDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscFunctionBeginUser;
  *g = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    *g += (x[d] - ob->point[d]) * ob->normal[d];
    n[d] = ob->normal[d];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleCreate_Plane(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->curved   = PETSC_FALSE;
  ob->check    = PlaneCheck;
  ob->distance = PlaneDistance;
  PetscFunctionReturn(0);
}
