/* The contact options (-contact, -contact_*, -iterative_dofs, the contact audit's tolerances, -mass), read
 * with their checks into the contact object (MMContactSetFromOptions). */
#include "../contactimpl.h"

const char *const MMPairsSlidings[] = {"auto", "small", "large", "MMPairsSliding", "MM_PAIRS_SLIDING_", NULL};

/* Each registered formulation's own options, all of them: the formulation is chosen at set-up
 * (-contact_formulation auto: by its cost model, src/contact/interface/cost.c), so an option of another formulation is read, not
 * refused as unused. A formulation's setfromoptions is found on a scratch object of its type. */
static PetscErrorCode FormulationsSetFromOptions(MMContact ct, PetscOptionItems *PetscOptionsObject)
{
  extern PetscFunctionList MMContactList;
  const char             **names;
  int                      n;

  PetscFunctionBeginUser;
  PetscCall(MMContactRegisterAll());
  PetscCall(PetscFunctionListGet(MMContactList, &names, &n));
  for (int i = 0; i < n && names[i]; ++i) { /* the array ends with NULL */
    PetscErrorCode (*create)(MMContact) = NULL;
    struct _p_MMContact scratch;
    PetscCall(PetscMemzero(&scratch, sizeof(scratch)));
    scratch.comm = ct->comm;
    PetscCall(PetscFunctionListFind(MMContactList, names[i], &create));
    PetscCall((*create)(&scratch));
    if (scratch.ops->setfromoptions) PetscCall((*scratch.ops->setfromoptions)(ct, PetscOptionsObject));
    if (scratch.ops->destroy) PetscCall((*scratch.ops->destroy)(&scratch));
  }
  PetscCall(PetscFree(names));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetFromOptions - Reads the contact options: -contact, -contact_formulation, -contact_tol,
  -contact_pairs_sliding, -mass, the audits' tolerances and the formulations' own

  Collective

  Input Parameter:
. ct - the contact object

  Level: beginner

.seealso: `MMContactCreate()`, `MMContactSetUp()`, `MMContactSetUpView()`
@*/
PetscErrorCode MMContactSetFromOptions(MMContact ct)
{
  MPI_Comm          comm = ct->comm;
  MMContactOptions *o    = &ct->opt;

  PetscFunctionBeginUser;
  PetscCall(MMContactMassSetFromOptions(comm, &ct->mass)); /* -mass: M*, the frame's (frame/mass_star.c) */
  PetscOptionsBegin(comm, NULL, "mmcontact contact", "MMContact");
  o->contact = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-contact", "Enforce unilateral contact; 0 gives linear elastodynamics on the same mesh (the contact boundary is then unused)", &o->contact));
  PetscCall(PetscStrncpy(o->contact_formulation, "auto", sizeof(o->contact_formulation)));
  o->iterative_dofs = -1;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-iterative_dofs", "Without contact (-contact 0): problems with at least this many dofs solve K~ by CG (ICC(0) on one rank, Jacobi on more) rather than factoring it; 0: always the factor; -1 (the default): whichever of the two a cost model fitted on measured runs predicts faster for the whole run (docs/scaling.md). With contact, -contact_formulation auto chooses instead", &o->iterative_dofs));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-contact_formulation", "Contact formulation: auto (the default: condensed or active_set, whichever a cost model fitted on measured runs predicts cheaper for the whole run, from the dofs, the dimension, c_p dt / h_c', friction, the law (linear or finite strain), the number of ranks and the number of steps to -ts_max_time; the start-up report shows both predictions), condensed (the VI on the contact dofs through the Delassus operator, K~ factored once per dt), full (the VI on all dofs, a factorization per VI iteration, frictionless), or active_set (the primal-dual active-set method on all dofs: CG on the free dofs with the contact_K_ PC, default ICC(0) on one rank and Jacobi on more, -contact_K_pc_type gamg or hypre for c_p dt / h_c' above about 10, set up once per dt; for large 3D meshes)", o->contact_formulation, sizeof(o->contact_formulation), NULL));
  o->contact_tol = 1e-11;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_tol", "Contact solves stop when ||K~ w - b - f_c|| <= contact_tol ||b|| (on top of -contact_snes_rtol/atol), in (0, 1)", &o->contact_tol));
  o->keep_factor = PETSC_TRUE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-contact_K_keep", "Keep K~ for the previous dt with its factor and cached columns (condensed) or its PC (active_set), so that dt growing back after a rejected step costs no factorization (the memory of a second factor)", &o->keep_factor));
  PetscCall(FormulationsSetFromOptions(ct, PetscOptionsObject));
  o->pairs_sliding = MM_PAIRS_SLIDING_SMALL; /* large: opt-in, docs/method.md section 11, "Large sliding" */
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-contact_pairs_sliding", "Contact pairs (-contact_pairs): small (each slave node's master facet, weights and gap found once, on the reference mesh), large (found again at each step's start on the current configuration, the pairs' transform N rebuilt; -elasticity svk or neohookean, frictionless pairs, -contact_formulation condensed), or auto (large where those hold, small otherwise); default small: on curved masters large sliding exchanges energy at each new pairing", MMPairsSlidings, (PetscEnum *)&o->pairs_sliding));
  o->pairs_depth = 1e-9;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_pairs_depth", "-contact_pairs_sliding large: a step whose end leaves a slave node deeper inside the master surface (as it is at the step's end) than this times h_c' is solved again from its start, that node's row turned to its facet's normal at the end, or to the facet it ended over (at most 3 times); < 0: never", &o->pairs_depth));
  /* The contact audit's tolerances, far above what correct runs reach: penetration at most 3e-14
   * h_c' over options/'s cases and the solver variants, the Coulomb residual at most 4e-5 (with
   * -mass standard, at dt down to 1/1024 of -ts_dt, where the reactions carry the round-off of
   * 4/dt^2 M), 1e-12 to 1e-10 otherwise (README "What is checked before the run") */
  o->audit_penetration_tol = 1e-6;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-audit_penetration_tol", "Stop the run when, after a step, a contact node lies inside an obstacle deeper than this times h_c' (> 0): the contact solve did not hold the constraint", &o->audit_penetration_tol));
  o->audit_coulomb_tol = 1e-2;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-audit_coulomb_tol", "Stop the run when a step's discrete Coulomb residual (the history's coulomb_residual: penetration and open gap over h_c', tension, complementarity and the friction law over the force scale) exceeds this (> 0)", &o->audit_coulomb_tol));
  o->initial_penetration_tol = 1e-6;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-initial_penetration_tol", "Refuse an initial state whose contact nodes penetrate the obstacle deeper than this times h_c' (>= 0)", &o->initial_penetration_tol));
  o->frames = MM_FRAMES_FIXED;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-contact_frames", "Contact frames on curved obstacles (sphere, circle, cylinder): fixed (each node's normal and gap at its reference position, all run: the small-sliding setting) or follow (at each step's start, a node near the obstacle whose normal at its current position turned by more than -contact_frames_angle takes that normal and the gap there; M* and K~ are rebuilt, and the kinetic energy this moves is booked as work_frame). Default: follow with -elasticity svk or neohookean, fixed with linear", MMFramesTypes, (PetscEnum *)&o->frames));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-contact_frames", &o->frames_set));
  o->frames_angle = 1e-3;
  o->frames_depth = PETSC_DEFAULT;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_frames_depth", "-contact_frames follow: a step whose end leaves a node deeper in its obstacle than this times h_c' is solved again from its start, that node's bound linearized where the step ended (at most 3 times: an edge of a meshed obstacle crossed within the step, or a long slide along a curve); < 0: never. Default 1e-12 with a meshed obstacle (type mesh), never otherwise", &o->frames_depth));
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-contact_frames_angle", "-contact_frames follow: a node's frame turns when its normal has turned by more than this angle (radians, >= 0) since its frame was set; the bound it keeps in between is off by at most R angle^2 / 2 on an obstacle of radius R", &o->frames_angle));
  {
    PetscBool view; /* viewed by app once set up (MMContactSetUpView), as PETSc's -ksp_view */
    PetscCall(PetscOptionsName("-contact_view", "Print the contact object's configuration once set up, before the first step (formulation, contact set, frames, mass, tolerances, K~'s solver): -contact_view, or -contact_view ascii:FILE to write it to FILE", "MMContactSetUpView", &view));
  }
  PetscOptionsEnd();
  PetscCheck(o->frames_angle >= 0 && o->frames_angle < 1, comm, PETSC_ERR_USER_INPUT, "-contact_frames_angle %g must be in [0, 1): an angle in radians", (double)o->frames_angle);
  PetscCheck(o->contact_tol > 0 && o->contact_tol < 1, comm, PETSC_ERR_USER_INPUT, "-contact_tol %g must lie in (0, 1): it is a relative residual", (double)o->contact_tol);
  PetscCheck(o->audit_penetration_tol > 0, comm, PETSC_ERR_USER_INPUT, "-audit_penetration_tol %.6g must be > 0: it is a fraction of h_c'", (double)o->audit_penetration_tol);
  PetscCheck(o->audit_coulomb_tol > 0, comm, PETSC_ERR_USER_INPUT, "-audit_coulomb_tol %.6g must be > 0: it is a normalized residual (the history's coulomb_residual)", (double)o->audit_coulomb_tol);
  PetscCheck(o->initial_penetration_tol >= 0, comm, PETSC_ERR_USER_INPUT, "-initial_penetration_tol %g must be >= 0: it is a fraction of h_c'", (double)o->initial_penetration_tol);
  PetscCheck(o->iterative_dofs >= -1, comm, PETSC_ERR_USER_INPUT, "-iterative_dofs %" PetscInt_FMT " must be >= -1 (-1: by the cost model, 0: always the factor)", o->iterative_dofs);
  PetscFunctionReturn(0);
}

/*@
  MMContactSetCoulombTolerance - Gives the contact object the friction solver's Coulomb audit
  tolerance

  Logically collective

  Input Parameters:
+ ct  - the contact object
- tol - -friction_coulomb_tol

  Note:
  The friction solver's Coulomb audit tolerance (-friction_coulomb_tol), which the active set's
  Tresca and Coulomb solves aim below

  Level: developer

.seealso: `MMContactGetTolerance()`, `MMContactSolveCoulombDofs()`
@*/
PetscErrorCode MMContactSetCoulombTolerance(MMContact ct, PetscReal tol)
{
  PetscFunctionBeginUser;
  ct->opt.friction_coulomb_tol = tol;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetTolerance - Gives the contact solves' tolerance, -contact_tol

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. tol - -contact_tol

  Note:
  -contact_tol, which the stepper's audit advice compares a residual with

  Level: developer

.seealso: `MMContactStepIsIterative()`, `MMContactSetCoulombTolerance()`
@*/
PetscErrorCode MMContactGetTolerance(MMContact ct, PetscReal *tol)
{
  PetscFunctionBeginUser;
  *tol = ct->opt.contact_tol;
  PetscFunctionReturn(0);
}

/*@
  MMContactStepIsIterative - Tells whether the step's K~ solves are iterative (CG)

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. iterative - PETSC_TRUE when K~ is solved by CG, PETSC_FALSE when it is factored or not set up yet

  Note:
  Whether the step's K~ solves are iterative (CG): their error is then contact_tol ||b||, not round-off

  Level: developer

.seealso: `MMContactGetTolerance()`, `MMContactGetStepKSP()`
@*/
PetscErrorCode MMContactStepIsIterative(MMContact ct, PetscBool *iterative)
{
  PetscFunctionBeginUser;
  *iterative = ct->kt.ksp ? ct->kt.iterative : PETSC_FALSE;
  PetscFunctionReturn(0);
}
