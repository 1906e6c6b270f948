/* Contact diagnostics of a state: active, switching, slipping and sticking nodes, contact forces,
 * penetration, the discrete Coulomb residual (docs/method.md section 6), and the output fields on
 * the contact boundary. */
#include "../contactimpl.h"
#include "obstacle.h"
#include "sys.h"

/* Per-node contact statistics of a state (w, react, sigma): sigma holds the velocity, whose
 * tangential components at a contact node are its slip velocity. */
typedef struct {
  PetscInt  active, switched, slipping, sticking;
  PetscReal force_normal, force_t[MM_MAX_DIM], max_penetration, coulomb;
  PetscReal penetration_free; /* the part of max_penetration into obstacles without a row for the node */
  PetscReal penetration_bound; /* the crossing of the nodes' own bounds (the solve's) */
} ContactStats;
/* force_t: in 2D the sum of the tangential reactions along each node's tangent (the tangents turn
 * with the normals, so the sum does not depend on the orientation of the mesh); in 3D the
 * Cartesian resultant of the tangential reactions, since the tangent bases of two nodes need not
 * share an orientation. */

/* With several obstacles: contact node k's deepest penetration of any obstacle, u.nu_b - g_b(t),
 * g_b(t) = g_b(X) + c_b(t).nu_b, linearized at the reference position like its own constraint
 * (docs/method.md section 8); w the node's frame components, cob the obstacles' displacements. A
 * node tied to one obstacle may cross another (a corner between two walls): the history and the
 * summary report it. */
static PetscReal OtherObstaclesPenetration(MMContact ct, PetscInt k, const PetscScalar w[], const PetscReal cob[])
{
  const PetscInt   dim = ct->dim, nob = ct->pb.n_rigid;
  const PetscReal *F   = &ct->node_frame[9 * k];
  PetscReal        u[MM_MAX_DIM] = {0, 0, 0}, worst = PETSC_MIN_REAL;

  PetscReal        y[MM_MAX_DIM] = {0, 0, 0};

  for (PetscInt e = 0; e < dim; ++e) y[e] = PetscRealPart(w[e]);
  /* a corner (the next row its second): w_1 = a y_0 + b y_1 */
  if (k + 1 < ct->n_local && ct->second[k + 1]) y[1] = (y[1] - ct->corner_ab[2 * (k + 1)] * y[0]) / ct->corner_ab[2 * (k + 1) + 1];
  for (PetscInt e = 0; e < dim; ++e)
    for (PetscInt d = 0; d < dim; ++d) u[d] += y[e] * F[3 * e + d];
  for (PetscInt b = 0; b < nob; ++b) {
    const PetscReal *nu = &ct->all_nu[3 * (k * nob + b)];
    PetscReal        p  = -ct->all_gap0[k * nob + b];
    for (PetscInt d = 0; d < dim; ++d) p += (u[d] - cob[MM_MAX_DIM * b + d]) * nu[d];
    worst = PetscMax(worst, p);
  }
  return worst;
}

/* One obstacle's Coulomb law at one node (docs/method.md section 6): its gap g - un, normal
 * reaction r, tangential force ft and slip vt (dim - 1 each, its own frame), whether its tangential
 * reaction is on the rim of its disk; the residual, and cnt[2] (slipping) or cnt[3] (sticking). */
typedef struct {
  PetscReal un, g, r, mu, ft[MM_MAX_DIM], vt[MM_MAX_DIM];
  PetscBool at_bound, friction;
} RowState;

static PetscReal RowResidual(const RowState *rs, PetscInt dim, PetscReal h_c, PetscReal dt, PetscReal fscale, PetscReal vtol, PetscInt cnt[4])
{
  const PetscBool active = (PetscBool)(rs->g - rs->un <= 1e-10 * h_c);
  PetscReal       tn = 0, vn = 0, res = 0;

  for (PetscInt d = 1; d < dim; ++d) {
    tn += PetscSqr(rs->ft[d]);
    vn += PetscSqr(rs->vt[d]);
  }
  tn  = PetscSqrtReal(tn);
  vn  = PetscSqrtReal(vn);
  res = PetscMax(res, (rs->un - rs->g) / h_c);                                    /* penetration */
  res = PetscMax(res, -rs->r / fscale);                                           /* tension */
  res = PetscMax(res, PetscAbsReal(rs->r * (rs->un - rs->g)) / (fscale * h_c));   /* complementarity */
  res = PetscMax(res, (tn - rs->mu * PetscMax(rs->r, 0)) / fscale);               /* cone */
  /* inside the cone a node must not slip */
  if (active && rs->friction && !rs->at_bound) res = PetscMax(res, vn * dt / (2 * h_c));
  if (active && rs->at_bound && vn > vtol) {
    PetscReal slip = 0; /* |t + mu r sigma/|sigma|| */
    for (PetscInt d = 1; d < dim; ++d) slip += PetscSqr(rs->ft[d] + rs->mu * rs->r * rs->vt[d] / vn);
    res = PetscMax(res, PetscSqrtReal(slip) / fscale);
    ++cnt[2];
  } else if (active && rs->friction) ++cnt[3];
  cnt[0] += active;
  return res;
}

/* A friction corner's second obstacle (docs/method.md section 12): its row state from the node's
 * w (its frame components), its slip sigma = 2/dt (w - u^n) - v^n (the one its law is solved with:
 * the node's normal velocity is the massless dofs' backward difference in v, not this) and r_2;
 * its force on the obstacle added to fob. sg: sigma at the node, the stepper's velocity of w
 * (MMContactStepVelocity; NULL before the stepper hands it: v). */
static void SecondObstacleRow(MMContact ct, PetscInt k, const PetscScalar w[], const PetscScalar v[], const PetscScalar sg[], PetscReal fob[], RowState *rs)
{
  const PetscInt   dim = ct->dim;
  const PetscReal *r2  = &ct->fc_r[dim * k], dt = ct->Kt_dt;
  PetscReal        F2[MM_MAX_DIM][MM_MAX_DIM], T[MM_MAX_DIM][MM_MAX_DIM], rt = 0, sigma[MM_MAX_DIM];

  MMContactCornerFrame2(dim, &ct->node_frame[9 * k], &ct->fc_ab[2 * k], F2);
  MMContactCornerT2(dim, &ct->fc_ab[2 * k], T);
  PetscMemzero(rs, sizeof(*rs));
  for (PetscInt e = 0; e < dim; ++e) sigma[e] = sg ? PetscRealPart(sg[e]) : PetscRealPart(v[e]);
  for (PetscInt e = 0; e < dim; ++e) rs->un += T[0][e] * PetscRealPart(w[e]);
  rs->g        = ct->fc_gap[k];
  rs->r        = r2[0];
  rs->mu       = ct->pb.obstacles[ct->fc_obstacle[k]].mu;
  rs->friction = PETSC_TRUE;
  for (PetscInt j = 1; j < dim; ++j) {
    rs->ft[j] = -r2[j];
    for (PetscInt e = 0; e < dim; ++e) rs->vt[j] += T[j][e] * sigma[e];
    rs->vt[j] -= dt > 0 ? 2 * ct->fc_slide[k * (dim - 1) + j - 1] / dt : 0;
    rt += PetscSqr(r2[j]);
  }
  rs->at_bound = (PetscBool)(PetscSqrtReal(rt) >= rs->mu * PetscMax(rs->r, 0) * (1 - 1e-6) - 2e-8);
  /* the force on the obstacle: minus the reaction on the body, -(-r_2), in Cartesian */
  for (PetscInt j = 0; j < dim; ++j)
    for (PetscInt c = 0; c < dim; ++c) fob[MM_MAX_DIM * ct->fc_obstacle[k] + c] += r2[j] * F2[j][c];
}

static PetscErrorCode ContactStatistics(MMContact ct, PetscReal t, Vec w, Vec react, Vec sigma, PetscBool record_switches, ContactStats *st)
{
  const PetscReal    dt = ct->Kt_dt;
  const PetscInt     nob = ct->pb.n_obstacles;
  const PetscScalar *mua;
  PetscReal         *fob, *cob;
  /* slip is judged by the step's slip increment sigma dt/2 against h_c', like penetration */
  const PetscReal    vtol = 1e-9 * 2 * ct->h_c / dt;
  PetscInt           dim = ct->dim, nc = ct->n_local, cnt[4] = {0, 0, 0, 0}, rstart;
  const PetscInt    *in;
  const PetscScalar *wa, *fa, *ga, *va, *ra = NULL, *rh = NULL, *sga = NULL;
  Vec                sigma2 = NULL; /* friction corners: the velocity of w over the step, for their second rows */
  const PetscInt     nr = ct->ncomp;
  PetscReal          sums[1 + MM_MAX_DIM] = {0, 0, 0, 0}, loc[4] = {0, 0, 0, 0}, rmax = 0, fscale;
  MPI_Comm           comm = PetscObjectComm((PetscObject)ct->dm);
  struct {
    double value; /* MPI_DOUBLE_INT's layout, for MPI_MAXLOC */
    int    rank;
  } slid;
  PetscInt slid_ob = 0;

  PetscFunctionBeginUser;
  slid.value = 0;
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    slid.rank = rank;
  }
  PetscCall(PetscMemzero(st, sizeof(*st)));
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(PetscCalloc1(MM_MAX_DIM * nob, &fob));
  PetscCall(PetscCalloc1(MM_MAX_DIM * nob, &cob));
  for (PetscInt b = 0; b < ct->pb.n_rigid && ct->all_gap0; ++b) MMObstacleDisplacement(&ct->pb.obstacles[b], dim, t, &cob[MM_MAX_DIM * b]);
  PetscCall(VecGetArrayRead(ct->mu, &mua));
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(react, &fa));
  PetscCall(VecGetArrayRead(sigma, &va));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  if (ct->n_fc && ct->step.velocity && dt > 0) {
    PetscCall(VecDuplicate(w, &sigma2));
    PetscCall(MMContactStepVelocity(ct, w, sigma2));
    PetscCall(VecGetArrayRead(sigma2, &sga));
  }
  if (nr > 1) {
    PetscCall(VecGetArrayRead(ct->rho, &ra));
    PetscCall(VecGetArrayRead(ct->rho_hi, &rh));
  }
  for (PetscInt k = 0; k < nc; ++k) rmax = PetscMax(rmax, -PetscRealPart(fa[in[k] - rstart]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rmax, 1, MPIU_REAL, MPIU_MAX, comm));
  /* force scale of the normalized residuals: the largest reaction, but at least the nodal force of a
   * 1e-3 strain on the contact layer, so that solver noise on a free boundary is not normalized by itself */
  fscale = PetscMax(rmax, 1e-3 * ct->material->E_max * PetscPowReal(ct->h_c, dim - 1));
  for (PetscInt k = 0; k < nc; ++k) {
    const PetscInt  i = in[k] - rstart;
    const PetscReal *F = &ct->node_frame[9 * k];
    const PetscBool corner = (PetscBool)(ct->fc_obstacle && ct->fc_obstacle[k] >= 0);
    PetscReal       res, f1[MM_MAX_DIM] = {0, 0, 0}, r1[MM_MAX_DIM] = {0, 0, 0}, r2[MM_MAX_DIM];
    RowState        rs;
    PetscBool       active;

    /* a friction corner's own obstacle's force: the node's, without the second's (corners.c) */
    for (PetscInt d = 0; d < nr; ++d) f1[d] = PetscRealPart(fa[i + d]);
    if (corner) {
      PetscScalar fs[MM_MAX_DIM] = {0, 0, 0};
      for (PetscInt d = 0; d < nr; ++d) fs[d] = -fa[i + d];
      MMContactCornerSplit(ct, nr, k, fs, r1, r2);
      for (PetscInt d = 0; d < nr; ++d) f1[d] = -r1[d];
    }
    PetscCall(PetscMemzero(&rs, sizeof(rs)));
    rs.un       = PetscRealPart(wa[i]);
    rs.g        = PetscRealPart(ga[k]);
    rs.r        = -f1[0];
    rs.mu       = PetscRealPart(mua[k]);
    rs.friction = (PetscBool)(nr > 1);
    for (PetscInt d = 1; d < nr; ++d) {
      /* slip is relative to the obstacle: its velocity V.tau_d is 2 slide_ref / dt */
      rs.vt[d] = PetscRealPart(va[i + d]) - (dt > 0 ? 2 * ct->slide_ref[k * (dim - 1) + d - 1] / dt : 0);
      rs.ft[d] = f1[d];
      if (dim == 2) sums[d] += f1[d];
      else
        for (PetscInt c = 0; c < dim; ++c) sums[1 + c] += f1[d] * F[3 * d + c];
    }
    /* the force on the obstacle: minus the reaction on the body, back to Cartesian */
    for (PetscInt d = 0; d < nr; ++d)
      for (PetscInt c = 0; c < dim; ++c) fob[MM_MAX_DIM * ct->obstacle[k] + c] -= f1[d] * (d ? F[3 * d + c] : MMContactRowNormal(ct, k)[c]);
    sums[0] += rs.r;
    /* the VI's own stick/slip split: a tangential reaction inside its bound sticks (RSLS holds a
     * variable within 1e-8, absolute, of its bound as active, hence the relative margin) */
    if (nr > 1) {
      PetscReal rt = 0, rsplit[MM_MAX_DIM], r2s[MM_MAX_DIM];
      MMContactCornerSplit(ct, nr, k, &ra[k * nr], rsplit, r2s);
      for (PetscInt d = 1; d < nr; ++d) rt += PetscSqr(rsplit[d]);
      rt = PetscSqrtReal(rt);
      /* 3D: on the disk's rim, a slipping node whose reaction reached its threshold, or no
       * threshold; 2D: a zero threshold is a bound too (a node touching without force slides freely) */
      rs.at_bound = (PetscBool)((nr == 2 || ct->slipping[k] || PetscRealPart(rh[k * nr + 1]) == 0) && rt >= PetscRealPart(rh[k * nr + 1]) - PetscMax(1e-6 * PetscRealPart(rh[k * nr + 1]), 2e-8));
    }
    res    = RowResidual(&rs, dim, ct->h_c, dt, fscale, vtol, cnt);
    active = (PetscBool)(rs.g - rs.un <= 1e-10 * ct->h_c);
    if (corner) {
      RowState rs2;
      PetscReal res2;
      SecondObstacleRow(ct, k, &wa[i], &va[i], sga ? &sga[i] : NULL, fob, &rs2);
      res2 = RowResidual(&rs2, dim, ct->h_c, dt, fscale, vtol, cnt); /* once: it counts (PetscMax evaluates twice) */
      res  = PetscMax(res, res2);
      sums[0] += rs2.r;
      loc[1] = PetscMax(loc[1], rs2.un - rs2.g);
    }
    if (record_switches) {
      cnt[1] += (active != ct->was_active[k]);
      ct->was_active[k] = active;
    }
    loc[0] = PetscMax(loc[0], res);
    loc[1] = PetscMax(loc[1], rs.un - rs.g);
    /* a pair's slave node: its w are relative displacements (it is on no rigid obstacle's surface) */
    if (ct->frames.follow && ct->obstacle[k] < ct->pb.n_rigid && !ct->second[k]) {
      /* frames that follow: the true geometry, g_b(X + u), each node's own obstacle and the others */
      PetscReal own, others;
      PetscCall(MMContactFramesPenetration(ct, k, t, &wa[i], &own, &others));
      loc[2] = PetscMax(loc[2], others);
      loc[3] = PetscMax(loc[3], own);
    } else if (ct->all_gap0 && ct->obstacle[k] < ct->pb.n_rigid && !ct->second[k]) loc[2] = PetscMax(loc[2], OtherObstaclesPenetration(ct, k, &wa[i], cob));
    if (record_switches && active && rs.r > 0) {
      PetscReal g;
      PetscCall(MMContactFramesSlid(ct, k, t, &wa[i], &g));
      if (PetscAbsReal(g) > slid.value) {
        slid.value = (double)PetscAbsReal(g);
        slid_ob    = ct->obstacle[k];
      }
    }
  }
  if (record_switches) {
    /* the farthest held row over the ranks, and its obstacle */
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &slid, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
    {
      PetscInt b = slid_ob;
      PetscCallMPI(MPI_Bcast(&b, 1, MPIU_INT, slid.rank, comm));
      ct->slid[0] = slid.value;
      ct->slid[1] = (PetscReal)b;
    }
  }
  if (nr > 1) {
    PetscCall(VecRestoreArrayRead(ct->rho, &ra));
    PetscCall(VecRestoreArrayRead(ct->rho_hi, &rh));
  }
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  if (sigma2) PetscCall(VecRestoreArrayRead(sigma2, &sga));
  PetscCall(VecDestroy(&sigma2));
  PetscCall(VecRestoreArrayRead(ct->mu, &mua));
  /* the obstacle forces are recorded for accepted steps only: no reduction inside the friction loop */
  if (record_switches) PetscCall(MPIU_Allreduce(fob, ct->force_obstacle, MM_MAX_DIM * nob, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(PetscFree(fob));
  PetscCall(PetscFree(cob));
  PetscCall(VecRestoreArrayRead(sigma, &va));
  PetscCall(VecRestoreArrayRead(react, &fa));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 4, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 1 + MM_MAX_DIM, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, loc, 4, MPIU_REAL, MPIU_MAX, comm));
  st->active          = cnt[0];
  st->switched        = cnt[1];
  st->slipping        = cnt[2];
  st->sticking        = cnt[3];
  st->force_normal    = sums[0];
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) st->force_t[d] = sums[1 + d];
  st->coulomb         = PetscMax(loc[0], 0.0);
  st->max_penetration  = PetscMax(PetscMax(PetscMax(loc[1], loc[2]), loc[3]), 0.0);
  st->penetration_free = PetscMax(loc[2], 0.0);
  st->penetration_bound = PetscMax(PetscMax(loc[1], loc[2]), 0.0);
  PetscFunctionReturn(0);
}

/*@
  MMContactCoulomb - Computes the discrete Coulomb residual of a state and its slipping and sticking
  counts

  Collective

  Input Parameters:
+ ct    - the contact object
. t     - the state's time
. w     - the displacement (w-frame)
. react - the contact force
- sigma - the slip velocity

  Output Parameters:
+ residual - the discrete Coulomb residual
. nslip    - the slipping rows
- nstick   - the sticking rows

  Note:
  The discrete Coulomb residual (docs/method.md section 6) of a state, and its slipping/sticking counts.

  Level: intermediate

.seealso: `MMContactDiagnostics()`, `MMContactAudit()`
@*/
PetscErrorCode MMContactCoulomb(MMContact ct, PetscReal t, Vec w, Vec react, Vec sigma, PetscReal *residual, PetscInt *nslip, PetscInt *nstick)
{
  ContactStats st;

  PetscFunctionBeginUser;
  PetscCall(ContactStatistics(ct, t, w, react, sigma, PETSC_FALSE, &st));
  *residual = st.coulomb;
  *nslip    = st.slipping;
  *nstick   = st.sticking;
  PetscFunctionReturn(0);
}

/*@
  MMContactDiagnostics - Computes the contact quantities of an accepted state for the history

  Collective

  Input Parameters:
+ ct    - the contact object
. t     - the state's time
. w     - the displacement (w-frame)
. react - the contact force
- v     - the velocity

  Output Parameter:
. h - the contact quantities

  Note:
  Per-step contact quantities (docs/method.md sections 5-6) of the accepted state.

  Level: intermediate

.seealso: `MMContactAudit()`, `MMContactCoulomb()`
@*/
PetscErrorCode MMContactDiagnostics(MMContact ct, PetscReal t, Vec w, Vec react, Vec v, MMContactStats *h)
{
  ContactStats st;

  PetscFunctionBeginUser;
  PetscCall(ContactStatistics(ct, t, w, react, v, PETSC_TRUE, &st));
  h->active           = st.active;
  h->switched         = st.switched;
  h->slipping         = st.slipping;
  h->force_normal     = st.force_normal;
  h->force_tangential = ct->dim == 2 ? st.force_t[0] : PetscSqrtReal(PetscSqr(st.force_t[0]) + PetscSqr(st.force_t[1]) + PetscSqr(st.force_t[2]));
  h->max_penetration  = st.max_penetration;
  h->coulomb_residual = st.coulomb;
  ct->penetration_free = st.penetration_free;
  ct->penetration_bound = st.penetration_bound;
  h->vi_its           = ct->vi_its;
  PetscCall(MMContactGetCandidateCounts(ct, &h->candidates, &h->resolves)); /* resolves: over the run so far */
  PetscFunctionReturn(0);
}

/*@
  MMContactBoundaryFields - Computes the contact fields of a snapshot: the nodal pressure, the gap,
  the tangential traction and the slip velocity

  Collective

  Input Parameters:
+ ct     - the contact object
. u      - the displacement (w-frame)
. v      - the velocity
. react  - the contact force
- dm_out - the output's Cartesian DM

  Output Parameters:
+ pressure   - the nodal pressure (scalar vertex vector)
. gap        - the current gap (scalar vertex vector)
. traction_t - the tangential traction (on dm_out)
- slip       - the slip velocity (on dm_out)

  Note:
  The contact fields of the output, zero off the contact boundary: nodal pressure r_i / int phi_i and
  current gap g_i - u.nu (scalars), tangential traction and slip velocity (Cartesian vectors on dm_out,
  the frame's tangential components mapped back).

  Level: intermediate

.seealso: `MMContactObstacleField()`
@*/
PetscErrorCode MMContactBoundaryFields(MMContact ct, Vec u, Vec v, Vec react, DM dm_out, Vec pressure, Vec gap, Vec traction_t, Vec slip)
{
  const PetscInt     dim = ct->dim;
  Vec                out[] = {pressure, gap, traction_t, slip};
  const PetscInt    *in;
  const PetscScalar *wa, *fa, *va, *ga, *aa;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  for (size_t i = 0; i < sizeof(out) / sizeof(out[0]); ++i) PetscCall(VecZeroEntries(out[i]));
  if (ct->enabled) {
    PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
    PetscCall(ISGetIndices(ct->is_normal, &in));
    PetscCall(VecGetArrayRead(u, &wa));
    PetscCall(VecGetArrayRead(react, &fa));
    PetscCall(VecGetArrayRead(v, &va));
    PetscCall(VecGetArrayRead(ct->gap, &ga));
    PetscCall(VecGetArrayRead(ct->area, &aa));
    for (PetscInt k = 0; k < ct->n_local; ++k) {
      const PetscInt i = in[k] - rstart;
      PetscInt       start, end;
      PetscScalar    tc[MM_MAX_DIM] = {0, 0, 0}, sc[MM_MAX_DIM] = {0, 0, 0}, f1[MM_MAX_DIM] = {0, 0, 0};
      PetscReal      r1[MM_MAX_DIM], r2[MM_MAX_DIM];

      /* a corner's two rows add their pressures; its gap, traction and slip are its first row's (a
       * friction corner: its first obstacle's share of the force, corners.c) */
      for (PetscInt d = 0; d < dim; ++d) f1[d] = -fa[i + d];
      MMContactCornerSplit(ct, dim, k, f1, r1, r2);
      for (PetscInt d = 0; d < dim; ++d) f1[d] = ct->ncomp > 1 ? -r1[d] : fa[i + d];
      PetscCall(VecSetValue(pressure, ct->scalar_index[k], (-f1[0] + r2[0]) / aa[k], ADD_VALUES));
      if (ct->second[k]) continue;
      PetscCall(VecSetValue(gap, ct->scalar_index[k], ga[k] - wa[i], INSERT_VALUES));
      for (PetscInt d = 1; d < dim; ++d)
        for (PetscInt c = 0; c < dim; ++c) {
          const PetscReal Vt = ct->Kt_dt > 0 ? 2 * ct->slide_ref[k * (dim - 1) + d - 1] / ct->Kt_dt : 0;
          tc[c] += f1[d] * ct->node_frame[9 * k + 3 * d + c] / aa[k];
          sc[c] += (va[i + d] - Vt) * ct->node_frame[9 * k + 3 * d + c];
        }
      PetscCall(DMPlexGetPointGlobal(dm_out, ct->vertex[k], &start, &end));
      for (PetscInt c = 0; c < dim; ++c) {
        PetscCall(VecSetValue(traction_t, start + c, tc[c], INSERT_VALUES));
        PetscCall(VecSetValue(slip, start + c, sc[c], INSERT_VALUES));
      }
    }
    PetscCall(VecRestoreArrayRead(ct->area, &aa));
    PetscCall(VecRestoreArrayRead(ct->gap, &ga));
    PetscCall(VecRestoreArrayRead(v, &va));
    PetscCall(VecRestoreArrayRead(react, &fa));
    PetscCall(VecRestoreArrayRead(u, &wa));
    PetscCall(ISRestoreIndices(ct->is_normal, &in));
  }
  for (size_t i = 0; i < sizeof(out) / sizeof(out[0]); ++i) {
    PetscCall(VecAssemblyBegin(out[i]));
    PetscCall(VecAssemblyEnd(out[i]));
  }
  PetscFunctionReturn(0);
}


/*@
  MMContactObstacleField - Sets the output field of each contact node's obstacle

  Collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. field - the obstacle's index per vertex, -1 off the contact boundary

  Note:
  The output field of each contact node's obstacle (its index in -obstacles), -1 off the contact
  boundary.

  Level: intermediate

.seealso: `MMContactBoundaryFields()`
@*/
PetscErrorCode MMContactObstacleField(MMContact ct, Vec field)
{

  PetscFunctionBeginUser;
  PetscCall(VecSet(field, -1.0));
  if (ct->enabled)
    for (PetscInt k = 0; k < ct->n_local; ++k) PetscCall(VecSetValue(field, ct->scalar_index[k], (PetscScalar)ct->obstacle[k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(field));
  PetscCall(VecAssemblyEnd(field));
  PetscFunctionReturn(0);
}

/*@
  MMContactAudit - Audits an accepted step: stops the run when a node lies inside an obstacle or the
  Coulomb residual exceeds its tolerance

  Collective

  Input Parameters:
+ ct   - the contact object
. step - the step's number
. t    - its time
- h    - its contact quantities (MMContactDiagnostics())

  Note:
  The contact audit of an accepted step, like the energy audit: a node inside an obstacle, or a
  Coulomb residual (docs/method.md section 6) past its tolerance, stops the run (exit 65) before
  the step is written. The contact solves hold both to round-off; a run that breaks them is
  wrong, usually from values the arithmetic cannot carry (-E 1e-30 on D1 crosses the plane by a
  third of h_c' with an exact energy balance), and its history would say so only to a reader.

  Level: intermediate

.seealso: `MMContactDiagnostics()`
@*/
PetscErrorCode MMContactAudit(MMContact ct, PetscInt step, PetscReal t, const MMContactStats *h)
{
  MPI_Comm         comm = PetscObjectComm((PetscObject)ct->dm);
  const char      *advice = "The usual cause is inconsistent units (SI throughout: the mesh in metres, -E in Pa, -rho in kg/m^3, loads in N/m^2 and m/s^2) or material values far from what was meant";

  PetscFunctionBeginUser;
  if (!ct->enabled) PetscFunctionReturn(0);
  /* a node tied to one obstacle may cross another it has no row for: say so, not the units */
  PetscCheck(ct->penetration_free <= ct->opt.audit_penetration_tol * ct->h_c, comm, MM_ERR_PHYSICS,
             "Contact audit failed at step %" PetscInt_FMT " (t = %.6g): a contact node is %.3g inside an obstacle it has no contact row for, %.3g h_c', above -audit_penetration_tol %.6g. Each contact node is constrained against its nearest obstacle at t = 0, and against a second one only when that one is within h_c' of it and the run is frictionless (README \"Several, curved and moving obstacles\"): this node met an obstacle it has no row for (a corner with friction, or an obstacle it was not near at t = 0). The output up to the previous step is intact",
             step, (double)t, (double)ct->penetration_free, (double)(ct->penetration_free / ct->h_c), (double)ct->opt.audit_penetration_tol);
  /* frames that follow: the history's penetration includes the true geometry's, which the bound
   * linearized at the step's start leaves at O((v dt)^2 / R) (docs/method.md section 8); the solve is
   * audited on the bound itself */
  {
    const PetscReal depth = ct->frames.follow ? ct->penetration_bound : h->max_penetration;
    PetscCheck(depth <= ct->opt.audit_penetration_tol * ct->h_c, comm, MM_ERR_PHYSICS,
               "Contact audit failed at step %" PetscInt_FMT " (t = %.6g): a contact node is %.3g inside an obstacle, %.3g h_c', above -audit_penetration_tol %.6g (-E %.6g, -rho %.6g). %s. The output up to the previous step is intact",
               step, (double)t, (double)depth, (double)(depth / ct->h_c), (double)ct->opt.audit_penetration_tol, (double)ct->pb.E, (double)ct->pb.rho, advice);
  }
  if (!ct->slid_warned && ct->slid[0] > 0.1 * ct->h_c) {
    ct->slid_warned = PETSC_TRUE;
    PetscCall(PetscPrintf(comm, "mmcontact warning: at step %" PetscInt_FMT " (t = %g) a contact node held by its bound is %.3g (%.3g h_c') off the true surface of obstacle %s: with fixed frames (-contact_frames fixed, the linear law's small-sliding setting) its bound is the tangent plane at its reference contact point, and it has slid away from that point. With -elasticity svk or neohookean the frames follow the contact point (README \"Several, curved and moving obstacles\") (warned once)\n", step, (double)t, (double)ct->slid[0], (double)(ct->slid[0] / ct->h_c), ct->pb.obstacles[(PetscInt)ct->slid[1]].name));
  }
  PetscCheck(h->coulomb_residual <= ct->opt.audit_coulomb_tol, comm, MM_ERR_PHYSICS,
             "Contact audit failed at step %" PetscInt_FMT " (t = %.6g): the discrete Coulomb residual (history column coulomb_residual) is %.3g, above -audit_coulomb_tol %.6g (-E %.6g, -rho %.6g). %s. The output up to the previous step is intact",
             step, (double)t, (double)h->coulomb_residual, (double)ct->opt.audit_coulomb_tol, (double)ct->pb.E, (double)ct->pb.rho, advice);
  PetscFunctionReturn(0);
}
