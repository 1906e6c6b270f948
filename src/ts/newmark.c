/* Trapezoidal Newmark (beta = 1/4, gamma = 1/2) with exact contact, as the PETSc TS type "newmark".
 *
 * Registering a TS type keeps -ts_dt, -ts_max_time, -ts_max_steps, -ts_monitor, -ts_view and
 * TSAdapt. Each step solves the one contact problem of docs/method.md section 3 for u^{n+1}; the
 * massless contact-normal dofs carry no inertia, so their equation is quasi-static. */
#include <petsc/private/tsimpl.h>
#include "newmarkimpl.h"
#include "sys.h"
#include "fem.h"
#include "friction.h"

/* The TS type's data: the context it steps */
typedef struct {
  MMNewmark nm;
} TS_Newmark;

/* a^{n+1}, v^{n+1} from u^{n+1} by the trapezoidal rule; the massless dofs get a = 0 and the
 * backward-difference velocity, which enter neither the dynamics nor the energy. */
static PetscErrorCode UpdateKinematics(MMNewmark nm, PetscReal dt, Vec w)
{
  MMState *s = &nm->state;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkStepIncrement(nm, w, s->work)); /* du: solved for by the linear step */
  PetscCall(VecAXPBYPCZ(s->a, 4.0 / (dt * dt), -4.0 / dt, 0.0, s->work, s->v_old));
  PetscCall(VecAXPY(s->a, -1.0, s->a_old));
  PetscCall(VecWAXPY(s->v, 1.0, s->a_old, s->a));
  PetscCall(VecAYPX(s->v, 0.5 * dt, s->v_old));
  if (MMNewmarkHasMasslessDofs(nm)) {
    Vec            vc, dc;
    MMContactNodes cn;
    PetscCall(MMContactGetNodes(nm->contact, &cn));
    PetscCall(VecISSet(s->a, cn.is_normal, 0.0));
    PetscCall(VecGetSubVector(s->v, cn.is_normal, &vc));
    PetscCall(VecGetSubVector(s->work, cn.is_normal, &dc));
    PetscCall(VecAXPBY(vc, 1.0 / dt, 0.0, dc));
    PetscCall(VecRestoreSubVector(s->work, cn.is_normal, &dc));
    PetscCall(VecRestoreSubVector(s->v, cn.is_normal, &vc));
  }
  PetscCall(VecCopy(w, s->u));
  PetscFunctionReturn(0);
}

static PetscErrorCode SaveOldState(MMState *s)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(s->u, s->u_old));
  PetscCall(VecCopy(s->v, s->v_old));
  PetscCall(VecCopy(s->a, s->a_old));
  PetscCall(VecCopy(s->react, s->react_old));
  PetscFunctionReturn(0);
}

/* A rejected step is retried with dt times TSAdapt's -ts_adapt_scale_solve_failed, down to
 * -ts_adapt_dt_min and at most -ts_max_reject times; past those the run stops and says why. */
static PetscErrorCode RejectStep(TS ts, MMNewmark nm, PetscInt rejections, MMRejectReason why, PetscReal w_c, PetscReal scale)
{
  const PetscReal dt = ts->time_step;
  PetscReal       h_c, cfl;
  MMContactNodes  cn;
  PetscReal       contraction;
  const PetscReal new_dt = dt * ts->adapt->scale_solve_failed;
  MPI_Comm        comm   = PetscObjectComm((PetscObject)ts);
  PetscReal       hmin, hmax;
  PetscBool       can_retry;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  h_c = cn.h_c;
  cfl = nm->material->c_p_max * dt / h_c;
  PetscCall(TSAdaptGetStepLimits(ts->adapt, &hmin, &hmax));
  PetscCall(MMFrictionGetConvergence(nm->friction, NULL, NULL, &contraction, NULL));
  ts->reject++;
  ts->num_snes_failures++;
  PetscCall(MMAdaptGrowBackRejected(ts, (PetscBool)(why == MM_REJECT_FRICTION)));
  PetscCall(VecCopy(nm->state.react_old, nm->state.react));
  PetscCall(MMFrictionRejectStep(nm->friction));
  can_retry = (PetscBool)(new_dt >= hmin && (ts->max_reject < 0 || rejections <= ts->max_reject));
  if (why == MM_REJECT_FRICTION) {
    PetscCheck(can_retry, comm, PETSC_ERR_NOT_CONVERGED,
               "The friction loop does not converge at t = %g: last dt = %g, observed contraction factor %.3f, c_p dt / h_c' = %.3f. The next dt %g would be below -ts_adapt_dt_min %g (or past -ts_max_reject %" PetscInt_FMT "). The paper's fixed point (Theorem 4.2) needs c_p dt / h_c' small enough for mu = %g: use -friction_type newton, or lower -ts_dt or -mu, or raise -friction_snes_max_it. The output up to t = %g is intact",
               (double)ts->ptime, (double)dt, (double)contraction, (double)cfl, (double)new_dt, (double)hmin, ts->max_reject, (double)nm->pb.mu, (double)ts->ptime);
    if (!nm->pb.quiet) PetscCall(PetscPrintf(comm, "  step rejected at t = %g: the friction loop did not converge with dt = %g (contraction factor %.3f, c_p dt / h_c' = %.3f); retrying with dt = %g\n", (double)ts->ptime, (double)dt, (double)contraction, (double)cfl, (double)new_dt));
  } else if (why == MM_REJECT_NONLINEAR) {
    PetscCheck(can_retry, comm, PETSC_ERR_NOT_CONVERGED, "The finite-strain step does not converge at t = %g: after %" PetscInt_FMT " iterations (-nonlinear_max_it) its residual is %.3g of the internal force (-nonlinear_rtol %g), with dt = %g. The next dt %g would be below -ts_adapt_dt_min %g (or past -ts_max_reject %" PetscInt_FMT "). Lower -ts_dt, raise -nonlinear_max_it, or use -nonlinear_tangent step. The output up to t = %g is intact",
               (double)ts->ptime, nm->nl.max_it, (double)nm->nl.residual, (double)nm->nl.rtol, (double)dt, (double)new_dt, (double)hmin, ts->max_reject, (double)ts->ptime);
    if (!nm->pb.quiet && nm->nl.friction_failed) PetscCall(PetscPrintf(comm, "  step rejected at t = %g: the friction solve of the finite-strain step's iteration %" PetscInt_FMT " did not converge with dt = %g (the last iterate's residual %.3g); retrying with dt = %g\n", (double)ts->ptime, nm->nl.its, (double)dt, nm->nl.its > 1 ? (double)nm->nl.residual : 0.0, (double)new_dt));
    else if (!nm->pb.quiet) PetscCall(PetscPrintf(comm, "  step rejected at t = %g: the finite-strain step did not converge with dt = %g (residual %.3g after %" PetscInt_FMT " iterations); retrying with dt = %g\n", (double)ts->ptime, (double)dt, (double)nm->nl.residual, nm->nl.max_it, (double)new_dt));
  } else {
    PetscCheck(can_retry, comm, PETSC_ERR_NOT_CONVERGED,
               "A contact release at t = %g creates energy that dt does not resolve: the step's contact work W_c = %g is %.3g of the energy scale, above -contact_work_tol %g, with dt = %g (c_p dt / h_c' = %.3g). The next dt %g would be below -ts_adapt_dt_min %g (or past -ts_max_reject %" PetscInt_FMT "). Use a -ts_dt near h_c' / c_p = %g, so that the contact pressure is resolved in time. The output up to t = %g is intact",
               (double)ts->ptime, (double)w_c, (double)(w_c / scale), (double)nm->contact_work_tol, (double)dt, (double)cfl, (double)new_dt, (double)hmin, ts->max_reject, (double)(h_c / nm->material->c_p_max), (double)ts->ptime);
    if (!nm->pb.quiet) PetscCall(PetscPrintf(comm, "  step rejected at t = %g: its contact work W_c = %g would create %.3g of the energy scale (-contact_work_tol %g) with dt = %g (c_p dt / h_c' = %.3g); retrying with dt = %g\n", (double)ts->ptime, (double)w_c, (double)(w_c / scale), (double)nm->contact_work_tol, (double)dt, (double)cfl, (double)new_dt));
  }
  ts->time_step = new_dt;
  PetscFunctionReturn(0);
}

/* The contact-work guard: the trapezoidal contact work 1/2 (lambda^n + lambda^{n+1}).du is not a
 * solver error, so the balance audit cannot see energy created at a release that dt does not
 * resolve (docs/method.md section 4, "Energy at contact release"). A step that creates more than
 * -contact_work_tol of the run's energy scale is refused. */
static PetscErrorCode ContactWorkTooLarge(MMNewmark nm, Vec w, PetscBool *too_large, PetscReal *w_c, PetscReal *scale)
{
  PetscFunctionBeginUser;
  *scale = PetscMax(nm->hist.energy_scale, PetscAbsReal(nm->hist.work_ext));
  PetscCall(MMEnergyContactWork(nm, w, w_c));
  /* with no energy in the run yet there is nothing to compare with */
  *too_large = (PetscBool)(*scale > 0 && *w_c > nm->contact_work_tol * *scale);
  PetscFunctionReturn(0);
}

/* How close to -ts_max_time a time counts as that time: far above the rounding of a sum of steps,
 * far below any step. */
static PetscReal FinalTimeTolerance(TS ts)
{
  return 1e-10 * ts->max_time;
}

/* -ts_exact_final_time matchstep (the default): a step that would end past the final time is
 * shortened to end on it (K~ = A + 4/dt^2 M* is then factored once more, for that last step);
 * stepover takes it whole, as PETSc's TS does (README "Options", time). A step that ends on the
 * final time up to rounding is left alone: it is snapped to the final time once taken. */
static PetscErrorCode MatchFinalTime(TS ts)
{
  PetscFunctionBeginUser;
  if (ts->exact_final_time != TS_EXACTFINALTIME_MATCHSTEP) PetscFunctionReturn(0);
  if (ts->ptime + ts->time_step > ts->max_time + FinalTimeTolerance(ts)) ts->time_step = ts->max_time - ts->ptime;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkFromTS - Gives the stepper's context of a TS made by MMNewmarkCreateTS()

  Not collective

  Input Parameter:
. ts - the TS

  Output Parameter:
. nm - its context

  Level: developer

.seealso: `MMNewmarkCreateTS()`
@*/
PetscErrorCode MMNewmarkFromTS(TS ts, MMNewmark *nm)
{
  PetscBool is;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSNEWMARK, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "The TS is not mmcontact's stepper");
  *nm = ((TS_Newmark *)ts->data)->nm;
  PetscFunctionReturn(0);
}

/* One step: solve, guard, and on rejection retry with a smaller dt; the adaptor (growback by default,
 * adapt_growback.c) then chooses the next dt. The linear and finite-strain steps differ by their law's
 * ops alone (step_laws.c, docs/developer.md "The step's data flow"). */
static PetscErrorCode TSStep_Newmark(TS ts)
{
  MMNewmark nm  = ((TS_Newmark *)ts->data)->nm;
  MMState  *s   = &nm->state;
  PetscReal dt = ts->time_step, next_dt;
  PetscBool accept, solved = PETSC_FALSE;
  PetscInt  rejections = 0, refines = 0;
  Vec       w  = ts->vec_sol;

  PetscFunctionBeginUser;
  PetscCall(MatchFinalTime(ts));
  if (nm->law->begin) PetscCall((*nm->law->begin)(nm, ts->ptime, ts->time_step)); /* frames and pairs that follow the body */
  PetscCall(SaveOldState(s));
  PetscCall(MMFrictionBeginStep(nm->friction));
  s->has_du = PETSC_FALSE;
  PetscCall(MMContactCornersAccept(nm->contact));
  while (!solved) {
    PetscReal w_c, scale;
    PetscBool    too_large = PETSC_FALSE;
    Vec          b;

    dt = ts->time_step;
    PetscCall(MMNewmarkSetStep(nm, dt)); /* K~, and the step's offset and scale (scheme.c) */
    PetscCall(MMContactSetTime(nm->contact, ts->ptime + dt, dt));
    PetscCall(MMLoadsSetTime(nm->loads, ts->ptime, ts->ptime + dt)); /* L^{n+1} and the lift of u_D(t^{n+1}) */
    PetscCall(MMContactGetRHS(nm->contact, &b));
    PetscCall(MMNewmarkPredictEnd(nm, dt, w)); /* scheme.c */
    PetscCall((*nm->law->solve)(nm, ts->ptime, dt, b, w, &solved));
    for (PetscInt tries = 1; solved; ++tries) { /* accepted by its certificate (certificate.c) */
      PetscBool again;
      PetscCall(MMCertificateCheck(nm, b, w, tries, &again));
      if (!again) break;
      PetscCall((*nm->law->solve)(nm, ts->ptime, dt, b, w, &solved));
    }
    if (!solved) {
      PetscCall(RejectStep(ts, nm, ++rejections, nm->law->failure, 0, 0));
      continue;
    }
    if (nm->law->refine) {
      PetscBool again;
      PetscCall((*nm->law->refine)(nm, ts->ptime, dt, w, ++refines, &again));
      if (again) { /* solved again from its start, with the frames where it ended (nonlinear.c) */
        PetscCall(MMFrictionRejectStep(nm->friction));
        PetscCall(SaveOldState(s)); /* the start, turned */
        solved = PETSC_FALSE;
        continue;
      }
    }
    PetscCall(ContactWorkTooLarge(nm, w, &too_large, &w_c, &scale));
    s->work_contact = w_c;
    if (too_large) {
      solved = PETSC_FALSE;
      PetscCall(RejectStep(ts, nm, ++rejections, MM_REJECT_CONTACT_WORK, w_c, scale));
    }
  }
  PetscCall(UpdateKinematics(nm, dt, w));
  PetscCall(MMNewmarkStepIncrement(nm, s->u, s->work));
  PetscCall(MMDampingUpdateVelocity(&nm->damping, s->work, dt));
  s->dt   = dt;
  next_dt = dt;
  PetscCall(TSAdaptChoose(ts->adapt, ts, dt, NULL, &next_dt, &accept));
  if (!accept) {
    ts->reason = TS_DIVERGED_STEP_REJECTED;
    PetscFunctionReturn(0);
  }
  /* TSAdapt's matchstep clipping changes dt by rounding when the next step ends on the final time:
   * keep dt, and the factorization of K~ that goes with it (the step is snapped to the final time) */
  if (PetscAbsReal(next_dt - dt) <= 1e-8 * dt) next_dt = dt;
  ts->ptime += dt;
  /* the sum of n steps misses n dt by rounding: a time within the tolerance of the final time is it,
   * so the run ends there instead of taking one more step past it */
  if (PetscAbsReal(ts->ptime - ts->max_time) <= FinalTimeTolerance(ts)) ts->ptime = ts->max_time;
  ts->time_step = next_dt;
  nm->hist.step = ts->steps + 1;
  nm->hist.time = ts->ptime;
  PetscCall(MMEnergyStep(nm));
  PetscCall(MMDeformationCheck(nm));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSDestroy_Newmark(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(ts->data));
  PetscFunctionReturn(0);
}

/* TSView's type part: the stepper's configuration (ts_view.c) */
static PetscErrorCode TSView_Newmark(TS ts, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(MMNewmarkView(((TS_Newmark *)ts->data)->nm, ts->time_step, viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSCreate_Newmark(TS ts)
{
  TS_Newmark *nm;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&nm));
  ts->data                = nm;
  ts->ops->step           = TSStep_Newmark;
  ts->ops->destroy        = TSDestroy_Newmark;
  ts->ops->view           = TSView_Newmark;
  ts->default_adapt_type  = TSADAPTGROWBACK;
  ts->usessnes            = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkRegister(void)
{
  PetscFunctionBeginUser;
  PetscCall(TSRegister(TSNEWMARK, TSCreate_Newmark));
  PetscCall(MMAdaptGrowBackRegister());
  PetscFunctionReturn(0);
}

/* -ts_dt and -ts_max_time when not given */
static const PetscReal MMDtDefault = 1e-3, MMMaxTimeDefault = 1.0;

/*@
  MMNewmarkSetDefaults - Sets a TS's type to newmark and its defaults, before the options are read

  Logically collective

  Input Parameter:
. ts - the TS

  Note:
  The stepper and its defaults, before the options (also what -help shows without a mesh).

  Level: developer

.seealso: `MMNewmarkCreateTS()`
@*/
PetscErrorCode MMNewmarkSetDefaults(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSSetType(ts, TSNEWMARK));
  PetscCall(TSSetProblemType(ts, TS_LINEAR));
  PetscCall(TSSetTimeStep(ts, MMDtDefault));
  PetscCall(TSSetMaxTime(ts, MMMaxTimeDefault));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetPlan - Gives the run's plan as the options give it, before the TS exists: dt and the
  number of steps

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameters:
+ dt    - -ts_dt
- steps - the steps to -ts_max_time or -ts_max_steps, whichever ends the run first (at least 1)

  Note:
  The run's plan as the options give it, before the TS exists: dt (-ts_dt) and the number of steps
  to -ts_max_time or -ts_max_steps, whichever ends the run first (at least 1). The contact
  formulation's cost model weighs its set-up against its steps with it (docs/scaling.md, "The
  formulation chosen by cost"); a dt that adaptation changes later is not foreseen. The values are
  checked where the TS reads them (CheckTimeOptions).

  Level: developer

.seealso: `MMNewmarkCreateTS()`, `MMContactSetUp()`
@*/
PetscErrorCode MMNewmarkGetPlan(MMNewmark nm, PetscReal *dt, PetscReal *steps)
{
  PetscReal tmax = MMMaxTimeDefault;
  PetscInt  nmax = -1;
  PetscBool set;

  PetscFunctionBeginUser;
  (void)nm;
  *dt = MMDtDefault;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-ts_dt", dt, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-ts_max_time", &tmax, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-ts_max_steps", &nmax, &set));
  *steps = *dt > 0 && tmax > 0 && !PetscIsInfOrNanReal(*dt) && !PetscIsInfOrNanReal(tmax) ? PetscCeilReal(tmax / *dt - 1e-10) : 1;
  if (set && nmax >= 0) *steps = PetscMin(*steps, (PetscReal)nmax);
  *steps = PetscMax(*steps, 1);
  PetscFunctionReturn(0);
}

/* The run's step count must fit the TS's step counter (a PetscInt): PETSc reads -ts_max_steps
 * 3000000000 as -1294967296, and -ts_max_time 1e30 at dt 1e-3 plans 1e33 steps, which the counter,
 * the progress line and the output schedule cannot count. Refused before anything is set up, with
 * the values as given. */
PetscErrorCode MMNewmarkCheckStepCount(MPI_Comm comm)
{
  PetscReal dt, steps, tmax = MMMaxTimeDefault;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, "-ts_dt", MM_VALUE_REAL));
  PetscCall(MMOptionsCheckValue(comm, "-ts_max_time", MM_VALUE_REAL));
  PetscCall(MMOptionsCheckValue(comm, "-ts_max_steps", MM_VALUE_INT));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-ts_max_time", &tmax, NULL));
  PetscCall(MMNewmarkGetPlan(NULL, &dt, &steps));
  PetscCheck(steps < (PetscReal)PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT, "-ts_max_time %g at -ts_dt %g is %.3g steps, beyond the %lld steps a run can count: give a shorter -ts_max_time, a larger -ts_dt, or a -ts_max_steps below %lld", (double)tmax, (double)dt, (double)steps, (long long)PETSC_MAX_INT, (long long)PETSC_MAX_INT);
  PetscFunctionReturn(0);
}

/* -ts_dt, -ts_max_time and -ts_max_steps, each refused with its range. */
static PetscErrorCode CheckTimeOptions(TS ts)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)ts);
  PetscReal              dt, tmax;
  PetscInt               nmax;
  TSExactFinalTimeOption eft;

  PetscFunctionBeginUser;
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(TSGetMaxTime(ts, &tmax));
  PetscCall(TSGetMaxSteps(ts, &nmax));
  PetscCheck(!PetscIsInfOrNanReal(dt) && dt > 0, comm, PETSC_ERR_USER_INPUT, "The time step -ts_dt %g must be > 0 and finite", (double)dt);
  PetscCheck(!PetscIsInfOrNanReal(tmax) && tmax > 0, comm, PETSC_ERR_USER_INPUT, "The final time -ts_max_time %g must be > 0 and finite", (double)tmax);
  PetscCheck(nmax >= 0, comm, PETSC_ERR_USER_INPUT, "-ts_max_steps %" PetscInt_FMT " must be >= 0", nmax);
  PetscCall(TSGetExactFinalTime(ts, &eft));
  PetscCheck(eft != TS_EXACTFINALTIME_INTERPOLATE, comm, PETSC_ERR_USER_INPUT, "-ts_exact_final_time interpolate is not supported: the scheme's energy identity, audited every step, holds at its steps and not between them, so no state is reported between steps. Use matchstep (the default: the last step is shortened to end at -ts_max_time) or stepover (the last step is taken whole, ending past it)");
  PetscCheck(dt <= tmax, comm, PETSC_ERR_USER_INPUT, "The time step -ts_dt %g is beyond the final time -ts_max_time %g: the run would take one step far past it. Give a -ts_dt below %g", (double)dt, (double)tmax, (double)tmax);
  PetscFunctionReturn(0);
}

/* c_p dt / h_c' >> 1: the contact pressure is not resolved in time, releases may create energy
 * (the contact-work guard then cuts dt), and Theorem 4.2's friction condition is far off. */
static PetscErrorCode WarnUnresolvedContact(MMNewmark nm, PetscReal dt)
{
  const PetscReal limit = 10;
  MMContactNodes  cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  if (!cn.enabled || cn.h_c <= 0) PetscFunctionReturn(0);
  const PetscReal cfl = nm->material->c_p_max * dt / cn.h_c;
  PetscCheck(!PetscIsInfOrNanReal(cfl), PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_USER_INPUT, "The wave speed c_p = %g from -E %g, -nu %g, -rho %g is not a finite number", (double)nm->material->c_p_max, (double)nm->pb.E, (double)nm->pb.nu, (double)nm->pb.rho);
  if (cfl > limit)
    PetscCall(PetscPrintf(PetscObjectComm((PetscObject)nm->dm), "WARNING: c_p dt / h_c' = %.3g is far above 1 (c_p = %g, h_c' = %g, dt = %g): the time step does not resolve the contact pressure. A release may create energy; steps that create more than -contact_work_tol %g of the energy scale are retried with smaller dt. A -ts_dt near h_c' / c_p = %g resolves the contact\n",
                          (double)cfl, (double)nm->material->c_p_max, (double)cn.h_c, (double)dt, (double)nm->contact_work_tol, (double)(cn.h_c / nm->material->c_p_max)));
  PetscFunctionReturn(0);
}

/* The adaptor only chooses dt after rejections: growback (the default) or none (dt stays where a
 * rejection left it). The others need an error estimate the scheme does not make. dt never grows
 * past -ts_dt, and unless -ts_adapt_dt_min says otherwise never falls below 1e-6 -ts_dt: a step
 * that still fails there fails for another reason than dt, and the run stops and says so instead of
 * crawling. */
static PetscErrorCode SetUpAdapt(TS ts, PetscReal dt)
{
  TSAdapt   adapt;
  TSAdaptType type;
  PetscBool gb, none, set;
  PetscReal hmin, hmax;

  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, &type));
  PetscCall(PetscStrcmp(type, TSADAPTGROWBACK, &gb));
  PetscCall(PetscStrcmp(type, TSADAPTNONE, &none));
  PetscCheck(gb || none, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER_INPUT, "-ts_adapt_type %s is not supported: the trapezoidal scheme makes no error estimate, and dt changes only after a rejected step. Use growback (the default: dt grows back after -ts_adapt_growback_steps accepted steps) or none (dt stays reduced)", type);
  PetscCall(TSAdaptGetStepLimits(adapt, &hmin, &hmax));
  PetscCall(PetscOptionsHasName(NULL, ((PetscObject)adapt)->prefix, "-ts_adapt_dt_min", &set));
  if (!set) hmin = 1e-6 * dt;
  PetscCall(TSAdaptSetStepLimits(adapt, hmin, PetscMin(hmax, dt)));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkCreateTS - Creates the TS of type newmark that steps the context, set from the options
  (-ts_*) and checked

  Collective

  Input Parameter:
. nm - the stepper's context, with its initial state

  Output Parameter:
. ts - the new TS

  Level: beginner

.seealso: `MMNewmarkSetDefaults()`, `MMNewmarkFromTS()`, `TSSolve()`, `TSView()`
@*/
PetscErrorCode MMNewmarkCreateTS(MMNewmark nm, TS *ts)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)nm->dm);
  PetscReal dt;
  TSType    type;
  PetscBool isnewmark;

  PetscFunctionBeginUser;
  PetscCall(TSCreate(comm, ts));
  PetscCall(MMNewmarkSetDefaults(*ts));
  PetscCall(TSSetFromOptions(*ts));
  PetscCall(TSGetType(*ts, &type));
  PetscCall(PetscStrcmp(type, TSNEWMARK, &isnewmark));
  PetscCheck(isnewmark, comm, PETSC_ERR_USER_INPUT, "-ts_type %s is not supported: mmcontact steps with its own -ts_type newmark", type);
  ((TS_Newmark *)(*ts)->data)->nm = nm;
  PetscCall(CheckTimeOptions(*ts));
  PetscCall(TSGetTimeStep(*ts, &dt));
  nm->state.dt_user = dt;
  PetscCall(SetUpAdapt(*ts, dt));
  PetscCall(WarnUnresolvedContact(nm, dt));
  PetscCall(TSSetSolution(*ts, nm->state.u_next));
  PetscFunctionReturn(0);
}
