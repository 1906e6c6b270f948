/* Rayleigh damping C = alpha M* + beta B in the trapezoidal scheme (docs/method.md sections 3, 4).
 *
 * The step equation gains C (2/dt u^n + vC^n) on its right-hand side and K~ becomes
 * K + 2 beta/dt B + (4/dt^2 + 2 alpha/dt) M*: MMDampingGetStepMatrix gives its coefficients to contact,
 * which builds it (MMContactSetStepMatrix).
 * vC is the trapezoidal velocity on all dofs, kept apart from the state's v. B is K, except with
 * the modified mass: there the massless contact-normal dofs are condensed out of each cell's
 * stiffness, so that C has no row or column on them (docs/method.md, "Rayleigh damping of the
 * massless dofs": on those dofs the trapezoidal vC carries an undamped (-1)^n mode, which C K-coupled
 * turned into a contact force alternating at rest, issue 38). With alpha = beta = 0 none of this
 * runs, so an undamped run is bitwise what it was. */
#include "newmarkimpl.h"
#include "fem.h"
#include "sys.h"

/* The options as given: nothing contradictory, nothing negative, frequencies where a ratio needs
 * them. Checked as soon as they are read, before the mesh is. */
static PetscErrorCode CheckOptions(MPI_Comm comm, const MMDamping *o)
{
  PetscFunctionBeginUser;
  PetscCheck(o->mass >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_mass %.6g must be >= 0: alpha (1/s) of the Rayleigh damping C = alpha M* + beta K; a negative value feeds energy in", (double)o->mass);
  PetscCheck(o->stiffness >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_stiffness %.6g must be >= 0: beta (s) of the Rayleigh damping C = alpha M* + beta K; a negative value feeds energy in", (double)o->stiffness);
  if (o->ratio_set) {
    PetscCheck(!o->mass_set && !o->stiffness_set, comm, PETSC_ERR_USER_INPUT, "-damping_ratio was given together with -damping_mass or -damping_stiffness: the ratio sets both alpha and beta. Give either -damping_ratio with -damping_frequencies, or -damping_mass and/or -damping_stiffness");
    PetscCheck(o->ratio >= 0, comm, PETSC_ERR_USER_INPUT, "-damping_ratio %.6g must be >= 0 (0.02 is 2%% of critical damping)", (double)o->ratio);
    PetscCheck(o->nfreq == 2, comm, PETSC_ERR_USER_INPUT, "-damping_ratio needs the two frequencies (Hz) at which it holds: give -damping_frequencies f1,f2 (%s)", o->nfreq < 0 ? "it is missing" : "it needs exactly 2 entries");
    PetscCheck(o->freq[0] > 0 && o->freq[1] > 0, comm, PETSC_ERR_USER_INPUT, "-damping_frequencies %.6g,%.6g: both frequencies must be > 0 (Hz)", (double)o->freq[0], (double)o->freq[1]);
  } else PetscCheck(o->nfreq < 0, comm, PETSC_ERR_USER_INPUT, "-damping_frequencies is only read with -damping_ratio: give -damping_ratio zeta too, or leave the frequencies out");
  PetscFunctionReturn(0);
}

/* alpha and beta: as given, or from the ratio zeta at w1, w2 (w = 2 pi f), where
 * zeta(w) = alpha/(2 w) + beta w/2 equals zeta: alpha = 2 zeta w1 w2/(w1 + w2), beta = 2 zeta/(w1 + w2). */
static void Coefficients(MMDamping *o)
{
  if (o->ratio_set) {
    const PetscReal w1 = 2 * PETSC_PI * o->freq[0], w2 = 2 * PETSC_PI * o->freq[1];
    o->alpha = 2 * o->ratio * w1 * w2 / (w1 + w2);
    o->beta  = 2 * o->ratio / (w1 + w2);
  } else {
    o->alpha = o->mass;
    o->beta  = o->stiffness;
  }
}

/* A real option and whether it was given: -damping_ratio excludes the other two. */
static PetscErrorCode OptionsRealSet(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscReal *v, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, name, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(name, help, NULL, *v, v, set));
  PetscCall(MMOptionsCheckFinite(comm, name, v, 1));
  PetscFunctionReturn(0);
}

/* Rayleigh damping C = alpha M* + beta K: alpha and beta, or a ratio at two frequencies; checked
 * together, and a ratio turned into alpha and beta. */
PetscErrorCode MMDampingSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMDamping *d)
{
  PetscFunctionBeginUser;
  d->mass = d->stiffness = d->ratio = 0;
  d->freq[0] = d->freq[1] = 0;
  PetscCall(OptionsRealSet(PetscOptionsObject, comm, "-damping_mass", "Rayleigh damping C = alpha M* + beta K: alpha (1/s), >= 0 (default 0: no damping)", &d->mass, &d->mass_set));
  PetscCall(OptionsRealSet(PetscOptionsObject, comm, "-damping_stiffness", "Rayleigh damping C = alpha M* + beta K: beta (s), >= 0 (default 0: no damping)", &d->stiffness, &d->stiffness_set));
  PetscCall(OptionsRealSet(PetscOptionsObject, comm, "-damping_ratio", "Rayleigh damping by its ratio to critical, >= 0, reached at the two -damping_frequencies: sets alpha = 2 zeta w1 w2/(w1 + w2) and beta = 2 zeta/(w1 + w2), w = 2 pi f (not with -damping_mass or -damping_stiffness)", &d->ratio, &d->ratio_set));
  PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, "-damping_frequencies", "The two frequencies f1,f2 (Hz, > 0) at which -damping_ratio holds; between them the damping ratio is lower, outside higher", 2, d->freq, &d->nfreq));
  PetscCall(CheckOptions(comm, d));
  Coefficients(d);
  PetscFunctionReturn(0);
}

/*@
  MMDampingOn - Tells whether Rayleigh damping is on (alpha or beta nonzero)

  Not collective

  Input Parameter:
. d - the damping

  Level: intermediate

.seealso: `MMNewmarkGetDamping()`, `MMDampingGetStepMatrix()`
@*/
PetscBool MMDampingOn(const MMDamping *d)
{
  return (PetscBool)(d->alpha != 0 || d->beta != 0);
}

/* After the initial velocity v0 is set: vC^0 = v^0 on all dofs, and B. The finite-strain step damps
 * with the viscous stress of its own step (docs/method.md section 13), a function of u^{n+1} - u^n and
 * not of vC, so the massless dofs carry no undamped mode there: B is K, in its iteration matrix only. */
PetscErrorCode MMDampingSetUp(MMDamping *d, MMContact ct, MMMaterial *material, IS is_massless, Vec v0)
{
  MMContactOperators ops;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(ct, &ops));
  d->Mstar = ops.Mstar;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(v0, &d->vC));
  PetscCall(VecDuplicate(v0, &d->work));
  PetscCall(VecDuplicate(v0, &d->x));
  PetscCall(VecCopy(v0, d->vC));
  /* B with the massless dofs condensed cell by cell, in the w-frame (contact's, docs/method.md section 12) */
  if (d->beta != 0 && ops.massless && !material->finite) PetscCall(MMContactDampingStiffness(ct, material, is_massless, &d->B));
  else {
    PetscCall(PetscObjectReference((PetscObject)ops.K));
    d->B = ops.K;
  }
  PetscFunctionReturn(0);
}

/*@
  MMDampingDestroy - Frees what the damping holds

  Collective

  Input Parameter:
. d - the damping

  Level: developer

.seealso: `MMNewmarkDestroy()`
@*/
PetscErrorCode MMDampingDestroy(MMDamping *d)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&d->vC));
  PetscCall(VecDestroy(&d->work));
  PetscCall(VecDestroy(&d->x));
  PetscCall(MatDestroy(&d->B));
  PetscFunctionReturn(0);
}

/*@
  MMDampingGetStepMatrix - Computes the coefficients of K~ = ck K + cb B + cm M* for dt under
  Rayleigh damping

  Not collective

  Input Parameters:
+ d  - the damping
. K  - the stiffness (unused: B is set up already)
- dt - the time step

  Output Parameter:
. sm - the coefficients and B (NULL undamped)

  Note:
  The coefficients of K~ = ck K + cb B + cm M* for dt (docs/method.md section 3), for the contact
  component that builds it: ck = 1, cb = 2 beta/dt with B (NULL undamped), cm = 4/dt^2 + 2 alpha/dt.
  B is K itself, or K with the massless dofs condensed out: with B == K contact scales K by ck + cb.

  Level: developer

.seealso: `MMNewmarkGetStepMatrix()`, `MMDampingOn()`
@*/
PetscErrorCode MMDampingGetStepMatrix(MMDamping *d, Mat K, PetscReal dt, MMStepMatrix *sm)
{
  PetscFunctionBeginUser;
  (void)K; /* B is already K or its condensed form (MMDampingSetUp) */
  PetscCall(PetscMemzero(sm, sizeof(*sm)));
  sm->dt = dt;
  sm->ck = 1.0;
  sm->cm = 4.0 / (dt * dt);
  if (d->alpha != 0) sm->cm += 2.0 * d->alpha / dt;
  sm->cb = d->beta != 0 ? 2.0 * d->beta / dt : 0;
  sm->B  = d->beta != 0 ? d->B : NULL;
  PetscFunctionReturn(0);
}

/*@
  MMDampingAddForce - Adds a C v, the damping force of a velocity, to a vector

  Collective

  Input Parameters:
+ d - the damping
. v - the velocity
- a - the factor

  Output Parameter:
. r - the vector added to

  Note:
  r += a C v: the damping force of a velocity in an equation of motion (the initial one).

  Level: developer

.seealso: `MMDampingOn()`
@*/
PetscErrorCode MMDampingAddForce(MMDamping *d, Vec v, PetscReal a, Vec r)
{
  PetscFunctionBeginUser;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(MatMult(d->Mstar, v, d->work));
  PetscCall(VecAXPY(r, a * d->alpha, d->work));
  PetscCall(MatMult(d->B, v, d->work));
  PetscCall(VecAXPY(r, a * d->beta, d->work));
  PetscFunctionReturn(0);
}

/* b += C (2/dt u^n + vC^n): the damping's part of the step's right-hand side. */
PetscErrorCode MMDampingAddStepRHS(MMDamping *d, Vec u, PetscReal dt, Vec b)
{
  PetscFunctionBeginUser;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(d->x, 2.0 / dt, u, d->vC));
  PetscCall(MatMult(d->Mstar, d->x, d->work));
  PetscCall(VecAXPY(b, d->alpha, d->work));
  PetscCall(MatMult(d->B, d->x, d->work));
  PetscCall(VecAXPY(b, d->beta, d->work));
  PetscFunctionReturn(0);
}

/* vC^{n+1} = 2/dt du - vC^n, du = u^{n+1} - u^n, once the step is accepted. */
PetscErrorCode MMDampingUpdateVelocity(MMDamping *d, Vec du, PetscReal dt)
{
  PetscFunctionBeginUser;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(VecAXPBY(d->vC, 2.0 / dt, -1.0, du));
  PetscFunctionReturn(0);
}

/* b += C vC^n: the damping's share of the increment's right-hand side (step_laws.c), b - K~ u^n with
 * the 2/dt C u^n of b and of K~ u^n cancelled */
PetscErrorCode MMDampingAddStepRHSIncrement(MMDamping *d, Vec b)
{
  PetscFunctionBeginUser;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(MatMult(d->Mstar, d->vC, d->work));
  PetscCall(VecAXPY(b, d->alpha, d->work));
  PetscCall(MatMult(d->B, d->vC, d->work));
  PetscCall(VecAXPY(b, d->beta, d->work));
  PetscFunctionReturn(0);
}

/* W_d = -(1/dt) du.C du <= 0, the work of the damping force over the step (docs/method.md
 * section 4): the trapezoidal mean of C vC over the step is C du/dt. */
PetscErrorCode MMDampingWork(MMDamping *d, Vec du, PetscReal dt, PetscReal *w)
{
  PetscScalar duMdu, duKdu;

  PetscFunctionBeginUser;
  *w = 0;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  PetscCall(MatMult(d->Mstar, du, d->work));
  PetscCall(VecDot(du, d->work, &duMdu));
  PetscCall(MatMult(d->B, du, d->work));
  PetscCall(VecDot(du, d->work, &duKdu));
  *w = -(d->alpha * PetscRealPart(duMdu) + d->beta * PetscRealPart(duKdu)) / dt;
  PetscFunctionReturn(0);
}
