/* The discretization's options (-mass_lumped, -assembly, -assembly_check), read by fem in its own
 * SetFromOptions: the names of the assemblies live with them. -mass (M*) is contact's frame's
 * (src/contact/frame/mass_star.c). */
#include "femimpl.h"
#include "sys.h" /* the checked option readers */

const char *const MMAssemblyTypes[] = {"closed_form", "fe", "MMAssemblyType", "MM_ASSEMBLY_", NULL};

/*@
  MMFESetFromOptions - Reads fem's options: the standard mass's kind (-mass_lumped) and the assembly
  of K and M (-assembly, -assembly_check)

  Collective

  Input Parameter:
. op - the operators, whose options are set

  Note:
  The standard mass's kind and the assembly of op, from the options.

  Level: beginner

.seealso: `MMFECreate()`, `MMFESetUp()`, `MMFEAssembleOperators()`
@*/
PetscErrorCode MMFESetFromOptions(MMOperators op)
{
  MPI_Comm comm = op->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact: the finite elements, their mass and assembly", "MMFE");
  op->lumped = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-mass_lumped", "Use the row-sum lumped mass instead of the consistent mass", &op->lumped));
  op->assembly = MM_ASSEMBLY_CLOSED_FORM;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-assembly", "How the stiffness and mass are assembled: closed_form (P1 element matrices in closed form, one pass over the cells) or fe (PetscFE quadrature, the slower reference)", MMAssemblyTypes, (PetscEnum *)&op->assembly));
  op->assembly_check = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-assembly_check", "Also assemble the stiffness and mass the other -assembly way, print the relative difference of each, and stop if one exceeds 1e-12", &op->assembly_check));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
