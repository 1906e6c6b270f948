/* Contact frames that follow the contact point on curved obstacles (-contact_frames follow,
 * docs/method.md section 8, "Frames that follow the contact point").
 *
 * At set-up each contact node gets the frame and the gap of its reference position (set.c). For a
 * plane that bound is exact for any displacement; on a sphere, circle or cylinder it is exact only
 * near the reference contact point. With frames that follow, at the start of each step a node near
 * its curved obstacle whose normal at its current position x = X + u^n has turned by more than
 * -contact_frames_angle takes the frame of x, nu = -n(x), and the gap along it measured from x:
 * w_nu^{n+1} <= g(x) + u^n.nu (exact for motion along nu, the distance being linear along the
 * normal line). Its dofs turn with it: every w-frame quantity x_w = Q^T x_cart becomes R^T x_w,
 * R = Q_old^T Q_new (block diagonal, identity off the turned nodes), every w-frame matrix R^T A R:
 * the Cartesian state, loads and stiffness are unchanged. M* is not a rotation of the old one: its
 * massless dofs now lie along the new normals, so it is rebuilt from the whole mass M (turned) as at
 * set-up (frame/mass_star.c), and K~ with it. */
#include "../contactimpl.h"
#include "fem.h"
#include "obstacle.h"

const char *const MMFramesTypes[] = {"fixed", "follow", "MMFramesType", "MM_FRAMES_", NULL};

/* Whether contact row k's frame may follow its contact point: a single-row node on a curved rigid
 * obstacle (a corner's two rows, a friction corner and a pair's slave node keep theirs). */
static PetscBool RowFollows(MMContact ct, PetscInt k)
{
  if (ct->second[k] || (k + 1 < ct->n_local && ct->second[k + 1])) return PETSC_FALSE;
  if (ct->fc_obstacle && ct->fc_obstacle[k] >= 0) return PETSC_FALSE;
  if (ct->obstacle[k] >= ct->pb.n_rigid) return PETSC_FALSE;
  return ct->pb.obstacles[ct->obstacle[k]].curved;
}

/* -contact_frames resolved (follow by default for the finite-strain laws) and, when the frames
 * follow, each contact row's reference position. Only curved rigid obstacles make it do anything:
 * with planes alone the frames stay fixed, and the run is the one of -contact_frames fixed. */
PetscErrorCode MMContactFramesSetUp(MMContact ct)
{
  MMContactFrames *fr  = &ct->frames;
  const PetscInt   dim = ct->dim;
  PetscBool        follow, curved = PETSC_FALSE;
  DM               dm = ct->dm;
  PetscSection     cs;
  Vec              X;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  follow = ct->opt.frames_set ? (PetscBool)(ct->opt.frames == MM_FRAMES_FOLLOW) : ct->material->finite;
  PetscCheck(!(ct->opt.frames_set && follow) || ct->material->finite, ct->comm, PETSC_ERR_SUP, "-contact_frames follow needs a finite-strain law (-elasticity svk or neohookean): the linear model's step uses the acceleration of the last step in its frame, which a turned frame would not balance. Use -contact_frames fixed with -elasticity linear");
  for (PetscInt b = 0; b < ct->pb.n_rigid; ++b) curved = (PetscBool)(curved || ct->pb.obstacles[b].curved);
  fr->angle  = ct->opt.frames_angle;
  fr->depth  = -1;
  for (PetscInt b = 0; b < ct->pb.n_rigid; ++b)
    if (ct->pb.obstacles[b].faceted) fr->depth = 1e-12; /* a facet's edge is crossed in one step: docs/method.md section 8 */
  if (ct->opt.frames_depth != PETSC_DEFAULT) fr->depth = ct->opt.frames_depth;
  fr->follow = (PetscBool)(follow && curved && ct->enabled);
  if (!curved || !ct->enabled) PetscFunctionReturn(0);
  PetscCheck(!fr->follow || ct->pb.n_obstacles == ct->pb.n_rigid, ct->comm, PETSC_ERR_SUP, "-contact_frames follow (the default with -elasticity svk and neohookean on curved obstacles) does not take contact pairs (-contact_pairs) yet: their transform N would have to be rebuilt with M*. Use -contact_frames fixed");
  /* the reference positions: frames that follow measure from them, and fixed frames on a curved
   * obstacle are audited on the true surface with them (MMContactFramesSlid) */
  PetscCall(PetscCalloc3((size_t)MM_MAX_DIM * ct->n_local + 1, &fr->X, 9 * (size_t)ct->n_local + 1, &fr->F_new, ct->n_local + 1, &fr->turn));
  PetscCall(PetscCalloc2(ct->n_local + 1, &fr->refined, (MM_MAX_DIM + 1) * (size_t)ct->n_local + 1, &fr->prev));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    PetscInt xoff;
    PetscCall(PetscSectionGetOffset(cs, ct->vertex[k], &xoff));
    for (PetscInt d = 0; d < dim; ++d) fr->X[MM_MAX_DIM * k + d] = PetscRealPart(x[xoff + d]);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactFramesDestroy(MMContactFrames *fr)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&fr->M));
  PetscCall(MatDestroy(&fr->R));
  PetscCall(PetscFree3(fr->X, fr->F_new, fr->turn));
  PetscCall(PetscFree2(fr->refined, fr->prev));
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesFollow - Tells whether the contact frames follow the contact point

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. follow - PETSC_TRUE with -contact_frames follow

  Level: intermediate

.seealso: `MMContactFramesUpdate()`
@*/
PetscErrorCode MMContactFramesFollow(MMContact ct, PetscBool *follow)
{
  PetscFunctionBeginUser;
  *follow = ct->frames.follow;
  PetscFunctionReturn(0);
}

/* Row k's Cartesian displacement from its frame components w (a single-row node: u = F^T w). */
static void RowCartesian(MMContact ct, PetscInt k, const PetscScalar w[], PetscReal u[])
{
  const PetscReal *F = &ct->node_frame[9 * k];

  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) u[d] = 0;
  for (PetscInt e = 0; e < ct->dim; ++e)
    for (PetscInt d = 0; d < ct->dim; ++d) u[d] += PetscRealPart(w[e]) * F[3 * e + d];
}

/* Row k's signed distance g and obstacle normal n at its current position X + u, the obstacle where
 * it is at time t (translated by c(t)), and c(t). */
static PetscErrorCode RowDistance(MMContact ct, PetscInt k, PetscInt b, PetscReal t, const PetscReal u[], PetscReal *g, PetscReal n[], PetscReal c[])
{
  const PetscInt    dim = ct->dim;
  const MMObstacle *ob  = &ct->pb.obstacles[b];
  PetscReal         x[MM_MAX_DIM] = {0, 0, 0};

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) c[d] = n[d] = 0;
  MMObstacleDisplacement(ob, dim, t, c);
  for (PetscInt d = 0; d < dim; ++d) x[d] = ct->frames.X[MM_MAX_DIM * k + d] + u[d] - c[d];
  PetscCall(MMObstacleDistance(ob, dim, x, g, n));
  PetscFunctionReturn(0);
}

/* The depth of contact row k inside the obstacles, on their true geometry at time t: -g_b(X + u) for
 * its own obstacle (own) and the deepest of the others (others; PETSC_MIN_REAL if none), w its frame
 * components; the history's penetration with frames that follow (docs/method.md section 8). */
PetscErrorCode MMContactFramesPenetration(MMContact ct, PetscInt k, PetscReal t, const PetscScalar w[], PetscReal *own, PetscReal *others)
{
  PetscReal u[MM_MAX_DIM];

  PetscFunctionBeginUser;
  *own = *others = PETSC_MIN_REAL;
  RowCartesian(ct, k, w, u);
  for (PetscInt b = 0; b < ct->pb.n_rigid; ++b) {
    PetscReal g, n[MM_MAX_DIM], c[MM_MAX_DIM];
    PetscCall(RowDistance(ct, k, b, t, u, &g, n, c));
    if (b == ct->obstacle[k]) *own = -g;
    else *others = PetscMax(*others, -g);
  }
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesSlid - With fixed frames, how far a contact row held by its bound is from the true
  surface of its curved obstacle

  Not collective

  Input Parameters:
+ ct - the contact object
. k  - the owned contact row
. t  - the state's time
- w  - the row's frame components

  Output Parameter:
. g - the row's signed distance to its obstacle's true surface at X + u; 0 for a row the check does
      not apply to (frames that follow, a plane, a corner's or a pair's row)

  Note:
  Fixed frames keep each node's bound on the tangent plane of its reference contact point: on a
  curved or meshed obstacle a node that slides away from that point is held off the surface (a bump,
  a step's edge past which the plane goes on) or let into it (a bowl). The audit warns once when a
  held node is farther than 0.1 h_c' either way (MMContactAudit).

  Level: developer

.seealso: `MMContactFramesPenetration()`, `MMContactAudit()`
@*/
PetscErrorCode MMContactFramesSlid(MMContact ct, PetscInt k, PetscReal t, const PetscScalar w[], PetscReal *g)
{
  PetscReal u[MM_MAX_DIM], n[MM_MAX_DIM], c[MM_MAX_DIM];

  PetscFunctionBeginUser;
  *g = 0;
  if (ct->frames.follow || !ct->frames.X || ct->second[k] || (k + 1 < ct->n_local && ct->second[k + 1])) PetscFunctionReturn(0);
  if ((ct->fc_obstacle && ct->fc_obstacle[k] >= 0) || ct->obstacle[k] >= ct->pb.n_rigid || !ct->pb.obstacles[ct->obstacle[k]].curved) PetscFunctionReturn(0);
  RowCartesian(ct, k, w, u);
  PetscCall(RowDistance(ct, k, ct->obstacle[k], t, u, g, n, c));
  PetscFunctionReturn(0);
}

/* Row k turns at this update: its new frame from the obstacle normal n, turned by acos(cosa) from
 * the old, and its bound's gaps g_0 (time 0) and g (now). */
static void TakeFrame(MMContact ct, PetscInt k, const PetscReal n[], PetscReal cosa, PetscScalar g0[], PetscReal g0k, PetscScalar ga[], PetscReal gk)
{
  MMContactFrames *fr = &ct->frames;
  PetscReal        Fn[MM_MAX_DIM][MM_MAX_DIM];

  MMContactFrameFromNormal(ct->dim, n, Fn);
  for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
    for (PetscInt b = 0; b < MM_MAX_DIM; ++b) fr->F_new[9 * k + 3 * a + b] = Fn[a][b];
  fr->angle_max = PetscMax(fr->angle_max, PetscAcosReal(PetscMin(1.0, cosa)));
  fr->turn[k]   = PETSC_TRUE;
  g0[k]         = g0k;
  ga[k]         = gk;
}

/* Which rows turn: a row that follows, whose obstacle normal at its current position has turned by
 * more than -contact_frames_angle from its frame's, and that is near: within h_c' of the obstacle or
 * of the bound it has now (on a convex obstacle, seen from outside, an old tangent plane can cut
 * into the free space: a node far from the obstacle may still be held by its old bound). Farther
 * nodes keep their frames, and the mass they carry, until they come near. Each turning row gets
 * its new frame in F_new and its new gap (g_0 at time 0 and g at time t) in place. */
static PetscErrorCode SelectTurningRows(MMContact ct, Vec u, Vec midpoint, PetscReal t_mid, PetscInt *count)
{
  MMContactFrames   *fr  = &ct->frames;
  const PetscInt     dim = ct->dim;
  const PetscInt    *in;
  const PetscScalar *ua, *ya;
  PetscScalar       *g0, *ga;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  *count = 0;
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(midpoint, &ya));
  PetscCall(VecGetArray(ct->gap0, &g0));
  PetscCall(VecGetArray(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscScalar *w = &ua[in[k] - rstart];
    const PetscReal   *F = &ct->node_frame[9 * k];
    PetscReal          uc[MM_MAX_DIM], n[MM_MAX_DIM], c[MM_MAX_DIM], g, cosa = 0, len = 0, slack, wn = 0, cn = 0, Fn[MM_MAX_DIM][MM_MAX_DIM];

    fr->turn[k] = PETSC_FALSE;
    if (!RowFollows(ct, k)) continue;
    /* at the step's predicted midpoint (the stepper's, u^n + dt/2 v^n): in steady sliding the node
     * then ends on the obstacle's chord, and the contact force does no work (docs/method.md section 8) */
    RowCartesian(ct, k, &ya[in[k] - rstart], uc);
    PetscCall(RowDistance(ct, k, ct->obstacle[k], t_mid, uc, &g, n, c));
    for (PetscInt d = 0; d < dim; ++d) {
      cosa -= n[d] * F[d];
      len += n[d] * n[d];
    }
    if (len < 0.5) continue; /* on a sphere's centre or a cylinder's axis: no normal */
    slack = PetscRealPart(ga[k] - w[0]);
    if (PetscAcosReal(PetscMin(1.0, cosa)) <= fr->angle || PetscMin(g, slack) > ct->h_c) continue;
    ++*count;
    /* the bound linearized at x_m = X + u_m, u_m = u^n + dt/2 v^n, along nu = -n: w_nu <= g(x_m) + u_m.nu,
     * and g(t') = g_0 + c(t').nu as for a moving obstacle (MMContactSetTime) */
    MMContactFrameFromNormal(dim, n, Fn);
    for (PetscInt d = 0; d < dim; ++d) {
      wn += uc[d] * Fn[0][d];
      cn += c[d] * Fn[0][d];
    }
    TakeFrame(ct, k, n, cosa, g0, g + wn - cn, ga, g + wn);
  }
  PetscCall(VecRestoreArray(ct->gap, &ga));
  PetscCall(VecRestoreArray(ct->gap0, &g0));
  PetscCall(VecRestoreArrayRead(midpoint, &ya));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* R = Q_old^T Q_new: at a turning node the block F_old F_new^T (Q's block is F^T), the identity
 * elsewhere, in Q's layout and pattern (frame.c), so that MMRotateP1 takes it as it takes Q. */
static PetscErrorCode BuildRotation(MMContact ct)
{
  MMContactFrames *fr  = &ct->frames;
  const PetscInt   dim = ct->dim;
  const PetscInt  *in;
  PetscInt         n, rstart;
  PetscBool       *block;

  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&fr->R));
  PetscCall(MatGetLocalSize(ct->transform.Q, &n, NULL));
  PetscCall(MatGetOwnershipRange(ct->transform.Q, &rstart, NULL));
  PetscCall(MatCreateAIJ(ct->comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, dim, NULL, 0, NULL, &fr->R));
  PetscCall(PetscCalloc1(n, &block));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal *Fo = &ct->node_frame[9 * k], *Fn = &fr->F_new[9 * k];
    if (ct->second[k] || !fr->turn[k]) continue;
    for (PetscInt a = 0; a < dim; ++a) {
      block[in[k] - rstart + a] = PETSC_TRUE;
      for (PetscInt b = 0; b < dim; ++b) {
        PetscReal r = 0;
        for (PetscInt d = 0; d < dim; ++d) r += Fo[3 * a + d] * Fn[3 * b + d];
        PetscCall(MatSetValue(fr->R, in[k] + a, in[k] + b, r, INSERT_VALUES));
      }
    }
  }
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  for (PetscInt i = 0; i < n; ++i)
    if (!block[i]) PetscCall(MatSetValue(fr->R, rstart + i, rstart + i, 1.0, INSERT_VALUES));
  PetscCall(PetscFree(block));
  PetscCall(MatAssemblyBegin(fr->R, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fr->R, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* x <- R^T x, a w-frame vector of the old frames into the new ones (a force as a displacement: R is
 * orthogonal); the one turn of every held vector (held.c) */
static PetscErrorCode RotateVec(MMContact ct, void *fctx, PetscBool force, Vec x)
{
  Vec y;

  PetscFunctionBeginUser;
  (void)fctx;
  (void)force;
  PetscCall(VecDuplicate(x, &y));
  PetscCall(MatMultTranspose(ct->frames.R, x, y));
  PetscCall(VecCopy(y, x));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

/* The turned rows' new frames into node_frame and Q's blocks (in place: Q keeps its pattern, and
 * whoever reads it through fem's frame ops sees the new one), and the friction warm starts that live in
 * frame components: the condensed reactions and, in 3D, the slip direction. */
static PetscErrorCode SetNewFrames(MMContact ct)
{
  MMContactFrames *fr  = &ct->frames;
  const PetscInt   dim = ct->dim, nr = ct->ncomp;
  const PetscInt  *in;
  PetscScalar     *rho = NULL;

  PetscFunctionBeginUser;
  PetscCall(ISGetIndices(ct->is_normal, &in));
  if (ct->rho && nr > 1) PetscCall(VecGetArray(ct->rho, &rho));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    PetscReal *F = &ct->node_frame[9 * k], *Fn = &fr->F_new[9 * k];
    if (!fr->turn[k]) continue;
    if (rho) {
      PetscReal c[MM_MAX_DIM] = {0, 0, 0};
      for (PetscInt j = 0; j < nr; ++j)
        for (PetscInt d = 0; d < dim; ++d) c[d] += PetscRealPart(rho[k * nr + j]) * F[3 * j + d];
      for (PetscInt j = 0; j < nr; ++j) {
        rho[k * nr + j] = 0;
        for (PetscInt d = 0; d < dim; ++d) rho[k * nr + j] += c[d] * Fn[3 * j + d];
      }
    }
    if (dim == 3 && nr > 1) {
      PetscReal c[3], s[2], len;
      for (PetscInt d = 0; d < 3; ++d) c[d] = ct->slip_dir[2 * k] * F[3 + d] + ct->slip_dir[2 * k + 1] * F[6 + d];
      for (PetscInt j = 0; j < 2; ++j) s[j] = c[0] * Fn[3 * (j + 1)] + c[1] * Fn[3 * (j + 1) + 1] + c[2] * Fn[3 * (j + 1) + 2];
      len = PetscSqrtReal(s[0] * s[0] + s[1] * s[1]);
      for (PetscInt j = 0; j < 2; ++j) ct->slip_dir[2 * k + j] = len > 0 ? s[j] / len : ct->slip_dir[2 * k + j];
    }
    for (PetscInt i = 0; i < 9; ++i) F[i] = Fn[i];
    for (PetscInt d = 0; d < dim; ++d)
      for (PetscInt e = 0; e < dim; ++e) PetscCall(MatSetValue(ct->transform.Q, in[k] + d, in[k] + e, F[3 * e + d], INSERT_VALUES));
  }
  if (rho) PetscCall(VecRestoreArray(ct->rho, &rho));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MatAssemblyBegin(ct->transform.Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->transform.Q, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The selected rows (turn, F_new, their gaps already set) turned: R, contact's w-frame operators K,
 * M, M*, Q and the frames; K~ is rebuilt at the next MMContactSetStepMatrix, the kept one dropped (it
 * is of the old frames). Then every w-frame vector, the load, the lift and the held ones (with the
 * state's: state), and the held matrices, by the one function of held.c. */
static PetscErrorCode TurnSelectedRows(MMContact ct, PetscBool state)
{
  MMContactFrames *fr = &ct->frames;
  MMOperators      op = ct->op;
  MMMassBoundary   mb;
  PetscBool        lumped;

  PetscFunctionBeginUser;
  PetscCall(MMFEIsMassLumped(op, &lumped));
  PetscCall(BuildRotation(ct));
  /* w-frame K and M <- R^T (.) R: a lumped M is m I at each node, which no rotation changes */
  PetscCall(MMRotateP1(fr->R, ct->K, lumped ? NULL : fr->M));
  PetscCall(SetNewFrames(ct));
  MMContactMassBoundary(ct, &mb);
  PetscCall(MMContactMassRebuild(&ct->mass, op, fr->M, ct->material, &mb));
  /* K~ (and its factor, the candidate columns, the PC) of the old frames: rebuilt for any dt */
  ct->Kt_dt   = 0;
  ct->kept.dt = 0;
  PetscCall(MMContactHeldTransform(ct, state, RotateVec, NULL));
  PetscCall(MMContactHeldTurnMatrices(ct, fr->R));
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesUpdate - Turns the frames of the rows near a curved obstacle at a step's start, and
  contact's operators, gaps and held data with them

  Collective

  Input Parameters:
+ ct - the contact object
. u        - the displacement at the step's start (w-frame)
. midpoint - the stepper's predicted displacement at the step's middle (w-frame; u^n + dt/2 v^n for
             the trapezoidal scheme, docs/method.md section 8)
- t_mid    - the time of the step's middle

  Output Parameter:
. turned - how many frames turned (all ranks)

  Note:
  The frames of the rows near a curved obstacle, from where the step's scheme predicts them at its
  middle (contact does not know the scheme: the stepper hands the prediction): the turned rows' frames and gaps, and contact's operators and the held data, the state with
  them, turned (TurnSelectedRows).

  Level: intermediate

.seealso: `MMContactFramesFollow()`, `MMContactFramesAddVec()`, `MMContactFramesRestore()`
@*/
PetscErrorCode MMContactFramesUpdate(MMContact ct, Vec u, Vec midpoint, PetscReal t_mid, PetscInt *turned)
{
  MMContactFrames *fr = &ct->frames;
  PetscInt         count;

  PetscFunctionBeginUser;
  *turned = 0;
  if (!fr->follow) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  for (PetscInt k = 0; k < ct->n_local; ++k) fr->refined[k] = 0; /* a new step */
  PetscCall(SelectTurningRows(ct, u, midpoint, t_mid, &count));
  PetscCall(MPIU_Allreduce(&count, turned, 1, MPIU_INT, MPI_SUM, ct->comm));
  if (*turned) {
    fr->updates++;
    fr->turned += *turned;
    PetscCall(TurnSelectedRows(ct, PETSC_TRUE));
  }
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The rows whose step ended inside their obstacle, deeper than depth h_c' at w (time t): each gets
 * the frame of its end position x_e and the bound linearized there, w_nu <= g(x_e) + u_e.nu, in F_new
 * and its gaps. On a flat facet this bound holds the node on the facet it ended on; a node that
 * crossed an edge within the step had its bound from the facet it left. A row that ends inside again
 * after that sits in a concave crease, where two facets hold it and one bound cannot be exact: it
 * takes once the bound between the two it had, their sum (w.(nu_1 + nu_2) <= g_1 + g_2, normalized),
 * whose plane holds the crease's line, and keeps it for the step (docs/method.md section 8). */
static PetscErrorCode SelectPenetratingRows(MMContact ct, Vec w, PetscReal t, PetscInt *count)
{
  MMContactFrames   *fr  = &ct->frames;
  const PetscInt     dim = ct->dim;
  const PetscInt    *in;
  const PetscScalar *wa;
  PetscScalar       *g0, *ga;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  *count = 0;
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArray(ct->gap0, &g0));
  PetscCall(VecGetArray(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal *F = &ct->node_frame[9 * k];
    PetscReal       *prev = &fr->prev[(MM_MAX_DIM + 1) * k];
    PetscReal        ue[MM_MAX_DIM], n[MM_MAX_DIM], c[MM_MAX_DIM], g, len = 0, cosa = 0, wn = 0, cn = 0, g0new;

    fr->turn[k] = PETSC_FALSE;
    if (!RowFollows(ct, k) || fr->refined[k] > 1) continue;
    RowCartesian(ct, k, &wa[in[k] - rstart], ue);
    PetscCall(RowDistance(ct, k, ct->obstacle[k], t, ue, &g, n, c));
    for (PetscInt d = 0; d < dim; ++d) len += n[d] * n[d];
    if (len < 0.5 || -g <= fr->depth * ct->h_c) continue;
    if (!fr->refined[k]) {
      for (PetscInt d = 0; d < dim; ++d) wn += ue[d] * -n[d];
      g0new = g + wn;
      for (PetscInt d = 0; d < dim; ++d) g0new -= c[d] * -n[d];
    } else {
      /* the crease: nu = (nu_1 + nu_2)/|.|, g_0 = (g_0,1 + g_0,2)/|.| */
      PetscReal s = 0;
      for (PetscInt d = 0; d < dim; ++d) {
        n[d] = -(F[d] + prev[d]);
        s += n[d] * n[d];
      }
      s = PetscSqrtReal(s);
      if (s < 1e-12) continue;
      for (PetscInt d = 0; d < dim; ++d) n[d] /= s;
      g0new = (PetscRealPart(g0[k]) + prev[MM_MAX_DIM]) / s;
    }
    for (PetscInt d = 0; d < dim; ++d) cosa -= n[d] * F[d];
    PetscCall(PetscInfo(NULL, "contact row %" PetscInt_FMT " ended %.3e inside its obstacle; its frame turns by %.3e rad%s\n", k, (double)-g, (double)PetscAcosReal(PetscMin(1.0, cosa)), fr->refined[k] ? ", between its last two bounds (a crease)" : " to where it ended"));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) prev[d] = F[d];
    prev[MM_MAX_DIM] = PetscRealPart(g0[k]);
    fr->refined[k]++;
    ++*count;
    for (PetscInt d = 0; d < dim; ++d) cn += c[d] * -n[d];
    TakeFrame(ct, k, n, cosa, g0, g0new, ga, g0new + cn);
  }
  PetscCall(VecRestoreArray(ct->gap, &ga));
  PetscCall(VecRestoreArray(ct->gap0, &g0));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesRefine - Turns, after a step was solved, the frames of the rows that ended inside
  their obstacle, to the frame and bound of where they ended, so that the step is solved again

  Collective

  Input Parameters:
+ ct - the contact object
. w  - the step's solution (w-frame)
- t  - the step's end time

  Output Parameter:
. turned - how many frames turned (all ranks); 0: the step's end is outside every obstacle to
           -contact_frames_depth, and stands

  Note:
  The midpoint's bound (MMContactFramesUpdate) is exact for motion along its normal; a node that
  crosses a concave edge of a meshed obstacle within the step, or moves far along the inside of a
  curve, ends inside the obstacle by up to its tangential travel times the angle it turned
  (docs/method.md section 8, "Frames at the step's end"). Its frame and bound are then taken where it
  ended, the held state turned with them (the caller solves the step again from its start, which
  has not moved: the state is the step's start until the step is accepted).

  Level: intermediate

.seealso: `MMContactFramesUpdate()`
@*/
PetscErrorCode MMContactFramesRefine(MMContact ct, Vec w, PetscReal t, PetscInt *turned)
{
  MMContactFrames *fr = &ct->frames;
  PetscInt         count;

  PetscFunctionBeginUser;
  *turned = 0;
  if (!fr->follow || fr->depth < 0) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  PetscCall(SelectPenetratingRows(ct, w, t, &count));
  PetscCall(MPIU_Allreduce(&count, turned, 1, MPIU_INT, MPI_SUM, ct->comm));
  if (*turned) {
    fr->resolves++;
    fr->turned += *turned;
    PetscCall(TurnSelectedRows(ct, PETSC_TRUE));
  }
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* ---- Checkpoints (src/io/checkpoint.c, docs/method.md section 9): a following row's frame is a
 * function of its obstacle normal alone (MMContactFrameFromNormal), so its normal nu and its gap
 * g_0 restore it bit for bit, on any partition; the state is kept in these frames. ---- */

/*@
  MMContactFramesGetRecord - Gives a contact row's frame record for a checkpoint: its normal and g_0

  Not collective

  Input Parameters:
+ ct - the contact object
- k  - the owned contact row

  Output Parameters:
+ has - the row follows (else rec is not set)
- rec - its record, MM_CONTACT_FRAME_RECORD reals

  Note:
  Row k's record: nu (MM_MAX_DIM) and g_0; *has: the row follows (the others keep their set-up
  frames, and a run with fixed frames writes no records).

  Level: developer

.seealso: `MMContactFramesRestore()`, `MMContactFramesGetCounters()`
@*/
PetscErrorCode MMContactFramesGetRecord(MMContact ct, PetscInt k, PetscBool *has, PetscScalar rec[])
{
  const PetscScalar *g0;

  PetscFunctionBeginUser;
  *has = (PetscBool)(ct->frames.follow && RowFollows(ct, k));
  if (!*has) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(ct->gap0, &g0));
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) rec[d] = ct->node_frame[9 * k + d];
  rec[MM_MAX_DIM] = g0[k];
  PetscCall(VecRestoreArrayRead(ct->gap0, &g0));
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesGetCounters - Gives the run's frame counters for a checkpoint

  Collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. counters - the updates, the node frames turned and the largest turn (all ranks)

  Note:
  The run's counters for the checkpoint: updates, node frames turned, the largest turn (all ranks)

  Level: developer

.seealso: `MMContactFramesGetRecord()`, `MMContactFramesRestore()`
@*/
PetscErrorCode MMContactFramesGetCounters(MMContact ct, PetscReal counters[3])
{
  const MMContactFrames *fr = &ct->frames;

  PetscFunctionBeginUser;
  counters[0] = (PetscReal)fr->updates;
  counters[1] = (PetscReal)fr->turned;
  PetscCall(MPIU_Allreduce(&fr->angle_max, &counters[2], 1, MPIU_REAL, MPIU_MAX, ct->comm));
  PetscFunctionReturn(0);
}

/*@
  MMContactFramesRestore - Restores the following rows' frames and gaps and the run's frame counters
  from a checkpoint (-restart), and turns contact's operators and the held set-up data with them

  Collective

  Input Parameters:
+ ct       - the contact object, set up
. rec      - the owned rows' records, as MMContactFramesGetRecord() wrote them
- counters - the run's counters, as MMContactFramesGetCounters() gave them

  Output Parameter:
. turned - how many frames turned (all ranks)

  Note:
  -restart of a run whose frames followed: each following row (n_local records, as
  MMContactFramesGetRecord wrote them) takes its checkpointed frame and gap, and contact's operators
  and the held set-up data turn with them, from the set-up frames (TurnSelectedRows); *turned: how
  many turned (all ranks). The state read from the checkpoint is already in these frames: it does
  not turn.

  Level: developer

.seealso: `MMContactFramesGetRecord()`, `MMContactFramesUpdate()`
@*/
PetscErrorCode MMContactFramesRestore(MMContact ct, const PetscScalar rec[], const PetscReal counters[3], PetscInt *turned)
{
  MMContactFrames *fr  = &ct->frames;
  const PetscInt   dim = ct->dim, bs = MM_CONTACT_FRAME_RECORD;
  PetscScalar     *g0, *ga;
  PetscInt         count = 0, bad = 0;

  PetscFunctionBeginUser;
  *turned = 0;
  if (!fr->follow) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  PetscCall(VecGetArray(ct->gap0, &g0));
  PetscCall(VecGetArray(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscScalar *r = &rec[bs * k];
    PetscReal          n[MM_MAX_DIM] = {0, 0, 0}, Fn[MM_MAX_DIM][MM_MAX_DIM], len = 0;
    PetscBool          same = PETSC_TRUE;

    fr->turn[k] = PETSC_FALSE;
    if (!RowFollows(ct, k)) continue;
    for (PetscInt d = 0; d < dim; ++d) {
      n[d] = -PetscRealPart(r[d]); /* nu = -n exactly: the frame is the one the run built */
      len += n[d] * n[d];
    }
    if (PetscAbsReal(len - 1) > 1e-8) {
      ++bad;
      continue;
    }
    MMContactFrameFromNormal(dim, n, Fn);
    for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
      for (PetscInt b = 0; b < MM_MAX_DIM; ++b) {
        fr->F_new[9 * k + 3 * a + b] = Fn[a][b];
        same = (PetscBool)(same && Fn[a][b] == ct->node_frame[9 * k + 3 * a + b]);
      }
    /* MMContactSetTime adds a moving obstacle's c(t).nu */
    g0[k] = ga[k] = r[MM_MAX_DIM];
    if (same) continue;
    fr->turn[k] = PETSC_TRUE;
    ++count;
  }
  PetscCall(VecRestoreArray(ct->gap, &ga));
  PetscCall(VecRestoreArray(ct->gap0, &g0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, ct->comm));
  PetscCheck(!bad, ct->comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint's contact frames (-contact_frames follow) have no unit normal at %" PetscInt_FMT " contact nodes whose frames follow here: the file is damaged, or of another contact set-up", bad);
  PetscCall(MPIU_Allreduce(&count, turned, 1, MPIU_INT, MPI_SUM, ct->comm));
  if (*turned) PetscCall(TurnSelectedRows(ct, PETSC_FALSE));
  /* the counters go on from the checkpoint's: the restore itself is no update */
  fr->updates   = (PetscInt)counters[0];
  fr->turned    = (PetscInt)counters[1];
  fr->angle_max = counters[2];
  PetscCall(PetscLogEventEnd(MMCONTACT_FrameFollow, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Its line of the closing summary. */
PetscErrorCode MMContactFramesView(MMContact ct, PetscViewer viewer)
{
  const MMContactFrames *fr = &ct->frames;
  PetscBool              ascii;
  PetscReal              amax;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii || !fr->follow) PetscFunctionReturn(0);
  PetscCall(MPIU_Allreduce(&fr->angle_max, &amax, 1, MPIU_REAL, MPIU_MAX, ct->comm));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact frames follow the contact point: %" PetscInt_FMT " updates, %" PetscInt_FMT " node frames turned (largest turn %.3g rad, -contact_frames_angle %g)", fr->updates, fr->turned, (double)amax, (double)fr->angle));
  if (fr->depth >= 0) PetscCall(PetscViewerASCIIPrintf(viewer, "; %" PetscInt_FMT " steps solved again with frames where they ended (-contact_frames_depth %g)", fr->resolves, (double)fr->depth));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscFunctionReturn(0);
}
