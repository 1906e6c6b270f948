/* -probes A,B: the mean displacement and velocity of each physical group's nodes, in history.csv
 * (probe_A_ux, ..., probe_A_vx, ...): what Abaqus's *NODE PRINT, code_aster's RELEVE and MOOSE's
 * postprocessors give.
 *
 * The mean is weighted by each node's lumped standard mass m_i = sum over its cells of rho |cell| /
 * (dim + 1) (the row sums of M, README "History columns"): sum_i m_i u_i / sum_i m_i over the group's nodes,
 * with the Cartesian displacement of solution.h5 (Dirichlet data included). Weighted, so that it is
 * the motion of the group's centre of mass and does not change when the mesh is refined in part of
 * the group, as a plain mean of nodes does. By M, not by M*: the modified and redistributed masses
 * have no normal mass at the contact nodes, so a probe on the contact face would have no mean
 * along the normal. For a whole body the probe is its centre of mass's motion: the ucm and vcm
 * columns when the run's M* is M (-mass standard); they are M*'s otherwise (README "History
 * columns"). */
#include "outputimpl.h"
#include "mesh.h"

/* 1 on the group's vertices (the closure of the points its label marks), on every rank that has
 * them: a vertex this rank owns may be marked only through another rank's cell. */
static PetscErrorCode GroupVertexFlags(const MMOutput *o, const char name[], Vec flags)
{
  DM           dm = o->dm, dms = o->dm_scalar;
  DMLabel      label;
  Vec          loc;
  PetscScalar *f;
  PetscInt     n, *pts, *vals, vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(MMMeshGetLabel(dm, name, &label));
  PetscCall(MMMeshLabelPoints(label, &n, &pts, &vals));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetLocalVector(dms, &loc));
  PetscCall(VecZeroEntries(loc));
  PetscCall(VecGetArray(loc, &f));
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt *closure = NULL, nc;
    PetscCall(DMPlexGetTransitiveClosure(dm, pts[i], PETSC_TRUE, &nc, &closure));
    for (PetscInt k = 0; k < nc; ++k) {
      const PetscInt p = closure[2 * k];
      PetscInt       off;
      if (p < vStart || p >= vEnd) continue;
      PetscCall(DMPlexGetPointLocal(dms, p, &off, NULL));
      f[off] = 1;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[i], PETSC_TRUE, &nc, &closure));
  }
  PetscCall(VecRestoreArray(loc, &f));
  PetscCall(PetscFree2(pts, vals));
  PetscCall(VecZeroEntries(flags));
  PetscCall(DMLocalToGlobal(dms, loc, ADD_VALUES, flags));
  PetscCall(DMRestoreLocalVector(dms, &loc));
  PetscFunctionReturn(0);
}

/* Group g's owned vertices and their masses appended to the tables. */
static PetscErrorCode AddGroup(MMOutput *o, PetscInt g, Vec flags, Vec mloc, PetscInt *cap)
{
  MMProbes          *pr  = &o->probes;
  DM                 dms = o->dm_scalar;
  PetscSection       gs;
  const PetscScalar *f, *m;
  PetscInt           vStart, vEnd, rstart, k = pr->start[g];

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dms, &gs));
  PetscCall(DMPlexGetDepthStratum(dms, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(flags, &rstart, NULL));
  PetscCall(VecGetArrayRead(flags, &f));
  PetscCall(VecGetArrayRead(mloc, &m));
  pr->mass[g] = 0;
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, loff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0 || PetscRealPart(f[goff - rstart]) == 0) continue; /* another rank's, or not in the group */
    PetscCall(DMPlexGetPointLocal(dms, v, &loff, NULL));
    if (k == *cap) {
      *cap = PetscMax(64, 2 * *cap);
      PetscCall(PetscRealloc(sizeof(PetscInt) * *cap, &pr->vertex));
      PetscCall(PetscRealloc(sizeof(PetscReal) * *cap, &pr->weight));
    }
    pr->vertex[k] = v;
    pr->weight[k] = PetscRealPart(m[loff]);
    pr->mass[g] += pr->weight[k];
    ++k;
  }
  pr->start[g + 1] = k;
  PetscCall(VecRestoreArrayRead(mloc, &m));
  PetscCall(VecRestoreArrayRead(flags, &f));
  PetscFunctionReturn(0);
}

/* Finds each -probes group's nodes and their lumped masses (mloc, local on dm_scalar; the caller's
 * MMFEVertexMasses): before the output is opened, so that a group the mesh lacks is refused with the
 * other input. */
PetscErrorCode MMProbesSetUp(MMOutput *o, Vec mloc)
{
  MMProbes *pr   = &o->probes;
  MPI_Comm  comm = PETSC_COMM_WORLD;
  char    **names;
  int       n;
  PetscInt  cap = 0;
  Vec       flags;

  PetscFunctionBeginUser;
  if (!o->probe_list[0]) PetscFunctionReturn(0);
  PetscCall(PetscStrToArray(o->probe_list, ',', &n, &names));
  pr->n = n;
  PetscCall(PetscCalloc4(n, &pr->name, n + 1, &pr->start, n, &pr->mass, 2 * MM_MAX_DIM * n, &pr->mean));
  pr->vertex = NULL; /* grown by AddGroup */
  pr->weight = NULL;
  PetscCall(DMGetGlobalVector(o->dm_scalar, &flags));
  for (PetscInt g = 0; g < n; ++g) {
    PetscCheck(names[g][0], comm, PETSC_ERR_USER_INPUT, "-probes %s has an empty name: give physical group names separated by commas", o->probe_list);
    for (PetscInt h = 0; h < g; ++h) PetscCheck(strcmp(names[g], names[h]), comm, PETSC_ERR_USER_INPUT, "-probes names the group %s twice: its columns would be repeated", names[g]);
    PetscCall(PetscStrncpy(pr->name[g], names[g], sizeof(pr->name[g])));
    PetscCall(GroupVertexFlags(o, names[g], flags));
    PetscCall(AddGroup(o, g, flags, mloc, &cap));
  }
  PetscCall(DMRestoreGlobalVector(o->dm_scalar, &flags));
  PetscCall(PetscStrToArrayDestroy(n, names));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, pr->mass, n, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt g = 0; g < n; ++g) PetscCheck(pr->mass[g] > 0, comm, PETSC_ERR_USER_INPUT, "-probes: the group %s has no nodes with mass", pr->name[g]);
  PetscFunctionReturn(0);
}

/* The means of the current state, from the whole Cartesian fields in disp_cart and vel_cart.
 * Collective. */
PetscErrorCode MMProbesEvaluate(MMOutput *o)
{
  MMProbes          *pr  = &o->probes;
  const PetscInt     dim = o->dim;
  PetscSection       gs;
  const PetscScalar *u, *v;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  if (!pr->n) PetscFunctionReturn(0);
  PetscCall(DMGetGlobalSection(o->dm_out, &gs));
  PetscCall(VecGetOwnershipRange(o->disp_cart, &rstart, NULL));
  PetscCall(VecGetArrayRead(o->disp_cart, &u));
  PetscCall(VecGetArrayRead(o->vel_cart, &v));
  for (PetscInt g = 0; g < pr->n; ++g) {
    PetscReal *s = pr->mean + 2 * dim * g;
    for (PetscInt d = 0; d < 2 * dim; ++d) s[d] = 0;
    for (PetscInt k = pr->start[g]; k < pr->start[g + 1]; ++k) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(gs, pr->vertex[k], &off));
      for (PetscInt d = 0; d < dim; ++d) {
        s[d] += pr->weight[k] * PetscRealPart(u[off - rstart + d]);
        s[dim + d] += pr->weight[k] * PetscRealPart(v[off - rstart + d]);
      }
    }
  }
  PetscCall(VecRestoreArrayRead(o->vel_cart, &v));
  PetscCall(VecRestoreArrayRead(o->disp_cart, &u));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, pr->mean, 2 * dim * pr->n, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  for (PetscInt g = 0; g < pr->n; ++g)
    for (PetscInt d = 0; d < 2 * dim; ++d) pr->mean[2 * dim * g + d] /= pr->mass[g];
  PetscFunctionReturn(0);
}

PetscErrorCode MMProbesDestroy(MMProbes *pr)
{
  PetscFunctionBeginUser;
  if (!pr->n) PetscFunctionReturn(0);
  PetscCall(PetscFree4(pr->name, pr->start, pr->mass, pr->mean));
  PetscCall(PetscFree(pr->vertex));
  PetscCall(PetscFree(pr->weight));
  pr->n = 0;
  PetscFunctionReturn(0);
}
