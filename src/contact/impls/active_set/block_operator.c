/* K~ in symmetric block storage (MATSBAIJ: one bs x bs block per pair of vertices, the upper
 * triangle of blocks only) for the products of the active-set CG. A P1 vector problem couples every
 * dof of a vertex to every dof of its neighbours, so K~'s AIJ pattern is made of full dim x dim
 * blocks; AIJ stores a column index per entry, block storage one per block, and K~ being symmetric
 * (SPD for every dt), the upper triangle of blocks holds all of it. A product is bound by the bytes
 * it reads, and SBAIJ reads about half of BAIJ's, which reads less than AIJ. PETSc 3.18's MatConvert
 * from MPIAIJ inserts entry by entry, too slow, so the block matrix is preallocated from the AIJ
 * pattern and filled a block row at a time here; a new dt refills its values in place. The figures:
 * docs/scaling.md, "The figures behind the code's choices" and "Products in block storage". */
#include "active_setimpl.h"

/* The local CSR of K~'s diagonal (d) and off-diagonal (o) parts, and the o part's global columns. */
typedef struct {
  Mat             Ad, Ao; /* Ao NULL on one rank (SeqAIJ): an empty off-diagonal part */
  const PetscInt *di, *dj, *oi, *oj, *garray;
  PetscInt       *ozero;  /* the empty part's row starts */
  PetscInt        m, cstart, bs;
} AIJParts;

static PetscErrorCode PartsGet(Mat A, PetscInt dim, AIJParts *p)
{
  PetscInt  n;
  PetscBool done;

  PetscFunctionBeginUser;
  PetscCall(MatGetBlockSize(A, &p->bs));
  /* with Dirichlet conditions PETSc's K~ has block size 1, but where only whole vertices are
   * constrained its rows still come in whole blocks: the pattern check decides */
  if (p->bs == 1) p->bs = dim;
  PetscCall(MatGetOwnershipRangeColumn(A, &p->cstart, NULL));
  p->ozero = NULL;
  PetscCall(MMKtGetLocalBlocks(A, "-active_set_block_matrix", &p->Ad, &p->Ao, &p->garray));
  PetscCall(MatGetRowIJ(p->Ad, 0, PETSC_FALSE, PETSC_FALSE, &p->m, &p->di, &p->dj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "K~'s diagonal block gives no CSR");
  if (p->Ao) {
    PetscCall(MatGetRowIJ(p->Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &p->oi, &p->oj, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "K~'s off-diagonal block gives no CSR");
  } else {
    PetscCall(PetscCalloc1(p->m + 1, &p->ozero));
    p->oi = p->ozero;
    p->oj = NULL;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PartsRestore(AIJParts *p)
{
  PetscInt  n;
  PetscBool done;

  PetscFunctionBeginUser;
  PetscCall(MatRestoreRowIJ(p->Ad, 0, PETSC_FALSE, PETSC_FALSE, &n, &p->di, &p->dj, &done));
  if (p->Ao) PetscCall(MatRestoreRowIJ(p->Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &p->oi, &p->oj, &done));
  PetscCall(PetscFree(p->ozero));
  PetscFunctionReturn(0);
}

/* Global column of entry k of a part: local in d (shift: the first owned column), an index into
 * garray (map) in o. */
static inline PetscInt GlobalColumn(const PetscInt *ja, const PetscInt *map, PetscInt shift, PetscInt k)
{
  return (map ? map[ja[k]] : ja[k]) + shift;
}

/* The first entry of row r0 of a part in the upper triangle of blocks (block column >= jrow, the
 * only blocks SBAIJ stores), and how many entries from there: a row's columns are sorted (the o
 * part's global columns too, garray being sorted), so the blocks left of the diagonal are a prefix.
 * The row is in whole blocks (BlockRow). */
static void UpperPart(const PetscInt *ia, const PetscInt *ja, const PetscInt *map, PetscInt shift, PetscInt bs, PetscInt r0, PetscInt jrow, PetscInt *k0, PetscInt *n)
{
  const PetscInt len = ia[r0 + 1] - ia[r0];

  *k0 = 0;
  while (*k0 < len && GlobalColumn(ja + ia[r0], map, shift, *k0) / bs < jrow) *k0 += bs;
  *n = len - *k0;
}

/* Whether the bs rows of block row ib have the same columns, in whole blocks: column c of the part
 * is global column g(c), and block q's bs columns are g = bs J, ..., bs J + bs - 1. Counts the row's
 * blocks in the upper triangle (J >= the row's global block index jrow). */
static PetscBool BlockRow(const PetscInt *ia, const PetscInt *ja, const PetscInt *map, PetscInt shift, PetscInt bs, PetscInt ib, PetscInt jrow, PetscInt *nb)
{
  const PetscInt r0 = bs * ib, len = ia[r0 + 1] - ia[r0];
  PetscInt       k0, n;

  if (len % bs) return PETSC_FALSE;
  for (PetscInt r = 1; r < bs; ++r) {
    if (ia[r0 + r + 1] - ia[r0 + r] != len) return PETSC_FALSE;
    for (PetscInt k = 0; k < len; ++k)
      if (ja[ia[r0 + r] + k] != ja[ia[r0] + k]) return PETSC_FALSE;
  }
  for (PetscInt k = 0; k < len; k += bs) {
    const PetscInt g0 = GlobalColumn(ja + ia[r0], map, shift, k);
    if (g0 % bs) return PETSC_FALSE;
    for (PetscInt j = 1; j < bs; ++j)
      if (GlobalColumn(ja + ia[r0], map, shift, k + j) != g0 + j) return PETSC_FALSE;
  }
  UpperPart(ia, ja, map, shift, bs, r0, jrow, &k0, &n);
  *nb = n / bs;
  return PETSC_TRUE;
}

/* Whether K~'s pattern is made of whole blocks on every rank (collective); if so, the upper
 * triangle's block counts of each block row in the two parts, for the preallocation. */
static PetscErrorCode BlockPattern(Mat A, const AIJParts *p, PetscInt dnnz[], PetscInt onnz[], PetscBool *ok)
{
  PetscInt  rstart;
  PetscBool mine;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(A, &rstart, NULL));
  mine = (PetscBool)(p->bs > 1 && p->m % p->bs == 0 && rstart % p->bs == 0 && p->cstart % p->bs == 0);
  for (PetscInt ib = 0; mine && ib < p->m / p->bs; ++ib) {
    const PetscInt jrow = rstart / p->bs + ib;
    mine = (PetscBool)(BlockRow(p->di, p->dj, NULL, p->cstart, p->bs, ib, jrow, &dnnz[ib]) && BlockRow(p->oi, p->oj, p->garray, 0, p->bs, ib, jrow, &onnz[ib]));
  }
  PetscCall(MPIU_Allreduce(&mine, ok, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)A)));
  PetscFunctionReturn(0);
}

/* B's values from A's, a block row at a time, its upper triangle of blocks (UpperPart). v holds the
 * kept blocks' bs rows, side by side (MatSetValuesBlocked's row-major layout). */
static PetscErrorCode FillBlocks(const AIJParts *p, const PetscScalar *da, const PetscScalar *oa, PetscInt rstart, PetscInt *cols, PetscScalar *v, Mat B)
{
  const PetscInt bs = p->bs;

  PetscFunctionBeginUser;
  for (PetscInt ib = 0; ib < p->m / bs; ++ib) {
    const PetscInt r0 = bs * ib, row = (rstart + r0) / bs;
    PetscInt       d0, o0, nd, no, w;

    UpperPart(p->di, p->dj, NULL, p->cstart, bs, r0, row, &d0, &nd);
    UpperPart(p->oi, p->oj, p->garray, 0, bs, r0, row, &o0, &no);
    w = nd + no;
    for (PetscInt k = 0; k < nd; k += bs) cols[k / bs] = GlobalColumn(p->dj + p->di[r0], NULL, p->cstart, d0 + k) / bs;
    for (PetscInt k = 0; k < no; k += bs) cols[(nd + k) / bs] = GlobalColumn(p->oj + p->oi[r0], p->garray, 0, o0 + k) / bs;
    for (PetscInt r = 0; r < bs; ++r) {
      PetscCall(PetscArraycpy(v + r * w, da + p->di[r0 + r] + d0, nd));
      PetscCall(PetscArraycpy(v + r * w + nd, oa + p->oi[r0 + r] + o0, no));
    }
    PetscCall(MatSetValuesBlocked(B, 1, &row, w / bs, cols, v, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Longest block row, in entries, for the fill's buffers. */
static PetscInt WidestRow(const AIJParts *p)
{
  PetscInt w = 0;
  for (PetscInt r = 0; r < p->m; ++r) w = PetscMax(w, p->di[r + 1] - p->di[r] + p->oi[r + 1] - p->oi[r]);
  return w;
}

/* *B (created on the first call, NULL when K~'s pattern is not in whole dim x dim blocks, e.g. a
 * vertex with only some of its dofs constrained) with A's values, its upper triangle of blocks. A is
 * AIJ (Seq or MPI) and symmetric, with the pattern every K~ of the run shares (K's). */
PetscErrorCode MMActiveSetBlockOperator(Mat A, PetscInt dim, Mat *B)
{
  AIJParts           p;
  PetscInt           rstart, M, N, n, *cols;
  const PetscScalar *da, *oa;
  PetscScalar       *v;
  PetscBool          ok = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(PartsGet(A, dim, &p));
  PetscCall(MatGetOwnershipRange(A, &rstart, NULL));
  if (!*B) {
    PetscInt *dnnz, *onnz;
    PetscCall(PetscMalloc2(PetscMax(1, p.m / PetscMax(1, p.bs)), &dnnz, PetscMax(1, p.m / PetscMax(1, p.bs)), &onnz));
    PetscCall(BlockPattern(A, &p, dnnz, onnz, &ok));
    if (ok) {
      PetscCall(MatGetSize(A, &M, &N));
      PetscCall(MatGetLocalSize(A, NULL, &n));
      PetscCall(MatCreateSBAIJ(PetscObjectComm((PetscObject)A), p.bs, p.m, n, M, N, 0, dnnz, 0, onnz, B));
      PetscCall(MatSetOption(*B, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    }
    PetscCall(PetscFree2(dnnz, onnz));
  }
  if (ok) {
    const PetscInt w = WidestRow(&p);
    PetscCall(PetscMalloc2(PetscMax(1, w), &cols, PetscMax(1, w * p.bs), &v));
    PetscCall(MatSeqAIJGetArrayRead(p.Ad, &da));
    oa = NULL;
    if (p.Ao) PetscCall(MatSeqAIJGetArrayRead(p.Ao, &oa));
    PetscCall(FillBlocks(&p, da, oa, rstart, cols, v, *B));
    PetscCall(MatSeqAIJRestoreArrayRead(p.Ad, &da));
    if (p.Ao) PetscCall(MatSeqAIJRestoreArrayRead(p.Ao, &oa));
    PetscCall(PetscFree2(cols, v));
  }
  PetscCall(PartsRestore(&p));
  PetscFunctionReturn(0);
}
