/* The contact set against a rigid plane: the contact nodes, their frames and gaps, the index sets of
 * the dofs, and h_c'; the rotation Q to frame dofs is built from the frames by frame/frame.c. */
#include <petscsf.h>
#include "mesh.h"
#include "../contactimpl.h"
#include "obstacle.h"

/* Orthonormal frame (nu, tau_1[, tau_2]) with nu = -n, n the obstacle's outward normal: nu is the
 * body's outward normal. A function of n alone, so a node shared by ranks gets the same frame on
 * each. */
void MMContactFrameFromNormal(PetscInt dim, const PetscReal n[], PetscReal F[MM_MAX_DIM][MM_MAX_DIM])
{
  for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
    for (PetscInt b = 0; b < MM_MAX_DIM; ++b) F[a][b] = 0;
  for (PetscInt d = 0; d < dim; ++d) F[0][d] = -n[d];
  if (dim == 2) {
    F[1][0] = -F[0][1];
    F[1][1] = F[0][0];
  } else {
    /* tau_1 = e x nu / |e x nu| with e the axis least aligned with nu */
    PetscInt  k = 0;
    PetscReal e[3] = {0, 0, 0}, nrm;
    for (PetscInt d = 1; d < 3; ++d)
      if (PetscAbsReal(F[0][d]) < PetscAbsReal(F[0][k])) k = d;
    e[k]    = 1;
    F[1][0] = e[1] * F[0][2] - e[2] * F[0][1];
    F[1][1] = e[2] * F[0][0] - e[0] * F[0][2];
    F[1][2] = e[0] * F[0][1] - e[1] * F[0][0];
    nrm     = PetscSqrtReal(PetscSqr(F[1][0]) + PetscSqr(F[1][1]) + PetscSqr(F[1][2]));
    for (PetscInt d = 0; d < 3; ++d) F[1][d] /= nrm;
    F[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    F[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    F[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  }
}

/* The single plane's frame, which the static sliding state uses (sliding.c). */
static PetscErrorCode BuildFrame(MMContact ct)
{
  PetscFunctionBeginUser;
  MMContactFrameFromNormal(ct->dim, ct->pb.obstacle_normal, ct->frame);
  PetscFunctionReturn(0);
}

/* The obstacle a contact node is constrained against: the nearest, by signed distance at its
 * reference position x (docs/method.md section 8), ties to the one listed first; its gap and normal
 * n there. The assignment and the frame are fixed for the run: M* removes the mass of each node's
 * normal dof, so a frame that turned would change M* and K~ and break the energy identity. */
static PetscErrorCode NearestObstacle(MMContact ct, const PetscReal x[], PetscInt *which, PetscReal *gap, PetscReal n[])
{
  const PetscInt dim = ct->dim;

  PetscFunctionBeginUser;
  *which = -1;
  for (PetscInt b = 0; b < ct->pb.n_rigid; ++b) {
    const MMObstacle *ob = &ct->pb.obstacles[b];
    PetscReal         g, nb[MM_MAX_DIM] = {0, 0, 0}, len = 0;
    PetscCall(MMObstacleDistance(ob, dim, x, &g, nb));
    for (PetscInt d = 0; d < dim; ++d) len += nb[d] * nb[d];
    if (*which >= 0 && g >= *gap) continue;
    /* a point on a sphere's centre or a cylinder's axis has no normal */
    PetscCheck(len > 0.5, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "A contact node at (%g, %g, %g) sits on the centre or axis of obstacle %s, where its normal is undefined: move the obstacle or the body", (double)x[0], (double)x[1], dim == 3 ? (double)x[2] : 0.0, ob->name);
    *which = b;
    *gap   = g;
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) n[d] = nb[d];
  }
  PetscFunctionReturn(0);
}

/* A corner (docs/method.md section 8): besides its nearest obstacle (normal n1), the nearest other
 * obstacle within h_c' of the node and not parallel to the first, which gets a second row; -1 if none. */
static PetscErrorCode SecondObstacle(MMContact ct, const PetscReal x[], PetscInt first, const PetscReal n1[], PetscInt *which, PetscReal *gap, PetscReal n[])
{
  const PetscInt dim = ct->dim;

  PetscFunctionBeginUser;
  *which = -1;
  for (PetscInt b = 0; b < ct->pb.n_rigid; ++b) {
    const MMObstacle *ob = &ct->pb.obstacles[b];
    PetscReal         g, nb[MM_MAX_DIM] = {0, 0, 0}, c = 0;
    if (b == first) continue;
    PetscCall(MMObstacleDistance(ob, dim, x, &g, nb));
    for (PetscInt d = 0; d < dim; ++d) c += nb[d] * n1[d];
    if (g > ct->h_c || PetscAbsReal(c) > 1 - 1e-6 || (*which >= 0 && g >= *gap)) continue;
    *which = b;
    *gap   = g;
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) n[d] = nb[d];
  }
  PetscFunctionReturn(0);
}

/* A corner node's frame: nu_1 = -n1, tau_1 in the plane of nu_1 and nu_2 = -n2, so that
 * nu_2 = a nu_1 + b tau_1 (b > 0) and nu_2.u = a y_0 + b y_1 in the frame components y. */
static void CornerFrame(PetscInt dim, const PetscReal n1[], const PetscReal n2[], PetscReal F[MM_MAX_DIM][MM_MAX_DIM], PetscReal *a, PetscReal *b)
{
  PetscReal len = 0;

  MMContactFrameFromNormal(dim, n1, F);
  *a = 0;
  for (PetscInt d = 0; d < dim; ++d) *a += -n2[d] * F[0][d];
  for (PetscInt d = 0; d < dim; ++d) {
    F[1][d] = -n2[d] - *a * F[0][d];
    len += F[1][d] * F[1][d];
  }
  len = PetscSqrtReal(len);
  for (PetscInt d = 0; d < dim; ++d) F[1][d] /= len;
  *b = len;
  if (dim == 3) {
    F[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    F[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    F[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  }
}

/* With several obstacles, contact node k's reference gap and normal (frame convention: nu = -n, the
 * body's outward normal) to every obstacle, so that its penetration of any of them is seen, not only
 * of the one it is constrained against (docs/method.md section 8). */
static PetscErrorCode AllObstacleGaps(MMContact ct, const PetscReal x[], PetscInt k)
{
  const PetscInt dim = ct->dim, nob = ct->pb.n_rigid;

  PetscFunctionBeginUser;
  if (nob < 2) PetscFunctionReturn(0);
  for (PetscInt b = 0; b < nob; ++b) {
    const MMObstacle *ob = &ct->pb.obstacles[b];
    PetscReal         n[MM_MAX_DIM] = {0, 0, 0};
    PetscCall(MMObstacleDistance(ob, dim, x, &ct->all_gap0[k * nob + b], n));
    for (PetscInt d = 0; d < 3; ++d) ct->all_nu[3 * (k * nob + b) + d] = -n[d];
  }
  PetscFunctionReturn(0);
}

/* Marks the points of one contact surface with value, and adds int_F phi_i to each vertex's area. */
static PetscErrorCode MarkSurface(MMContact ct, const char name[], PetscInt value, PetscInt mark[], PetscScalar aa[])
{
  DM          dm = ct->dm, dms;
  DMLabel     label;
  MMFacetList fl;
  PetscInt    pStart, n, *pts, *vals;
  PetscReal   one = 1;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetScalarDM(ct->op, &dms));
  PetscCall(MMMeshGetLabel(dm, name, &label));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(MMMeshLabelPoints(label, &n, &pts, &vals));
  for (PetscInt j = 0; j < n; ++j) {
    PetscInt *closure = NULL, ncl, h;
    PetscCall(DMPlexGetPointHeight(dm, pts[j], &h));
    PetscCheck(h >= 1, PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "Contact surface \"%s\" contains cells: it must be a Physical Curve (2D) or Physical Surface (3D)", name);
    PetscCall(DMPlexGetTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &closure));
    for (PetscInt k = 0; k < ncl; ++k) {
      const PetscInt q = closure[2 * k];
      PetscCheck(!mark[q - pStart] || mark[q - pStart] == value, PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "Contact surface \"%s\" shares a node with another contact surface (-contact_boundary or a pair's slave surface): a node carries one kind of constraint. Separate the physical groups", name);
      mark[q - pStart] = value;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &closure));
  }
  PetscCall(PetscFree2(pts, vals));
  /* int_F phi_i for P1 on each facet F: the contact nodes' areas */
  PetscCall(MMMeshGetFacets(dm, name, &fl));
  PetscCall(MMMeshFacetsAddNodal(dm, &fl, dms, 1, &one, aa));
  PetscCall(MMFacetListDestroy(&fl));
  PetscFunctionReturn(0);
}

/* Marks the vertices of the contact faces, agreed over ranks through the point SF: a vertex can
 * sit on a rank that does not hold the face it belongs to. The mark is 1 on -contact_boundary (the
 * rigid obstacles') and 2 + p on pair p's slave surface. */
static PetscErrorCode MarkContactVertices(MMContact ct, PetscInt **mark, Vec area)
{
  Vec          aloc;
  PetscScalar *aa;
  DM           dm = ct->dm, dms;
  PetscInt     pStart, pEnd;
  PetscInt    *root;
  PetscSF      sf;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetScalarDM(ct->op, &dms));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1(pEnd - pStart, mark));
  PetscCall(PetscCalloc1(pEnd - pStart, &root));
  PetscCall(DMGetLocalVector(dms, &aloc));
  PetscCall(VecZeroEntries(aloc));
  PetscCall(VecGetArray(aloc, &aa));
  if (ct->pb.n_rigid) {
    DMLabel label;
    /* a missing group says whether its name is the default one, tried because the option was not given */
    PetscCall(MMMeshGetLabelFor(dm, ct->pb.contact_name, ct->pb.contact_name_given ? "-contact_boundary" : "the default of -contact_boundary, which was not given: name the mesh's contact boundary with -contact_boundary NAME", &label));
    PetscCall(MarkSurface(ct, ct->pb.contact_name, 1, *mark, aa));
  }
  for (PetscInt b = ct->pb.n_rigid; b < ct->pb.n_obstacles; ++b) PetscCall(MarkSurface(ct, ct->pb.obstacles[b].slave, 2 + b - ct->pb.n_rigid, *mark, aa));
  PetscCall(VecRestoreArray(aloc, &aa));
  PetscCall(VecZeroEntries(area));
  PetscCall(DMLocalToGlobal(dms, aloc, ADD_VALUES, area));
  PetscCall(DMRestoreLocalVector(dms, &aloc));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscArraycpy(root, *mark, pEnd - pStart));
  PetscCall(PetscSFReduceBegin(sf, MPIU_INT, *mark, root, MPI_MAX));
  PetscCall(PetscSFReduceEnd(sf, MPIU_INT, *mark, root, MPI_MAX));
  PetscCall(PetscSFBcastBegin(sf, MPIU_INT, root, *mark, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_INT, root, *mark, MPI_REPLACE));
  PetscCall(PetscArraycpy(*mark, root, pEnd - pStart));
  PetscCall(PetscFree(root));
  PetscFunctionReturn(0);
}

/* h_c': the smallest diameter of the cells touching a contact node (Theorem 4.2); mark NULL: of all
 * cells (the linear path's cost model, without contact). */
static PetscErrorCode SmallestDiameter(MMContact ct, const PetscInt mark[], PetscReal *h)
{
  DM             dm = ct->dm;
  const MMCells *cells;
  PetscInt       cStart, cEnd, pStart, cdim;
  PetscReal      hmin = PETSC_MAX_REAL;
  Vec            X;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetCells(ct->op, &cells));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscScalar *xc      = NULL;
    PetscInt     nx;
    PetscBool    touches = PETSC_FALSE;
    PetscReal    diam    = 0;

    for (PetscInt a = 0; a < cells->nv; ++a) touches = (PetscBool)(touches || !mark || mark[cells->vertex[cells->nv * (c - cStart) + a] - pStart]);
    if (!touches) continue;
    PetscCall(DMPlexVecGetClosure(dm, NULL, X, c, &nx, &xc));
    for (PetscInt i = 0; i < nx / cdim; ++i)
      for (PetscInt j = i + 1; j < nx / cdim; ++j) {
        PetscReal d2 = 0;
        for (PetscInt d = 0; d < cdim; ++d) d2 += PetscSqr(PetscRealPart(xc[i * cdim + d] - xc[j * cdim + d]));
        diam = PetscMax(diam, PetscSqrtReal(d2));
      }
    PetscCall(DMPlexVecRestoreClosure(dm, NULL, X, c, &nx, &xc));
    hmin = PetscMin(hmin, diam);
  }
  PetscCall(MPIU_Allreduce(&hmin, h, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/* The friction corners' arrays, per row (docs/method.md section 12). */
static PetscErrorCode FrictionCornersAllocate(MMContact ct, PetscInt dim, PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &ct->fc_obstacle));
  for (PetscInt k = 0; k < n; ++k) ct->fc_obstacle[k] = -1;
  PetscCall(PetscCalloc4(2 * (size_t)n, &ct->fc_ab, n, &ct->fc_gap0, n, &ct->fc_gap, (size_t)n * (dim - 1), &ct->fc_slide));
  PetscCall(PetscCalloc2((size_t)n * dim, &ct->fc_r, (size_t)n * dim, &ct->fc_r_old));
  PetscFunctionReturn(0);
}

/* Row k, with friction, against a second obstacle b at gap g: nu_2 = a nu_1 + b tau_1 in its frame. */
static void FrictionCornerSet(MMContact ct, PetscInt k, PetscInt b, PetscReal g, const PetscReal ab[2])
{

  ct->fc_obstacle[k]   = b;
  ct->fc_ab[2 * k]     = ab[0];
  ct->fc_ab[2 * k + 1] = ab[1];
  ct->fc_gap0[k] = ct->fc_gap[k] = g;
}

/* Index sets of the owned contact dofs, the gaps, and each contact node's frame (Q's block: frame/frame.c). */
static PetscErrorCode BuildContactDofs(MMContact ct, const PetscInt mark[], Vec area)
{
  PetscInt           astart;
  const PetscScalar *av;
  PetscReal         *nodal_area;
  DM           dm = ct->dm, dms;
  PetscSection gs, ls, cs;
  PetscInt     vStart, vEnd, pStart, dim = ct->dim, n, rstart, rend, nc = 0, nt = 0, nm = 0, *in, *it, *is, *im, b2, bf;
  PetscReal    ab[2] = {0, 0}, n2[MM_MAX_DIM] = {0, 0, 0}, g2 = 0;
  PetscReal   *gap;
  Vec          X, g;
  const PetscScalar *x;
  PetscInt    *is_contact_dof; /* 0: other, 1: contact dof, 2: contact-normal dof */
  MPI_Comm     comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(MMFEGetScalarDM(ct->op, &dms));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMCreateGlobalVector(dm, &g));
  PetscCall(VecGetLocalSize(g, &n));
  PetscCall(VecGetOwnershipRange(g, &rstart, &rend));
  PetscCall(VecDestroy(&g));
  PetscCall(PetscMalloc5(n, &in, n, &it, n, &is, n, &gap, n, &im));
  PetscCall(PetscCalloc1(n, &is_contact_dof));
  PetscCall(PetscMalloc1(n, &ct->scalar_index));
  PetscCall(PetscMalloc1(n, &ct->vertex));
  PetscCall(PetscMalloc1(n, &nodal_area));
  PetscCall(PetscMalloc1(n, &ct->obstacle));
  PetscCall(PetscCalloc2(n, &ct->second, 2 * (size_t)n, &ct->corner_ab));
  if (ct->ncomp > 1) PetscCall(FrictionCornersAllocate(ct, dim, n));
  PetscCall(PetscMalloc1(9 * (size_t)n, &ct->node_frame));
  if (ct->pb.n_rigid > 1) PetscCall(PetscMalloc2((size_t)n * ct->pb.n_rigid, &ct->all_gap0, 3 * (size_t)n * ct->pb.n_rigid, &ct->all_nu));
  PetscCall(VecGetOwnershipRange(area, &astart, NULL));
  PetscCall(VecGetArrayRead(area, &av));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, cdof, xoff;
    if (!mark[v - pStart]) continue;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    b2 = bf = -1;
    if (cdof) {
      char at[128];
      if (dim == 2) PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g)", (double)PetscRealPart(x[xoff]), (double)PetscRealPart(x[xoff + 1])));
      else PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g, %g)", (double)PetscRealPart(x[xoff]), (double)PetscRealPart(x[xoff + 1]), (double)PetscRealPart(x[xoff + 2])));
      SETERRQ(comm, PETSC_ERR_USER_INPUT, "A node of the contact boundary \"%s\" at %s is also on a Dirichlet boundary. Contact dofs must be free: separate the two physical groups", mark[v - pStart] >= 2 ? ct->pb.obstacles[ct->pb.n_rigid + mark[v - pStart] - 2].slave : ct->pb.contact_name, at);
    }
    {
      PetscReal xv[MM_MAX_DIM] = {0, 0, 0}, n[MM_MAX_DIM] = {0, 0, 0}, F[MM_MAX_DIM][MM_MAX_DIM];
      for (PetscInt d = 0; d < dim; ++d) xv[d] = PetscRealPart(x[xoff + d]);
      if (mark[v - pStart] >= 2) {
        const PetscInt p = mark[v - pStart] - 2;
        PetscCall(MMContactPairsProject(ct, p, nc, xv, &gap[nc], n));
        ct->obstacle[nc] = ct->pb.n_rigid + p;
      } else {
        PetscCall(NearestObstacle(ct, xv, &ct->obstacle[nc], &gap[nc], n));
        PetscCall(AllObstacleGaps(ct, xv, nc));
        /* a node near two walls: frictionless, a row for each; with friction one row whose dofs
         * carry both obstacles' Coulomb laws (docs/method.md section 12) */
        PetscCall(SecondObstacle(ct, xv, ct->obstacle[nc], n, &b2, &g2, n2));
        if (b2 >= 0 && ct->ncomp == 1) gap[nc + 1] = g2;
        if (b2 >= 0 && ct->ncomp > 1) {
          bf = b2;
          b2 = -1;
        }
      }
      if (b2 >= 0 || bf >= 0) CornerFrame(dim, n, n2, F, &ab[0], &ab[1]);
      else MMContactFrameFromNormal(dim, n, F);
      for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
        for (PetscInt b = 0; b < MM_MAX_DIM; ++b) ct->node_frame[9 * nc + 3 * a + b] = F[a][b];
    }
    for (PetscInt d = 0; d < dim; ++d) is_contact_dof[goff - rstart + d] = 1;
    /* the tangential dofs: all but the normals (a corner's second normal is its first tangent) */
    for (PetscInt d = b2 >= 0 ? 2 : 1; d < dim; ++d) it[nt++] = goff + d;
    /* the massless dofs: the normals, and a friction corner's tau_1 (its second normal lies in the
     * plane of nu_1 and tau_1) */
    for (PetscInt r = 0; r < (b2 >= 0 || bf >= 0 ? 2 : 1); ++r) im[nm++] = goff + r;
    if (bf >= 0) FrictionCornerSet(ct, nc, bf, g2, ab);
    for (PetscInt r = 0; r < (b2 >= 0 ? 2 : 1); ++r) {
      PetscInt sstart, send;
      in[nc] = goff + r;
      PetscCall(DMPlexGetPointGlobal(dms, v, &sstart, &send));
      ct->scalar_index[nc] = sstart;
      ct->vertex[nc]       = v;
      nodal_area[nc]       = PetscRealPart(av[sstart - astart]);
      ct->second[nc]       = (PetscBool)(r == 1);
      if (r == 1) {
        /* the second row: the dof y_1 replaced by w_1 = nu_2.u = a y_0 + b y_1 (pairs.c builds N) */
        PetscReal F2[MM_MAX_DIM][MM_MAX_DIM];
        ct->obstacle[nc]          = b2;
        ct->corner_ab[2 * nc]     = ab[0];
        ct->corner_ab[2 * nc + 1] = ab[1];
        MMContactFrameFromNormal(dim, n2, F2);
        for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
          for (PetscInt b = 0; b < MM_MAX_DIM; ++b) ct->node_frame[9 * nc + 3 * a + b] = F2[a][b];
        if (ct->all_gap0)
          for (PetscInt b = 0; b < ct->pb.n_rigid; ++b) {
            ct->all_gap0[nc * ct->pb.n_rigid + b] = ct->all_gap0[(nc - 1) * ct->pb.n_rigid + b];
            for (PetscInt d = 0; d < 3; ++d) ct->all_nu[3 * (nc * ct->pb.n_rigid + b) + d] = ct->all_nu[3 * ((nc - 1) * ct->pb.n_rigid + b) + d];
          }
      }
      ++nc;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecRestoreArrayRead(area, &av));
  {
    PetscInt ns = 0;
    /* the star dofs: all but the massless ones (tangential contact dofs keep their mass, but for a
     * friction corner's tau_1) */
    for (PetscInt k = 0; k < nm; ++k) is_contact_dof[im[k] - rstart] = 2;
    for (PetscInt i = 0; i < n; ++i)
      if (is_contact_dof[i] != 2) is[ns++] = rstart + i;
    PetscCall(ISCreateGeneral(comm, ns, is, PETSC_COPY_VALUES, &ct->is_star));
    ns = 0;
    for (PetscInt i = 0; i < n; ++i)
      if (!is_contact_dof[i]) is[ns++] = rstart + i;
    PetscCall(ISCreateGeneral(comm, ns, is, PETSC_COPY_VALUES, &ct->is_interior));
  }
  PetscCall(ISCreateGeneral(comm, nc, in, PETSC_COPY_VALUES, &ct->is_normal));
  PetscCall(ISCreateGeneral(comm, nm, im, PETSC_COPY_VALUES, &ct->is_massless));
  PetscCall(ISCreateGeneral(comm, nt, it, PETSC_COPY_VALUES, &ct->is_tangent));
  /* the condensed dofs, node by node: the normal one, and the tangential ones with friction */
  for (PetscInt k = 0; k < nc; ++k)
    for (PetscInt c = 0; c < ct->ncomp; ++c) is[k * ct->ncomp + c] = in[k] + c;
  PetscCall(ISCreateGeneral(comm, nc * ct->ncomp, is, PETSC_COPY_VALUES, &ct->is_cond));
  PetscCall(VecCreateMPI(comm, nc, PETSC_DETERMINE, &ct->gap));
  PetscCall(VecDuplicate(ct->gap, &ct->area));
  PetscCall(VecDuplicate(ct->gap, &ct->mu));
  {
    PetscScalar *ga, *aa, *ma;
    PetscCall(VecGetArray(ct->gap, &ga));
    PetscCall(VecGetArray(ct->area, &aa));
    PetscCall(VecGetArray(ct->mu, &ma));
    for (PetscInt k = 0; k < nc; ++k) {
      ga[k] = gap[k];
      aa[k] = nodal_area[k];
      ma[k] = ct->pb.obstacles[ct->obstacle[k]].mu;
    }
    PetscCall(VecRestoreArray(ct->mu, &ma));
    PetscCall(VecRestoreArray(ct->gap, &ga));
    PetscCall(VecRestoreArray(ct->area, &aa));
  }
  PetscCall(VecDuplicate(ct->gap, &ct->gap0));
  PetscCall(VecCopy(ct->gap, ct->gap0));
  PetscCall(PetscCalloc1((size_t)nc * (dim - 1) + 1, &ct->slide_ref));
  PetscCall(PetscFree(nodal_area));
  ct->n_local = nc;
  PetscCall(MPIU_Allreduce(&nc, &ct->n_global, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscCalloc1(nc, &ct->was_active));
  PetscCall(PetscCalloc2(nc, &ct->slipping, 2 * nc, &ct->slip_dir));
  PetscCall(PetscFree5(in, it, is, gap, im));
  if (ct->fc_obstacle) {
    PetscInt n_fc = 0;
    for (PetscInt k = 0; k < nc; ++k) n_fc += ct->fc_obstacle[k] >= 0;
    PetscCall(MPIU_Allreduce(&n_fc, &ct->n_fc, 1, MPIU_INT, MPI_SUM, comm));
  }
  PetscCall(PetscFree(is_contact_dof));
  PetscFunctionReturn(0);
}

/* Without contact: every dof is a star dof (and Q = I, frame/frame.c). */
static PetscErrorCode BuildNoContact(MMContact ct)
{
  Vec      g;
  PetscInt n, rstart;
  MPI_Comm comm = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(ct->dm, &g));
  PetscCall(VecGetLocalSize(g, &n));
  PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ct->is_normal));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ct->is_massless));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ct->is_tangent));
  PetscCall(ISCreateStride(comm, 0, 0, 1, &ct->is_cond));
  PetscCall(ISCreateStride(comm, n, rstart, 1, &ct->is_star));
  PetscCall(ISCreateStride(comm, n, rstart, 1, &ct->is_interior));
  PetscCall(VecCreateMPI(comm, 0, PETSC_DETERMINE, &ct->gap));
  PetscCall(PetscCalloc1(1, &ct->slide_ref));
  PetscCall(VecDestroy(&g));
  ct->h_c = 0;
  PetscFunctionReturn(0);
}

/* Finds the contact nodes and builds Q; runs before the operators are assembled. */
static PetscErrorCode SetUp(MMContact ct)
{
  PetscInt  *mark;
  Vec        area;
  DM         dms;

  PetscFunctionBeginUser;
  ct->enabled     = ct->opt.contact;
  ct->tol         = ct->opt.contact_tol;
  ct->ncomp       = ct->pb.mu_max > 0 ? ct->dim : 1;
  PetscCall(PetscCalloc1(MM_MAX_DIM * ct->pb.n_obstacles, &ct->force_obstacle));
  for (PetscInt b = 0; b < ct->pb.n_obstacles; ++b)
    for (PetscInt d = 0; d < ct->dim; ++d) ct->moving = (PetscBool)(ct->moving || ct->pb.obstacles[b].velocity[d] != 0);
  if (ct->pb.static_sliding) {
    PetscBool plane;
    PetscCall(MMObstacleGetPlane(&ct->pb.obstacles[0], ct->pb.obstacle_point, ct->pb.obstacle_normal, &plane));
    PetscCheck(ct->pb.n_obstacles == 1 && plane && !ct->moving, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_USER_INPUT, "-initial_state static_sliding needs a single fixed plane obstacle: the sliding state is built on one plane");
  }
  PetscCall(BuildFrame(ct));
  if (!ct->enabled) {
    PetscCall(SmallestDiameter(ct, NULL, &ct->h_min)); /* the linear path's cost model (cost.c) */
    PetscCall(MMContactSetType(ct));
    PetscCall(BuildNoContact(ct));
    PetscCall(MMContactFrameBuildRotation(ct, ct->op));
    PetscFunctionReturn(0);
  }
  PetscCall(MMFEGetScalarDM(ct->op, &dms));
  PetscCall(DMCreateGlobalVector(dms, &area));
  PetscCall(MarkContactVertices(ct, &mark, area));
  {
    PetscInt vStart, vEnd;
    PetscCall(DMPlexGetDepthStratum(ct->dm, 0, &vStart, &vEnd));
    PetscCall(MMContactPairsSetUp(ct, mark, vEnd - vStart));
  }
  PetscCall(SmallestDiameter(ct, mark, &ct->h_c)); /* before the rows: h_c' is the reach of a second obstacle */
  PetscCall(BuildContactDofs(ct, mark, area));
  PetscCall(MMContactSetType(ct)); /* auto's cost model needs h_c' and the friction corners */
  if (ct->pairs.n) PetscCall(MMContactPairsResolveSliding(ct));
  PetscCall(MMContactFrameBuildRotation(ct, ct->op));
  PetscCall(MMContactPairsBuildTransform(ct));
  PetscCall(PetscFree(mark));
  PetscCall(VecDestroy(&area));
  PetscCall(MMContactFramesSetUp(ct)); /* -contact_frames */
  /* a friction corner's two Coulomb laws on one node's dofs are solved in contact space only */
  PetscCheck(!ct->n_fc || ct->ops->solvecoulomb, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_SUP, "%" PetscInt_FMT " contact nodes are within h_c' of two obstacles with friction (-mu %g), and -contact_formulation %s cannot carry both obstacles' Coulomb laws on one node: use -contact_formulation condensed (or auto, which chooses it here)", ct->n_fc, (double)ct->pb.mu_max, ct->type);
  PetscCheck(ct->ncomp == 1 || ct->ops->solvecontactdofs, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_SUP, "Friction (-mu %g) needs a contact formulation that solves the contact dofs alone, and -contact_formulation %s cannot: use condensed or active_set", (double)ct->pb.mu_max, ct->type);
  PetscCheck(ct->n_global > 0, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_USER_INPUT, "The contact boundary \"%s\" has no nodes", ct->pb.contact_name);
  PetscFunctionReturn(0);
}


/*@
  MMContactSetUp - Finds the contact nodes and builds the contact set, the frames Q and the chosen
  formulation from the problem

  Collective

  Input Parameters:
+ ct       - the contact object, its options read
. op       - fem's operators (borrowed until destroy)
. material - the bodies' material (borrowed until destroy)
- pb       - the problem as contact reads it (copied, its arrays and strings borrowed)

  Level: beginner

.seealso: `MMContactSetFromOptions()`, `MMContactSetUpFrame()`, `MMContactSetUpView()`, `MMContactDestroy()`
@*/
PetscErrorCode MMContactSetUp(MMContact ct, MMOperators op, const MMMaterial *material, const MMContactProblem *pb)
{
  PetscFunctionBeginUser;
  ct->pb = *pb; /* the obstacles and the contact boundary's name are the caller's, kept until destroy */
  ct->op       = op;
  ct->material = material;
  PetscCall(MMFEGetDM(op, &ct->dm));
  PetscCall(MMFEGetDimension(op, &ct->dim));
  PetscCall(SetUp(ct));
  PetscFunctionReturn(0);
}

/*@
  MMContactGetPlane - Gives the plane of the static sliding state, -obstacle_point and
  -obstacle_normal

  Not collective

  Input Parameter:
. ct - the contact object, set up

  Output Parameters:
+ point  - a point of the plane, MM_MAX_DIM entries
- normal - its normal, MM_MAX_DIM entries

  Level: intermediate

.seealso: `MMContactSolveStatic()`, `MMContactGetNodes()`
@*/
PetscErrorCode MMContactGetPlane(MMContact ct, PetscReal point[], PetscReal normal[])
{
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    point[d]  = ct->pb.obstacle_point[d];
    normal[d] = ct->pb.obstacle_normal[d];
  }
  PetscFunctionReturn(0);
}

/* A friction corner's second obstacle at time t: its gap g_2(t) = g_2(0) + c_2(t).nu_2 and its
 * sliding dt/2 V_2.tau'_j along the second row's tangents (docs/method.md section 12). */
static void FrictionCornerSetTime(MMContact ct, PetscInt k, PetscReal t, PetscReal dt)
{
  const PetscInt    dim = ct->dim;
  const MMObstacle *ob  = &ct->pb.obstacles[ct->fc_obstacle[k]];
  PetscReal         c[MM_MAX_DIM] = {0, 0, 0}, V[MM_MAX_DIM] = {0, 0, 0}, F2[MM_MAX_DIM][MM_MAX_DIM];

  MMObstacleDisplacement(ob, dim, t, c);
  MMObstacleVelocity(ob, dim, t, V);
  MMContactCornerFrame2(dim, &ct->node_frame[9 * k], &ct->fc_ab[2 * k], F2);
  ct->fc_gap[k] = ct->fc_gap0[k];
  for (PetscInt d = 0; d < dim; ++d) ct->fc_gap[k] += c[d] * F2[0][d];
  for (PetscInt j = 1; j < dim; ++j) {
    PetscReal vt = 0;
    for (PetscInt d = 0; d < dim; ++d) vt += V[d] * F2[j][d];
    ct->fc_slide[k * (dim - 1) + j - 1] = 0.5 * dt * vt;
  }
}

/*@
  MMContactSetTime - Moves the obstacles to the time of a step's end: the gaps follow moving
  obstacles, and slip is measured relative to their velocity

  Not collective

  Input Parameters:
+ ct - the contact object
. t  - the step's end time t^{n+1}
- dt - the step

  Note:
  The obstacles at time t^{n+1} = t for a step of dt: each node's gap follows its obstacle's
  translation c(t) along the node's fixed normal, g_i(t) = g_i(0) + c(t).nu_i (exact for a plane;
  for a curved obstacle, exact while the node stays on its normal line, docs/method.md section 8),
  and the friction law measures slip relative to the obstacle's velocity V, through
  slide_ref = dt/2 V.tau_j.

  Level: intermediate

.seealso: `MMContactSetStepMatrix()`, `MMContactSolve()`
@*/
PetscErrorCode MMContactSetTime(MMContact ct, PetscReal t, PetscReal dt)
{
  const PetscInt     dim = ct->dim;
  const PetscScalar *g0;
  PetscScalar       *g;

  PetscFunctionBeginUser;
  if (!ct->enabled || !ct->moving) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ct->gap0, &g0));
  PetscCall(VecGetArray(ct->gap, &g));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const MMObstacle *ob = &ct->pb.obstacles[ct->obstacle[k]];
    const PetscReal  *F  = &ct->node_frame[9 * k];
    PetscReal         c[MM_MAX_DIM] = {0, 0, 0}, V[MM_MAX_DIM] = {0, 0, 0}, cn = 0;
    MMObstacleDisplacement(ob, dim, t, c);
    MMObstacleVelocity(ob, dim, t, V);
    for (PetscInt d = 0; d < dim; ++d) cn += c[d] * F[d];
    g[k] = g0[k] + cn;
    if (ct->fc_obstacle && ct->fc_obstacle[k] >= 0) FrictionCornerSetTime(ct, k, t, dt);
    for (PetscInt j = 1; j < dim; ++j) {
      PetscReal vt = 0;
      for (PetscInt d = 0; d < dim; ++d) vt += V[d] * F[3 * j + d];
      ct->slide_ref[k * (dim - 1) + j - 1] = 0.5 * dt * vt;
    }
  }
  PetscCall(VecRestoreArray(ct->gap, &g));
  PetscCall(VecRestoreArrayRead(ct->gap0, &g0));
  PetscFunctionReturn(0);
}

/*@
  MMContactShiftBounds - Makes the contact bounds those of an increment from an origin, or gives them
  back

  Collective

  Input Parameters:
+ ct     - the contact object, its time set (MMContactSetTime)
. origin - the origin u^n of the increment (w-frame)
- shift  - PETSC_TRUE: the bounds become g - u^n_nu, for du = w - u^n; PETSC_FALSE: back to g

  Note:
  The linear step solves for du (docs/method.md section 3, "The step's unknown"): each row's bound
  w_nu <= g becomes du_nu <= g - u^n_nu. The gaps are kept and copied back, not shifted back, so that
  they come out bit for bit. Not with friction corners, whose second bound is of T2 w.

  Level: developer

.seealso: `MMContactSetTime()`, `MMContactSetStepOffset()`
@*/
PetscErrorCode MMContactShiftBounds(MMContact ct, Vec origin, PetscBool shift)
{
  const PetscInt    *in;
  const PetscScalar *oa;
  PetscScalar       *ga;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCheck(!ct->n_fc, ct->comm, PETSC_ERR_SUP, "The bounds of an increment do not take friction corners");
  if (!shift) {
    PetscCall(VecCopy(ct->gap_step, ct->gap));
    PetscFunctionReturn(0);
  }
  if (!ct->gap_step) PetscCall(VecDuplicate(ct->gap, &ct->gap_step));
  PetscCall(VecCopy(ct->gap, ct->gap_step));
  PetscCall(VecGetOwnershipRange(origin, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(origin, &oa));
  PetscCall(VecGetArray(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) ga[k] -= oa[in[k] - rstart];
  PetscCall(VecRestoreArray(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(origin, &oa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}
