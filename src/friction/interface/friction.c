/* The friction solver's interface: the registry of types, set-up, and the per-step solve as a shell
 * SNES (prefix friction_), so that -friction_snes_rtol, _max_it, _monitor and _converged_reason apply
 * whatever the type.
 *
 * A type fills an ops table (frictionimpl.h): a contact-space solve on the condensed formulation's
 * candidate set (solveset), and/or a threshold loop over the formulation's own Tresca solves
 * (solvethresholds, for formulations without a Delassus operator). A NULL entry is a capability the
 * type lacks. Adding a type: one folder in src/friction/impls/ and one MMFrictionRegister line. */
#include "../frictionimpl.h"

PetscFunctionList MMFrictionList = NULL;
static PetscBool  registered     = PETSC_FALSE;

/*@
  MMFrictionRegister - Adds a friction solver type to the registry, chosen by -friction_type

  Not collective

  Input Parameters:
+ name   - the type's name
- create - the function that fills the solver's ops table for the type

  Level: developer

.seealso: `MMFrictionRegisterAll()`, `MMFrictionSetUp()`
@*/
PetscErrorCode MMFrictionRegister(const char name[], PetscErrorCode (*create)(MMFriction))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&MMFrictionList, name, create));
  PetscFunctionReturn(0);
}

/*@
  MMFrictionRegisterAll - Registers the built-in friction solver types, newton and fixedpoint, once

  Not collective

  Note:
  Called by MMFrictionCreate(); a later call does nothing.

  Level: developer

.seealso: `MMFrictionRegister()`, `MMFrictionCreate()`
@*/
PetscErrorCode MMFrictionRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(0);
  registered = PETSC_TRUE;
  PetscCall(MMFrictionRegister("newton", MMFrictionCreate_Newton));
  PetscCall(MMFrictionRegister("fixedpoint", MMFrictionCreate_FixedPoint));
  PetscFunctionReturn(0);
}

/* The discrete Coulomb residual of the iterate (docs/method.md section 6): the audit every type's
 * answer must pass, whatever its own stopping test. */
PetscErrorCode MMFrictionCoulombResidual(MMFriction fr, PetscReal *coulomb, PetscInt *nslip, PetscInt *nstick)
{
  PetscFunctionBeginUser;
  /* sigma: the velocity of w over the step, the stepper's; on the tangential contact dofs, the slip velocity */
  PetscCall(MMContactStepVelocity(fr->contact, fr->w, fr->sigma));
  PetscCall(MMContactCoulomb(fr->contact, fr->time, fr->w, fr->react, fr->sigma, coulomb, nslip, nstick));
  PetscFunctionReturn(0);
}

static PetscErrorCode SolveSetAdaptor(void *ptr, const MMContactSetProblem *sp, PetscScalar x[], PetscBool *ok)
{
  MMFriction       fr = (MMFriction)ptr;
  MMCoulombProblem p  = {sp->n, sp->nc, sp->W, sp->q, sp->mu, NULL, sp->redundant};
  MMCoulombResult  res;
  PetscLogDouble   t0, t1;
  PetscScalar     *x0 = NULL;
  const PetscBool  dump = (PetscBool)(fr->dump[0] != 0);

  PetscFunctionBeginUser;
  if (dump) { /* the warm start, for the dump */
    PetscCall(PetscMalloc1(sp->n * sp->nc, &x0));
    PetscCall(PetscArraycpy(x0, x, sp->n * sp->nc));
  }
  PetscCall(PetscTime(&t0));
  PetscCall(fr->ops->solveset(fr, &p, x, &res));
  PetscCall(PetscTime(&t1));
  if (dump) PetscCall(MMFrictionDump(fr, &p, x0, x, &res, t1 - t0));
  PetscCall(PetscFree(x0));
  /* a set that grew is solved again: the iterations add up */
  fr->its += res.its;
  fr->inner_its += res.inner_its;
  fr->contraction     = res.contraction;
  fr->contraction_max = PetscMax(fr->contraction_max, res.contraction);
  *ok                 = res.converged;
  PetscFunctionReturn(0);
}

/* A converged solve's verdict, from the Coulomb audit of its answer (fr->coulomb): the monitor line,
 * SNES's monitor and its converged reason. */
static PetscErrorCode ReportAudit(MMFriction fr, SNES snes, const char where[], PetscInt nslip, PetscInt nstick)
{
  PetscFunctionBeginUser;
  if (fr->monitor) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    friction (%s%s): %" PetscInt_FMT " iterations (%" PetscInt_FMT " inner), Coulomb residual %.3e, slipping %" PetscInt_FMT ", sticking %" PetscInt_FMT "\n", fr->type, where, fr->its, fr->inner_its, (double)fr->coulomb, nslip, nstick));
  PetscCall(SNESMonitor(snes, fr->its, fr->coulomb));
  PetscCall(SNESSetConvergedReason(snes, fr->coulomb <= fr->coulomb_tol ? SNES_CONVERGED_FNORM_RELATIVE : SNES_DIVERGED_INNER));
  PetscFunctionReturn(0);
}

/* The contact-space solve on the candidate set's Delassus block (condensed formulation). The
 * solver's own test (its residual over the force scale) and the Coulomb audit (on the recovered w)
 * measure the same thing on different scales: a solve that passed its own test but not the audit is
 * polished from where it stopped with a tighter test, at most twice, instead of rejecting the step
 * over rounding. */
static PetscErrorCode SolveContactSpace(MMFriction fr, SNES snes)
{
  const PetscReal rtol = fr->rtol;
  PetscBool       ok;
  PetscInt        nslip = 0, nstick = 0;

  PetscFunctionBeginUser;
  for (PetscInt polish = 0;; ++polish) {
    PetscCall(MMContactSolveCoulomb(fr->contact, fr->b, fr->w, fr->react, SolveSetAdaptor, fr, &ok));
    if (!ok) break;
    PetscCall(MMFrictionCoulombResidual(fr, &fr->coulomb, &nslip, &nstick));
    if (fr->coulomb <= fr->coulomb_tol || polish == 2) break;
    fr->rtol *= 1e-2;
  }
  fr->rtol = rtol;
  PetscCall(SNESSetIterationNumber(snes, fr->its));
  if (!ok) {
    PetscCall(SNESSetConvergedReason(snes, SNES_DIVERGED_MAX_IT));
    PetscFunctionReturn(0);
  }
  PetscCall(ReportAudit(fr, snes, "", nslip, nstick));
  PetscFunctionReturn(0);
}

/* The formulation's own Coulomb solve on all dofs (active set: its semismooth Newton with the
 * thresholds mu r_n following the iterate, docs/method.md section 3), warm-started from the last
 * step's thresholds fr->s, which it updates; then the Coulomb audit. One iteration is one linear
 * solve on the free dofs, against one Tresca solve of several for the threshold loop. */
PetscErrorCode MMFrictionSolveDofs(MMFriction fr, Vec b, Vec w, Vec react)
{
  PetscBool ok;
  PetscInt  its, nslip = 0, nstick = 0;

  PetscFunctionBeginUser;
  PetscCall(MMContactSolveCoulombDofs(fr->contact, b, w, react, fr->s, fr->rtol, &its, &ok));
  fr->its = fr->inner_its = its;
  PetscCall(SNESSetIterationNumber(fr->snes, its));
  if (!ok) {
    PetscCall(SNESSetConvergedReason(fr->snes, SNES_DIVERGED_MAX_IT));
    PetscFunctionReturn(0);
  }
  PetscCall(MMFrictionCoulombResidual(fr, &fr->coulomb, &nslip, &nstick));
  PetscCall(ReportAudit(fr, fr->snes, ", all dofs", nslip, nstick));
  PetscFunctionReturn(0);
}

/* The shell SNES's solve: the type's contact-space solve where the formulation has the Delassus
 * operator; else the formulation's own Coulomb solve, or the threshold loop over its Tresca solves. */
static PetscErrorCode FrictionShellSolve(SNES snes, Vec unused)
{
  MMFriction fr;
  PetscBool  has, dofs;

  PetscFunctionBeginUser;
  PetscCall(SNESShellGetContext(snes, &fr));
  fr->its = fr->inner_its = 0;
  fr->contraction = fr->contraction_max = 0;
  PetscCall(MMContactHasDelassus(fr->contact, &has));
  PetscCall(MMContactHasCoulombDofs(fr->contact, &dofs));
  if (has && fr->ops->solveset) PetscCall(SolveContactSpace(fr, snes));
  else if (dofs && fr->ops->solvedofs) PetscCall(fr->ops->solvedofs(fr, fr->b, fr->w, fr->react));
  else PetscCall(fr->ops->solvethresholds(fr, fr->b, fr->w, fr->react));
  PetscFunctionReturn(0);
}

static PetscBool MMFrictionPackageInitialized = PETSC_FALSE;
PetscLogEvent    MMFRICTION_Loop;

/*@
  MMFrictionInitializePackage - Registers the friction component's class and its event
  MMFrictionLoop for -log_view, once

  Not collective

  Note:
  The friction component's class and event (-log_view), registered once, by MMFrictionCreate.

  Level: developer

.seealso: `MMFrictionCreate()`
@*/
PetscErrorCode MMFrictionInitializePackage(void)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  if (MMFrictionPackageInitialized) PetscFunctionReturn(0);
  MMFrictionPackageInitialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MMFriction", &id));
  PetscCall(PetscLogEventRegister("MMFrictionLoop", id, &MMFRICTION_Loop));
  PetscFunctionReturn(0);
}

/*@
  MMFrictionCreate - Creates a friction solver, its type not yet chosen

  Collective

  Input Parameter:
. comm - the communicator

  Output Parameter:
. fr - the friction solver

  Note:
  Initializes the package and registers the built-in types first. The type is chosen by
  MMFrictionSetUp().

  Level: intermediate

.seealso: `MMFrictionSetFromOptions()`, `MMFrictionSetUp()`, `MMFrictionDestroy()`
@*/
PetscErrorCode MMFrictionCreate(MPI_Comm comm, MMFriction *fr)
{
  PetscFunctionBeginUser;
  PetscCall(MMFrictionInitializePackage());
  PetscCall(MMFrictionRegisterAll());
  PetscCall(PetscNew(fr));
  (*fr)->comm = comm;
  PetscFunctionReturn(0);
}

/*@
  MMFrictionSetFromOptions - Reads the -friction_ options, with their checks

  Collective

  Input Parameter:
. fr - the friction solver

  Note:
  The options: -friction_coulomb_tol (in (0, 1), default 1e-8), -friction_type, -friction_dump,
  -friction_monitor, and -friction_view, which app acts on once the solver is set up. The shell
  SNES's own -friction_snes_* options are read by MMFrictionSetUp().

  Level: intermediate

.seealso: `MMFrictionCreate()`, `MMFrictionSetUp()`, `MMFrictionView()`
@*/
PetscErrorCode MMFrictionSetFromOptions(MMFriction fr)
{
  MPI_Comm comm = fr->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact friction", "MMFriction");
  fr->coulomb_tol = 1e-8;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-friction_coulomb_tol", "The Coulomb audit of every friction solve, in (0, 1): the step's discrete Coulomb residual (penetration and gap over h_c', tension, complementarity, the cone and the slip direction over the force scale) must be below this; a solve that met its own -friction_snes_rtol but not this is polished with a 100 times tighter test, at most twice, and then the step is rejected and retried with a smaller dt", &fr->coulomb_tol));
  PetscCall(PetscStrncpy(fr->type_name, "newton", sizeof(fr->type_name)));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-friction_type", "Coulomb friction solver: newton (the default: semismooth Newton, on Alart-Curnier's function in contact space with -contact_formulation condensed, on all dofs with the thresholds following the iterate with active_set) or fixedpoint (the paper's fixed point on the thresholds, each Tresca problem solved exactly)", fr->type_name, sizeof(fr->type_name), &fr->type_set));
  fr->dump[0] = 0;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-friction_dump", "Directory (created if missing) for each step's Coulomb problem on the candidate set, in the Friction Contact Library's form u = W r + q (docs/method.md section 6), with our reactions and solve time: step_NNNNNN.h5. scripts/fclib_compare.py solves them with Siconos. Needs the condensed formulation", fr->dump, sizeof(fr->dump), NULL));
  fr->monitor = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-friction_monitor", "Print each friction iteration: threshold change, Coulomb residual, contraction factor, slipping and sticking node counts", &fr->monitor));
  {
    PetscBool view; /* viewed by app once set up (MMFrictionView), as PETSc's -ksp_view */
    PetscCall(PetscOptionsName("-friction_view", "Print the friction solver's configuration once set up, before the first step (type, tolerances, iterations): -friction_view, or -friction_view ascii:FILE to write it to FILE", "MMFrictionView", &view));
  }
  PetscOptionsEnd();
  PetscCheck(fr->coulomb_tol > 0 && fr->coulomb_tol < 1, comm, PETSC_ERR_USER_INPUT, "-friction_coulomb_tol %g must lie in (0, 1): it is a normalized residual", (double)fr->coulomb_tol);
  PetscFunctionReturn(0);
}

/*@
  MMFrictionGetCoulombTolerance - Gives the Coulomb audit's tolerance (-friction_coulomb_tol), which
  the contact solves also aim below

  Not collective

  Input Parameter:
. fr - the friction solver

  Output Parameter:
. tol - the tolerance

  Level: intermediate

.seealso: `MMFrictionSetFromOptions()`
@*/
PetscErrorCode MMFrictionGetCoulombTolerance(MMFriction fr, PetscReal *tol)
{
  PetscFunctionBeginUser;
  *tol = fr->coulomb_tol;
  PetscFunctionReturn(0);
}

/*@
  MMFrictionSetUp - Sets up the friction solver for a contact object: its type, the shell SNES and
  the first thresholds

  Collective

  Input Parameters:
+ fr     - the friction solver
. ct     - the contact object
. mu_max - the largest friction coefficient (0: frictionless, the contact solve alone)
. E_max  - the largest Young's modulus (the force scale)
- react  - the initial reactions (w-frame)

  Note:
  The solver for the contact ct: its type (-friction_type, or the default the formulation calls
  for), the shell SNES, and the first thresholds from the initial reactions react. mu_max: the
  largest friction coefficient (0: frictionless, the contact solve alone); E_max: the largest
  Young's modulus (the force scale); react: the initial reactions (w-frame). The slip velocities are
  the stepper's velocities of w, through contact (MMContactStepVelocity).

  The type defaults to newton where the formulation gives the Delassus operator or solves Coulomb
  itself, else to fixedpoint; a type that cannot solve the formulation's Coulomb problem, and
  -friction_dump where no contact-space problem is solved, are refused. The SNES (prefix friction_)
  and the thresholds mu r_n are made only when mu_max > 0 and contact is on.

  Level: intermediate

.seealso: `MMFrictionCreate()`, `MMFrictionSolve()`, `MMFrictionView()`
@*/
PetscErrorCode MMFrictionSetUp(MMFriction fr, MMContact ct, PetscReal mu_max, PetscReal E_max, Vec react)
{
  PetscErrorCode (*create)(MMFriction) = NULL;
  PetscBool      has, dofs;
  const char    *type, *formulation, *choice, *products;
  MPI_Comm       comm = fr->comm;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ct, &cn));
  PetscCall(MMContactGetSolverText(ct, &formulation, &choice, &products));
  fr->contact = ct;
  fr->s_floor = mu_max * 1e-3 * E_max * PetscPowReal(cn.h_c, cn.dim - 1);
  PetscCall(MMContactHasDelassus(ct, &has));
  PetscCall(MMContactHasCoulombDofs(ct, &dofs));
  /* the default: Newton where the formulation gives the Delassus operator or solves Coulomb itself,
   * else the fixed point */
  type = fr->type_set ? fr->type_name : (has || dofs || !cn.enabled ? "newton" : "fixedpoint");
  PetscCall(PetscFunctionListFind(MMFrictionList, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "-friction_type %s is not a friction solver: use newton (semismooth Newton on the Coulomb problem, the default) or fixedpoint (the paper's fixed point on the thresholds)", type);
  PetscCall(PetscStrncpy(fr->type, type, sizeof(fr->type)));
  PetscCall((*create)(fr));
  PetscCheck(!fr->dump[0] || (mu_max > 0 && has && fr->ops->solveset), comm, PETSC_ERR_USER_INPUT, "-friction_dump %s writes the contact-space Coulomb problems, which this run does not solve: it needs -mu > 0, -contact_formulation condensed and a -friction_type that solves them (newton or fixedpoint)", fr->dump);
  PetscCall(MMFrictionDumpSetUp(fr));
  if (mu_max == 0 || !cn.enabled) PetscFunctionReturn(0);
  PetscCheck(has ? fr->ops->solveset != NULL : (dofs && fr->ops->solvedofs) || fr->ops->solvethresholds, comm, PETSC_ERR_USER_INPUT,
             "-friction_type %s cannot solve the Coulomb problem of -contact_formulation %s: use -friction_type fixedpoint", type, formulation);
  PetscCall(SNESCreate(comm, &fr->snes));
  PetscCall(SNESSetOptionsPrefix(fr->snes, "friction_"));
  PetscCall(SNESSetType(fr->snes, SNESSHELL));
  PetscCall(SNESShellSetContext(fr->snes, fr));
  PetscCall(SNESShellSetSolve(fr->snes, FrictionShellSolve));
  PetscCall(SNESSetTolerances(fr->snes, PETSC_DEFAULT, fr->ops->default_rtol, PETSC_DEFAULT, 100, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(fr->snes));
  PetscCall(SNESGetTolerances(fr->snes, NULL, &fr->rtol, NULL, &fr->maxit, NULL));
  PetscCall(VecDuplicate(cn.gap, &fr->s));
  PetscCall(VecDuplicate(cn.gap, &fr->s_new));
  PetscCall(VecZeroEntries(fr->s_new));
  PetscCall(VecDuplicate(react, &fr->sigma));
  /* the first thresholds of a threshold loop: mu times the initial normal reactions */
  {
    Vec rn;
    PetscCall(VecGetSubVector(react, cn.is_normal, &rn));
    PetscCall(VecAXPBY(fr->s, -1.0, 0.0, rn));
    PetscCall(VecPointwiseMult(fr->s, fr->s, cn.mu));
    PetscCall(VecRestoreSubVector(react, cn.is_normal, &rn));
    PetscCall(VecPointwiseMax(fr->s, fr->s, fr->s_new)); /* s_new is zero here: clip tension */
  }
  PetscFunctionReturn(0);
}

/*@
  MMFrictionSolve - Solves the step problem with friction; without friction, the contact solve
  itself

  Collective

  Input Parameters:
+ fr   - the friction solver
. step - the last accepted step
. t    - its time
- b    - the step's right-hand side

  Output Parameters:
+ w     - the solution
. react - the contact reactions
- ok    - false when the solver did not converge (the caller retries with a smaller dt)

  Note:
  The step problem with friction; *ok is false when the solver did not converge (the caller retries
  with a smaller dt). Without friction it is the contact solve itself. step, t: the last accepted
  step and its time (the audit's obstacle positions, the dump's names).

  A converged friction solve, which updates only the contact dofs, is completed by one full-size
  solve (MMContactRecover()).

  Level: intermediate

.seealso: `MMFrictionSetUp()`, `MMFrictionGetConvergence()`, `MMContactSolve()`
@*/
PetscErrorCode MMFrictionSolve(MMFriction fr, PetscInt step, PetscReal t, Vec b, Vec w, Vec react, PetscBool *ok)
{
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  *ok      = PETSC_TRUE;
  fr->its  = fr->inner_its = 0;
  fr->step = step;
  fr->time = t;
  if (!fr->snes) {
    PetscCall(MMContactSolve(fr->contact, b, w, react));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(MMFRICTION_Loop, 0, 0, 0, 0));
  fr->b     = b;
  fr->w     = w;
  fr->react = react;
  PetscCall(SNESSolve(fr->snes, NULL, fr->s));
  PetscCall(SNESGetConvergedReason(fr->snes, &reason));
  *ok = (PetscBool)(reason > 0);
  /* the solve updated only the contact dofs: one full-size solve completes the step (a rejected
   * step is solved again, so it needs none) */
  if (*ok) PetscCall(MMContactRecover(fr->contact, b, w, react));
  PetscCall(PetscLogEventEnd(MMFRICTION_Loop, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMFrictionGetType - Gives the friction solver's type, as chosen by MMFrictionSetUp()

  Not collective

  Input Parameter:
. fr - the friction solver

  Output Parameter:
. type - the type's name, empty before set-up

  Level: intermediate

.seealso: `MMFrictionSetUp()`, `MMFrictionView()`
@*/
PetscErrorCode MMFrictionGetType(MMFriction fr, const char **type)
{
  PetscFunctionBeginUser;
  *type = fr->type;
  PetscFunctionReturn(0);
}

/*@
  MMFrictionGetConvergence - Gives the last step's iteration counts and the threshold loop's
  contraction rates

  Not collective

  Input Parameter:
. fr - the friction solver, or NULL (every answer 0)

  Output Parameters:
+ its             - the type's own iterations, or NULL
. inner_its       - the Newton steps inside them, or NULL
. contraction     - the contraction rate of the last threshold loop, or NULL
- contraction_max - its largest over the step, or NULL

  Note:
  The last step's iterations (the type's own loop, and Newton steps inside it), the contraction rate
  of the last threshold loop and its largest over the step (0 for Newton).

  Level: intermediate

.seealso: `MMFrictionSolve()`
@*/
PetscErrorCode MMFrictionGetConvergence(MMFriction fr, PetscInt *its, PetscInt *inner_its, PetscReal *contraction, PetscReal *contraction_max)
{
  PetscFunctionBeginUser;
  if (its) *its = fr ? fr->its : 0;
  if (inner_its) *inner_its = fr ? fr->inner_its : 0;
  if (contraction) *contraction = fr ? fr->contraction : 0;
  if (contraction_max) *contraction_max = fr ? fr->contraction_max : 0;
  PetscFunctionReturn(0);
}

/*@
  MMFrictionGetThresholds - Gives the thresholds mu r_n of the threshold loop, which the checkpoint
  saves

  Not collective

  Input Parameter:
. fr - the friction solver, or NULL

  Output Parameter:
. s - the thresholds, not a copy; NULL without friction

  Level: intermediate

.seealso: `MMFrictionSetUp()`
@*/
PetscErrorCode MMFrictionGetThresholds(MMFriction fr, Vec *s)
{
  PetscFunctionBeginUser;
  *s = fr ? fr->s : NULL;
  PetscFunctionReturn(0);
}

/*@
  MMFrictionBeginStep - Keeps the thresholds at a step's start, where a rejected step's retry starts

  Collective

  Input Parameter:
. fr - the friction solver, or NULL

  Level: developer

.seealso: `MMFrictionRejectStep()`
@*/
PetscErrorCode MMFrictionBeginStep(MMFriction fr)
{
  PetscFunctionBeginUser;
  if (!fr || !fr->s) PetscFunctionReturn(0);
  if (!fr->s_start) PetscCall(VecDuplicate(fr->s, &fr->s_start));
  PetscCall(VecCopy(fr->s, fr->s_start));
  PetscFunctionReturn(0);
}

/*@
  MMFrictionRejectStep - Gives back the thresholds of the step's start to a rejected step's retry

  Collective

  Input Parameter:
. fr - the friction solver, or NULL

  Note:
  Each solve warm-starts from the thresholds the last one left, and a solve that did not converge,
  or an iterate of a diverging finite-strain step, leaves any: on the svk ball of issue 50 they
  reached 1e23 and every retry's first CG diverged down to dt/256.

  Level: developer

.seealso: `MMFrictionBeginStep()`
@*/
PetscErrorCode MMFrictionRejectStep(MMFriction fr)
{
  PetscFunctionBeginUser;
  if (!fr || !fr->s_start) PetscFunctionReturn(0);
  PetscCall(VecCopy(fr->s_start, fr->s));
  PetscFunctionReturn(0);
}

/*@
  MMFrictionDestroy - Destroys a friction solver

  Collective

  Input Parameter:
. fr - the friction solver; NULL does nothing

  Level: intermediate

.seealso: `MMFrictionCreate()`
@*/
PetscErrorCode MMFrictionDestroy(MMFriction *fr)
{
  PetscFunctionBeginUser;
  if (!*fr) PetscFunctionReturn(0);
  PetscCall(SNESDestroy(&(*fr)->snes));
  PetscCall(VecDestroy(&(*fr)->s));
  PetscCall(VecDestroy(&(*fr)->s_new));
  PetscCall(VecDestroy(&(*fr)->s_start));
  PetscCall(VecDestroy(&(*fr)->sigma));
  PetscCall(MMCoulombWorkDestroy(&(*fr)->work));
  PetscCall(PetscFree(*fr));
  PetscFunctionReturn(0);
}
