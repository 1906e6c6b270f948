/* -contact_view: the contact object's configuration once it is set up, before the first step, as
 * PETSc's KSPView prints a solver's (docs/reference.md, "Viewing the set-up"). MMContactView is the
 * closing summary's part: what the run did, not how it was configured. */
#include "../contactimpl.h"

/* K~'s solver as set up: its prefix, Krylov method and preconditioner (the PC's own KSP when the
 * formulation solves through one). */
static PetscErrorCode StepSolverView(MMContact ct, PetscViewer viewer)
{
  KSP         krylov = NULL, pc_ksp = NULL;
  PC          pc;
  KSPType     ktype;
  PCType      ptype;
  const char *prefix;

  PetscFunctionBeginUser;
  if (!ct->ops->getstepksp) PetscFunctionReturn(0);
  PetscCall(MMContactGetStepKSP(ct, &krylov, &pc_ksp));
  if (!krylov) PetscFunctionReturn(0);
  PetscCall(KSPGetOptionsPrefix(krylov, &prefix));
  PetscCall(KSPGetType(krylov, &ktype));
  PetscCall(KSPGetPC(pc_ksp ? pc_ksp : krylov, &pc));
  PetscCall(PCGetType(pc, &ptype));
  PetscCall(PetscViewerASCIIPrintf(viewer, "K~ solver (prefix %s): KSP %s, PC %s; K~ for the previous dt kept (-contact_K_keep): %s\n", prefix ? prefix : "", ktype ? ktype : "unset", ptype ? ptype : "unset", ct->opt.keep_factor ? "yes" : "no"));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetUpView - Prints the contact configuration once set up (-contact_view)

  Collective

  Input Parameters:
+ ct     - the contact object, set up
- viewer - the viewer: only an ASCII viewer prints

  Note:
  The formulation (and why, when auto chose it), the contact set, the obstacles, the frames, the
  mass, the tolerances and audits, and K~'s solver. Collective; printed once, by the viewer's first
  rank.

  Level: intermediate

.seealso: `MMContactView()`, `MMContactMassView()`, `MMContactGetSolverText()`
@*/
PetscErrorCode MMContactSetUpView(MMContact ct, PetscViewer viewer)
{
  const MMContactProblem *pb = &ct->pb;
  PetscBool               ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "MMContact: formulation %s%s\n", ct->type, ct->auto_type && ct->enabled ? ct->auto_why : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (!ct->enabled) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "no contact (-contact 0): K~ %s%s\n", ct->prefer_iterative ? "solved by CG" : "factored", ct->opt.iterative_dofs < 0 ? ct->auto_why : (ct->opt.iterative_dofs > 0 ? " (-iterative_dofs)" : " (-iterative_dofs 0)")));
    PetscCall(StepSolverView(ct, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "contact boundary %s: %" PetscInt_FMT " contact rows (%" PetscInt_FMT " second rows at corners, %" PetscInt_FMT " friction corners), %" PetscInt_FMT " reaction component%s per row; h_c' = %g\n", pb->contact_name ? pb->contact_name : "contact", ct->n_global, ct->n_corners, ct->n_fc, ct->ncomp, ct->ncomp > 1 ? "s" : "", (double)ct->h_c));
  PetscCall(PetscViewerASCIIPrintf(viewer, "obstacles: %" PetscInt_FMT " rigid, %" PetscInt_FMT " contact pair%s%s%s; largest friction coefficient %g\n", pb->n_rigid, pb->n_obstacles - pb->n_rigid, pb->n_obstacles - pb->n_rigid == 1 ? "" : "s", ct->pairs.large ? " with large sliding" : "", ct->moving ? "; some obstacle moves" : "", (double)pb->mu_max));
  if (ct->frames.follow) PetscCall(PetscViewerASCIIPrintf(viewer, "contact frames: follow the contact point (a frame turns past -contact_frames_angle %g rad)\n", (double)ct->frames.angle));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "contact frames: fixed at the reference positions\n"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "mass: -mass %s\n", MMMassTypes[ct->mass.type]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "tolerances: -contact_tol %g; audits: -audit_penetration_tol %g h_c', -audit_coulomb_tol %g, -initial_penetration_tol %g h_c'\n", (double)ct->opt.contact_tol, (double)ct->opt.audit_penetration_tol, (double)ct->opt.audit_coulomb_tol, (double)ct->opt.initial_penetration_tol));
  PetscCall(StepSolverView(ct, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
