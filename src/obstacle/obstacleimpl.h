/* Internals of the obstacle component: the ops table a shape fills (its parameters, its data's
 * size, its signed distance); each shape's create function is registered in interface/obstacle.c. */
#pragma once
#include "obstacle.h"

/* A shape's parameter -obstacle_NAME_<name>: read by the interface under the obstacle's prefix into
 * the shape's data at offset, required once the dimension is known; a parameter of another shape
 * given to this one is refused ("does not apply"). */
typedef enum {
  MM_OBSTACLE_POINT,     /* d entries */
  MM_OBSTACLE_DIRECTION, /* d entries, nonzero, made unit */
  MM_OBSTACLE_LENGTH,    /* one value, > 0 */
  MM_OBSTACLE_LENGTHS    /* d entries, each > 0 */
} MMObstacleParameterKind;

/* A parameter's values in the shape's data: n entries given, -1 if not set. */
typedef struct {
  PetscReal v[MM_MAX_DIM];
  PetscInt  n;
} MMObstacleValue;

typedef struct {
  const char             *name; /* the option's suffix */
  MMObstacleParameterKind kind;
  const char             *help;
  size_t                  offset; /* of its MMObstacleValue in the shape's data */
} MMObstacleParameter;

struct _MMObstacleOps {
  const MMObstacleParameter *params; /* what the shape reads, in the order it requires them */
  PetscInt                   nparams;
  size_t                     datasize; /* its data: a struct of MMObstacleValue */
  PetscBool                  curved;   /* its normal varies along its surface */
  PetscBool                  faceted;  /* its normal jumps across its facets' edges (a mesh) */
  PetscBool                  sided;    /* the body may be inside it (-obstacle_NAME_side inside) */
  PetscInt                   dim;      /* the one dimension it exists in, 0: any */
  const char                *other;    /* dim given: the shape to use in the other dimension */
  /* the shape's own checks beyond its parameters' (NULL: none), once they are given */
  PetscErrorCode (*check)(MMObstacle *ob, MPI_Comm comm, PetscInt dim);
  /* signed distance g of x (positive outside the obstacle) and n = grad g, in the obstacle's
   * position at time 0 */
  PetscErrorCode (*distance)(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[]);
  /* A shape with options that are not real parameters (the meshed obstacle's file), NULL for the
   * others: their suffixes, NULL-terminated, so that another shape refuses them; the reading, under
   * the obstacle's prefix; what -obstacle_view prints of them; the text a checkpoint compares on
   * restart (the same shape, not only the same file name); freeing what the data points to. */
  const char *const *options;
  PetscErrorCode (*setfromoptions)(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMObstacle *ob);
  PetscErrorCode (*view)(const MMObstacle *ob, PetscViewer viewer);
  PetscErrorCode (*describe)(const MMObstacle *ob, char text[], size_t len);
  PetscErrorCode (*destroy)(MMObstacle *ob);
};

PETSC_EXTERN PetscErrorCode MMObstacleSetType(MMObstacle *ob, MPI_Comm comm, const char type[]);
