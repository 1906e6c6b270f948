/* The stepper's configuration: the view op of the TS type "newmark" (TSView, -ts_view; docs/reference.md,
 * "Viewing the set-up"), printed under PETSc's own TS lines. */
#include "newmarkimpl.h"

/* Each body's elasticity law, on one line. */
static PetscErrorCode LawView(const MMMaterial *mat, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (mat->n_bodies == 1) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "elasticity law: %s%s\n", MMElasticityTypes[mat->body[0].elasticity], mat->finite ? " (finite strain: the step iterates, below)" : " (small strain: one contact solve per step)"));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "elasticity laws:"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
  for (PetscInt b = 0; b < mat->n_bodies; ++b) PetscCall(PetscViewerASCIIPrintf(viewer, "%s %s %s", b ? "," : "", mat->body[b].name, MMElasticityTypes[mat->body[b].elasticity]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", mat->finite ? " (finite strain: the step iterates, below)" : " (small strain: one contact solve per step)"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* Rayleigh damping C = alpha M* + beta B (damping.c), as given and as used. */
static PetscErrorCode DampingView(const MMDamping *d, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!MMDampingOn(d)) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "damping: none\n"));
    PetscFunctionReturn(0);
  }
  if (d->ratio_set) PetscCall(PetscViewerASCIIPrintf(viewer, "damping: Rayleigh C = alpha M* + beta B, alpha %g 1/s, beta %g s (-damping_ratio %g at %g and %g Hz)\n", (double)d->alpha, (double)d->beta, (double)d->ratio, (double)d->freq[0], (double)d->freq[1]));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "damping: Rayleigh C = alpha M* + beta B, alpha %g 1/s, beta %g s\n", (double)d->alpha, (double)d->beta));
  PetscFunctionReturn(0);
}

/* The finite-strain step's iteration (nonlinear.c), its settings once set up. */
static PetscErrorCode NonlinearView(const MMNonlinear *nl, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "finite-strain iteration: -nonlinear_tangent %s, -nonlinear_rtol %g, -nonlinear_audit_rtol %g, -nonlinear_max_it %" PetscInt_FMT ", -nonlinear_anderson %" PetscInt_FMT, MMTangentPolicies[nl->policy], (double)nl->rtol, (double)nl->rtol_audit, nl->max_it, nl->anderson));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
  if (nl->policy == MM_TANGENT_AUTO && nl->refresh != PETSC_DEFAULT) PetscCall(PetscViewerASCIIPrintf(viewer, ", -nonlinear_refresh_ratio %g", (double)nl->refresh));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* The scheme, the law, the damping, the step matrix's coefficients at dt, the finite-strain
 * iteration and the audits. Before MMNewmarkSetUp (the scratch TS of -help) the scheme alone. */
PetscErrorCode MMNewmarkView(MMNewmark nm, PetscReal dt, PetscViewer viewer)
{
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Trapezoidal Newmark (beta = 1/4, gamma = 1/2), contact exact at t^{n+1}\n"));
  if (!nm || !nm->op || !nm->material) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(LawView(nm->material, viewer));
  PetscCall(DampingView(&nm->damping, viewer));
  {
    MMStepMatrix sm;
    PetscCall(MMNewmarkGetStepMatrix(nm, dt, &sm));
    PetscCall(PetscViewerASCIIPrintf(viewer, "step matrix K~ = ck K + cb B + cm M* at dt %g: ck %g, cb %g, cm %g%s\n", (double)dt, (double)sm.ck, (double)sm.cb, (double)sm.cm, sm.K ? " (K: the finite-strain iteration matrix)" : ""));
  }
  if (nm->material->finite) PetscCall(NonlinearView(&nm->nl, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "audits: -audit_tol %g, -contact_work_tol %g; deformation audit %s\n", (double)nm->audit_tol, (double)nm->contact_work_tol, nm->deformation_audit ? "on" : "off (-deformation_audit 0)"));
  if (nm->cert.on) PetscCall(PetscViewerASCIIPrintf(viewer, "step certificate: a step is accepted when its residual's work, resultant and moment are within %g round-offs of their terms, solved again with a tighter -contact_tol otherwise\n", (double)MM_CERT_ROUNDOFFS));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "step certificate: %s\n", nm->law->certified ? "off (-step_certificate 0): the solves stop at -contact_tol" : "the finite-strain iteration's: a stalled iterate within the round-off of its terms ends the step"));
  if (nm->deformation_audit) PetscCall(PetscViewerASCIIPrintf(viewer, "  -strain_warn %g, -max_strain %g\n", (double)nm->strain_warn, (double)nm->max_strain));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
