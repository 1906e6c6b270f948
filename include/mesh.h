/* The mesh (src/mesh/): the gmsh file read and checked, distributed, its physical groups as labels,
 * and its cells tabulated once. */
#pragma once
#include "mmbase.h"
PETSC_EXTERN PetscErrorCode MMMeshCheckFile(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode MMMeshFileNodes(MPI_Comm, DM, const char[], PetscInt **, PetscInt **);

/* The facet physical groups (names and physical tags) of a mesh read without faces (src/mesh/facets.c). */
typedef struct {
  PetscInt ngroups;
  char   (*name)[256];
  PetscInt *tag;
  PetscBool read;  /* the file was read by src/mesh/facets.c: MMMeshDistribute labels the vertices */
} MMMeshFacets;
PETSC_EXTERN PetscErrorCode MMMeshRead(MPI_Comm comm, const char file[], DM *dm, MMMeshFacets *facets, PetscInt **vertex_file);
PETSC_EXTERN PetscErrorCode MMMeshDistribute(const PetscReal rotation[], const PetscReal center[], MMMeshFacets *facets, DM *dm, PetscInt **vertex_orig);
PETSC_EXTERN PetscErrorCode MMMeshFacetsRead(MPI_Comm, DM, const char[], const PetscInt[], MMMeshFacets *, PetscBool *);
PETSC_EXTERN PetscErrorCode MMMeshFacetsLabelVertices(MMMeshFacets *, DM);
PETSC_EXTERN PetscErrorCode MMMeshPointGroupsRead(MPI_Comm, DM, const char[], const PetscInt[]);
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
PETSC_EXTERN PetscErrorCode MMMeshGetFacets(DM, const char[], MMFacetList *);
PETSC_EXTERN PetscErrorCode MMFacetListDestroy(MMFacetList *);
PETSC_EXTERN PetscErrorCode MMFacetGeometry(DM, const MMFacetList *, PetscInt, PetscSection, const PetscScalar[], PetscInt[], PetscReal[], PetscReal *);
PETSC_EXTERN PetscErrorCode MMMeshFacetsAddNodal(DM, const MMFacetList *, DM, PetscInt, const PetscReal[], PetscScalar[]);
PETSC_EXTERN PetscErrorCode MMMeshLabelPoints(DMLabel, PetscInt *, PetscInt **, PetscInt **);
PETSC_EXTERN PetscErrorCode MMMeshLabelHoldsCells(DM, DMLabel, PetscBool *);
PETSC_EXTERN PetscErrorCode MMMeshFacetsDestroy(MMMeshFacets *);
PETSC_EXTERN PetscErrorCode MMMeshGetLabel(DM, const char[], DMLabel *);
PETSC_EXTERN PetscBool      MMMeshIsPhysicalGroup(const char[]);
PETSC_EXTERN PetscErrorCode MMMeshGetLabelFor(DM, const char[], const char[], DMLabel *);
PETSC_EXTERN PetscErrorCode MMMeshGetSizes(DM, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode MMMeshCellCentroid(DM, PetscInt, PetscReal[]);
PETSC_EXTERN PetscErrorCode MMMeshCellGroups(DM, char[], size_t);
PETSC_EXTERN PetscErrorCode MMMeshCellVertices(DM, PetscInt, PetscInt, PetscInt, PetscInt[]);

/* The local cells as simplices, tabulated once (src/mesh/cells.c), indexed by c - cStart of the
 * mesh and of its clones, which share its points. */
typedef struct {
  PetscInt   cStart, ncells, nv; /* local cells; vertices per cell, dim + 1 */
  PetscInt  *vertex;   /* nv per cell: its vertices' local point numbers */
  PetscReal *volume;   /* per cell: its area (2D) or volume (3D) */
  PetscReal *centroid; /* MM_MAX_DIM per cell: the mean of its vertices */
} MMCells;
PETSC_EXTERN PetscErrorCode MMCellsCreate(DM, MMCells *);
PETSC_EXTERN PetscErrorCode MMCellsDestroy(MMCells *);
/* det of the dim x dim matrix a, and its inverse into inv when inv is not NULL and det != 0 */
PETSC_EXTERN PetscReal MMDetInverse(PetscInt, const PetscReal[MM_MAX_DIM][MM_MAX_DIM], PetscReal[MM_MAX_DIM][MM_MAX_DIM]);
