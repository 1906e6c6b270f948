/* The local cells as simplices, tabulated once after the mesh is distributed: each cell's vertices
 * (local point numbers), volume and centroid. The set-up's loops over cells (lumped masses,
 * materials, the mass redistribution, the contact set, the stress output, checksums) read them
 * here. Asking DMPlex per cell for a transitive closure and an FVM geometry instead walks every
 * face and edge and looks up each point's type in a label, in each of the set-up's dozen loops
 * (the figures: docs/scaling.md, "The figures behind the code's choices"). */
#include "mesh.h"

#define MM_NV_MAX (MM_MAX_DIM + 1)

/* The k+1 vertices of a k-simplex p of an interpolated mesh: those of its first facet, plus the
 * vertex of its second facet that the first lacks. Cones only, no transitive closure: this is the
 * cheapest walk down the Hasse diagram. */
static PetscErrorCode SimplexVertices(DM dm, PetscInt p, PetscInt k, PetscInt v[])
{
  const PetscInt *cone;
  PetscInt        w[MM_NV_MAX];

  PetscFunctionBeginUser;
  if (k == 0) {
    v[0] = p;
    PetscFunctionReturn(0);
  }
  PetscCall(DMPlexGetCone(dm, p, &cone));
  if (k == 1) {
    v[0] = cone[0];
    v[1] = cone[1];
    PetscFunctionReturn(0);
  }
  PetscCall(SimplexVertices(dm, cone[0], k - 1, v));
  PetscCall(SimplexVertices(dm, cone[1], k - 1, w));
  for (PetscInt i = 0; i < k; ++i) {
    PetscBool found = PETSC_FALSE;
    for (PetscInt j = 0; j < k; ++j) found = (PetscBool)(found || w[i] == v[j]);
    if (!found) {
      v[k] = w[i];
      break;
    }
  }
  PetscFunctionReturn(0);
}

/*@
  MMMeshCellVertices - Gives the dim + 1 vertices of a simplex cell, refusing a cell that is not a
  simplex

  Not collective

  Input Parameters:
+ dm    - the mesh
. depth - the mesh's depth: 1 for a mesh without faces and edges, whose cell's cone is its vertices
. dim   - the mesh's dimension
- c     - the cell

  Output Parameter:
. v - its dim + 1 vertices, local point numbers

  Note:
  The dim+1 vertices of cell c (depth 1: an uninterpolated mesh, its cone), checked to be a simplex.
  The order is the walk's, not the closure's: every user builds its element quantities for the order
  returned.

  On an interpolated mesh the vertices are found through cones only, without a transitive closure.

  Level: developer

.seealso: `MMCellsCreate()`, `MMFacetGeometry()`
@*/
PetscErrorCode MMMeshCellVertices(DM dm, PetscInt depth, PetscInt dim, PetscInt c, PetscInt v[])
{
  PetscInt csize;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetConeSize(dm, c, &csize));
  PetscCheck(csize == dim + 1, PETSC_COMM_SELF, PETSC_ERR_SUP, "P1 elements need simplices: cell %" PetscInt_FMT " has %" PetscInt_FMT " faces", c, csize);
  if (depth == 1) {
    const PetscInt *cone;
    PetscCall(DMPlexGetCone(dm, c, &cone));
    for (PetscInt a = 0; a <= dim; ++a) v[a] = cone[a];
  } else PetscCall(SimplexVertices(dm, c, dim, v));
  PetscFunctionReturn(0);
}

/* The measure of the simplex with vertices x (dim + 1 of them, cdim coordinates): the area of a
 * triangle (in the plane or in space), the volume of a tetrahedron. */
static PetscReal SimplexMeasure(PetscInt dim, PetscInt cdim, const PetscReal x[][MM_MAX_DIM])
{
  PetscReal e[MM_MAX_DIM][MM_MAX_DIM] = {{0}};

  for (PetscInt a = 0; a < dim; ++a)
    for (PetscInt d = 0; d < cdim; ++d) e[a][d] = x[a + 1][d] - x[0][d];
  if (dim == 2) {
    const PetscReal z = e[0][0] * e[1][1] - e[0][1] * e[1][0], xx = e[0][1] * e[1][2] - e[0][2] * e[1][1], y = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    return 0.5 * PetscSqrtReal(xx * xx + y * y + z * z);
  }
  return PetscAbsReal(MMDetInverse(3, e, NULL)) / 6.0;
}

/*@
  MMCellsCreate - Tabulates the local cells once: each cell's vertices, volume and centroid

  Not collective

  Input Parameter:
. dm - the distributed mesh

  Output Parameter:
. cells - the table, indexed by c - cStart

  Note:
  The volume is a triangle's area (in the plane or in space) or a tetrahedron's volume; the centroid
  is the mean of the vertices. The set-up's loops over cells read them here rather than asking
  DMPlex per cell (the head comment of this file).

  Level: intermediate

.seealso: `MMCellsDestroy()`, `MMMeshCellVertices()`
@*/
PetscErrorCode MMCellsCreate(DM dm, MMCells *cells)
{
  PetscSection       cs;
  Vec                X;
  const PetscScalar *x;
  PetscInt           dim, cdim, depth, cStart, cEnd, nv;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  nv            = dim + 1;
  cells->cStart = cStart;
  cells->ncells = cEnd - cStart;
  cells->nv     = nv;
  PetscCall(PetscMalloc3(nv * cells->ncells, &cells->vertex, cells->ncells, &cells->volume, MM_MAX_DIM * cells->ncells, &cells->centroid));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt c = 0; c < cells->ncells; ++c) {
    PetscInt *v = &cells->vertex[nv * c];
    PetscReal xv[MM_MAX_DIM + 1][MM_MAX_DIM] = {{0}}, *g = &cells->centroid[MM_MAX_DIM * c];

    PetscCall(MMMeshCellVertices(dm, depth, dim, cStart + c, v));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) g[d] = 0;
    for (PetscInt a = 0; a < nv; ++a) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(cs, v[a], &off));
      for (PetscInt d = 0; d < cdim; ++d) {
        xv[a][d] = PetscRealPart(x[off + d]);
        g[d] += xv[a][d] / nv;
      }
    }
    cells->volume[c] = SimplexMeasure(dim, cdim, xv);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

/*@
  MMCellsDestroy - Frees the table of the local cells

  Not collective

  Input Parameter:
. cells - the table

  Level: intermediate

.seealso: `MMCellsCreate()`
@*/
PetscErrorCode MMCellsDestroy(MMCells *cells)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(cells->vertex, cells->volume, cells->centroid));
  cells->ncells = 0;
  PetscFunctionReturn(0);
}

/*@
  MMDetInverse - Computes the determinant of a 2 x 2 or 3 x 3 matrix, and its inverse when wanted

  Not collective

  Input Parameters:
+ dim - the matrix's size, 2 or 3
- a   - the matrix

  Output Parameter:
. inv - its inverse, when inv is not NULL and the determinant is not 0

  Note:
  Returns the determinant (a PetscReal) rather than an error code.

  Level: developer

.seealso: `MMCellsCreate()`
@*/
PetscReal MMDetInverse(PetscInt dim, const PetscReal a[MM_MAX_DIM][MM_MAX_DIM], PetscReal inv[MM_MAX_DIM][MM_MAX_DIM])
{
  PetscReal det;

  if (dim == 2) {
    det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if (inv && det != 0) {
      inv[0][0] = a[1][1] / det;
      inv[0][1] = -a[0][1] / det;
      inv[1][0] = -a[1][0] / det;
      inv[1][1] = a[0][0] / det;
    }
    return det;
  }
  det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (inv && det != 0)
    for (PetscInt i = 0; i < 3; ++i)
      for (PetscInt j = 0; j < 3; ++j) {
        const PetscInt i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        inv[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
      }
  return det;
}
