/* The material of each cell (docs/method.md section 2, "Bodies"): one body, the whole mesh with
 * -E, -nu, -rho and -v0, or the bodies of -bodies, each a physical group of cells with its own
 * material and initial velocity. Built once at set-up, before anything is assembled; everything
 * that needs the material reads it per cell from here: the closed-form K and M, the lumped masses,
 * the redistributed mass, the stress, the wave speed of the CFL number.
 *
 * Without -bodies every cell gets the one material, computed by the same expressions as before it
 * had a per-cell form, so that the single-body path is bitwise what it was. */
#include <petscsf.h>
#include "femimpl.h"
#include "mesh.h"

/* E, nu -> Lame (plane strain in 2D, so the same in both dimensions) and the wave speeds. The
 * expressions, and their order, are those of the constants of the PetscDS (fem.c). */
static void BodyConstants(MMBody *b)
{
  b->mu     = b->E / (2 * (1 + b->nu));
  b->lambda = b->E * b->nu / ((1 + b->nu) * (1 - 2 * b->nu));
  b->c_p    = PetscSqrtReal((b->lambda + 2 * b->mu) / b->rho);
  b->c_s    = PetscSqrtReal(b->mu / b->rho);
}

/* The bodies as the options give them: one, the whole mesh, without -bodies. */
static PetscErrorCode CreateBodies(MMMaterial *mat, const MMFEProblem *o)
{

  PetscFunctionBeginUser;
  mat->named    = (PetscBool)(o->n_bodies > 0);
  mat->n_bodies = mat->named ? o->n_bodies : 1;
  PetscCall(PetscCalloc1(mat->n_bodies, &mat->body));
  for (PetscInt b = 0; b < mat->n_bodies; ++b) {
    MMBody *body = &mat->body[b];
    if (mat->named) {
      const MMBodyOptions *bo = &o->bodies[b];
      body->name  = bo->name;
      body->group = bo->group;
      body->E     = bo->E;
      body->nu    = bo->nu;
      body->rho   = bo->rho;
      body->elasticity = bo->elasticity;
      for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->v0[d] = bo->v0[d];
    } else {
      body->name = "body";
      body->E    = o->E;
      body->nu   = o->nu;
      body->rho  = o->rho;
      body->elasticity = o->elasticity;
      for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->v0[d] = o->v0[d];
    }
    BodyConstants(body);
    if (body->elasticity != MM_ELASTICITY_LINEAR) mat->finite = PETSC_TRUE;
  }
  mat->uniform = PETSC_TRUE;
  mat->c_p_max = mat->body[0].c_p;
  mat->E_max   = mat->body[0].E;
  for (PetscInt b = 1; b < mat->n_bodies; ++b) {
    const MMBody *body = &mat->body[b];
    mat->uniform = (PetscBool)(mat->uniform && body->E == mat->body[0].E && body->nu == mat->body[0].nu && body->rho == mat->body[0].rho);
    mat->c_p_max = PetscMax(mat->c_p_max, body->c_p);
    mat->E_max   = PetscMax(mat->E_max, body->E);
  }
  PetscFunctionReturn(0);
}

/* A cell's place, on every rank, for a message about it: the centroid of the first such cell of
 * the lowest rank that has one (found says whether this rank has). */
static PetscErrorCode SharedCentroid(DM dm, PetscBool found, PetscInt c, PetscInt extra[2], char where[], size_t len)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);
  PetscMPIInt rank, size, root;
  PetscReal   x[MM_MAX_DIM] = {0, 0, 0};
  PetscInt    dim;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  root = found ? rank : size;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &root, 1, MPI_INT, MPI_MIN, comm));
  if (found && rank == root) PetscCall(MMMeshCellCentroid(dm, c, x));
  PetscCallMPI(MPI_Bcast(x, MM_MAX_DIM, MPIU_REAL, root, comm));
  PetscCallMPI(MPI_Bcast(extra, 2, MPIU_INT, root, comm));
  PetscCall(DMGetCoordinateDim(dm, &dim));
  if (dim == 2) PetscCall(PetscSNPrintf(where, len, "(%g, %g)", (double)x[0], (double)x[1]));
  else PetscCall(PetscSNPrintf(where, len, "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]));
  PetscFunctionReturn(0);
}

/* -bodies: each local cell's body from the physical groups of the bodies, every cell in exactly
 * one; a group without cells, a cell in none and a cell in two are refused, with where. */
static PetscErrorCode AssignCells(MMMaterial *mat, DM dm, PetscInt dim)
{
  MPI_Comm        comm = PetscObjectComm((PetscObject)dm);
  const PetscInt  nb   = mat->n_bodies;
  DMLabel        *label;
  PetscInt       *def, *count, bad[2] = {0, 0}, first[2] = {-1, -1}, pair[2] = {-1, -1}, ncells = mat->ncells;
  char            where[128], groups[2048];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(nb, &label, nb, &def, nb, &count));
  for (PetscInt b = 0; b < nb; ++b) {
    PetscCall(MMMeshGetLabel(dm, mat->body[b].group, &label[b]));
    PetscCall(DMLabelGetDefaultValue(label[b], &def[b]));
    count[b] = 0;
  }
  for (PetscInt c = 0; c < mat->ncells; ++c) {
    PetscInt in = 0;
    mat->cell_body[c] = -1;
    for (PetscInt b = 0; b < nb; ++b) {
      PetscInt val;
      PetscCall(DMLabelGetValue(label[b], mat->cStart + c, &val));
      if (val == def[b]) continue;
      if (!in++) mat->cell_body[c] = b;
      else if (in == 2 && !bad[1]++) {
        first[1] = mat->cStart + c;
        pair[0]  = mat->cell_body[c];
        pair[1]  = b;
      }
      ++count[b];
    }
    if (!in && !bad[0]++) first[0] = mat->cStart + c;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, nb, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bad, 2, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  for (PetscInt b = 0; b < nb; ++b) {
    if (count[b]) continue;
    PetscCall(MMMeshCellGroups(dm, groups, sizeof(groups)));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "-body_%s_group %s: the physical group \"%s\" holds no cells; a body is a group of cells, a Physical %s. The mesh's groups of cells are:%s", mat->body[b].name, mat->body[b].group, mat->body[b].group, dim == 2 ? "Surface in 2D" : "Volume in 3D", groups);
  }
  if (bad[1]) {
    PetscCall(SharedCentroid(dm, (PetscBool)(first[1] >= 0), first[1], pair, where, sizeof(where)));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "%" PetscInt_FMT " cell%s of the mesh %s in two bodies' groups, the first at %s in both body %s (-body_%s_group %s) and body %s (-body_%s_group %s): every cell must be in exactly one body. Give the bodies groups that do not overlap", bad[1], bad[1] > 1 ? "s" : "", bad[1] > 1 ? "are" : "is", where, mat->body[pair[0]].name, mat->body[pair[0]].name, mat->body[pair[0]].group, mat->body[pair[1]].name, mat->body[pair[1]].name, mat->body[pair[1]].group);
  }
  if (bad[0]) {
    PetscInt none[2] = {0, 0};
    PetscCall(SharedCentroid(dm, (PetscBool)(first[0] >= 0), first[0], none, where, sizeof(where)));
    PetscCall(MMMeshCellGroups(dm, groups, sizeof(groups)));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "%" PetscInt_FMT " of the mesh's %" PetscInt_FMT " cells %s in no body's group (the first at %s): every cell must be in exactly one body of -bodies. Add a body for them (-bodies NAME,... with -body_NAME_group GROUP); the mesh's groups of cells are:%s", bad[0], ncells, bad[0] > 1 ? "are" : "is", where, groups);
  }
  for (PetscInt b = 0; b < nb; ++b) mat->body[b].ncells = count[b];
  PetscCall(PetscFree3(label, def, count));
  PetscFunctionReturn(0);
}

/* The per-cell Lame parameters and density, and each body's volume and mass. */
static PetscErrorCode CellMaterial(MMMaterial *mat, const MMCells *cells, DM dm)
{
  PetscReal  *vol;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(mat->n_bodies, &vol));
  for (PetscInt c = 0; c < mat->ncells; ++c) {
    const MMBody *body = &mat->body[mat->cell_body[c]];
    mat->lambda[c] = body->lambda;
    mat->mu[c]     = body->mu;
    mat->rho[c]    = body->rho;
    vol[mat->cell_body[c]] += cells->volume[c];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, vol, mat->n_bodies, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  for (PetscInt b = 0; b < mat->n_bodies; ++b) {
    mat->body[b].volume = vol[b];
    mat->body[b].mass   = mat->body[b].rho * vol[b];
  }
  PetscCall(PetscFree(vol));
  PetscFunctionReturn(0);
}

/* -omega0: each body's rigid rotation, -body_NAME_omega0 or the whole mesh's -omega0; a body
 * without one adds nothing (docs/method.md section 2, "Bodies"). */
static void BodySpins(MMMaterial *mat, const MMFEProblem *o)
{
  for (PetscInt b = 0; b < mat->n_bodies; ++b) {
    MMBody          *body = &mat->body[b];
    const PetscReal *w    = mat->named ? o->bodies[b].omega0 : o->omega0;
    body->omega0_set      = mat->named ? o->bodies[b].omega0_set : o->omega0_set;
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->omega0[d] = body->omega0_set ? w[d] : 0;
    if (body->omega0_set) mat->spin = PETSC_TRUE;
  }
}

/* -omega0: the centre of mass of each body, sum_T rho_T |T| x_T / sum_T rho_T |T| over its cells
 * on all ranks (x_T the centroid: exact for P1's consistent mass). */
static PetscErrorCode BodyCentres(MMMaterial *mat, const MMCells *cells, DM dm)
{
  const PetscInt n = mat->n_bodies * (MM_MAX_DIM + 1); /* per body: the first moment, the mass */
  PetscReal     *sum;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(n, &sum));
  for (PetscInt c = 0; c < mat->ncells; ++c) {
    const PetscReal m = mat->rho[c] * cells->volume[c], *x = &cells->centroid[MM_MAX_DIM * c];
    PetscReal      *s = &sum[mat->cell_body[c] * (MM_MAX_DIM + 1)];
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) s[d] += m * x[d];
    s[MM_MAX_DIM] += m;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, n, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  for (PetscInt b = 0; b < mat->n_bodies; ++b)
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) mat->body[b].x_cm[d] = sum[b * (MM_MAX_DIM + 1) + d] / sum[b * (MM_MAX_DIM + 1) + MM_MAX_DIM];
  PetscCall(PetscFree(sum));
  PetscFunctionReturn(0);
}

/* The velocity a cell of body b gives its vertex at x: the body's v0, or (spin) the rigid rotation
 * omega0 x (x - x_cm) of its -omega0, zero for a body without one. */
static void CellVertexVelocity(const MMBody *b, PetscBool spin, PetscInt dim, const PetscScalar x[], PetscReal v[])
{
  const PetscReal *w = b->omega0;
  PetscReal        r[3] = {0, 0, 0};

  if (!spin) {
    for (PetscInt d = 0; d < dim; ++d) v[d] = b->v0[d];
    return;
  }
  for (PetscInt d = 0; d < dim; ++d) r[d] = PetscRealPart(x[d]) - b->x_cm[d];
  if (dim == 2) {
    v[0] = -w[0] * r[1];
    v[1] = w[0] * r[0];
  } else {
    v[0] = w[1] * r[2] - w[2] * r[1];
    v[1] = w[2] * r[0] - w[0] * r[2];
    v[2] = w[0] * r[1] - w[1] * r[0];
  }
}

/* On every copy of each point, the min (op MPI_MIN) or max of a over its copies, through the point
 * SF: reduced to the owner, then sent back. a has one entry per point of the chart. */
static PetscErrorCode PointReduce(DM dm, MPI_Op op, PetscReal a[])
{
  PetscSF   sf;
  PetscInt  nroots, pStart, pEnd;
  PetscReal *root;

  PetscFunctionBeginUser;
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, NULL, NULL, NULL));
  if (nroots < 0) PetscFunctionReturn(0); /* a mesh that was never distributed: no shared points */
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscMalloc1(pEnd - pStart, &root));
  PetscCall(PetscArraycpy(root, a, pEnd - pStart));
  PetscCall(PetscSFReduceBegin(sf, MPIU_REAL, a, root, op));
  PetscCall(PetscSFReduceEnd(sf, MPIU_REAL, a, root, op));
  PetscCall(PetscArraycpy(a, root, pEnd - pStart));
  PetscCall(PetscSFBcastBegin(sf, MPIU_REAL, root, a, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_REAL, root, a, MPI_REPLACE));
  PetscCall(PetscFree(root));
  PetscFunctionReturn(0);
}

/* -bodies: each vertex's initial velocity, the v0 of the body of its cells (spin: the rotation of
 * its -omega0 instead, into vertex_omega0). Bodies are normally
 * separate components of the mesh; a vertex in cells of two bodies takes their v0 if they agree,
 * and is refused if they differ (the body would tear at t = 0). Exact: the componentwise min and
 * max of v0 over the vertex's cells, on all ranks, must be equal. */
static PetscErrorCode VertexVelocities(MMMaterial *mat, const MMCells *cells, PetscInt dim, DM dm, PetscBool spin)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)dm);
  PetscInt       pStart, pEnd, vStart, vEnd, first = -1, nbad;
  PetscReal     *lo[MM_MAX_DIM], *hi[MM_MAX_DIM], info[3 * MM_MAX_DIM] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  PetscReal     *out;
  PetscMPIInt    rank, size, root;
  PetscSection   cs;
  Vec            X;
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(dim * (vEnd - vStart), &out));
  if (spin) mat->vertex_omega0 = out;
  else mat->vertex_v0 = out;
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &xa));
  for (PetscInt d = 0; d < dim; ++d) {
    PetscCall(PetscMalloc2(pEnd - pStart, &lo[d], pEnd - pStart, &hi[d]));
    for (PetscInt p = 0; p < pEnd - pStart; ++p) {
      lo[d][p] = PETSC_MAX_REAL;
      hi[d][p] = PETSC_MIN_REAL;
    }
  }
  for (PetscInt c = 0; c < mat->ncells; ++c) {
    for (PetscInt a = 0; a < cells->nv; ++a) {
      const PetscInt p = cells->vertex[cells->nv * c + a] - pStart;
      PetscReal      v[MM_MAX_DIM];
      PetscInt       off;
      PetscCall(PetscSectionGetOffset(cs, p + pStart, &off));
      CellVertexVelocity(&mat->body[mat->cell_body[c]], spin, dim, &xa[off], v);
      for (PetscInt d = 0; d < dim; ++d) {
        lo[d][p] = PetscMin(lo[d][p], v[d]);
        hi[d][p] = PetscMax(hi[d][p], v[d]);
      }
    }
  }
  for (PetscInt d = 0; d < dim; ++d) {
    PetscCall(PointReduce(dm, MPI_MIN, lo[d]));
    PetscCall(PointReduce(dm, MPI_MAX, hi[d]));
  }
  for (PetscInt v = vStart; v < vEnd; ++v)
    for (PetscInt d = 0; d < dim; ++d) {
      out[(v - vStart) * dim + d] = lo[d][v - pStart];
      if (first < 0 && lo[d][v - pStart] != hi[d][v - pStart]) first = v;
    }
  if (first >= 0) { /* its place, and the range of v0 over its cells */
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, first, &off));
    for (PetscInt d = 0; d < dim; ++d) {
      info[d]                  = PetscRealPart(xa[off + d]);
      info[MM_MAX_DIM + d]     = lo[d][first - pStart];
      info[2 * MM_MAX_DIM + d] = hi[d][first - pStart];
    }
  }
  PetscCall(VecRestoreArrayRead(X, &xa));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(PetscFree2(lo[d], hi[d]));
  nbad = first >= 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbad, 1, MPIU_INT, MPI_SUM, comm));
  if (!nbad) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  root = first >= 0 ? rank : size;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &root, 1, MPI_INT, MPI_MIN, comm));
  PetscCallMPI(MPI_Bcast(info, 3 * MM_MAX_DIM, MPIU_REAL, root, comm));
  {
    char where[128], range[256];
    if (dim == 2) {
      PetscCall(PetscSNPrintf(where, sizeof(where), "(%g, %g)", (double)info[0], (double)info[1]));
      PetscCall(PetscSNPrintf(range, sizeof(range), "x from %g to %g, y from %g to %g", (double)info[3], (double)info[6], (double)info[4], (double)info[7]));
    } else {
      PetscCall(PetscSNPrintf(where, sizeof(where), "(%g, %g, %g)", (double)info[0], (double)info[1], (double)info[2]));
      PetscCall(PetscSNPrintf(range, sizeof(range), "x from %g to %g, y from %g to %g, z from %g to %g", (double)info[3], (double)info[6], (double)info[4], (double)info[7], (double)info[5], (double)info[8]));
    }
    PetscCheck(!spin, comm, PETSC_ERR_USER_INPUT, "The vertex at %s is shared by cells of bodies with different initial rotations (-omega0 or -body_NAME_omega0, each about its own body's centre of mass: %s): the bodies are glued there and would tear apart at t = 0. Give -body_NAME_omega0 only to bodies that share no node with another, or give the glued bodies one rotation with -omega and -omega_center", where, range);
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "The vertex at %s is shared by cells of bodies with different initial velocities (-body_NAME_v0: %s): the bodies are glued there and would tear apart at t = 0. Give the bodies that touch the same -body_NAME_v0, or mesh them as separate parts that share no node", where, range);
  }
}

/* What cannot take several bodies, refused before anything is built. */
static PetscErrorCode CheckSupported(const MMMaterial *mat, MMOperators op, const MMFEProblem *pb, MPI_Comm comm)
{

  PetscFunctionBeginUser;
  PetscCheck(!mat->named || !pb->static_sliding, comm, PETSC_ERR_SUP, "-initial_state static_sliding with -bodies is not supported: the sliding state is built for one body of one material sliding with -v0. Drop -bodies (give the material with -E, -nu, -rho and the velocity with -v0)");
  /* the PetscFE path takes the material from the PetscDS constants, one for every cell */
  PetscCheck(mat->uniform || (op->assembly != MM_ASSEMBLY_FE && !op->assembly_check), comm, PETSC_ERR_SUP, "-assembly fe%s with bodies of different materials is not supported: the PetscFE quadrature takes one material for the whole mesh. Use -assembly closed_form (the default), which assembles each cell with its body's material", op->assembly_check ? " (and -assembly_check, which runs it)" : "");
  PetscFunctionReturn(0);
}

/*@
  MMMaterialSetUp - Sets the material of each local cell from the problem's bodies

  Collective

  Input Parameters:
+ mat - the material
. op  - the operators, their cells tabulated
- pb  - the problem

  Note:
  The material of each local cell of op's mesh (its cells tabulated) from the problem's bodies.

  Level: intermediate

.seealso: `MMMaterialChecksum()`, `MMMaterialDestroy()`, `MMFESetUp()`
@*/
PetscErrorCode MMMaterialSetUp(MMMaterial *mat, MMOperators op, const MMFEProblem *pb)
{
  DM          dm   = op->dm;
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);
  PetscInt    cEnd;

  PetscFunctionBeginUser;
  /* the cells' geometry reads the local coordinates, which a -mesh_rotation has reset (collective) */
  PetscCall(DMGetCoordinatesLocalSetUp(dm));
  PetscCall(CreateBodies(mat, pb));
  BodySpins(mat, pb);
  PetscCall(CheckSupported(mat, op, pb, comm));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &mat->cStart, &cEnd));
  mat->ncells = cEnd - mat->cStart;
  PetscCall(PetscMalloc4(mat->ncells, &mat->cell_body, mat->ncells, &mat->lambda, mat->ncells, &mat->mu, mat->ncells, &mat->rho));
  if (mat->named) PetscCall(AssignCells(mat, dm, op->dim));
  else {
    PetscInt n = mat->ncells;
    for (PetscInt c = 0; c < mat->ncells; ++c) mat->cell_body[c] = 0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm));
    mat->body[0].ncells = n;
  }
  PetscCall(CellMaterial(mat, &op->cells, dm));
  if (mat->named) PetscCall(VertexVelocities(mat, &op->cells, op->dim, dm, PETSC_FALSE));
  if (mat->spin) {
    PetscCall(BodyCentres(mat, &op->cells, dm));
    PetscCall(VertexVelocities(mat, &op->cells, op->dim, dm, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/*@
  MMMaterialChecksum - Computes the material's part of a checkpoint's fingerprint

  Collective

  Input Parameters:
+ mat - the material
- op  - the operators

  Output Parameter:
. sum - the weighted integrals of lambda, mu and rho (all ranks)

  Note:
  The material's part of a checkpoint's fingerprint (docs/method.md section 9): sum_T |T| w(x_T) q_T
  for q = lambda, mu, rho, w = 1 + the centroid's place in the bounding box, so that bodies that
  trade materials change it too. Summed over ranks: equal up to rounding on any partition.

  Level: developer

.seealso: `MMMaterialSetUp()`
@*/
PetscErrorCode MMMaterialChecksum(const MMMaterial *mat, MMOperators op, PetscReal sum[3])
{
  DM                dm  = op->dm;
  PetscReal         lo[MM_MAX_DIM], hi[MM_MAX_DIM];
  PetscInt          dim;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDim(dm, &dim));
  PetscCall(DMGetBoundingBox(dm, lo, hi));
  sum[0] = sum[1] = sum[2] = 0;
  for (PetscInt c = 0; c < mat->ncells; ++c) {
    const PetscReal vol = op->cells.volume[c], *x = &op->cells.centroid[MM_MAX_DIM * c];
    PetscReal       w   = 1;
    for (PetscInt d = 0; d < dim; ++d) w += (d + 1) * (x[d] - lo[d]) / (hi[d] > lo[d] ? hi[d] - lo[d] : 1.0);
    sum[0] += vol * w * mat->lambda[c];
    sum[1] += vol * w * mat->mu[c];
    sum[2] += vol * w * mat->rho[c];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 3, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/*@
  MMMaterialDestroy - Frees what the material holds

  Not collective

  Input Parameter:
. mat - the material

  Level: intermediate

.seealso: `MMMaterialSetUp()`
@*/
PetscErrorCode MMMaterialDestroy(MMMaterial *mat)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(mat->body));
  PetscCall(PetscFree4(mat->cell_body, mat->lambda, mat->mu, mat->rho));
  PetscCall(PetscFree(mat->vertex_v0));
  PetscCall(PetscFree(mat->vertex_omega0));
  PetscFunctionReturn(0);
}
