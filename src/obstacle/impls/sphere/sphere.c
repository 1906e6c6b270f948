/* A sphere (3D) or a circle (2D): centre and radius, the body outside it (a bump) or inside it (a
 * bowl, a rail, a cavity). Along the radial line through a point the distance is exactly linear,
 * so the bound along a node's own normal is exact for motion along that normal. */
#include "../../obstacleimpl.h"

static PetscErrorCode RoundCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim, PetscInt need)
{
  PetscFunctionBeginUser;
  PetscCheck(dim == need, comm, PETSC_ERR_USER_INPUT, "Obstacle %s is a %s, a %" PetscInt_FMT "D shape, but the mesh is %" PetscInt_FMT "D: use type %s", ob->name, ob->type, need, dim, dim == 2 ? "circle" : "sphere");
  PetscCall(MMObstacleRefuseUnused(ob, comm, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE));
  PetscCall(MMObstacleRequireVector(ob, comm, dim, "center", ob->ncenter, ob->center, PETSC_FALSE));
  PetscCall(MMObstacleRequireRadius(ob, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode SphereCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCall(RoundCheck(ob, comm, dim, 3));
  PetscFunctionReturn(0);
}

static PetscErrorCode CircleCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  PetscFunctionBeginUser;
  PetscCall(RoundCheck(ob, comm, dim, 2));
  PetscFunctionReturn(0);
}

/* g = |x - c| - R outside, R - |x - c| inside; n = +-(x - c)/|x - c|. At the centre the normal is
 * undefined: the caller refuses a contact node there. */
static PetscErrorCode RoundDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscReal r = 0, s = ob->inside ? -1.0 : 1.0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; ++d) r += PetscSqr(x[d] - ob->center[d]);
  r  = PetscSqrtReal(r);
  *g = s * (r - ob->radius);
  for (PetscInt d = 0; d < dim; ++d) n[d] = r > 0 ? s * (x[d] - ob->center[d]) / r : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleCreate_Sphere(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->curved   = PETSC_TRUE;
  ob->check    = SphereCheck;
  ob->distance = RoundDistance;
  PetscFunctionReturn(0);
}

PetscErrorCode MMObstacleCreate_Circle(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->curved   = PETSC_TRUE;
  ob->check    = CircleCheck;
  ob->distance = RoundDistance;
  PetscFunctionReturn(0);
}
