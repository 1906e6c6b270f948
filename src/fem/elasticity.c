/* The total Lagrangian P1 internal force of the finite-strain laws (docs/method.md section 13).
 *
 * On the reference mesh, F = I + grad u is constant per cell; a cell's algorithmic force on its
 * vertex a is |T| P_alg grad phi_a, with P_alg the law's algorithmic stress of the step
 * (src/fem/elasticity_laws.c). The vectors are local Cartesian vectors of the operators' DM with the
 * Dirichlet data inserted, so the boundary's motion enters the force as any other; the force is
 * returned on the free dofs in the w-frame, as the linear K w + lift is. */
#include "elasticityimpl.h"
#include "femimpl.h"
#include "assembly_p1.h"
#include "mesh.h"
#include <petscblaslapack.h>

#define MM_NV_MAX (MM_MAX_DIM + 1)
#define MM_KE_MAX (MM_NV_MAX * MM_MAX_DIM) /* a cell matrix's rows */

/* Once: each local cell's vertex offsets in the local vectors, P1 gradients and volume (the force is
 * evaluated several times per step: reading the sections and inverting the edge matrix each time
 * cost a third of it) */
static PetscErrorCode CellCache(MMElasticity *el, MMOperators op)
{
  const PetscInt     dim = op->dim, nc = op->cells.ncells;
  PetscSection       ls, cs;
  Vec                coords;
  const PetscScalar *xc;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2((dim + 1) * nc, &el->cell_off, MM_ELASTICITY_GEOM * nc, &el->cell_geom));
  PetscCall(DMGetLocalSection(op->dm, &ls));
  PetscCall(DMGetCoordinateSection(op->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(op->dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xc));
  for (PetscInt cl = 0; cl < nc; ++cl) {
    const PetscInt *v = &op->cells.vertex[(dim + 1) * cl];
    PetscReal       X[MM_NV_MAX][MM_MAX_DIM], g[MM_NV_MAX][MM_MAX_DIM], vol;
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscInt xo;
      PetscCall(PetscSectionGetOffset(cs, v[a], &xo));
      PetscCall(PetscSectionGetOffset(ls, v[a], &el->cell_off[(dim + 1) * cl + a]));
      for (PetscInt i = 0; i < dim; ++i) X[a][i] = PetscRealPart(xc[xo + i]);
    }
    PetscCall(MMP1CellGradients(dim, (const PetscReal(*)[MM_MAX_DIM])X, g, &vol));
    for (PetscInt a = 0; a <= dim; ++a)
      for (PetscInt i = 0; i < dim; ++i) el->cell_geom[MM_ELASTICITY_GEOM * cl + a * dim + i] = g[a][i];
    el->cell_geom[MM_ELASTICITY_GEOM * cl + (dim + 1) * dim] = vol;
  }
  PetscCall(VecRestoreArrayRead(coords, &xc));
  PetscFunctionReturn(0);
}

/*@
  MMElasticitySetUp - Creates the finite-strain force's scratch vectors and caches each local cell's
  dof offsets and geometry

  Collective

  Input Parameters:
+ el - the finite-strain elasticity
- op - the operators

  Level: intermediate

.seealso: `MMElasticityDestroy()`, `MMElasticityForce()`
@*/
PetscErrorCode MMElasticitySetUp(MMElasticity *el, MMOperators op)
{
  PetscFunctionBeginUser;
  el->clamp = PETSC_TRUE;
  PetscCall(DMCreateLocalVector(op->dm, &el->l0));
  PetscCall(VecDuplicate(el->l0, &el->l1));
  PetscCall(VecDuplicate(el->l0, &el->lf));
  PetscCall(DMCreateGlobalVector(op->dm, &el->g));
  PetscCall(CellCache(el, op));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityDestroy - Frees the finite-strain elasticity's vectors and caches

  Collective

  Input Parameter:
. el - the finite-strain elasticity

  Level: intermediate

.seealso: `MMElasticitySetUp()`
@*/
PetscErrorCode MMElasticityDestroy(MMElasticity *el)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&el->l0));
  PetscCall(VecDestroy(&el->l1));
  PetscCall(VecDestroy(&el->lf));
  PetscCall(VecDestroy(&el->g));
  PetscCall(PetscFree2(el->cell_off, el->cell_geom));
  PetscCall(PetscFree(el->G0));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityLocal - Gives the Cartesian local vector of a w-frame state with the Dirichlet data of
  a time inserted

  Collective

  Input Parameters:
+ el - the finite-strain elasticity
. op - the operators
. ld - the loads
. w  - the w-frame state
- t  - the Dirichlet data's time

  Output Parameter:
. l - the local vector

  Level: intermediate

.seealso: `MMElasticityForce()`, `MMLoadsInsertBoundaryValues()`
@*/
PetscErrorCode MMElasticityLocal(MMElasticity *el, MMOperators op, MMLoads *ld, Vec w, PetscReal t, Vec l)
{
  PetscFunctionBeginUser;
  PetscCall(MMFEToCartesian(op, w, el->g));
  PetscCall(VecZeroEntries(l));
  PetscCall(DMGlobalToLocal(op->dm, el->g, INSERT_VALUES, l));
  PetscCall(MMLoadsInsertBoundaryValues(ld, l, t));
  PetscFunctionReturn(0);
}

/* What the tangent's element callback reads: the cell cache, the material and the displacement */
typedef struct {
  const MMElasticity *el;
  MMOperators         op;
  const MMMaterial   *mat;
  const PetscScalar  *u;
} TangentData;

/* Cell cl's vertices' offsets in the local vectors, its P1 gradients and volume, from the cache */
static inline void CellGeometry(const MMElasticity *el, PetscInt dim, PetscInt cl, PetscInt off[], PetscReal g[][MM_MAX_DIM], PetscReal *vol)
{
  const PetscInt  *o = &el->cell_off[(dim + 1) * cl];
  const PetscReal *q = &el->cell_geom[MM_ELASTICITY_GEOM * cl];

  for (PetscInt a = 0; a <= dim; ++a) {
    off[a] = o[a];
    for (PetscInt i = 0; i < dim; ++i) g[a][i] = q[a * dim + i];
  }
  *vol = q[(dim + 1) * dim];
}

/* G = grad u = sum_a u_a (x) grad phi_a (the laws take G, not F = I + G: src/fem/elasticity_laws.c) */
static void DisplacementGradient(PetscInt dim, const PetscScalar *u, const PetscInt off[], const PetscReal g[][MM_MAX_DIM], PetscReal G[MM_MAX_DIM][MM_MAX_DIM])
{
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J) {
      G[i][J] = 0;
      for (PetscInt a = 0; a <= dim; ++a) G[i][J] += PetscRealPart(u[off[a] + i]) * g[a][J];
    }
}


static inline const MMElasticityOps *CellLaw(const MMMaterial *mat, PetscInt cl)
{
  return MMElasticityGetOps(mat->body[mat->cell_body[cl]].elasticity);
}


/*@
  MMElasticitySetStepStart - Keeps each local cell's displacement gradient at the step's start for
  the step's iterations

  Not collective

  Input Parameters:
+ el - the finite-strain elasticity
. op - the operators
- l0 - the step's start (MMElasticityLocal())

  Note:
  G0 of every local cell at the step's start, kept for the step's iterations (elasticity.c)

  Level: intermediate

.seealso: `MMElasticityForce()`, `MMElasticityDissipation()`
@*/
PetscErrorCode MMElasticitySetStepStart(MMElasticity *el, MMOperators op, Vec l0)
{
  const PetscInt     dim = op->dim;
  const PetscScalar *u;

  PetscFunctionBeginUser;
  if (!el->G0) PetscCall(PetscMalloc1(MM_MAX_DIM * MM_MAX_DIM * op->cells.ncells, &el->G0));
  PetscCall(VecGetArrayRead(l0, &u));
  for (PetscInt cl = 0; cl < op->cells.ncells; ++cl) {
    PetscInt  off[MM_NV_MAX];
    PetscReal g[MM_NV_MAX][MM_MAX_DIM], vol;
    CellGeometry(el, dim, cl, off, g, &vol);
    DisplacementGradient(dim, u, off, (const PetscReal(*)[MM_MAX_DIM])g, (PetscReal(*)[MM_MAX_DIM])&el->G0[MM_MAX_DIM * MM_MAX_DIM * cl]);
  }
  PetscCall(VecRestoreArrayRead(l0, &u));
  PetscFunctionReturn(0);
}

/* The cells' forces into the local array f, dim a constant once inlined so that the small loops unroll:
 * of the step from the kept G0 (step) or of the state u1 itself (its P(F), no viscous part); mag:
 * their magnitudes |f_e| summed instead, the round-off scale of the sum */
static inline void ForceCells(const PetscInt dim, const MMElasticity *el, const MMMaterial *mat, PetscInt ncells, PetscBool step, PetscBool mag, const PetscScalar *u1, PetscScalar *f)
{
  for (PetscInt cl = 0; cl < ncells; ++cl) {
    const PetscInt  *off = &el->cell_off[(dim + 1) * cl];
    const PetscReal *q = &el->cell_geom[MM_ELASTICITY_GEOM * cl], vol = q[(dim + 1) * dim];
    const PetscReal *g0 = step ? &el->G0[MM_MAX_DIM * MM_MAX_DIM * cl] : NULL;
    PetscReal        G0[MM_MAX_DIM][MM_MAX_DIM], G1[MM_MAX_DIM][MM_MAX_DIM], P[MM_MAX_DIM][MM_MAX_DIM];

    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt J = 0; J < dim; ++J) {
        PetscReal t = 0;
        for (PetscInt a = 0; a <= dim; ++a) t += PetscRealPart(u1[off[a] + i]) * q[a * dim + J];
        G1[i][J] = t;
        G0[i][J] = step ? g0[MM_MAX_DIM * i + J] : t;
      }
    CellLaw(mat, cl)->stress_alg(dim, mat->lambda[cl], mat->mu[cl], step ? el->visc : 0, (const PetscReal(*)[MM_MAX_DIM])G0, (const PetscReal(*)[MM_MAX_DIM])G1, P);
    for (PetscInt a = 0; a <= dim; ++a)
      for (PetscInt i = 0; i < dim; ++i) {
        PetscReal r = 0;
        for (PetscInt J = 0; J < dim; ++J) r += P[i][J] * q[a * dim + J];
        f[off[a] + i] += mag ? PetscAbsReal(vol * r) : vol * r;
      }
  }
}

/* el->lf = the cells' forces, unassembled: of the step from the kept start to l1, or of the state l1 */
static PetscErrorCode LocalForce(MMElasticity *el, MMOperators op, const MMMaterial *mat, PetscBool step, PetscBool mag, Vec l1)
{
  const PetscScalar *u1;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCheck(el->G0 || !step, PETSC_COMM_SELF, PETSC_ERR_ORDER, "MMElasticitySetStepStart() must come first");
  PetscCall(VecGetArrayRead(l1, &u1));
  PetscCall(VecZeroEntries(el->lf));
  PetscCall(VecGetArray(el->lf, &f));
  if (op->dim == 2) ForceCells(2, el, mat, op->cells.ncells, step, mag, u1, f);
  else ForceCells(3, el, mat, op->cells.ncells, step, mag, u1, f);
  PetscCall(VecRestoreArray(el->lf, &f));
  PetscCall(VecRestoreArrayRead(l1, &u1));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityForceLocal - Computes the internal force P(F) of a state itself into el->lf,
  unassembled, leaving the step's start as it is

  Not collective

  Input Parameters:
+ el  - the finite-strain elasticity, el->lf set on return
. op  - the operators
. mat - the bodies' material
- l   - the state (MMElasticityLocal())

  Note:
  The force P(F) of the state l itself (the step from l to l): for the Dirichlet supports' reactions,
  between the step and its audits, so the step's kept start G0 is left as it is

  Level: developer

.seealso: `MMElasticityForce()`, `MMLoadsSetElasticity()`
@*/
PetscErrorCode MMElasticityForceLocal(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_FE_ElasticForce, 0, 0, 0, 0));
  PetscCall(LocalForce(el, op, mat, PETSC_FALSE, PETSC_FALSE, l));
  PetscCall(PetscLogEventEnd(MM_FE_ElasticForce, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityForce - Computes the algorithmic internal force of the step from its start to a state,
  in the w-frame

  Collective

  Input Parameters:
+ el  - the finite-strain elasticity, its step start set
. op  - the operators
. mat - the bodies' material
- l1  - the state (MMElasticityLocal())

  Output Parameter:
. fw - the force on the free dofs (w-frame)

  Note:
  fw = the algorithmic force of the step from the start set by MMElasticitySetStepStart to l1

  Level: intermediate

.seealso: `MMElasticitySetStepStart()`, `MMElasticityForceLocal()`, `MMElasticityAssembleTangent()`
@*/
PetscErrorCode MMElasticityForce(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l1, Vec fw)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_FE_ElasticForce, 0, 0, 0, 0));
  PetscCall(LocalForce(el, op, mat, PETSC_TRUE, PETSC_FALSE, l1));
  PetscCall(VecZeroEntries(el->g));
  PetscCall(DMLocalToGlobal(op->dm, el->lf, ADD_VALUES, el->g)); /* the Dirichlet dofs drop out */
  PetscCall(MMFEForceFromCartesian(op, el->g, fw));
  PetscCall(PetscLogEventEnd(MM_FE_ElasticForce, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityForceMagnitude - Computes, per dof, the sum of the magnitudes of the cells' forces of a
  state: the round-off scale of its internal force

  Collective

  Input Parameters:
+ el  - the finite-strain elasticity
. op  - the operators
. mat - the bodies' material
- l   - the state (MMElasticityLocal())

  Output Parameter:
. sw - sum_e |f_e,i| on the free dofs (w-frame components, taken in magnitude)

  Note:
  A slender part's internal force is a small difference of large element forces: its rounding is
  eps times these sums, not eps times the force (the static start's stop, docs/method.md section 13)

  Level: developer

.seealso: `MMElasticityForce()`, `MMElasticityForceLocal()`
@*/
PetscErrorCode MMElasticityForceMagnitude(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, Vec sw)
{
  PetscFunctionBeginUser;
  PetscCall(LocalForce(el, op, mat, PETSC_FALSE, PETSC_TRUE, l));
  PetscCall(VecZeroEntries(el->g));
  PetscCall(DMLocalToGlobal(op->dm, el->lf, ADD_VALUES, el->g));
  PetscCall(MMFEForceFromCartesian(op, el->g, sw));
  PetscCall(VecAbs(sw));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityEnergy - Computes the elastic energy of a state with each cell's law

  Collective

  Input Parameters:
+ el  - the finite-strain elasticity
. op  - the operators
. mat - the bodies' material
- l   - the state (MMElasticityLocal())

  Output Parameter:
. energy - the elastic energy (all ranks)

  Level: intermediate

.seealso: `MMElasticityDissipation()`, `MMElasticityForce()`
@*/
PetscErrorCode MMElasticityEnergy(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, PetscReal *energy)
{
  const PetscInt     dim = op->dim;
  const PetscScalar *u;
  PetscReal          e = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_FE_ElasticEnergy, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(l, &u));
  for (PetscInt cl = 0; cl < op->cells.ncells; ++cl) {
    PetscInt  off[MM_NV_MAX];
    PetscReal g[MM_NV_MAX][MM_MAX_DIM], vol, G[MM_MAX_DIM][MM_MAX_DIM];

    CellGeometry(el, dim, cl, off, g, &vol);
    DisplacementGradient(dim, u, off, (const PetscReal(*)[MM_MAX_DIM])g, G);
    e += vol * CellLaw(mat, cl)->energy(dim, mat->lambda[cl], mat->mu[cl], (const PetscReal(*)[MM_MAX_DIM])G);
  }
  PetscCall(VecRestoreArrayRead(l, &u));
  PetscCall(MPIU_Allreduce(&e, energy, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)op->dm)));
  PetscCall(PetscLogEventEnd(MM_FE_ElasticEnergy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityDissipation - Computes the sum over the cells of |T| dE : D : dE, each cell's law's
  dissipation, for the step from its start to a state

  Collective

  Input Parameters:
+ el  - the finite-strain elasticity, its step start set
. op  - the operators
. mat - the bodies' material
- l1  - the state (MMElasticityLocal())

  Output Parameter:
. d - the sum (all ranks)

  Level: developer

.seealso: `MMElasticitySetStepStart()`, `MMElasticityEnergy()`
@*/
PetscErrorCode MMElasticityDissipation(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l1, PetscReal *d)
{
  const PetscInt     dim = op->dim;
  const PetscScalar *u;
  PetscReal          e = 0;

  PetscFunctionBeginUser;
  PetscCheck(el->G0, PETSC_COMM_SELF, PETSC_ERR_ORDER, "MMElasticitySetStepStart() must come first");
  PetscCall(VecGetArrayRead(l1, &u));
  for (PetscInt cl = 0; cl < op->cells.ncells; ++cl) {
    PetscInt  off[MM_NV_MAX];
    PetscReal g[MM_NV_MAX][MM_MAX_DIM], vol, G[MM_MAX_DIM][MM_MAX_DIM];

    CellGeometry(el, dim, cl, off, g, &vol);
    DisplacementGradient(dim, u, off, (const PetscReal(*)[MM_MAX_DIM])g, G);
    e += vol * CellLaw(mat, cl)->dissipation(dim, mat->lambda[cl], mat->mu[cl], (const PetscReal(*)[MM_MAX_DIM]) & el->G0[MM_MAX_DIM * MM_MAX_DIM * cl], (const PetscReal(*)[MM_MAX_DIM])G);
  }
  PetscCall(VecRestoreArrayRead(l1, &u));
  PetscCall(MPIU_Allreduce(&e, d, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)op->dm)));
  PetscFunctionReturn(0);
}

/* The cell matrix Ke (n x n, symmetric) made positive semi-definite: its negative eigenvalues set to 0
 * (LAPACK syev), the closest such matrix. A compressed cell's geometric stiffness is indefinite; leaving
 * out the whole of it (as the tangent did before issue 50) also drops the stiffness of the directions the
 * cell is stretched in, and the iteration matrix is then softer than the force along the massless
 * contact rows, which no mass term steadies: the iteration overshoots and diverges (docs/method.md
 * section 13, "The iteration matrix"). Only the cell's negative modes are left out here. */
static PetscErrorCode ClampNegativeEigenvalues(PetscInt n, PetscScalar Ke[])
{
  PetscScalar  V[MM_KE_MAX * MM_KE_MAX], work[8 * MM_KE_MAX];
  PetscReal    ev[MM_KE_MAX];
  PetscBLASInt bn, lwork = 8 * MM_KE_MAX, info;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n * n; ++i) V[i] = Ke[i];
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, V, &bn, ev, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (%d) on a cell's tangent", (int)info);
  for (PetscInt i = 0; i < n * n; ++i) Ke[i] = 0;
  for (PetscInt e = 0; e < n; ++e) { /* column e of V (column-major) is the eigenvector of ev[e] */
    if (ev[e] <= 0) continue;
    for (PetscInt r = 0; r < n; ++r)
      for (PetscInt c = 0; c < n; ++c) Ke[r * n + c] += ev[e] * V[e * n + r] * V[e * n + c];
  }
  PetscFunctionReturn(0);
}

/* Whether the cell's tangent A, as the symmetric dim^2 x dim^2 matrix A[(i J)][(k L)], is positive
 * definite, by a Cholesky factorization whose pivots stay above 1e-10 of the largest diagonal entry.
 * The cell matrix is |T| B^T A B with B onto every displacement gradient, so A definite makes it
 * semi-definite: a compressed cell whose geometric term the material term outweighs (nearly all of
 * them at moderate strains) needs no eigen-decomposition (ClampNegativeEigenvalues). */
static PetscBool TangentIsDefinite(PetscInt dim, const MMTangent A)
{
  const PetscInt m = dim * dim;
  PetscReal      L[MM_MAX_DIM * MM_MAX_DIM][MM_MAX_DIM * MM_MAX_DIM], dmax = 0;

  for (PetscInt p = 0; p < m; ++p)
    for (PetscInt q = 0; q < m; ++q) L[p][q] = A[p / dim][p % dim][q / dim][q % dim];
  for (PetscInt p = 0; p < m; ++p) dmax = PetscMax(dmax, L[p][p]);
  for (PetscInt j = 0; j < m; ++j) {
    PetscReal d = L[j][j];
    for (PetscInt k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    if (!(d > 1e-10 * dmax)) return PETSC_FALSE;
    L[j][j] = PetscSqrtReal(d);
    for (PetscInt i = j + 1; i < m; ++i) {
      PetscReal t = L[i][j];
      for (PetscInt k = 0; k < j; ++k) t -= L[i][k] * L[j][k];
      L[i][j] = t / L[j][j];
    }
  }
  return PETSC_TRUE;
}

/* The tangent's element matrix: K_e[a i][b k] = |T| grad phi_a,J A_iJkL grad phi_b,L, with the cell's
 * offsets and gradients from the cache (the assembler's own g and vol are the same);
 * a compressed cell's made semi-definite (ClampNegativeEigenvalues) where el->clamp asks for it */
static PetscErrorCode TangentElement(void *ctx, PetscInt c, const PetscInt v[], const PetscReal g_unused[][MM_MAX_DIM], PetscReal vol_unused, PetscScalar Ke[])
{
  const TangentData *td  = (const TangentData *)ctx;
  const PetscInt     dim = td->op->dim, n = (dim + 1) * dim, cl = c - td->op->cells.cStart;
  PetscInt           off[MM_NV_MAX];
  PetscReal          g[MM_NV_MAX][MM_MAX_DIM], vol, G[MM_MAX_DIM][MM_MAX_DIM];
  MMTangent          A;
  PetscBool          definite;

  PetscFunctionBeginUser;
  (void)v;
  (void)g_unused;
  (void)vol_unused;
  CellGeometry(td->el, dim, cl, off, g, &vol);
  DisplacementGradient(dim, td->u, off, (const PetscReal(*)[MM_MAX_DIM])g, G);
  CellLaw(td->mat, cl)->tangent(dim, td->mat->lambda[cl], td->mat->mu[cl], (const PetscReal(*)[MM_MAX_DIM])G, A, &definite);
  for (PetscInt a = 0; a <= dim; ++a) {
    PetscReal ga[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM]; /* vol g_a,J A_iJkL, then contracted with each g_b */
    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt L = 0; L < dim; ++L) {
          PetscReal t = 0;
          for (PetscInt J = 0; J < dim; ++J) t += g[a][J] * A[i][J][k][L];
          ga[i][k][L] = vol * t;
        }
    for (PetscInt b = 0; b <= dim; ++b)
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt k = 0; k < dim; ++k) {
          PetscReal t = 0;
          for (PetscInt L = 0; L < dim; ++L) t += ga[i][k][L] * g[b][L];
          Ke[(a * dim + i) * n + b * dim + k] = t;
        }
  }
  if (!definite && td->el->clamp && !td->el->consistent && !TangentIsDefinite(dim, (const PetscReal(*)[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM])A)) PetscCall(ClampNegativeEigenvalues(n, Ke)); /* the static start's Newton takes dP/dF itself */
  PetscFunctionReturn(0);
}

/*@
  MMElasticityAssembleTangent - Assembles the tangent dP/dF at a state on the Cartesian dofs

  Collective

  Input Parameters:
+ el  - the finite-strain elasticity
. op  - the operators
. mat - the bodies' material
. l   - the state (MMElasticityLocal())
- Kc  - a P1 matrix of op's DM pattern, assembled on return

  Level: intermediate

.seealso: `MMContactFrameMatrixBegin()`, `MMContactFrameMatrixEnd()`, `MMElasticityForce()`
@*/
PetscErrorCode MMElasticityAssembleTangent(MMElasticity *el, MMOperators op, const MMMaterial *mat, Vec l, Mat Kc)
{
  TangentData td = {.el = el, .op = op, .mat = mat};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_FE_ElasticTangent, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(l, &td.u));
  PetscCall(MMAssembleP1Elements(op->dm, Kc, TangentElement, &td));
  PetscCall(VecRestoreArrayRead(l, &td.u));
  PetscCall(PetscLogEventEnd(MM_FE_ElasticTangent, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMElasticityCauchy - Computes the Cauchy stress of a cell at a displacement gradient with the
  cell's law

  Not collective

  Input Parameters:
+ mat - the bodies' material
. cl  - the local cell
. dim - the dimension
- G   - the displacement gradient

  Output Parameter:
. sigma - the Cauchy stress

  Level: developer

.seealso: `MMStressCompute()`
@*/
PetscErrorCode MMElasticityCauchy(const MMMaterial *mat, PetscInt cl, PetscInt dim, const PetscReal G[MM_MAX_DIM][MM_MAX_DIM], PetscReal sigma[MM_MAX_DIM][MM_MAX_DIM])
{
  PetscFunctionBeginUser;
  CellLaw(mat, cl)->cauchy(dim, mat->lambda[cl], mat->mu[cl], G, sigma);
  PetscFunctionReturn(0);
}
