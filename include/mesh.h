#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMMeshLoad(MPI_Comm, MMOptions *, DM *, PetscInt **, PetscInt **);
PETSC_EXTERN PetscErrorCode MMMeshCheckFile(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode MMMeshFileNodes(MPI_Comm, DM, const char[], PetscInt **, PetscInt **);

/* The facet physical groups (names and physical tags) of a mesh read without faces (src/mesh/facets.c). */
typedef struct {
  PetscInt ngroups;
  char   (*name)[256];
  PetscInt *tag;
} MMMeshFacets;
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
PETSC_EXTERN PetscErrorCode MMCellsCreate(DM, MMCells *);
PETSC_EXTERN PetscErrorCode MMCellsDestroy(MMCells *);
