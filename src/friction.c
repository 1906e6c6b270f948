/* Coulomb friction: the fixed point of the proof of Theorem 4.2 (map Phi^n) on the thresholds.
 *
 * An outer SNES of type shell (prefix friction_) wraps the contact VI: each iteration freezes the
 * thresholds s_i = mu r_i, solves the Tresca-plus-contact step exactly (the contact module), and updates r.
 * It converges when the thresholds stop changing (-friction_snes_rtol) and the discrete Coulomb
 * residual is below -friction_coulomb_tol. A loop that does not contract is reported as
 * diverged, and the stepper retries the step with a smaller dt. */
#include <petsc/private/snesimpl.h>
#include "friction.h"
#include "contact.h"

/* sigma = 2/dt (w - u^n) - v^n: the velocity of w; on the tangential contact dofs, the slip velocity. */
static PetscErrorCode SlipVelocity(MMCtx *ctx, Vec w, Vec sigma)
{
  MMState  *s  = &ctx->state;
  PetscReal dt = ctx->contact.Kt_dt;

  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(sigma, -1.0, s->u_old, w));
  PetscCall(VecAXPBY(sigma, -1.0, 2.0 / dt, s->v_old));
  PetscFunctionReturn(0);
}

static PetscErrorCode FrictionLoop(SNES snes, Vec s)
{
  MMCtx      *ctx;
  MMFriction *fr;
  PetscReal   rtol, ds_prev = 0, ds_first = 0;
  PetscInt    maxit, growing = 0;

  PetscFunctionBeginUser;
  PetscCall(SNESShellGetContext(snes, &ctx));
  fr = &ctx->friction;
  PetscCall(SNESGetTolerances(snes, NULL, &rtol, NULL, &maxit, NULL));
  fr->contraction_max = 0;
  snes->reason        = SNES_CONVERGED_ITERATING;
  for (PetscInt k = 0; k < maxit; ++k) {
    PetscReal ds, snorm, coulomb, dchange;
    PetscInt  nslip, nstick, nswitch;

    PetscCall(MMContactSetFrictionThresholds(ctx, s));
    /* contact dofs only: the thresholds, slip, Coulomb residual and states need nothing else */
    PetscCall(MMContactSolveContactDofs(ctx, fr->b, fr->w, fr->react));
    PetscCall(MMContactGetNormalReactions(ctx, fr->s_new));
    PetscCall(VecPointwiseMult(fr->s_new, fr->s_new, ctx->contact.mu));
    PetscCall(VecNorm(s, NORM_INFINITY, &snorm));
    PetscCall(VecNorm(fr->s_new, NORM_INFINITY, &ds));
    /* relative to the thresholds, but not below mu times the nodal force of a 1e-3 strain: a
     * node losing contact drives its threshold to zero, and its relative change to infinity */
    snorm = PetscMax(PetscMax(snorm, ds), fr->s_floor);
    PetscCall(VecAXPY(s, -1.0, fr->s_new));
    PetscCall(VecNorm(s, NORM_INFINITY, &ds));
    ds /= PetscMax(snorm, PETSC_SMALL * PETSC_SMALL);
    PetscCall(VecCopy(fr->s_new, s));
    /* the ratio of successive changes, while they are above the noise of the solves, and the
     * mean rate since the first iteration, which is what Theorem 4.2's contraction governs */
    fr->contraction = (k && ds_prev > 1e3 * rtol) ? ds / ds_prev : 0;
    if (k == 0) ds_first = ds;
    if (k > 0 && ds > 1e3 * rtol && ds_first > 0) fr->contraction_max = PetscPowReal(ds / ds_first, 1.0 / k);
    PetscCall(SlipVelocity(ctx, fr->w, fr->sigma));
    PetscCall(MMContactCoulomb(ctx, fr->w, fr->react, fr->sigma, &coulomb, &nslip, &nstick));
    /* 3D, condensed: the stick/slip states and slip directions are part of the fixed point */
    PetscCall(MMContactUpdateFrictionStates(ctx, s, fr->sigma, &nswitch, &dchange));
    ds = PetscMax(ds, dchange);
    snes->iter = k + 1;
    PetscCall(SNESMonitor(snes, k, ds));
    if (fr->monitor) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    friction %2" PetscInt_FMT ": threshold change %.3e, Coulomb residual %.3e, contraction %.3f, slipping %" PetscInt_FMT ", sticking %" PetscInt_FMT "\n", k, (double)ds, (double)coulomb, (double)fr->contraction, nslip, nstick));
    if (ds <= rtol && !nswitch && coulomb <= fr->coulomb_tol) {
      snes->reason = SNES_CONVERGED_FNORM_RELATIVE;
      PetscFunctionReturn(0);
    }
    /* a map that keeps expanding does not contract: Theorem 4.2's condition fails at this dt */
    growing = (k > 1 && fr->contraction >= 1.0 && ds > 1e3 * rtol) ? growing + 1 : 0;
    if (growing >= 3) {
      snes->reason = SNES_DIVERGED_DTOL;
      PetscFunctionReturn(0);
    }
    ds_prev = ds;
  }
  snes->reason = SNES_DIVERGED_MAX_IT;
  PetscFunctionReturn(0);
}

PetscErrorCode MMFrictionSetUp(MMCtx *ctx)
{
  MMFriction *fr = &ctx->friction;

  PetscFunctionBeginUser;
  fr->coulomb_tol = ctx->opt.friction_coulomb_tol;
  fr->s_floor     = ctx->opt.mu_max * 1e-3 * ctx->opt.E * PetscPowReal(ctx->contact.h_c, ctx->op.dim - 1);
  fr->monitor     = ctx->opt.friction_monitor;
  if (ctx->opt.mu_max == 0 || !ctx->contact.enabled) PetscFunctionReturn(0);
  PetscCall(SNESCreate(PetscObjectComm((PetscObject)ctx->op.dm), &fr->snes));
  PetscCall(SNESSetOptionsPrefix(fr->snes, "friction_"));
  PetscCall(SNESSetType(fr->snes, SNESSHELL));
  PetscCall(SNESShellSetContext(fr->snes, ctx));
  PetscCall(SNESShellSetSolve(fr->snes, FrictionLoop));
  PetscCall(SNESSetTolerances(fr->snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 100, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(fr->snes));
  PetscCall(VecDuplicate(ctx->contact.gap, &fr->s));
  PetscCall(VecDuplicate(ctx->contact.gap, &fr->s_new));
  PetscCall(VecZeroEntries(fr->s_new));
  PetscCall(VecDuplicate(ctx->state.u, &fr->sigma));
  /* the first thresholds: mu times the initial normal reactions */
  {
    Vec rn;
    PetscCall(VecGetSubVector(ctx->state.react, ctx->contact.is_normal, &rn));
    PetscCall(VecAXPBY(fr->s, -1.0, 0.0, rn));
    PetscCall(VecPointwiseMult(fr->s, fr->s, ctx->contact.mu));
    PetscCall(VecRestoreSubVector(ctx->state.react, ctx->contact.is_normal, &rn));
    PetscCall(VecPointwiseMax(fr->s, fr->s, fr->s_new)); /* s_new is zero here: clip tension */
  }
  PetscFunctionReturn(0);
}

/* The step problem with friction; *ok is false when the loop did not converge (the caller retries
 * with a smaller dt). Without friction it is the contact solve itself. */
PetscErrorCode MMFrictionSolve(MMCtx *ctx, Vec b, Vec w, Vec react, PetscBool *ok)
{
  MMFriction         *fr = &ctx->friction;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  *ok      = PETSC_TRUE;
  fr->its  = 0;
  if (!fr->snes) {
    PetscCall(MMContactSolve(ctx, b, w, react));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(ctx->log.friction, 0, 0, 0, 0));
  fr->b     = b;
  fr->w     = w;
  fr->react = react;
  /* warm start: the thresholds of the last step */
  PetscCall(SNESSolve(fr->snes, NULL, fr->s));
  PetscCall(SNESGetConvergedReason(fr->snes, &reason));
  PetscCall(SNESGetIterationNumber(fr->snes, &fr->its));
  *ok = (PetscBool)(reason > 0);
  /* the loop updated only the contact dofs: one full-size solve completes the step (a rejected
   * step is solved again, so it needs none) */
  if (*ok) PetscCall(MMContactRecover(ctx, b, w, react));
  PetscCall(PetscLogEventEnd(ctx->log.friction, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMFrictionDestroy(MMFriction *fr)
{
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&fr->snes));
  PetscCall(VecDestroy(&fr->s));
  PetscCall(VecDestroy(&fr->s_new));
  PetscCall(VecDestroy(&fr->sigma));
  PetscFunctionReturn(0);
}
