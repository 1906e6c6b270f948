/* -friction_type fixedpoint: the paper's fixed point on the thresholds (the map Phi^n of the proof of
 * Theorem 4.2, docs/method.md section 6): freeze s = mu r_n, solve the Tresca problem with these
 * thresholds exactly, update s from its normal reactions, until s stops changing. It converges when
 * the map contracts (c_p dt / h_c' small enough for mu) and is the reference the Newton solver is
 * checked against.
 *
 * With the condensed formulation each Tresca problem is solved exactly on the disk (3D) or the
 * interval (2D) by the same semismooth Newton with fixed thresholds. With the active-set formulation
 * (no Delassus operator) the formulation's own Tresca solve is used. */
#include "../../frictionimpl.h"

/* The change of thresholds relative to their scale, but not below mu times the nodal force of a 1e-3
 * strain (s_floor): a node losing contact drives its threshold to zero, and its relative change to
 * infinity. */
static PetscReal ThresholdChange(PetscInt n, const PetscReal s[], const PetscReal s_new[], PetscReal s_floor)
{
  PetscReal ds = 0, scale = s_floor;
  for (PetscInt i = 0; i < n; ++i) {
    ds    = PetscMax(ds, PetscAbsReal(s_new[i] - s[i]));
    scale = PetscMax(scale, PetscMax(PetscAbsReal(s[i]), PetscAbsReal(s_new[i])));
  }
  return ds / PetscMax(scale, PETSC_SMALL * PETSC_SMALL);
}

static PetscErrorCode SolveSet_FixedPoint(MMFriction fr, const MMCoulombProblem *p, PetscScalar r[], MMCoulombResult *res)
{
  const PetscInt   nc = p->nc;
  MMCoulombProblem tp = *p;
  PetscReal       *s, *s_new, ds = 0, ds_first = 0;

  PetscFunctionBeginUser;
  res->its = res->inner_its = 0;
  res->contraction          = 0;
  res->converged            = PETSC_TRUE;
  if (!p->n) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(p->n, &s, p->n, &s_new));
  for (PetscInt i = 0; i < p->n; ++i) s[i] = p->mu[i] * PetscMax(PetscRealPart(r[i * nc]), 0.0);
  tp.s           = s;
  res->converged = PETSC_FALSE;
  for (PetscInt k = 0; k < fr->maxit; ++k) {
    MMCoulombResult tr;
    /* the Tresca problem exactly: far below the threshold tolerance, so its error does not stall the loop */
    PetscCall(MMCoulombNewton(&tp, &fr->work, PetscMin(1e-13, 1e-2 * fr->rtol), 100, r, &tr));
    res->inner_its += tr.its;
    res->residual = tr.residual;
    PetscCheck(tr.converged, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "The Tresca solve of the friction fixed point did not converge in 100 Newton steps (residual %g)", (double)tr.residual);
    for (PetscInt i = 0; i < p->n; ++i) s_new[i] = p->mu[i] * PetscMax(PetscRealPart(r[i * nc]), 0.0);
    ds = ThresholdChange(p->n, s, s_new, fr->s_floor);
    PetscCall(PetscArraycpy(s, s_new, p->n));
    res->its = k + 1;
    if (k == 0) ds_first = ds;
    /* the mean rate since the first iteration: what Theorem 4.2's contraction governs */
    if (k > 0 && ds > 1e3 * fr->rtol && ds_first > 0) res->contraction = PetscPowReal(ds / ds_first, 1.0 / k);
    if (fr->monitor) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "      fixed point %2" PetscInt_FMT ": threshold change %.3e, %" PetscInt_FMT " Newton steps\n", k, (double)ds, tr.its));
    if (ds <= fr->rtol) {
      res->converged = PETSC_TRUE;
      break;
    }
  }
  PetscCall(PetscFree2(s, s_new));
  PetscFunctionReturn(0);
}

/* The same fixed point through a formulation's own Tresca solves (the active-set formulation, which
 * builds no Delassus operator): the thresholds live on all contact nodes, in fr->s, warm-started
 * from the last step's. */
PetscErrorCode MMFrictionThresholdLoop(MMFriction fr, Vec b, Vec w, Vec react)
{
  MMContactNodes cn;
  PetscReal ds_prev = 0, ds_first = 0;
  PetscInt  growing = 0;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(fr->contact, &cn));
  PetscCall(SNESSetConvergedReason(fr->snes, SNES_CONVERGED_ITERATING));
  for (PetscInt k = 0; k < fr->maxit; ++k) {
    PetscReal ds, snorm, coulomb;
    PetscInt  nslip, nstick;

    PetscCall(MMContactSetFrictionThresholds(fr->contact, fr->s));
    PetscCall(MMContactSolveContactDofs(fr->contact, b, w, react));
    PetscCall(MMContactGetNormalReactions(fr->contact, fr->s_new));
    PetscCall(VecPointwiseMult(fr->s_new, fr->s_new, cn.mu));
    PetscCall(VecNorm(fr->s, NORM_INFINITY, &snorm));
    PetscCall(VecNorm(fr->s_new, NORM_INFINITY, &ds));
    snorm = PetscMax(PetscMax(snorm, ds), fr->s_floor);
    PetscCall(VecAXPY(fr->s, -1.0, fr->s_new));
    PetscCall(VecNorm(fr->s, NORM_INFINITY, &ds));
    ds /= PetscMax(snorm, PETSC_SMALL * PETSC_SMALL);
    PetscCall(VecCopy(fr->s_new, fr->s));
    fr->contraction = (k && ds_prev > 1e3 * fr->rtol) ? ds / ds_prev : 0;
    if (k == 0) ds_first = ds;
    if (k > 0 && ds > 1e3 * fr->rtol && ds_first > 0) fr->contraction_max = PetscPowReal(ds / ds_first, 1.0 / k);
    PetscCall(MMFrictionCoulombResidual(fr, &coulomb, &nslip, &nstick));
    fr->its     = k + 1;
    fr->coulomb = coulomb;
    PetscCall(SNESSetIterationNumber(fr->snes, k + 1));
    PetscCall(SNESMonitor(fr->snes, k, ds));
    if (fr->monitor) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    friction %2" PetscInt_FMT ": threshold change %.3e, Coulomb residual %.3e, contraction %.3f, slipping %" PetscInt_FMT ", sticking %" PetscInt_FMT "\n", k, (double)ds, (double)coulomb, (double)fr->contraction, nslip, nstick));
    if (ds <= fr->rtol && coulomb <= fr->coulomb_tol) {
      PetscCall(SNESSetConvergedReason(fr->snes, SNES_CONVERGED_FNORM_RELATIVE));
      PetscFunctionReturn(0);
    }
    /* a map that keeps expanding does not contract: Theorem 4.2's condition fails at this dt */
    growing = (k > 1 && fr->contraction >= 1.0 && ds > 1e3 * fr->rtol) ? growing + 1 : 0;
    if (growing >= 3) {
      PetscCall(SNESSetConvergedReason(fr->snes, SNES_DIVERGED_DTOL));
      PetscFunctionReturn(0);
    }
    ds_prev = ds;
  }
  PetscCall(SNESSetConvergedReason(fr->snes, SNES_DIVERGED_MAX_IT));
  PetscFunctionReturn(0);
}

/* no Coulomb solve on all dofs: without a Delassus operator it loops over the formulation's Tresca solves */
static const MMFrictionOps FixedPointOps = {
  .solveset        = SolveSet_FixedPoint,
  .solvethresholds = MMFrictionThresholdLoop,
  .default_rtol    = 1e-10,
  .rtol_meaning    = "relative change of the thresholds",
};

PetscErrorCode MMFrictionCreate_FixedPoint(MMFriction fr)
{
  PetscFunctionBeginUser;
  fr->ops = &FixedPointOps;
  PetscFunctionReturn(0);
}
