/* The mesh (src/mesh/): the gmsh file read and checked, distributed, its physical groups as labels,
 * and its cells tabulated once. */
#pragma once
#include "mmbase.h"
PETSC_EXTERN PetscErrorCode MMMeshCheckFile(MPI_Comm comm, const char file[]);
PETSC_EXTERN PetscErrorCode MMMeshFileNodes(MPI_Comm comm, DM dm, const char file[], PetscInt **pos, PetscInt **vtag);

/* The facet physical groups (names and physical tags) of a mesh read without faces (src/mesh/facets.c). */
typedef struct {
  PetscInt ngroups;
  char   (*name)[256];
  PetscInt *tag;
  PetscBool read;  /* the file was read by src/mesh/facets.c: MMMeshDistribute labels the vertices */
} MMMeshFacets;
PETSC_EXTERN PetscErrorCode MMMeshRead(MPI_Comm comm, const char file[], DM *dm, MMMeshFacets *facets, PetscInt **vertex_file);
PETSC_EXTERN PetscErrorCode MMMeshDistribute(const PetscReal rotation[], const PetscReal center[], MMMeshFacets *facets, DM *dm, PetscInt **vertex_orig);
PETSC_EXTERN PetscErrorCode MMMeshFacetsRead(MPI_Comm comm, DM dm, const char file[], const PetscInt vtag[], MMMeshFacets *groups, PetscBool *ok);
PETSC_EXTERN PetscErrorCode MMMeshFacetsLabelVertices(MMMeshFacets *groups, DM dm);
PETSC_EXTERN PetscErrorCode MMMeshPointGroupsRead(MPI_Comm comm, DM dm, const char file[], const PetscInt vtag[]);
/* The cell labels that carry the facet groups through the distribution (src/mesh/facets.c) */
#define MM_MESH_FACET_MARK "mmcontact facet cells of "

/* A facet group's facets on this rank, each once over all ranks: the face of cell[i] opposite its
 * vertex off[i] (position in MMMeshCellVertices' order); interior[i] when a second cell shares it. */
typedef struct {
  PetscInt   n, cap;
  PetscInt   dim, depth; /* the mesh's, for the cells' vertices */
  PetscInt  *cell, *off;
  PetscBool *interior;
} MMFacetList;
PETSC_EXTERN PetscErrorCode MMMeshGetFacets(DM dm, const char name[], MMFacetList *fl);
PETSC_EXTERN PetscErrorCode MMFacetListDestroy(MMFacetList *fl);
PETSC_EXTERN PetscErrorCode MMFacetGeometry(DM dm, const MMFacetList *fl, PetscInt i, PetscSection cs, const PetscScalar xc[], PetscInt v[], PetscReal x[], PetscReal *measure);
PETSC_EXTERN PetscErrorCode MMMeshFacetsAddNodal(DM dm, const MMFacetList *fl, DM dmv, PetscInt ncomp, const PetscReal value[], PetscScalar a[]);
PETSC_EXTERN PetscErrorCode MMMeshLabelPoints(DMLabel label, PetscInt *n, PetscInt **pts, PetscInt **vals);
PETSC_EXTERN PetscErrorCode MMMeshLabelHoldsCells(DM dm, DMLabel label, PetscBool *holds);
PETSC_EXTERN PetscErrorCode MMMeshFacetsDestroy(MMMeshFacets *groups);
PETSC_EXTERN PetscErrorCode MMMeshGetLabel(DM dm, const char name[], DMLabel *label);
PETSC_EXTERN PetscBool      MMMeshIsPhysicalGroup(const char name[]);
PETSC_EXTERN PetscErrorCode MMMeshGetLabelFor(DM dm, const char name[], const char option[], DMLabel *label);
PETSC_EXTERN PetscErrorCode MMMeshGetSizes(DM dm, PetscInt *ncells, PetscInt *nvertices);
PETSC_EXTERN PetscErrorCode MMMeshCellCentroid(DM dm, PetscInt c, PetscReal centroid[]);
PETSC_EXTERN PetscErrorCode MMMeshCellGroups(DM dm, char list[], size_t len);
PETSC_EXTERN PetscErrorCode MMMeshCellVertices(DM dm, PetscInt depth, PetscInt dim, PetscInt c, PetscInt v[]);

/* The local cells as simplices, tabulated once (src/mesh/cells.c), indexed by c - cStart of the
 * mesh and of its clones, which share its points. */
typedef struct {
  PetscInt   cStart, ncells, nv; /* local cells; vertices per cell, dim + 1 */
  PetscInt  *vertex;   /* nv per cell: its vertices' local point numbers */
  PetscReal *volume;   /* per cell: its area (2D) or volume (3D) */
  PetscReal *centroid; /* MM_MAX_DIM per cell: the mean of its vertices */
} MMCells;
PETSC_EXTERN PetscErrorCode MMCellsCreate(DM dm, MMCells *cells);
PETSC_EXTERN PetscErrorCode MMCellsDestroy(MMCells *cells);
/* det of the dim x dim matrix a, and its inverse into inv when inv is not NULL and det != 0 */
PETSC_EXTERN PetscReal MMDetInverse(PetscInt dim, const PetscReal a[MM_MAX_DIM][MM_MAX_DIM], PetscReal inv[MM_MAX_DIM][MM_MAX_DIM]);
