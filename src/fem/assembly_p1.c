/* Closed-form P1 stiffness and consistent mass, assembled in one pass over the cells.
 *
 * The P1 shape functions of a simplex have constant gradients, so its stiffness is exact with one
 * point and its mass has a closed form: no quadrature, no tabulation, no PetscFE. DMPlex still
 * owns the mesh and the sections, and the matrices come from DMCreateMatrix: the dofs, the
 * preallocation and the dropped Dirichlet dofs are those of the PetscFE path (fem.c).
 *
 * The element matrices are added straight into the CSR value arrays of K and M. MatSetValues
 * costs a row search and a function call per element row and, once the matrix outgrows the cache,
 * most of the assembly time; here each pair of vertices of a cell costs one binary search, shared
 * by K and M and by all components. Rows owned by another rank still go through MatSetValues, to
 * be sent at assembly. */
#include "assembly_p1.h"
#include "mesh.h"
#include <petscblaslapack.h>

#define MM_NV_MAX   (MM_MAX_DIM + 1)
#define MM_NDOF_MAX (MM_NV_MAX * MM_MAX_DIM)

/* Per-vertex data gathered once, so the cell loop reads plain arrays: the dim global dof indices
 * of each vertex (negative for a Dirichlet-constrained component) and its coordinates. */
typedef struct {
  PetscInt   dim, vStart;
  PetscInt  *dof;
  PetscReal *x;
} VertexTable;

/* One sequential AIJ block of K and the same block of M. K and M come from DMCreateMatrix on the
 * same DM, so they share the nonzero pattern: one entry position serves both. */
typedef struct {
  Mat             K, M;
  PetscInt        nrows;
  const PetscInt *i, *j;
  PetscScalar    *k, *m;
} CSRBlock;

/* Where the locally owned rows of K and M live: the diagonal block (columns [cstart, cend), local
 * numbering) and, on several ranks, the off-diagonal one (columns through garray, which is sorted,
 * so a row's off-diagonal columns are in global order too). */
typedef struct {
  PetscInt        rstart, rend, cstart, cend;
  CSRBlock        d, o;
  const PetscInt *garray;
} CSRTarget;

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

/* The CSR arrays of one sequential AIJ block of K and of M. Entries are written in place, so the
 * pattern must be the one DMCreateMatrix filled and assembled, the same in K and M. */
static PetscErrorCode CSRBlockGet(Mat K, Mat M, CSRBlock *b)
{
  PetscInt        n, mrows;
  const PetscInt *mi, *mj;
  PetscBool       done, seqaij;
  MatType         type;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)K, MATSEQAIJ, &seqaij));
  PetscCall(MatGetType(K, &type));
  PetscCheck(seqaij, PetscObjectComm((PetscObject)K), PETSC_ERR_SUP, "Closed-form assembly writes AIJ matrices, not %s (use -assembly fe)", type);
  b->K = K;
  b->M = M;
  PetscCall(MatGetRowIJ(K, 0, PETSC_FALSE, PETSC_FALSE, &b->nrows, &b->i, &b->j, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "Closed-form assembly needs the CSR arrays of the stiffness matrix");
  PetscCall(MatSeqAIJGetArray(K, &b->k));
  b->m = NULL;
  if (!M) PetscFunctionReturn(0);
  PetscCall(MatGetRowIJ(M, 0, PETSC_FALSE, PETSC_FALSE, &mrows, &mi, &mj, &done));
  PetscCheck(done && mrows == b->nrows && mi[mrows] == b->i[b->nrows], PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP, "Closed-form assembly needs K and M with one nonzero pattern (both from DMCreateMatrix on the same DM)");
  n = mrows;
  PetscCall(MatRestoreRowIJ(M, 0, PETSC_FALSE, PETSC_FALSE, &n, &mi, &mj, &done));
  PetscCall(MatSeqAIJGetArray(M, &b->m));
  PetscFunctionReturn(0);
}

static PetscErrorCode CSRBlockRestore(CSRBlock *b)
{
  PetscBool done;

  PetscFunctionBeginUser;
  if (!b->K) PetscFunctionReturn(0);
  PetscCall(MatSeqAIJRestoreArray(b->K, &b->k));
  PetscCall(MatRestoreRowIJ(b->K, 0, PETSC_FALSE, PETSC_FALSE, &b->nrows, &b->i, &b->j, &done));
  if (b->M) PetscCall(MatSeqAIJRestoreArray(b->M, &b->m));
  PetscFunctionReturn(0);
}

/* An assembled matrix is needed: before its first assembly an AIJ matrix has room for its
 * entries but no column indices yet (DMCreateMatrix with -dm_preallocate_only). */
static PetscErrorCode CheckFilledPattern(Mat A)
{
  PetscBool assembled;

  PetscFunctionBeginUser;
  PetscCall(MatAssembled(A, &assembled));
  PetscCheck(assembled, PetscObjectComm((PetscObject)A), PETSC_ERR_ARG_WRONGSTATE, "Closed-form assembly writes into the nonzero pattern DMCreateMatrix fills; this matrix has none (was -dm_preallocate_only given?). Use -assembly fe");
  PetscFunctionReturn(0);
}

static PetscErrorCode CSRTargetGet(Mat K, Mat M, CSRTarget *t)
{
  PetscMPIInt size;
  Mat         Kd, Ko, Md = NULL, Mo = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(t, sizeof(*t)));
  PetscCall(CheckFilledPattern(K));
  if (M) PetscCall(CheckFilledPattern(M));
  PetscCall(MatGetOwnershipRange(K, &t->rstart, &t->rend));
  PetscCall(MatGetOwnershipRangeColumn(K, &t->cstart, &t->cend));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)K), &size));
  if (size == 1) {
    PetscCall(CSRBlockGet(K, M, &t->d));
    PetscFunctionReturn(0);
  }
  PetscCall(MatMPIAIJGetSeqAIJ(K, &Kd, &Ko, &t->garray));
  if (M) PetscCall(MatMPIAIJGetSeqAIJ(M, &Md, &Mo, NULL));
  PetscCall(CSRBlockGet(Kd, Md, &t->d));
  PetscCall(CSRBlockGet(Ko, Mo, &t->o));
  PetscFunctionReturn(0);
}

static PetscErrorCode CSRTargetRestore(CSRTarget *t)
{
  PetscFunctionBeginUser;
  PetscCall(CSRBlockRestore(&t->d));
  PetscCall(CSRBlockRestore(&t->o));
  PetscFunctionReturn(0);
}

/* Gradients g[a][i] of the P1 basis and the volume of the simplex with vertex coordinates x[a][i].
 * With J = [x_1 - x_0, ..., x_d - x_0], the reference coordinates are xi = J^{-1} (x - x_0), so
 * grad phi_a = row a-1 of J^{-1} (a >= 1) and grad phi_0 = -sum of the others. */
static PetscErrorCode SimplexGradients(PetscInt dim, const PetscReal x[][MM_MAX_DIM], PetscReal g[][MM_MAX_DIM], PetscReal *vol)
{
  PetscReal J[MM_MAX_DIM][MM_MAX_DIM], det, idet;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt k = 0; k < dim; ++k) J[i][k] = x[k + 1][i] - x[0][i];
  if (dim == 2) {
    det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    PetscCheck(det != 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Degenerate cell: zero volume");
    idet    = 1 / det;
    g[1][0] = J[1][1] * idet;
    g[1][1] = -J[0][1] * idet;
    g[2][0] = -J[1][0] * idet;
    g[2][1] = J[0][0] * idet;
    *vol    = PetscAbsReal(det) / 2;
  } else {
    /* rows of J^{-1}: the cofactors of J's columns, divided by det J */
    const PetscReal c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1], c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2], c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
    det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
    PetscCheck(det != 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Degenerate cell: zero volume");
    idet    = 1 / det;
    g[1][0] = c00 * idet;
    g[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * idet;
    g[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * idet;
    g[2][0] = c01 * idet;
    g[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * idet;
    g[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * idet;
    g[3][0] = c02 * idet;
    g[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * idet;
    g[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * idet;
    *vol    = PetscAbsReal(det) / 6;
  }
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
  const PetscInt  n = (dim + 1) * dim;
  const PetscReal l = vol * lambda, m = vol * mu;

  for (PetscInt a = 0; a <= dim; ++a)
    for (PetscInt b = 0; b <= dim; ++b) {
      PetscReal gg = 0;
      for (PetscInt k = 0; k < dim; ++k) gg += g[a][k] * g[b][k];
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt j = 0; j < dim; ++j) Ke[(a * dim + i) * n + b * dim + j] = l * g[a][i] * g[b][j] + m * g[a][j] * g[b][i] + (i == j ? m * gg : 0);
    }
}

/* The position of column col in the sorted row of a block: diagonal columns are local indices,
 * off-diagonal ones index garray. -1 if the pattern lacks it. */
static inline PetscInt FindColumn(const PetscInt *j, PetscInt lo, PetscInt end, const PetscInt *garray, PetscInt col)
{
  PetscInt hi = end;

  while (lo < hi) {
    const PetscInt mid = lo + (hi - lo) / 2, c = garray ? garray[j[mid]] : j[mid];
    if (c < col) lo = mid + 1;
    else hi = mid;
  }
  return lo < end && (garray ? garray[j[lo]] : j[lo]) == col ? lo : -1;
}

/* Adds the block of vertex pair (a, b) to the owned rows of a: the components of a vertex are
 * consecutive in a row and share their pattern (DMPlex's adjacency is per point), so one search in
 * a's first row places all dim x dim entries of K and the dim diagonal ones of M. */
static PetscErrorCode AddVertexPair(const CSRTarget *t, PetscInt dim, const PetscInt da[], const PetscInt db[], PetscInt a, PetscInt b, const PetscScalar Ke[], PetscScalar mab)
{
  const PetscInt  n = (dim + 1) * dim;
  PetscInt        ra = -1, cb = -1, rel;
  const CSRBlock *blk;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dim && ra < 0; ++i) ra = da[i];
  for (PetscInt j = 0; j < dim && cb < 0; ++j) cb = db[j];
  if (ra < 0 || cb < 0) PetscFunctionReturn(0); /* all components of a or b are constrained */
  ra -= t->rstart;
  if (cb >= t->cstart && cb < t->cend) {
    blk = &t->d;
    rel = FindColumn(blk->j, blk->i[ra], blk->i[ra + 1], NULL, cb - t->cstart);
  } else {
    blk = &t->o;
    rel = blk->K ? FindColumn(blk->j, blk->i[ra], blk->i[ra + 1], t->garray, cb) : -1;
  }
  PetscCheck(rel >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Closed-form assembly: global column %" PetscInt_FMT " is not in the pattern of row %" PetscInt_FMT, cb, ra + t->rstart);
  rel -= blk->i[ra];
  for (PetscInt i = 0; i < dim; ++i) {
    PetscInt row;
    if (da[i] < 0) continue;
    row = blk->i[da[i] - t->rstart] + rel - cb;
    for (PetscInt j = 0; j < dim; ++j) {
      if (db[j] < 0) continue;
      blk->k[row + db[j]] += Ke[(a * dim + i) * n + b * dim + j];
    }
    if (blk->m && db[i] >= 0) blk->m[row + db[i]] += mab;
  }
  PetscFunctionReturn(0);
}

/* The rows of vertex a of the element matrices, when another rank owns them: MatSetValues stashes
 * them until the assembly sends them. Only cells on the partition boundary have such vertices. */
static PetscErrorCode AddGhostRows(Mat K, Mat M, PetscInt dim, const PetscInt idx[], PetscInt a, const PetscScalar Ke[], const PetscScalar Me[])
{
  const PetscInt nv = dim + 1, n = nv * dim;

  PetscFunctionBeginUser;
  PetscCall(MatSetValues(K, dim, &idx[a * dim], n, idx, &Ke[a * dim * n], ADD_VALUES));
  if (!M) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < dim; ++i) {
    PetscInt midx[MM_NV_MAX];
    for (PetscInt b = 0; b < nv; ++b) midx[b] = idx[b * dim + i];
    PetscCall(MatSetValues(M, 1, &idx[a * dim + i], nv, midx, &Me[a * nv], ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/* Cell c's vertices, their coordinates and global dof indices from the vertex table */
static PetscErrorCode GatherCell(DM dm, PetscInt depth, const VertexTable *vt, PetscInt c, PetscInt v[], PetscReal x[][MM_MAX_DIM], PetscInt idx[])
{
  const PetscInt dim = vt->dim;

  PetscFunctionBeginUser;
  PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
  for (PetscInt a = 0; a <= dim; ++a)
    for (PetscInt i = 0; i < dim; ++i) {
      x[a][i]          = vt->x[(v[a] - vt->vStart) * dim + i];
      idx[a * dim + i] = vt->dof[(v[a] - vt->vStart) * dim + i];
    }
  PetscFunctionReturn(0);
}

/* Adds a cell's element matrices to K and M (M and Me may be NULL): its owned rows in place, the
 * others through MatSetValues */
static PetscErrorCode AddElement(const CSRTarget *t, Mat K, Mat M, PetscInt dim, const PetscInt idx[], const PetscScalar Ke[], const PetscScalar Me[])
{
  const PetscInt nv = dim + 1;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < nv; ++a) {
    PetscInt r = -1;
    for (PetscInt i = 0; i < dim && r < 0; ++i) r = idx[a * dim + i];
    if (r < 0) continue;
    if (r < t->rstart || r >= t->rend) {
      PetscCall(AddGhostRows(K, M, dim, idx, a, Ke, Me));
      continue;
    }
    for (PetscInt b = 0; b < nv; ++b) PetscCall(AddVertexPair(t, dim, &idx[a * dim], &idx[b * dim], a, b, Ke, Me ? Me[a * nv + b] : 0));
  }
  PetscFunctionReturn(0);
}

/* Computes the element matrices of cell c and adds them to K and M. */
static PetscErrorCode AddCell(DM dm, PetscInt depth, const VertexTable *vt, const CSRTarget *t, PetscReal lambda, PetscReal mu, PetscReal rho, Mat K, Mat M, PetscInt c)
{
  const PetscInt  dim = vt->dim, nv = dim + 1;
  /* int phi_a phi_b = vol (1 + delta_ab) / ((d+1)(d+2)) on a d-simplex */
  const PetscReal mscale = rho / (nv * (nv + 1));
  PetscInt        v[MM_NV_MAX], idx[MM_NDOF_MAX];
  PetscReal       x[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
  PetscScalar     Ke[MM_NDOF_MAX * MM_NDOF_MAX], Me[MM_NV_MAX * MM_NV_MAX];

  PetscFunctionBeginUser;
  PetscCall(GatherCell(dm, depth, vt, c, v, x, idx));
  PetscCall(SimplexGradients(dim, (const PetscReal(*)[MM_MAX_DIM])x, g, &vol));
  ElementStiffness(dim, lambda, mu, vol, (const PetscReal(*)[MM_MAX_DIM])g, Ke);
  for (PetscInt a = 0; a < nv; ++a)
    for (PetscInt b = 0; b < nv; ++b) Me[a * nv + b] = mscale * vol * (a == b ? 2 : 1);
  PetscCall(AddElement(t, K, M, dim, idx, Ke, Me));
  PetscFunctionReturn(0);
}

/* Adds the element matrix that element() computes for cell c to K (its owned rows in place, the
 * others through MatSetValues): the finite-strain tangent's path (src/fem/elasticity.c). */
static PetscErrorCode AddCellElement(DM dm, PetscInt depth, const VertexTable *vt, const CSRTarget *t, Mat K, PetscInt c, MMP1ElementFn element, void *ctx)
{
  const PetscInt dim = vt->dim;
  PetscInt       v[MM_NV_MAX], idx[MM_NDOF_MAX];
  PetscReal      x[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
  PetscScalar    Ke[MM_NDOF_MAX * MM_NDOF_MAX];

  PetscFunctionBeginUser;
  PetscCall(GatherCell(dm, depth, vt, c, v, x, idx));
  PetscCall(SimplexGradients(dim, (const PetscReal(*)[MM_MAX_DIM])x, g, &vol));
  PetscCall((*element)(ctx, c, v, (const PetscReal(*)[MM_MAX_DIM])g, vol, Ke));
  PetscCall(AddElement(t, K, NULL, dim, idx, Ke, NULL));
  PetscFunctionReturn(0);
}

/* K = sum_T K_T with K_T from element(): K from DMCreateMatrix on dm (or a matrix of its pattern, such as
 * the rotated stiffness), its entries replaced. */
PetscErrorCode MMAssembleP1Elements(DM dm, Mat K, MMP1ElementFn element, void *ctx)
{
  VertexTable vt;
  CSRTarget   t;
  PetscInt    depth, cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(VertexTableCreate(dm, &vt));
  PetscCall(MatZeroEntries(K));
  PetscCall(CSRTargetGet(K, NULL, &t));
  for (PetscInt c = cStart; c < cEnd; ++c) PetscCall(AddCellElement(dm, depth, &vt, &t, K, c, element, ctx));
  PetscCall(CSRTargetRestore(&t));
  PetscCall(VertexTableDestroy(&vt));
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The P1 basis gradients and volume of cell c (coordinates from the local coordinate vector) */
PetscErrorCode MMP1CellGradients(PetscInt dim, const PetscReal x[][MM_MAX_DIM], PetscReal g[][MM_MAX_DIM], PetscReal *vol)
{
  PetscFunctionBeginUser;
  PetscCall(SimplexGradients(dim, x, g, vol));
  PetscFunctionReturn(0);
}

/* Assembles the stiffness (each cell's Lame lambda, mu from mat; plane strain in 2D) into K and the
 * consistent mass (its density rho) into M, one pass over the cells: K = sum_T K_T(lambda_T, mu_T),
 * M = sum_T rho_T M_T (docs/method.md section 2, "Bodies"). M may be NULL (a lumped mass needs
 * only K). Both come from DMCreateMatrix on dm (M may be K's duplicate), dm the mesh of mat or a
 * clone of it; their entries are replaced. */
PetscErrorCode MMAssembleP1(DM dm, const MMMaterial *mat, Mat K, Mat M)
{
  VertexTable vt;
  CSRTarget   t;
  PetscInt    dim, depth, cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCheck(dim == 2 || dim == 3, PetscObjectComm((PetscObject)dm), PETSC_ERR_SUP, "Closed-form assembly is for triangles and tetrahedra, not dimension %" PetscInt_FMT, dim);
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(VertexTableCreate(dm, &vt));
  PetscCall(MatZeroEntries(K));
  if (M) PetscCall(MatZeroEntries(M));
  PetscCall(CSRTargetGet(K, M, &t));
  PetscCheck(cStart == mat->cStart && cEnd - cStart == mat->ncells, PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP, "Closed-form assembly: the mesh has cells [%" PetscInt_FMT ", %" PetscInt_FMT "), the material %" PetscInt_FMT " from %" PetscInt_FMT, cStart, cEnd, mat->ncells, mat->cStart);
  for (PetscInt c = cStart; c < cEnd; ++c) PetscCall(AddCell(dm, depth, &vt, &t, mat->lambda[c - cStart], mat->mu[c - cStart], mat->rho[c - cStart], K, M, c));
  PetscCall(CSRTargetRestore(&t));
  PetscCall(VertexTableDestroy(&vt));
  /* both matrices' off-rank rows are sent before either is received */
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The block size of the P1 operators: dim when no vertex has a Dirichlet-constrained component (the
 * dofs then come in whole vertices), else 1; as DMCreateMatrix sets it. */
static PetscErrorCode P1BlockSize(DM dm, const VertexTable *vt, PetscInt nv, PetscInt *bs)
{
  PetscInt whole = 1;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nv * vt->dim && whole; ++i) whole = vt->dof[i] >= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &whole, 1, MPIU_INT, MPI_MIN, PetscObjectComm((PetscObject)dm)));
  *bs = whole ? vt->dim : 1;
  PetscFunctionReturn(0);
}

/* Marks the couplings of vertex a with its n neighbours b[] (a among them) in the preallocator P,
 * row a only: with bs = dim one entry stands for the vertex block; with bs = 1 every free component
 * pair. Rows owned elsewhere go through P's stash to their owner, which merges them with its own
 * (the edges of the partition boundary come from both ranks, the ones only the other rank's cells
 * hold from it alone). */
static PetscErrorCode MarkVertexRow(Mat P, const VertexTable *vt, PetscInt bs, PetscInt a, PetscInt n, const PetscInt b[], PetscInt cols[], PetscScalar zeros[])
{
  const PetscInt *da = &vt->dof[(a - vt->vStart) * vt->dim];
  const PetscInt  m  = bs > 1 ? 1 : vt->dim;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; ++k)
    for (PetscInt c = 0; c < m; ++c) cols[k * m + c] = vt->dof[(b[k] - vt->vStart) * vt->dim + c];
  PetscCall(MatSetValues(P, m, da, n * m, cols, zeros, INSERT_VALUES));
  PetscFunctionReturn(0);
}

/* Each local vertex's neighbours (itself and the vertices it shares a cell with), sorted and
 * unique, in CSR form: a vertex pair is marked once, where the cells hold it about five times. */
static PetscErrorCode VertexNeighbours(DM dm, PetscInt depth, PetscInt dim, PetscInt vStart, PetscInt vEnd, PetscInt **offsets, PetscInt **nbrs)
{
  const PetscInt nv = vEnd - vStart;
  PetscInt       cStart, cEnd, *off, *nb, *fill;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscCalloc1(nv + 1, &off));
  PetscCall(PetscCalloc1(PetscMax(nv, 1), &fill));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt v[MM_NV_MAX];
    PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
    for (PetscInt a = 0; a <= dim; ++a) off[v[a] - vStart + 1] += dim + 1;
  }
  for (PetscInt i = 0; i < nv; ++i) off[i + 1] += off[i];
  PetscCall(PetscMalloc1(PetscMax(off[nv], 1), &nb));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt v[MM_NV_MAX];
    PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
    for (PetscInt a = 0; a <= dim; ++a)
      for (PetscInt b = 0; b <= dim; ++b) nb[off[v[a] - vStart] + fill[v[a] - vStart]++] = v[b];
  }
  /* sorted, unique, compacted in place */
  {
    PetscInt w = 0;
    for (PetscInt i = 0; i < nv; ++i) {
      PetscInt n = off[i + 1] - off[i];
      PetscCall(PetscSortRemoveDupsInt(&n, nb + off[i]));
      PetscCall(PetscArraymove(nb + w, nb + off[i], n));
      off[i] = w;
      w += n;
    }
    off[nv] = w;
  }
  PetscCall(PetscFree(fill));
  *offsets = off;
  *nbrs    = nb;
  PetscFunctionReturn(0);
}

/* The matrix the closed-form assembly fills (MMAssembleP1): an AIJ matrix on the DM's global
 * section whose pattern, filled with zeros and assembled, couples exactly the vertices that share
 * an edge, with each vertex's free dofs; what DMCreateMatrix builds for P1, which gets it from the
 * DMPlex point adjacency at several times the cost of the assembly itself (docs/scaling.md, "Assembly of K
 * and M, measured"). Here the couplings are the cells' vertex pairs, each marked once per row (the mesh has no
 * edges: src/mesh/facets.c), and MATPREALLOCATOR merges them across ranks. */
PetscErrorCode MMCreateMatrixP1(DM dm, Mat *A)
{
  MPI_Comm               comm = PetscObjectComm((PetscObject)dm);
  VertexTable            vt;
  PetscSection           gs;
  Mat                    P;
  PetscInt               n, bs = 1, depth, dim, vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(VertexTableCreate(dm, &vt));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(P1BlockSize(dm, &vt, vEnd - vStart, &bs));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(PetscSectionGetConstrainedStorageSize(gs, &n));
  PetscCall(MatCreate(comm, &P));
  PetscCall(MatSetSizes(P, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(P, bs));
  PetscCall(MatSetType(P, MATPREALLOCATOR));
  PetscCall(MatSetUp(P));
  {
    PetscInt    *off = NULL, *nb = NULL, maxn = 0, *cols;
    PetscScalar *zeros;
    PetscCall(VertexNeighbours(dm, depth, dim, vStart, vEnd, &off, &nb));
    for (PetscInt i = 0; i < vEnd - vStart; ++i) maxn = PetscMax(maxn, off[i + 1] - off[i]);
    PetscCall(PetscMalloc1(maxn * dim, &cols));
    PetscCall(PetscCalloc1(maxn * dim * dim, &zeros));
    for (PetscInt v = vStart; v < vEnd; ++v) PetscCall(MarkVertexRow(P, &vt, bs, v, off[v - vStart + 1] - off[v - vStart], nb + off[v - vStart], cols, zeros));
    PetscCall(PetscFree(cols));
    PetscCall(PetscFree(zeros));
    PetscCall(PetscFree(off));
    PetscCall(PetscFree(nb));
  }
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreate(comm, A));
  PetscCall(MatSetSizes(*A, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(*A, bs));
  PetscCall(MatSetType(*A, MATAIJ));
  PetscCall(MatPreallocatorPreallocate(P, PETSC_TRUE, *A));
  PetscCall(MatDestroy(&P));
  PetscCall(MatSetDM(*A, dm));
  PetscCall(VertexTableDestroy(&vt));
  PetscFunctionReturn(0);
}

/* The elastic force K x and energy 1/2 x.K x of a Cartesian local vector x (all dofs, constrained ones
 * included), cell by cell with each cell's material: what the PetscFE residual and integral of the
 * elastic energy compute with one material (fem.c). f (a local vector, added to) and energy (summed
 * over ranks) may each be NULL. */
PetscErrorCode MMApplyP1(DM dm, const MMMaterial *mat, Vec x, Vec f, PetscReal *energy)
{
  PetscSection       ls, cs;
  Vec                coords;
  const PetscScalar *xa, *xc;
  PetscScalar       *fa = NULL;
  PetscInt           dim, depth, cStart, cEnd;
  PetscReal          e = 0;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCheck(cStart == mat->cStart && cEnd - cStart == mat->ncells, PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP, "Closed-form elastic force: the mesh's cells are not the material's");
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xc));
  PetscCall(VecGetArrayRead(x, &xa));
  if (f) PetscCall(VecGetArray(f, &fa));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    const PetscInt nv = dim + 1, n = nv * dim;
    PetscInt       v[MM_NV_MAX], off[MM_NV_MAX];
    PetscReal      X[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
    PetscScalar    Ke[MM_NDOF_MAX * MM_NDOF_MAX];

    PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
    for (PetscInt a = 0; a < nv; ++a) {
      PetscInt xo;
      PetscCall(PetscSectionGetOffset(cs, v[a], &xo));
      PetscCall(PetscSectionGetOffset(ls, v[a], &off[a]));
      for (PetscInt i = 0; i < dim; ++i) X[a][i] = PetscRealPart(xc[xo + i]);
    }
    PetscCall(SimplexGradients(dim, (const PetscReal(*)[MM_MAX_DIM])X, g, &vol));
    ElementStiffness(dim, mat->lambda[c - cStart], mat->mu[c - cStart], vol, (const PetscReal(*)[MM_MAX_DIM])g, Ke);
    for (PetscInt a = 0; a < nv; ++a)
      for (PetscInt i = 0; i < dim; ++i) {
        PetscScalar r = 0;
        for (PetscInt b = 0; b < nv; ++b)
          for (PetscInt j = 0; j < dim; ++j) r += Ke[(a * dim + i) * n + b * dim + j] * xa[off[b] + j];
        if (fa) fa[off[a] + i] += r;
        e += 0.5 * PetscRealPart(r * xa[off[a] + i]);
      }
  }
  if (f) PetscCall(VecRestoreArray(f, &fa));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(coords, &xc));
  if (energy) PetscCall(MPIU_Allreduce(&e, energy, 1, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/* What the rotation needs of Q at one dof g: the dofs [first, first + n) of g's diagonal block of
 * Q, and row g of that block. Packed in PetscScalars, so VecScatter can bring them for the ghost
 * columns of K. */
#define MM_QINFO (2 + MM_MAX_DIM)
enum { MM_QINFO_FIRST, MM_QINFO_N, MM_QINFO_ROW };

/* The Q information of the owned dofs, into a vector of block size MM_QINFO. The rotation works
 * block by block: each row of Q must hold exactly the consecutive dofs of its block, as the
 * contact frames of docs/method.md section 2 do (one vertex's dofs, or the dof alone). */
static PetscErrorCode QInfoCreate(Mat Q, Vec *info)
{
  PetscInt     rstart, rend;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(Q, &rstart, &rend));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)Q), (rend - rstart) * MM_QINFO, PETSC_DETERMINE, info));
  PetscCall(VecSetBlockSize(*info, MM_QINFO));
  PetscCall(VecZeroEntries(*info));
  PetscCall(VecGetArray(*info, &a));
  for (PetscInt r = rstart; r < rend; ++r) {
    PetscInt           ncols;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscScalar       *q = &a[(r - rstart) * MM_QINFO];
    PetscBool          ok;

    PetscCall(MatGetRow(Q, r, &ncols, &cols, &vals));
    ok = (PetscBool)(ncols > 0 && ncols <= MM_MAX_DIM && cols[0] <= r && r < cols[0] + ncols && cols[0] >= rstart && cols[0] + ncols <= rend);
    for (PetscInt k = 0; ok && k < ncols; ++k) {
      ok        = (PetscBool)(cols[k] == cols[0] + k);
      q[MM_QINFO_ROW + k] = vals[k];
    }
    q[MM_QINFO_FIRST] = ok ? cols[0] : -1;
    q[MM_QINFO_N]     = ncols;
    PetscCall(MatRestoreRow(Q, r, &ncols, &cols, &vals));
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "The frame rotation Q is not block diagonal with blocks of consecutive owned dofs at row %" PetscInt_FMT, r);
  }
  for (PetscInt r = rstart; r < rend; ++r) {
    const PetscScalar *q = &a[(r - rstart) * MM_QINFO], *q0 = &a[((PetscInt)PetscRealPart(q[MM_QINFO_FIRST]) - rstart) * MM_QINFO];
    PetscCheck(q[MM_QINFO_N] == q0[MM_QINFO_N], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "The rows of the frame rotation Q's block at dof %" PetscInt_FMT " disagree on its size", r);
  }
  PetscCall(VecRestoreArray(*info, &a));
  PetscFunctionReturn(0);
}

/* The Q information of the off-diagonal columns of K, in garray order. */
static PetscErrorCode QInfoGhosts(Vec info, const PetscInt garray[], PetscInt ncols, Vec *ghosts)
{
  IS         is;
  VecScatter sc;

  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, ncols * MM_QINFO, ghosts));
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, MM_QINFO, ncols, garray, PETSC_COPY_VALUES, &is));
  PetscCall(VecScatterCreate(info, is, *ghosts, NULL, &sc));
  PetscCall(VecScatterBegin(sc, info, *ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, info, *ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Whether the block of Q whose rows start at q differs from the identity. */
static PetscBool QBlockRotates(const PetscScalar *q)
{
  const PetscInt n = (PetscInt)PetscRealPart(q[MM_QINFO_N]);

  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j)
      if (q[i * MM_QINFO + MM_QINFO_ROW + j] != (PetscScalar)(i == j)) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* B <- Qa^T B Qb for the na x nb block at offset rel of rows ra of blk, in K and in M; qa and qb
 * hold the rows of the two blocks of Q, MM_QINFO apart. */
static void RotateBlock(const CSRBlock *blk, PetscInt ra, PetscInt na, PetscInt rel, PetscInt nb, const PetscScalar *qa, const PetscScalar *qb)
{
  for (PetscInt s = 0; s < 2; ++s) {
    PetscScalar *val = s == 0 ? blk->k : blk->m, B[MM_MAX_DIM][MM_MAX_DIM], T[MM_MAX_DIM][MM_MAX_DIM];
    if (!val) continue;
    for (PetscInt i = 0; i < na; ++i)
      for (PetscInt j = 0; j < nb; ++j) B[i][j] = val[blk->i[ra + i] + rel + j];
    for (PetscInt i = 0; i < na; ++i)
      for (PetscInt j = 0; j < nb; ++j) {
        T[i][j] = 0;
        for (PetscInt k = 0; k < nb; ++k) T[i][j] += B[i][k] * qb[k * MM_QINFO + MM_QINFO_ROW + j];
      }
    for (PetscInt i = 0; i < na; ++i)
      for (PetscInt j = 0; j < nb; ++j) {
        PetscScalar sum = 0;
        for (PetscInt k = 0; k < na; ++k) sum += qa[k * MM_QINFO + MM_QINFO_ROW + i] * T[k][j];
        val[blk->i[ra + i] + rel + j] = sum;
      }
  }
}

/* Rotates the rows [ra, ra + na) of one Q block (local numbering) in the CSR block blk, whose
 * columns' Q information is cinfo (by local column): the row's columns are walked a Q block at a
 * time, as a block's dofs are consecutive columns, and only blocks that Q rotates are touched. */
static void RotateRows(const CSRBlock *blk, const PetscScalar *cinfo, const PetscScalar *qa, PetscBool rota, PetscInt ra, PetscInt na)
{
  for (PetscInt k = blk->i[ra]; k < blk->i[ra + 1];) {
    const PetscScalar *qb = &cinfo[blk->j[k] * MM_QINFO];
    const PetscInt     nb = (PetscInt)PetscRealPart(qb[MM_QINFO_N]);
    if (rota || QBlockRotates(qb)) RotateBlock(blk, ra, na, k - blk->i[ra], nb, qa, qb);
    k += nb;
  }
}

/*@
  MMRotateP1 - Rotates K and M into the contact frames in place, K <- Q^T K Q and M <- Q^T M Q, on
  the P1 pattern

  Collective

  Input Parameters:
+ Q - the frames, block diagonal with blocks of consecutive dofs
. K - the stiffness, rotated on return
- M - the mass, rotated on return (or NULL)

  Note:
  K <- Q^T K Q and M <- Q^T M Q in place, for K and M as MMAssembleP1 takes them (M may be NULL) and
  Q block diagonal with blocks of consecutive dofs, one rank's: the contact frames of
  docs/method.md section 2. A block of the result is Q_a^T K_ab Q_b, so the pattern stays (DMPlex
  couples all the dofs of two adjacent vertices) and only the blocks Q rotates change. MatPtAP
  would compute the same into a new matrix, after a symbolic product.

  Level: developer

.seealso: `MMContactSetUpFrame()`, `MMContactFrameMatrixEnd()`
@*/
PetscErrorCode MMRotateP1(Mat Q, Mat K, Mat M)
{
  CSRTarget          t;
  Vec                info, ghosts = NULL;
  const PetscScalar *qi, *qg = NULL;
  PetscInt           nco = 0;

  PetscFunctionBeginUser;
  PetscCall(QInfoCreate(Q, &info));
  PetscCall(CSRTargetGet(K, M, &t));
  PetscCheck(t.rstart == t.cstart && t.rend == t.cend, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "The frame rotation needs the same row and column layout");
  if (t.o.K) {
    PetscCall(MatGetSize(t.o.K, NULL, &nco));
    PetscCall(QInfoGhosts(info, t.garray, nco, &ghosts));
    PetscCall(VecGetArrayRead(ghosts, &qg));
  }
  PetscCall(VecGetArrayRead(info, &qi));
  for (PetscInt r = 0; r < t.rend - t.rstart;) {
    const PetscScalar *qa   = &qi[r * MM_QINFO];
    const PetscInt     na   = (PetscInt)PetscRealPart(qa[MM_QINFO_N]);
    const PetscBool    rota = QBlockRotates(qa);
    RotateRows(&t.d, qi, qa, rota, r, na);
    if (t.o.K) RotateRows(&t.o, qg, qa, rota, r, na);
    r += na;
  }
  PetscCall(VecRestoreArrayRead(info, &qi));
  if (ghosts) PetscCall(VecRestoreArrayRead(ghosts, &qg));
  PetscCall(CSRTargetRestore(&t));
  PetscCall(VecDestroy(&ghosts));
  PetscCall(VecDestroy(&info));
  /* nothing to send: the assembly only marks K and M as changed, for whatever caches on them */
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  if (M) PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The stiffness of the Rayleigh damping on the modified mass (docs/method.md section 3, "Rayleigh
 * damping of the massless dofs"): B = sum_T S_T, S_T the cell's stiffness in the w-frame with the
 * cell's massless dofs (qmark = 1: the contact-normal dofs) condensed out,
 *
 *   S_T = K_T,ff - K_T,fq K_T,qq^+ K_T,qf   on the cell's other dofs f, nothing on its q dofs.
 *
 * S_T is symmetric positive semi-definite and zero on the cell's rigid motions (K_T is, and the
 * range of K_T,qf lies in that of K_T,qq), so B leaves rigid motion undamped, has no row or column
 * on a massless dof, and lies in K's pattern. Cells without massless dofs give K_T itself. B is
 * assembled straight in the w-frame: Q's vertex blocks rotate each cell's matrix first. */

/* The w-frame data of every local vertex (owned or not): Q's dim x dim block and the massless
 * marks of its dofs, gathered by the vertices' global dofs. */
typedef struct {
  PetscScalar *q;    /* dim * dim per vertex: q[i * dim + k] = Q[dof_i, dof_k] */
  PetscScalar *mark; /* dim per vertex: 1 on a massless dof */
} VertexFrames;

static PetscErrorCode VertexFramesCreate(const VertexTable *vt, PetscInt nvert, Mat Q, Vec qmark, VertexFrames *f)
{
  const PetscInt     dim = vt->dim;
  PetscInt          *gi, n = 0;
  Vec                info, ginfo, gmark;
  IS                 is, ism;
  VecScatter         sc, scm;
  const PetscScalar *a, *m;

  PetscFunctionBeginUser;
  PetscCall(QInfoCreate(Q, &info));
  PetscCall(PetscMalloc1(nvert * dim, &gi));
  for (PetscInt k = 0; k < nvert * dim; ++k)
    if (vt->dof[k] >= 0) gi[n++] = vt->dof[k];
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n * MM_QINFO, &ginfo));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &gmark));
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, MM_QINFO, n, gi, PETSC_COPY_VALUES, &is));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, gi, PETSC_COPY_VALUES, &ism));
  PetscCall(VecScatterCreate(info, is, ginfo, NULL, &sc));
  PetscCall(VecScatterCreate(qmark, ism, gmark, NULL, &scm));
  PetscCall(VecScatterBegin(sc, info, ginfo, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterBegin(scm, qmark, gmark, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, info, ginfo, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scm, qmark, gmark, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(PetscCalloc2(nvert * dim * dim, &f->q, nvert * dim, &f->mark));
  PetscCall(VecGetArrayRead(ginfo, &a));
  PetscCall(VecGetArrayRead(gmark, &m));
  for (PetscInt v = 0, k = 0; v < nvert; ++v) {
    const PetscInt *dv = &vt->dof[v * dim];
    PetscInt        pos[MM_MAX_DIM];
    for (PetscInt i = 0; i < dim; ++i) pos[i] = dv[i] >= 0 ? k++ : -1;
    for (PetscInt i = 0; i < dim; ++i) {
      const PetscScalar *qi;
      PetscInt           first, nb;
      if (pos[i] < 0) continue;
      qi    = &a[pos[i] * MM_QINFO];
      first = (PetscInt)PetscRealPart(qi[MM_QINFO_FIRST]);
      nb    = (PetscInt)PetscRealPart(qi[MM_QINFO_N]);
      f->mark[v * dim + i] = m[pos[i]];
      for (PetscInt j = 0; j < dim; ++j)
        if (dv[j] >= first && dv[j] < first + nb) f->q[(v * dim + i) * dim + j] = qi[MM_QINFO_ROW + dv[j] - first];
    }
  }
  PetscCall(VecRestoreArrayRead(gmark, &m));
  PetscCall(VecRestoreArrayRead(ginfo, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecScatterDestroy(&scm));
  PetscCall(ISDestroy(&is));
  PetscCall(ISDestroy(&ism));
  PetscCall(VecDestroy(&ginfo));
  PetscCall(VecDestroy(&gmark));
  PetscCall(VecDestroy(&info));
  PetscCall(PetscFree(gi));
  PetscFunctionReturn(0);
}

/* Ke <- S: Ke rotated to the w-frame (Qe^T Ke Qe, Qe the cell's vertex blocks), then its massless
 * dofs condensed out by the pseudo-inverse of their block (eigenvalues below 1e-12 of the largest
 * dropped: a cell whose massless block is singular, which P1 cells on a smooth boundary never are,
 * still gives a semi-definite S). Constrained dofs are left out (the caller drops them). */
static PetscErrorCode CondenseCell(PetscInt dim, const PetscInt v[], PetscInt vStart, const PetscInt idx[], const VertexFrames *fr, PetscScalar Ke[])
{
  const PetscInt n = (dim + 1) * dim;
  PetscScalar    T[MM_NDOF_MAX * MM_NDOF_MAX], Kq[MM_NDOF_MAX * MM_NDOF_MAX], w[MM_NDOF_MAX], work[3 * MM_NDOF_MAX * MM_NDOF_MAX];
  PetscReal      ev[MM_NDOF_MAX], emax = 0;
  PetscInt       q[MM_NDOF_MAX], nq = 0;
  PetscBLASInt   bn, lwork = 3 * MM_NDOF_MAX * MM_NDOF_MAX, info;

  PetscFunctionBeginUser;
  /* T = Ke Qe, then Ke = Qe^T T: Qe is block diagonal, vertex a's block fr->q of v[a] */
  for (PetscInt r = 0; r < n; ++r)
    for (PetscInt b = 0; b <= dim; ++b) {
      const PetscScalar *qb = &fr->q[(v[b] - vStart) * dim * dim];
      for (PetscInt k = 0; k < dim; ++k) {
        PetscScalar s = 0;
        for (PetscInt j = 0; j < dim; ++j) s += Ke[r * n + b * dim + j] * qb[j * dim + k];
        T[r * n + b * dim + k] = s;
      }
    }
  for (PetscInt a = 0; a <= dim; ++a) {
    const PetscScalar *qa = &fr->q[(v[a] - vStart) * dim * dim];
    for (PetscInt k = 0; k < dim; ++k)
      for (PetscInt c = 0; c < n; ++c) {
        PetscScalar s = 0;
        for (PetscInt i = 0; i < dim; ++i) s += qa[i * dim + k] * T[(a * dim + i) * n + c];
        Ke[(a * dim + k) * n + c] = s;
      }
  }
  for (PetscInt a = 0; a <= dim; ++a)
    for (PetscInt k = 0; k < dim; ++k)
      if (idx[a * dim + k] >= 0 && PetscRealPart(fr->mark[(v[a] - vStart) * dim + k]) != 0) q[nq++] = a * dim + k;
  if (!nq) PetscFunctionReturn(0);
  /* K_qq = V diag(ev) V^T (LAPACK syev), K_qq^+ = V diag(1/ev) V^T on the kept eigenvalues */
  for (PetscInt i = 0; i < nq; ++i)
    for (PetscInt j = 0; j < nq; ++j) Kq[i * nq + j] = 0.5 * (Ke[q[i] * n + q[j]] + Ke[q[j] * n + q[i]]);
  PetscCall(PetscBLASIntCast(nq, &bn));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, Kq, &bn, ev, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (%d) on a cell's massless block", (int)info);
  for (PetscInt e = 0; e < nq; ++e) emax = PetscMax(emax, ev[e]);
  /* T = Ke - sum_e (Ke[:,q] V_e)(V_e^T Ke[q,:]) / ev_e, columns of V in Kq (column-major) */
  for (PetscInt i = 0; i < n * n; ++i) T[i] = Ke[i];
  for (PetscInt e = 0; e < nq; ++e) {
    if (ev[e] <= 1e-12 * emax) continue;
    for (PetscInt r = 0; r < n; ++r) {
      PetscScalar s = 0;
      for (PetscInt i = 0; i < nq; ++i) s += Ke[r * n + q[i]] * Kq[e * nq + i];
      w[r] = s;
    }
    for (PetscInt r = 0; r < n; ++r)
      for (PetscInt c = 0; c < n; ++c) T[r * n + c] -= w[r] * w[c] / ev[e];
  }
  /* symmetric to round-off; the massless rows and columns are zero exactly */
  for (PetscInt r = 0; r < n; ++r)
    for (PetscInt c = 0; c < n; ++c) Ke[r * n + c] = 0.5 * (T[r * n + c] + T[c * n + r]);
  for (PetscInt i = 0; i < nq; ++i)
    for (PetscInt c = 0; c < n; ++c) Ke[q[i] * n + c] = Ke[c * n + q[i]] = 0;
  PetscFunctionReturn(0);
}

/*@
  MMAssembleP1DampingStiffness - Assembles the Rayleigh damping stiffness B in the w-frame, each
  cell's massless dofs condensed out of its stiffness

  Collective

  Input Parameters:
+ dm    - the displacement DM
. mat   - the bodies' material
. Q     - the contact frames, block diagonal by vertex
. qmark - 1 on the massless dofs (w-frame), 0 elsewhere
- B     - the matrix of K's pattern, assembled on return

  Level: developer

.seealso: `MMContactDampingStiffness()`, `MMRotateP1()`
@*/
PetscErrorCode MMAssembleP1DampingStiffness(DM dm, const MMMaterial *mat, Mat Q, Vec qmark, Mat B)
{
  VertexTable  vt;
  VertexFrames fr;
  CSRTarget    t;
  PetscInt     dim, depth, cStart, cEnd, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(VertexTableCreate(dm, &vt));
  PetscCall(DMPlexGetDepthStratum(dm, 0, NULL, &vEnd));
  PetscCall(VertexFramesCreate(&vt, vEnd - vt.vStart, Q, qmark, &fr));
  PetscCall(MatZeroEntries(B));
  PetscCall(CSRTargetGet(B, NULL, &t));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    const PetscInt nv = dim + 1;
    PetscInt       v[MM_NV_MAX], idx[MM_NDOF_MAX];
    PetscReal      x[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
    PetscScalar    Ke[MM_NDOF_MAX * MM_NDOF_MAX];

    PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
    for (PetscInt a = 0; a < nv; ++a)
      for (PetscInt i = 0; i < dim; ++i) {
        x[a][i]          = vt.x[(v[a] - vt.vStart) * dim + i];
        idx[a * dim + i] = vt.dof[(v[a] - vt.vStart) * dim + i];
      }
    PetscCall(SimplexGradients(dim, (const PetscReal(*)[MM_MAX_DIM])x, g, &vol));
    ElementStiffness(dim, mat->lambda[c - cStart], mat->mu[c - cStart], vol, (const PetscReal(*)[MM_MAX_DIM])g, Ke);
    PetscCall(CondenseCell(dim, v, vt.vStart, idx, &fr, Ke));
    for (PetscInt a = 0; a < nv; ++a) {
      PetscInt r = -1;
      for (PetscInt i = 0; i < dim && r < 0; ++i) r = idx[a * dim + i];
      if (r < 0) continue;
      if (r < t.rstart || r >= t.rend) {
        PetscCall(AddGhostRows(B, NULL, dim, idx, a, Ke, NULL));
        continue;
      }
      for (PetscInt b = 0; b < nv; ++b) PetscCall(AddVertexPair(&t, dim, &idx[a * dim], &idx[b * dim], a, b, Ke, 0));
    }
  }
  PetscCall(CSRTargetRestore(&t));
  PetscCall(PetscFree2(fr.q, fr.mark));
  PetscCall(VertexTableDestroy(&vt));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}
