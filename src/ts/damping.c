/* Rayleigh damping C = alpha M* + beta B in the trapezoidal scheme (docs/method.md sections 3, 4).
 *
 * The step equation gains C (2/dt u^n + vC^n) on its right-hand side and K~ becomes
 * K + 2 beta/dt B + (4/dt^2 + 2 alpha/dt) M* (MMDampingGetStepMatrix gives its coefficients to contact, which builds K~).
 * vC is the trapezoidal velocity on all dofs, kept apart from the state's v. B is K, except with
 * the modified mass: there the massless contact-normal dofs are condensed out of each cell's
 * stiffness, so that C has no row or column on them (docs/method.md, "Rayleigh damping of the
 * massless dofs": on those dofs the trapezoidal vC carries an undamped (-1)^n mode, which C K-coupled
 * turned into a contact force alternating at rest, issue 38). With alpha = beta = 0 none of this
 * runs, so an undamped run is bitwise what it was. */
#include "damping.h"
#include "fem.h"
#include "contact.h"

/* The options as given: nothing contradictory, nothing negative, frequencies where a ratio needs
 * them. Called with the other range checks, before the mesh is read. */
PetscErrorCode MMDampingCheckOptions(MPI_Comm comm, const MMOptions *o)
{
  PetscFunctionBeginUser;
  PetscCheck(o->damping_mass >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_mass %.6g must be >= 0: alpha (1/s) of the Rayleigh damping C = alpha M* + beta K; a negative value feeds energy in", (double)o->damping_mass);
  PetscCheck(o->damping_stiffness >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_stiffness %.6g must be >= 0: beta (s) of the Rayleigh damping C = alpha M* + beta K; a negative value feeds energy in", (double)o->damping_stiffness);
  if (o->damping_ratio_set) {
    PetscCheck(!o->damping_mass_set && !o->damping_stiffness_set, comm, PETSC_ERR_USER_INPUT, "-damping_ratio was given together with -damping_mass or -damping_stiffness: the ratio sets both alpha and beta. Give either -damping_ratio with -damping_frequencies, or -damping_mass and/or -damping_stiffness");
    PetscCheck(o->damping_ratio >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_ratio %.6g must be >= 0 (0.02 is 2%% of critical damping)", (double)o->damping_ratio);
    PetscCheck(o->damping_nfreq == 2, comm, PETSC_ERR_USER_INPUT, "-damping_ratio needs the two frequencies (Hz) at which it holds: give -damping_frequencies f1,f2 (%s)", o->damping_nfreq < 0 ? "it is missing" : "it needs exactly 2 entries");
    PetscCheck(o->damping_freq[0] > 0 && o->damping_freq[1] > 0, comm, PETSC_ERR_USER_INPUT, "-damping_frequencies %.6g,%.6g: both frequencies must be > 0 (Hz)", (double)o->damping_freq[0], (double)o->damping_freq[1]);
  } else PetscCheck(o->damping_nfreq < 0, comm, PETSC_ERR_USER_INPUT, "-damping_frequencies is only read with -damping_ratio: give -damping_ratio zeta too, or leave the frequencies out");
  PetscFunctionReturn(0);
}

/* alpha and beta: as given, or from the ratio zeta at w1, w2 (w = 2 pi f), where
 * zeta(w) = alpha/(2 w) + beta w/2 equals zeta: alpha = 2 zeta w1 w2/(w1 + w2), beta = 2 zeta/(w1 + w2). */
PetscErrorCode MMDampingCoefficients(const MMOptions *o, PetscReal *alpha, PetscReal *beta)
{
  PetscFunctionBeginUser;
  if (o->damping_ratio_set) {
    const PetscReal w1 = 2 * PETSC_PI * o->damping_freq[0], w2 = 2 * PETSC_PI * o->damping_freq[1];
    *alpha = 2 * o->damping_ratio * w1 * w2 / (w1 + w2);
    *beta  = 2 * o->damping_ratio / (w1 + w2);
  } else {
    *alpha = o->damping_mass;
    *beta  = o->damping_stiffness;
  }
  PetscFunctionReturn(0);
}

PetscBool MMDampingOn(const MMCtx *ctx)
{
  return (PetscBool)(ctx->damping.alpha != 0 || ctx->damping.beta != 0);
}

/* B with the massless dofs (the contact normals and the friction corners' tau_1, docs/method.md
 * section 12) condensed cell by cell (MMAssembleP1DampingStiffness), in the w-frame of
 * K: the cells are rotated by Q there, and contact pairs transform it by N as K (N^T B N keeps the
 * slave-normal rows and columns zero: N's columns of those dofs are unit vectors). Its massless
 * rows and columns are then set to zero exactly, against the condensation's round-off. */
static PetscErrorCode CondensedDampingStiffness(MMCtx *ctx, Mat *B)
{
  MMContactNodes cn;
  Vec mark;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  PetscCall(MMFECreateMatrix(&ctx->op, ctx->op.dm, B));
  PetscCall(DMCreateGlobalVector(ctx->op.dm, &mark));
  PetscCall(VecZeroEntries(mark));
  PetscCall(VecISSet(mark, cn.is_massless, 1.0));
  PetscCall(MMAssembleP1DampingStiffness(ctx->op.dm, &ctx->material, ctx->op.Q, mark, *B));
  PetscCall(VecDestroy(&mark));
  if (ctx->op.N) {
    Mat BN;
    PetscCall(MatPtAP(*B, ctx->op.N, MAT_INITIAL_MATRIX, 2.0, &BN));
    PetscCall(MatDestroy(B));
    *B = BN;
  }
  PetscCall(MatZeroRowsColumnsIS(*B, cn.is_massless, 0.0, NULL, NULL));
  PetscFunctionReturn(0);
}

/* After the initial velocity is set: vC^0 = v^0 on all dofs, and B. */
PetscErrorCode MMDampingSetUp(MMCtx *ctx)
{
  MMDamping *d = &ctx->damping;

  PetscFunctionBeginUser;
  PetscCall(MMDampingCoefficients(&ctx->opt, &d->alpha, &d->beta));
  if (!MMDampingOn(ctx)) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ctx->state.v, &d->vC));
  PetscCall(VecDuplicate(ctx->state.v, &d->work));
  PetscCall(VecDuplicate(ctx->state.v, &d->x));
  PetscCall(VecCopy(ctx->state.v, d->vC));
  if (d->beta != 0 && MMFEHasMasslessDofs(&ctx->op)) PetscCall(CondensedDampingStiffness(ctx, &d->B));
  else {
    PetscCall(PetscObjectReference((PetscObject)ctx->op.K));
    d->B = ctx->op.K;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMDampingDestroy(MMDamping *d)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&d->vC));
  PetscCall(VecDestroy(&d->work));
  PetscCall(VecDestroy(&d->x));
  PetscCall(MatDestroy(&d->B));
  PetscFunctionReturn(0);
}

/* The coefficients of K~ = ck K + cb B + cm M* for dt (docs/method.md section 3), for the contact
 * component that builds it: ck = 1, cb = 2 beta/dt with B (NULL undamped), cm = 4/dt^2 + 2 alpha/dt. */
PetscErrorCode MMDampingGetStepMatrix(MMDamping *d, Mat K, PetscReal dt, MMStepMatrix *sm)
{
  PetscFunctionBeginUser;
  (void)K; /* B is K itself, or K with the massless dofs condensed out */
  sm->dt = dt;
  sm->ck = 1.0;
  sm->cm = 4.0 / (dt * dt);
  if (d->alpha != 0) sm->cm += 2.0 * d->alpha / dt;
  sm->cb = d->beta != 0 ? 2.0 * d->beta / dt : 0;
  sm->B  = d->beta != 0 ? d->B : NULL;
  PetscFunctionReturn(0);
}

/* r += a C v: the damping force of a velocity in an equation of motion (the initial one). */
PetscErrorCode MMDampingAddForce(MMCtx *ctx, Vec v, PetscReal a, Vec r)
{
  MMDamping *d = &ctx->damping;

  PetscFunctionBeginUser;
  if (!MMDampingOn(ctx)) PetscFunctionReturn(0);
  PetscCall(MatMult(ctx->op.Mstar, v, d->work));
  PetscCall(VecAXPY(r, a * d->alpha, d->work));
  PetscCall(MatMult(d->B, v, d->work));
  PetscCall(VecAXPY(r, a * d->beta, d->work));
  PetscFunctionReturn(0);
}

/* b += C (2/dt u^n + vC^n): the damping's part of the step's right-hand side. */
PetscErrorCode MMDampingAddStepRHS(MMCtx *ctx, PetscReal dt, Vec b)
{
  MMDamping *d = &ctx->damping;

  PetscFunctionBeginUser;
  if (!MMDampingOn(ctx)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(d->x, 2.0 / dt, ctx->state.u, d->vC));
  PetscCall(MatMult(ctx->op.Mstar, d->x, d->work));
  PetscCall(VecAXPY(b, d->alpha, d->work));
  PetscCall(MatMult(d->B, d->x, d->work));
  PetscCall(VecAXPY(b, d->beta, d->work));
  PetscFunctionReturn(0);
}

/* vC^{n+1} = 2/dt (u^{n+1} - u^n) - vC^n, once the step is accepted. */
PetscErrorCode MMDampingUpdateVelocity(MMCtx *ctx, PetscReal dt)
{
  MMDamping *d = &ctx->damping;
  MMState   *s = &ctx->state;

  PetscFunctionBeginUser;
  if (!MMDampingOn(ctx)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(d->work, -1.0, s->u_old, s->u));
  PetscCall(VecAXPBY(d->vC, 2.0 / dt, -1.0, d->work));
  PetscFunctionReturn(0);
}

/* W_d = -(1/dt) du.C du <= 0, the work of the damping force over the step (docs/method.md
 * section 4): the trapezoidal mean of C vC over the step is C du/dt. */
PetscErrorCode MMDampingWork(MMCtx *ctx, Vec du, PetscReal dt, PetscReal *w)
{
  MMDamping  *d = &ctx->damping;
  PetscScalar duMdu, duKdu;

  PetscFunctionBeginUser;
  *w = 0;
  if (!MMDampingOn(ctx)) PetscFunctionReturn(0);
  PetscCall(MatMult(ctx->op.Mstar, du, d->work));
  PetscCall(VecDot(du, d->work, &duMdu));
  PetscCall(MatMult(d->B, du, d->work));
  PetscCall(VecDot(du, d->work, &duKdu));
  *w = -(d->alpha * PetscRealPart(duMdu) + d->beta * PetscRealPart(duKdu)) / dt;
  PetscFunctionReturn(0);
}
