/* The mass in time stepping, M* (docs/method.md section 2): -mass, M* from the w-frame M, and the
 * mass's view. The modified mass drops the contact nodes' normal mass (their rows and columns), so
 * that the contact-normal dofs carry no inertia; the redistributed one gives that mass back to the
 * other nodes (mass_redistribution.c); the standard one is M. */
#include "../contactimpl.h"

const char *const MMMassTypes[] = {"modified", "standard", "redistributed", "MMMassType", "MM_MASS_", NULL};

PetscErrorCode MMContactMassSetFromOptions(MPI_Comm comm, MMContactMass *mass)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact: the mass in time stepping", "MMContact");
  mass->type = MM_MASS_REDISTRIBUTED;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-mass", "Mass matrix in time stepping: modified (normal mass of contact nodes removed), redistributed (modified, with the removed mass given to the other nodes so that the total mass, centre of gravity and inertia are those of the standard mass) or standard", MMMassTypes, (PetscEnum *)&mass->type));
  mass->free_flight = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-mass_free_flight", "Finite-strain laws: the standard mass M while no contact node is within reach of an obstacle, so that a body in free flight keeps its angular momentum exactly; -mass's M* from the step that brings a node near (docs/method.md section 2, \"The mass in free flight\")", &mass->free_flight));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mass_free_flight", &mass->free_flight_set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/*@
  MMContactGetMassType - Gives the mass in time stepping, -mass

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. type - the mass type

  Level: intermediate

.seealso: `MMContactMassView()`, `MMContactHasMasslessDofs()`
@*/
PetscErrorCode MMContactGetMassType(MMContact ct, MMMassType *type)
{
  PetscFunctionBeginUser;
  *type = ct->mass.type;
  PetscFunctionReturn(0);
}

/* The contact boundary as M* sees it: without contact, or in free flight (mass_free.c), no dof loses
 * its mass. */
void MMContactMassBoundary(MMContact ct, MMMassBoundary *mb)
{
  mb->massless     = ct->enabled && !ct->mass.is_free ? ct->is_massless : NULL;
  mb->n            = ct->n_local;
  mb->vertex       = ct->vertex;
  mb->scalar_index = ct->scalar_index;
  mb->second       = ct->second;
  mb->frame        = ct->node_frame;
  mb->fc_obstacle  = ct->fc_obstacle;
}

/* Mstar (a copy of the w-frame M) loses the massless dofs' rows and columns; -mass redistributed gives
 * their mass back to the other nodes; then the masses of M*'s translations and rotations */
static PetscErrorCode DropMasslessMass(MMContactMass *mass, MMOperators op, const MMMaterial *material, const MMMassBoundary *mb)
{
  PetscFunctionBeginUser;
  if (mass->massless) PetscCall(MatZeroRowsColumnsIS(mass->Mstar, mass->massless, 0.0, NULL, NULL));
  if (mass->massless && mass->type == MM_MASS_REDISTRIBUTED) {
    PetscCall(PetscLogEventBegin(MMCONTACT_MassRedistribute, 0, 0, 0, 0));
    PetscCall(MMContactRedistributeMass(mass, op, material, mb));
    PetscCall(PetscLogEventEnd(MMCONTACT_MassRedistribute, 0, 0, 0, 0));
  }
  PetscCall(MMContactMassMoments(mass, op));
  PetscFunctionReturn(0);
}

/* M* from op's w-frame M, with the masses of its translations (read by the stepper through
 * MMContactGetOperators); the modified and the redistributed mass leave mb's massless dofs without inertia. */
PetscErrorCode MMContactMassStar(MMContactMass *mass, MMOperators op, const MMMaterial *material, const MMMassBoundary *mb)
{
  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(mass->M, MAT_COPY_VALUES, &mass->Mstar));
  if (mb->massless && mass->type != MM_MASS_STANDARD) {
    PetscCall(PetscObjectReference((PetscObject)mb->massless));
    mass->massless = mb->massless;
  }
  PetscCall(DropMasslessMass(mass, op, material, mb));
  PetscFunctionReturn(0);
}

/* M* again from the whole w-frame mass M, after the contact frames turned (-contact_frames follow,
 * docs/method.md section 8): the massless dofs are the same dofs, now along the new normals, and
 * -mass redistributed gives their mass back anew. M* keeps its pattern (M's), so the matrices that
 * borrow it see the new values. */
PetscErrorCode MMContactMassRebuild(MMContactMass *mass, MMOperators op, Mat M, const MMMaterial *material, const MMMassBoundary *mb)
{
  PetscFunctionBeginUser;
  mass->M = M; /* borrowed: the redistribution and the moments read M */
  PetscCall(MatCopy(M, mass->Mstar, SAME_NONZERO_PATTERN));
  PetscCall(DropMasslessMass(mass, op, material, mb));
  mass->M = NULL;
  PetscFunctionReturn(0);
}

/* -mass redistributed's account: the moments matched and how well, and the correction's size
 * (a coarse mesh: the bounded correction, perhaps the inertia left; docs/method.md section 2). */
static PetscErrorCode RedistributionText(const MMContactMass *mass, PetscInt dim, char text[], size_t len)
{
  const char *which = "moments";
  char        bounded[160] = "", unreachable[160] = "";

  PetscFunctionBeginUser;
  if (mass->moment_unreachable > 1e-14) PetscCall(PetscSNPrintf(unreachable, sizeof(unreachable), " (and %.1e in the trace of the translation-rotation block, out of reach: docs/method.md section 2)", (double)mass->moment_unreachable));
  if (mass->moments < MMFENumRigidModes(dim)) {
    which = "total mass and first moments";
    PetscCall(PetscSNPrintf(bounded, sizeof(bounded), "; bounded correction, the inertia off by %.2g of the mass", (double)mass->inertia_mismatch));
  } else if (mass->bounded) PetscCall(PetscStrncpy(bounded, "; bounded correction", sizeof(bounded)));
  PetscCall(PetscSNPrintf(text, len, "; M*'s %s equal M's to %.1e (largest node correction %.3g of its mass%s)%s", which, (double)mass->moment_mismatch, (double)mass->correction, bounded, unreachable));
  PetscFunctionReturn(0);
}

/*@
  MMContactMassView - Prints the mass's line of the reports: M's total, M*'s along each axis, and
  what -mass redistributed kept of M's moments

  Collective

  Input Parameters:
+ ct     - the contact object, its frame set up
- viewer - the viewer: only an ASCII viewer prints

  Note:
  One line: M's total mass, M*'s along each axis, and -mass redistributed's account.

  Level: intermediate

.seealso: `MMContactGetMassType()`, `MMContactSetUpView()`
@*/
PetscErrorCode MMContactMassView(MMContact ct, PetscViewer viewer)
{
  const PetscInt     dim = ct->dim;
  char               star[128] = "", moments[512] = "";
  PetscDS            ds;
  PetscInt           n_dirichlet;
  PetscBool          ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  for (PetscInt d = 0; d < dim; ++d) {
    size_t len;
    PetscCall(PetscStrlen(star, &len));
    PetscCall(PetscSNPrintf(star + len, sizeof(star) - len, "%s%c %.10g", d ? ", " : "", "xyz"[d], (double)ct->mass.mass_star[d * dim + d]));
  }
  if (ct->mass.massless && ct->mass.type == MM_MASS_REDISTRIBUTED) PetscCall(RedistributionText(&ct->mass, dim, moments, sizeof(moments)));
  /* M is over the free dofs: a node held by -dirichlet (one boundary of the DS each) is the
   * support's, outside the system */
  PetscCall(DMGetDS(ct->dm, &ds));
  PetscCall(PetscDSGetNumBoundary(ds, &n_dirichlet));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  mass: total of M %.10g%s; of M* along %s%s\n", (double)ct->mass.total, n_dirichlet ? " (without the dofs held by -dirichlet)" : "", star, moments));
  PetscFunctionReturn(0);
}
