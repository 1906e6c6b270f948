/* The step's laws: what the linear and the finite-strain steps do differently in TSStep_Newmark's one
 * skeleton (newmark.c), as an ops table, as the elasticity laws have theirs (src/fem/elasticity_laws.c).
 * The linear law's step is one contact (and friction) solve of K~ w = b with the trapezoidal
 * right-hand side (docs/method.md section 3); the finite-strain law's is the iteration of
 * nonlinear.c (docs/method.md section 13), whose frames and pairs follow the body at the step's
 * start. The table is chosen once, at set-up (MMNewmarkSetUp). */
#include "newmarkimpl.h"
#include "friction.h"

/* b = L(t^{n+1}) - lift(t^{n+1}) + M* (4/dt^2 u^n + 4/dt v^n + a^n) [+ C (2/dt u^n + vC^n) with damping] */
static PetscErrorCode StepRHS(MMNewmark nm, PetscReal dt, Vec b)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(VecAXPBYPCZ(s->work, 4.0 / (dt * dt), 4.0 / dt, 0.0, s->u, s->v));
  PetscCall(VecAXPY(s->work, 1.0, s->a));
  PetscCall(MatMult(ops.Mstar, s->work, b));
  PetscCall(VecAXPY(b, 1.0, ops.load));
  PetscCall(VecAXPY(b, -1.0, ops.lift));
  PetscCall(MMDampingAddStepRHS(&nm->damping, s->u, dt, b));
  PetscFunctionReturn(0);
}

/* K~ = K + 2 beta/dt B + (4/dt^2 + 2 alpha/dt) M* (damping.c) */
static PetscErrorCode LinearStepMatrix(MMNewmark nm, PetscReal dt, MMStepMatrix *sm)
{
  MMContactOperators ops;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMDampingGetStepMatrix(&nm->damping, ops.K, dt, sm));
  PetscFunctionReturn(0);
}

/* The increment's right-hand side b - K~ u^n, formed without the 4/dt^2 M* u^n that the two cancel:
 * L - lift + M* (4/dt v^n + a^n) - K u^n [+ C vC^n with damping] (K~ = K + cb B + cm M*, ck = 1) */
static PetscErrorCode StepRHSIncrement(MMNewmark nm, PetscReal dt, Vec b)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(VecAXPBYPCZ(s->work, 4.0 / dt, 1.0, 0.0, s->v, s->a));
  PetscCall(MatMult(ops.Mstar, s->work, b));
  PetscCall(VecAXPY(b, 1.0, ops.load));
  PetscCall(VecAXPY(b, -1.0, ops.lift));
  PetscCall(MatMult(ops.K, s->u, s->work));
  PetscCall(VecAXPY(b, -1.0, s->work));
  PetscCall(MMDampingAddStepRHSIncrement(&nm->damping, b));
  PetscFunctionReturn(0);
}

/* b completed with the step's right-hand side, and the one contact (and friction) solve. With
 * -step_increments the unknown is du = w - u^n (docs/method.md section 3, "The step's unknown"): the
 * bounds, the offset and the velocity of the step are taken from the origin u^n, du is solved for
 * and kept (the kinematics, the certificate and the audit use it), and w = u^n + du. */
static PetscErrorCode LinearSolve(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, PetscBool *solved)
{
  MMState *s = &nm->state;

  PetscFunctionBeginUser;
  (void)t0;
  s->has_du = PETSC_FALSE;
  if (!nm->increments) {
    PetscCall(StepRHS(nm, dt, b));
    PetscCall(MMFrictionSolve(nm->friction, nm->hist.step, nm->hist.time, b, w, s->react, solved));
    PetscFunctionReturn(0);
  }
  PetscCall(StepRHSIncrement(nm, dt, b));
  PetscCall(VecWAXPY(s->du, -1.0, s->u_old, w)); /* the predictor's increment: where the solve starts */
  PetscCall(MMNewmarkSchemeIncrement(nm, dt, PETSC_TRUE));
  PetscCall(MMContactShiftBounds(nm->contact, s->u_old, PETSC_TRUE));
  PetscCall(MMFrictionSolve(nm->friction, nm->hist.step, nm->hist.time, b, s->du, s->react, solved));
  PetscCall(MMContactShiftBounds(nm->contact, s->u_old, PETSC_FALSE));
  PetscCall(MMNewmarkSchemeIncrement(nm, dt, PETSC_FALSE));
  PetscCall(VecWAXPY(w, 1.0, s->u_old, s->du));
  s->has_du = *solved;
  PetscFunctionReturn(0);
}

/* The contact frames of the nodes near a curved obstacle follow their contact point (docs/method.md
 * section 8), M* is M or -mass's as the body is far from its obstacles or near (free_flight.c), then
 * the contact pairs' large-sliding pairing */
static PetscErrorCode FiniteBegin(MMNewmark nm, PetscReal t, PetscReal dt)
{
  Vec midpoint;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkPredictMidpoint(nm, dt, &midpoint)); /* the scheme's prediction (scheme.c) */
  PetscCall(MMNonlinearFollowFrames(nm, t, dt, midpoint));
  PetscCall(MMNonlinearFreeFlight(nm, t, dt));
  PetscCall(MMNonlinearSlidePairs(nm, dt));
  PetscFunctionReturn(0);
}

/* The finite-strain iteration (nonlinear.c); a step solved with the standard mass in which a node
 * touched is solved again from its start with -mass's M* (free_flight.c) */
static PetscErrorCode FiniteSolve(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, PetscBool *solved)
{
  PetscBool touched;

  PetscFunctionBeginUser;
  PetscCall(MMNonlinearSolve(nm, t0, dt, b, w, solved));
  if (!*solved) PetscFunctionReturn(0);
  PetscCall(MMNonlinearFreeFlightTouched(nm, w, t0 + dt, &touched));
  if (!touched) PetscFunctionReturn(0);
  PetscCall(MMNewmarkSetStep(nm, dt)); /* K~ of the new M* */
  PetscCall(MMNewmarkPredictEnd(nm, dt, w));
  PetscCall(MMNonlinearSolve(nm, t0, dt, b, w, solved));
  PetscFunctionReturn(0);
}

static const MMStepLawOps LinearLaw = {.begin = NULL, .stepmatrix = LinearStepMatrix, .solve = LinearSolve, .failure = MM_REJECT_FRICTION, .certified = PETSC_TRUE};
static const MMStepLawOps FiniteLaw = {.begin = FiniteBegin, .stepmatrix = MMNonlinearStepMatrix, .solve = FiniteSolve, .refine = MMNonlinearRefineStep, .failure = MM_REJECT_NONLINEAR, .certified = PETSC_FALSE};

/* The step's law of the elasticity law: the finite-strain step for the finite-strain laws */
const MMStepLawOps *MMStepLawGetOps(const MMMaterial *material)
{
  return material->finite ? &FiniteLaw : &LinearLaw;
}

/*@
  MMNewmarkGetStepMatrix - Computes the coefficients of the step matrix K~ = ck K + cb B + cm M* for
  dt, as each step builds it

  Not collective

  Input Parameters:
+ nm - the stepper's context
- dt - the time step

  Output Parameter:
. sm - the coefficients, B and the stiffness in K~ (NULL: fem's K)

  Note:
  The step law's stepmatrix op: with a finite-strain law the iteration matrix (K_s, the tangent of a
  restart's checkpoint too), else the (damped) K~

  Level: intermediate

.seealso: `MMDampingGetStepMatrix()`, `MMContactSetStepMatrix()`
@*/
PetscErrorCode MMNewmarkGetStepMatrix(MMNewmark nm, PetscReal dt, MMStepMatrix *sm)
{
  PetscFunctionBeginUser;
  PetscCall((*nm->law->stepmatrix)(nm, dt, sm));
  PetscFunctionReturn(0);
}
