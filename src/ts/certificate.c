/* The step's certificate (docs/method.md section 3, "A step accepted by its certificate"): a step is
 * accepted when the residual r = b + f_c - K~ w of its equation does no work over the step and has
 * no resultant and no moment beyond the round-off of the sums that make them. Each is measured
 * against the round-off of its own terms, sum_i |du_i| (|b_i| + |f_c,i| + |(K~ w)_i|) and the like,
 * not against a fraction of the energy or of ||b||: a slender or stiff part makes such a fraction
 * smaller than the arithmetic can give, or a translated body larger than the physics allows.
 * The iterative solves beneath stay inexact on the way (-contact_tol starts them); when a step's
 * certificate fails, their tolerance is tightened by what the certificate asks and the step solved
 * again from where it stands. A residual that no longer falls has reached its round-off floor: the
 * step is accepted there (and counted), never cut for it. */
#include "newmarkimpl.h"

/* MM_CERT_ROUNDOFFS (newmarkimpl.h), how many round-offs of its terms a defect may be: the direct
 * solves of the condensed formulation give at most 0.16 of one over nine cases of the suite; an
 * inexact solve at -contact_tol 1e-11 gives 20 to 600 (docs/method.md section 3). */

/* The defects of a step's solution w with residual r and round-off scale per entry (all ranks). The
 * linear scheme's energy identity holds to 1/2 du.(r^n + r^{n+1}) (the trapezoidal rule on the step's
 * two residuals, a^n carrying the last one: r_old), so that both this step's defect and its
 * residual's own work, which the next step's defect will carry, are tested; the finite-strain step
 * carries none (r_old NULL). */
static PetscErrorCode Defects(MMNewmark nm, Vec w, Vec r, Vec r_old, Vec scale, MMStepCertificate *c)
{
  MMCertificateData *cd = &nm->cert;
  MMState           *s  = &nm->state;
  const PetscScalar *ra, *oa = NULL, *sa, *da, *wa;
  PetscReal          sums[4] = {0, 0, 0, 0}, F[3], T[3], umax = 0;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(w, &n));
  PetscCall(VecGetArrayRead(r, &ra));
  if (r_old) PetscCall(VecGetArrayRead(r_old, &oa));
  PetscCall(VecGetArrayRead(scale, &sa));
  PetscCall(MMNewmarkStepIncrement(nm, w, s->work));
  PetscCall(VecGetArrayRead(s->work, &da));
  PetscCall(VecGetArrayRead(w, &wa));
  for (PetscInt i = 0; i < n; ++i) {
    const PetscReal du = PetscRealPart(da[i]);
    sums[0] += du * PetscRealPart(ra[i]);
    if (oa) sums[1] += du * PetscRealPart(oa[i]);
    sums[2] += PetscAbsReal(du) * PetscRealPart(sa[i]);
    sums[3] += PetscRealPart(sa[i]);
    umax = PetscMax(umax, PetscAbsScalar(wa[i]));
  }
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(VecRestoreArrayRead(s->work, &da));
  PetscCall(VecRestoreArrayRead(scale, &sa));
  if (r_old) PetscCall(VecRestoreArrayRead(r_old, &oa));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 4, MPIU_REAL, MPIU_SUM, nm->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &umax, 1, MPIU_REAL, MPIU_MAX, nm->comm));
  PetscCall(MMMomentaOfForce(nm, w, r, F, T));
  c->energy     = PetscMax(PetscAbsReal(0.5 * (sums[0] + sums[1])), PetscAbsReal(sums[0]));
  c->energy_tol = MM_CERT_ROUNDOFFS * PETSC_MACHINE_EPSILON * sums[2];
  c->force      = PetscSqrtReal(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
  c->force_tol  = MM_CERT_ROUNDOFFS * PETSC_MACHINE_EPSILON * sums[3];
  c->torque     = PetscSqrtReal(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
  c->torque_tol = c->force_tol * (cd->radius + umax); /* moments about the origin, at X + u */
  c->ratio      = PetscMax(c->energy / PetscMax(c->energy_tol, PETSC_MIN_REAL), PetscMax(c->force / PetscMax(c->force_tol, PETSC_MIN_REAL), c->torque / PetscMax(c->torque_tol, PETSC_MIN_REAL)));
  PetscFunctionReturn(0);
}

/* The linear step's: its residual r = b + f_c - K~ w (contact's step residual); of the increment,
 * b - K~ u^n + f_c - K~ du, when the step solved for du (-step_increments, b is then b - K~ u^n) */
static PetscErrorCode Measure(MMNewmark nm, Vec b, Vec w, MMStepCertificate *c)
{
  MMCertificateData *cd = &nm->cert;

  PetscFunctionBeginUser;
  PetscCall(MMContactStepResidual(nm->contact, b, nm->state.has_du ? nm->state.du : w, nm->state.react, cd->r, cd->scale));
  PetscCall(Defects(nm, w, cd->r, cd->r_old, cd->scale, c));
  PetscFunctionReturn(0);
}

/* The finite-strain step's certificate at the iterate w: its whole residual, b_nl + H + f_c - K~ w
 * with H = c(w) the correction at w (nonlinear.c: the inner solve's residual and the correction's
 * change together), against the round-off of its terms, the cells' force magnitudes among them
 * (force_scale: a slender part's force is a small difference of large cell forces). bH: b_nl + H,
 * formed by the caller; of the increment du when the iteration solves for it (nonlinear.c). */
PetscErrorCode MMCertificateOfIterate(MMNewmark nm, Vec bH, Vec w, Vec force_scale, MMStepCertificate *c)
{
  MMCertificateData *cd = &nm->cert;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MM_TS_Certificate, 0, 0, 0, 0));
  PetscCall(MMContactStepResidual(nm->contact, bH, nm->state.has_du ? nm->state.du : w, nm->state.react, cd->r, cd->scale));
  PetscCall(VecAXPY(cd->scale, 1.0, force_scale)); /* the rounding of the cells' forces, which the net force hides */
  PetscCall(Defects(nm, w, cd->r, NULL, cd->scale, c));
  {
    PetscReal rn, sn;
    PetscCall(VecNorm(cd->r, NORM_2, &rn));
    PetscCall(VecNorm(cd->scale, NORM_2, &sn));
    c->size = rn / PetscMax(PETSC_MACHINE_EPSILON * sn, PETSC_MIN_REAL);
  }
  PetscCall(PetscLogEventEnd(MM_TS_Certificate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The finite-strain step's whole residual at the iterate w, b_nl + H + f_c - K~ w (of du when the
 * iteration solves for it): the outer iteration's change of the correction and the inner solve's own
 * residual together, what the audits will see (nonlinear.c). In the certificate's storage. */
PetscErrorCode MMCertificateResidualOfIterate(MMNewmark nm, Vec bH, Vec w, Vec *r)
{
  MMCertificateData *cd = &nm->cert;

  PetscFunctionBeginUser;
  PetscCall(MMContactStepResidual(nm->contact, bH, nm->state.has_du ? nm->state.du : w, nm->state.react, cd->r, cd->scale));
  *r = cd->r;
  PetscFunctionReturn(0);
}

/* The static start's certificate (static_finite.c): its residual r at w with the round-off scale
 * of its terms, the work over the load step from u_old */
PetscErrorCode MMCertificateOfResidual(MMNewmark nm, Vec r, Vec scale, Vec w, MMStepCertificate *c)
{
  PetscFunctionBeginUser;
  PetscCall(Defects(nm, w, r, NULL, scale, c));
  PetscFunctionReturn(0);
}

/* After a solved step: *again true asks for the step to be solved once more, from w, with the
 * tighter tolerance set here. tries: the solves of this step so far (1 after the first). */
PetscErrorCode MMCertificateCheck(MMNewmark nm, Vec b, Vec w, PetscInt tries, PetscBool *again)
{
  MMCertificateData *cd = &nm->cert;
  MMStepCertificate  c;
  PetscReal          tol, user;

  PetscFunctionBeginUser;
  *again = PETSC_FALSE;
  if (!cd->on) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MM_TS_Certificate, 0, 0, 0, 0));
  PetscCall(Measure(nm, b, w, &c));
  PetscCall(MMContactGetSolveTolerance(nm->contact, &tol, &user));
  PetscCall(PetscInfo(NULL, "step certificate (solve %" PetscInt_FMT ", -contact_tol now %.1e): work of the residual %.3e (round-off %.3e), resultant %.3e (%.3e), moment %.3e (%.3e): %.3g round-offs\n", tries, (double)tol, (double)c.energy, (double)c.energy_tol, (double)c.force, (double)c.force_tol, (double)c.torque, (double)c.torque_tol, (double)c.ratio));
  if (c.ratio <= 1) {
    /* met: the next step starts looser again, as long as it keeps meeting it */
    if (tries == 1 && c.ratio < 1e-2 && tol < user) PetscCall(MMContactSetSolveTolerance(nm->contact, PetscMin(user, 10 * tol)));
    cd->ratio_max = PetscMax(cd->ratio_max, c.ratio);
  } else if ((tries > 1 && c.ratio > 0.5 * cd->ratio_prev) || tries >= MM_CERT_MAX_SOLVES || tol <= 10 * PETSC_MACHINE_EPSILON) {
    /* the last tightening did not halve the defect (or none is left): the residual is at its floor, accepted there */
    MMCertificateAtFloor(cd, c.ratio);
  } else {
    /* the residual falls about as the tolerance: ask for what the certificate lacks, and 10 times more */
    PetscCall(MMContactSetSolveTolerance(nm->contact, PetscMax(10 * PETSC_MACHINE_EPSILON, tol / (10 * c.ratio))));
    cd->resolves++;
    *again = PETSC_TRUE;
  }
  cd->ratio_prev = c.ratio;
  if (!*again) PetscCall(VecCopy(cd->r, cd->r_old));
  PetscCall(PetscLogEventEnd(MM_TS_Certificate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCertificateSetUp(MMNewmark nm)
{
  MMCertificateData *cd = &nm->cert;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DMGetBoundingBox(nm->dm, lo, hi));
  cd->radius = 0;
  for (PetscInt d = 0; d < 3; ++d) cd->radius += PetscSqr(PetscMax(PetscAbsReal(lo[d]), PetscAbsReal(hi[d])));
  cd->radius = PetscSqrtReal(cd->radius);
  /* the finite-strain iteration measures its stalled iterates too (MMCertificateOfIterate) */
  PetscCall(VecDuplicate(nm->state.u, &cd->r));
  PetscCall(VecDuplicate(nm->state.u, &cd->scale));
  if (cd->on) PetscCall(VecDuplicate(nm->state.u, &cd->r_old));
  PetscFunctionReturn(0);
}

PetscErrorCode MMCertificateDestroy(MMCertificateData *cd)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&cd->r));
  PetscCall(VecDestroy(&cd->scale));
  PetscCall(VecDestroy(&cd->r_old));
  PetscFunctionReturn(0);
}

/*@
  MMCertificateView - Reports the steps' certificates: how many steps were solved again with a
  tighter tolerance, and how many were accepted at their residual's round-off floor

  Collective

  Input Parameters:
+ nm     - the stepper's context
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `MMNonlinearView()`, `TSView()`
@*/
PetscErrorCode MMCertificateView(MMNewmark nm, PetscViewer viewer)
{
  const MMCertificateData *cd = &nm->cert;
  PetscReal                tol, user;
  PetscBool                ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!(cd->on || cd->floor_steps) || !ascii) PetscFunctionReturn(0);
  if (!cd->on) { /* the finite-strain steps, whose iteration accepts a floor by its certificate */
    PetscCall(PetscViewerASCIIPrintf(viewer, "  step certificate: %" PetscInt_FMT " finite-strain steps accepted at their residual's round-off floor (largest %.3g round-offs of its terms)\n", cd->floor_steps, (double)cd->floor_max));
    PetscFunctionReturn(0);
  }
  PetscCall(MMContactGetSolveTolerance(nm->contact, &tol, &user));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  step certificate: every step's residual within %g round-offs of its terms (largest %.2g); %" PetscInt_FMT " solves again with a tighter -contact_tol (%.1e at the end, %.1e given); %" PetscInt_FMT " steps accepted at their residual's floor\n", (double)MM_CERT_ROUNDOFFS,
                                   (double)cd->ratio_max, cd->resolves, (double)tol, (double)user, cd->floor_steps));
  if (cd->floor_steps) PetscCall(PetscViewerASCIIPrintf(viewer, "    (largest: %.3g round-offs: the iterative solve's residual stops falling there; -contact_formulation condensed solves exactly)\n", (double)cd->floor_max));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetCertificateResidual - Gives the last accepted step's residual, which the next step's
  certificate sums with its own, for a checkpoint to keep and a restart to put back

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameter:
. r - the residual (w-frame, owned by the context), or NULL when the steps are not certified

  Level: developer

.seealso: `MMCertificateView()`, `MMContactSetSolveTolerance()`
@*/
PetscErrorCode MMNewmarkGetCertificateResidual(MMNewmark nm, Vec *r)
{
  PetscFunctionBeginUser;
  *r = nm->cert.on ? nm->cert.r_old : NULL;
  PetscFunctionReturn(0);
}
