/* The rigid-body modes of the free dofs: GAMG's near-null space (src/contact/interface/kt.c) and
 * the moments of the mass (src/contact/frame/mass_redistribution.c, docs/method.md section 2). */
#include "femimpl.h"

/* Component c of rigid-body mode m at x: translations e_0..e_{d-1}, then rotations (2D: one, 3D:
 * three, e_k x x). */
static PetscReal RigidMode(PetscInt dim, PetscInt m, PetscInt c, const PetscReal x[])
{
  if (m < dim) return m == c ? 1 : 0;
  if (dim == 2) return c == 0 ? -x[1] : x[0];
  {
    const PetscInt k = m - dim, i = (k + 1) % 3, j = (k + 2) % 3;
    return c == i ? -x[j] : c == j ? x[i] : 0;
  }
}

/*@
  MMFERigidModeMatrix - Gives the rigid-body modes' velocities at a point

  Not collective

  Input Parameters:
+ dim - the dimension
- x   - the point

  Output Parameter:
. T - row c, column m: the velocity component c at x of rigid mode m, zero beyond dim

  Note:
  T(x): row c, column m, the velocity component c at x of rigid mode m; zero beyond dim.

  Level: developer

.seealso: `MMFERigidModesCartesian()`
@*/
void MMFERigidModeMatrix(PetscInt dim, const PetscReal x[], PetscReal T[MM_MAX_DIM][MM_MAX_RIGID])
{
  for (PetscInt c = 0; c < MM_MAX_DIM; ++c)
    for (PetscInt m = 0; m < MM_MAX_RIGID; ++m) T[c][m] = (c < dim && m < MMFENumRigidModes(dim)) ? RigidMode(dim, m, c, x) : 0;
}

/*@
  MMFERigidModesCartesian - Sets the rigid-body modes of the free dofs, Cartesian, about a point and
  scaled by a length

  Collective

  Input Parameters:
+ op     - the operators
. x0     - the rotations' centre
. ell    - the length the modes are divided by
- nmodes - how many modes

  Output Parameter:
. modes - the modes, global vectors of the displacement DM

  Note:
  The rigid-body modes of the free dofs, Cartesian, about x0 and scaled by 1/ell (x0 = 0, ell = 1:
  the plain modes), into the given global vectors of the displacement DM: the global section lists
  each owned vertex's free components (Dirichlet-constrained ones dropped).

  Level: developer

.seealso: `MMFERigidModeMatrix()`
@*/
PetscErrorCode MMFERigidModesCartesian(MMOperators op, const PetscReal x0[], PetscReal ell, PetscInt nmodes, Vec modes[])
{
  DM                 dm  = op->dm;
  const PetscInt     dim = op->dim;
  PetscSection       gs, ls, cs;
  PetscInt           vStart, vEnd, rstart;
  Vec                X;
  const PetscScalar *xa;
  PetscScalar       *ma[MM_MAX_RIGID];

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(modes[0], &rstart, NULL));
  PetscCall(VecGetArrayRead(X, &xa));
  for (PetscInt m = 0; m < nmodes; ++m) PetscCall(VecGetArray(modes[m], &ma[m]));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt        goff, cdof, xoff, i = 0;
    const PetscInt *cind = NULL;
    PetscReal       x[MM_MAX_DIM] = {0, 0, 0};
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue; /* not owned */
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    if (cdof) PetscCall(PetscSectionGetConstraintIndices(ls, v, &cind));
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    for (PetscInt d = 0; d < dim; ++d) x[d] = (PetscRealPart(xa[xoff + d]) - x0[d]) / ell;
    for (PetscInt c = 0; c < dim; ++c) {
      PetscBool fixed = PETSC_FALSE;
      for (PetscInt j = 0; j < cdof; ++j) fixed = (PetscBool)(fixed || cind[j] == c);
      if (fixed) continue;
      for (PetscInt m = 0; m < nmodes; ++m) ma[m][goff - rstart + i] = RigidMode(dim, m, c, x);
      ++i;
    }
  }
  for (PetscInt m = 0; m < nmodes; ++m) PetscCall(VecRestoreArray(modes[m], &ma[m]));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscFunctionReturn(0);
}
