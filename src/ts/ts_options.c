/* The stepper's options: the energy audit's tolerance, the deformation audit and the Rayleigh
 * damping, read by ts in MMNewmarkSetFromOptions with their checks beside them (sys's readers refuse
 * a value of the wrong kind, naming the option). */
#include "newmarkimpl.h"
#include "sys.h"

/*@
  MMNewmarkSetFromOptions - Reads the stepper's options: the energy and deformation audits, Rayleigh
  damping, the finite-strain iteration, -ts_view

  Collective

  Input Parameter:
. nm - the stepper's context

  Note:
  The energy audit's tolerances (the balance, and the contact work that rejects a step), the
  deformation audit's switch and thresholds, and the damping.

  Level: beginner

.seealso: `MMNewmarkCreate()`, `MMNewmarkSetUp()`
@*/
PetscErrorCode MMNewmarkSetFromOptions(MMNewmark nm)
{
  MPI_Comm comm = nm->comm;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkCheckStepCount(comm));
  PetscOptionsBegin(comm, NULL, "mmcontact: the time stepper's audits and damping", "MMNewmark");
  nm->cert.on = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-step_certificate", "Accept a step when its residual does no work, has no resultant and no moment beyond the round-off of their terms, solving it again with tighter -contact_tol until it does (or its residual stops falling); 0: the solves stop at -contact_tol alone", &nm->cert.on));
  nm->increments = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-step_increments", "The step (the linear law's solve, each finite-strain iterate) solves for the increment du = u^{n+1} - u^n, its right-hand side formed without the 4/dt^2 M* u^n that the total displacement's equation cancels, so that its round-off does not grow as 1/dt^2 (docs/method.md section 3); 0: for u^{n+1}. Not with friction corners", &nm->increments));
  nm->audit_tol = 1e-6;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-audit_tol", "Stop the run when a step's relative energy-balance residual exceeds this (> 0): the scheme's identity no longer holds", &nm->audit_tol));
  nm->contact_work_tol = 1e-3;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_work_tol", "Reject and retry with a smaller dt a step whose contact work W_c creates more energy than this times the run's energy scale (> 0): a release that dt does not resolve", &nm->contact_work_tol));
  nm->deformation_audit = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-deformation_audit", "After every step, check each cell's deformation: a cell turned inside out or a strain above -max_strain stops the run, one above -strain_warn is warned (0: no check, for nondimensional verification cases whose strains are large by design)", &nm->deformation_audit));
  nm->strain_warn = 0.1;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-strain_warn", "Warn once when a cell's strain (its largest principal strain, in magnitude) exceeds this, > 0: beyond it the small-strain model is an approximation", &nm->strain_warn));
  nm->max_strain = 1.0;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-max_strain", "Stop the run when a cell's strain exceeds this, >= -strain_warn: the small-strain model's result is then meaningless (a cell turned inside out always stops the run)", &nm->max_strain));
  PetscCall(MMDampingSetFromOptions(PetscOptionsObject, comm, &nm->damping));
  PetscCall(MMNonlinearSetFromOptions(PetscOptionsObject, comm, &nm->nl));
  {
    PetscBool view; /* viewed by app once set up (TSView, whose type's view op is MMNewmarkView); TSSolve views it again at its end */
    PetscCall(PetscOptionsName("-ts_view", "Print the time stepper's configuration once set up, before the first step (PETSc's TS lines, then the scheme, the elasticity law, the damping, the step matrix's coefficients, the finite-strain iteration, the audits), and again when TSSolve ends: -ts_view, or -ts_view ascii:FILE to write it to FILE", "TSView", &view));
  }
  PetscOptionsEnd();
  PetscCheck(nm->audit_tol > 0, comm, PETSC_ERR_USER_INPUT, "-audit_tol %g must be > 0: it is a relative energy-balance residual", (double)nm->audit_tol);
  PetscCheck(nm->contact_work_tol > 0, comm, PETSC_ERR_USER_INPUT, "-contact_work_tol %g must be > 0: it is a fraction of the run's energy scale", (double)nm->contact_work_tol);
  PetscCheck(nm->strain_warn > 0, comm, PETSC_ERR_USER_INPUT, "-strain_warn %g must be > 0: it is a strain", (double)nm->strain_warn);
  PetscCheck(nm->max_strain >= nm->strain_warn, comm, PETSC_ERR_USER_INPUT, "-max_strain %g must be >= -strain_warn %g", (double)nm->max_strain, (double)nm->strain_warn);
  PetscFunctionReturn(0);
}
