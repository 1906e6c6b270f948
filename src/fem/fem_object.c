/* fem's operators as an object (docs/developer.md, "Components"): its creation, the mesh app hands it,
 * and what the other components read of it; the struct is private to fem (femimpl.h). */
#include "femimpl.h"

/*@
  MMFECreate - Creates fem's empty operators

  Collective

  Input Parameter:
. comm - the run's communicator

  Output Parameter:
. op - the new operators

  Note:
  MMFESetFromOptions reads their options, MMFESetDM hands them the mesh, MMFESetUp discretizes it.

  Level: beginner

.seealso: `MMFESetFromOptions()`, `MMFESetDM()`, `MMFESetUp()`, `MMFEDestroy()`
@*/
PetscErrorCode MMFECreate(MPI_Comm comm, MMOperators *op)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(op));
  (*op)->comm = comm;
  PetscFunctionReturn(0);
}

/*@
  MMFESetDM - Hands fem the mesh it discretizes

  Logically Collective

  Input Parameters:
+ op - the operators
- dm - the distributed mesh (referenced: the caller keeps its own reference)

  Level: beginner

.seealso: `MMFECreate()`, `MMFESetUp()`, `MMFEGetDM()`
@*/
PetscErrorCode MMFESetDM(MMOperators op, DM dm)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)dm));
  PetscCall(DMDestroy(&op->dm));
  op->dm = dm;
  PetscCall(DMGetDimension(dm, &op->dim));
  PetscFunctionReturn(0);
}

/*@
  MMFEGetDM - Gets the mesh's DM, whose P1 vector field carries the Cartesian displacements

  Not collective

  Input Parameter:
. op - the operators

  Output Parameter:
. dm - the DM (borrowed: not to be destroyed)

  Note:
  Its global vectors have the layout of the w-frame ones too (contact's frame turns each node's dofs).

  Level: beginner

.seealso: `MMFESetDM()`, `MMFEGetScalarDM()`, `MMFEGetDimension()`
@*/
PetscErrorCode MMFEGetDM(MMOperators op, DM *dm)
{
  PetscFunctionBeginUser;
  *dm = op->dm;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetScalarDM - Gets the scalar vertex DM: one P1 scalar per vertex, no constraints

  Not collective

  Input Parameter:
. op - the operators, set up

  Output Parameter:
. dm - the scalar DM (borrowed): lumped masses, contact pressure and gap, von Mises

  Level: intermediate

.seealso: `MMFEGetDM()`, `MMFESetUp()`
@*/
PetscErrorCode MMFEGetScalarDM(MMOperators op, DM *dm)
{
  PetscFunctionBeginUser;
  *dm = op->dm_scalar;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetDimension - Gets the mesh's dimension, 2 or 3

  Not collective

  Input Parameter:
. op - the operators, their DM set

  Output Parameter:
. dim - the dimension

  Level: beginner

.seealso: `MMFEGetDM()`, `MMFESetDM()`
@*/
PetscErrorCode MMFEGetDimension(MMOperators op, PetscInt *dim)
{
  PetscFunctionBeginUser;
  *dim = op->dim;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetCells - Gets the cell table: each local cell's vertices, volume and centroid

  Not collective

  Input Parameter:
. op - the operators, set up

  Output Parameter:
. cells - the cell table (borrowed, read-only)

  Level: intermediate

.seealso: `MMFESetUp()`, `MMCellsCreate()`
@*/
PetscErrorCode MMFEGetCells(MMOperators op, const MMCells **cells)
{
  PetscFunctionBeginUser;
  *cells = &op->cells;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetLoad - Gets the Cartesian load L, body force and tractions, constant in time

  Not collective

  Input Parameter:
. op - the operators, assembled

  Output Parameter:
. load - the load (borrowed, read-only: contact keeps its own w-frame copy)

  Level: developer

.seealso: `MMFEGetLift()`, `MMFEAssembleOperators()`, `MMContactSetUpFrame()`
@*/
PetscErrorCode MMFEGetLoad(MMOperators op, Vec *load)
{
  PetscFunctionBeginUser;
  *load = op->load;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetLift - Gets the Cartesian lift K_fD u_D, the Dirichlet data's elastic force on the free dofs

  Not collective

  Input Parameter:
. op - the operators, assembled

  Output Parameter:
. lift - the lift (borrowed, read-only: contact keeps its own w-frame copy)

  Level: developer

.seealso: `MMFEGetLoad()`, `MMFEAssembleOperators()`, `MMContactSetUpFrame()`
@*/
PetscErrorCode MMFEGetLift(MMOperators op, Vec *lift)
{
  PetscFunctionBeginUser;
  *lift = op->lift;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetLumpedMass - Gets the lumped standard mass per Cartesian dof

  Not collective

  Input Parameter:
. op - the operators, assembled

  Output Parameter:
. m - the lumped masses (borrowed, read-only), whatever -mass_lumped says

  Level: intermediate

.seealso: `MMFEIsMassLumped()`, `MMFEAssembleOperators()`
@*/
PetscErrorCode MMFEGetLumpedMass(MMOperators op, Vec *m)
{
  PetscFunctionBeginUser;
  *m = op->mass_lumped_cart;
  PetscFunctionReturn(0);
}

/*@
  MMFEIsMassLumped - Tells whether the standard mass M is the lumped one (-mass_lumped) or the consistent one

  Not collective

  Input Parameter:
. op - the operators, their options read

  Output Parameter:
. lumped - `PETSC_TRUE` with -mass_lumped

  Level: intermediate

.seealso: `MMFESetFromOptions()`, `MMFEGetLumpedMass()`
@*/
PetscErrorCode MMFEIsMassLumped(MMOperators op, PetscBool *lumped)
{
  PetscFunctionBeginUser;
  *lumped = op->lumped;
  PetscFunctionReturn(0);
}

/*@
  MMFEGetDirichletEnergy - Gets the elastic energy of the Dirichlet data alone, 1/2 u_D.A_DD u_D

  Not collective

  Input Parameter:
. op - the operators, assembled

  Output Parameter:
. energy - the energy, 0 without a Dirichlet boundary

  Level: developer

.seealso: `MMFEElasticEnergyIntegral()`, `MMContactElasticEnergy()`
@*/
PetscErrorCode MMFEGetDirichletEnergy(MMOperators op, PetscReal *energy)
{
  PetscFunctionBeginUser;
  *energy = op->energy_dirichlet;
  PetscFunctionReturn(0);
}
