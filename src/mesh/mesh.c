/* Reading a gmsh mesh into DMPlex, naming its physical groups, and distributing it. */
#include <petscsf.h>
#include "mesh.h"
#include "partition_metis.h"

/* Labels DMPlex makes itself, and our facet marks: not physical groups the user named. */
static PetscBool IsInternalLabel(const char name[])
{
  const char *internal[] = {"depth", "celltype", "Cell Sets", "Face Sets", "Vertex Sets", "Edge Sets", "marker", "boundary"};
  for (size_t i = 0; i < sizeof(internal) / sizeof(internal[0]); ++i) {
    PetscBool same;
    if (PetscStrcmp(name, internal[i], &same) || same) return PETSC_TRUE;
  }
  return (PetscBool)!strncmp(name, MM_MESH_FACET_MARK, sizeof(MM_MESH_FACET_MARK) - 1); /* our facet groups' cell marks */
}

/*@
  MMMeshIsPhysicalGroup - Tells whether a label of the mesh is a physical group the user named

  Not collective

  Input Parameter:
. name - the label's name

  Note:
  Returns the answer (a PetscBool) rather than an error code. False for the labels DMPlex makes
  itself (depth, celltype, Cell Sets, Face Sets, Vertex Sets, Edge Sets, marker, boundary) and for
  the facet groups' cell marks (MM_MESH_FACET_MARK).

  Whether a label of the mesh is a physical group the user named (the data check lists them).

  Level: developer

.seealso: `MMMeshGetLabelFor()`, `MMMeshCellGroups()`
@*/
PetscBool MMMeshIsPhysicalGroup(const char name[])
{
  return (PetscBool)!IsInternalLabel(name);
}

/*@
  MMMeshGetLabelFor - Gets the label of a physical group by name, refusing an unknown name with the
  list of the ones the mesh has

  Logically collective on dm

  Input Parameters:
+ dm     - the mesh
. name   - the physical group's name
- option - the option the name came from, for the message, or NULL

  Output Parameter:
. label - the group's label

  Note:
  Gets the label of a physical group by name; an unknown name lists the ones the mesh has, and names
  where it came from when the caller says (option: "-contact_boundary", or a default).

  Level: intermediate

.seealso: `MMMeshGetLabel()`, `MMMeshIsPhysicalGroup()`
@*/
PetscErrorCode MMMeshGetLabelFor(DM dm, const char name[], const char option[], DMLabel *label)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(DMHasLabel(dm, name, &has));
  if (!has) {
    char     known[4096] = "";
    PetscInt nl;

    PetscCall(DMGetNumLabels(dm, &nl));
    for (PetscInt l = 0; l < nl; ++l) {
      const char *lname;
      PetscCall(DMGetLabelName(dm, l, &lname));
      if (IsInternalLabel(lname)) continue;
      PetscCall(PetscStrlcat(known, " \"", sizeof(known)));
      PetscCall(PetscStrlcat(known, lname, sizeof(known)));
      PetscCall(PetscStrlcat(known, "\"", sizeof(known)));
    }
    SETERRQ(PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "The mesh has no physical group named \"%s\"%s%s%s. Its physical names are:%s. Fix the option or add the Physical group to the .geo", name, option ? " (" : "", option ? option : "", option ? ")" : "", known[0] ? known : " (none: name the groups with Physical Curve/Surface/Volume(\"name\") in the .geo)");
  }
  PetscCall(DMGetLabel(dm, name, label));
  PetscFunctionReturn(0);
}

/*@
  MMMeshGetLabel - Gets the label of a physical group by name, refusing an unknown name

  Logically collective on dm

  Input Parameters:
+ dm   - the mesh
- name - the physical group's name

  Output Parameter:
. label - the group's label

  Note:
  MMMeshGetLabelFor() without an option to name in the refusal.

  Level: intermediate

.seealso: `MMMeshGetLabelFor()`
@*/
PetscErrorCode MMMeshGetLabel(DM dm, const char name[], DMLabel *label)
{
  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabelFor(dm, name, NULL, label));
  PetscFunctionReturn(0);
}

/*@
  MMMeshLabelHoldsCells - Tells whether a label marks some cell on this rank

  Not collective

  Input Parameters:
+ dm    - the mesh
- label - the label

  Output Parameter:
. holds - whether a local cell has a value other than the label's default

  Level: developer

.seealso: `MMMeshCellGroups()`
@*/
PetscErrorCode MMMeshLabelHoldsCells(DM dm, DMLabel label, PetscBool *holds)
{
  PetscInt cStart, cEnd, def;

  PetscFunctionBeginUser;
  *holds = PETSC_FALSE;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMLabelGetDefaultValue(label, &def));
  for (PetscInt c = cStart; c < cEnd && !*holds; ++c) {
    PetscInt val;
    PetscCall(DMLabelGetValue(label, c, &val));
    *holds = (PetscBool)(val != def);
  }
  PetscFunctionReturn(0);
}

/*@
  MMMeshCellGroups - Lists the physical groups that hold cells, what a body can be made of

  Collective on dm

  Input Parameters:
+ dm  - the mesh
- len - the size of list

  Output Parameter:
. list - the groups as " \"a\" \"b\"", or " (none)"

  Note:
  The physical groups that hold cells (a Physical Surface in 2D, Volume in 3D), as " \"a\" \"b\"",
  or " (none)": what a body can be made of. Collective: a group's cells may all be on other ranks.

  Level: developer

.seealso: `MMMeshLabelHoldsCells()`, `MMMeshIsPhysicalGroup()`
@*/
PetscErrorCode MMMeshCellGroups(DM dm, char list[], size_t len)
{
  PetscInt nl;

  PetscFunctionBeginUser;
  list[0] = 0;
  PetscCall(DMGetNumLabels(dm, &nl));
  for (PetscInt l = 0; l < nl; ++l) {
    const char *lname;
    DMLabel     label;
    PetscInt    n = 0;
    PetscCall(DMGetLabelName(dm, l, &lname));
    PetscCall(DMGetLabelByNum(dm, l, &label));
    if (!IsInternalLabel(lname)) {
      PetscBool holds;
      PetscCall(MMMeshLabelHoldsCells(dm, label, &holds));
      n = holds;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)dm)));
    if (!n) continue;
    PetscCall(PetscStrlcat(list, " \"", len));
    PetscCall(PetscStrlcat(list, lname, len));
    PetscCall(PetscStrlcat(list, "\"", len));
  }
  if (!list[0]) PetscCall(PetscStrncpy(list, " (none)", len));
  PetscFunctionReturn(0);
}

/* A rigid rotation of the coordinates: angle in 2D, rotation vector in 3D (Rodrigues). */
static PetscErrorCode RotateCoordinates(DM dm, const PetscReal rot[], const PetscReal center[])
{
  PetscInt     dim, n;
  PetscReal    R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec          X;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDim(dm, &dim));
  if (dim == 2) {
    const PetscReal c = PetscCosReal(rot[0]), s = PetscSinReal(rot[0]);
    R[0] = c; R[1] = -s; R[3] = s; R[4] = c;
  } else {
    const PetscReal th = PetscSqrtReal(PetscSqr(rot[0]) + PetscSqr(rot[1]) + PetscSqr(rot[2]));
    if (th == 0) PetscFunctionReturn(0);
    const PetscReal k[3] = {rot[0] / th, rot[1] / th, rot[2] / th}, c = PetscCosReal(th), s = PetscSinReal(th);
    for (PetscInt i = 0; i < 3; ++i)
      for (PetscInt j = 0; j < 3; ++j) R[i * 3 + j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
    R[1] -= s * k[2]; R[2] += s * k[1]; R[3] += s * k[2]; R[5] -= s * k[0]; R[6] -= s * k[1]; R[7] += s * k[0];
  }
  PetscCall(DMGetCoordinates(dm, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArray(X, &x));
  for (PetscInt p = 0; p < n / dim; ++p) {
    PetscReal y[3] = {0, 0, 0};
    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt j = 0; j < dim; ++j) y[i] += R[i * 3 + j] * (PetscRealPart(x[p * dim + j]) - center[j]);
    for (PetscInt i = 0; i < dim; ++i) x[p * dim + i] = center[i] + y[i];
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(DMSetCoordinates(dm, X));
  /* the local coordinates again, for whoever reads them before a distribution would rebuild them */
  PetscCall(DMGetCoordinatesLocalSetUp(dm));
  PetscFunctionReturn(0);
}

#define MM_SUPPORTED_MESHES "mmcontact reads gmsh .msh files (format 2.2 to 4.1) of first-order triangles (2D) or tetrahedra (3D) with named physical groups"

/* Reads the gmsh file. PETSc's reader stops a truncated or foreign file with a message about
 * items and sections that does not name the file: catch it and say what is wrong with which file. */
static PetscErrorCode ReadGmsh(MPI_Comm comm, const char file[], PetscBool interpolate, DM *dm, PetscBool *failed)
{
  PetscErrorCode ierr;
  const char    *text     = NULL;
  char          *specific = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromFile(comm, file, "mmcontact", interpolate, dm);
  PetscCall(PetscPopErrorHandler());
  if (failed) {
    /* the caller tries again with PETSc's interpolation, which names the problem if there is one;
     * every rank together, though the reader may have failed on rank 0 alone */
    *failed = (PetscBool)(ierr != 0);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, failed, 1, MPIU_BOOL, MPI_LOR, comm));
    if (*failed) PetscCall(DMDestroy(dm));
    PetscFunctionReturn(0);
  }
  if (ierr) PetscCall(PetscErrorMessage(ierr, &text, &specific));
  PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) could not be read: it is truncated or not a valid gmsh file (the reader says: %s). " MM_SUPPORTED_MESHES ": regenerate it from its .geo (make meshes, or gmsh -2/-3 file.geo)", file, specific && specific[0] ? specific : text);
  PetscFunctionReturn(0);
}

/* P1 assembly needs straight simplices: triangles in 2D, tetrahedra in 3D. Quadrilaterals
 * (Recombine) would fail at assembly with a closure-size message. Serial mesh: rank 0 has
 * every cell, hence the reductions. */
static PetscErrorCode CheckCellTypes(MPI_Comm comm, DM dm, const char file[])
{
  PetscInt       dim, cStart, cEnd, nbad = 0, ncells, first = -1;
  DMPolytopeType expected;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCheck(dim == 2 || dim == 3, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) is a %" PetscInt_FMT "D mesh. " MM_SUPPORTED_MESHES ": mesh the .geo with gmsh -2 or -3", file, dim);
  expected = dim == 2 ? DM_POLYTOPE_TRIANGLE : DM_POLYTOPE_TETRAHEDRON;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    DMPolytopeType ct;
    PetscCall(DMPlexGetCellType(dm, c, &ct));
    if (ct != expected && !nbad++) first = ct;
  }
  ncells = cEnd - cStart;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbad, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &first, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!nbad, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) has %" PetscInt_FMT " %s cells (of %" PetscInt_FMT "): mmcontact supports first-order triangles (2D) and tetrahedra (3D) only. Mesh with gmsh -2 (or -3) at the default order 1 and without Recombine (no Recombine Surface, Mesh.RecombineAll 0)",
             file, nbad, DMPolytopeTypes[first], ncells);
  PetscFunctionReturn(0);
}

/* The polynomial degree of the coordinate field: 1 unless the reader made a high-order one. */
static PetscErrorCode CoordinateDegree(DM dm, PetscInt *degree)
{
  DM           cdm;
  PetscInt     nf;
  PetscObject  disc;
  PetscClassId id;
  PetscSpace   sp;

  PetscFunctionBeginUser;
  *degree = 1;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetNumFields(cdm, &nf));
  if (!nf) PetscFunctionReturn(0);
  PetscCall(DMGetField(cdm, 0, NULL, &disc));
  PetscCall(PetscObjectGetClassId(disc, &id));
  if (id != PETSCFE_CLASSID) PetscFunctionReturn(0);
  PetscCall(PetscFEGetBasisSpace((PetscFE)disc, &sp));
  PetscCall(PetscSpaceGetDegree(sp, degree, NULL));
  PetscFunctionReturn(0);
}

/* A second-order mesh (gmsh -order 2) reads as straight-celled topology with its coordinates a
 * P2 field, carried on edges or cells, not vertex positions; every geometric computation here
 * reads vertex coordinates. Refuse any coordinate dof off the vertices. */
static PetscErrorCode CheckLinearGeometry(MPI_Comm comm, DM dm, const char file[])
{
  PetscSection cs;
  PetscInt     cdim, pStart, pEnd, vStart, vEnd, cStart, cEnd, degree, nbad = 0;
  PetscInt     ct = -1;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(PetscSectionGetChart(cs, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt dof;
    PetscCall(PetscSectionGetDof(cs, p, &dof));
    if (p >= vStart && p < vEnd ? dof != cdim : dof != 0) ++nbad;
  }
  if (vStart < pStart || vEnd > pEnd) nbad += vEnd - vStart; /* vertices without coordinates */
  PetscCall(CoordinateDegree(dm, &degree));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  if (cEnd > cStart) {
    DMPolytopeType t;
    PetscCall(DMPlexGetCellType(dm, cStart, &t));
    ct = t;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbad, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &degree, 1, MPIU_INT, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ct, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(degree <= 1, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) has high-order (order %" PetscInt_FMT ", curved) %s cells: its coordinates are a degree-%" PetscInt_FMT " field carried on edges or cells, not vertex positions. mmcontact supports first-order triangles (2D) and tetrahedra (3D) only: mesh with gmsh -2 (or -3) at the default order 1 (no -order 2, no Mesh.ElementOrder > 1)",
             file, degree, ct >= 0 ? DMPolytopeTypes[ct] : "unknown", degree);
  PetscCheck(!nbad, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) has coordinates that are not vertex positions (%" PetscInt_FMT " points with other coordinate dofs; a discontinuous coordinate field, e.g. from -dm_plex_gmsh_highorder). mmcontact supports first-order triangles (2D) and tetrahedra (3D) with vertex coordinates only: drop that option", file, nbad);
  PetscFunctionReturn(0);
}

/*@
  MMMeshCellCentroid - Computes the mean of a cell's vertices, on the rank that holds it

  Not collective

  Input Parameters:
+ dm - the mesh
- c  - the cell, a local point

  Output Parameter:
. centroid - the mean, one entry per coordinate

  Level: developer

.seealso: `MMCellsCreate()`
@*/
PetscErrorCode MMMeshCellCentroid(DM dm, PetscInt c, PetscReal centroid[])
{
  DM           cdm;
  Vec          X;
  PetscScalar *xc = NULL;
  PetscInt     nx, cdim;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexVecGetClosure(cdm, NULL, X, c, &nx, &xc));
  for (PetscInt d = 0; d < cdim; ++d) {
    centroid[d] = 0;
    for (PetscInt i = 0; i < nx / cdim; ++i) centroid[d] += PetscRealPart(xc[i * cdim + d]) / (nx / cdim);
  }
  PetscCall(DMPlexVecRestoreClosure(cdm, NULL, X, c, &nx, &xc));
  PetscFunctionReturn(0);
}

/* The vertices of simplex cell c in the order of its closure, which is the order the file gave them
 * (the reader keeps it and interpolation preserves it), found through cones and orientations
 * instead of a closure: the closure of a triangle starts with its first edge as oriented, and a
 * tetrahedron's with its first face as oriented, whose orientation is a rotation (o >= 0, the same
 * cyclic order) or a reflection (o < 0); the last vertex is the one off that face. Only the cyclic
 * order of the first face matters for the sign of the determinant, so a reflected face is returned
 * in its own order with *flip set. */
static PetscErrorCode ClosureVertexOrder(DM dm, PetscInt depth, PetscInt dim, PetscInt c, PetscInt v[], PetscBool *flip)
{
  const PetscInt *cone, *ornt, *econe, *tcone, *tornt;
  PetscInt        tri = c;

  PetscFunctionBeginUser;
  *flip = PETSC_FALSE;
  if (depth == 1) {
    PetscCall(DMPlexGetCone(dm, c, &cone));
    for (PetscInt a = 0; a <= dim; ++a) v[a] = cone[a];
    PetscFunctionReturn(0);
  }
  if (dim == 3) {
    PetscCall(DMPlexGetCone(dm, c, &cone));
    PetscCall(DMPlexGetConeOrientation(dm, c, &ornt));
    tri   = cone[0];
    *flip = (PetscBool)(ornt[0] < 0);
  }
  PetscCall(DMPlexGetCone(dm, tri, &tcone));
  PetscCall(DMPlexGetConeOrientation(dm, tri, &tornt));
  {
    const PetscInt *arr = DMPolytopeTypeGetVertexArrangment(DM_POLYTOPE_SEGMENT, tornt[0]);
    PetscCall(DMPlexGetCone(dm, tcone[0], &econe));
    v[0] = econe[arr[0]];
    v[1] = econe[arr[1]];
  }
  PetscCall(DMPlexGetCone(dm, tcone[1], &econe));
  v[2] = econe[0] == v[0] || econe[0] == v[1] ? econe[1] : econe[0];
  if (dim == 3) {
    /* the vertex off the first face: one of the second face's edges has it */
    PetscCall(DMPlexGetCone(dm, cone[1], &tcone));
    for (PetscInt e = 0; e < 3; ++e) {
      PetscCall(DMPlexGetCone(dm, tcone[e], &econe));
      for (PetscInt k = 0; k < 2; ++k)
        if (econe[k] != v[0] && econe[k] != v[1] && econe[k] != v[2]) v[3] = econe[k];
    }
  }
  PetscFunctionReturn(0);
}

/* The Jacobian determinant of cell c's map from DMPlex's reference simplex, from its closure's
 * vertex order: DMPlexComputeCellGeometryAffineFEM's, > 0 for a cell oriented as the reference. */
static PetscErrorCode CellSignedDet(DM dm, PetscInt depth, PetscInt dim, PetscSection cs, const PetscScalar *x, PetscInt c, PetscReal *det)
{
  PetscInt  v[MM_MAX_DIM + 1];
  PetscReal J[MM_MAX_DIM][MM_MAX_DIM] = {{0}}, x0[MM_MAX_DIM];
  PetscBool flip;

  PetscFunctionBeginUser;
  PetscCall(ClosureVertexOrder(dm, depth, dim, c, v, &flip));
  for (PetscInt a = 0; a <= dim; ++a) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v[a], &off));
    for (PetscInt d = 0; d < dim; ++d) {
      if (!a) x0[d] = PetscRealPart(x[off + d]);
      else J[d][a - 1] = PetscRealPart(x[off + d]) - x0[d];
    }
  }
  *det = MMDetInverse(dim, J, NULL);
  /* DMPlex's reference tetrahedron is oriented the other way (its first face's normal points
   * inwards): a valid tetrahedron has the negative determinant in closure order */
  if (flip != (dim == 3)) *det = -*det;
  *det /= dim == 2 ? 4.0 : 8.0; /* the reference simplex has edges of length 2 */
  PetscFunctionReturn(0);
}

/* An inverted cell (vertex order reversed, negative Jacobian determinant) enters the mass and
 * stiffness with the wrong sign and the run goes on silently: DMPlex's gmsh reader keeps the
 * file's vertex order. Refuse it on the serial mesh, naming the first one. */
static PetscErrorCode CheckOrientation(MPI_Comm comm, DM dm, const char file[])
{
  PetscInt    cStart, cEnd, ninv = 0, ncells, first = -1, dim, cdim, depth;
  PetscSection       cs;
  Vec                X;
  const PetscScalar *x;
  PetscReal   first_det = 0, centroid[3] = {0, 0, 0};
  char        where[128];

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscReal detJ = 0;
    if (dim == cdim) PetscCall(CellSignedDet(dm, depth, dim, cs, x, c, &detJ));
    else {
      PetscReal v0[3], J[9], invJ[9]; /* a surface mesh in space: PETSc's own, by closures */
      PetscCall(DMPlexComputeCellGeometryAffineFEM(dm, c, v0, J, invJ, &detJ));
    }
    if (detJ > 0) continue;
    if (!ninv++) {
      first     = c;
      first_det = detJ;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  if (first >= 0) PetscCall(MMMeshCellCentroid(dm, first, centroid));
  ncells = cEnd - cStart;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ninv, 1, MPIU_INT, MPI_SUM, comm));
  if (!ninv) PetscFunctionReturn(0);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  /* the serial mesh lives on rank 0 */
  PetscCallMPI(MPI_Bcast(&first, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&first_det, 1, MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(centroid, 3, MPIU_REAL, 0, comm));
  if (dim == 2) PetscCall(PetscSNPrintf(where, sizeof(where), "(%g, %g)", (double)centroid[0], (double)centroid[1]));
  else PetscCall(PetscSNPrintf(where, sizeof(where), "(%g, %g, %g)", (double)centroid[0], (double)centroid[1], (double)centroid[2]));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) has an inverted (negatively oriented) element: cell %" PetscInt_FMT " (counting the file's %s from 0) with centroid %s has Jacobian determinant %g <= 0 (inverted cells: %" PetscInt_FMT " of %" PetscInt_FMT "). Their mass and stiffness would enter with the wrong sign. %s",
          file, first, dim == 2 ? "triangles" : "tetrahedra", where, (double)first_det, ninv, ncells,
          ninv == ncells ? "The whole surface (volume) is oriented backwards: reverse its Curve Loop (Surface Loop) in the .geo, or add ReverseMesh, and remesh" : "Regenerate the mesh from its .geo with gmsh, or fix the node order of that element");
}

/* Each local vertex's number in the file's serial mesh (from 0), through the migration SF of the
 * distribution, whose roots are the serial mesh's points on rank 0: a key that does not depend on
 * the number of ranks, for checkpoints (docs/method.md section 9). */
static PetscErrorCode OriginalVertexNumbers(MPI_Comm comm, DM dist, PetscSF migration, PetscInt vStart0, PetscInt **orig)
{
  PetscInt           vStart, vEnd, pStart, pEnd, nleaves, *point;
  const PetscInt    *ilocal;
  const PetscSFNode *iremote;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&vStart0, 1, MPIU_INT, 0, comm));
  PetscCall(DMPlexGetDepthStratum(dist, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetChart(dist, &pStart, &pEnd));
  PetscCall(PetscMalloc1(vEnd - vStart, orig));
  if (!migration) {
    for (PetscInt v = vStart; v < vEnd; ++v) (*orig)[v - vStart] = v - vStart;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(pEnd - pStart, &point));
  for (PetscInt p = pStart; p < pEnd; ++p) point[p - pStart] = -1;
  PetscCall(PetscSFGetGraph(migration, NULL, &nleaves, &ilocal, &iremote));
  for (PetscInt l = 0; l < nleaves; ++l) point[(ilocal ? ilocal[l] : l) - pStart] = iremote[l].index;
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscCheck(point[v - pStart] >= vStart0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Vertex %" PetscInt_FMT " has no vertex of the serial mesh", v);
    (*orig)[v - vStart] = point[v - pStart] - vStart0;
  }
  PetscCall(PetscFree(point));
  PetscFunctionReturn(0);
}

/*@
  MMMeshRead - Reads the serial mesh of a gmsh file and checks it (cell types, linear geometry,
  nodes, orientation), its facet and point groups read

  Collective

  Input Parameters:
+ comm - the communicator of the run
- file - the mesh file (-mesh)

  Output Parameters:
+ dm          - the serial mesh, on rank 0, named "mesh"
. facets      - its facet groups, for MMMeshDistribute()
- vertex_file - each serial vertex's position among the file's nodes (MMMeshFileNodes())

  Note:
  The serial mesh of file, checked (cell types, linear geometry, orientation), with its facet groups
  read (facets, for MMMeshDistribute) and each vertex's position among the file's nodes.

  The physical names become label names (-dm_plex_gmsh_use_regions), so every option can refer to
  groups by name. The mesh is read without faces and edges when this code can read the file's facet
  groups (MMMeshFacetsRead()); otherwise by PETSc's reader, interpolated, which labels the facets
  itself. An empty file name is refused.

  Level: intermediate

.seealso: `MMMeshDistribute()`, `MMMeshCheckFile()`, `MMMeshFacetsRead()`, `MMMeshPointGroupsRead()`
@*/
PetscErrorCode MMMeshRead(MPI_Comm comm, const char file[], DM *dm, MMMeshFacets *facets, PetscInt **vertex_file)
{
  PetscInt  *vtag = NULL;
  PetscBool  failed;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(facets, sizeof(*facets)));
  PetscCheck(file[0], comm, PETSC_ERR_USER_INPUT, "No mesh given: set -mesh FILE.msh (a gmsh mesh with named physical groups; `make meshes` builds the ones in meshes/)");
  PetscCall(MMMeshCheckFile(comm, file));
  /* physical names become label names, so every option can refer to groups by name */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  /* without faces and edges, never interpolated: P1 needs cells and vertices, and the facet groups
   * are read here and carried by their cells (src/mesh/facets.c) */
  PetscCall(ReadGmsh(comm, file, PETSC_FALSE, dm, &failed));
  /* a second-order mesh needs the reader's interpolation, which then leads to its refusal below */
  if (failed) PetscCall(ReadGmsh(comm, file, PETSC_TRUE, dm, NULL));
  /* on the serial mesh, before distribution: the first bad cell is named by its file order */
  PetscCall(CheckCellTypes(comm, *dm, file));
  PetscCall(CheckLinearGeometry(comm, *dm, file));
  /* before the orientation check, which would call a cell with a NaN vertex inverted */
  PetscCall(MMMeshFileNodes(comm, *dm, file, vertex_file, &vtag));
  if (!failed) PetscCall(MMMeshFacetsRead(comm, *dm, file, vtag, facets, &facets->read));
  if (!failed && !facets->read) {
    /* a file read here cannot be (binary): PETSc's reader labels the facets, interpolating on rank 0.
     * The vertices are the same, in the same order. */
    PetscCall(DMDestroy(dm));
    PetscCall(ReadGmsh(comm, file, PETSC_TRUE, dm, NULL));
  }
  /* the Physical Points (-point_force), labelled on the serial mesh: the distribution carries them */
  if (!failed) PetscCall(MMMeshPointGroupsRead(comm, *dm, file, vtag));
  PetscCall(PetscFree(vtag));
  PetscCall(CheckOrientation(comm, *dm, file));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscFunctionReturn(0);
}

/*@
  MMMeshDistribute - Rotates the serial mesh and distributes it by METIS, its facet groups labelled
  on the vertices

  Collective on dm

  Input Parameters:
+ rotation - MM_MAX_DIM angles: an angle in 2D, a rotation vector in 3D; all zero for none
- center   - the point rotated about

  Output Parameters:
+ facets      - the facet groups MMMeshRead() gave, freed
. dm          - on input the serial mesh, on output the distributed one
- vertex_orig - each local vertex's number in the serial mesh, a key that does not depend on the
                number of ranks

  Note:
  The serial mesh read by MMMeshRead rotated by rotation (MM_MAX_DIM angles, about center) and
  distributed by METIS, its facet groups labelled on the vertices; each vertex's number in the
  serial mesh into vertex_orig. Frees facets.

  DMSetFromOptions() is then called with PETSc's own distribution off, so that the mesh is not
  distributed a second time, and -dm_view shows it.

  Level: intermediate

.seealso: `MMMeshRead()`, `MMMeshFacetsLabelVertices()`
@*/
PetscErrorCode MMMeshDistribute(const PetscReal rotation[], const PetscReal center[], MMMeshFacets *facets, DM *dm, PetscInt **vertex_orig)
{
  MPI_Comm  comm   = PetscObjectComm((PetscObject)*dm);
  PetscBool rotate = PETSC_FALSE;
  DM        dist;
  PetscSF   migration = NULL;
  PetscInt  vStart0, vEnd0;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) rotate = (PetscBool)(rotate || rotation[d] != 0);
  if (rotate) PetscCall(RotateCoordinates(*dm, rotation, center));

  PetscCall(MMPartitionerRegisterMetis());
  {
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(*dm, &part));
    PetscCall(PetscPartitionerSetType(part, MM_PARTITIONER_METIS));
    PetscCall(PetscPartitionerSetFromOptions(part));
    PetscCall(MMPartitionerMetisSetDM(part, *dm));
  }
  PetscCall(DMPlexGetDepthStratum(*dm, 0, &vStart0, &vEnd0));
  PetscCall(DMPlexDistribute(*dm, 0, &migration, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscCall(OriginalVertexNumbers(comm, *dm, migration, vStart0, vertex_orig));
  PetscCall(PetscSFDestroy(&migration));
  if (facets->read) PetscCall(MMMeshFacetsLabelVertices(facets, *dm));
  PetscCall(MMMeshFacetsDestroy(facets));
  /* DMSetFromOptions would distribute the mesh a second time, moving every vertex away from the
   * numbers just computed: the METIS partition above is the one wanted */
  PetscCall(DMPlexDistributeSetDefault(*dm, PETSC_FALSE));
  PetscCall(DMSetFromOptions(*dm));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscFunctionReturn(0);
}

/*@
  MMMeshGetSizes - Gives the global numbers of cells and vertices of the distributed mesh

  Collective on dm

  Input Parameter:
. dm - the mesh

  Output Parameters:
+ ncells    - the number of cells
- nvertices - the number of vertices

  Note:
  Global numbers of cells and vertices of the distributed mesh: a point shared by several ranks is a
  leaf of the point SF on all of them but its owner, so the leaves are left out.

  Level: intermediate

.seealso: `MMCellsCreate()`
@*/
PetscErrorCode MMMeshGetSizes(DM dm, PetscInt *ncells, PetscInt *nvertices)
{
  PetscSF         sf;
  PetscInt        vStart, vEnd, cStart, cEnd, nleaves, n[2];
  const PetscInt *leaves;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  n[0] = cEnd - cStart;
  n[1] = vEnd - vStart;
  for (PetscInt l = 0; l < PetscMax(nleaves, 0); ++l) {
    const PetscInt p = leaves ? leaves[l] : l;
    if (p >= cStart && p < cEnd) --n[0];
    if (p >= vStart && p < vEnd) --n[1];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, n, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  *ncells    = n[0];
  *nvertices = n[1];
  PetscFunctionReturn(0);
}
