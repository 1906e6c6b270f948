/* The trapezoidal scheme's share of a step that the solvers beneath the stepper need (docs/developer.md,
 * "The step's data flow"): the step's offset u^n + dt/2 v^n, the scale 2/dt and the velocity of a
 * displacement over the step, handed to contact (and through it to friction) with the step matrix.
 * Contact and friction never see u^n or v^n: the scheme is the stepper's alone (docs/method.md
 * section 3). */
#include "newmarkimpl.h"

/* sigma = 2/dt (w - u^n) - v^n: the velocity of w over the step (MMStepOffset's velocity); while the
 * linear step solves for the increment (MMNewmarkSolveIncrement), w is du and sigma = 2/dt du - v^n */
static PetscErrorCode StepVelocity(void *ctx, Vec w, Vec sigma)
{
  MMNewmark nm = (MMNewmark)ctx;

  PetscFunctionBeginUser;
  if (nm->scheme_origin_zero) PetscCall(VecCopy(w, sigma));
  else PetscCall(VecWAXPY(sigma, -1.0, nm->state.u_old, w));
  PetscCall(VecAXPBY(sigma, -1.0, nm->scheme.scale, nm->state.v_old));
  PetscFunctionReturn(0);
}

/* offset = u + dt/2 v, entry by entry in this order: the rounding the contact rows' tangential
 * bounds have always had (a BLAS axpy may fuse the multiply and the add) */
static PetscErrorCode Midpoint(Vec u, Vec v, PetscReal dt, Vec offset)
{
  const PetscScalar *ua, *va;
  PetscScalar       *oa;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(offset, &n));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(v, &va));
  PetscCall(VecGetArrayWrite(offset, &oa));
  for (PetscInt i = 0; i < n; ++i) oa[i] = ua[i] + 0.5 * dt * va[i];
  PetscCall(VecRestoreArrayWrite(offset, &oa));
  PetscCall(VecRestoreArrayRead(v, &va));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscFunctionReturn(0);
}

/* The step's offset from its saved start u^n, v^n; from the origin of the increment, dt/2 v^n, while
 * the linear step solves for du (MMNewmarkSolveIncrement) */
static PetscErrorCode StepOffset(MMNewmark nm, PetscReal dt)
{
  PetscFunctionBeginUser;
  if (nm->scheme_origin_zero) PetscCall(VecAXPBY(nm->scheme.offset, 0.5 * dt, 0.0, nm->state.v_old));
  else PetscCall(Midpoint(nm->state.u_old, nm->state.v_old, dt, nm->scheme.offset));
  PetscFunctionReturn(0);
}

/* The scheme's prediction of the displacement at the middle of the next step of dt, from the current
 * state (before the step saves its start): u + dt/2 v, the zero-velocity point of the trapezoidal
 * step, where the contact frames that follow are taken (MMContactFramesUpdate). In the offset's
 * storage, which MMNewmarkSetStep fills again for the step itself. */
PetscErrorCode MMNewmarkPredictMidpoint(MMNewmark nm, PetscReal dt, Vec *midpoint)
{
  PetscFunctionBeginUser;
  PetscCall(Midpoint(nm->state.u, nm->state.v, dt, nm->scheme.offset));
  *midpoint = nm->scheme.offset;
  PetscFunctionReturn(0);
}

/* The step's predictor u + dt v + dt^2/4 a from the current state, exact for a constant acceleration:
 * where the step's solve starts (newmark.c), the large-sliding pairing (nonlinear.c) and the mass in
 * free flight (free_flight.c) look */
PetscErrorCode MMNewmarkPredictEnd(MMNewmark nm, PetscReal dt, Vec w)
{
  PetscFunctionBeginUser;
  PetscCall(VecAXPBYPCZ(w, dt, 0.25 * dt * dt, 0.0, nm->state.v, nm->state.a));
  PetscCall(VecAXPY(w, 1.0, nm->state.u));
  PetscFunctionReturn(0);
}

/* Before any contact solve: the offset of a state at rest at the origin (u^n = v^n = 0 until the
 * first step saves its start), no scale yet (MMNewmarkSetStep gives it with the first dt). */
PetscErrorCode MMNewmarkSchemeSetUp(MMNewmark nm)
{
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(nm->state.u, &nm->scheme.offset));
  PetscCall(VecZeroEntries(nm->scheme.offset));
  nm->scheme.scale    = 0;
  nm->scheme.velocity = StepVelocity;
  nm->scheme.ctx      = nm;
  PetscCall(MMContactSetStepOffset(nm->contact, &nm->scheme));
  PetscFunctionReturn(0);
}

/* The step of dt handed to contact: its matrix (the law's ops, as MMNewmarkGetStepMatrix gives it), and the offset
 * and scale of the step from the saved start u^n, v^n. At each try of a step, and once at set-up. */
PetscErrorCode MMNewmarkSetStep(MMNewmark nm, PetscReal dt)
{
  MMStepMatrix sm;

  PetscFunctionBeginUser;
  PetscCall((*nm->law->stepmatrix)(nm, dt, &sm)); /* the law's K~ coefficients (step_laws.c) */
  PetscCall(MMContactSetStepMatrix(nm->contact, &sm));
  PetscCall(StepOffset(nm, dt));
  nm->scheme.scale = 2.0 / dt;
  PetscCall(MMContactSetStepOffset(nm->contact, &nm->scheme));
  PetscFunctionReturn(0);
}

/* While the linear step solves for its increment du (step_laws.c): the offset and the velocity of the
 * step are those of du, the origin u^n taken out (on), or of w again (off) */
PetscErrorCode MMNewmarkSchemeIncrement(MMNewmark nm, PetscReal dt, PetscBool on)
{
  PetscFunctionBeginUser;
  nm->scheme_origin_zero = on;
  PetscCall(StepOffset(nm, dt));
  PetscCall(MMContactSetStepOffset(nm->contact, &nm->scheme));
  PetscFunctionReturn(0);
}

/* The step's increment du = w - u^n: the one the linear step solved for, or formed */
PetscErrorCode MMNewmarkStepIncrement(MMNewmark nm, Vec w, Vec du)
{
  PetscFunctionBeginUser;
  if (nm->state.has_du) PetscCall(VecCopy(nm->state.du, du));
  else PetscCall(VecWAXPY(du, -1.0, nm->state.u_old, w));
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkSchemeDestroy(MMNewmark nm)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&nm->scheme.offset));
  PetscFunctionReturn(0);
}
