/* The static sliding state (benchmarks.md F1): the body sliding on the plane along the direction
 * of -v0 at the rigid acceleration a = (F_e - mu P)/m, its base nodes on the plane, each pulled
 * back by a friction force mu r_i. In the frame sliding with it the state is static:
 *   K u = L - m a e + f_c,  u_n = g and t_i = -mu r_i e_t at the contact nodes,
 * a linear problem once the friction law's direction is known, with the translation along the
 * plane pinned at one node. From it, u = u_qs + (v0 t + a t^2/2) e exactly. */
#include "sliding.h"
#include "contact.h"
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
static PetscErrorCode SlidingLoads(MMCtx *ctx, PetscReal e[], PetscReal *Fe, PetscReal *P, PetscReal *m, PetscBool *from_rest)
{
  const PetscInt   dim = ctx->op.dim;
  const PetscReal *n = ctx->opt.obstacle_normal;
  PetscReal        ne, F[MM_MAX_DIM] = {0, 0, 0};
  PetscInt         bs;
  Vec              Lc;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(ctx->op.dm, &Lc));
  PetscCall(MMFEToCartesian(ctx, ctx->op.load, Lc));
  PetscCall(VecGetBlockSize(Lc, &bs));
  PetscCheck(bs == dim, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_SUP, "-initial_state static_sliding needs a body without Dirichlet boundaries");
  for (PetscInt d = 0; d < dim; ++d) PetscCall(VecStrideSum(Lc, d, (PetscScalar *)&F[d]));
  PetscCall(DMRestoreGlobalVector(ctx->op.dm, &Lc));
  ne         = Tangential(n, ctx->opt.v0, dim, e);
  *from_rest = (PetscBool)(ne == 0);
  if (*from_rest) ne = Tangential(n, F, dim, e);
  PetscCheck(ne > 0, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_USER_INPUT, "-initial_state static_sliding needs a direction along the obstacle plane: from -v0, or from the load when at rest");
  for (PetscInt d = 0; d < dim; ++d) e[d] /= ne;
  PetscCall(VecSum(ctx->op.mass_lumped_cart, (PetscScalar *)m));
  *m /= dim;
  *Fe = *P = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    *Fe += F[d] * e[d];
    *P -= F[d] * n[d];
  }
  PetscFunctionReturn(0);
}

/* Rows of the base nodes: u_n = g, and (K u - f)_t - mu e_t (K u - f)_n = 0 (t = -mu r e_t). */
static PetscErrorCode SlidingSystem(MMCtx *ctx, const PetscReal et, Vec f, Mat *A, Vec rhs)
{
  MMContact         *ct = &ctx->contact;
  const PetscReal    mu = ctx->opt.mu;
  const PetscInt    *in;
  const PetscScalar *fa, *ga;
  PetscScalar       *ra;
  PetscInt           rstart, pin = -1, first;

  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(ctx->op.K, MAT_COPY_VALUES, A));
  PetscCall(VecCopy(f, rhs));
  PetscCall(VecGetOwnershipRange(f, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(VecGetArray(rhs, &ra));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt     i = in[k], it = in[k] + 1;
    PetscInt           nn, nt;
    const PetscInt    *cn, *ctt;
    const PetscScalar *vn, *vt;
    PetscScalar       *row;

    PetscCall(MatGetRow(ctx->op.K, i, &nn, &cn, &vn));
    PetscCall(MatGetRow(ctx->op.K, it, &nt, &ctt, &vt));
    PetscCheck(nn == nt, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Rows of one node with different patterns");
    PetscCall(PetscMalloc1(nt, &row));
    for (PetscInt j = 0; j < nt; ++j) row[j] = vt[j] - mu * et * vn[j];
    PetscCall(MatSetValues(*A, 1, &it, nt, ctt, row, INSERT_VALUES));
    PetscCall(PetscFree(row));
    PetscCall(MatRestoreRow(ctx->op.K, it, &nt, &ctt, &vt));
    PetscCall(MatRestoreRow(ctx->op.K, i, &nn, &cn, &vn));
    ra[it - rstart] = fa[it - rstart] - mu * et * fa[i - rstart];
    ra[i - rstart]  = ga[k];
  }
  PetscCall(VecRestoreArray(rhs, &ra));
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  /* u_n = g, and the translation along the plane pinned at the first contact node */
  first = ct->n_local ? in[0] + 1 : PETSC_MAX_INT;
  PetscCall(MPIU_Allreduce(&first, &pin, 1, MPIU_INT, MPI_MIN, PetscObjectComm((PetscObject)f)));
  {
    PetscInt *rows, nr = 0;
    PetscCall(PetscMalloc1(ct->n_local + 1, &rows));
    for (PetscInt k = 0; k < ct->n_local; ++k) rows[nr++] = in[k];
    if (ct->n_local && in[0] + 1 == pin) rows[nr++] = pin;
    PetscCall(MatZeroRows(*A, nr, rows, 1.0, NULL, NULL));
    if (ct->n_local && in[0] + 1 == pin) PetscCall(VecSetValue(rhs, pin, 0.0, INSERT_VALUES));
    PetscCall(PetscFree(rows));
  }
  PetscCall(VecAssemblyBegin(rhs));
  PetscCall(VecAssemblyEnd(rhs));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* w = u_qs, and react = K w - f, the contact forces of the sliding state (normal and friction). */
PetscErrorCode MMInitialStaticSliding(MMCtx *ctx, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;
  MPI_Comm   comm = PetscObjectComm((PetscObject)ctx->op.dm);
  PetscReal  e[MM_MAX_DIM] = {0, 0, 0}, Fe = 0, P = 0, m = 0, a, et = 0, rmin;
  PetscBool  from_rest = PETSC_FALSE;
  Vec        f, rhs, me, rn;
  Mat        A;
  KSP        ksp;

  PetscFunctionBeginUser;
  PetscCheck(ct->enabled && ctx->op.dim == 2 && ctx->opt.n_dirichlet == 0, comm, PETSC_ERR_SUP, "-initial_state static_sliding needs contact on, a 2D body and no Dirichlet boundary");
  PetscCall(SlidingLoads(ctx, e, &Fe, &P, &m, &from_rest));
  a = (Fe - ctx->opt.mu * P) / m;
  /* from rest, a load that cannot overcome friction has no sliding state; the stuck equilibrium
   * is no static Coulomb state either (the base corners slip under the Poisson shear) */
  PetscCheck(!from_rest || a > 0, comm, PETSC_ERR_USER_INPUT, "-initial_state static_sliding from rest: the tangential load %g cannot overcome friction mu P = %g, so there is no sliding state. Start from -initial_state given", (double)Fe, (double)(ctx->opt.mu * P));
  for (PetscInt d = 0; d < 2; ++d) et += e[d] * ct->frame[1][d];
  /* f = L - m_i a e, the load in the frame sliding with the body */
  PetscCall(VecDuplicate(w, &f));
  PetscCall(VecDuplicate(w, &rhs));
  PetscCall(VecDuplicate(ctx->op.mass_lumped_cart, &me));
  PetscCall(VecCopy(ctx->op.mass_lumped_cart, me));
  for (PetscInt d = 0; d < 2; ++d) PetscCall(VecStrideScale(me, d, -a * e[d]));
  PetscCall(MMFEFromCartesian(ctx, me, f));
  PetscCall(VecAXPY(f, 1.0, ctx->op.load));
  PetscCall(SlidingSystem(ctx, et, f, &A, rhs));
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "sliding_"));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(MMKSPSetDirect(ksp));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, rhs, w));
  PetscCall(MatMult(ctx->op.K, w, react));
  PetscCall(VecAXPY(react, -1.0, f));
  PetscCall(VecISSet(react, ct->is_interior, 0.0));
  PetscCall(VecGetSubVector(react, ct->is_normal, &rn));
  PetscCall(VecMax(rn, NULL, &rmin)); /* react_n = -r_i: all reactions > 0 means max < 0 */
  PetscCall(VecRestoreSubVector(react, ct->is_normal, &rn));
  PetscCheck(rmin < 0, comm, PETSC_ERR_USER_INPUT, "The static sliding state has a base node without compressive reaction (r = %g): the body would lift off; it is not a sliding state", (double)-rmin);
  if (!ctx->opt.quiet) PetscCall(PetscPrintf(comm, "  static sliding state: rigid acceleration a = %g along (%g, %g)\n", (double)a, (double)e[0], (double)e[1]));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&me));
  PetscFunctionReturn(0);
}
