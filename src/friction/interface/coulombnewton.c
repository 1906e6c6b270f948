/* The semismooth Newton kernel of the step's Coulomb (or Tresca) problem in contact space
 * (docs/method.md section 6, "Solving the step's Coulomb problem").
 *
 * Alart-Curnier's function, per node i with rho_i = 1 / |W_ii|_F and z = r - rho (W r - q):
 *   Phi_n = r_n - max(0, z_n),   Phi_t = r_t - P_{D(R)}(z_t),   R = mu max(0, z_n) or s.
 * Phi(r) = 0 is the problem. Newton's step uses an element of the generalized Jacobian
 * J = I - DP + DP rho W (DP the Jacobian of the projection per node), and an Armijo line search on
 * |Phi|^2 / 2 makes every step decrease it, so the iteration cannot cycle. A node with DP = 0 (z_n <= 0:
 * it leaves the obstacle) has the row J_i = I and the step d_i = -Phi_i, so only the nodes that can
 * carry a reaction enter the dense LU: the linear system is reduced to them. */
#include "../frictionimpl.h"
#include <petscblaslapack.h>

static PetscErrorCode WorkReserve(MMCoulombWork *wk, PetscInt m)
{
  PetscFunctionBeginUser;
  if (m <= wk->cap) PetscFunctionReturn(0);
  PetscCall(MMCoulombWorkDestroy(wk));
  wk->cap = PetscMax(m, 2 * wk->cap);
  PetscCall(PetscMalloc5(wk->cap, &wk->rho, wk->cap, &wk->u, wk->cap, &wk->z, wk->cap, &wk->F, wk->cap, &wk->Fn));
  PetscCall(PetscMalloc5(wk->cap, &wk->d, wk->cap, &wk->rt, wk->cap, &wk->y, 9 * wk->cap, &wk->DP, (size_t)wk->cap * wk->cap, &wk->J));
  PetscCall(PetscMalloc2(wk->cap, &wk->act, wk->cap, &wk->ipiv));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCoulombWorkDestroy(MMCoulombWork *wk)
{
  PetscFunctionBeginUser;
  if (!wk->cap) PetscFunctionReturn(0);
  PetscCall(PetscFree5(wk->rho, wk->u, wk->z, wk->F, wk->Fn));
  PetscCall(PetscFree5(wk->d, wk->rt, wk->y, wk->DP, wk->J));
  PetscCall(PetscFree2(wk->act, wk->ipiv));
  wk->cap = 0;
  PetscFunctionReturn(0);
}

/* u = W r - q */
static PetscErrorCode Velocity(const MMCoulombProblem *p, const PetscReal r[], PetscReal u[])
{
  PetscBLASInt   m, one = 1;
  const PetscReal a = 1.0, b = 0.0;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(p->n * p->nc, &m));
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &m, &m, &a, p->W, &m, r, &one, &b, u, &one));
  for (PetscInt i = 0; i < m; ++i) u[i] -= PetscRealPart(p->q[i]);
  PetscFunctionReturn(0);
}

/* The radius of node i's disk for the argument z. */
static inline PetscReal Radius(const MMCoulombProblem *p, PetscInt i, const PetscReal z[])
{
  return p->s ? p->s[i] : p->mu[i] * PetscMax(z[i * p->nc], 0.0);
}

/* F = Phi(r), with u and z kept for the Jacobian; returns |F|^2 / 2. */
static PetscErrorCode Residual(const MMCoulombProblem *p, MMCoulombWork *wk, const PetscReal r[], PetscReal F[], PetscReal *merit)
{
  const PetscInt nc = p->nc;
  PetscReal      sum = 0;

  PetscFunctionBeginUser;
  PetscCall(Velocity(p, r, wk->u));
  for (PetscInt i = 0; i < p->n; ++i) {
    const PetscReal *ri = &r[i * nc];
    PetscReal       *zi = &wk->z[i * nc], *Fi = &F[i * nc], R, nt = 0;
    for (PetscInt c = 0; c < nc; ++c) zi[c] = ri[c] - wk->rho[i] * wk->u[i * nc + c];
    R = Radius(p, i, wk->z);
    for (PetscInt c = 1; c < nc; ++c) nt += zi[c] * zi[c];
    nt    = PetscSqrtReal(nt);
    Fi[0] = ri[0] - PetscMax(zi[0], 0.0);
    for (PetscInt c = 1; c < nc; ++c) Fi[c] = ri[c] - (nt > R ? R * zi[c] / nt : zi[c]);
    for (PetscInt c = 0; c < nc; ++c) sum += Fi[c] * Fi[c];
  }
  *merit = 0.5 * sum;
  PetscFunctionReturn(0);
}

/* Per node, DP = dP/dz (nc x nc, row-major in wk->DP[9 i]); returns whether DP is nonzero. */
static PetscBool ProjectionJacobian(const MMCoulombProblem *p, PetscInt i, const PetscReal z[], PetscReal DP[9])
{
  const PetscInt   nc = p->nc;
  const PetscReal *zi = &z[i * nc], R = Radius(p, i, z);
  PetscReal        nt = 0;
  PetscBool        nonzero = PETSC_FALSE;

  for (PetscInt k = 0; k < 9; ++k) DP[k] = 0;
  for (PetscInt c = 1; c < nc; ++c) nt += zi[c] * zi[c];
  nt = PetscSqrtReal(nt);
  if (zi[0] > 0) DP[0] = 1, nonzero = PETSC_TRUE;
  if (R <= 0) return nonzero; /* the disk is a point: its projection is constant */
  nonzero = PETSC_TRUE;
  if (nt <= R) {
    for (PetscInt c = 1; c < nc; ++c) DP[c * nc + c] = 1;
    return nonzero;
  }
  /* on the rim: R/|z_t| (I - theta theta^T), and in Coulomb's case mu theta along z_n */
  for (PetscInt a = 1; a < nc; ++a) {
    const PetscReal ta = zi[a] / nt;
    for (PetscInt b = 1; b < nc; ++b) DP[a * nc + b] = R / nt * ((a == b) - ta * zi[b] / nt);
    if (!p->s && zi[0] > 0) DP[a * nc] = p->mu[i] * ta;
  }
  return nonzero;
}

/* LAPACK's least-norm solver by complete orthogonal factorization (QR with column pivoting), which
 * PETSc's BLAS/LAPACK header does not declare */
#define MMLAPACKgelsy_ PETSCBLAS(gelsy, GELSY)
BLAS_EXTERN void MMLAPACKgelsy_(const PetscBLASInt *, const PetscBLASInt *, const PetscBLASInt *, PetscReal *, const PetscBLASInt *, PetscReal *, const PetscBLASInt *, PetscBLASInt *, const PetscReal *, PetscBLASInt *, PetscReal *, const PetscBLASInt *, PetscBLASInt *);

/* J d = rhs for a J that two nodes on one node's dofs make singular (a friction corner in contact
 * with both obstacles: the split of its force between them is free, docs/method.md section 12):
 * the least-norm solution, so that the step does not move along the free split and the answer
 * does not depend on the rounding of W (1 rank against 2). J is overwritten. QR with column
 * pivoting, not the SVD: a few times an LU, where the SVD took most of the run (docs/scaling.md, "The figures behind the code's choices"). */
static PetscErrorCode LeastNormSolve(PetscBLASInt ma, PetscReal J[], PetscReal rhs[], PetscBLASInt *info)
{
  PetscBLASInt    one = 1, rank, lwork = -1, *jpvt;
  const PetscReal rcond = 1e-10;
  PetscReal       wq, *work;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(ma, &jpvt));
  PetscCallBLAS("LAPACKgelsy", MMLAPACKgelsy_(&ma, &ma, &one, J, &ma, rhs, &ma, jpvt, &rcond, &rank, &wq, &lwork, info));
  PetscCall(PetscBLASIntCast((PetscInt)wq, &lwork));
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCallBLAS("LAPACKgelsy", MMLAPACKgelsy_(&ma, &ma, &one, J, &ma, rhs, &ma, jpvt, &rcond, &rank, work, &lwork, info));
  PetscCall(PetscFree(work));
  PetscCall(PetscFree(jpvt));
  PetscFunctionReturn(0);
}

/* The Newton direction d from J d = -F, reduced to the nodes with DP != 0. */
static PetscErrorCode NewtonDirection(const MMCoulombProblem *p, MMCoulombWork *wk, const PetscReal F[], PetscReal d[], PetscBool *ok)
{
  const PetscInt nc = p->nc, m = p->n * nc;
  PetscInt       na = 0;
  PetscBLASInt   ma, one = 1, info, mm;
  const PetscReal a1 = 1.0, b0 = 0.0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < p->n; ++i)
    if (ProjectionJacobian(p, i, wk->z, &wk->DP[9 * i])) wk->act[na++] = i;
  /* inactive nodes: d_i = -F_i; their effect on the active rows goes to the right-hand side */
  for (PetscInt k = 0; k < m; ++k) d[k] = -F[k];
  for (PetscInt k = 0; k < na; ++k)
    for (PetscInt c = 0; c < nc; ++c) d[wk->act[k] * nc + c] = 0;
  *ok = PETSC_TRUE;
  if (!na) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(m, &mm));
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &mm, &mm, &a1, p->W, &mm, d, &one, &b0, wk->y, &one));
  PetscCall(PetscBLASIntCast(na * nc, &ma));
  /* J_AA = (I - DP) + DP rho W_AA, and rhs_A = -F_A - DP rho (W d_I)_A; column-major in wk->J */
  for (PetscInt k = 0; k < na; ++k) {
    const PetscInt   i  = wk->act[k];
    const PetscReal *DP = &wk->DP[9 * i], ri = wk->rho[i];
    for (PetscInt a = 0; a < nc; ++a) {
      const PetscInt row = k * nc + a;
      PetscReal      rhs = -F[i * nc + a];
      for (PetscInt b = 0; b < nc; ++b) rhs -= DP[a * nc + b] * ri * wk->y[i * nc + b];
      wk->rt[row] = rhs;
      for (PetscInt l = 0; l < na; ++l) {
        const PetscInt j = wk->act[l];
        for (PetscInt c = 0; c < nc; ++c) {
          PetscReal v = 0;
          for (PetscInt b = 0; b < nc; ++b) v += DP[a * nc + b] * PetscRealPart(p->W[(i * nc + b) + (size_t)(j * nc + c) * m]);
          v *= ri;
          if (j == i) v += (a == c) - DP[a * nc + c];
          wk->J[row + (size_t)(l * nc + c) * ma] = v;
        }
      }
    }
  }
  if (p->redundant) PetscCall(LeastNormSolve(ma, wk->J, wk->rt, &info));
  else PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&ma, &one, wk->J, &ma, wk->ipiv, wk->rt, &ma, &info));
  if (info) {
    /* a singular J (degenerate contact): the projection step -F is still a descent direction of a
     * kind, and the line search takes care of the rest */
    for (PetscInt k = 0; k < m; ++k) d[k] = -F[k];
    *ok = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 0; k < na; ++k)
    for (PetscInt c = 0; c < nc; ++c) d[wk->act[k] * nc + c] = wk->rt[k * nc + c];
  PetscFunctionReturn(0);
}

/* Node i's own problem with the others' reactions fixed, by its projection map r_i <- P(r_i - rho_i
 * (W_ii r_i - q_i')), a contraction for fixed thresholds (rho_i = 1/|W_ii|_F), at most 200 times:
 * the step of projected Gauss-Seidel. */
static void LocalSolve(const MMCoulombProblem *p, MMCoulombWork *wk, PetscInt i, PetscReal x[])
{
  const PetscInt nc = p->nc, m = p->n * nc;
  PetscReal      qi[MM_MAX_DIM], xi[MM_MAX_DIM], z[MM_MAX_DIM];

  for (PetscInt a = 0; a < nc; ++a) {
    qi[a] = PetscRealPart(p->q[i * nc + a]);
    for (PetscInt j = 0; j < m; ++j)
      if (j / nc != i) qi[a] -= PetscRealPart(p->W[(i * nc + a) + (size_t)j * m]) * x[j];
    xi[a] = x[i * nc + a];
  }
  for (PetscInt it = 0; it < 200; ++it) {
    PetscReal nt = 0, R, change = 0, size = 0;
    for (PetscInt a = 0; a < nc; ++a) {
      PetscReal u = -qi[a];
      for (PetscInt b = 0; b < nc; ++b) u += PetscRealPart(p->W[(i * nc + a) + (size_t)(i * nc + b) * m]) * xi[b];
      z[a] = xi[a] - wk->rho[i] * u;
    }
    R = p->s ? p->s[i] : p->mu[i] * PetscMax(z[0], 0.0);
    for (PetscInt a = 1; a < nc; ++a) nt += z[a] * z[a];
    nt = PetscSqrtReal(nt);
    z[0] = PetscMax(z[0], 0.0);
    for (PetscInt a = 1; a < nc; ++a) z[a] = nt > R ? R * z[a] / nt : z[a];
    for (PetscInt a = 0; a < nc; ++a) {
      change = PetscMax(change, PetscAbsReal(z[a] - xi[a]));
      size   = PetscMax(size, PetscAbsReal(z[a]));
      xi[a]  = z[a];
    }
    if (change <= 1e-15 * size) break;
  }
  for (PetscInt a = 0; a < nc; ++a) x[i * nc + a] = xi[a];
}

/* A problem whose W is singular (two nodes on one node's dofs, a friction corner) can hold Newton
 * where |Phi| has a stationary point that is not a solution (its two rows ask the shared dof for
 * two things and the least-norm step splits the difference); sweeps of projected Gauss-Seidel,
 * whose one-node problems are regular, leave it (docs/method.md section 12). */
static void GaussSeidelSweeps(const MMCoulombProblem *p, MMCoulombWork *wk, PetscInt sweeps, PetscReal x[])
{
  for (PetscInt s = 0; s < sweeps; ++s)
    for (PetscInt i = 0; i < p->n; ++i) LocalSolve(p, wk, i, x);
}

/* The force scale of the residual: the largest reaction that closes a node's predicted gap alone
 * (rho_i |q_i|), the thresholds, and the current reactions. */
static PetscReal ForceScale(const MMCoulombProblem *p, const PetscReal rho[], const PetscReal r[])
{
  PetscReal scale = 0;
  for (PetscInt i = 0; i < p->n; ++i) {
    for (PetscInt c = 0; c < p->nc; ++c) {
      scale = PetscMax(scale, rho[i] * PetscAbsReal(PetscRealPart(p->q[i * p->nc + c])));
      scale = PetscMax(scale, PetscAbsReal(r[i * p->nc + c]));
    }
    if (p->s) scale = PetscMax(scale, p->s[i]);
  }
  return scale > 0 ? scale : 1.0;
}

static PetscReal NormInf(PetscInt m, const PetscReal x[])
{
  PetscReal v = 0;
  for (PetscInt k = 0; k < m; ++k) v = PetscMax(v, PetscAbsReal(x[k]));
  return v;
}

/* Solves Phi(r) = 0 from the warm start r to |Phi|_inf <= rtol * (force scale), at most maxit
 * Newton steps. r is overwritten with the solution. */
PetscErrorCode MMCoulombNewton(const MMCoulombProblem *p, MMCoulombWork *wk, PetscReal rtol, PetscInt maxit, PetscScalar r[], MMCoulombResult *res)
{
  const PetscInt nc = p->nc, m = p->n * nc;
  PetscReal      merit, scale, *x;

  PetscFunctionBeginUser;
  res->its       = 0;
  res->converged = PETSC_TRUE;
  res->residual  = 0;
  if (!m) PetscFunctionReturn(0);
  PetscCall(WorkReserve(wk, m));
  PetscCall(PetscMalloc1(m, &x));
  for (PetscInt k = 0; k < m; ++k) x[k] = PetscRealPart(r[k]);
  for (PetscInt i = 0; i < p->n; ++i) {
    PetscReal f = 0;
    for (PetscInt a = 0; a < nc; ++a)
      for (PetscInt b = 0; b < nc; ++b) f += PetscSqr(PetscRealPart(p->W[(i * nc + a) + (size_t)(i * nc + b) * m]));
    wk->rho[i] = 1.0 / PetscSqrtReal(f);
  }
  PetscCall(Residual(p, wk, x, wk->F, &merit));
  for (;;) {
    PetscBool ok;
    PetscReal t = 1, trial;

    scale         = ForceScale(p, wk->rho, x);
    res->residual = NormInf(m, wk->F) / scale;
    PetscCall(PetscInfo(NULL, "Coulomb Newton %" PetscInt_FMT ": residual %g of the force scale %g\n", res->its, (double)res->residual, (double)scale));
    if (res->residual <= rtol) break;
    if (res->its >= maxit) {
      res->converged = PETSC_FALSE;
      break;
    }
    ++res->its;
    PetscCall(NewtonDirection(p, wk, wk->F, wk->d, &ok));
    /* Armijo: |Phi|^2 must decrease by a fraction of the step; halve it until it does */
    for (;;) {
      for (PetscInt k = 0; k < m; ++k) wk->y[k] = x[k] + t * wk->d[k];
      PetscCall(Residual(p, wk, wk->y, wk->Fn, &trial));
      if (trial <= (1 - 1e-4 * t) * merit || t < 1e-8) break;
      t *= 0.5;
    }
    PetscCall(PetscArraycpy(x, wk->y, m));
    PetscCall(PetscArraycpy(wk->F, wk->Fn, m));
    merit = trial;
    if (p->redundant && t < 1e-3) {
      GaussSeidelSweeps(p, wk, 20, x);
      PetscCall(Residual(p, wk, x, wk->F, &merit));
    }
  }
  for (PetscInt k = 0; k < m; ++k) r[k] = x[k];
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}
