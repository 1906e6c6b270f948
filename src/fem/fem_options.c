/* The discretization's options (-mass, -mass_lumped, -assembly, -assembly_check), read by fem in its
 * own SetFromOptions: the names of the masses and assemblies live with them. */
#include "fem.h"
#include "sys.h" /* the checked option readers */

const char *const MMMassTypes[]     = {"modified", "standard", "redistributed", "MMMassType", "MM_MASS_", NULL};
const char *const MMAssemblyTypes[] = {"closed_form", "fe", "MMAssemblyType", "MM_ASSEMBLY_", NULL};

/* The mass and the assembly of op, from the options. */
PetscErrorCode MMFESetFromOptions(MPI_Comm comm, MMOperators *op)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact: the finite elements, their mass and assembly", "MMFE");
  op->mass_type = MM_MASS_REDISTRIBUTED;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-mass", "Mass matrix in time stepping: modified (normal mass of contact nodes removed), redistributed (modified, with the removed mass given to the other nodes so that the total mass, centre of gravity and inertia are those of the standard mass) or standard", MMMassTypes, (PetscEnum *)&op->mass_type));
  op->lumped = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-mass_lumped", "Use the row-sum lumped mass instead of the consistent mass", &op->lumped));
  op->assembly = MM_ASSEMBLY_CLOSED_FORM;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-assembly", "How the stiffness and mass are assembled: closed_form (P1 element matrices in closed form, one pass over the cells) or fe (PetscFE quadrature, the slower reference)", MMAssemblyTypes, (PetscEnum *)&op->assembly));
  op->assembly_check = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-assembly_check", "Also assemble the stiffness and mass the other -assembly way, print the relative difference of each, and stop if one exceeds 1e-12", &op->assembly_check));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
