/* obstacle: the rigid obstacles (src/obstacle/): the registry of shapes (interface/), each shape in
 * impls/<type>/, its private helpers in obstacleimpl.h; what the rest of the program asks of one. */
#pragma once
#include "mmbase.h"

/* A rigid obstacle (docs/method.md section 8): a shape from the registry (src/obstacle/) that
 * gives the signed distance of a point and its gradient, the outward normal of the obstacle; it
 * may translate at a constant velocity between a start and a stop time. */
typedef struct _MMObstacle MMObstacle;
struct _MMObstacle {
  char      name[64], type[32];
  PetscReal point[MM_MAX_DIM], normal[MM_MAX_DIM], center[MM_MAX_DIM], axis[MM_MAX_DIM], radius;
  PetscInt  npoint, nnormal, ncenter, naxis, nvelocity; /* entries given, -1 if not set */
  PetscBool radius_set;
  PetscBool inside;                  /* the body is inside the sphere, circle or cylinder */
  PetscBool curved;                  /* its normal varies along its surface (not a plane): a contact node's
                                        frame may follow the contact point (-contact_frames follow) */
  PetscReal mu;                      /* friction coefficient against this obstacle */
  PetscReal velocity[MM_MAX_DIM], start, stop; /* moves at velocity for start < t <= stop */
  /* a contact pair between two surfaces of the mesh (-contact_pairs), not a rigid shape: its slave
   * and master surfaces; it never moves and has no distance function */
  PetscBool pair;
  char      slave[64], master[64];
  /* checks the parameters the shape needs, once the dimension is known */
  PetscErrorCode (*check)(MMObstacle *ob, MPI_Comm comm, PetscInt dim);
  /* signed distance g of x (positive outside the obstacle) and n = grad g, in the obstacle's
   * position at time 0 */
  PetscErrorCode (*distance)(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[]);
};

PETSC_EXTERN PetscErrorCode MMObstacleRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMObstacleSetType(MMObstacle *ob, MPI_Comm comm, const char type[]);
PETSC_EXTERN PetscErrorCode MMObstacleTypesList(char buf[], size_t len);
PETSC_EXTERN PetscErrorCode MMObstacleCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim);
PETSC_EXTERN PetscErrorCode MMObstacleView(const MMObstacle *ob, PetscViewer viewer); /* -obstacle_view */
PETSC_EXTERN void           MMObstacleDisplacement(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal c[]);
PETSC_EXTERN void           MMObstacleVelocity(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal V[]);
PETSC_EXTERN PetscErrorCode MMObstacleFinalize(void);
