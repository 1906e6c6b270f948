/* The mass's rigid-body moments, and the redistributed modified mass (docs/method.md section 2,
 * "Mass redistribution").
 *
 * A mass matrix acts on rigid motions r = T(x) p (p: translation and rotation) through its Gram
 * matrix G = R^T M R, R the rigid modes: G holds the total mass, the first moments (the centre of
 * gravity) and the second moments (the inertia tensor). The modified mass M* drops the contact
 * nodes' normal mass, and with it part of G. -mass redistributed gives it back on the other nodes,
 * in node-diagonal blocks, so that G(M*) = G(M) exactly while M*'s normal rows and columns stay
 * zero (the paper's (3.5)):
 *  1. local: each cell gives the normal mass its contact vertices lose in it, rho |T| / (d+1)
 *     along the vertex's normal, to its vertices that are neither contact nor Dirichlet nodes, in
 *     equal parts. The removed mass stays where it was, within a cell;
 *  2. global: what the local step misses of G (the first and second moments it moves by a cell's
 *     size, and the share of cells with no such vertex) is matched exactly by the smallest
 *     correction D_j = m_j T_j Lambda T_j^T on the free non-contact nodes, weighted by their
 *     mass: Lambda solves sum_j m_j A_j Lambda A_j = G(M) - G(M* + local), A_j = T_j^T T_j, a
 *     6x6 (3x3 in 2D) system summed over the ranks. With several bodies each body's moments are
 *     matched on its own nodes, so that no mass moves from one body to another.
 * Both steps visit each cell and each node on exactly one rank, so M* is the same on any number
 * of ranks (to the order of the sums). */
#include "frameimpl.h"
#include <petscblaslapack.h>

/* What the redistribution reads and builds: the operators (M, M*, the lumped masses), the material
 * and the contact boundary; what it finds goes to mass, for the mass's view. */
typedef struct {
  MMOperators           op;
  const MMMaterial     *material;
  const MMMassBoundary *mb;
  MMContactMass        *mass;
  /* what it reads of fem's operators, fetched once (MassRedistGetFE) */
  DM                    dm, dms;     /* the mesh and its scalar vertex DM */
  PetscInt              dim;
  PetscBool             lumped;      /* -mass_lumped */
  Vec                   mass_lumped; /* the lumped standard mass per Cartesian dof */
  const MMCells        *cells;
} MassRedist;

static PetscErrorCode MassRedistGetFE(MassRedist *r)
{
  PetscFunctionBeginUser;
  PetscCall(MMFEGetDM(r->op, &r->dm));
  PetscCall(MMFEGetScalarDM(r->op, &r->dms));
  PetscCall(MMFEGetDimension(r->op, &r->dim));
  PetscCall(MMFEIsMassLumped(r->op, &r->lumped));
  PetscCall(MMFEGetLumpedMass(r->op, &r->mass_lumped));
  PetscCall(MMFEGetCells(r->op, &r->cells));
  PetscFunctionReturn(0);
}

/* The centre and half-diagonal of the mesh's bounding box: rigid modes about it, scaled by it, keep
 * the Gram matrices of order one whatever the units and the position of the body. */
static PetscErrorCode RigidFrame(MassRedist *r, PetscReal x0[], PetscReal *ell)
{
  const PetscInt dim = r->dim;
  PetscReal      lo[MM_MAX_DIM], hi[MM_MAX_DIM], d2 = 0;

  PetscFunctionBeginUser;
  PetscCall(DMGetBoundingBox(r->dm, lo, hi));
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) x0[d] = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    x0[d] = 0.5 * (lo[d] + hi[d]);
    d2 += 0.25 * (hi[d] - lo[d]) * (hi[d] - lo[d]);
  }
  *ell = PetscSqrtReal(d2);
  PetscFunctionReturn(0);
}

/* The rigid modes as w-frame vectors on the free dofs, about x0 and scaled by 1/ell. */
static PetscErrorCode RigidModes(MassRedist *r, const PetscReal x0[], PetscReal ell, Vec R[])
{
  const PetscInt nr = MMFENumRigidModes(r->dim);
  Vec            cart;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(r->dm, &cart));
  for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDuplicate(cart, &R[k]));
  PetscCall(MMFERigidModesCartesian(r->op, x0, ell, nr, R));
  for (PetscInt k = 0; k < nr; ++k) {
    PetscCall(MatMultTranspose(r->mass->Q, R[k], cart)); /* to the w-frame */
    PetscCall(VecCopy(cart, R[k]));
  }
  PetscCall(DMRestoreGlobalVector(r->dm, &cart));
  PetscFunctionReturn(0);
}

/* G = R^T A R: A's moments on the rigid modes. */
static PetscErrorCode Gram(Mat A, PetscInt nr, Vec R[], PetscReal G[MM_MAX_RIGID][MM_MAX_RIGID])
{
  Vec         AR;
  PetscScalar dots[MM_MAX_RIGID];

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(R[0], &AR));
  for (PetscInt k = 0; k < nr; ++k) {
    PetscCall(MatMult(A, R[k], AR));
    PetscCall(VecMDot(AR, nr, R, dots));
    for (PetscInt l = 0; l < nr; ++l) G[k][l] = PetscRealPart(dots[l]);
  }
  PetscCall(VecDestroy(&AR));
  PetscFunctionReturn(0);
}

/* Each local vertex's kind, ghosts included: 1 a contact node, 0 a free node, -1 a node with a
 * Dirichlet component; and each contact node's normal, component by component (n[d], all on the
 * scalar vertex DM: the set-up has no vector one yet). */
static PetscErrorCode VertexKinds(MassRedist *r, Vec *kind, Vec n[])
{
  const MMMassBoundary *ct = r->mb;
  DM             dms = r->dms;
  const PetscInt dim = r->dim;
  PetscSection   ls;
  PetscInt       vStart, vEnd, sstart;
  Vec            g;
  PetscScalar   *k;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dms, &g));
  PetscCall(VecGetOwnershipRange(g, &sstart, NULL));
  for (PetscInt d = -1; d < dim; ++d) {
    Vec *out = d < 0 ? kind : &n[d];
    PetscCall(VecZeroEntries(g));
    PetscCall(VecGetArray(g, &k));
    /* row 0 of a node's frame is its normal */
    for (PetscInt c = 0; c < ct->n; ++c)
      if (!ct->second[c]) k[ct->scalar_index[c] - sstart] = d < 0 ? 1.0 : ct->frame[9 * c + d];
    PetscCall(VecRestoreArray(g, &k));
    PetscCall(DMCreateLocalVector(dms, out));
    PetscCall(DMGlobalToLocal(dms, g, INSERT_VALUES, *out));
  }
  PetscCall(DMRestoreGlobalVector(dms, &g));
  /* the Dirichlet nodes, known on every rank from the local section */
  PetscCall(DMGetLocalSection(r->dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dms, 0, &vStart, &vEnd));
  PetscCall(VecGetArray(*kind, &k));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt off, cdof;
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    PetscCall(DMPlexGetPointLocal(dms, v, &off, NULL));
    if (cdof) k[off] = -1;
  }
  PetscCall(VecRestoreArray(*kind, &k));
  PetscFunctionReturn(0);
}

/* The global dof of a vertex's first component, owned or not (a ghost's offset is -(off + 1)). */
static PetscErrorCode VertexGlobalDof(PetscSection gs, PetscInt v, PetscInt *g)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSectionGetOffset(gs, v, g));
  if (*g < 0) *g = -(*g + 1);
  PetscFunctionReturn(0);
}

/* Step 1: each cell's lost normal mass to its free non-contact vertices. The blocks go in the
 * Cartesian frame, which is the w-frame of a non-contact node (docs/method.md section 8). */
static PetscErrorCode AddCellShares(MassRedist *r, Vec kind, Vec normal[], const PetscInt vgroup[], PetscInt group, PetscReal sign, Mat A)
{
  DM                 dm = r->dm, dms = r->dms;
  const PetscInt     dim = r->dim;
  PetscSection       gs;
  PetscInt           cStart, cEnd, vStart, vEnd;
  const PetscScalar *k, *n[MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(kind, &k));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecGetArrayRead(normal[d], &n[d]));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    const MMCells *cells = r->cells;
    PetscInt       contact[MM_MAX_DIM + 1], others[MM_MAX_DIM + 1], nc = 0, nf = 0;
    PetscReal      vol, B[MM_MAX_DIM][MM_MAX_DIM] = {{0}};
    PetscScalar    vals[MM_MAX_DIM * MM_MAX_DIM];

    for (PetscInt a = 0; a < cells->nv; ++a) {
      const PetscInt p = cells->vertex[cells->nv * (c - cStart) + a];
      PetscInt       off;
      PetscCall(DMPlexGetPointLocal(dms, p, &off, NULL));
      if (PetscRealPart(k[off]) > 0.5) contact[nc++] = p;
      else if (PetscRealPart(k[off]) > -0.5) others[nf++] = p;
    }
    if (!nc || !nf) continue; /* nothing lost here, or nowhere to put it: the global step's */
    if (vgroup && vgroup[others[0] - vStart] != group) continue;
    vol = cells->volume[c - cStart];
    for (PetscInt i = 0; i < nc; ++i) {
      PetscInt off;
      PetscCall(DMPlexGetPointLocal(dms, contact[i], &off, NULL));
      for (PetscInt a = 0; a < dim; ++a)
        for (PetscInt b = 0; b < dim; ++b) B[a][b] += sign * r->material->rho[c - cStart] * vol / (dim + 1) / nf * PetscRealPart(n[a][off] * n[b][off]);
    }
    for (PetscInt a = 0; a < dim; ++a)
      for (PetscInt b = 0; b < dim; ++b) vals[a * dim + b] = B[a][b];
    for (PetscInt j = 0; j < nf; ++j) {
      PetscInt g, idx[MM_MAX_DIM];
      PetscCall(VertexGlobalDof(gs, others[j], &g));
      for (PetscInt a = 0; a < dim; ++a) idx[a] = g + a;
      PetscCall(MatSetValues(A, dim, idx, dim, idx, vals, ADD_VALUES));
    }
  }
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecRestoreArrayRead(normal[d], &n[d]));
  PetscCall(VecRestoreArrayRead(kind, &k));
  PetscFunctionReturn(0);
}

/* The smallest eigenvalue of a symmetric dim x dim block. */
static PetscErrorCode SmallestEigenvalue(PetscInt dim, PetscReal D[MM_MAX_DIM][MM_MAX_DIM], PetscReal *lmin)
{
  PetscScalar  a[MM_MAX_DIM * MM_MAX_DIM], work[16 * MM_MAX_DIM];
  PetscReal    w[MM_MAX_DIM];
  PetscBLASInt n, lwork = 16 * MM_MAX_DIM, info;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(dim, &n));
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) a[i * dim + j] = D[i][j];
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &n, a, &n, w, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed with info %d", (int)info);
  *lmin = w[0];
  PetscFunctionReturn(0);
}

/* Step 2: the smallest mass-weighted node-block correction with moments dG, on the owned nodes
 * that may carry mass: the free non-contact nodes in every direction, the contact nodes in their
 * tangent plane only (P = I - n n^T: (3.5) stays exact, and the surface's lever arm restores the
 * inertia with small blocks). Minimizing sum_j |D_j|^2 / m_j under sum_j T_j^T D_j T_j = dG gives
 * D_j = m_j P_j T_j Lambda T_j^T P_j, Lambda solving sum_j m_j A_j Lambda A_j = dG with
 * A_j = T_j^T P_j T_j: an nr^2 system, summed over the ranks. */
static PetscErrorCode AddMomentCorrection(MassRedist *r, Vec kind, const PetscInt vgroup[], PetscInt group, const PetscReal x0[], PetscReal ell, PetscReal dG[MM_MAX_RIGID][MM_MAX_RIGID], Mat A, PetscBool *exceeded)
{
  DM                 dm = r->dm, dms = r->dms;
  const MMMassBoundary *ct = r->mb;
  const PetscInt     dim = r->dim, nr = MMFENumRigidModes(dim), n2 = nr * nr;
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);
  PetscSection       gs, cs;
  PetscInt           vStart, vEnd, rstart, *node;
  Vec                X;
  const PetscScalar *x, *k, *m;
  PetscReal          S[MM_MAX_RIGID * MM_MAX_RIGID * MM_MAX_RIGID * MM_MAX_RIGID] = {0}, lam[MM_MAX_RIGID * MM_MAX_RIGID], worst = 0;
  /* the consistent mass is at least 1/(d+2) of the lumped one (the P1 element matrix is
   * rho |T| (I + 1 1^T) / ((d+1)(d+2))): a block above -0.9 of that keeps M* positive definite */
  const PetscReal    floor = 0.9 / (r->lumped ? 1.0 : (PetscReal)(dim + 2));
  PetscBLASInt       bn, one = 1, info;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(vEnd - vStart, &node));
  for (PetscInt v = 0; v < vEnd - vStart; ++v) node[v] = -1;
  for (PetscInt c = 0; c < ct->n; ++c)
    if (!ct->second[c]) node[ct->vertex[c] - vStart] = c;
  PetscCall(VecGetOwnershipRange(r->mass_lumped, &rstart, NULL));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArrayRead(kind, &k));
  PetscCall(VecGetArrayRead(r->mass_lumped, &m));
  *exceeded = PETSC_FALSE;
  /* pass 0 sums the system, pass 1 measures the blocks, pass 2 adds them if they keep M* definite */
  for (PetscInt pass = 0; pass < 3; ++pass) {
    if (pass == 2) {
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPIU_MAX, comm));
      r->mass->correction = worst;
      if (worst > floor) { /* the bounded correction's (AddBoundedCorrection) */
        *exceeded = PETSC_TRUE;
        break;
      }
    }
    for (PetscInt v = vStart; v < vEnd; ++v) {
      PetscInt         goff, xoff, soff;
      PetscReal        xh[MM_MAX_DIM] = {0, 0, 0}, T[MM_MAX_DIM][MM_MAX_RIGID], PT[MM_MAX_DIM][MM_MAX_RIGID] = {{0}}, Aj[MM_MAX_RIGID][MM_MAX_RIGID] = {{0}}, mj;
      const PetscReal *F = node[v - vStart] >= 0 ? &ct->frame[9 * node[v - vStart]] : NULL;
      /* a corner node (its row followed by a second row, or a friction corner) is massless along tau_1 too */
      const PetscBool  corner = (PetscBool)(F && ((node[v - vStart] + 1 < ct->n && ct->second[node[v - vStart] + 1]) || (ct->fc_obstacle && ct->fc_obstacle[node[v - vStart]] >= 0)));

      PetscCall(PetscSectionGetOffset(gs, v, &goff));
      PetscCall(DMPlexGetPointLocal(dms, v, &soff, NULL));
      if (goff < 0 || PetscRealPart(k[soff]) < 0 || vgroup[v - vStart] != group) continue;
      PetscCall(PetscSectionGetOffset(cs, v, &xoff));
      mj = PetscRealPart(m[goff - rstart]);
      for (PetscInt d = 0; d < dim; ++d) xh[d] = (PetscRealPart(x[xoff + d]) - x0[d]) / ell;
      MMFERigidModeMatrix(dim, xh, T);
      /* PT = P T, P the projection on the tangent plane (the identity off the contact boundary) */
      for (PetscInt a = 0; a < dim; ++a)
        for (PetscInt c = 0; c < nr; ++c) {
          PT[a][c] = T[a][c];
          if (F)
            for (PetscInt b = 0; b < dim; ++b) PT[a][c] -= F[a] * F[b] * T[b][c];
          if (corner)
            for (PetscInt b = 0; b < dim; ++b) PT[a][c] -= F[3 + a] * F[3 + b] * T[b][c];
        }
      if (pass == 0) { /* S_{(ab),(cd)} += m_j A_ac A_bd */
        for (PetscInt a = 0; a < nr; ++a)
          for (PetscInt b = 0; b < nr; ++b)
            for (PetscInt c = 0; c < dim; ++c) Aj[a][b] += PT[c][a] * PT[c][b];
        for (PetscInt a = 0; a < nr; ++a)
          for (PetscInt b = 0; b < nr; ++b)
            for (PetscInt c = 0; c < nr; ++c)
              for (PetscInt d = 0; d < nr; ++d) S[(a * nr + b) * n2 + c * nr + d] += mj * Aj[a][c] * Aj[b][d];
      } else { /* D_j = m_j PT Lambda PT^T, symmetrized against the solve's round-off */
        PetscReal   D[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, W[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, lmin = 0;
        PetscScalar vals[MM_MAX_DIM * MM_MAX_DIM];
        PetscInt    idx[MM_MAX_DIM], first = F ? (corner ? 2 : 1) : 0, nb = dim - first;
        for (PetscInt a = 0; a < dim; ++a)
          for (PetscInt b = 0; b < dim; ++b)
            for (PetscInt c = 0; c < nr; ++c)
              for (PetscInt d = 0; d < nr; ++d) D[a][b] += 0.5 * mj * PT[a][c] * (lam[c * nr + d] + lam[d * nr + c]) * PT[b][d];
        if (pass == 1) {
          PetscCall(SmallestEigenvalue(dim, D, &lmin));
          worst = PetscMax(worst, -lmin / mj);
          continue;
        }
        /* in the node's w-frame, W = F D F^T (row e of F is the frame's e-th vector); the normal
         * row and column (e = 0) are not touched */
        for (PetscInt a = 0; a < dim; ++a)
          for (PetscInt b = 0; b < dim; ++b) {
            if (!F) W[a][b] = D[a][b];
            else
              for (PetscInt c = 0; c < dim; ++c)
                for (PetscInt d = 0; d < dim; ++d) W[a][b] += F[3 * a + c] * D[c][d] * F[3 * b + d];
          }
        for (PetscInt a = 0; a < nb; ++a) {
          idx[a] = goff + first + a;
          for (PetscInt b = 0; b < nb; ++b) vals[a * nb + b] = W[first + a][first + b];
        }
        PetscCall(MatSetValues(A, nb, idx, nb, idx, vals, ADD_VALUES));
      }
    }
    if (pass == 0) {
      /* S is singular: in 3D every node-block mass has tr(K G) = 0 for K = [[0, I], [I, 0]] (T K T^T
       * = 0 at every point), and so has dG; such directions of Lambda change no D_j. The
       * least-squares solution of least norm (SVD, LAPACK gelss) leaves them out. */
      PetscReal    sv[MM_MAX_RIGID * MM_MAX_RIGID], work[8 * MM_MAX_RIGID * MM_MAX_RIGID], rcond = 1e-12;
      PetscBLASInt rank, lwork = 8 * MM_MAX_RIGID * MM_MAX_RIGID;
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, S, n2 * n2, MPIU_REAL, MPIU_SUM, comm));
      for (PetscInt a = 0; a < nr; ++a)
        for (PetscInt b = 0; b < nr; ++b) lam[a * nr + b] = dG[a][b];
      PetscCall(PetscBLASIntCast(n2, &bn));
      PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
      PetscCallBLAS("LAPACKgelss", LAPACKgelss_(&bn, &bn, &one, S, &bn, lam, &bn, sv, &rcond, &rank, work, &lwork, &info));
      PetscCall(PetscFPTrapPop());
      PetscCheck(info == 0, comm, PETSC_ERR_LIB, "-mass redistributed: LAPACK gelss failed with info %d", (int)info);
    }
  }
  PetscCall(VecRestoreArrayRead(r->mass_lumped, &m));
  PetscCall(VecRestoreArrayRead(kind, &k));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(PetscFree(node));
  PetscFunctionReturn(0);
}

/* A node that may carry a correction, for the bounded correction: its first w-frame dof that may
 * carry mass (goff + first: the first after a contact node's normal, and after tau_1 at a corner),
 * their number k, its lumped mass, and B = V^T T (k x nr), its rigid modes on those dofs (V: the
 * frame's tangent vectors, the identity off the contact boundary). */
typedef struct {
  PetscInt  dof, k;
  PetscReal m, B[MM_MAX_DIM][MM_MAX_RIGID];
} MassNode;

static PetscErrorCode CollectMassNodes(MassRedist *r, Vec kind, const PetscInt vgroup[], PetscInt group, const PetscReal x0[], PetscReal ell, PetscInt *n, MassNode **nodes)
{
  DM                 dm = r->dm, dms = r->dms;
  const MMMassBoundary *ct = r->mb;
  const PetscInt     dim = r->dim, nr = MMFENumRigidModes(dim);
  PetscSection       gs, cs;
  PetscInt           vStart, vEnd, rstart, *node;
  Vec                X;
  const PetscScalar *x, *k, *m;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(vEnd - vStart, &node));
  PetscCall(PetscMalloc1(vEnd - vStart, nodes));
  for (PetscInt v = 0; v < vEnd - vStart; ++v) node[v] = -1;
  for (PetscInt c = 0; c < ct->n; ++c)
    if (!ct->second[c]) node[ct->vertex[c] - vStart] = c;
  PetscCall(VecGetOwnershipRange(r->mass_lumped, &rstart, NULL));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArrayRead(kind, &k));
  PetscCall(VecGetArrayRead(r->mass_lumped, &m));
  *n = 0;
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt         goff, xoff, soff, first;
    PetscReal        xh[MM_MAX_DIM] = {0, 0, 0}, T[MM_MAX_DIM][MM_MAX_RIGID];
    const PetscReal *F      = node[v - vStart] >= 0 ? &ct->frame[9 * node[v - vStart]] : NULL;
    const PetscBool  corner = (PetscBool)(F && node[v - vStart] + 1 < ct->n && ct->second[node[v - vStart] + 1]);
    MassNode        *nd     = &(*nodes)[*n];

    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    PetscCall(DMPlexGetPointLocal(dms, v, &soff, NULL));
    if (goff < 0 || PetscRealPart(k[soff]) < 0 || vgroup[v - vStart] != group) continue;
    first = F ? (corner ? 2 : 1) : 0;
    if (first >= dim) continue; /* a 2D corner: no dof with mass */
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    for (PetscInt d = 0; d < dim; ++d) xh[d] = (PetscRealPart(x[xoff + d]) - x0[d]) / ell;
    MMFERigidModeMatrix(dim, xh, T);
    nd->dof = goff + first;
    nd->k   = dim - first;
    nd->m   = PetscRealPart(m[goff - rstart]);
    /* row e of F is the frame's e-th vector: B's rows are the tangent vectors' components of T */
    for (PetscInt e = 0; e < nd->k; ++e)
      for (PetscInt c = 0; c < nr; ++c) {
        nd->B[e][c] = 0;
        if (!F) nd->B[e][c] = T[e][c];
        else
          for (PetscInt b = 0; b < dim; ++b) nd->B[e][c] += F[3 * (first + e) + b] * T[b][c];
      }
    ++*n;
  }
  PetscCall(VecRestoreArrayRead(r->mass_lumped, &m));
  PetscCall(VecRestoreArrayRead(kind, &k));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(PetscFree(node));
  PetscFunctionReturn(0);
}

/* The eigenvalues s (ascending) and eigenvectors (U[r][i]: component i of vector r) of a node's
 * symmetric k x k block S = B Lambda B^T. */
static PetscErrorCode NodeEigen(const MassNode *nd, PetscInt nr, const PetscReal L[MM_MAX_RIGID][MM_MAX_RIGID], PetscReal s[], PetscReal U[MM_MAX_DIM][MM_MAX_DIM])
{
  PetscScalar  a[MM_MAX_DIM * MM_MAX_DIM], work[16 * MM_MAX_DIM];
  PetscBLASInt n, lwork = 16 * MM_MAX_DIM, info;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nd->k; ++i)
    for (PetscInt j = 0; j < nd->k; ++j) {
      PetscReal sij = 0;
      for (PetscInt c = 0; c < nr; ++c)
        for (PetscInt d = 0; d < nr; ++d) sij += nd->B[i][c] * L[c][d] * nd->B[j][d];
      a[i * nd->k + j] = sij;
    }
  PetscCall(PetscBLASIntCast(nd->k, &n));
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, a, &n, s, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed with info %d", (int)info);
  for (PetscInt r = 0; r < nd->k; ++r)
    for (PetscInt i = 0; i < nd->k; ++i) U[r][i] = PetscRealPart(a[r * nd->k + i]);
  PetscFunctionReturn(0);
}

/* The dual of the bounded correction (docs/method.md section 2, "When the smallest correction would
 * make M* indefinite") at Lambda = sum_p lam_p E_p over the np moment pairs (pa[p], pb[p]):
 *   psi = sum_j c m_j tr(exp(S_j) - I - S_j) - <Lambda, dG>,  S_j = B_j Lambda B_j^T,
 * its gradient g_p = <E_p, sum_j B_j^T E_j B_j - dG> (E_j = c m_j (exp(S_j) - I), the correction)
 * and, with H != NULL, its Hessian H_pq = sum_j c m_j tr(Y_p Dexp_{S_j}[Y_q]), Y_p = B_j E_p B_j^T,
 * by the Daleckii-Krein formula in S_j's eigenbasis. *smax: the largest |eigenvalue| of any S_j. */
static PetscErrorCode BoundedDual(MPI_Comm comm, PetscInt n, const MassNode nodes[], PetscReal c, PetscInt nr, PetscInt np, const PetscInt pa[], const PetscInt pb[], const PetscReal lam[], PetscReal dG[MM_MAX_RIGID][MM_MAX_RIGID], PetscReal *psi, PetscReal g[], PetscReal H[], PetscReal *smax)
{
  const PetscInt np2 = np * np;
  PetscReal      L[MM_MAX_RIGID][MM_MAX_RIGID] = {{0}}, *sum; /* [psi, R (nr x nr), H (np x np), -smax] */
  const PetscInt nsum = 1 + MM_MAX_RIGID * MM_MAX_RIGID + np2;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nsum + 1, &sum));
  for (PetscInt p = 0; p < np; ++p) L[pa[p]][pb[p]] = L[pb[p]][pa[p]] = lam[p];
  sum[nsum] = -PETSC_MAX_REAL;
  for (PetscInt j = 0; j < n; ++j) {
    const MassNode *nd = &nodes[j];
    const PetscReal w  = c * nd->m;
    PetscReal       s[MM_MAX_DIM], U[MM_MAX_DIM][MM_MAX_DIM], C[MM_MAX_DIM][MM_MAX_RIGID] = {{0}}, ex[MM_MAX_DIM];

    PetscCall(NodeEigen(nd, nr, L, s, U));
    for (PetscInt r = 0; r < nd->k; ++r) {
      ex[r] = PetscExpReal(s[r]);
      sum[0] += w * (expm1(s[r]) - s[r]);
      sum[nsum] = PetscMax(sum[nsum], PetscAbsReal(s[r]));
      for (PetscInt a = 0; a < nr; ++a)
        for (PetscInt i = 0; i < nd->k; ++i) C[r][a] += U[r][i] * nd->B[i][a]; /* C = U^T B */
    }
    /* R = sum_j c m_j C^T diag(exp(s) - 1) C */
    for (PetscInt a = 0; a < nr; ++a)
      for (PetscInt b = 0; b < nr; ++b)
        for (PetscInt r = 0; r < nd->k; ++r) sum[1 + a * MM_MAX_RIGID + b] += w * C[r][a] * expm1(s[r]) * C[r][b];
    if (H) {
      PetscReal Gam[MM_MAX_DIM][MM_MAX_DIM], Y[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2][MM_MAX_DIM][MM_MAX_DIM];
      /* Gamma_rs = (e^{s_r} - e^{s_s}) / (s_r - s_s), e^{s_r} when they meet */
      for (PetscInt r = 0; r < nd->k; ++r)
        for (PetscInt q = 0; q < nd->k; ++q) Gam[r][q] = PetscAbsReal(s[r] - s[q]) < 1e-12 ? ex[r] : ex[q] * expm1(s[r] - s[q]) / (s[r] - s[q]);
      for (PetscInt p = 0; p < np; ++p)
        for (PetscInt r = 0; r < nd->k; ++r)
          for (PetscInt q = 0; q < nd->k; ++q) Y[p][r][q] = C[r][pa[p]] * C[q][pb[p]] + (pa[p] != pb[p] ? C[r][pb[p]] * C[q][pa[p]] : 0);
      for (PetscInt p = 0; p < np; ++p)
        for (PetscInt q = p; q < np; ++q) {
          PetscReal h = 0;
          for (PetscInt r = 0; r < nd->k; ++r)
            for (PetscInt t = 0; t < nd->k; ++t) h += Gam[r][t] * Y[p][r][t] * Y[q][r][t];
          sum[1 + MM_MAX_RIGID * MM_MAX_RIGID + p * np + q] += w * h;
        }
    }
  }
  sum[nsum] = -sum[nsum];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, nsum, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum[nsum], 1, MPIU_REAL, MPIU_MIN, comm));
  *psi  = sum[0];
  *smax = -sum[nsum];
  for (PetscInt p = 0; p < np; ++p) {
    const PetscInt  a = pa[p], b = pb[p];
    const PetscReal w = a == b ? 1.0 : 2.0; /* <E_p, X> for a symmetric X */
    *psi -= w * lam[p] * dG[a][b];
    g[p] = w * (sum[1 + a * MM_MAX_RIGID + b] - dG[a][b]);
  }
  if (H)
    for (PetscInt p = 0; p < np; ++p)
      for (PetscInt q = p; q < np; ++q) H[p * np + q] = H[q * np + p] = sum[1 + MM_MAX_RIGID * MM_MAX_RIGID + p * np + q];
  PetscCall(PetscFree(sum));
  PetscFunctionReturn(0);
}

/* The bounded correction, when the smallest one would take more than M* can lose (docs/method.md
 * section 2): D_j = c m_j V_j (exp(S_j) - I) V_j^T, S_j = B_j Lambda B_j^T, which is above -c m_j on
 * every node whatever Lambda, so M* stays positive definite; Lambda minimizes the convex dual
 * BoundedDual by Newton's method with a backtracking line search. To first order in Lambda it is
 * the smallest correction (AddMomentCorrection). moments: MM_MAX_RIGID matches every moment, dim
 * only the total masses and first moments (the pairs with a translation). *matched is false, and
 * nothing is added, when Newton's method finds no Lambda: the moments are out of the bound's reach. */
static PetscErrorCode AddBoundedCorrection(MassRedist *r, Vec kind, const PetscInt vgroup[], PetscInt group, const PetscReal x0[], PetscReal ell, PetscReal dG0[MM_MAX_RIGID][MM_MAX_RIGID], PetscInt moments, PetscReal mass, Mat A, PetscBool *matched)
{
  const PetscInt dim = r->dim, nr = MMFENumRigidModes(dim);
  MPI_Comm       comm = PetscObjectComm((PetscObject)r->dm);
  /* the bound of AddMomentCorrection: 0.9 of the consistent mass's margin 1/(d+2), or of all of a lumped one */
  const PetscReal c = 0.9 / (r->lumped ? 1.0 : (PetscReal)(dim + 2));
  PetscInt        n = 0, np = 0, pa[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], pb[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], it;
  PetscReal       dG[MM_MAX_RIGID][MM_MAX_RIGID], lam[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2] = {0}, psi, smax, res = PETSC_MAX_REAL, worst = 0;
  MassNode       *nodes;
  /* exp(30): a node given 1e13 times its mass, exp(-30): one stripped to its bound to 1e-13, and a
   * correction entropy of 1e3 times the mass: beyond, the moments are out of the bound's reach */
  const PetscReal smax_ok = 30, psi_ok = 1e3;

  PetscFunctionBeginUser;
  *matched = PETSC_FALSE;
  for (PetscInt a = 0; a < nr; ++a)
    for (PetscInt b = 0; b < nr; ++b) dG[a][b] = dG0[a][b];
  /* the trace of the translation-rotation block is out of any node block's reach (MomentMismatch):
   * left in, the dual would fall linearly along Lambda = [[0, I], [I, 0]] forever */
  if (nr == 6) {
    PetscReal k = 0;
    for (PetscInt a = 0; a < 3; ++a) k += dG[a][3 + a];
    for (PetscInt a = 0; a < 3; ++a) dG[a][3 + a] -= k / 3, dG[3 + a][a] -= k / 3;
  }
  for (PetscInt a = 0; a < nr; ++a)
    for (PetscInt b = a; b < nr; ++b)
      if (a < moments) pa[np] = a, pb[np] = b, ++np;
  PetscCall(CollectMassNodes(r, kind, vgroup, group, x0, ell, &n, &nodes));
  for (it = 0; it < 60; ++it) {
    PetscReal    g[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], H[MM_MAX_RIGID * MM_MAX_RIGID * (MM_MAX_RIGID + 1) * (MM_MAX_RIGID + 1) / 4], step[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], slope = 0, t = 1;
    PetscReal    sv[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], work[8 * MM_MAX_RIGID * MM_MAX_RIGID], rcond = 1e-15;
    PetscBLASInt bn, one = 1, rank, lwork = 8 * MM_MAX_RIGID * MM_MAX_RIGID, info;

    PetscCall(BoundedDual(comm, n, nodes, c, nr, np, pa, pb, lam, dG, &psi, g, H, &smax));
    res = 0;
    for (PetscInt p = 0; p < np; ++p) res = PetscMax(res, PetscAbsReal(g[p]));
    PetscCall(PetscInfo(NULL, "bounded mass correction, Newton step %" PetscInt_FMT ": psi %.15g, residual %g of the mass, largest exponent %g\n", it, (double)psi, (double)(res / mass), (double)smax));
    if (res <= 1e-14 * mass) break;
    /* Newton's step. The Hessian is singular along the trace direction Lambda = [[0, I], [I, 0]],
     * which changes no S_j and which dG no longer holds: a penalty on it makes it regular there
     * without changing the step, and the least-norm solve is left with the directions that far
     * out are ill-conditioned only */
    if (nr == 6) {
      PetscReal kappa = 0;
      for (PetscInt p = 0; p < np; ++p) kappa += H[p * np + p] / np;
      for (PetscInt p = 0; p < np; ++p)
        for (PetscInt q = 0; q < np; ++q)
          if (pb[p] == pa[p] + 3 && pb[q] == pa[q] + 3) H[p * np + q] += kappa / 3;
    }
    for (PetscInt p = 0; p < np; ++p) step[p] = -g[p];
    PetscCall(PetscBLASIntCast(np, &bn));
    PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
    PetscCallBLAS("LAPACKgelss", LAPACKgelss_(&bn, &bn, &one, H, &bn, step, &bn, sv, &rcond, &rank, work, &lwork, &info));
    PetscCall(PetscFPTrapPop());
    PetscCheck(info >= 0, comm, PETSC_ERR_LIB, "-mass redistributed: LAPACK gelss failed with info %d", (int)info);
    if (info > 0) break; /* no SVD of a Hessian that far out: the moments are out of reach */
    for (PetscInt p = 0; p < np; ++p) slope += g[p] * step[p];
    /* backtrack until psi falls (Armijo); psi is convex, so a descent step always exists */
    for (; t > 1e-12; t *= 0.5) {
      PetscReal trial[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], gt[MM_MAX_RIGID * (MM_MAX_RIGID + 1) / 2], psit, st;
      for (PetscInt p = 0; p < np; ++p) trial[p] = lam[p] + t * step[p];
      PetscCall(BoundedDual(comm, n, nodes, c, nr, np, pa, pb, trial, dG, &psit, gt, NULL, &st));
      if (st <= smax_ok && psit <= psi + 1e-4 * t * slope) {
        for (PetscInt p = 0; p < np; ++p) lam[p] = trial[p];
        break;
      }
    }
    /* no descent left within |S_j| <= smax_ok, or the dual falling without bound (its minimum is
     * minus the least correction entropy, a few times the mass when the moments are in reach) */
    if (t <= 1e-12 || psi < -psi_ok * mass) break;
  }
  PetscCall(PetscInfo(NULL, "bounded mass correction (%" PetscInt_FMT " moments): %" PetscInt_FMT " Newton steps, residual %g of the mass, largest exponent %g\n", np, it, (double)(res / mass), (double)smax));
  if (res <= 1e-14 * mass) {
    PetscReal L[MM_MAX_RIGID][MM_MAX_RIGID] = {{0}};
    *matched = PETSC_TRUE;
    for (PetscInt p = 0; p < np; ++p) L[pa[p]][pb[p]] = L[pb[p]][pa[p]] = lam[p];
    for (PetscInt j = 0; j < n; ++j) {
      const MassNode *nd = &nodes[j];
      PetscReal       s[MM_MAX_DIM], U[MM_MAX_DIM][MM_MAX_DIM];
      PetscScalar     vals[MM_MAX_DIM * MM_MAX_DIM];
      PetscInt        idx[MM_MAX_DIM];

      PetscCall(NodeEigen(nd, nr, L, s, U));
      /* E_j = c m_j U diag(exp(s) - 1) U^T on the node's dofs with mass, in its w-frame */
      for (PetscInt a = 0; a < nd->k; ++a) {
        idx[a] = nd->dof + a;
        for (PetscInt b = 0; b < nd->k; ++b) {
          PetscReal e = 0;
          for (PetscInt r = 0; r < nd->k; ++r) e += U[r][a] * expm1(s[r]) * U[r][b];
          vals[a * nd->k + b] = c * nd->m * e;
        }
      }
      worst = PetscMax(worst, -c * expm1(s[0]));
      PetscCall(MatSetValues(A, nd->k, idx, nd->k, idx, vals, ADD_VALUES));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPIU_MAX, comm));
    r->mass->correction = worst;
  }
  PetscCall(PetscFree(nodes));
  PetscFunctionReturn(0);
}

/* The nodes of a group off the contact boundary and free of Dirichlet data, over all ranks: the only
 * ones that can carry mass along a contact normal, for the refusal's message. */
static PetscErrorCode CountInnerNodes(MassRedist *r, Vec kind, const PetscInt vgroup[], PetscInt group, PetscInt *count)
{
  PetscSection       gs;
  PetscInt           vStart, vEnd;
  const PetscScalar *k;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(r->dm, &gs));
  PetscCall(DMPlexGetDepthStratum(r->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(kind, &k));
  *count = 0;
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, soff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    PetscCall(DMPlexGetPointLocal(r->dms, v, &soff, NULL));
    if (goff >= 0 && PetscAbsReal(PetscRealPart(k[soff])) < 0.5 && vgroup[v - vStart] == group) ++*count;
  }
  PetscCall(VecRestoreArrayRead(kind, &k));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)r->dm)));
  PetscFunctionReturn(0);
}

/* The bodies whose masses are matched separately: each body of -bodies, bodies that share a node
 * (glued) counted as one, so that every body keeps its own mass, centre of gravity and inertia and no
 * mass moves from one body to another (docs/method.md section 11). Per local vertex its group, the
 * smallest body index of its class; *ngroups the bodies (a group number is a body index). */
static PetscErrorCode VertexGroups(MassRedist *r, PetscInt **vgroup)
{
  const MMMaterial *mat = r->material;
  DM                dm  = r->dm;
  const PetscInt    nb  = PetscMax(mat->n_bodies, 1);
  PetscInt          vStart, vEnd, cStart, cEnd, *link;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc1(vEnd - vStart, vgroup));
  PetscCall(PetscCalloc1(nb * nb, &link));
  for (PetscInt v = 0; v < vEnd - vStart; ++v) (*vgroup)[v] = -1;
  for (PetscInt c = cStart; c < cEnd; ++c) {
    const PetscInt b     = mat->cell_body ? mat->cell_body[c - cStart] : 0;
    const MMCells *cells = r->cells;
    for (PetscInt a = 0; a < cells->nv; ++a) {
      const PetscInt v = cells->vertex[cells->nv * (c - cStart) + a];
      if ((*vgroup)[v - vStart] >= 0 && (*vgroup)[v - vStart] != b) link[(*vgroup)[v - vStart] * nb + b] = link[b * nb + (*vgroup)[v - vStart]] = 1;
      (*vgroup)[v - vStart] = b;
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, link, nb * nb, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)dm)));
  /* each body's class by its smallest member: a few passes of the transitive closure */
  for (PetscInt b = 0; b < nb; ++b) link[b * nb + b] = 1;
  for (PetscInt m = 0; m < nb; ++m)
    for (PetscInt a = 0; a < nb; ++a)
      for (PetscInt b = 0; b < nb; ++b)
        if (link[a * nb + m] && link[m * nb + b]) link[a * nb + b] = 1;
  for (PetscInt v = 0; v < vEnd - vStart; ++v) {
    const PetscInt b = (*vgroup)[v] < 0 ? 0 : (*vgroup)[v];
    PetscInt       g = b;
    for (PetscInt a = 0; a < b; ++a)
      if (link[a * nb + b]) {
        g = a;
        break;
      }
    (*vgroup)[v] = g;
  }
  PetscCall(PetscFree(link));
  PetscFunctionReturn(0);
}

/* The rigid modes restricted to one group's dofs (all of them with one group: unchanged). */
static PetscErrorCode GroupModes(MassRedist *r, const PetscInt vgroup[], PetscInt group, PetscInt nr, Vec R[], Vec Rg[])
{
  DM           dm = r->dm;
  PetscSection gs, ls;
  PetscInt     vStart, vEnd, rstart;
  Vec          mask;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecDuplicate(R[0], &mask));
  PetscCall(VecGetOwnershipRange(mask, &rstart, NULL));
  PetscCall(VecGetArray(mask, &a));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, dof, cdof;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    PetscCall(PetscSectionGetDof(ls, v, &dof));
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    if (goff < 0) continue;
    /* the vertex's free dofs: the global vectors hold no Dirichlet component */
    for (PetscInt d = 0; d < dof - cdof; ++d) a[goff - rstart + d] = vgroup[v - vStart] == group ? 1.0 : 0.0;
  }
  PetscCall(VecRestoreArray(mask, &a));
  for (PetscInt k = 0; k < nr; ++k) {
    PetscCall(VecDuplicate(R[k], &Rg[k]));
    PetscCall(VecPointwiseMult(Rg[k], R[k], mask));
  }
  PetscCall(VecDestroy(&mask));
  PetscFunctionReturn(0);
}

/* max |G(M) - G(M*)| over the moments node blocks can set. In 3D one combination is out of their
 * reach: the trace of the translation-rotation block, sum_a G[a][3+a], is zero for any node block
 * that is a multiple of I (M's) and for any node-block correction (T K T^T = 0, K = [[0, I], [I,
 * 0]]), but not for the consistent M* when neighbouring contact nodes have different normals (its
 * pair blocks m_ij P_i P_j are not symmetric). It is none of the total mass, the centre of gravity
 * (the antisymmetric part of that block) or the inertia tensor; it is left out, and reported. */
static PetscReal MomentMismatch(PetscInt nr, PetscInt moments, PetscReal GM[MM_MAX_RIGID][MM_MAX_RIGID], PetscReal Gs[MM_MAX_RIGID][MM_MAX_RIGID], PetscReal *unreachable, PetscReal *inertia)
{
  PetscReal r[MM_MAX_RIGID][MM_MAX_RIGID], k = 0, d = 0;

  for (PetscInt a = 0; a < nr; ++a)
    for (PetscInt b = 0; b < nr; ++b) r[a][b] = GM[a][b] - Gs[a][b];
  if (nr == 6) {
    for (PetscInt a = 0; a < 3; ++a) k += r[a][3 + a];
    for (PetscInt a = 0; a < 3; ++a) r[a][3 + a] -= k / 3, r[3 + a][a] -= k / 3;
  }
  /* moments < nr: the second moments (the inertia) were not matched, and are reported apart */
  *inertia = 0;
  for (PetscInt a = 0; a < nr; ++a)
    for (PetscInt b = 0; b < nr; ++b) {
      if (a < moments || b < moments) d = PetscMax(d, PetscAbsReal(r[a][b]));
      else *inertia = PetscMax(*inertia, PetscAbsReal(r[a][b]));
    }
  *unreachable = PetscAbsReal(k);
  return d;
}

/* -mass redistributed: M* (already without its contact-normal rows and columns) gets the lost
 * moments back on the other nodes, and is checked: its Gram matrix equals M's to 1e-12 of the mass
 * (docs/method.md section 2). */
PetscErrorCode MMContactRedistributeMass(MMContactMass *mass, MMOperators op, const MMMaterial *material, const MMMassBoundary *mb)
{
  MassRedist     rd = {op, material, mb, mass}, *r = &rd;
  PetscInt       nr;
  MPI_Comm       comm;
  PetscReal      x0[MM_MAX_DIM], ell = 1, GM[MM_MAX_RIGID][MM_MAX_RIGID], Gs[MM_MAX_RIGID][MM_MAX_RIGID], dG[MM_MAX_RIGID][MM_MAX_RIGID];
  PetscReal      mismatch = 0, unreachable = 0, correction = 0, inertia = 0;
  Vec            R[MM_MAX_RIGID], Rg[MM_MAX_RIGID], kind, normal[MM_MAX_DIM];
  PetscInt      *vgroup, matched_moments;

  PetscFunctionBeginUser;
  PetscCall(MassRedistGetFE(r));
  nr              = MMFENumRigidModes(r->dim);
  comm            = PetscObjectComm((PetscObject)r->dm);
  matched_moments = nr;
  PetscCall(RigidFrame(r, x0, &ell));
  PetscCall(RigidModes(r, x0, ell, R));
  PetscCall(VertexKinds(r, &kind, normal));
  PetscCall(VertexGroups(r, &vgroup));
  PetscCall(MatSetOption(r->mass->Mstar, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(AddCellShares(r, kind, normal, NULL, 0, 1.0, r->mass->Mstar));
  PetscCall(MatAssemblyBegin(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
  /* each body (group) on its own: its moments matched by corrections on its own nodes */
  for (PetscInt g = 0; g < PetscMax(r->material->n_bodies, 1); ++g) {
    PetscCall(GroupModes(r, vgroup, g, nr, R, Rg));
    PetscCall(Gram(r->mass->M, nr, Rg, GM));
    if (GM[0][0] > 0) {
      PetscCall(Gram(r->mass->Mstar, nr, Rg, Gs));
      for (PetscInt a = 0; a < nr; ++a)
        for (PetscInt b = 0; b < nr; ++b) dG[a][b] = GM[a][b] - Gs[a][b];
      PetscInt  moments = nr;         /* the moments matched: all, or the masses and first moments */
      PetscBool bounded = PETSC_FALSE; /* the bounded correction in place of the smallest */
      PetscReal largest = 0;
      /* the correction, and up to two more on what round-off left of dG (iterative refinement, for
       * contact surfaces that leave the moment system ill-conditioned) */
      for (PetscInt it = 0; it < 3; ++it) {
        PetscReal mm, un, ri;
        PetscBool exceeded = PETSC_FALSE, matched = PETSC_TRUE;
        if (!bounded) PetscCall(AddMomentCorrection(r, kind, vgroup, g, x0, ell, dG, r->mass->Mstar, &exceeded));
        if (exceeded) {
          /* the smallest correction would leave M* indefinite (coarse meshes whose contact boundary
           * holds much of the mass): the bounded one, every moment if it can, else the masses and
           * first moments, which make the body fall at g (docs/method.md section 2) */
          bounded = PETSC_TRUE;
          /* the cell shares taken back first: the bound then applies to the modified mass, whose
           * every node keeps 1/(d+2) of its lumped mass, and the correction may place the mass
           * where the moments need it (a wider set of corrections than on top of the shares) */
          PetscCall(AddCellShares(r, kind, normal, vgroup, g, -1.0, r->mass->Mstar));
          PetscCall(MatAssemblyBegin(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
          PetscCall(MatAssemblyEnd(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
          PetscCall(Gram(r->mass->Mstar, nr, Rg, Gs));
          for (PetscInt a = 0; a < nr; ++a)
            for (PetscInt b = 0; b < nr; ++b) dG[a][b] = GM[a][b] - Gs[a][b];
          PetscCall(AddBoundedCorrection(r, kind, vgroup, g, x0, ell, dG, nr, GM[0][0], r->mass->Mstar, &matched));
          if (!matched) {
            moments = r->dim;
            PetscCall(AddBoundedCorrection(r, kind, vgroup, g, x0, ell, dG, moments, GM[0][0], r->mass->Mstar, &matched));
          }
          if (!matched) {
            PetscInt inner;
            PetscCall(CountInnerNodes(r, kind, vgroup, g, &inner));
            SETERRQ(comm, PETSC_ERR_USER_INPUT, "-mass redistributed cannot give the contact nodes' normal mass back on this mesh without making M* indefinite: %" PetscInt_FMT " node%s off the contact boundary and free of Dirichlet data cannot carry it at the centre of gravity. Name as -contact_boundary only the surface that can touch an obstacle, or mesh the body finer (more nodes inside); -mass modified runs, but falls faster than g along the contact normals", inner, inner == 1 ? "" : "s");
          }
        } else if (bounded) PetscCall(AddBoundedCorrection(r, kind, vgroup, g, x0, ell, dG, moments, GM[0][0], r->mass->Mstar, &matched));
        largest = PetscMax(largest, r->mass->correction);
        PetscCall(MatAssemblyBegin(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
        PetscCall(MatAssemblyEnd(r->mass->Mstar, MAT_FINAL_ASSEMBLY));
        PetscCall(Gram(r->mass->Mstar, nr, Rg, Gs));
        mm = MomentMismatch(nr, moments, GM, Gs, &un, &ri) / PetscMax(GM[0][0], PETSC_SMALL);
        if (it == 2 || mm <= 1e-14) {
          mismatch    = PetscMax(mismatch, mm);
          unreachable = PetscMax(unreachable, un / PetscMax(GM[0][0], PETSC_SMALL));
          inertia     = PetscMax(inertia, ri / PetscMax(GM[0][0], PETSC_SMALL));
        }
        if (mm <= 1e-14) break;
        for (PetscInt a = 0; a < nr; ++a)
          for (PetscInt b = 0; b < nr; ++b) dG[a][b] = GM[a][b] - Gs[a][b];
      }
      correction = PetscMax(correction, largest);
      matched_moments = PetscMin(matched_moments, moments);
      if (bounded) r->mass->bounded = PETSC_TRUE;
    }
    for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDestroy(&Rg[k]));
  }
  r->mass->correction         = correction;
  r->mass->moment_mismatch    = mismatch;
  r->mass->moment_unreachable = unreachable;
  r->mass->moments            = matched_moments;
  r->mass->inertia_mismatch   = inertia;
  PetscCall(PetscFree(vgroup));
  /* what no node-block correction can reach: a body whose every node is on the contact boundary or
   * held by Dirichlet data (one cell across), or whose free nodes are too few to carry the moments */
  PetscCheck(r->mass->moment_mismatch <= 1e-12, comm, PETSC_ERR_USER_INPUT, "-mass redistributed cannot give the contact nodes' normal mass back: after the redistribution the moments of M* still differ from those of M by %.3g of the mass, because too few nodes are off the contact boundary and free of Dirichlet data to carry it (a body one cell across has none). Mesh the body with more cells across, or use -mass modified", (double)r->mass->moment_mismatch);
  PetscCall(VecDestroy(&kind));
  for (PetscInt d = 0; d < r->dim; ++d) PetscCall(VecDestroy(&normal[d]));
  for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDestroy(&R[k]));
  PetscFunctionReturn(0);
}

/* The masses the diagnostics need: M's total mass, and M*'s mass for rigid translations (a dim x dim
 * matrix: the modified mass lacks the normal masses, so it is not m I) and its inverse. */
PetscErrorCode MMContactMassMoments(MMContactMass *mass, MMOperators op)
{
  MassRedist     rd = {op, NULL, NULL, mass}, *r = &rd;
  PetscInt       dim, nr;
  PetscReal      zero[MM_MAX_DIM] = {0, 0, 0}, GM[MM_MAX_RIGID][MM_MAX_RIGID], Gs[MM_MAX_RIGID][MM_MAX_RIGID];
  Vec            R[MM_MAX_RIGID];

  PetscFunctionBeginUser;
  PetscCall(MassRedistGetFE(r));
  dim = r->dim;
  nr  = MMFENumRigidModes(dim);
  PetscCall(RigidModes(r, zero, 1.0, R));
  PetscCall(Gram(r->mass->M, nr, R, GM));
  PetscCall(Gram(r->mass->Mstar, nr, R, Gs));
  r->mass->total = GM[0][0];
  for (PetscInt a = 0; a < dim; ++a)
    for (PetscInt b = 0; b < dim; ++b) r->mass->mass_star[a * dim + b] = Gs[a][b];
  /* its inverse, for the centre-of-mass columns of every step (zero for a body without mass) */
  {
    PetscReal m[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, inv[MM_MAX_DIM][MM_MAX_DIM] = {{0}};
    for (PetscInt a = 0; a < dim; ++a)
      for (PetscInt b = 0; b < dim; ++b) m[a][b] = Gs[a][b];
    if (PetscAbsReal(MMDetInverse(dim, m, inv)) <= PETSC_SMALL * PetscPowRealInt(PetscMax(r->mass->total, PETSC_SMALL), dim))
      for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
        for (PetscInt b = 0; b < MM_MAX_DIM; ++b) inv[a][b] = 0;
    for (PetscInt a = 0; a < dim; ++a)
      for (PetscInt b = 0; b < dim; ++b) r->mass->mass_star_inv[a * dim + b] = inv[a][b];
  }
  /* M* that lost more than a tenth of M along an axis: the body falls faster than g along it, by
   * M/M*, and hits with that share of its momentum (README "The mass"). One line, on stderr. */
  {
    char      axes[192] = "";
    PetscReal worst     = 1;
    for (PetscInt d = 0; d < dim; ++d)
      if (GM[d][d] > 0 && Gs[d][d] < 0.9 * GM[d][d]) {
        size_t len;
        PetscCall(PetscStrlen(axes, &len));
        PetscCall(PetscSNPrintf(axes + len, sizeof(axes) - len, "%s%.3g along %c", len ? ", " : "", (double)(Gs[d][d] / GM[d][d]), "xyz"[d]));
        worst = PetscMin(worst, Gs[d][d] / GM[d][d]);
      }
    if (axes[0] && !r->mass->warned) {
      char faster[96] = "the body has no inertia along the contact normal";
      if (worst > 1e-6) PetscCall(PetscSNPrintf(faster, sizeof(faster), "the body falls up to %.3g times faster than g along the contact normal", (double)(1 / worst)));
      r->mass->warned = PETSC_TRUE;
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "mmcontact warning: -mass %s keeps only %s of M's mass: %s and hits with that share of its momentum; the default -mass redistributed keeps all of it (README \"The mass\")\n", MMMassTypes[r->mass->type], axes, faster));
    }
  }
  for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDestroy(&R[k]));
  PetscFunctionReturn(0);
}
