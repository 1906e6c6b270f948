/* Closed-form P1 stiffness and consistent mass, assembled in one pass over the cells.
 *
 * The P1 shape functions of a simplex have constant gradients, so its stiffness is exact with one
 * point and its mass has a closed form: no quadrature, no tabulation, no PetscFE. DMPlex still
 * owns the mesh and the sections, and the matrices come from DMCreateMatrix: the dofs, the
 * preallocation and the dropped Dirichlet dofs are those of the PetscFE path (fem.c). */
#include "assembly_p1.h"

#define MM_NV_MAX   (MM_MAX_DIM + 1)
#define MM_NDOF_MAX (MM_NV_MAX * MM_MAX_DIM)

/* Per-vertex data gathered once, so the cell loop reads plain arrays: the dim global dof indices
 * of each vertex (negative for a Dirichlet-constrained component, which MatSetValues skips) and
 * its coordinates. */
typedef struct {
  PetscInt   dim, vStart;
  PetscInt  *dof;
  PetscReal *x;
} VertexTable;

/* The global indices of a vertex, as DMPlexGetClosureIndices computes them from the local section
 * (constraints) and the global section (offsets, -(offset+1) at points owned elsewhere): the free
 * components are numbered consecutively, the constrained ones are dropped. */
static PetscErrorCode VertexDofs(PetscSection ls, PetscSection gs, PetscInt v, PetscInt dim, PetscInt dof[])
{
  PetscInt        ndof, ncdof, goff;
  const PetscInt *cidx = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscSectionGetDof(ls, v, &ndof));
  PetscCheck(ndof == dim, PETSC_COMM_SELF, PETSC_ERR_SUP, "Closed-form assembly needs one P1 vector field: vertex %" PetscInt_FMT " has %" PetscInt_FMT " dofs, not %" PetscInt_FMT " (use -assembly fe)", v, ndof, dim);
  PetscCall(PetscSectionGetConstraintDof(ls, v, &ncdof));
  if (ncdof) PetscCall(PetscSectionGetConstraintIndices(ls, v, &cidx));
  PetscCall(PetscSectionGetOffset(gs, v, &goff));
  if (goff < 0) goff = -(goff + 1);
  for (PetscInt c = 0, k = 0, skipped = 0; c < dim; ++c) {
    if (k < ncdof && cidx[k] == c) {
      dof[c] = -1;
      ++k;
      ++skipped;
    } else dof[c] = goff + c - skipped;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode VertexTableCreate(DM dm, VertexTable *t)
{
  PetscSection       ls, gs, cs;
  Vec                coords;
  const PetscScalar *xa;
  PetscInt           vEnd, dim;
  PetscBool          localized;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinatesLocalized(dm, &localized));
  PetscCheck(!localized, PetscObjectComm((PetscObject)dm), PETSC_ERR_SUP, "Closed-form assembly reads vertex coordinates; periodic (localized) coordinates need -assembly fe");
  PetscCall(DMPlexGetDepthStratum(dm, 0, &t->vStart, &vEnd));
  t->dim = dim;
  PetscCall(PetscMalloc2((vEnd - t->vStart) * dim, &t->dof, (vEnd - t->vStart) * dim, &t->x));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt v = t->vStart; v < vEnd; ++v) {
    PetscInt off;
    PetscCall(VertexDofs(ls, gs, v, dim, &t->dof[(v - t->vStart) * dim]));
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < dim; ++d) t->x[(v - t->vStart) * dim + d] = PetscRealPart(xa[off + d]);
  }
  PetscCall(VecRestoreArrayRead(coords, &xa));
  PetscFunctionReturn(0);
}

static PetscErrorCode VertexTableDestroy(VertexTable *t)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(t->dof, t->x));
  PetscFunctionReturn(0);
}

/* The k+1 vertices of a k-simplex p of an interpolated mesh: those of its first facet, plus the
 * vertex of its second facet that the first lacks. Cones only, no transitive closure: this is the
 * cheapest walk down the Hasse diagram. The vertex order does not matter, as the element matrices
 * are built for the order returned. */
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

/* Gradients g[a][i] of the P1 basis and the volume of the simplex with vertex coordinates x[a][i].
 * With J = [x_1 - x_0, ..., x_d - x_0], the reference coordinates are xi = J^{-1} (x - x_0), so
 * grad phi_a = row a-1 of J^{-1} (a >= 1) and grad phi_0 = -sum of the others. */
static PetscErrorCode SimplexGradients(PetscInt dim, const PetscReal x[][MM_MAX_DIM], PetscReal g[][MM_MAX_DIM], PetscReal *vol)
{
  PetscReal J[MM_MAX_DIM][MM_MAX_DIM], det;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt k = 0; k < dim; ++k) J[i][k] = x[k + 1][i] - x[0][i];
  if (dim == 2) {
    det     = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    g[1][0] = J[1][1] / det;
    g[1][1] = -J[0][1] / det;
    g[2][0] = -J[1][0] / det;
    g[2][1] = J[0][0] / det;
    *vol    = PetscAbsReal(det) / 2;
  } else {
    /* rows of J^{-1}: the cofactors of J's columns, divided by det J */
    const PetscReal c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1], c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2], c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
    det     = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
    g[1][0] = c00 / det;
    g[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
    g[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
    g[2][0] = c01 / det;
    g[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
    g[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
    g[3][0] = c02 / det;
    g[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
    g[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
    *vol    = PetscAbsReal(det) / 6;
  }
  PetscCheck(det != 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Degenerate cell: zero volume");
  for (PetscInt i = 0; i < dim; ++i) {
    g[0][i] = 0;
    for (PetscInt a = 1; a <= dim; ++a) g[0][i] -= g[a][i];
  }
  PetscFunctionReturn(0);
}

/* K_e[a i][b j] = vol (lambda g_a,i g_b,j + mu g_a,j g_b,i + mu delta_ij g_a.g_b): the derivative of
 * fem.c's f1_elas_u, dofs vertex-major and component-minor. */
static void ElementStiffness(PetscInt dim, PetscReal lambda, PetscReal mu, PetscReal vol, const PetscReal g[][MM_MAX_DIM], PetscScalar Ke[])
{
  const PetscInt n = (dim + 1) * dim;

  for (PetscInt a = 0; a <= dim; ++a)
    for (PetscInt b = 0; b <= dim; ++b) {
      PetscReal gg = 0;
      for (PetscInt k = 0; k < dim; ++k) gg += g[a][k] * g[b][k];
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt j = 0; j < dim; ++j) Ke[(a * dim + i) * n + b * dim + j] = vol * (lambda * g[a][i] * g[b][j] + mu * g[a][j] * g[b][i] + (i == j ? mu * gg : 0));
    }
}

/* Assembles the stiffness (Lame lambda, mu; plane strain in 2D) into K and the consistent mass
 * (density rho) into M, one pass over the cells. M may be NULL (a lumped mass needs only K). Both
 * come from DMCreateMatrix on dm; their entries are replaced. */
PetscErrorCode MMAssembleP1(DM dm, PetscReal lambda, PetscReal mu, PetscReal rho, Mat K, Mat M)
{
  VertexTable t;
  PetscInt    dim, depth, cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCheck(dim == 2 || dim == 3, PetscObjectComm((PetscObject)dm), PETSC_ERR_SUP, "Closed-form assembly is for triangles and tetrahedra, not dimension %" PetscInt_FMT, dim);
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(VertexTableCreate(dm, &t));
  PetscCall(MatZeroEntries(K));
  if (M) PetscCall(MatZeroEntries(M));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    const PetscInt nv = dim + 1, n = nv * dim;
    /* int phi_a phi_b = vol (1 + delta_ab) / ((d+1)(d+2)) on a d-simplex */
    const PetscReal mscale = rho / (nv * (nv + 1));
    PetscInt        v[MM_NV_MAX], csize, idx[MM_NDOF_MAX], midx[MM_NV_MAX];
    PetscReal       x[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
    PetscScalar     Ke[MM_NDOF_MAX * MM_NDOF_MAX], Me[MM_NV_MAX * MM_NV_MAX];

    PetscCall(DMPlexGetConeSize(dm, c, &csize));
    PetscCheck(csize == nv, PETSC_COMM_SELF, PETSC_ERR_SUP, "Closed-form assembly needs simplices: cell %" PetscInt_FMT " has %" PetscInt_FMT " faces", c, csize);
    if (depth == 1) {
      const PetscInt *cone;
      PetscCall(DMPlexGetCone(dm, c, &cone));
      for (PetscInt a = 0; a < nv; ++a) v[a] = cone[a];
    } else PetscCall(SimplexVertices(dm, c, dim, v));
    for (PetscInt a = 0; a < nv; ++a)
      for (PetscInt i = 0; i < dim; ++i) {
        x[a][i]            = t.x[(v[a] - t.vStart) * dim + i];
        idx[a * dim + i] = t.dof[(v[a] - t.vStart) * dim + i];
      }
    PetscCall(SimplexGradients(dim, (const PetscReal(*)[MM_MAX_DIM])x, g, &vol));
    ElementStiffness(dim, lambda, mu, vol, (const PetscReal(*)[MM_MAX_DIM])g, Ke);
    PetscCall(MatSetValues(K, n, idx, n, idx, Ke, ADD_VALUES));
    if (!M) continue;
    /* the mass couples equal components only: one (d+1) x (d+1) block per component */
    for (PetscInt a = 0; a < nv; ++a)
      for (PetscInt b = 0; b < nv; ++b) Me[a * nv + b] = mscale * vol * (a == b ? 2 : 1);
    for (PetscInt i = 0; i < dim; ++i) {
      for (PetscInt a = 0; a < nv; ++a) midx[a] = idx[a * dim + i];
      PetscCall(MatSetValues(M, nv, midx, nv, midx, Me, ADD_VALUES));
    }
  }
  PetscCall(VertexTableDestroy(&t));
  /* both matrices' off-rank entries are sent before either is received */
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}
