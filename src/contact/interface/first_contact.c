/* The first-contact estimate of the data check (-check_input, src/app/datacheck.c): when the first
 * contact row would close if every node kept its initial velocity and acceleration. It is an
 * estimate, cheap by design: one pass over the rows, no step taken.
 *
 * Row k constrains w_k <= g_k(t) (w in the w-frame of docs/method.md sections 3 and 11: the node's
 * displacement along its obstacle's normal nu_k, or a slave node's relative displacement along its
 * master facet's normal), with g_k(t) = g_k(0) + c(t).nu_k for an obstacle translated by c(t)
 * (MMContactSetTime). With w_k(t) = w + v tau + a tau^2 / 2 (tau = t - t0), the row's gap
 *   h(t) = g_k(t) - w_k(t)
 * is a quadratic in t on each piece where the obstacle's velocity is constant (before -start, between
 * -start and -stop, after -stop): its first zero is the row's first contact. */
#include "../contactimpl.h"
#include "obstacle.h"

/* The smallest tau in [0, len] with A + B tau + C tau^2 <= 0, given A > 0; -1 if none. The roots
 * without cancellation: q = -(B + sign(B) sqrt(B^2 - 4 A C)) / 2, roots q / C and A / q. */
static PetscReal FirstZero(PetscReal A, PetscReal B, PetscReal C, PetscReal len)
{
  PetscReal best = -1;

  if (C == 0) {
    if (B < 0) best = -A / B;
  } else {
    const PetscReal disc = B * B - 4 * A * C;
    if (disc >= 0) {
      const PetscReal q    = -0.5 * (B + (B >= 0 ? 1 : -1) * PetscSqrtReal(disc));
      const PetscReal r[2] = {q != 0 ? q / C : -1, q != 0 ? A / q : -1};
      for (PetscInt i = 0; i < 2; ++i)
        if (r[i] >= 0 && (best < 0 || r[i] < best)) best = r[i];
    }
  }
  return best >= 0 && best <= len ? best : -1;
}

/* The normal component of obstacle b's translation, c(t).nu, and its velocity on (t, t+): the
 * obstacle moves at -obstacle_NAME_velocity between its -start and -stop (src/obstacle/). */
static void ObstacleNormalMotion(const MMObstacle *ob, PetscInt dim, const PetscReal nu[], PetscReal t, PetscReal *cn, PetscReal *vn)
{
  PetscReal c[MM_MAX_DIM] = {0, 0, 0};

  MMObstacleDisplacement(ob, dim, t, c);
  *cn = *vn = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    *cn += c[d] * nu[d];
    if (t >= ob->start && t < ob->stop) *vn += ob->velocity[d] * nu[d];
  }
}

/* Row k's first contact in (t0, t_end]: the time, or PETSC_MAX_REAL if it stays open. The pieces
 * are cut at the obstacle's -start and -stop. */
static PetscReal RowFirstContact(const MMObstacle *ob, PetscInt dim, const PetscReal nu[], PetscReal g0, PetscReal w, PetscReal v, PetscReal a, PetscReal t0, PetscReal t_end)
{
  PetscReal cut[4] = {t0, t_end, t_end, t_end};
  PetscInt  ncut = 1;

  if (ob->start > t0 && ob->start < t_end) cut[ncut++] = ob->start;
  if (ob->stop > t0 && ob->stop < t_end && ob->stop > ob->start) cut[ncut++] = ob->stop;
  cut[ncut++] = t_end;
  for (PetscInt i = 0; i + 1 < ncut; ++i) {
    const PetscReal lo = cut[i], hi = cut[i + 1], tau = lo - t0;
    PetscReal       cn, vn, A, B, C, z;

    ObstacleNormalMotion(ob, dim, nu, lo, &cn, &vn);
    A = g0 + cn - (w + v * tau + 0.5 * a * tau * tau);
    B = vn - (v + a * tau);
    C = -0.5 * a;
    if (A <= 0) return lo;
    z = FirstZero(A, B, C, hi - lo);
    if (z >= 0) return lo + z;
  }
  return PETSC_MAX_REAL;
}

/*@
  MMContactFirstContact - Estimates for the data check the earliest time a contact row closes, and
  the rows touching at the start

  Collective

  Input Parameters:
+ ct    - the contact object
. u     - the displacement (w-frame)
. v     - the velocity
. a     - the acceleration
. t0    - the start time
- t_end - the end time

  Output Parameter:
. fc - the estimate

  Note:
  The earliest row to close, over all ranks, from the state (u, v, a) at t0 (w-frame vectors); rows
  closed at t0 already (within 1e-12 h_c') are counted apart, as touching.

  Level: intermediate

.seealso: `MMContactObstacleGaps()`
@*/
PetscErrorCode MMContactFirstContact(MMContact ct, Vec u, Vec v, Vec a, PetscReal t0, PetscReal t_end, MMFirstContact *fc)
{
  const PetscInt     dim = ct->dim;
  const PetscScalar *ua, *va, *aa, *ga;
  const PetscInt    *in;
  PetscInt           rstart, first = -1;
  PetscMPIInt        rank;
  MPI_Comm           comm = PetscObjectComm((PetscObject)ct->dm);
  struct {
    double t;
    int    rank;
  } loc = {PETSC_MAX_REAL, 0}, glob;
  PetscReal info[3 + MM_MAX_DIM + 1] = {0}; /* gap, approach speed and acceleration, the node's position, its obstacle */

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(fc, sizeof(*fc)));
  fc->t        = PETSC_MAX_REAL;
  fc->obstacle = -1;
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  loc.rank = rank;
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(v, &va));
  PetscCall(VecGetArrayRead(a, &aa));
  PetscCall(VecGetArrayRead(ct->gap0, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const MMObstacle *ob = &ct->pb.obstacles[ct->obstacle[k]];
    const PetscReal  *nu = &ct->node_frame[9 * k];
    const PetscInt    i  = in[k] - rstart;
    PetscReal         cn, vn, t;

    ObstacleNormalMotion(ob, dim, nu, t0, &cn, &vn);
    if (PetscRealPart(ga[k]) + cn - PetscRealPart(ua[i]) <= 1e-12 * ct->h_c) {
      ++fc->touching;
      continue;
    }
    t = RowFirstContact(ob, dim, nu, PetscRealPart(ga[k]), PetscRealPart(ua[i]), PetscRealPart(va[i]), PetscRealPart(aa[i]), t0, t_end);
    if (t < loc.t) {
      loc.t = t;
      first = k;
    }
  }
  if (first >= 0) {
    const PetscInt     i = in[first] - rstart;
    PetscSection       cs;
    Vec                X;
    PetscInt           off;
    const PetscScalar *xa;
    PetscReal          cn, vn;

    ObstacleNormalMotion(&ct->pb.obstacles[ct->obstacle[first]], dim, &ct->node_frame[9 * first], t0, &cn, &vn);
    info[0] = PetscRealPart(ga[first]) + cn - PetscRealPart(ua[i]);
    info[1] = PetscRealPart(va[i]) - vn;
    info[2] = PetscRealPart(aa[i]);
    PetscCall(DMGetCoordinateSection(ct->dm, &cs));
    PetscCall(DMGetCoordinatesLocal(ct->dm, &X));
    PetscCall(PetscSectionGetOffset(cs, ct->vertex[first], &off));
    PetscCall(VecGetArrayRead(X, &xa));
    for (PetscInt d = 0; d < dim; ++d) info[3 + d] = PetscRealPart(xa[off + d]);
    PetscCall(VecRestoreArrayRead(X, &xa));
    info[3 + MM_MAX_DIM] = (PetscReal)ct->obstacle[first];
  }
  PetscCall(VecRestoreArrayRead(ct->gap0, &ga));
  PetscCall(VecRestoreArrayRead(a, &aa));
  PetscCall(VecRestoreArrayRead(v, &va));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fc->touching, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm));
  if (glob.t >= PETSC_MAX_REAL) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(info, (PetscMPIInt)PETSC_STATIC_ARRAY_LENGTH(info), MPIU_REAL, glob.rank, comm));
  fc->t        = glob.t;
  fc->gap      = info[0];
  fc->speed    = info[1];
  fc->accel    = info[2];
  fc->obstacle = (PetscInt)info[3 + MM_MAX_DIM];
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) fc->x[d] = info[3 + d];
  PetscFunctionReturn(0);
}

/*@
  MMContactObstacleGaps - Gives per obstacle its contact nodes and the smallest gap of its rows at
  t0, with that row's node

  Collective

  Input Parameters:
+ ct - the contact object
. u  - the displacement (w-frame)
- t0 - the time

  Output Parameters:
+ count - per obstacle, its contact nodes
. gap   - per obstacle, the smallest gap, PETSC_MAX_REAL without rows
- x     - per obstacle, that row's node (reference position, MM_MAX_DIM entries)

  Note:
  Per obstacle (rigid ones, then the pairs): the contact nodes constrained against it (their first
  row, as the contact_obstacle field has them) and the smallest gap of its rows at t0, g_k(t0) - w_k,
  with that row's node (reference position; the first of equal gaps on the lowest rank). Arrays of
  n_obstacles entries, x of MM_MAX_DIM each; a gap is PETSC_MAX_REAL for an obstacle without rows.

  Level: intermediate

.seealso: `MMContactFirstContact()`
@*/
PetscErrorCode MMContactObstacleGaps(MMContact ct, Vec u, PetscReal t0, PetscInt count[], PetscReal gap[], PetscReal x[])
{
  const PetscInt     dim = ct->dim, nob = ct->pb.n_obstacles;
  const PetscScalar *ua, *ga, *xa;
  const PetscInt    *in;
  PetscInt           rstart, *best;
  PetscMPIInt        rank;
  PetscSection       cs;
  Vec                X;
  MPI_Comm           comm = PetscObjectComm((PetscObject)ct->dm);
  struct {
    double g;
    int    rank;
  } *loc, *glob;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(count, nob));
  PetscCall(PetscArrayzero(x, MM_MAX_DIM * nob));
  for (PetscInt b = 0; b < nob; ++b) gap[b] = PETSC_MAX_REAL;
  if (!ct->enabled || !nob) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMalloc3(nob, &loc, nob, &glob, nob, &best));
  for (PetscInt b = 0; b < nob; ++b) {
    loc[b].g    = PETSC_MAX_REAL;
    loc[b].rank = rank;
    best[b]     = -1;
  }
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(ct->gap0, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt b = ct->obstacle[k];
    PetscReal      cn, vn, g;

    ObstacleNormalMotion(&ct->pb.obstacles[b], dim, &ct->node_frame[9 * k], t0, &cn, &vn);
    g = PetscRealPart(ga[k]) + cn - PetscRealPart(ua[in[k] - rstart]);
    if (!ct->second[k]) ++count[b];
    if (g < loc[b].g) {
      loc[b].g = g;
      best[b]  = k;
    }
  }
  PetscCall(VecRestoreArrayRead(ct->gap0, &ga));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, nob, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(loc, glob, (PetscMPIInt)nob, MPI_DOUBLE_INT, MPI_MINLOC, comm));
  /* the winner's node: its coordinates, zeros elsewhere, summed */
  PetscCall(DMGetCoordinateSection(ct->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(ct->dm, &X));
  PetscCall(VecGetArrayRead(X, &xa));
  for (PetscInt b = 0; b < nob; ++b) {
    PetscInt off;
    gap[b] = glob[b].g;
    if (glob[b].rank != rank || best[b] < 0) continue;
    PetscCall(PetscSectionGetOffset(cs, ct->vertex[best[b]], &off));
    for (PetscInt d = 0; d < dim; ++d) x[MM_MAX_DIM * b + d] = PetscRealPart(xa[off + d]);
  }
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, x, MM_MAX_DIM * nob, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(PetscFree3(loc, glob, best));
  PetscFunctionReturn(0);
}
