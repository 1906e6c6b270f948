/* Contact between two elastic bodies (docs/method.md section 11): the pairs of -contact_pairs.
 *
 * Each slave node s is projected, in the reference configuration, on the closest facet of its
 * pair's master surface: local coordinates phi_j on the facet's vertices m_j, the facet's outward
 * normal n and the gap g = n.(X_s - sum_j phi_j X_mj). Its constraint is the node-to-segment (2D)
 * or node-to-facet (3D) condition nu.(u_s - sum_j phi_j u_mj) <= g, nu = -n.
 *
 * The constraint becomes a bound on one dof by a change of variables. With y = Q^T u the contact
 * frame components, the slave node's frame components are replaced by relative ones,
 * w_s = y_s - sum_j phi_j F_s u_mj (F_s the node's frame), every other dof unchanged: y = N w with
 * N = I + C, C nonzero only in the slave rows and the master columns. Since no master node is a
 * slave or a rigid-contact node, C^2 = 0 and N^{-1} = I - C. The normal component of w_s is then
 * bounded by g exactly as against a rigid obstacle, and every contact formulation and friction
 * solver runs unchanged on K_w = N^T K_y N and M*_w = N^T M*_y N. M*_y has no mass on the slave
 * normals, so N^T M*_y N = M*_y when only the normal is relative (frictionless): the slave nodes'
 * normal mass is removed as in Hager, Hueber and Wohlmuth (2008). With friction the tangential
 * components are relative too, so that the friction law sees the relative slip.
 *
 * The master surface is small next to the mesh: it is gathered on every rank, so that a slave node
 * and its master facet may sit on different ranks.
 *
 * Under large sliding (pairs_sliding.c, frictionless) the pairing is found again before each step,
 * and the row's direction is the facet's current normal nu_c: N then differs from I in the slave's row 0
 * alone (its diagonal and tangential entries too), still where M*_y has no mass, so M*_w = M*_y. */
#include <petscsf.h>
#include "mesh.h"
#include "../contactimpl.h"

/* A facet's (dim vertices x) normal by the right-hand rule on its vertex order, not normalized: the
 * segment's tangent turned by -90 degrees (2D), the cross product of two edges (3D) */
void MMContactPairsFacetCross(PetscInt dim, const PetscReal x[], PetscReal n[])
{
  if (dim == 2) {
    n[0] = x[3] - x[1];
    n[1] = -(x[2] - x[0]);
  } else {
    const PetscReal a[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]}, b[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
  }
}

/* A normal of a facet (dim vertices x) pointing away from its cell, not normalized, and its length */
PetscErrorCode MMContactPairsFacetNormal(DM dm, PetscInt dim, PetscInt cell, const PetscReal x[], PetscReal n[], PetscReal *length)
{
  PetscReal ccen[MM_MAX_DIM] = {0, 0, 0}, len = 0, dot = 0;

  PetscFunctionBeginUser;
  MMContactPairsFacetCross(dim, x, n);
  PetscCall(MMMeshCellCentroid(dm, cell, ccen));
  for (PetscInt d = 0; d < dim; ++d) {
    len += n[d] * n[d];
    dot += (ccen[d] - x[d]) * n[d];
  }
  if (dot > 0)
    for (PetscInt d = 0; d < dim; ++d) n[d] = -n[d];
  *length = PetscSqrtReal(len);
  PetscFunctionReturn(0);
}

/* The facets of pair p's master surface owned or seen here: vertex coordinates, outward normal
 * (away from the master body's cell), and the global index of each vertex's first dof, -1 for a
 * vertex held by Dirichlet data (it does not move). */
static PetscErrorCode LocalMasterFacets(MMContact ct, const MMObstacle *ob, const PetscInt mark[], PetscInt *nf, PetscReal **xf, PetscInt **df)
{
  DM                 dm = ct->dm;
  const PetscInt     dim = ct->dim;
  DMLabel            label;
  MMFacetList        fl;
  PetscInt           pStart, counts[3] = {0, 0, 0}; /* facets, cells in the group, interior facets */
  PetscSection       gs, ls, cs;
  Vec                X;
  const PetscScalar *xc;
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, ob->master, &label));
  PetscCall(MMMeshGetFacets(dm, ob->master, &fl));
  counts[0] = fl.n;
  {
    PetscBool holds;
    PetscCall(MMMeshLabelHoldsCells(dm, label, &holds));
    counts[1] = holds;
  }
  for (PetscInt i = 0; i < fl.n; ++i)
    if (fl.interior[i]) counts[2]++;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, comm));
  PetscCheck(counts[0] && !counts[1], comm, PETSC_ERR_USER_INPUT, "The master surface \"%s\" of contact pair %s contains points that are not facets: it must be a Physical Curve (2D) or Physical Surface (3D)", ob->master, ob->name);
  PetscCheck(!counts[2], comm, PETSC_ERR_USER_INPUT, "The master surface \"%s\" of contact pair %s has a facet inside the mesh (2 cells on it): it must lie on the boundary of its body", ob->master, ob->name);
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(VecGetArrayRead(X, &xc));
  PetscCall(PetscMalloc2(PetscMax(fl.n, 1) * MM_FACET_REALS, xf, PetscMax(fl.n, 1) * MM_MAX_DIM, df));
  for (PetscInt j = 0; j < fl.n; ++j) {
    PetscInt   v[MM_MAX_DIM];
    PetscReal *f = &(*xf)[j * MM_FACET_REALS], area, len, cen[MM_MAX_DIM] = {0, 0, 0};

    PetscCall(MMFacetGeometry(dm, &fl, j, cs, xc, v, f, &area));
    for (PetscInt a = 0; a < dim; ++a) {
      PetscInt goff, cdof;
      PetscCheck(!mark[v[a] - pStart], comm, PETSC_ERR_USER_INPUT, "The master surface \"%s\" of contact pair %s shares a node with a contact surface (a slave surface or -contact_boundary): a master node cannot carry a constraint itself. Separate the surfaces", ob->master, ob->name);
      PetscCall(PetscSectionGetOffset(gs, v[a], &goff));
      PetscCall(PetscSectionGetConstraintDof(ls, v[a], &cdof));
      PetscCheck(cdof == 0 || cdof == dim, comm, PETSC_ERR_SUP, "A node of the master surface \"%s\" of contact pair %s has %" PetscInt_FMT " of its %" PetscInt_FMT " components held by Dirichlet data: a master node is either free or fully held. Keep partial Dirichlet conditions off the master surface", ob->master, ob->name, cdof, dim);
      (*df)[j * MM_MAX_DIM + a] = cdof ? -1 : (goff < 0 ? -(goff + 1) : goff);
    }
    /* the unit normal, oriented away from the master body's cell */
    PetscCall(MMContactPairsFacetNormal(dm, dim, fl.cell[j], f, &f[dim * dim], &len));
    for (PetscInt d = 0; d < dim; ++d) f[dim * dim + d] /= len;
    /* the centroid breaks ties between equidistant facets the same way on any number of ranks */
    for (PetscInt k = 0; k < dim; ++k)
      for (PetscInt d = 0; d < dim; ++d) cen[d] += f[k * dim + d] / dim;
    for (PetscInt d = 0; d < dim; ++d) f[dim * dim + dim + d] = cen[d];
  }
  PetscCall(VecRestoreArrayRead(X, &xc));
  *nf = fl.n;
  PetscCall(MMFacetListDestroy(&fl));
  PetscFunctionReturn(0);
}

/* Pair p's master surface gathered on every rank (each facet once). */
static PetscErrorCode GatherMasterSurface(MMContact ct, PetscInt p, const PetscInt mark[])
{
  MMContactPairs *pr   = &ct->pairs;
  const MMObstacle *ob = &ct->pb.obstacles[ct->pb.n_rigid + p];
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);
  PetscMPIInt     size, nl, *cnt, *dsp, *cntd, *dspd;
  PetscInt        nf = 0, ntot = 0;
  PetscReal      *xf;
  PetscInt       *df;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(LocalMasterFacets(ct, ob, mark, &nf, &xf, &df));
  PetscCall(PetscMalloc4(size, &cnt, size, &dsp, size, &cntd, size, &dspd));
  PetscCall(PetscMPIIntCast(nf, &nl));
  PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; ++r) ntot += cnt[r];
  PetscCheck(ntot > 0, comm, PETSC_ERR_USER_INPUT, "The master surface \"%s\" of contact pair %s has no facets", ob->master, ob->name);
  dsp[0] = dspd[0] = 0;
  for (PetscMPIInt r = 0; r < size; ++r) {
    cntd[r] = cnt[r] * MM_MAX_DIM;
    cnt[r] *= MM_FACET_REALS;
    if (r) {
      dsp[r]  = dsp[r - 1] + cnt[r - 1];
      dspd[r] = dspd[r - 1] + cntd[r - 1];
    }
  }
  pr->nf[p] = ntot;
  PetscCall(PetscMalloc2(ntot * MM_FACET_REALS, &pr->xf[p], ntot * MM_MAX_DIM, &pr->df[p]));
  PetscCallMPI(MPI_Allgatherv(xf, nl * MM_FACET_REALS, MPIU_REAL, pr->xf[p], cnt, dsp, MPIU_REAL, comm));
  PetscCallMPI(MPI_Allgatherv(df, nl * MM_MAX_DIM, MPIU_INT, pr->df[p], cntd, dspd, MPIU_INT, comm));
  PetscCall(PetscFree4(cnt, dsp, cntd, dspd));
  PetscCall(PetscFree2(xf, df));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactPairsSetUp(MMContact ct, const PetscInt mark[], PetscInt n_vertex_bound)
{
  MMContactPairs *pr = &ct->pairs;
  const PetscInt  np = ct->pb.n_obstacles - ct->pb.n_rigid;

  PetscFunctionBeginUser;
  pr->n = np;
  if (!np) PetscFunctionReturn(0);
  PetscCall(PetscCalloc4(np, &pr->nf, np, &pr->xf, np, &pr->df, 2 * np, &pr->count));
  for (PetscInt p = 0; p < np; ++p) PetscCall(GatherMasterSurface(ct, p, mark));
  /* per contact node (an upper bound: the owned vertices) its master vertices' dofs and weights, its
   * facet and its reference position */
  PetscCall(PetscMalloc2(MM_MAX_DIM * n_vertex_bound, &pr->phi, MM_MAX_DIM * n_vertex_bound, &pr->mdof));
  PetscCall(PetscMalloc3(n_vertex_bound, &pr->facet, MM_MAX_DIM * n_vertex_bound, &pr->xs, MM_MAX_DIM * n_vertex_bound, &pr->nuc));
  PetscCall(PetscCalloc2(n_vertex_bound, &pr->far, n_vertex_bound, &pr->far_d));
  PetscFunctionReturn(0);
}

/* The closest point of the segment or triangle f (dim vertices) to x: its barycentric coordinates
 * phi and squared distance. */
static PetscReal ClosestOnFacet(PetscInt dim, const PetscReal f[], const PetscReal x[], PetscReal phi[])
{
  PetscReal best = PETSC_MAX_REAL;

  if (dim == 2) {
    const PetscReal e[2] = {f[2] - f[0], f[3] - f[1]}, r[2] = {x[0] - f[0], x[1] - f[1]};
    PetscReal       t = (r[0] * e[0] + r[1] * e[1]) / (e[0] * e[0] + e[1] * e[1]);
    t      = PetscMin(1.0, PetscMax(0.0, t));
    phi[0] = 1 - t;
    phi[1] = t;
  } else {
    const PetscReal *a = f, *b = f + 3, *c = f + 6;
    const PetscReal  ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, ap[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const PetscReal  d00 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2], d01 = ab[0] * ac[0] + ab[1] * ac[1] + ab[2] * ac[2], d11 = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
    const PetscReal  d20 = ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2], d21 = ap[0] * ac[0] + ap[1] * ac[1] + ap[2] * ac[2], den = d00 * d11 - d01 * d01;
    const PetscReal  v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    if (v >= 0 && w >= 0 && v + w <= 1) {
      phi[0] = 1 - v - w;
      phi[1] = v;
      phi[2] = w;
    } else {
      /* outside: the closest point is on one of the three edges */
      for (PetscInt e = 0; e < 3; ++e) {
        const PetscInt   i = e, j = (e + 1) % 3;
        const PetscReal *p = f + 3 * i, *q = f + 3 * j;
        PetscReal        pq[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, t = 0, l2 = 0, d2 = 0, ph[3] = {0, 0, 0};
        for (PetscInt d = 0; d < 3; ++d) {
          t += (x[d] - p[d]) * pq[d];
          l2 += pq[d] * pq[d];
        }
        t = PetscMin(1.0, PetscMax(0.0, t / l2));
        for (PetscInt d = 0; d < 3; ++d) d2 += PetscSqr(p[d] + t * pq[d] - x[d]);
        ph[i] = 1 - t;
        ph[j] = t;
        if (d2 < best) {
          best = d2;
          for (PetscInt k = 0; k < 3; ++k) phi[k] = ph[k];
        }
      }
    }
  }
  /* snapped, so that a slave node facing a master node couples to it alone, exactly (node to node) */
  {
    PetscReal s = 0;
    for (PetscInt k = 0; k < dim; ++k) {
      if (phi[k] < 1e-10) phi[k] = 0;
      if (phi[k] > 1 - 1e-10) phi[k] = 1;
      s += phi[k];
    }
    for (PetscInt k = 0; k < dim; ++k) phi[k] /= s;
  }
  best = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    PetscReal xp = 0;
    for (PetscInt k = 0; k < dim; ++k) xp += phi[k] * f[k * dim + d];
    best += PetscSqr(xp - x[d]);
  }
  return best;
}

/* The closest of the nf facets xf (MM_FACET_REALS each) to x: its index and weights. Equidistant
 * facets (a node facing a master vertex) are told apart by their centroid keys, the reference ones,
 * so the choice does not depend on the partition. */
PetscInt MMContactPairsClosestFacet(PetscInt dim, PetscInt nf, const PetscReal xf_all[], const PetscReal x[], PetscReal phib[])
{
  PetscInt  fb = -1;
  PetscReal db = PETSC_MAX_REAL;

  for (PetscInt f = 0; f < nf; ++f) {
    const PetscReal *xf = &xf_all[f * MM_FACET_REALS];
    PetscReal        phi[MM_MAX_DIM], d2 = ClosestOnFacet(dim, xf, x, phi), scale = 0;
    PetscBool        take = PETSC_FALSE;
    for (PetscInt d = 0; d < dim; ++d) scale += PetscSqr(xf[d] - xf[dim + d]);
    if (fb < 0 || d2 < db - 1e-13 * scale) take = PETSC_TRUE;
    else if (d2 <= db + 1e-13 * scale) {
      const PetscReal *c0 = &xf_all[fb * MM_FACET_REALS + dim * dim + dim], *c1 = &xf[dim * dim + dim];
      for (PetscInt d = 0; d < dim; ++d) {
        if (c1[d] == c0[d]) continue;
        take = (PetscBool)(c1[d] < c0[d]);
        break;
      }
    }
    if (!take) continue;
    fb = f;
    db = d2;
    for (PetscInt j = 0; j < dim; ++j) phib[j] = phi[j];
  }
  return fb;
}

/* Slave node k's weights and master dofs for facet fb of pair p */
void MMContactPairsSetPairing(MMContactPairs *pr, PetscInt dim, PetscInt p, PetscInt k, PetscInt fb, const PetscReal phib[])
{
  pr->facet[k] = fb;
  for (PetscInt j = 0; j < MM_MAX_DIM; ++j) {
    pr->phi[MM_MAX_DIM * k + j]  = j < dim ? phib[j] : 0;
    pr->mdof[MM_MAX_DIM * k + j] = j < dim ? pr->df[p][fb * MM_MAX_DIM + j] : -1;
  }
}

/* Slave node k (reference position x) of pair p: its closest master facet, the weights and master
 * dofs of its constraint, its gap and the facet's outward normal n. */
PetscErrorCode MMContactPairsProject(MMContact ct, PetscInt p, PetscInt k, const PetscReal x[], PetscReal *gap, PetscReal n[])
{
  MMContactPairs  *pr  = &ct->pairs;
  const PetscInt   dim = ct->dim;
  PetscReal        phib[MM_MAX_DIM] = {0, 0, 0};
  const PetscInt   fb = MMContactPairsClosestFacet(dim, pr->nf[p], pr->xf[p], x, phib);
  const PetscReal *xf = &pr->xf[p][fb * MM_FACET_REALS];

  PetscFunctionBeginUser;
  *gap = 0;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) n[d] = d < dim ? xf[dim * dim + d] : 0;
  for (PetscInt d = 0; d < dim; ++d) {
    PetscReal xp = 0;
    for (PetscInt j = 0; j < dim; ++j) xp += phib[j] * xf[j * dim + d];
    *gap += n[d] * (x[d] - xp);
  }
  MMContactPairsSetPairing(pr, dim, p, k, fb, phib);
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
    pr->xs[MM_MAX_DIM * k + d]  = d < dim ? x[d] : 0;
    pr->nuc[MM_MAX_DIM * k + d] = -n[d]; /* the frame's nu (set.c FrameFromNormal) */
  }
  PetscFunctionReturn(0);
}

/* N = I + C and N^{-1} = I - C, C[s_a, m_j d] = phi_j F_a[d] for the slave node s's frame rows a (the
 * normal; the tangents too with friction, for the relative slip) and its master vertices m_j. A
 * corner node's second row (a node against two obstacles, set.c) is its own 2x2 block of N, with
 * its explicit inverse: N stays the identity where there are neither pairs nor corners. */
PetscErrorCode MMContactPairsBuildN(MMContact ct)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim, nr = ct->ncomp;
  const PetscInt *in;
  PetscInt        n, rstart;
  Mat             N[2];
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  PetscCall(MatGetLocalSize(ct->transform.Q, &n, NULL));
  PetscCall(MatGetOwnershipRange(ct->transform.Q, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  for (PetscInt s = 0; s < 2; ++s) {
    const PetscScalar sign = s ? -1.0 : 1.0;
    PetscCall(MatCreateAIJ(comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 1 + dim * dim, NULL, dim * dim, NULL, &N[s]));
    PetscCall(MatSetOption(N[s], MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
    for (PetscInt i = rstart; i < rstart + n; ++i) PetscCall(MatSetValue(N[s], i, i, 1.0, INSERT_VALUES));
    for (PetscInt k = 0; k < ct->n_local; ++k) {
      const PetscReal *F = &ct->node_frame[9 * k];
      if (ct->second[k]) {
        /* a corner's second row: y_1 = (w_1 - a w_0)/b, w_1 = a y_0 + b y_1 (set.c CornerFrame) */
        const PetscReal a = ct->corner_ab[2 * k], b = ct->corner_ab[2 * k + 1];
        PetscCall(MatSetValue(N[s], in[k], in[k] - 1, s ? a : -a / b, INSERT_VALUES));
        PetscCall(MatSetValue(N[s], in[k], in[k], s ? b : 1 / b, INSERT_VALUES));
        continue;
      }
      if (ct->obstacle[k] < ct->pb.n_rigid) continue;
      if (pr->large) {
        /* large sliding (frictionless): the row's dof is w_0 = nu_c.(u_s - sum_j phi_j u_mj), nu_c the current
         * facet's direction, = c_0 y_0 + sum_e c_e y_e - sum_j phi_j nu_c.u_mj with c_e = nu_c.F_e, so that
         * y_0 = (w_0 - sum_e c_e y_e + sum_j phi_j nu_c.u_mj) / c_0: N and N^{-1} differ from I in row 0 alone,
         * where M* has no mass (docs/method.md section 11, "Large sliding") */
        const PetscReal *nc = &pr->nuc[MM_MAX_DIM * k];
        PetscReal        c[MM_MAX_DIM] = {0, 0, 0};
        for (PetscInt e = 0; e < dim; ++e)
          for (PetscInt d = 0; d < dim; ++d) c[e] += nc[d] * F[3 * e + d];
        PetscCall(MatSetValue(N[s], in[k], in[k], s ? c[0] : 1 / c[0], INSERT_VALUES));
        for (PetscInt e = 1; e < dim; ++e)
          if (c[e] != 0) PetscCall(MatSetValue(N[s], in[k], in[k] + e, s ? c[e] : -c[e] / c[0], INSERT_VALUES));
        for (PetscInt j = 0; j < dim; ++j) {
          const PetscInt m = pr->mdof[MM_MAX_DIM * k + j];
          if (m < 0 || pr->phi[MM_MAX_DIM * k + j] == 0) continue;
          for (PetscInt d = 0; d < dim; ++d) PetscCall(MatSetValue(N[s], in[k], m + d, s ? -pr->phi[MM_MAX_DIM * k + j] * nc[d] : pr->phi[MM_MAX_DIM * k + j] * nc[d] / c[0], INSERT_VALUES));
        }
        continue;
      }
      for (PetscInt a = 0; a < nr; ++a)
        for (PetscInt j = 0; j < dim; ++j) {
          const PetscInt m = pr->mdof[MM_MAX_DIM * k + j];
          if (m < 0 || pr->phi[MM_MAX_DIM * k + j] == 0) continue; /* a held master node does not move */
          for (PetscInt d = 0; d < dim; ++d) PetscCall(MatSetValue(N[s], in[k] + a, m + d, sign * pr->phi[MM_MAX_DIM * k + j] * F[3 * a + d], INSERT_VALUES));
        }
    }
    PetscCall(MatAssemblyBegin(N[s], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(N[s], MAT_FINAL_ASSEMBLY));
  }
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  ct->transform.N    = N[0];
  ct->transform.Ninv = N[1];
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactPairsBuildTransform(MMContact ct)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim;
  PetscInt        corners = 0;
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < ct->n_local; ++k) corners += ct->second[k];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &corners, 1, MPIU_INT, MPI_SUM, comm));
  ct->n_corners = corners;
  /* per pair its slave nodes, and those that face a master node (one weight 1: node to node) */
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt p = ct->obstacle[k] - ct->pb.n_rigid;
    PetscBool      facing = PETSC_FALSE;
    if (p < 0 || ct->second[k]) continue;
    for (PetscInt j = 0; j < dim; ++j) facing = (PetscBool)(facing || pr->phi[MM_MAX_DIM * k + j] == 1.0);
    pr->count[2 * p] += 1;
    pr->count[2 * p + 1] += facing;
  }
  if (pr->n) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, pr->count, 2 * pr->n, MPIU_INT, MPI_SUM, comm));
  if (!pr->n && !corners) PetscFunctionReturn(0);
  PetscCall(MMContactPairsBuildN(ct));
  PetscFunctionReturn(0);
}

/* The w-frame operators and loads of the pairs' relative variables, from the contact-frame ones:
 * K <- N^T K N, M <- N^T M N, M* <- N^T M* N, and the loads L <- N^T L (docs/method.md section 11).
 * Runs after M* is built and its moments taken, which N leaves unchanged (frame/frame.c). */
PetscErrorCode MMContactPairsTransformOperators(MMContact ct, MMOperators op)
{
  Mat         *A[3] = {&ct->K, &ct->mass.M, &ct->mass.Mstar}, B;
  Vec          t;

  PetscFunctionBeginUser;
  if (!ct->transform.N) PetscFunctionReturn(0);
  if (ct->pairs.large) { /* the contact-frame K and M*, from which each new pairing's are built */
    PetscCall(MatDuplicate(ct->K, MAT_COPY_VALUES, &ct->pairs.Ky));
    PetscCall(MatDuplicate(ct->mass.Mstar, MAT_COPY_VALUES, &ct->pairs.My));
  }
  for (PetscInt i = 0; i < 3; ++i) {
    PetscCall(MatPtAP(*A[i], ct->transform.N, MAT_INITIAL_MATRIX, 2.0, &B));
    PetscCall(MatDestroy(A[i]));
    *A[i] = B;
  }
  PetscCall(VecDuplicate(ct->load, &t));
  PetscCall(VecCopy(ct->load, t));
  PetscCall(MatMultTranspose(ct->transform.N, t, ct->load));
  PetscCall(VecCopy(ct->lift, t));
  PetscCall(MatMultTranspose(ct->transform.N, t, ct->lift));
  PetscCall(VecDestroy(&t));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactPairsDestroy(MMContactPairs *pr)
{
  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < pr->n; ++p) PetscCall(PetscFree2(pr->xf[p], pr->df[p]));
  if (pr->n) PetscCall(PetscFree4(pr->nf, pr->xf, pr->df, pr->count));
  PetscCall(PetscFree2(pr->phi, pr->mdof));
  PetscCall(PetscFree3(pr->facet, pr->xs, pr->nuc));
  PetscCall(PetscFree2(pr->far, pr->far_d));
  PetscCall(MatDestroy(&pr->Ky));
  PetscCall(MatDestroy(&pr->My));
  PetscCall(VecDestroy(&pr->y));
  PetscCall(VecDestroy(&pr->um));
  PetscCall(VecScatterDestroy(&pr->to_um));
  PetscCall(PetscFree(pr->um_off));
  pr->n = 0;
  PetscFunctionReturn(0);
}
