/* P1 elasticity: discretization, boundary conditions, and the Cartesian operators K, M, L and the lift
 * (contact's frame, src/contact/frame/, turns them into the w-frame ones). */
#include <float.h>
#include "femimpl.h"
#include "assembly_p1.h"
#include "elasticityimpl.h"

/* fem's events (MMFEInitializePackage): the operators' assembly (from MMFEAssembleOperators to
 * MMFEAssembleOperatorsEnd, contact's frame included), the Cartesian K and M alone by the selected
 * -assembly path */
static PetscLogEvent MM_FEAssemble, MM_FEAssembleKM, MM_FEPreallocate, MM_FELoads;
/* the finite-strain laws' force, energy and tangent (elasticity.c) */
PetscLogEvent MM_FE_ElasticForce, MM_FE_ElasticEnergy, MM_FE_ElasticTangent;

/*@
  MMFEInitializePackage - Registers fem's class and its logging events, once

  Not collective

  Note:
  fem's class and events, registered once (as KSPInitializePackage)

  Level: developer

.seealso: `MMFESetUp()`, `MMContactInitializePackage()`
@*/
PetscErrorCode MMFEInitializePackage(void)
{
  static PetscBool initialized = PETSC_FALSE;
  PetscClassId     id;

  PetscFunctionBeginUser;
  if (initialized) PetscFunctionReturn(0);
  initialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MMFE", &id));
  PetscCall(PetscLogEventRegister("MMFEAssemble", id, &MM_FEAssemble));
  PetscCall(PetscLogEventRegister("MMFEPreallocate", id, &MM_FEPreallocate));
  PetscCall(PetscLogEventRegister("MMAssembleKM", id, &MM_FEAssembleKM));
  PetscCall(PetscLogEventRegister("MMFELoads", id, &MM_FELoads));
  PetscCall(PetscLogEventRegister("MMElasticForce", id, &MM_FE_ElasticForce));
  PetscCall(PetscLogEventRegister("MMElasticEnergy", id, &MM_FE_ElasticEnergy));
  PetscCall(PetscLogEventRegister("MMElasticTangent", id, &MM_FE_ElasticTangent));
  PetscFunctionReturn(0);
}

/* Field layout of every kernel: one field u (displacement), dim components, P1.
 * constants[] = {lambda, mu, rho, w_K, w_M, g_x, g_y, g_z} (MMConstantIndex). The weights select
 * the matrix an assembly produces, w_K K + w_M M, since PetscDS cannot unset a kernel. */

/* Internal force: f1 = sigma(u) = lambda tr(eps) I + 2 mu eps */
static void f1_elas_u(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar f1[])
{
  const PetscReal lambda = PetscRealPart(constants[MM_C_LAMBDA]), mu = PetscRealPart(constants[MM_C_MU]);
  PetscScalar     tr     = 0;
  for (PetscInt c = 0; c < dim; ++c) tr += u_x[c * dim + c];
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) f1[c * dim + d] = mu * (u_x[c * dim + d] + u_x[d * dim + c]) + (c == d ? lambda * tr : 0.0);
}

/* Stiffness: the derivative of f1_elas_u with respect to grad u */
static void g3_elas_uu(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g3[])
{
  const PetscReal w = PetscRealPart(constants[MM_C_WEIGHT_K]);
  const PetscReal lambda = w * PetscRealPart(constants[MM_C_LAMBDA]), mu = w * PetscRealPart(constants[MM_C_MU]);
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt f = 0; f < dim; ++f)
      for (PetscInt d = 0; d < dim; ++d)
        for (PetscInt e = 0; e < dim; ++e) g3[((c * dim + f) * dim + d) * dim + e] = (c == f && d == e ? mu : 0) + (c == e && d == f ? mu : 0) + (c == d && f == e ? lambda : 0);
}

/* Consistent mass: rho delta_cf */
static void g0_mass_uu(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g0[])
{
  for (PetscInt c = 0; c < dim; ++c) g0[c * dim + c] = constants[MM_C_WEIGHT_M] * constants[MM_C_RHO];
}

/* Elastic energy density 1/2 sigma(u) : eps(u) */
static void obj_elastic_energy(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar obj[])
{
  const PetscReal lambda = PetscRealPart(constants[MM_C_LAMBDA]), mu = PetscRealPart(constants[MM_C_MU]);
  PetscScalar     tr = 0, ee = 0;
  for (PetscInt c = 0; c < dim; ++c) tr += u_x[c * dim + c];
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) ee += 0.25 * PetscSqr(u_x[c * dim + d] + u_x[d * dim + c]);
  obj[0] = mu * ee + 0.5 * lambda * tr * tr;
}

static PetscErrorCode DirichletEnergy(MMOperators op, const MMMaterial *mat);

/* Dirichlet data: value a(t) + velocity t per fixed component (docs/method.md section 10); ctx is
 * the MMDirichlet. Without an amplitude or a velocity the value is exactly the constant one. */
static PetscErrorCode bc_constant(PetscInt dim, PetscReal time, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ctx)
{
  const MMDirichlet *bc = (const MMDirichlet *)ctx;
  const PetscReal    a  = bc->amp ? MMAmplitudeValue(bc->amp, time) : 1.0;
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0;
  for (PetscInt c = 0; c < bc->ncomp; ++c) u[bc->comps[c]] = bc->nvelocity > 0 ? bc->values[c] * a + bc->velocity[c] * time : bc->values[c] * a;
  return 0;
}

/* The single value a physical group carries in its label (its gmsh tag), agreed over ranks. */
static PetscErrorCode LabelValue(DM dm, DMLabel label, PetscInt *value)
{
  IS              vis;
  PetscInt        n, v = PETSC_MIN_INT;
  const PetscInt *vals;

  PetscFunctionBeginUser;
  PetscCall(DMLabelGetValueIS(label, &vis));
  PetscCall(ISGetLocalSize(vis, &n));
  PetscCall(ISGetIndices(vis, &vals));
  for (PetscInt i = 0; i < n; ++i) v = PetscMax(v, vals[i]);
  PetscCall(ISRestoreIndices(vis, &vals));
  PetscCall(ISDestroy(&vis));
  PetscCall(MPIU_Allreduce(&v, value, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUpDirichlet(MMOperators op, const MMFEProblem *pb)
{
  DM dm = op->dm;

  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < pb->n_dirichlet; ++b) {
    MMDirichlet *bc = &pb->dirichlet[b];
    DMLabel      label;
    PetscInt     value;

    PetscCall(MMMeshGetLabel(dm, bc->name, &label));
    PetscCall(LabelValue(dm, label, &value));
    PetscCall(DMAddBoundary(dm, DM_BC_ESSENTIAL, bc->name, label, 1, &value, 0, bc->ncomp, bc->comps, (void (*)(void))bc_constant, NULL, bc, NULL));
  }
  PetscFunctionReturn(0);
}

/* The PetscDS constants: the material of the first body, which is every cell's when the material is
 * uniform (the PetscFE kernels then hold it; otherwise they are not used for it, src/fem/material.c),
 * and the wave speed of the CFL number, the largest of the bodies'. */
static PetscErrorCode SetConstants(MMOperators op, const MMMaterial *mat, const MMFEProblem *pb)
{
  const MMBody *b = &mat->body[0];

  PetscFunctionBeginUser;
  op->constants[MM_C_LAMBDA] = b->lambda;
  op->constants[MM_C_MU]     = b->mu;
  op->constants[MM_C_RHO]    = b->rho;
  op->constants[MM_C_WEIGHT_K] = 1.0;
  op->constants[MM_C_WEIGHT_M] = 0.0;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) op->constants[MM_C_GRAVITY + d] = pb->gravity[d];
  op->c_p = mat->c_p_max;
  PetscFunctionReturn(0);
}

/*@
  MMFESetUp - Sets up the discretization: the cells, each cell's material, the P1 displacement field
  with its Dirichlet constraints, and the scalar vertex DM

  Collective

  Input Parameters:
+ op  - the operators, their DM set (MMFESetDM()) and options read
. mat - the material, set up from pb
- pb  - the problem as the user described it

  Note:
  Creates the P1 vector field, the Dirichlet constraints and the scalar vertex DM used for masses and output.

  Level: beginner

.seealso: `MMFECreate()`, `MMFESetDM()`, `MMFESetFromOptions()`, `MMFEAssembleOperators()`, `MMMaterialSetUp()`, `MMFEDestroy()`
@*/
PetscErrorCode MMFESetUp(MMOperators op, MMMaterial *mat, const MMFEProblem *pb)
{
  DM           dm = op->dm;
  PetscFE      fe;
  PetscDS      ds;
  PetscInt     dim;
  PetscSection s;
  const char  *names[] = {"displacement_x", "displacement_y", "displacement_z"};

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  op->dim = dim;
  PetscCall(MMCellsCreate(dm, &op->cells));
  PetscCall(MMFEInitializePackage());
  PetscCall(MMMaterialSetUp(mat, op, pb));
  PetscCall(SetConstants(op, mat, pb));
  PetscCall(PetscFECreateLagrange(PetscObjectComm((PetscObject)dm), dim, dim, PETSC_TRUE, 1, PETSC_DETERMINE, &fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "displacement"));
  PetscCall(DMSetField(dm, 0, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  PetscCall(DMCreateDS(dm));
  PetscCall(DMGetDS(dm, &ds));
  PetscCall(PetscDSSetConstants(ds, MM_C_NUM, op->constants));
  PetscCall(PetscDSSetResidual(ds, 0, NULL, f1_elas_u));
  PetscCall(PetscDSSetObjective(ds, 0, obj_elastic_energy));
  PetscCall(SetUpDirichlet(op, pb));
  PetscCall(DMGetLocalSection(dm, &s));
  for (PetscInt c = 0; c < dim; ++c) PetscCall(PetscSectionSetComponentName(s, 0, c, names[c]));

  /* one P1 scalar per vertex, no constraints: lumped masses, contact pressure and gap */
  {
    DM      dms;
    PetscFE fes;

    PetscCall(DMClone(dm, &dms));
    PetscCall(PetscFECreateLagrange(PetscObjectComm((PetscObject)dm), dim, 1, PETSC_TRUE, 1, PETSC_DETERMINE, &fes));
    PetscCall(PetscObjectSetName((PetscObject)fes, "nodal"));
    PetscCall(DMSetField(dms, 0, NULL, (PetscObject)fes));
    PetscCall(PetscFEDestroy(&fes));
    PetscCall(DMCreateDS(dms));
    op->dm_scalar = dms;
  }
  PetscFunctionReturn(0);
}

/* Lumped mass per vertex, int rho phi_i = sum_T rho_T |T| / (d+1): exact row sums of the consistent
 * mass, Dirichlet columns included. */
static PetscErrorCode VertexMasses(MMOperators op, const MMMaterial *mat, Vec mloc)
{
  DM             dms   = op->dm_scalar;
  const MMCells *cells = &op->cells;
  PetscInt       dim   = op->dim;
  Vec            mglob;
  PetscScalar   *m;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(mloc));
  PetscCall(VecGetArray(mloc, &m));
  for (PetscInt c = 0; c < cells->ncells; ++c) {
    const PetscReal mv = mat->rho[c] * cells->volume[c] / (dim + 1);
    for (PetscInt a = 0; a < cells->nv; ++a) {
      PetscInt off, end;
      PetscCall(DMPlexGetPointLocal(dms, cells->vertex[cells->nv * c + a], &off, &end));
      m[off] += mv;
    }
  }
  PetscCall(VecRestoreArray(mloc, &m));
  PetscCall(DMGetGlobalVector(dms, &mglob));
  PetscCall(VecZeroEntries(mglob));
  PetscCall(DMLocalToGlobal(dms, mloc, ADD_VALUES, mglob));
  PetscCall(DMGlobalToLocal(dms, mglob, INSERT_VALUES, mloc));
  PetscCall(DMRestoreGlobalVector(dms, &mglob));
  PetscFunctionReturn(0);
}

/*@
  MMFEVertexMasses - Computes the lumped mass of each vertex

  Collective

  Input Parameters:
+ op  - the operators
- mat - the bodies' material

  Output Parameter:
. mloc - the masses, a local vector of the scalar vertex DM

  Note:
  The lumped mass per vertex on the scalar DM's local vector (gravity's load part, src/fem/loads.c).

  Level: developer

.seealso: `MMFEAddTraction()`, `MMLoadsSetUp()`
@*/
PetscErrorCode MMFEVertexMasses(MMOperators op, const MMMaterial *mat, Vec mloc)
{
  PetscFunctionBeginUser;
  PetscCall(VertexMasses(op, mat, mloc));
  PetscFunctionReturn(0);
}

/* Spreads a per-vertex scalar onto every free dof of that vertex, times a per-component factor. */
static PetscErrorCode SpreadVertexScalar(MMOperators op, Vec sloc, const PetscReal factor[], Vec g)
{
  DM                 dm = op->dm;
  PetscSection       gs, ls;
  PetscInt           vStart, vEnd, dim = op->dim;
  const PetscScalar *s;
  PetscScalar       *a;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
  PetscCall(VecGetArrayRead(sloc, &s));
  PetscCall(VecGetArray(g, &a));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, soff, ncdof;
    const PetscInt *cidx;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(DMPlexGetPointLocal(op->dm_scalar, v, &soff, NULL));
    PetscCall(PetscSectionGetConstraintDof(ls, v, &ncdof));
    PetscCall(PetscSectionGetConstraintIndices(ls, v, &cidx));
    for (PetscInt c = 0, k = 0; c < dim; ++c) {
      PetscBool fixed = PETSC_FALSE;
      for (PetscInt j = 0; j < ncdof; ++j) fixed = (PetscBool)(fixed || cidx[j] == c);
      if (fixed) continue;
      a[goff - rstart + k++] = s[soff] * factor[c];
    }
  }
  PetscCall(VecRestoreArray(g, &a));
  PetscCall(VecRestoreArrayRead(sloc, &s));
  PetscFunctionReturn(0);
}

/* A traction acts on faces: a group of cells (the body) or of lower-dimensional points would load
 * nothing, silently. */
static PetscErrorCode CheckTractionGroup(DM dm, const char name[], DMLabel label, const MMFacetList *fl)
{
  PetscInt  counts[2] = {fl->n, 0}; /* facets, cells */
  PetscBool holds;

  PetscFunctionBeginUser;
  PetscCall(MMMeshLabelHoldsCells(dm, label, &holds));
  counts[1] = holds;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCheck(!counts[1], PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "-traction %s: the physical group \"%s\" holds cells, not boundary faces. A traction acts on a Physical %s of the boundary", name, name, fl->dim == 2 ? "Curve (2D)" : "Surface (3D)");
  PetscCheck(counts[0], PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "-traction %s: the physical group \"%s\" holds no faces. A traction acts on a Physical %s of the boundary", name, name, fl->dim == 2 ? "Curve (2D)" : "Surface (3D)");
  PetscFunctionReturn(0);
}

/*@
  MMFEAddTraction - Adds a traction's nodal loads to a local force vector

  Not collective

  Input Parameters:
+ op   - the operators
. tr   - the traction group
- floc - the local Cartesian force vector, added to

  Note:
  Nodal loads of traction b: int_F t phi_i = t |F| / d on each vertex of a boundary face F, added
  to the local vector floc (each facet is listed on one rank: summed over ranks by a
  DMLocalToGlobal with ADD).

  Level: developer

.seealso: `MMFEAddPressure()`, `MMFEAddPointForce()`, `MMLoadsSetUp()`
@*/
PetscErrorCode MMFEAddTraction(MMOperators op, const MMTraction *tr, Vec floc)
{
  DM          dm = op->dm;
  DMLabel     label;
  MMFacetList fl;
  PetscScalar *f;

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, tr->name, &label));
  PetscCall(MMMeshGetFacets(dm, tr->name, &fl));
  PetscCall(CheckTractionGroup(dm, tr->name, label, &fl));
  PetscCall(VecGetArray(floc, &f));
  PetscCall(MMMeshFacetsAddNodal(dm, &fl, dm, op->dim, tr->value, f));
  PetscCall(VecRestoreArray(floc, &f));
  PetscCall(MMFacetListDestroy(&fl));
  PetscFunctionReturn(0);
}

/* Nodal loads of the tractions, pressures and point forces at amplitude 1. */
static PetscErrorCode AddTractions(MMOperators op, const MMFEProblem *pb, Vec Lcart)
{
  DM  dm = op->dm;
  Vec floc;

  PetscFunctionBeginUser;
  if (!pb->n_traction && !pb->n_pressure && !pb->n_point_force) PetscFunctionReturn(0);
  PetscCall(DMGetLocalVector(dm, &floc));
  PetscCall(VecZeroEntries(floc));
  for (PetscInt b = 0; b < pb->n_traction; ++b) PetscCall(MMFEAddTraction(op, &pb->traction[b], floc));
  for (PetscInt b = 0; b < pb->n_pressure; ++b) PetscCall(MMFEAddPressure(op, &pb->pressure[b], floc));
  for (PetscInt b = 0; b < pb->n_point_force; ++b) PetscCall(MMFEAddPointForce(op, &pb->point_force[b], floc));
  /* traction loads on Dirichlet-constrained components are dropped, as the reaction absorbs them */
  PetscCall(DMLocalToGlobal(dm, floc, ADD_VALUES, Lcart));
  PetscCall(DMRestoreLocalVector(dm, &floc));
  PetscFunctionReturn(0);
}

/* Assembles w_K K + w_M M. */
static PetscErrorCode AssembleMatrix(MMOperators op, PetscReal wK, PetscReal wM, Mat A)
{
  DM      dm = op->dm;
  PetscDS ds;
  Vec     xloc;

  PetscFunctionBeginUser;
  op->constants[MM_C_WEIGHT_K] = wK;
  op->constants[MM_C_WEIGHT_M] = wM;
  PetscCall(DMGetDS(dm, &ds));
  PetscCall(PetscDSSetConstants(ds, MM_C_NUM, op->constants));
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(VecZeroEntries(xloc));
  PetscCall(MatZeroEntries(A));
  PetscCall(DMPlexSNESComputeJacobianFEM(dm, xloc, A, A, NULL));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  op->constants[MM_C_WEIGHT_K] = 1.0;
  op->constants[MM_C_WEIGHT_M] = 0.0;
  PetscCall(PetscDSSetConstants(ds, MM_C_NUM, op->constants));
  PetscFunctionReturn(0);
}

/* K_fD u_D: the elastic force of the Dirichlet data on the free dofs, the residual at u_free = 0: cell
 * by cell in closed form with each cell's material (assembly_p1.c), or by the PetscFE residual with
 * -assembly fe (one material), several times slower. */
/* Whether any Dirichlet condition was set (-dirichlet): without one the data u_D is zero, and the
 * set-up's passes over every cell for its force and energy are skipped. */
static PetscErrorCode HasDirichlet(DM dm, PetscBool *has)
{
  PetscDS  ds;
  PetscInt nb;

  PetscFunctionBeginUser;
  PetscCall(DMGetDS(dm, &ds));
  PetscCall(PetscDSGetNumBoundary(ds, &nb));
  *has = (PetscBool)(nb > 0);
  PetscFunctionReturn(0);
}

static PetscErrorCode DirichletLift(MMOperators op, const MMMaterial *mat, Vec lift)
{
  DM        dm = op->dm;
  Vec       xloc, floc;
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(lift));
  PetscCall(HasDirichlet(dm, &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(DMGetLocalVector(dm, &floc));
  PetscCall(VecZeroEntries(xloc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(DMPlexInsertBoundaryValues(dm, PETSC_TRUE, xloc, 0.0, NULL, NULL, NULL));
  /* in PETSc 3.18 both vectors of the FEM residual are local */
  if (op->assembly == MM_ASSEMBLY_FE) PetscCall(DMPlexSNESComputeResidualFEM(dm, xloc, floc, NULL));
  else PetscCall(MMApplyP1(dm, mat, xloc, floc, NULL));
  PetscCall(VecZeroEntries(lift));
  PetscCall(DMLocalToGlobal(dm, floc, ADD_VALUES, lift));
  PetscCall(DMRestoreLocalVector(dm, &floc));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  PetscFunctionReturn(0);
}

/* The Cartesian stiffness into K and, unless M is NULL, the consistent mass into M, by either path. */
static PetscErrorCode AssembleKM(MMOperators op, const MMMaterial *mat, MMAssemblyType type, Mat K, Mat M)
{
  PetscFunctionBeginUser;
  if (type == MM_ASSEMBLY_CLOSED_FORM) {
    PetscCall(MMAssembleP1(op->dm, mat, K, M));
  } else {
    PetscCall(AssembleMatrix(op, 1.0, 0.0, K));
    if (M) PetscCall(AssembleMatrix(op, 0.0, 1.0, M));
  }
  PetscFunctionReturn(0);
}

/* max |A - B| / max |B|: A and B share the DMCreateMatrix layout and pattern. */
static PetscErrorCode RelativeMaxDifference(Mat A, Mat B, PetscReal *diff)
{
  Mat       D;
  PetscReal nD, nB;

  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(A, MAT_COPY_VALUES, &D));
  PetscCall(MatAXPY(D, -1.0, B, SAME_NONZERO_PATTERN));
  PetscCall(MatNorm(D, NORM_MAX, &nD));
  PetscCall(MatNorm(B, NORM_MAX, &nB));
  PetscCall(MatDestroy(&D));
  *diff = nB > 0 ? nD / nB : nD;
  PetscFunctionReturn(0);
}

/* -assembly_check: K and M again by the other path, compared entry by entry. The closed form and
 * the quadrature are both exact for P1, so they agree to rounding. */
static PetscErrorCode CheckAssembly(MMOperators op, const MMMaterial *mat, Mat K, Mat M)
{
  const MMAssemblyType other = op->assembly == MM_ASSEMBLY_FE ? MM_ASSEMBLY_CLOSED_FORM : MM_ASSEMBLY_FE;
  MPI_Comm             comm  = PetscObjectComm((PetscObject)op->dm);
  Mat                  K2, M2 = NULL;
  PetscReal            dK, dM = 0;
  PetscLogDouble       t0, t1;

  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(K, MAT_DO_NOT_COPY_VALUES, &K2));
  if (M) PetscCall(MatDuplicate(K, MAT_DO_NOT_COPY_VALUES, &M2));
  PetscCall(PetscTime(&t0));
  PetscCall(AssembleKM(op, mat, other, K2, M2));
  PetscCall(PetscTime(&t1));
  PetscCall(RelativeMaxDifference(K, K2, &dK));
  if (M) PetscCall(RelativeMaxDifference(M, M2, &dM));
  PetscCall(MatDestroy(&K2));
  PetscCall(MatDestroy(&M2));
  PetscCall(PetscPrintf(comm, "Assembly check, %s against %s: K max|diff|/max|entry| = %.3e, M %.3e (%s); %s took %.3f s\n", MMAssemblyTypes[op->assembly], MMAssemblyTypes[other], (double)dK, (double)dM, M ? "consistent" : "lumped, not compared", MMAssemblyTypes[other], (double)(t1 - t0)));
  PetscCheck(dK <= 1e-12 && dM <= 1e-12, comm, PETSC_ERR_PLIB, "-assembly_check: the %s and %s assemblies differ by %.3e in K and %.3e in M (relative to the largest entry), above 1e-12", MMAssemblyTypes[op->assembly], MMAssemblyTypes[other], (double)dK, (double)dM);
  PetscFunctionReturn(0);
}

/*@
  MMFECreateMatrix - Creates a matrix of the P1 pattern on which K and M are assembled

  Collective

  Input Parameters:
+ op - the operators (their -assembly)
- dm - the DM of the matrix

  Output Parameter:
. A - the new matrix

  Note:
  The matrix K and M are assembled into: for the closed form, with the P1 edge pattern built
  directly (MMCreateMatrixP1, several times faster than DMCreateMatrix's point adjacency); for
  -assembly fe, DMCreateMatrix's, which the PetscFE path fills. The patterns are the same.

  Level: intermediate

.seealso: `MMFEAssembleOperators()`, `MMContactFrameMatrixBegin()`
@*/
PetscErrorCode MMFECreateMatrix(MMOperators op, DM dm, Mat *A)
{
  PetscFunctionBeginUser;
  if (op->assembly == MM_ASSEMBLY_CLOSED_FORM) {
    PetscCall(MMCreateMatrixP1(dm, A));
    PetscFunctionReturn(0);
  }
  PetscCall(DMSetMatType(dm, MATAIJ));
  PetscCall(DMCreateMatrix(dm, A));
  PetscFunctionReturn(0);
}

/*@
  MMFEInterpolate - Sets a Cartesian global vector to the P1 interpolant of a function, its value at
  each vertex

  Collective

  Input Parameters:
+ op   - the operators
. f    - the function, of DMProjectFunction()'s signature
- fctx - its context

  Output Parameter:
. u - the interpolant (Cartesian global vector)

  Note:
  The P1 interpolant of f (f's signature is DMProjectFunction's) into the Cartesian global vector u:
  f at each vertex, which is what DMProjectFunction computes for P1 through the dual basis, at a
  fraction of its cost; the Dirichlet dofs drop out in the local-to-global map.

  Level: intermediate

.seealso: `MMFEToCartesian()`, `MMFEFromCartesian()`
@*/
PetscErrorCode MMFEInterpolate(MMOperators op, PetscErrorCode (*f)(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar *, void *), void *fctx, Vec u)
{
  DM                 dm = op->dm;
  const PetscInt     dim = op->dim;
  PetscSection       ls, cs;
  Vec                uloc, coords;
  const PetscScalar *xc;
  PetscScalar       *ua;
  PetscInt           vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecGetArray(uloc, &ua));
  PetscCall(VecGetArrayRead(coords, &xc));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt  off, xo;
    PetscReal x[MM_MAX_DIM];
    PetscCall(PetscSectionGetOffset(ls, v, &off));
    PetscCall(PetscSectionGetOffset(cs, v, &xo));
    for (PetscInt d = 0; d < dim; ++d) x[d] = PetscRealPart(xc[xo + d]);
    PetscCall((*f)(dim, 0.0, x, dim, &ua[off], fctx));
  }
  PetscCall(VecRestoreArrayRead(coords, &xc));
  PetscCall(VecRestoreArray(uloc, &ua));
  PetscCall(DMLocalToGlobal(dm, uloc, INSERT_VALUES, u));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscFunctionReturn(0);
}

/* -E 1e308 overflows the stiffness, -rho 1e-310 underflows the mass (its entries subnormal or 0):
 * say so before a solve fails on it. */
static PetscErrorCode CheckFiniteOperators(MMOperators op, const MMFEProblem *pb)
{
  PetscReal nK, nM;

  PetscFunctionBeginUser;
  PetscCall(MatNorm(op->K, NORM_FROBENIUS, &nK));
  PetscCall(MatNorm(op->M, NORM_FROBENIUS, &nM));
  PetscCheck(!PetscIsInfOrNanReal(nK) && !PetscIsInfOrNanReal(nM), PetscObjectComm((PetscObject)op->dm), PETSC_ERR_USER_INPUT, "The %s matrix overflows with -E %g, -rho %g on this mesh: use consistent units (for steel in SI units, -E 2.1e11 -rho 7850)", PetscIsInfOrNanReal(nK) ? "stiffness" : "mass", (double)pb->E, (double)pb->rho);
  {
    PetscReal mmin;
    Vec       d;
    PetscCall(MatCreateVecs(op->M, &d, NULL));
    PetscCall(MatGetDiagonal(op->M, d));
    PetscCall(VecMin(d, NULL, &mmin));
    PetscCall(VecDestroy(&d));
    /* the mass of the smallest node (M is positive definite: every diagonal entry is a node's) */
    PetscCheck(mmin >= DBL_MIN, PetscObjectComm((PetscObject)op->dm), PETSC_ERR_USER_INPUT, "The mass matrix underflows with -E %.6g, -rho %.6g on this mesh (a node's mass is %.3g, below the smallest normal double %.3g): use consistent units (for steel in SI units, -E 2.1e11 -rho 7850)", (double)pb->E, (double)pb->rho, (double)mmin, DBL_MIN);
  }
  PetscFunctionReturn(0);
}

/*@
  MMFEAssembleOperators - Assembles K, M, the load and the lift on the Cartesian free dofs

  Collective

  Input Parameters:
+ op  - the operators, set up
. mat - the bodies' material
- pb  - the problem

  Note:
  K, M, the load and the lift on the Cartesian dofs (free dofs only); contact's frame
  (MMContactSetUpFrame) turns them into the w-frame ones and builds M* between this and
  MMFEAssembleOperatorsEnd.

  Level: beginner

.seealso: `MMFEAssembleOperatorsEnd()`, `MMContactSetUpFrame()`, `MMFECreateMatrix()`
@*/
PetscErrorCode MMFEAssembleOperators(MMOperators op, const MMMaterial *mat, const MMFEProblem *pb)
{
  DM          dm = op->dm;
  PetscDS     ds;
  Mat         Kc, Mc = NULL;
  Vec         mloc;
  PetscReal   ones[MM_MAX_DIM] = {1, 1, 1};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_FEAssemble, 0, 0, 0, 0));
  PetscCall(DMGetDS(dm, &ds));
  PetscCall(PetscLogEventBegin(MM_FEPreallocate, 0, 0, 0, 0));
  PetscCall(MMFECreateMatrix(op, dm, &Kc));
  /* a lumped mass is built from vertex masses below: no consistent mass to assemble. M has K's
   * pattern, and duplicating it skips a second DMPlex preallocation, which alone costs several
   * assemblies (docs/scaling.md, "Assembly of K and M, measured") */
  if (!op->lumped) PetscCall(MatDuplicate(Kc, MAT_DO_NOT_COPY_VALUES, &Mc));
  PetscCall(PetscLogEventEnd(MM_FEPreallocate, 0, 0, 0, 0));
  PetscCall(PetscDSSetJacobian(ds, 0, 0, g0_mass_uu, NULL, NULL, g3_elas_uu));
  PetscCall(PetscLogEventBegin(MM_FEAssembleKM, 0, 0, 0, 0));
  PetscCall(AssembleKM(op, mat, op->assembly, Kc, Mc));
  PetscCall(PetscLogEventEnd(MM_FEAssembleKM, 0, 0, 0, 0));
  if (op->assembly_check) PetscCall(CheckAssembly(op, mat, Kc, Mc));
  op->K = Kc;

  PetscCall(PetscLogEventBegin(MM_FELoads, 0, 0, 0, 0));
  PetscCall(DMCreateGlobalVector(dm, &op->load));
  PetscCall(VecDuplicate(op->load, &op->lift));
  PetscCall(VecDuplicate(op->load, &op->mass_lumped_cart));
  PetscCall(DMGetLocalVector(op->dm_scalar, &mloc));
  PetscCall(VertexMasses(op, mat, mloc));
  PetscCall(SpreadVertexScalar(op, mloc, ones, op->mass_lumped_cart));
  /* body force: int rho g phi_i = m_i g, exactly, for constant g */
  PetscCall(SpreadVertexScalar(op, mloc, pb->gravity, op->load));
  PetscCall(DMRestoreLocalVector(op->dm_scalar, &mloc));
  PetscCall(AddTractions(op, pb, op->load));
  PetscCall(DirichletLift(op, mat, op->lift));
  PetscCall(DirichletEnergy(op, mat));
  PetscCall(PetscLogEventEnd(MM_FELoads, 0, 0, 0, 0));

  if (op->lumped) {
    /* equal per component at each node: contact's frame rotation leaves it diagonal and unchanged */
    PetscCall(MatDuplicate(op->K, MAT_DO_NOT_COPY_VALUES, &op->M));
    PetscCall(MatZeroEntries(op->M));
    PetscCall(MatDiagonalSet(op->M, op->mass_lumped_cart, INSERT_VALUES));
  } else op->M = Mc;
  PetscCall(CheckFiniteOperators(op, pb));
  PetscFunctionReturn(0);
}

/*@
  MMFEHandMatrices - Hands the assembled Cartesian K and M over to their new owner, contact's frame,
  after viewing them (-stiffness_view, -mass_view)

  Collective

  Input Parameter:
. op - the operators, assembled by MMFEAssembleOperators()

  Output Parameters:
+ K - the stiffness, now the caller's to turn and destroy
- M - the standard mass (consistent or lumped), likewise

  Note:
  fem keeps no matrix that a frame could turn: contact turns these into the w-frame in place rather
  than turning a copy, which would keep a second matrix of K's pattern for the whole run. Called
  once; fem's K and M are NULL afterwards (docs/developer.md, "The contact frame").

  Level: developer

.seealso: `MMFEAssembleOperators()`, `MMContactSetUpFrame()`
@*/
PetscErrorCode MMFEHandMatrices(MMOperators op, Mat *K, Mat *M)
{
  PetscFunctionBeginUser;
  PetscCheck(op->K && op->M, PetscObjectComm((PetscObject)op->dm), PETSC_ERR_ORDER, "MMFEHandMatrices: K and M were handed over already, or never assembled");
  PetscCall(MatViewFromOptions(op->K, NULL, "-stiffness_view"));
  PetscCall(MatViewFromOptions(op->M, NULL, "-mass_view"));
  *K    = op->K;
  *M    = op->M;
  op->K = NULL;
  op->M = NULL;
  PetscFunctionReturn(0);
}

/*@
  MMFEAssembleOperatorsEnd - Ends the operators' assembly event after contact's frame

  Collective

  Input Parameter:
. op - the operators, their K and M handed to contact (MMFEHandMatrices())

  Note:
  After contact's frame (MMContactSetUpFrame: the rotation, M* and the pairs' transform): the end of
  the assembly's event, begun in MMFEAssembleOperators, so that the frame's set-up is counted in it.

  Level: intermediate

.seealso: `MMFEAssembleOperators()`, `MMContactSetUpFrame()`
@*/
PetscErrorCode MMFEAssembleOperatorsEnd(MMOperators op)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventEnd(MM_FEAssemble, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMFESetFrame - Installs the contact frame's transforms, which the MMFEToCartesian family calls

  Logically Collective

  Input Parameters:
+ op  - the operators
. ops - the frame's transforms (copied)
- ctx - their context (contact's)

  Note:
  The frame, Q and the contact pairs' N, is contact's (docs/developer.md, "The contact frame"): fem
  holds no Q or N, it turns vectors through these ops. Contact installs them when it builds Q.

  Level: developer

.seealso: `MMFEToCartesian()`, `MMContactSetUp()`
@*/
PetscErrorCode MMFESetFrame(MMOperators op, const MMFrameOps *ops, void *ctx)
{
  PetscFunctionBeginUser;
  op->frame.ops = *ops;
  op->frame.ctx = ctx;
  PetscFunctionReturn(0);
}

/*@
  MMFEToCartesian - Turns a w-frame displacement into the Cartesian one

  Collective

  Input Parameters:
+ op - the operators, their frames set by contact
- w  - the w-frame vector

  Output Parameter:
. ucart - the Cartesian vector

  Level: intermediate

.seealso: `MMFEFromCartesian()`, `MMFEForceToCartesian()`
@*/
PetscErrorCode MMFEToCartesian(MMOperators op, Vec w, Vec ucart)
{
  PetscFunctionBeginUser;
  PetscCall(op->frame.ops.tocartesian(op->frame.ctx, w, ucart));
  PetscFunctionReturn(0);
}

/*@
  MMFEFromCartesian - Turns a Cartesian displacement into the w-frame one

  Collective

  Input Parameters:
+ op    - the operators, their frames set by contact
- ucart - the Cartesian vector

  Output Parameter:
. w - the w-frame vector

  Level: intermediate

.seealso: `MMFEToCartesian()`, `MMFEForceFromCartesian()`
@*/
PetscErrorCode MMFEFromCartesian(MMOperators op, Vec ucart, Vec w)
{
  PetscFunctionBeginUser;
  PetscCall(op->frame.ops.fromcartesian(op->frame.ctx, ucart, w));
  PetscFunctionReturn(0);
}

/*@
  MMFEForceToCartesian - Turns a w-frame force into the Cartesian one

  Collective

  Input Parameters:
+ op - the operators, their frames set by contact
- fw - the w-frame force

  Output Parameter:
. fcart - the Cartesian force

  Level: intermediate

.seealso: `MMFEForceFromCartesian()`, `MMFEToCartesian()`
@*/
PetscErrorCode MMFEForceToCartesian(MMOperators op, Vec fw, Vec fcart)
{
  PetscFunctionBeginUser;
  PetscCall(op->frame.ops.forcetocartesian(op->frame.ctx, fw, fcart));
  PetscFunctionReturn(0);
}

/*@
  MMFEForceFromCartesian - Turns a Cartesian force into the w-frame one

  Collective

  Input Parameters:
+ op    - the operators, their frames set by contact
- fcart - the Cartesian force

  Output Parameter:
. fw - the w-frame force

  Level: intermediate

.seealso: `MMFEForceToCartesian()`, `MMFEFromCartesian()`
@*/
PetscErrorCode MMFEForceFromCartesian(MMOperators op, Vec fcart, Vec fw)
{
  PetscFunctionBeginUser;
  PetscCall(op->frame.ops.forcefromcartesian(op->frame.ctx, fcart, fw));
  PetscFunctionReturn(0);
}

/*@
  MMFEElasticEnergyIntegral - Computes the elastic energy 1/2 int sigma(u):eps(u) of a Cartesian
  displacement by quadrature, with the Dirichlet data of t = 0

  Collective

  Input Parameters:
+ op    - the operators
. mat   - the bodies' material
- ucart - the Cartesian global displacement

  Output Parameter:
. energy - the elastic energy

  Note:
  1/2 int sigma(u):eps(u) of a Cartesian global vector u with the Dirichlet data of t = 0 inserted:
  cell by cell in closed form with each cell's material (assembly_p1.c), or by the PetscDS's
  quadrature with -assembly fe (one material).

  Level: developer

.seealso: `MMContactElasticEnergy()`, `MMContactCheckElasticEnergy()`
@*/
PetscErrorCode MMFEElasticEnergyIntegral(MMOperators op, const MMMaterial *mat, Vec ucart, PetscReal *energy)
{
  DM          dm = op->dm;
  PetscScalar integral[1];
  Vec         xloc;

  PetscFunctionBeginUser;
  if (op->assembly == MM_ASSEMBLY_FE) {
    PetscCall(DMPlexComputeIntegralFEM(dm, ucart, integral, NULL));
    *energy = PetscRealPart(integral[0]);
    PetscFunctionReturn(0);
  }
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(VecZeroEntries(xloc));
  PetscCall(DMGlobalToLocal(dm, ucart, INSERT_VALUES, xloc));
  PetscCall(DMPlexInsertBoundaryValues(dm, PETSC_TRUE, xloc, 0.0, NULL, NULL, NULL));
  PetscCall(MMApplyP1(dm, mat, xloc, NULL, energy));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  PetscFunctionReturn(0);
}

/* 1/2 int sigma(u_D):eps(u_D), once: the free dofs zero, the Dirichlet data inserted. */
static PetscErrorCode DirichletEnergy(MMOperators op, const MMMaterial *mat)
{
  Vec       zero;
  PetscBool has;

  PetscFunctionBeginUser;
  op->energy_dirichlet = 0;
  PetscCall(HasDirichlet(op->dm, &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(DMGetGlobalVector(op->dm, &zero));
  PetscCall(VecZeroEntries(zero));
  PetscCall(MMFEElasticEnergyIntegral(op, mat, zero, &op->energy_dirichlet));
  PetscCall(DMRestoreGlobalVector(op->dm, &zero));
  PetscFunctionReturn(0);
}

/*@
  MMFEDestroy - Destroys the operators and what they hold

  Collective

  Input Parameter:
. op - the operators, NULL on return

  Level: beginner

.seealso: `MMFECreate()`, `MMFESetUp()`
@*/
PetscErrorCode MMFEDestroy(MMOperators *pop)
{
  MMOperators op = *pop;

  PetscFunctionBeginUser;
  if (!op) PetscFunctionReturn(0);
  PetscCall(MMCellsDestroy(&op->cells));
  PetscCall(MatDestroy(&op->K));
  PetscCall(MatDestroy(&op->M));
  PetscCall(VecDestroy(&op->load));
  PetscCall(VecDestroy(&op->lift));
  PetscCall(VecDestroy(&op->mass_lumped_cart));
  PetscCall(DMDestroy(&op->dm_scalar));
  PetscCall(DMDestroy(&op->dm));
  PetscCall(PetscFree(*pop));
  PetscFunctionReturn(0);
}
