/* A box with rounded edges and corners, axis-aligned: its centre, half sizes and the rounding
 * radius (2D: a rounded rectangle; 3D: rounded edges and corners); the body outside it (a step, a
 * kerb, a block). It is the set of points within the radius of its core, the box of half sizes
 * h - r: its surface is flat on the faces and round on the edges and corners, so its normal is
 * continuous and a contact node's frame can follow it (docs/method.md section 8). */
#include "../../obstacleimpl.h"

typedef struct {
  MMObstacleValue center, half_sizes, radius;
} Box;

static const MMObstacleParameter BoxParameters[] = {
  {"center",     MM_OBSTACLE_POINT,   "box: the centre, d entries",                                          offsetof(Box, center)    },
  {"half_sizes", MM_OBSTACLE_LENGTHS, "box: the half sizes along x, y[, z] (the box's half extents, the rounding included), d entries > 0", offsetof(Box, half_sizes)},
  {"radius",     MM_OBSTACLE_LENGTH,  "box: the rounding radius of its edges and corners, > 0, at most the smallest half size", offsetof(Box, radius)    },
};

/* The rounding fits inside the box. */
static PetscErrorCode BoxCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  const Box *bx = (const Box *)ob->data;
  PetscReal  hmin = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; ++d) hmin = PetscMin(hmin, bx->half_sizes.v[d]);
  PetscCheck(bx->radius.v[0] <= hmin, comm, PETSC_ERR_USER_INPUT, "-obstacle_%s_radius %g is larger than the smallest of -obstacle_%s_half_sizes (%g): the rounding must fit inside the box", ob->name, (double)bx->radius.v[0], ob->name, (double)hmin);
  PetscFunctionReturn(0);
}

/* With p = x - c and q = |p| - (h - r) per axis, the distance to the core is |max(q, 0)| outside it
 * and max q inside it; g = that - r, and n points from the core's nearest point to x (inside the
 * core, along the axis of max q). */
static PetscErrorCode BoxDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Box *bx = (const Box *)ob->data;
  const PetscReal r = bx->radius.v[0];
  PetscReal  p[MM_MAX_DIM], q[MM_MAX_DIM], out = 0;
  PetscInt   k = 0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; ++d) {
    p[d] = x[d] - bx->center.v[d];
    q[d] = PetscAbsReal(p[d]) - (bx->half_sizes.v[d] - r);
    out += PetscSqr(PetscMax(q[d], 0.0));
    if (q[d] > q[k]) k = d;
  }
  out = PetscSqrtReal(out);
  for (PetscInt d = 0; d < dim; ++d) {
    const PetscReal sign = p[d] < 0 ? -1.0 : 1.0;
    n[d] = out > 0 ? sign * PetscMax(q[d], 0.0) / out : (d == k ? sign : 0.0);
  }
  *g = (out > 0 ? out : q[k]) - r;
  PetscFunctionReturn(0);
}

static const MMObstacleOps BoxOps = {
  .params   = BoxParameters,
  .nparams  = PETSC_STATIC_ARRAY_LENGTH(BoxParameters),
  .datasize = sizeof(Box),
  .curved   = PETSC_TRUE,
  .sided    = PETSC_FALSE,
  .check    = BoxCheck,
  .distance = BoxDistance,
};

PetscErrorCode MMObstacleCreate_Box(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &BoxOps;
  PetscFunctionReturn(0);
}
