/* The nodal forces of the pressures (-pressure) and the concentrated forces (-point_force) at
 * amplitude 1, README "Loads in time" and docs/method.md section 10. Small strain: both act in
 * the reference configuration, so each is a fixed vector, one load part of src/fem/loads.c.
 *
 * A pressure p on a facet F of outward unit normal n is the traction t = -p n: its nodal forces are
 * int_F -p n phi_i = -p n |F| / d on each of F's d vertices (P1 on a simplex facet), the same rule
 * as a traction's (MMMeshFacetsAddNodal). A point force is added once, on the rank that owns its
 * vertex. The callers sum over ranks by a DMLocalToGlobal with ADD, as for the tractions. */
#include "femimpl.h"
#include "mesh.h"

/* A pressure acts on boundary faces: a group of cells or of nodes would load nothing, and a face
 * between two cells has no outward side. */
static PetscErrorCode CheckPressureGroup(DM dm, const char name[], DMLabel label, const MMFacetList *fl)
{
  PetscInt  counts[3] = {fl->n, 0, 0}; /* facets, cells, interior facets */
  PetscBool holds;
  MPI_Comm  comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(MMMeshLabelHoldsCells(dm, label, &holds));
  counts[1] = holds;
  for (PetscInt i = 0; i < fl->n; ++i) counts[2] += fl->interior[i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!counts[1], comm, PETSC_ERR_USER_INPUT, "-pressure %s: the physical group \"%s\" holds cells, not boundary faces. A pressure acts on a Physical %s of the boundary", name, name, fl->dim == 2 ? "Curve (2D)" : "Surface (3D)");
  PetscCheck(counts[0], comm, PETSC_ERR_USER_INPUT, "-pressure %s: the physical group \"%s\" holds no faces. A pressure acts on a Physical %s of the boundary", name, name, fl->dim == 2 ? "Curve (2D)" : "Surface (3D)");
  PetscCheck(!counts[2], comm, PETSC_ERR_USER_INPUT, "-pressure %s: %" PetscInt_FMT " of the group's faces lie inside the mesh, between two cells, where a face has no outward normal. Give a pressure on the boundary only (or a -traction, which needs no normal)", name, counts[2]);
  PetscFunctionReturn(0);
}

/* Facet i's unit normal pointing away from its cell's vertex off it: the outward normal. */
static PetscErrorCode FacetOutwardNormal(DM dm, const MMFacetList *fl, PetscInt i, PetscSection cs, const PetscScalar xc[], const PetscReal y[], PetscReal n[])
{
  const PetscInt dim = fl->dim;
  PetscInt       w[MM_MAX_DIM + 1], off;
  PetscReal      len = 0, side = 0;

  PetscFunctionBeginUser;
  if (dim == 2) {
    n[0] = y[3] - y[1];
    n[1] = -(y[2] - y[0]);
  } else {
    const PetscReal a[3] = {y[3] - y[0], y[4] - y[1], y[5] - y[2]}, b[3] = {y[6] - y[0], y[7] - y[1], y[8] - y[2]};
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
  }
  PetscCall(MMMeshCellVertices(dm, fl->depth, dim, fl->cell[i], w));
  PetscCall(PetscSectionGetOffset(cs, w[fl->off[i]], &off));
  for (PetscInt d = 0; d < dim; ++d) {
    len += n[d] * n[d];
    side += n[d] * (PetscRealPart(xc[off + d]) - y[d]);
  }
  len = PetscSqrtReal(len);
  /* the cell's own vertex lies inside: the outward normal points away from it */
  for (PetscInt d = 0; d < dim; ++d) n[d] *= (side > 0 ? -1.0 : 1.0) / len;
  PetscFunctionReturn(0);
}

/*@
  MMFEAddPressure - Adds a pressure's nodal forces at amplitude 1 to a local force vector

  Not collective

  Input Parameters:
+ op   - the operators
. pr   - the pressure group
- floc - the local Cartesian force vector of op's DM, added to

  Note:
  Nodal forces of pressure pr at amplitude 1: -p n |F| / d on each vertex of each facet F, added to
  the local vector floc of op->dm (Cartesian).

  Level: developer

.seealso: `MMFEAddTraction()`, `MMFEAddPointForce()`
@*/
PetscErrorCode MMFEAddPressure(MMOperators op, const MMPressure *pr, Vec floc)
{
  DM                 dm  = op->dm;
  const PetscInt     dim = op->dim;
  DMLabel            label;
  MMFacetList        fl;
  PetscSection       cs;
  Vec                X;
  const PetscScalar *xc;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, pr->name, &label));
  PetscCall(MMMeshGetFacets(dm, pr->name, &fl));
  PetscCall(CheckPressureGroup(dm, pr->name, label, &fl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &xc));
  PetscCall(VecGetArray(floc, &f));
  for (PetscInt i = 0; i < fl.n; ++i) {
    PetscInt  v[MM_MAX_DIM];
    PetscReal y[MM_MAX_DIM * MM_MAX_DIM], n[MM_MAX_DIM], measure;
    PetscCall(MMFacetGeometry(dm, &fl, i, cs, xc, v, y, &measure));
    PetscCall(FacetOutwardNormal(dm, &fl, i, cs, xc, y, n));
    for (PetscInt k = 0; k < dim; ++k) {
      PetscInt off, end;
      PetscCall(DMPlexGetPointLocal(dm, v[k], &off, &end));
      for (PetscInt c = 0; c < dim; ++c) f[off + c] += -pr->value[0] * n[c] * measure / dim;
    }
  }
  PetscCall(VecRestoreArray(floc, &f));
  PetscCall(VecRestoreArrayRead(X, &xc));
  PetscCall(MMFacetListDestroy(&fl));
  PetscFunctionReturn(0);
}

/* A point force acts on the nodes of a Physical Point group: a group of faces or cells would put
 * the whole force on each of its many nodes, which is never what a user means. */
static PetscErrorCode CheckPointGroup(DM dm, const char name[], DMLabel label, PetscInt nnodes)
{
  PetscInt    counts[3] = {nnodes, 0, 0}; /* owned nodes, cells, facets */
  PetscBool   holds;
  MMFacetList fl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCall(MMMeshLabelHoldsCells(dm, label, &holds));
  PetscCall(MMMeshGetFacets(dm, name, &fl));
  counts[1] = holds;
  counts[2] = fl.n;
  PetscCall(MMFacetListDestroy(&fl));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!counts[1] && !counts[2], comm, PETSC_ERR_USER_INPUT, "-point_force %s: the physical group \"%s\" holds %s, and a point force would load each of its %" PetscInt_FMT " nodes with the whole force. Give a Physical Point group, or spread the load with -traction or -pressure", name, name, counts[1] ? "cells" : "faces", counts[0]);
  PetscCheck(counts[0], comm, PETSC_ERR_USER_INPUT, "-point_force %s: the physical group \"%s\" holds no node of the mesh. Give a Physical Point of the .geo at a node of the mesh", name, name);
  PetscFunctionReturn(0);
}

/*@
  MMFEAddPointForce - Adds a point force's nodal forces at amplitude 1 to a local force vector, on
  the rank that owns each node

  Not collective

  Input Parameters:
+ op   - the operators
. pf   - the point force group
- floc - the local Cartesian force vector, added to

  Note:
  Nodal forces of point force pf at amplitude 1: its vector on each node of the group, added to
  floc on the rank that owns the node only (a shared node is in several ranks' local vectors).

  Level: developer

.seealso: `MMFEAddTraction()`, `MMFEAddPressure()`
@*/
PetscErrorCode MMFEAddPointForce(MMOperators op, const MMPointForce *pf, Vec floc)
{
  DM                  dm  = op->dm;
  const PetscInt      dim = op->dim;
  DMLabel             label;
  PetscSection        gs;
  PetscInt            np, *pts, *vals, vStart, vEnd, nnodes = 0;
  PetscScalar        *f;

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, pf->name, &label));
  PetscCall(MMMeshLabelPoints(label, &np, &pts, &vals));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArray(floc, &f));
  for (PetscInt i = 0; i < np; ++i) {
    PetscInt goff, off, end;
    if (pts[i] < vStart || pts[i] >= vEnd) continue;
    PetscCall(PetscSectionGetOffset(gs, pts[i], &goff));
    if (goff < 0) continue; /* another rank's */
    PetscCall(DMPlexGetPointLocal(dm, pts[i], &off, &end));
    for (PetscInt c = 0; c < dim; ++c) f[off + c] += pf->value[c];
    ++nnodes;
  }
  PetscCall(VecRestoreArray(floc, &f));
  PetscCall(PetscFree2(pts, vals));
  PetscCall(CheckPointGroup(dm, pf->name, label, nnodes));
  PetscFunctionReturn(0);
}
