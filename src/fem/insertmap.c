/* DMLocalToGlobal with INSERT_VALUES, from a map built once.
 *
 * PETSc 3.18's DMLocalToGlobal(INSERT_VALUES) on a DM with a section walks the whole chart and asks
 * both sections six questions per point, at every call. The loads' reactions and work convert
 * between the constrained DM and its unconstrained copy several times a step (src/fem/loads.c), and
 * on the 315k-dof slab with its moving press that was most of the energy audit's time (docs/scaling.md,
 * "Without faces and edges"). The map keeps, for every owned dof PETSc would copy, its local and
 * global offsets, in PETSc's order and with its rules: off-rank points and points without global
 * dofs are skipped, and a constrained dof is dropped when the global section drops it. */
#include <petscsection.h>
#include "fem.h"

static PetscErrorCode Build(DM dm, MMInsertMap *m, Vec g)
{
  PetscSection s, gs;
  PetscInt     pStart, pEnd, gStart, cap;

  PetscFunctionBeginUser;
  PetscCall(MMInsertMapDestroy(m));
  m->dm = dm;
  PetscCall(DMHasBasisTransform(dm, &m->transform));
  if (m->transform) PetscFunctionReturn(0);
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(PetscSectionGetChart(s, &pStart, &pEnd));
  PetscCall(VecGetOwnershipRange(g, &gStart, NULL));
  PetscCall(VecGetLocalSize(g, &cap));
  PetscCall(PetscMalloc2(cap, &m->loc, cap, &m->glob));
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt dof, gdof, cdof, gcdof, off, goff;

    PetscCall(PetscSectionGetDof(s, p, &dof));
    PetscCall(PetscSectionGetDof(gs, p, &gdof));
    PetscCall(PetscSectionGetConstraintDof(s, p, &cdof));
    PetscCall(PetscSectionGetConstraintDof(gs, p, &gcdof));
    PetscCall(PetscSectionGetOffset(s, p, &off));
    PetscCall(PetscSectionGetOffset(gs, p, &goff));
    if (!gdof || goff < 0) continue;
    PetscCheck(dof == gdof && (!gcdof || cdof == gcdof), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Inconsistent sections at point %" PetscInt_FMT ": dof %" PetscInt_FMT ", global dof %" PetscInt_FMT ", constrained %" PetscInt_FMT " and %" PetscInt_FMT, p, dof, gdof, cdof, gcdof);
    if (!gcdof) {
      for (PetscInt d = 0; d < dof; ++d) {
        m->loc[m->n]    = off + d;
        m->glob[m->n++] = goff - gStart + d;
      }
    } else {
      const PetscInt *cdofs;
      PetscInt        cind = 0, e = 0;
      PetscCall(PetscSectionGetConstraintIndices(s, p, &cdofs));
      for (PetscInt d = 0; d < dof; ++d) {
        if (cind < cdof && d == cdofs[cind]) {
          ++cind;
          continue;
        }
        m->loc[m->n]    = off + d;
        m->glob[m->n++] = goff - gStart + e++;
      }
    }
    PetscCheck(m->n <= cap, PETSC_COMM_SELF, PETSC_ERR_PLIB, "More owned dofs than the global vector holds");
  }
  PetscFunctionReturn(0);
}

/*@
  MMInsertMapLocalToGlobal - Inserts a local vector's owned dofs into a global vector, as
  DMLocalToGlobal() with INSERT_VALUES does, through a map of dof pairs built once per DM

  Collective

  Input Parameters:
+ dm - the DM of l and g
. m  - the map, (re)built when it was built for another DM
- l  - the local vector

  Output Parameter:
. g - the global vector, its owned dofs set

  Note:
  g = l on g's owned dofs, as DMLocalToGlobal(dm, l, INSERT_VALUES, g); m is (re)built when it was
  built for another DM.

  Level: developer

.seealso: `MMInsertMapDestroy()`
@*/
PetscErrorCode MMInsertMapLocalToGlobal(DM dm, MMInsertMap *m, Vec l, Vec g)
{
  const PetscScalar *la;
  PetscScalar       *ga;

  PetscFunctionBeginUser;
  if (m->dm != dm) PetscCall(Build(dm, m, g));
  if (m->transform) {
    PetscCall(DMLocalToGlobal(dm, l, INSERT_VALUES, g));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(l, &la));
  PetscCall(VecGetArray(g, &ga));
  for (PetscInt k = 0; k < m->n; ++k) ga[m->glob[k]] = la[m->loc[k]];
  PetscCall(VecRestoreArray(g, &ga));
  PetscCall(VecRestoreArrayRead(l, &la));
  PetscFunctionReturn(0);
}

/*@
  MMInsertMapDestroy - Frees an insertion map and resets it

  Not collective

  Input Parameter:
. m - the map

  Level: developer

.seealso: `MMInsertMapLocalToGlobal()`
@*/
PetscErrorCode MMInsertMapDestroy(MMInsertMap *m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(m->loc, m->glob));
  m->n         = 0;
  m->dm        = NULL;
  m->transform = PETSC_FALSE;
  PetscFunctionReturn(0);
}
