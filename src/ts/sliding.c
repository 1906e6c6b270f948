/* The static sliding state (benchmarks.md F1): the body sliding on the plane along the direction
 * of -v0 at the rigid acceleration a = (F_e - mu P)/m, its base nodes on the plane, each pulled
 * back by a friction force mu r_i. In the frame sliding with it the state is static:
 *   K u = L - m a e + f_c,  u_n = g and t_i = -mu r_i e_t at the contact nodes,
 * a linear problem once the friction law's direction is known, with the translation along the
 * plane pinned at one node. From it, u = u_qs + (v0 t + a t^2/2) e exactly. */
#include "newmarkimpl.h"
#include "fem.h"

/* The tangential part of a vector along the obstacle plane; its norm. */
static PetscReal Tangential(const PetscReal n[], const PetscReal v[], PetscInt dim, PetscReal e[])
{
  PetscReal vn = 0, ne = 0;
  for (PetscInt d = 0; d < dim; ++d) vn += v[d] * n[d];
  for (PetscInt d = 0; d < dim; ++d) e[d] = v[d] - vn * n[d];
  for (PetscInt d = 0; d < dim; ++d) ne += e[d] * e[d];
  return PetscSqrtReal(ne);
}

/* Total body load along the sliding direction e and into the plane, the body's mass, and e: the
 * tangential direction of -v0, or from rest that of the load. */
static PetscErrorCode SlidingLoads(MMNewmark nm, PetscReal e[], PetscReal *Fe, PetscReal *P, PetscReal *m, PetscBool *from_rest)
{
  MMContactOperators ops;
  const PetscInt     dim = nm->dim;
  const PetscReal   *n = nm->pb.obstacle_normal;
  PetscReal          ne, F[MM_MAX_DIM] = {0, 0, 0};
  PetscInt           bs;
  Vec                Lc, mass;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetLumpedMass(nm->op, &mass));
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(DMGetGlobalVector(nm->dm, &Lc));
  PetscCall(MMFEForceToCartesian(nm->op, ops.load, Lc));
  PetscCall(VecGetBlockSize(Lc, &bs));
  PetscCheck(bs == dim, PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_SUP, "-initial_state static_sliding needs a body without Dirichlet boundaries");
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecStrideSum(Lc, d, (PetscScalar *)&F[d]));
  PetscCall(DMRestoreGlobalVector(nm->dm, &Lc));
  ne         = Tangential(n, nm->pb.v0, dim, e);
  *from_rest = (PetscBool)(ne == 0);
  if (*from_rest) ne = Tangential(n, F, dim, e);
  PetscCheck(ne > 0, PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_USER_INPUT, "-initial_state static_sliding needs a direction along the obstacle plane: from -v0, or from the load when at rest");
  for (PetscInt d = 0; d < dim; ++d) e[d] /= ne;
  PetscCall(VecSum(mass, (PetscScalar *)m));
  *m /= dim;
  *Fe = *P = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    *Fe += F[d] * e[d];
    *P -= F[d] * n[d];
  }
  PetscFunctionReturn(0);
}

/* The contact node with the smallest normal-dof index (global), and its coordinates, on every rank. */
static PetscErrorCode ContactNodeCoordinates(MMNewmark nm, PetscInt k, PetscReal x[])
{
  PetscSection       cs;
  Vec                X;
  const PetscScalar *xa;
  PetscInt           off;

  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  PetscCall(DMGetCoordinateSection(nm->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(nm->dm, &X));
  PetscCall(PetscSectionGetOffset(cs, cn.vertex[k], &off));
  PetscCall(VecGetArrayRead(X, &xa));
  for (PetscInt d = 0; d < nm->dim; ++d) x[d] = PetscRealPart(xa[off + d]);
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscFunctionReturn(0);
}

/* Dofs that pin the rigid motions along the plane, which the sliding state leaves free: the
 * tangential dofs of contact node A (the one of smallest index), and in 3D the tangential dof of
 * the contact node B farthest from A that an in-plane rotation about A moves most. */
static PetscErrorCode RigidPins(MMNewmark nm, PetscInt pins[], PetscInt *npins)
{
  MMContactNodes     nodes, *ct = &nodes;
  const PetscInt  dim = nm->dim;
  MPI_Comm        comm = PetscObjectComm((PetscObject)nm->dm);
  const PetscInt *in;
  PetscInt        A = PETSC_MAX_INT, mine, kA = -1, B = PETSC_MAX_INT;
  PetscReal       xA[MM_MAX_DIM] = {0, 0, 0}, xB[MM_MAX_DIM] = {0, 0, 0}, dmax = -1, gmax;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &nodes));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  if (ct->n_local) kA = 0;
  mine = ct->n_local ? in[0] : PETSC_MAX_INT;
  PetscCall(MPIU_Allreduce(&mine, &A, 1, MPIU_INT, MPI_MIN, comm));
  if (kA >= 0 && in[0] == A) PetscCall(ContactNodeCoordinates(nm, 0, xA));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, xA, MM_MAX_DIM, MPIU_REAL, MPIU_SUM, comm));
  *npins = 0;
  for (PetscInt d = 1; d < dim; ++d) pins[(*npins)++] = A + d;
  if (dim == 3) {
    PetscInt  kB = -1, j = 1;
    PetscReal r[3], nr[3];
    for (PetscInt k = 0; k < ct->n_local; ++k) {
      PetscReal x[3], dist = 0;
      PetscCall(ContactNodeCoordinates(nm, k, x));
      for (PetscInt d = 0; d < 3; ++d) dist += PetscSqr(x[d] - xA[d]);
      if (dist > dmax) {
        dmax = dist;
        kB   = k;
      }
    }
    PetscCall(MPIU_Allreduce(&dmax, &gmax, 1, MPIU_REAL, MPIU_MAX, comm));
    {
      mine = (kB >= 0 && dmax == gmax) ? in[kB] : PETSC_MAX_INT;
      PetscCall(MPIU_Allreduce(&mine, &B, 1, MPIU_INT, MPI_MIN, comm));
      if (mine == B && kB >= 0) PetscCall(ContactNodeCoordinates(nm, kB, xB));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, xB, MM_MAX_DIM, MPIU_REAL, MPIU_SUM, comm));
    }
    /* an in-plane rotation about A moves B along n x (x_B - x_A) */
    for (PetscInt d = 0; d < 3; ++d) r[d] = xB[d] - xA[d];
    nr[0] = ct->frame[0][1] * r[2] - ct->frame[0][2] * r[1];
    nr[1] = ct->frame[0][2] * r[0] - ct->frame[0][0] * r[2];
    nr[2] = ct->frame[0][0] * r[1] - ct->frame[0][1] * r[0];
    {
      PetscReal p1 = 0, p2 = 0;
      for (PetscInt d = 0; d < 3; ++d) {
        p1 += nr[d] * ct->frame[1][d];
        p2 += nr[d] * ct->frame[2][d];
      }
      j = PetscAbsReal(p1) >= PetscAbsReal(p2) ? 1 : 2;
    }
    pins[(*npins)++] = B + j;
  }
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* Rows of the base nodes: u_n = g, and (K u - f)_tj - mu e_tj (K u - f)_n = 0 (t = -mu r e_t). */
static PetscErrorCode SlidingSystem(MMNewmark nm, const PetscReal et[], Vec f, Mat *A, Vec rhs)
{
  MMContactOperators ops;
  MMContactNodes     nodes, *ct = &nodes;
  const PetscReal    mu  = nm->pb.mu;
  const PetscInt     dim = nm->dim;
  const PetscInt    *in;
  const PetscScalar *fa, *ga;
  PetscScalar       *ra;
  PetscInt           rstart, rend, pins[3], npins, *rows, nr = 0;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactGetNodes(nm->contact, &nodes));
  PetscCall(MatDuplicate(ops.K, MAT_COPY_VALUES, A));
  PetscCall(VecCopy(f, rhs));
  PetscCall(VecGetOwnershipRange(f, &rstart, &rend));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(VecGetArray(rhs, &ra));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt     i = in[k];
    PetscInt           nn, nt;
    const PetscInt    *cn, *ctt;
    const PetscScalar *vn, *vt;
    PetscScalar       *row;

    PetscScalar       *normal;

    /* a parallel matrix lends one row at a time: keep a copy of the normal row */
    PetscInt           nnormal;
    PetscCall(MatGetRow(ops.K, i, &nn, &cn, &vn));
    nnormal = nn; /* MatRestoreRow zeroes the count */
    PetscCall(PetscMalloc2(nn, &row, nn, &normal));
    PetscCall(PetscArraycpy(normal, vn, nn));
    PetscCall(MatRestoreRow(ops.K, i, &nn, &cn, &vn));
    nn = nnormal;
    for (PetscInt d = 1; d < dim; ++d) {
      const PetscInt it = i + d;
      PetscCall(MatGetRow(ops.K, it, &nt, &ctt, &vt));
      PetscCheck(nn == nt, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Rows of one node with different patterns");
      for (PetscInt j = 0; j < nt; ++j) row[j] = vt[j] - mu * et[d - 1] * normal[j];
      PetscCall(MatSetValues(*A, 1, &it, nt, ctt, row, INSERT_VALUES));
      PetscCall(MatRestoreRow(ops.K, it, &nt, &ctt, &vt));
      ra[it - rstart] = fa[it - rstart] - mu * et[d - 1] * fa[i - rstart];
    }
    PetscCall(PetscFree2(row, normal));
    ra[i - rstart] = ga[k];
  }
  PetscCall(VecRestoreArray(rhs, &ra));
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  /* u_n = g, and the rigid motions along the plane pinned */
  PetscCall(RigidPins(nm, pins, &npins));
  PetscCall(PetscMalloc1(ct->n_local + npins, &rows));
  for (PetscInt k = 0; k < ct->n_local; ++k) rows[nr++] = in[k];
  for (PetscInt p = 0; p < npins; ++p)
    if (pins[p] >= rstart && pins[p] < rend) {
      rows[nr++] = pins[p];
      PetscCall(VecSetValue(rhs, pins[p], 0.0, INSERT_VALUES));
    }
  PetscCall(MatZeroRows(*A, nr, rows, 1.0, NULL, NULL));
  PetscCall(PetscFree(rows));
  PetscCall(VecAssemblyBegin(rhs));
  PetscCall(VecAssemblyEnd(rhs));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* w = u_qs, and react = K w - f, the contact forces of the sliding state (normal and friction). */
PetscErrorCode MMInitialStaticSliding(MMNewmark nm, Vec w, Vec react)
{
  MMContactOperators ops;
  MMContactNodes     nodes, *ct = &nodes;
  MPI_Comm           comm = PetscObjectComm((PetscObject)nm->dm);
  PetscReal          e[MM_MAX_DIM] = {0, 0, 0}, Fe = 0, P = 0, m = 0, a, et[2] = {0, 0}, rmin;
  PetscInt           dim = nm->dim;
  PetscBool          from_rest = PETSC_FALSE;
  Vec                f, rhs, me, rn, mass;
  Mat                A;
  KSP                ksp;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetLumpedMass(nm->op, &mass));
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactGetNodes(nm->contact, &nodes));
  PetscCheck(ct->enabled && !nm->pb.dirichlet, comm, PETSC_ERR_SUP, "-initial_state static_sliding needs contact on and no Dirichlet boundary");
  PetscCall(SlidingLoads(nm, e, &Fe, &P, &m, &from_rest));
  a = (Fe - nm->pb.mu * P) / m;
  /* from rest, a load that cannot overcome friction has no sliding state; the stuck equilibrium
   * is no static Coulomb state either (the base corners slip under the Poisson shear) */
  PetscCheck(!from_rest || a > 0, comm, PETSC_ERR_USER_INPUT, "-initial_state static_sliding from rest: the tangential load %g cannot overcome friction mu P = %g, so there is no sliding state. Start from -initial_state given", (double)Fe, (double)(nm->pb.mu * P));
  for (PetscInt j = 1; j < dim; ++j)
    for (PetscInt d = 0; d < dim; ++d) et[j - 1] += e[d] * ct->frame[j][d];
  /* f = L - M* (a e), the load in the frame sliding with the body: the inertia of the uniform
   * acceleration a e is the scheme's, M*'s (the redistributed mass has node blocks that are not
   * m_i I), and the strides are the Cartesian components (no Dirichlet data here) */
  PetscCall(VecDuplicate(w, &f));
  PetscCall(VecDuplicate(w, &rhs));
  PetscCall(VecDuplicate(mass, &me));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecStrideSet(me, d, -a * e[d]));
  PetscCall(MMFEForceFromCartesian(nm->op, me, rhs));
  PetscCall(MatMult(ops.Mstar, rhs, f));
  PetscCall(VecAXPY(f, 1.0, ops.load));
  PetscCall(SlidingSystem(nm, et, f, &A, rhs));
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "sliding_"));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(MMKSPSetDirect(ksp));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, rhs, w));
  PetscCall(MatMult(ops.K, w, react));
  PetscCall(VecAXPY(react, -1.0, f));
  PetscCall(VecISSet(react, ct->is_interior, 0.0));
  PetscCall(VecGetSubVector(react, ct->is_normal, &rn));
  PetscCall(VecMax(rn, NULL, &rmin)); /* react_n = -r_i: all reactions > 0 means max < 0 */
  PetscCall(VecRestoreSubVector(react, ct->is_normal, &rn));
  PetscCheck(rmin < 0, comm, PETSC_ERR_USER_INPUT, "The static sliding state has a base node without compressive reaction (r = %g): the body would lift off; it is not a sliding state", (double)-rmin);
  if (!nm->pb.quiet) PetscCall(PetscPrintf(comm, "  static sliding state: rigid acceleration a = %g along (%g, %g, %g)\n", (double)a, (double)e[0], (double)e[1], (double)e[2]));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&me));
  PetscFunctionReturn(0);
}
