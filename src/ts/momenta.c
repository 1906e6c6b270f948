/* The momentum audit of every step: the centre of mass, the scheme's own momenta P and J, and the
 * physical angular momentum (docs/method.md section 4, "Momentum").
 *
 * Every one but the angular momentum is a fixed linear functional of u or v: a sum over vertices
 * of a Cartesian component of M* u or M* v, weighted by 1 or by a reference coordinate. With
 * f = T f_w the map of forces to Cartesian (T = Q N^{-T}, fem.c) and e the Cartesian weights,
 * e.(T M* x) = (M* T^T e).x, and T^T = N^{-1} Q^T is the map of displacements from Cartesian. So
 * each functional is a vector g = M* (from Cartesian)(e), built once, and a step costs one
 * multiple dot product on u and v: no product with M* and no Cartesian copy of them. */
#include "newmarkimpl.h"
#include "fem.h"

/* The Cartesian weights, on this rank's owned vertices. They are rigid-body modes about the
 * origin (src/fem/rigid_modes.c):
 * - e[d], the translations over every free component (MMFERigidModesCartesian: a Dirichlet
 *   component counts as 0): the centre of mass;
 * - p[d] and a[k], the translations and the rotations e_k x X (k = z alone in 2D), over the vertices
 *   with no Dirichlet dof only: P, the loads' resultant, and J_k = sum_i (X_i x q_i)_k = sum_i
 *   q_i . (e_k x X_i);
 * and the table of those vertices for the angular momentum. */
static PetscErrorCode MomentaWeights(MMNewmark nm, Vec e[], Vec p[], Vec a[])
{
  MMMomenta         *mo  = &nm->momenta;
  DM                 dm  = nm->dm;
  const PetscInt     dim = nm->dim;
  const PetscReal    origin[MM_MAX_DIM] = {0, 0, 0};
  PetscSection       gs, ls, cs;
  PetscInt           vStart, vEnd, rstart, nv = 0;
  Vec                X;
  const PetscScalar *x;
  PetscScalar       *pw[MM_MAX_DIM], *aw[3];

  PetscFunctionBeginUser;
  PetscCall(MMFERigidModesCartesian(nm->op, origin, 1.0, dim, e));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc2(vEnd - vStart, &mo->vert_u, vEnd - vStart, &mo->vert_x));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecGetArray(p[d], &pw[d]));
  for (PetscInt k = 0; k < mo->nJ; ++k) PetscCall(VecGetArray(a[k], &aw[k]));
  PetscCall(VecGetOwnershipRange(e[0], &rstart, NULL));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt  goff, ncdof, xoff, i;
    PetscReal r[MM_MAX_DIM] = {0, 0, 0}, T[MM_MAX_DIM][MM_MAX_RIGID];

    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue; /* another rank's */
    PetscCall(PetscSectionGetConstraintDof(ls, v, &ncdof));
    if (ncdof) continue; /* P, J and the angular momentum leave out the vertices held by Dirichlet data */
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    i = goff - rstart;
    for (PetscInt c = 0; c < dim; ++c) r[c] = PetscRealPart(x[xoff + c]);
    MMFERigidModeMatrix(dim, r, T);
    for (PetscInt c = 0; c < dim; ++c) {
      for (PetscInt d = 0; d < dim; ++d) pw[d][i + c] = T[c][d];
      for (PetscInt k = 0; k < mo->nJ; ++k) aw[k][i + c] = T[c][dim + k];
    }
    mo->vert_u[nv]   = i;
    mo->vert_x[nv++] = xoff;
  }
  mo->nv = nv;
  PetscCall(VecRestoreArrayRead(X, &x));
  for (PetscInt k = 0; k < mo->nJ; ++k) PetscCall(VecRestoreArray(a[k], &aw[k]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecRestoreArray(p[d], &pw[d]));
  PetscFunctionReturn(0);
}

/* Once, on the final M* (after the mass redistribution): the functionals g and the selectors of P. */
static PetscErrorCode MomentaSetUp(MMNewmark nm)
{
  MMContactOperators ops;
  MMMomenta         *mo  = &nm->momenta;
  const PetscInt     dim = nm->dim;
  Vec                w[3 * MM_MAX_DIM], t;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  mo->nJ = dim == 3 ? 3 : 1;
  mo->ng = 2 * dim + mo->nJ;
  for (PetscInt k = 0; k < mo->ng; ++k) {
    PetscCall(DMCreateGlobalVector(nm->dm, &w[k]));
    PetscCall(VecZeroEntries(w[k]));
  }
  PetscCall(MomentaWeights(nm, w, &w[dim], &w[2 * dim]));
  PetscCall(VecDuplicate(w[0], &t));
  for (PetscInt k = 0; k < mo->ng; ++k) {
    PetscCall(VecDuplicate(w[0], &mo->g[k]));
    PetscCall(MMFEFromCartesian(nm->op, w[k], t));
    PetscCall(MatMult(ops.Mstar, t, mo->g[k]));
  }
  PetscCall(VecDestroy(&t));
  for (PetscInt d = 0; d < dim; ++d) mo->sel[d] = w[dim + d]; /* kept, for the loads' resultant */
  for (PetscInt k = 0; k < mo->ng; ++k)
    if (k < dim || k >= 2 * dim) PetscCall(VecDestroy(&w[k]));
  PetscFunctionReturn(0);
}

/* The physical angular momentum about the centre of mass, L = sum_i m_i (x_i - x_cm) x v_i with the
 * lumped standard mass, x_i = X_i + u_i the current position, over the nodes whose dofs are all
 * free. It stays the standard mass's: the modified mass lacks the contact nodes' normal masses, so
 * it has no single centre, and its rigid translation would carry an angular momentum. The scheme's
 * own (M*) momenta are P and J. Quadratic in the state, so a pass over the vertex table. */
static PetscErrorCode AngularMomentum(MMNewmark nm, MMHistory *h)
{
  MMMomenta         *mo = &nm->momenta;
  DM                 dm = nm->dm;
  const PetscInt     dim = nm->dim;
  Vec                uc, vc, X, mass;
  const PetscScalar *u, *v, *m, *x;
  PetscReal          sum[1 + MM_MAX_DIM] = {0}, cm[MM_MAX_DIM] = {0, 0, 0}, L[3] = {0, 0, 0};
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(MMFEGetLumpedMass(nm->op, &mass));
  PetscCall(DMGetGlobalVector(dm, &uc));
  PetscCall(DMGetGlobalVector(dm, &vc));
  PetscCall(MMFEToCartesian(nm->op, nm->state.u, uc));
  PetscCall(MMFEToCartesian(nm->op, nm->state.v, vc));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(uc, &u));
  PetscCall(VecGetArrayRead(vc, &v));
  PetscCall(VecGetArrayRead(mass, &m));
  PetscCall(VecGetArrayRead(X, &x));
  /* first pass: mass and first moment of the current position */
  for (PetscInt n = 0; n < mo->nv; ++n) {
    const PetscInt i = mo->vert_u[n], xo = mo->vert_x[n];
    sum[0] += PetscRealPart(m[i]);
    for (PetscInt d = 0; d < dim; ++d) sum[1 + d] += PetscRealPart(m[i] * (x[xo + d] + u[i + d]));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 1 + MM_MAX_DIM, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt d = 0; d < dim; ++d) cm[d] = sum[1 + d] / PetscMax(sum[0], PETSC_SMALL);
  /* the finite-strain laws: the scheme's own J about the current positions (CurrentPositionMoment), moved to
   * x_cm, is conserved exactly; the lumped masses' L would drift by the lumping error */
  for (PetscInt n = 0; n < mo->nv && !nm->material->finite; ++n) {
    const PetscInt i = mo->vert_u[n], xo = mo->vert_x[n];
    const PetscReal mp = PetscRealPart(m[i]);
    PetscReal       r[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    for (PetscInt d = 0; d < dim; ++d) {
      r[d] = PetscRealPart(x[xo + d] + u[i + d]) - cm[d];
      w[d] = PetscRealPart(v[i + d]);
    }
    L[0] += mp * (r[1] * w[2] - r[2] * w[1]);
    L[1] += mp * (r[2] * w[0] - r[0] * w[2]);
    L[2] += mp * (r[0] * w[1] - r[1] * w[0]);
  }
  PetscCall(MPIU_Allreduce(L, h->L, 3, MPIU_REAL, MPIU_SUM, comm));
  if (nm->material->finite) {
    const PetscReal *P = h->P;
    h->L[0] = h->J[0] - (cm[1] * P[2] - cm[2] * P[1]);
    h->L[1] = h->J[1] - (cm[2] * P[0] - cm[0] * P[2]);
    h->L[2] = h->J[2] - (cm[0] * P[1] - cm[1] * P[0]);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecRestoreArrayRead(mass, &m));
  PetscCall(VecRestoreArrayRead(vc, &v));
  PetscCall(VecRestoreArrayRead(uc, &u));
  PetscCall(DMRestoreGlobalVector(dm, &vc));
  PetscCall(DMRestoreGlobalVector(dm, &uc));
  PetscFunctionReturn(0);
}

/* The resultant of the loads L, Cartesian, over the vertices with no Dirichlet dof: a constant L's
 * on the initial state only, L(t)'s at every step. */
static PetscErrorCode LoadResultant(MMNewmark nm, MMHistory *h)
{
  MMContactOperators ops;
  MMMomenta         *mo = &nm->momenta;
  Vec                lc;
  PetscScalar        r[MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(DMGetGlobalVector(nm->dm, &lc));
  PetscCall(MMFEForceToCartesian(nm->op, ops.load, lc));
  PetscCall(VecMDot(lc, nm->dim, mo->sel, r));
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) h->load[d] = d < nm->dim ? PetscRealPart(r[d]) : 0;
  PetscCall(DMRestoreGlobalVector(nm->dm, &lc));
  PetscFunctionReturn(0);
}

static PetscErrorCode ForceMoments(MMNewmark nm, Vec u, Vec f, PetscBool reference, PetscReal F[3], PetscReal T[3]);

/* The finite-strain laws: their algorithmic force has no moment about the mean position of the step
 * (docs/method.md section 13), so the scheme's angular momentum is J = sum_i (X_i + u_i) x (M* v)_i,
 * about the current positions: J gets sum_i u_i x (M* v)_i, over the same vertices. */
static PetscErrorCode CurrentPositionMoment(MMNewmark nm, MMHistory *h)
{
  MMContactOperators ops;
  PetscReal          F[3], T[3];

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, nm->state.v, nm->state.work));
  PetscCall(ForceMoments(nm, nm->state.u, nm->state.work, PETSC_FALSE, F, T));
  for (PetscInt k = 0; k < 3; ++k) h->J[k] += T[k];
  PetscFunctionReturn(0);
}

/* The functionals of the current frames: built on first use, and again when contact's frames turned
 * or its pairing changed since (they are M* (from Cartesian)(e), of the frame they were built in) */
static PetscErrorCode MomentaCurrent(MMNewmark nm)
{
  MMMomenta       *mo = &nm->momenta;
  PetscObjectState frames;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetFrameState(nm->contact, &frames));
  if (mo->ng && mo->frames != frames) PetscCall(MMMomentaDestroy(mo));
  if (!mo->ng) {
    PetscCall(MomentaSetUp(nm));
    mo->frames = frames;
  }
  PetscFunctionReturn(0);
}

/* Centre-of-mass displacement and velocity of the discrete system, weighted by M*, whose momentum
 * the scheme conserves: the modified mass lacks the contact nodes' normal masses, so its mass for a
 * rigid translation is a matrix m*, not m I, and ucm = m*^-1 sum_i (M* u)_i, vcm = m*^-1 sum_i
 * (M* v)_i. The scheme's momenta P = sum_i (M* v)_i and J = sum_i X_i x (M* v)_i about the origin
 * over the vertices with no Dirichlet dof: rigid translations and infinitesimal rotations are in
 * the kernel of the stiffness, so P and J change over a step by dt times the trapezoidal mean of
 * the resultant (and moment) of L and the contact forces, whatever the deformation. */
PetscErrorCode MMRigidBodyDiagnostics(MMNewmark nm, MMHistory *h)
{
  MMContactOperators ops;
  MMMomenta         *mo  = &nm->momenta;
  const PetscInt     dim = nm->dim;
  PetscScalar        su[MM_MAX_DIM], sv[3 * MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(PetscLogEventBegin(MM_TS_Momenta, 0, 0, 0, 0));
  PetscCall(MomentaCurrent(nm));
  /* one reduction for both */
  PetscCall(VecMDotBegin(nm->state.u, dim, mo->g, su));
  PetscCall(VecMDotBegin(nm->state.v, mo->ng, mo->g, sv));
  PetscCall(VecMDotEnd(nm->state.u, dim, mo->g, su));
  PetscCall(VecMDotEnd(nm->state.v, mo->ng, mo->g, sv));
  for (PetscInt a = 0; a < dim; ++a) {
    h->ucm[a] = h->vcm[a] = 0;
    for (PetscInt b = 0; b < dim; ++b) {
      h->ucm[a] += ops.mass_star_inv[a * dim + b] * PetscRealPart(su[b]);
      h->vcm[a] += ops.mass_star_inv[a * dim + b] * PetscRealPart(sv[b]);
    }
  }
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) h->P[d] = d < dim ? PetscRealPart(sv[dim + d]) : 0;
  for (PetscInt k = 0; k < 3; ++k) h->J[k] = 0;
  if (dim == 3)
    for (PetscInt k = 0; k < 3; ++k) h->J[k] = PetscRealPart(sv[2 * dim + k]);
  else h->J[2] = PetscRealPart(sv[2 * dim]);
  if (nm->material->finite) PetscCall(CurrentPositionMoment(nm, h));
  if (h->step == 0 || nm->loads->in_time) PetscCall(LoadResultant(nm, h));
  PetscCall(AngularMomentum(nm, h));
  PetscCall(PetscLogEventEnd(MM_TS_Momenta, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMMomentaDestroy(MMMomenta *mo)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < mo->ng; ++k) PetscCall(VecDestroy(&mo->g[k]));
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) PetscCall(VecDestroy(&mo->sel[d]));
  PetscCall(PetscFree2(mo->vert_u, mo->vert_x));
  mo->ng = 0;
  PetscFunctionReturn(0);
}

/* The resultant F and the moment T about the origin of the w-frame force f over the vertices with no
 * Dirichlet dof, at the current positions X + u (reference: with X, else about the displacements u alone) */
static PetscErrorCode ForceMoments(MMNewmark nm, Vec u, Vec f, PetscBool reference, PetscReal F[3], PetscReal T[3])
{
  MMMomenta         *mo  = &nm->momenta;
  DM                 dm  = nm->dm;
  const PetscInt     dim = nm->dim;
  Vec                uc, fc, X;
  const PetscScalar *ua, *fa, *x;
  PetscReal          s[6] = {0, 0, 0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(MomentaCurrent(nm));
  PetscCall(DMGetGlobalVector(dm, &uc));
  PetscCall(DMGetGlobalVector(dm, &fc));
  PetscCall(MMFEToCartesian(nm->op, u, uc));
  PetscCall(MMFEForceToCartesian(nm->op, f, fc));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(uc, &ua));
  PetscCall(VecGetArrayRead(fc, &fa));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt n = 0; n < mo->nv; ++n) {
    const PetscInt i = mo->vert_u[n], xo = mo->vert_x[n];
    PetscReal      r[3] = {0, 0, 0}, q[3] = {0, 0, 0};
    for (PetscInt d = 0; d < dim; ++d) {
      r[d] = reference ? PetscRealPart(x[xo + d] + ua[i + d]) : PetscRealPart(ua[i + d]);
      q[d] = PetscRealPart(fa[i + d]);
      s[d] += q[d];
    }
    s[3] += r[1] * q[2] - r[2] * q[1];
    s[4] += r[2] * q[0] - r[0] * q[2];
    s[5] += r[0] * q[1] - r[1] * q[0];
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecRestoreArrayRead(fc, &fa));
  PetscCall(VecRestoreArrayRead(uc, &ua));
  PetscCall(DMRestoreGlobalVector(dm, &fc));
  PetscCall(DMRestoreGlobalVector(dm, &uc));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s, 6, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)dm)));
  for (PetscInt k = 0; k < 3; ++k) {
    F[k] = s[k];
    T[k] = s[3 + k];
  }
  PetscFunctionReturn(0);
}

/* What f changes of P and J in a step, per unit time (the finite-strain step's stop, nonlinear.c) */
PetscErrorCode MMMomentaOfForce(MMNewmark nm, Vec u, Vec f, PetscReal F[3], PetscReal T[3])
{
  PetscFunctionBeginUser;
  PetscCall(ForceMoments(nm, u, f, PETSC_TRUE, F, T));
  PetscFunctionReturn(0);
}
