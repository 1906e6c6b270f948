/* obstacle: the rigid obstacles (src/obstacle/): the registry of shapes (interface/), each shape in
 * impls/<type>/, its private helpers in obstacleimpl.h; what the rest of the program asks of one. */
#pragma once
#include "mmbase.h"

/* A rigid obstacle (docs/method.md section 8): a shape from the registry (src/obstacle/) that
 * gives the signed distance of a point and its gradient, the outward normal of the obstacle; it
 * may translate at a constant velocity between a start and a stop time. Its shape's parameters
 * are the shape's own (data), read under its prefix -obstacle_NAME_ by MMObstacleSetFromOptions. */
typedef struct _MMObstacleOps MMObstacleOps;
typedef struct _MMObstacle    MMObstacle;
struct _MMObstacle {
  char      name[64], type[32];
  PetscBool inside;                  /* the body is inside the shape (-obstacle_NAME_side inside) */
  PetscBool curved;                  /* its normal varies along its surface (not a plane): a contact node's
                                        frame may follow the contact point (-contact_frames follow) */
  PetscBool faceted;                 /* its normal jumps across the edges of its facets (type mesh): a
                                        node may cross one within a step (-contact_frames_depth) */
  PetscReal mu;                      /* friction coefficient against this obstacle */
  PetscBool mu_given;                /* its own _mu was given (else it took -mu) */
  PetscBool prefixed;                /* it read its options under -obstacle_NAME_ (not the plane of -obstacle_point) */
  PetscReal velocity[MM_MAX_DIM], start, stop; /* moves at velocity for start < t <= stop */
  PetscInt  nvelocity;               /* entries given to -obstacle_NAME_velocity, -1 if not set */
  /* a contact pair between two surfaces of the mesh (-contact_pairs), not a rigid shape: its slave
   * and master surfaces; it never moves and has no distance function */
  PetscBool pair;
  char      slave[64], master[64];
  const MMObstacleOps *ops;          /* the shape's (src/obstacle/obstacleimpl.h) */
  void                *data;         /* the shape's parameters */
};

/* The registry (src/obstacle/interface/obstacle.c): the shapes, a new one added by
 * MMObstacleRegister; MMObstacleTypesList gives "plane|sphere|..." for help strings and refusals. */
PETSC_EXTERN PetscErrorCode MMObstacleRegisterAll(void);
PETSC_EXTERN PetscErrorCode MMObstacleRegister(const char type[], PetscErrorCode (*create)(MMObstacle *));
PETSC_EXTERN PetscErrorCode MMObstacleTypesList(char buf[], size_t len);
PETSC_EXTERN PetscErrorCode MMObstacleFinalize(void);
/* From the options (src/obstacle/interface/options.c): obstacle NAME of -obstacles under its prefix
 * -obstacle_NAME_, contact pair NAME of -contact_pairs under -contact_pair_NAME_; mu, the default of
 * their own _mu. MMObstacleCreatePlane makes the single plane of -obstacle_point/-obstacle_normal,
 * whose point and normal MMObstacleSetPlane gives once the dimension is known. */
PETSC_EXTERN PetscErrorCode MMObstacleSetFromOptions(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu);
PETSC_EXTERN PetscErrorCode MMObstacleSetPairFromOptions(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu);
PETSC_EXTERN PetscErrorCode MMObstacleCreatePlane(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu);
PETSC_EXTERN PetscErrorCode MMObstacleSetPlane(MMObstacle *ob, PetscInt dim, const PetscReal point[], const PetscReal normal[]);
/* Once the dimension is known: the motion and mu checked, the shape's parameters required, another
 * shape's refused. */
PETSC_EXTERN PetscErrorCode MMObstacleCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim);
/* What the rest of the program asks of one: a plane's point and normal (plane false for another
 * shape), a parameter's first n values by its option suffix (0 where the shape has none), the
 * parameters' names, the signed distance and normal at x, the motion at time t. */
PETSC_EXTERN PetscErrorCode MMObstacleGetPlane(const MMObstacle *ob, PetscReal point[], PetscReal normal[], PetscBool *plane);
PETSC_EXTERN PetscErrorCode MMObstacleGetParameter(const MMObstacle *ob, const char name[], PetscInt n, PetscReal v[], PetscBool *has);
PETSC_EXTERN PetscErrorCode MMObstacleGetParameterNames(const MMObstacle *ob, PetscInt max, PetscInt *n, const char *names[]);
PETSC_EXTERN PetscErrorCode MMObstacleDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[]);
PETSC_EXTERN PetscErrorCode MMObstacleView(const MMObstacle *ob, PetscViewer viewer); /* -obstacle_view */
PETSC_EXTERN PetscErrorCode MMObstacleDescribe(const MMObstacle *ob, char text[], size_t len); /* for a restart's comparison */
PETSC_EXTERN void           MMObstacleDisplacement(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal c[]);
PETSC_EXTERN void           MMObstacleVelocity(const MMObstacle *ob, PetscInt dim, PetscReal t, PetscReal V[]);
/* Frees the shape's data. */
PETSC_EXTERN PetscErrorCode MMObstacleDestroy(MMObstacle *ob);
