/* The mesh in solution.h5, as the XDMF index reads it: /geometry/vertices (the coordinates in
 * the order of the global vertex numbering) and /viz/topology/cells (each cell's dim + 1 global
 * vertex numbers, positively oriented as VTK's triangles and tetrahedra are). This is what DMView
 * with PETSC_VIEWER_HDF5_XDMF writes, from the cell table (src/mesh/cells.c) instead of a
 * transitive closure per cell and a numbering of every face and edge, a large part of the set-up at
 * a million dofs (docs/scaling.md, "The figures behind the code's choices"). */
#include "io.h"
#include <petscviewerhdf5.h>
#include "outputimpl.h"
#include "fem.h"

static PetscErrorCode WriteVertices(DM dm, PetscViewer viewer)
{
  Vec      X, w;
  PetscInt n, N, bs;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinates(dm, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetSize(X, &N));
  PetscCall(VecGetBlockSize(X, &bs));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecCreateMPIWithArray(PetscObjectComm((PetscObject)dm), bs, n, N, x, &w));
  PetscCall(PetscObjectSetName((PetscObject)w, "vertices"));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/geometry"));
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_NATIVE));
  PetscCall(VecView(w, viewer));
  PetscCall(PetscViewerPopFormat(viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&w));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

/* Whether the simplex with vertices x (dim + 1 of them) is negatively oriented. */
static PetscBool Negative(PetscInt dim, const PetscReal x[][MM_MAX_DIM])
{
  PetscReal e[MM_MAX_DIM][MM_MAX_DIM] = {{0}};

  for (PetscInt a = 0; a < dim; ++a)
    for (PetscInt d = 0; d < dim; ++d) e[a][d] = x[a + 1][d] - x[0][d];
  return (PetscBool)(MMDetInverse(dim, e, NULL) < 0);
}

static PetscErrorCode WriteCells(DM dm, PetscInt dim, const MMCells *cells, PetscViewer viewer)
{
  const PetscInt     nv = cells->nv;
  PetscSection       cs;
  Vec                X;
  IS                 vnum, cellIS;
  const PetscInt    *gv;
  const PetscScalar *x;
  PetscInt          *conn, vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetVertexNumbering(dm, &vnum));
  PetscCall(ISGetIndices(vnum, &gv));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscMalloc1(nv * cells->ncells, &conn));
  for (PetscInt c = 0; c < cells->ncells; ++c) {
    const PetscInt *v = &cells->vertex[nv * c];
    PetscReal       xv[MM_MAX_DIM + 1][MM_MAX_DIM] = {{0}};
    for (PetscInt a = 0; a < nv; ++a) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(cs, v[a], &off));
      for (PetscInt d = 0; d < dim; ++d) xv[a][d] = PetscRealPart(x[off + d]);
      conn[nv * c + a] = gv[v[a] - vStart] < 0 ? -(gv[v[a] - vStart] + 1) : gv[v[a] - vStart];
    }
    if (Negative(dim, xv)) {
      const PetscInt t = conn[nv * c + 1];
      conn[nv * c + 1] = conn[nv * c + 2];
      conn[nv * c + 2] = t;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(ISRestoreIndices(vnum, &gv));
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)dm), nv * cells->ncells, conn, PETSC_OWN_POINTER, &cellIS));
  PetscCall(ISSetBlockSize(cellIS, nv));
  PetscCall(PetscObjectSetName((PetscObject)cellIS, "cells"));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/viz/topology"));
  PetscCall(ISView(cellIS, viewer));
  PetscCall(PetscViewerHDF5WriteObjectAttribute(viewer, (PetscObject)cellIS, "cell_corners", PETSC_INT, (void *)&nv));
  PetscCall(PetscViewerHDF5WriteObjectAttribute(viewer, (PetscObject)cellIS, "cell_dim", PETSC_INT, (void *)&dim));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(ISDestroy(&cellIS));
  PetscFunctionReturn(0);
}

PetscErrorCode MMOutputWriteMesh(MMOperators op, PetscViewer viewer)
{
  DM             dm;
  PetscInt       dim;
  const MMCells *cells;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetDM(op, &dm));
  PetscCall(MMFEGetDimension(op, &dim));
  PetscCall(MMFEGetCells(op, &cells));
  PetscCall(WriteVertices(dm, viewer));
  PetscCall(WriteCells(dm, dim, cells, viewer));
  PetscFunctionReturn(0);
}
