/* Friction corners (docs/method.md section 12): with friction, a contact node within h_c' of a
 * second obstacle keeps one row, whose frame (nu_1, tau_1, tau_2) has tau_1 in the plane of both
 * normals, nu_2 = a nu_1 + b tau_1. The second obstacle's frame is then (nu_2, tau'_1, tau_2) with
 * tau'_1 = b nu_1 - a tau_1: its components are T2 y, T2 = [[a, b, 0], [b, -a, 0], [0, 0, 1]]
 * (symmetric and orthogonal, T2 = T2^T = T2^{-1}). Each obstacle keeps its own Coulomb law: the node's
 * reaction in its frame is rho = r_1 + T2 r_2, r_1 and r_2 each in its obstacle's frame (normal
 * first), and the condensed formulation's contact-space problem gets a second node, on the same
 * dofs, for r_2. */
#include "../contactimpl.h"
#include "obstacle.h"

void MMContactCornerT2(PetscInt dim, const PetscReal ab[2], PetscReal T[MM_MAX_DIM][MM_MAX_DIM])
{
  for (PetscInt i = 0; i < MM_MAX_DIM; ++i)
    for (PetscInt j = 0; j < MM_MAX_DIM; ++j) T[i][j] = (i == j && i >= 2) ? 1 : 0;
  T[0][0] = ab[0];
  T[0][1] = T[1][0] = ab[1];
  T[1][1] = -ab[0];
  (void)dim;
}

/* The second obstacle's frame (rows nu_2, tau'_1, tau_2, Cartesian) from the node's, F1 (9 reals). */
void MMContactCornerFrame2(PetscInt dim, const PetscReal F1[], const PetscReal ab[2], PetscReal F2[MM_MAX_DIM][MM_MAX_DIM])
{
  PetscReal T[MM_MAX_DIM][MM_MAX_DIM];

  MMContactCornerT2(dim, ab, T);
  for (PetscInt i = 0; i < MM_MAX_DIM; ++i)
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
      F2[i][d] = 0;
      for (PetscInt e = 0; e < dim; ++e) F2[i][d] += T[i][e] * F1[3 * e + d];
    }
}

/* y = T2 x on dim components. */
static void ApplyT2(PetscInt dim, const PetscReal ab[2], const PetscReal x[], PetscReal y[])
{
  PetscReal T[MM_MAX_DIM][MM_MAX_DIM];

  MMContactCornerT2(dim, ab, T);
  for (PetscInt i = 0; i < dim; ++i) {
    y[i] = 0;
    for (PetscInt e = 0; e < dim; ++e) y[i] += T[i][e] * x[e];
  }
}

/* Row k's two obstacles' reactions from the node's total rho_k (ncomp = dim components): r_2 is
 * kept (ct->fc_r), r_1 = rho - T2 r_2. Not a friction corner: r_1 = rho, r_2 = 0. */
void MMContactCornerSplit(MMContact ct, PetscInt dim, PetscInt k, const PetscScalar rho[], PetscReal r1[], PetscReal r2[])
{
  PetscReal t[MM_MAX_DIM] = {0, 0, 0};

  for (PetscInt c = 0; c < dim; ++c) r2[c] = 0;
  if (ct->fc_obstacle && ct->fc_obstacle[k] >= 0) {
    for (PetscInt c = 0; c < dim; ++c) r2[c] = ct->fc_r[k * dim + c];
    ApplyT2(dim, &ct->fc_ab[2 * k], r2, t);
  }
  for (PetscInt c = 0; c < dim; ++c) r1[c] = PetscRealPart(rho[c]) - t[c];
}

/* The candidate set's gathers of the corners' data: (b, a) and mu_2 (fixed), q_2 and r_2 (per step). */
PetscErrorCode MMContactCornersSetUpVecs(MMContact ct)
{
  PetscScalar *ga, *ma;

  PetscFunctionBeginUser;
  if (ct->fc_geom || !ct->n_fc) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ct->rho, &ct->fc_geom));
  PetscCall(VecDuplicate(ct->rho, &ct->fc_mu));
  PetscCall(VecDuplicate(ct->rho, &ct->fc_q));
  PetscCall(VecDuplicate(ct->rho, &ct->fc_x));
  PetscCall(VecZeroEntries(ct->fc_geom));
  PetscCall(VecZeroEntries(ct->fc_mu));
  PetscCall(VecGetArray(ct->fc_geom, &ga));
  PetscCall(VecGetArray(ct->fc_mu, &ma));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    if (ct->fc_obstacle[k] < 0) continue;
    ga[ct->ncomp * k]     = ct->fc_ab[2 * k + 1];
    ga[ct->ncomp * k + 1] = ct->fc_ab[2 * k];
    ma[ct->ncomp * k]     = ct->pb.obstacles[ct->fc_obstacle[k]].mu;
  }
  PetscCall(VecRestoreArray(ct->fc_mu, &ma));
  PetscCall(VecRestoreArray(ct->fc_geom, &ga));
  PetscFunctionReturn(0);
}

/* The second rows' right-hand side, q_2 = T2 z_c - offset_2 with offset_2 = (g_2, T2 o + dt/2
 * V_2.tau'), o = u^n + dt/2 v^n the step's offset (MMContactSetStepOffset), as CondensedRHS does for
 * the first (docs/method.md section 12), and their warm start r_2 from the last solve. row: each
 * condensed slot's local dof. */
PetscErrorCode MMContactCornersRHS(MMContact ct, const PetscInt row[])
{
  const PetscInt     dim = ct->dim;
  const PetscScalar *za, *sa;
  PetscScalar       *qa, *xa;

  PetscFunctionBeginUser;
  if (!ct->n_fc) PetscFunctionReturn(0);
  PetscCall(MMContactCornersSetUpVecs(ct));
  PetscCall(VecGetArrayRead(ct->z, &za));
  PetscCall(VecGetArrayRead(ct->step.offset, &sa));
  PetscCall(VecGetArray(ct->fc_q, &qa));
  PetscCall(VecGetArray(ct->fc_x, &xa));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    PetscReal z[MM_MAX_DIM], o[MM_MAX_DIM], Tz[MM_MAX_DIM], To[MM_MAX_DIM];
    if (ct->fc_obstacle[k] < 0) continue;
    for (PetscInt c = 0; c < dim; ++c) {
      const PetscInt i = row[dim * k + c];
      z[c] = PetscRealPart(za[i]);
      o[c] = PetscRealPart(sa[i]);
    }
    ApplyT2(dim, &ct->fc_ab[2 * k], z, Tz);
    ApplyT2(dim, &ct->fc_ab[2 * k], o, To);
    qa[dim * k] = Tz[0] - ct->fc_gap[k];
    for (PetscInt c = 1; c < dim; ++c) qa[dim * k + c] = Tz[c] - To[c] - ct->fc_slide[k * (dim - 1) + c - 1];
    for (PetscInt c = 0; c < dim; ++c) xa[dim * k + c] = ct->fc_r[dim * k + c];
  }
  PetscCall(VecRestoreArray(ct->fc_x, &xa));
  PetscCall(VecRestoreArray(ct->fc_q, &qa));
  PetscCall(VecRestoreArrayRead(ct->step.offset, &sa));
  PetscCall(VecRestoreArrayRead(ct->z, &za));
  PetscFunctionReturn(0);
}

/* Whether row k's second obstacle is crossed by the owned condensed solution wc (nc per row), beyond
 * tol: the candidate set grows by such nodes as by those crossing their first. */
PetscBool MMContactCornerCrosses(MMContact ct, PetscInt dim, PetscInt k, const PetscScalar wc[], PetscReal tol)
{
  PetscReal w[MM_MAX_DIM], Tw[MM_MAX_DIM];

  if (!ct->fc_obstacle || ct->fc_obstacle[k] < 0) return PETSC_FALSE;
  for (PetscInt c = 0; c < dim; ++c) w[c] = PetscRealPart(wc[dim * k + c]);
  ApplyT2(dim, &ct->fc_ab[2 * k], w, Tw);
  return (PetscBool)(Tw[0] - ct->fc_gap[k] > tol);
}

/* The set's problem with a second node for each friction corner in it (after the set's own n
 * nodes, in set order): W_e = T W T^T, T the identity on the set's nodes and T2 on a corner's second
 * node; q, mu and the warm start x (= rho - T2 r_2 and r_2) likewise. geom, mu2, q2, x2: the set's
 * gathers of fc_geom, fc_mu, fc_q, fc_x. Returns the extended node count and the arrays (to free). */
PetscErrorCode MMContactCornersExpand(PetscInt n, PetscInt nc, const PetscScalar W[], const PetscScalar q[], const PetscReal mu[], const PetscScalar x[], const PetscScalar geom[], const PetscScalar mu2[], const PetscScalar q2[], const PetscScalar x2[], PetscInt *ne, PetscInt **of, PetscScalar **We, PetscScalar **qe, PetscReal **mue, PetscScalar **xe)
{
  PetscInt     m = n * nc, me, nx = 0, *corner;
  PetscScalar *A;
  PetscReal  (*T)[MM_MAX_DIM][MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &corner));
  for (PetscInt i = 0; i < n; ++i) corner[i] = PetscRealPart(geom[i * nc]) > 0 ? n + nx++ : -1;
  *ne = n + nx;
  me  = *ne * nc;
  PetscCall(PetscMalloc1(PetscMax(nx, 1), &T));
  PetscCall(PetscMalloc1(nx, of));
  for (PetscInt i = 0; i < n; ++i)
    if (corner[i] >= 0) {
      const PetscReal ab[2] = {PetscRealPart(geom[i * nc + 1]), PetscRealPart(geom[i * nc])};
      MMContactCornerT2(nc, ab, T[corner[i] - n]);
      (*of)[corner[i] - n] = i;
    }
  PetscCall(PetscMalloc4((size_t)me * me, We, me, qe, *ne, mue, me, xe));
  PetscCall(PetscMalloc1((size_t)m * me, &A));
  /* A = W T^T (m x me), then W_e = T A; column-major */
  for (PetscInt jb = 0; jb < *ne; ++jb)
    for (PetscInt c = 0; c < nc; ++c)
      for (PetscInt r = 0; r < m; ++r) {
        PetscScalar v = 0;
        if (jb < n) v = W[r + (size_t)(jb * nc + c) * m];
        else
          for (PetscInt e = 0; e < nc; ++e) v += W[r + (size_t)((*of)[jb - n] * nc + e) * m] * T[jb - n][c][e];
        A[r + (size_t)(jb * nc + c) * m] = v;
      }
  for (PetscInt col = 0; col < me; ++col)
    for (PetscInt ib = 0; ib < *ne; ++ib)
      for (PetscInt c = 0; c < nc; ++c) {
        PetscScalar v = 0;
        if (ib < n) v = A[ib * nc + c + (size_t)col * m];
        else
          for (PetscInt e = 0; e < nc; ++e) v += T[ib - n][c][e] * A[(*of)[ib - n] * nc + e + (size_t)col * m];
        (*We)[ib * nc + c + (size_t)col * me] = v;
      }
  for (PetscInt i = 0; i < n; ++i) {
    (*mue)[i] = mu[i];
    for (PetscInt c = 0; c < nc; ++c) {
      (*qe)[i * nc + c] = q[i * nc + c];
      (*xe)[i * nc + c] = x[i * nc + c];
    }
    if (corner[i] < 0) continue;
    (*mue)[corner[i]] = PetscRealPart(mu2[i * nc]);
    for (PetscInt c = 0; c < nc; ++c) {
      (*qe)[corner[i] * nc + c] = q2[i * nc + c];
      (*xe)[corner[i] * nc + c] = x2[i * nc + c];
      for (PetscInt e = 0; e < nc; ++e) (*xe)[i * nc + c] -= T[corner[i] - n][c][e] * x2[i * nc + e];
    }
  }
  PetscCall(PetscFree(A));
  PetscCall(PetscFree(T));
  PetscCall(PetscFree(corner));
  PetscFunctionReturn(0);
}

/* Back from the extended problem's reactions xe: x = r_1 + T2 r_2 on the set's nodes, x2 = r_2. */
PetscErrorCode MMContactCornersContract(PetscInt n, PetscInt nc, PetscInt ne, const PetscInt of[], const PetscScalar geom[], const PetscScalar xe[], PetscScalar x[], PetscScalar x2[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n * nc; ++k) {
    x[k]  = xe[k];
    x2[k] = 0;
  }
  for (PetscInt jb = n; jb < ne; ++jb) {
    const PetscInt  i     = of[jb - n];
    const PetscReal ab[2] = {PetscRealPart(geom[i * nc + 1]), PetscRealPart(geom[i * nc])};
    PetscReal       T[MM_MAX_DIM][MM_MAX_DIM];
    MMContactCornerT2(nc, ab, T);
    for (PetscInt c = 0; c < nc; ++c) {
      x2[i * nc + c] = xe[jb * nc + c];
      for (PetscInt e = 0; e < nc; ++e) x[i * nc + c] += T[c][e] * xe[jb * nc + e];
    }
  }
  PetscFunctionReturn(0);
}

/* The last solve's r_2 into ct->fc_r, from fc_x (global, layout of rho). */
PetscErrorCode MMContactCornersStore(MMContact ct)
{
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  if (!ct->n_fc) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ct->fc_x, &xa));
  for (PetscInt k = 0; k < ct->n_local; ++k)
    if (ct->fc_obstacle[k] >= 0)
      for (PetscInt c = 0; c < ct->ncomp; ++c) ct->fc_r[ct->ncomp * k + c] = PetscRealPart(xa[ct->ncomp * k + c]);
  PetscCall(VecRestoreArrayRead(ct->fc_x, &xa));
  PetscFunctionReturn(0);
}

/*@
  MMContactCornersAccept - Keeps an accepted step's friction-corner reactions r_2 as the next step's
  old ones

  Not collective

  Input Parameter:
. ct - the contact object

  Note:
  An accepted step's r_2 becomes the next step's old one (the trapezoidal works of section 12).

  Level: developer

.seealso: `MMContactCornersWork()`
@*/
PetscErrorCode MMContactCornersAccept(MMContact ct)
{

  PetscFunctionBeginUser;
  if (ct->fc_r) PetscCall(PetscArraycpy(ct->fc_r_old, ct->fc_r, (size_t)ct->n_local * ct->dim));
  PetscFunctionReturn(0);
}

/*@
  MMContactCornersWork - Computes the friction corners' corrections to the step's split of the works

  Collective

  Input Parameters:
+ ct - the contact object
. t0 - the step's start time
. t1 - its end time
- du - the step's displacement increment (w-frame)

  Output Parameters:
+ dwc - the correction of the contact work W_c
. dwn - that of the obstacles' normal work
- dwt - that of the obstacles' tangential work

  Note:
  The friction corners' part of the works over the step t0 -> t1 with increment du (w-frame), as
  corrections to the generic split (energy.c), which puts a node's y_0 force in W_c and its other
  components in W_f, each with both obstacles' parts, and measures the obstacle's work with the
  node's first obstacle only. Per obstacle instead (docs/method.md section 12): W_c gets each
  obstacle's normal force on its own normal displacement, W_f the tangential ones, and each
  obstacle's work is its own force on its own displacement. dwc + dwf = 0 and the obstacle works
  move between the terms only: the energy balance is unchanged, its split is each obstacle's. dwn,
  dwt: the corrections of the obstacles' normal and tangential works. Uses the trapezoidal
  averages of r_2 (this solve's and the accepted step's).

  Level: developer

.seealso: `MMContactCornersAccept()`
@*/
PetscErrorCode MMContactCornersWork(MMContact ct, PetscReal t0, PetscReal t1, Vec du, PetscReal *dwc, PetscReal *dwn, PetscReal *dwt)
{
  const PetscInt     dim = ct->dim;
  const PetscInt    *in;
  const PetscScalar *da;
  PetscInt           rstart;
  PetscReal          w[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  *dwc = *dwn = *dwt = 0;
  if (!ct->enabled || !ct->n_fc) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(du, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(du, &da));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const MMObstacle *ob1 = &ct->pb.obstacles[ct->obstacle[k]];
    PetscReal         r2[MM_MAX_DIM], f2[MM_MAX_DIM], g2[MM_MAX_DIM], d[MM_MAX_DIM], Td[MM_MAX_DIM], c0[MM_MAX_DIM] = {0, 0, 0}, c1[MM_MAX_DIM] = {0, 0, 0}, e0[MM_MAX_DIM] = {0, 0, 0}, e1[MM_MAX_DIM] = {0, 0, 0}, dc1[MM_MAX_DIM], dc2[MM_MAX_DIM], Tdc2[MM_MAX_DIM];
    const PetscReal  *F1 = &ct->node_frame[9 * k];
    if (ct->fc_obstacle[k] < 0) continue;
    /* the second obstacle's force on the body, trapezoidal: -r_2 in its frame, g2; f2 = T2 g2 in the node's */
    for (PetscInt c = 0; c < dim; ++c) {
      r2[c] = -0.5 * (ct->fc_r[dim * k + c] + ct->fc_r_old[dim * k + c]);
      d[c]  = PetscRealPart(da[in[k] - rstart + c]);
    }
    for (PetscInt c = 0; c < dim; ++c) g2[c] = r2[c];
    ApplyT2(dim, &ct->fc_ab[2 * k], g2, f2);
    ApplyT2(dim, &ct->fc_ab[2 * k], d, Td);
    /* W_c: the second obstacle's normal force on its own normal, not its y_0 component on y_0 */
    w[0] += g2[0] * Td[0] - f2[0] * d[0];
    if (!ct->moving) continue;
    MMObstacleDisplacement(ob1, dim, t0, c0);
    MMObstacleDisplacement(ob1, dim, t1, c1);
    MMObstacleDisplacement(&ct->pb.obstacles[ct->fc_obstacle[k]], dim, t0, e0);
    MMObstacleDisplacement(&ct->pb.obstacles[ct->fc_obstacle[k]], dim, t1, e1);
    for (PetscInt c = 0; c < dim; ++c) {
      dc1[c] = dc2[c] = 0;
      for (PetscInt e = 0; e < dim; ++e) {
        dc1[c] += (c1[e] - c0[e]) * F1[3 * c + e];
        dc2[c] += (e1[e] - e0[e]) * F1[3 * c + e];
      }
    }
    ApplyT2(dim, &ct->fc_ab[2 * k], dc2, Tdc2);
    /* the generic obstacle work took f2 on the first obstacle's displacement: f2.dc1 out, g2.T2 dc2 in */
    w[1] += g2[0] * Tdc2[0] - f2[0] * dc1[0];
    for (PetscInt c = 1; c < dim; ++c) w[2] += g2[c] * Tdc2[c] - f2[c] * dc1[c];
  }
  PetscCall(VecRestoreArrayRead(du, &da));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, w, 3, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ct->dm)));
  *dwc = w[0];
  *dwn = w[1];
  *dwt = w[2];
  PetscFunctionReturn(0);
}
