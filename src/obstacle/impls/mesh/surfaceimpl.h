/* A meshed rigid obstacle's surface (docs/method.md section 8, "A meshed obstacle"): the facets of
 * a gmsh file (segments in 2D, triangles in 3D), their normals and pseudo-normals, and a tree of
 * boxes that finds a point's nearest facet among a few. Read by read.c, searched by closest.c,
 * made an obstacle shape by mesh.c. */
#pragma once
#include "../../obstacleimpl.h"

typedef struct {
  PetscInt   dim;      /* 2: segments, 3: triangles */
  PetscInt   nv, nf;   /* vertices, facets */
  PetscReal *x;        /* nv x 3 coordinates */
  PetscInt  *f;        /* nf x dim vertex indices, in the file's orientation */
  PetscReal *fn;       /* nf x 3: the facet's unit normal, towards the body */
  PetscReal *en;       /* 3D: nf x 3 x 3, the pseudo-normal of the facet's edge k (vertices k, k+1) */
  PetscReal *vn;       /* nv x 3: the vertex pseudo-normals (angle-weighted in 3D) */
  PetscBool *eflat;    /* 3D: nf x 3, the facet's edge k joins facets that are flat there */
  PetscBool *vflat;    /* nv: the facets at the vertex are flat there */
  /* the bounding-volume tree (closest.c): node n's box box[6n .. 6n + 6) (low corner, high corner),
   * its children child[2n], child[2n + 1] (-1: a leaf), its facets order[range[2n] .. range[2n + 1]) */
  PetscInt   nnodes, *order, *child, *range;
  PetscReal *box;
  PetscReal  size; /* the diagonal of the facets' bounding box */
} MMSurface;

/* read.c: the facets of an ASCII gmsh 2.2 or 4.1 file, read on rank 0 and broadcast; a refusal
 * names the file and what to change. */
PETSC_INTERN PetscErrorCode MMSurfaceRead(MPI_Comm comm, const char option[], const char file[], PetscInt dim, MMSurface *s);
/* closest.c: orientation checked, normals and pseudo-normals, the grid; the signed distance. */
PETSC_INTERN PetscErrorCode MMSurfaceSetUp(MPI_Comm comm, const char option[], PetscBool flip, MMSurface *s);
PETSC_INTERN void           MMSurfaceDistance(const MMSurface *s, const PetscReal x[], PetscReal *g, PetscReal n[]);
PETSC_INTERN PetscErrorCode MMSurfaceDestroy(MMSurface *s);
