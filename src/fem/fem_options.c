/* The discretization's options (-mass, -mass_lumped, -assembly, -assembly_check), read by fem in its
 * own SetFromOptions: the names of the masses and assemblies live with them. */
#include <strings.h> /* strcasecmp */
#include "fem.h"

const char *const MMMassTypes[]     = {"modified", "standard", "redistributed", "MMMassType", "MM_MASS_", NULL};
const char *const MMAssemblyTypes[] = {"closed_form", "fe", "MMAssemblyType", "MM_ASSEMBLY_", NULL};

/* An enumerated option, refused when given without a value (it would keep its default in silence).
 * The same check as every option's (src/app/options.c); to be the shared reader of src/sys/ once
 * there is one. */
static PetscErrorCode OptionsEnum(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], const char *const list[], PetscEnum *v)
{
  const char *value;
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, name, &value, &set));
  PetscCheck(!set || value, comm, PETSC_ERR_USER_INPUT, "%s was given without a value: write \"%s VALUE\", or leave the option out for its default", name, name);
  PetscCall(PetscOptionsEnum(name, help, NULL, list, *v, v, NULL));
  PetscFunctionReturn(0);
}

/* A switch: given alone it is on; given a value, that value must be one PETSc reads as a logical
 * (its own error does not name the option). */
static PetscErrorCode OptionsBool(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscBool *v)
{
  static const char *const words[] = {"1", "0", "true", "false", "yes", "no", "on", "off"};
  const char              *value;
  PetscBool                set, known = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, name, &value, &set));
  for (size_t i = 0; set && value && value[0] && i < PETSC_STATIC_ARRAY_LENGTH(words); ++i) known = (PetscBool)(known || !strcasecmp(value, words[i]));
  PetscCheck(!set || !value || !value[0] || known, comm, PETSC_ERR_USER_INPUT, "%s %s: give 1 or 0 (also true/false, yes/no, on/off), or %s alone for 1", name, value, name);
  PetscCall(PetscOptionsBool(name, help, NULL, *v, v, NULL));
  PetscFunctionReturn(0);
}

/* The mass and the assembly of op, from the options. */
PetscErrorCode MMFESetFromOptions(MPI_Comm comm, MMOperators *op)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact: the finite elements, their mass and assembly", "MMFE");
  op->mass_type = MM_MASS_REDISTRIBUTED;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-mass", "Mass matrix in time stepping: modified (normal mass of contact nodes removed), redistributed (modified, with the removed mass given to the other nodes so that the total mass, centre of gravity and inertia are those of the standard mass) or standard", MMMassTypes, (PetscEnum *)&op->mass_type));
  op->lumped = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-mass_lumped", "Use the row-sum lumped mass instead of the consistent mass", &op->lumped));
  op->assembly = MM_ASSEMBLY_CLOSED_FORM;
  PetscCall(OptionsEnum(PetscOptionsObject, comm, "-assembly", "How the stiffness and mass are assembled: closed_form (P1 element matrices in closed form, one pass over the cells) or fe (PetscFE quadrature, the slower reference)", MMAssemblyTypes, (PetscEnum *)&op->assembly));
  op->assembly_check = PETSC_FALSE;
  PetscCall(OptionsBool(PetscOptionsObject, comm, "-assembly_check", "Also assemble the stiffness and mass the other -assembly way, print the relative difference of each, and stop if one exceeds 1e-12", &op->assembly_check));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
