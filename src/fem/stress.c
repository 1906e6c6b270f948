/* The stress a user looks at first (docs/method.md section 5, "Stress"): sigma = lambda tr(eps) I +
 * 2 mu eps, eps = sym(grad u), constant on each P1 cell, and its L2 projection on the P1 space with
 * the lumped mass, sigma_v = sum_T |T| sigma_T / sum_T |T| over the cells T around vertex v, for
 * smooth plots; and the von Mises stress of the projected tensor. 2D is plane strain:
 * sigma_zz = lambda (eps_xx + eps_yy), sigma_xz = sigma_yz = 0. The tensor is written as XDMF's
 * Tensor6 (xx, xy, xz, yy, yz, zz), so ParaView shows it as a tensor in 2D and 3D. A uniform strain
 * gives the exact stress at every vertex: the projection of a constant is that constant. The cell
 * stress itself, and its von Mises value, are written too (cell fields, in the order of the cells
 * of the XDMF topology: each rank's cells in local order, the mesh being distributed without
 * overlap). With a finite-strain law (-elasticity svk, neohookean) it is the Cauchy stress of the
 * current configuration, plotted on the reference mesh (ParaView's Warp By Vector shows it deformed). */
#include "femimpl.h"

#define MM_SYM 6
#define MM_GEOM (MM_MAX_DIM * MM_MAX_DIM + 1) /* per cell: J^{-1} (row-major, MM_MAX_DIM wide), then |T| */

static PetscErrorCode StressGeometry(MMStress *st, MMOperators op);

/*@
  MMStressCreate - Creates the stress's DM, its vectors and each cell's geometry

  Collective

  Input Parameter:
. op - the operators

  Output Parameter:
. st - the stress, created

  Note:
  Once: the stress DM (6 components per vertex, no constraints), its vectors, each cell's geometry.

  Level: intermediate

.seealso: `MMStressCompute()`, `MMStressDestroy()`
@*/
PetscErrorCode MMStressCreate(MMOperators op, MMStress *st)
{
  const PetscInt dim = op->dim;
  const char    *names[MM_SYM] = {"stress_xx", "stress_xy", "stress_xz", "stress_yy", "stress_yz", "stress_zz"};
  PetscFE        fe;
  PetscSection   s;
  PetscInt       cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(DMClone(op->dm, &st->dm));
  PetscCall(PetscFECreateLagrange(PETSC_COMM_WORLD, dim, MM_SYM, PETSC_TRUE, 1, PETSC_DETERMINE, &fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "stress"));
  PetscCall(DMSetField(st->dm, 0, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  PetscCall(DMCreateDS(st->dm));
  PetscCall(DMGetLocalSection(st->dm, &s));
  for (PetscInt c = 0; c < MM_SYM; ++c) PetscCall(PetscSectionSetComponentName(s, 0, c, names[c]));
  PetscCall(DMCreateGlobalVector(st->dm, &st->nodal));
  PetscCall(PetscObjectSetName((PetscObject)st->nodal, "stress"));
  PetscCall(DMCreateGlobalVector(op->dm_scalar, &st->von_mises));
  PetscCall(PetscObjectSetName((PetscObject)st->von_mises, "von_mises"));
  PetscCall(DMCreateGlobalVector(op->dm_scalar, &st->weight));
  PetscCall(DMPlexGetHeightStratum(op->dm, 0, &cStart, &cEnd));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, MM_SYM * (cEnd - cStart), PETSC_DETERMINE, &st->cell));
  PetscCall(VecSetBlockSize(st->cell, MM_SYM));
  PetscCall(PetscObjectSetName((PetscObject)st->cell, "stress_cell"));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, cEnd - cStart, PETSC_DETERMINE, &st->von_mises_cell));
  PetscCall(PetscObjectSetName((PetscObject)st->von_mises_cell, "von_mises_cell"));
  PetscCall(StressGeometry(st, op));
  PetscFunctionReturn(0);
}

/* J: its columns the edges from vertex 0 of the cell with vertices x. */
static void EdgeMatrix(PetscInt dim, const PetscReal x[][MM_MAX_DIM], PetscReal J[MM_MAX_DIM][MM_MAX_DIM])
{
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) J[i][j] = x[j + 1][i] - x[0][i];
}

/* One cell's stress (MM_SYM, Tensor6 order) from its inverse edge matrix Ji (MM_GEOM layout) and
 * its vertices' Cartesian displacements u: grad u = D J^{-1}, D's columns the displacement
 * differences along the edges. */
static void CellStress(PetscInt dim, const PetscReal Ji[], const PetscReal u[][MM_MAX_DIM], PetscReal lambda, PetscReal mu, PetscReal s[MM_SYM])
{
  PetscReal e[3][3] = {{0}}, tr;

  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      PetscReal g = 0;
      for (PetscInt k = 0; k < dim; ++k) g += (u[k + 1][i] - u[0][i]) * Ji[MM_MAX_DIM * k + j];
      e[i][j] += 0.5 * g;
      e[j][i] += 0.5 * g;
    }
  tr   = e[0][0] + e[1][1] + e[2][2];
  s[0] = lambda * tr + 2 * mu * e[0][0];
  s[1] = 2 * mu * e[0][1];
  s[2] = 2 * mu * e[0][2];
  s[3] = lambda * tr + 2 * mu * e[1][1];
  s[4] = 2 * mu * e[1][2];
  s[5] = lambda * tr + 2 * mu * e[2][2]; /* 2D: plane strain, e_zz = 0 */
}

/* The finite-strain laws: the Cauchy stress of the current configuration, from F = I + grad u
 * (docs/method.md section 13); plane strain in 2D, with sigma_zz from F_zz = 1 */
static PetscErrorCode CellCauchy(PetscInt dim, const PetscReal Ji[], const PetscReal u[][MM_MAX_DIM], const MMMaterial *mat, PetscInt c, PetscReal s[MM_SYM])
{
  PetscReal G[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, sig[MM_MAX_DIM][MM_MAX_DIM];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j)
      for (PetscInt k = 0; k < dim; ++k) G[i][j] += (u[k + 1][i] - u[0][i]) * Ji[MM_MAX_DIM * k + j];
  PetscCall(MMElasticityCauchy(mat, c, MM_MAX_DIM, (const PetscReal(*)[MM_MAX_DIM])G, sig));
  s[0] = sig[0][0];
  s[1] = sig[0][1];
  s[2] = sig[0][2];
  s[3] = sig[1][1];
  s[4] = sig[1][2];
  s[5] = sig[2][2];
  PetscFunctionReturn(0);
}

static PetscReal VonMises(const PetscScalar s[MM_SYM])
{
  return PetscSqrtReal(0.5 * (PetscSqr(PetscRealPart(s[0] - s[3])) + PetscSqr(PetscRealPart(s[3] - s[5])) + PetscSqr(PetscRealPart(s[5] - s[0]))) + 3 * (PetscSqr(PetscRealPart(s[1])) + PetscSqr(PetscRealPart(s[2])) + PetscSqr(PetscRealPart(s[4]))));
}

/* Geometry only, computed once: each cell's inverse edge matrix and volume (st->geom), and the
 * lumped weights sum_T |T| of each vertex. */
static PetscErrorCode StressGeometry(MMStress *st, MMOperators op)
{
  const PetscInt     dim = op->dim;
  DM                 cdm;
  PetscSection       sw, sx;
  Vec                lw, X;
  const PetscScalar *xa;
  PetscScalar       *wa;
  PetscInt           cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(op->dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc1(MM_GEOM * (cEnd - cStart), &st->geom));
  PetscCall(DMGetLocalVector(op->dm_scalar, &lw));
  PetscCall(VecZeroEntries(lw));
  PetscCall(DMGetLocalSection(op->dm_scalar, &sw));
  PetscCall(DMGetCoordinateDM(op->dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &sx));
  PetscCall(DMGetCoordinatesLocal(op->dm, &X));
  PetscCall(VecGetArrayRead(X, &xa));
  PetscCall(VecGetArray(lw, &wa));
  for (PetscInt c = 0; c < cEnd - cStart; ++c) {
    const PetscInt *v = &op->cells.vertex[(dim + 1) * c]; /* simplices: MMCellsCreate checked */
    PetscReal      *g = &st->geom[MM_GEOM * c];
    PetscReal       x[MM_MAX_DIM + 1][MM_MAX_DIM] = {{0}}, J[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, Ji[MM_MAX_DIM][MM_MAX_DIM] = {{0}};
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscInt ox;
      PetscCall(PetscSectionGetOffset(sx, v[a], &ox));
      for (PetscInt d = 0; d < dim; ++d) x[a][d] = PetscRealPart(xa[ox + d]);
    }
    EdgeMatrix(dim, x, J);
    g[MM_GEOM - 1] = PetscAbsReal(MMDetInverse(dim, J, Ji)) / (dim == 2 ? 2.0 : 6.0);
    for (PetscInt i = 0; i < MM_MAX_DIM; ++i)
      for (PetscInt j = 0; j < MM_MAX_DIM; ++j) g[MM_MAX_DIM * i + j] = Ji[i][j];
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscInt ow;
      PetscCall(PetscSectionGetOffset(sw, v[a], &ow));
      wa[ow] += g[MM_GEOM - 1];
    }
  }
  PetscCall(VecRestoreArray(lw, &wa));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(VecZeroEntries(st->weight));
  PetscCall(DMLocalToGlobal(op->dm_scalar, lw, ADD_VALUES, st->weight));
  PetscCall(DMRestoreLocalVector(op->dm_scalar, &lw));
  PetscFunctionReturn(0);
}

/*@
  MMStressCompute - Computes the cell stress and von Mises stress of a displacement, and optionally
  the nodal ones

  Collective

  Input Parameters:
+ st    - the stress, created
. op    - the operators
. mat   - the bodies' material
. dm_u  - the DM of u, a clone of op's DM without constraints
. u     - the whole Cartesian displacement
- nodal - also compute the nodal values

  Note:
  The cell stress and von Mises of the displacement u (whole, Cartesian, a global vector of dm_u: a
  clone of op->dm without constraints), and with nodal, the nodal ones (a restart copies those from
  the old file).

  Level: intermediate

.seealso: `MMStressCreate()`, `MMElasticityCauchy()`
@*/
PetscErrorCode MMStressCompute(MMStress *st, MMOperators op, const MMMaterial *mat, DM dm_u, Vec u, PetscBool nodal)
{
  const PetscInt     dim = op->dim;
  PetscSection       su, ss;
  Vec                lu, ls;
  const PetscScalar *ua;
  PetscScalar       *sa, *wa, *vm, *sc, *vc;
  PetscInt           cStart, cEnd, n;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(dm_u, &lu));
  PetscCall(DMGlobalToLocal(dm_u, u, INSERT_VALUES, lu));
  PetscCall(DMGetLocalVector(st->dm, &ls));
  PetscCall(VecZeroEntries(ls));
  PetscCall(DMGetLocalSection(dm_u, &su));
  PetscCall(DMGetLocalSection(st->dm, &ss));
  PetscCall(DMPlexGetHeightStratum(op->dm, 0, &cStart, &cEnd));
  PetscCall(VecGetArrayRead(lu, &ua));
  PetscCall(VecGetArray(ls, &sa));
  PetscCall(VecGetArray(st->cell, &sc));
  PetscCall(VecGetArray(st->von_mises_cell, &vc));
  for (PetscInt c = 0; c < cEnd - cStart; ++c) {
    const PetscInt *v = &op->cells.vertex[(dim + 1) * c]; /* simplices: MMCellsCreate checked */
    const PetscReal *g   = &st->geom[MM_GEOM * c], vol = g[MM_GEOM - 1];
    PetscReal        u[MM_MAX_DIM + 1][MM_MAX_DIM] = {{0}}, s[MM_SYM];
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscInt ou;
      PetscCall(PetscSectionGetOffset(su, v[a], &ou));
      for (PetscInt d = 0; d < dim; ++d) u[a][d] = PetscRealPart(ua[ou + d]);
    }
    if (mat->finite) PetscCall(CellCauchy(dim, g, u, mat, c, s));
    else CellStress(dim, g, u, mat->lambda[c], mat->mu[c], s); /* each cell with its body's material */
    for (PetscInt k = 0; k < MM_SYM; ++k) sc[MM_SYM * c + k] = s[k];
    vc[c] = VonMises(&sc[MM_SYM * c]);
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscInt os;
      PetscCall(PetscSectionGetOffset(ss, v[a], &os));
      for (PetscInt k = 0; k < MM_SYM; ++k) sa[os + k] += vol * s[k];
    }
  }
  PetscCall(VecRestoreArray(st->von_mises_cell, &vc));
  PetscCall(VecRestoreArray(st->cell, &sc));
  PetscCall(VecRestoreArray(ls, &sa));
  PetscCall(VecRestoreArrayRead(lu, &ua));
  if (!nodal) {
    PetscCall(DMRestoreLocalVector(st->dm, &ls));
    PetscCall(DMRestoreLocalVector(dm_u, &lu));
    PetscFunctionReturn(0);
  }
  PetscCall(VecZeroEntries(st->nodal));
  PetscCall(DMLocalToGlobal(st->dm, ls, ADD_VALUES, st->nodal));
  PetscCall(DMRestoreLocalVector(st->dm, &ls));
  PetscCall(DMRestoreLocalVector(dm_u, &lu));
  /* the two DMs number the owned vertices alike: block i of the stress is vertex i of the weights */
  PetscCall(VecGetLocalSize(st->weight, &n));
  PetscCall(VecGetArray(st->nodal, &sa));
  PetscCall(VecGetArrayRead(st->weight, (const PetscScalar **)&wa));
  PetscCall(VecGetArray(st->von_mises, &vm));
  for (PetscInt i = 0; i < n; ++i) {
    PetscScalar *s = sa + MM_SYM * i;
    for (PetscInt k = 0; k < MM_SYM; ++k) s[k] /= wa[i];
    vm[i] = VonMises(s);
  }
  PetscCall(VecRestoreArray(st->von_mises, &vm));
  PetscCall(VecRestoreArrayRead(st->weight, (const PetscScalar **)&wa));
  PetscCall(VecRestoreArray(st->nodal, &sa));
  PetscFunctionReturn(0);
}

/*@
  MMStressDestroy - Frees the stress's DM and vectors

  Collective

  Input Parameter:
. st - the stress

  Level: intermediate

.seealso: `MMStressCreate()`
@*/
PetscErrorCode MMStressDestroy(MMStress *st)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&st->nodal));
  PetscCall(VecDestroy(&st->von_mises));
  PetscCall(VecDestroy(&st->weight));
  PetscCall(VecDestroy(&st->cell));
  PetscCall(VecDestroy(&st->von_mises_cell));
  PetscCall(DMDestroy(&st->dm));
  PetscCall(PetscFree(st->geom));
  PetscFunctionReturn(0);
}
