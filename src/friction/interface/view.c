/* -friction_view: the friction solver's configuration once it is set up, before the first step, as
 * PETSc's KSPView prints a solver's (docs/reference.md, "Viewing the set-up"). */
#include "../frictionimpl.h"

/*@
  MMFrictionView - Prints the friction solver's configuration once set up (-friction_view)

  Collective

  Input Parameters:
+ fr     - the friction solver
- viewer - an ASCII viewer; another type prints nothing

  Note:
  The type and the contact formulation it solves over, its tolerances and iteration limit, the
  Coulomb audit, the dump and the monitor. Collective; printed once, by the viewer's first rank.

  Level: intermediate

.seealso: `MMFrictionSetUp()`, `MMFrictionSetFromOptions()`
@*/
PetscErrorCode MMFrictionView(MMFriction fr, PetscViewer viewer)
{
  PetscBool   ascii;
  const char *formulation = "", *choice, *products;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  if (fr->contact) PetscCall(MMContactGetSolverText(fr->contact, &formulation, &choice, &products));
  PetscCall(PetscViewerASCIIPrintf(viewer, "MMFriction: type %s%s\n", fr->type[0] ? fr->type : fr->type_name, fr->type_set ? "" : " (the default for this formulation)"));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (!fr->snes) {
    /* MMFrictionSetUp creates the solver only where some obstacle has friction */
    PetscCall(PetscViewerASCIIPrintf(viewer, "no friction solve in this run: every obstacle and pair is frictionless (mu 0), or contact is off\n"));
  } else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "over the contact formulation %s; a SNES of prefix friction_\n", formulation));
    PetscCall(PetscViewerASCIIPrintf(viewer, "tolerances: -friction_snes_rtol %g (%s), at most %" PetscInt_FMT " iterations (-friction_snes_max_it)\n", (double)fr->rtol, fr->ops && fr->ops->rtol_meaning ? fr->ops->rtol_meaning : "", fr->maxit));
    PetscCall(PetscViewerASCIIPrintf(viewer, "Coulomb audit of every solve: -friction_coulomb_tol %g\n", (double)fr->coulomb_tol));
    PetscCall(PetscViewerASCIIPrintf(viewer, "threshold floor %g (1e-3 of mu E h_c'^(d-1) at the largest mu and E)\n", (double)fr->s_floor));
  }
  if (fr->dump[0]) PetscCall(PetscViewerASCIIPrintf(viewer, "each step's Coulomb problem written to %s (-friction_dump)\n", fr->dump));
  if (fr->monitor) PetscCall(PetscViewerASCIIPrintf(viewer, "each iteration printed (-friction_monitor)\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
