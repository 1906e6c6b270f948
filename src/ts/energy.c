/* The energy audit of every step (docs/method.md section 4) and rigid-body diagnostics. */
#include "newmarkimpl.h"
#include "fem.h"
#include "obstacle.h"
#include "friction.h"

static PetscErrorCode KineticEnergy(MMNewmark nm, Vec v, PetscReal *ek)
{
  MMContactOperators ops;
  PetscScalar        vMv;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, v, nm->state.work));
  PetscCall(VecDot(v, nm->state.work, &vMv));
  *ek = 0.5 * PetscRealPart(vMv);
  if (nm->loads->moving) {
    PetscReal ekD;
    PetscCall(MMLoadsDirichletKinetic(nm->loads, v, &ekD)); /* the moving boundary's nodes (docs/method.md section 10) */
    *ek += ekD;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TotalEnergy(MMNewmark nm, MMHistory *h)
{
  PetscFunctionBeginUser;
  PetscCall(KineticEnergy(nm, nm->state.v, &h->kinetic));
  if (nm->material->finite) PetscCall(MMNonlinearElasticEnergy(nm, nm->state.u, h->time, &h->elastic));
  else PetscCall(MMContactElasticEnergy(nm->contact, nm->state.u, &h->elastic));
  h->total = h->kinetic + h->elastic;
  PetscFunctionReturn(0);
}

/* 1/2 (f^n + f^{n+1}).du over the dofs of is: the trapezoidal work of a nodal force. */
static PetscErrorCode TrapezoidalWork(MMNewmark nm, IS is, Vec du, PetscReal *work)
{
  MMState    *s = &nm->state;
  Vec         f, fo, d;
  PetscScalar w1, w0;

  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(s->react, is, &f));
  PetscCall(VecGetSubVector(s->react_old, is, &fo));
  PetscCall(VecGetSubVector(du, is, &d));
  PetscCall(VecDot(f, d, &w1));
  PetscCall(VecDot(fo, d, &w0));
  PetscCall(VecRestoreSubVector(du, is, &d));
  PetscCall(VecRestoreSubVector(s->react_old, is, &fo));
  PetscCall(VecRestoreSubVector(s->react, is, &f));
  *work = 0.5 * PetscRealPart(w1 + w0);
  PetscFunctionReturn(0);
}

/* The work of the moving obstacles over the step from t0 to t1: at each contact node, the
 * trapezoidal contact force (frame components, normal and tangential) times the obstacle's
 * displacement in the node's frame (docs/method.md section 8). The contact and friction works on
 * the body split into this and the method's own remainder; wn and wt are the normal and
 * tangential parts. Zero when nothing moves. */
static PetscErrorCode ObstacleWork(MMNewmark nm, PetscReal t0, PetscReal t1, PetscReal *wn, PetscReal *wt)
{
  MMContactNodes     nodes, *ct = &nodes;
  const PetscInt     dim = nm->dim;
  const PetscInt    *in;
  const PetscScalar *f1, *f0;
  PetscInt           rstart;
  PetscReal          w[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &nodes));
  *wn = *wt = 0;
  if (!ct->enabled || !ct->moving) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(nm->state.react, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(nm->state.react, &f1));
  PetscCall(VecGetArrayRead(nm->state.react_old, &f0));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const MMObstacle *ob = &nm->pb.obstacles[ct->obstacle[k]];
    const PetscReal  *F  = &ct->node_frame[9 * k];
    PetscReal         c0[MM_MAX_DIM] = {0, 0, 0}, c1[MM_MAX_DIM] = {0, 0, 0};
    MMObstacleDisplacement(ob, dim, t0, c0);
    MMObstacleDisplacement(ob, dim, t1, c1);
    for (PetscInt j = 0; j < ct->ncomp; ++j) { /* frictionless: the tangential reactions are zero */
      const PetscInt i  = in[k] - rstart + j;
      PetscReal      dc = 0;
      for (PetscInt d = 0; d < dim; ++d) dc += (c1[d] - c0[d]) * F[3 * j + d];
      w[j ? 1 : 0] += 0.5 * PetscRealPart(f1[i] + f0[i]) * dc;
    }
  }
  PetscCall(VecRestoreArrayRead(nm->state.react_old, &f0));
  PetscCall(VecRestoreArrayRead(nm->state.react, &f1));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, w, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)nm->dm)));
  *wn = w[0];
  *wt = w[1];
  PetscFunctionReturn(0);
}

/* W_c of a candidate step w (not yet accepted: u still holds u^n), for the contact-work guard; the
 * stepper keeps the accepted step's value in state.work_contact for the energy audit. It excludes
 * the moving obstacles' normal work, which is not the method's doing. */
PetscErrorCode MMEnergyContactWork(MMNewmark nm, Vec w, PetscReal *w_c)
{
  MMState       *s = &nm->state;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  *w_c = 0;
  if (!cn.enabled) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(s->work, -1.0, s->u, w));
  PetscCall(TrapezoidalWork(nm, cn.is_normal, s->work, w_c));
  {
    PetscReal wn, wt, dwc, dwn, dwt;
    PetscCall(ObstacleWork(nm, nm->hist.time, nm->hist.time + cn.dt, &wn, &wt));
    /* a friction corner's two obstacles, each its own normal (docs/method.md section 12) */
    PetscCall(MMContactCornersWork(nm->contact, nm->hist.time, nm->hist.time + cn.dt, s->work, &dwc, &dwn, &dwt));
    *w_c += dwc - (wn + dwn);
  }
  PetscFunctionReturn(0);
}

/* The contact's part of the history row, and its audit after a step. */
static PetscErrorCode ContactDiagnostics(MMNewmark nm, Vec u, Vec react, Vec v, PetscBool audit, MMHistory *h)
{
  MMContactStats st;

  PetscFunctionBeginUser;
  PetscCall(MMContactDiagnostics(nm->contact, nm->hist.time, u, react, v, &st));
  h->active           = st.active;
  h->switched         = st.switched;
  h->slipping         = st.slipping;
  h->force_normal     = st.force_normal;
  h->force_tangential = st.force_tangential;
  h->max_penetration  = st.max_penetration;
  h->coulomb_residual = st.coulomb_residual;
  h->vi_its           = st.vi_its;
  h->candidates       = st.candidates;
  h->resolves         = st.resolves;
  if (audit) PetscCall(MMContactAudit(nm->contact, h->step, h->time, &st));
  PetscFunctionReturn(0);
}

/* A NaN or inf anywhere in the state shows in its energies and works: stop before it is recorded. */
static PetscErrorCode CheckFinite(MMNewmark nm, const MMHistory *h, PetscReal w_ext, PetscReal w_c, PetscReal w_f)
{
  const char *name[] = {"kinetic energy", "elastic energy", "external work", "contact work", "friction work"};
  PetscReal   val[]  = {h->kinetic, h->elastic, w_ext, w_c, w_f};

  PetscFunctionBeginUser;
  for (size_t i = 0; i < sizeof(val) / sizeof(val[0]); ++i)
    PetscCheck(!PetscIsInfOrNanReal(val[i]), PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_FP,
               "The %s is %s at step %" PetscInt_FMT " (t = %g): the state overflowed or a solve failed. Check the units of the material (-E %g, -rho %g), the loads and the initial velocity. The output up to the previous step is intact",
               name[i], PetscIsNanReal(val[i]) ? "NaN" : "infinite", h->step, (double)h->time, (double)nm->pb.E, (double)nm->pb.rho);
  PetscFunctionReturn(0);
}

/*@
  MMEnergyInitial - Fills the history's first row from the initial state: its energy (checked
  finite), the contact diagnostics, the momenta and the reactions

  Collective

  Input Parameters:
+ nm        - the stepper's context, with its initial state
- restarted - the state comes from a checkpoint

  Level: intermediate

.seealso: `MMNewmarkInitialState()`, `MMCheckpointRestoreHistory()`
@*/
PetscErrorCode MMEnergyInitial(MMNewmark nm, PetscBool restarted)
{
  MMHistory     *h = &nm->hist;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  h->step = 0;
  h->time = 0;
  h->work_ext = h->work_contact = h->work_friction = h->work_obstacle = 0;
  h->work_damping = 0;
  h->work_dirichlet = 0;
  h->work_frame = 0;
  h->balance_residual = h->max_balance = h->max_penetration_run = 0;
  h->cfl = cn.enabled ? nm->material->c_p_max * h->dt / cn.h_c : 0;
  /* the quadrature inserts the Dirichlet data of t = 0: a restarted run's moving boundary is elsewhere */
  if (!(nm->loads->moving && restarted) && !nm->material->finite) PetscCall(MMContactCheckElasticEnergy(nm->contact, nm->material, nm->state.u));
  PetscCall(TotalEnergy(nm, h));
  PetscCall(CheckFinite(nm, h, 0, 0, 0));
  h->energy_scale = PetscAbsReal(h->total);
  PetscCall(ContactDiagnostics(nm, nm->state.u, nm->state.react, nm->state.v, PETSC_FALSE, h));
  h->switched = 0;
  h->vi_its   = 0;
  h->max_penetration_run = h->max_penetration;
  PetscCall(MMRigidBodyDiagnostics(nm, h));
  PetscCall(MMLoadsReactions(nm->loads, nm->state.u, nm->state.a));
  PetscFunctionReturn(0);
}

/* What a failed energy audit saw and what to do (docs/reference.md, "What is checked before the
 * run"). The balance sums the step's works: it holds to the residual of the step's solve. Where
 * that solve is iterative (the active-set formulation's projected CG, or CG on K~), it stops at
 * -contact_tol of ||b||, and its residual is what the audit sees: the linear cube spinning onto a
 * plane with -mass standard ends at 1.7e-6 under active_set, 5.2e-8 with -contact_tol 1e-13, 2.1e-9
 * with 1e-14, 5.7e-11 under condensed and 1.1e-10 under full (tests/test_limits_and_advice.py). Where
 * the solves are exact factorizations, a residual far above -contact_tol is no solver's: the usual
 * cause is inconsistent units (a mesh in millimetres with E in Pa), which leave K~ so
 * ill-conditioned that no solve is exact. With the step certificate on (the default, certificate.c)
 * the iterative solves go on to the round-off of each step's terms, and that cube runs. */
static PetscErrorCode AuditAdvice(MMNewmark nm, PetscReal residual, char advice[], size_t len)
{
  const char *type, *choice, *products;
  PetscReal   tol;
  PetscBool   iterative, active_set;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetTolerance(nm->contact, &tol));
  PetscCall(MMContactGetSolverText(nm->contact, &type, &choice, &products));
  PetscCall(MMContactStepIsIterative(nm->contact, &iterative));
  PetscCall(PetscStrcmp(type, "active_set", &active_set));
  if (nm->material->finite) {
    /* the step is the finite-strain iteration, each of its solves by the formulation: it met
     * -nonlinear_rtol, so the state, not a tolerance, is at fault (D1 neo-Hookean at E = 1 thrown at
     * 5 times the pressure wave speed fails so with any -nonlinear_rtol, -ts_dt or formulation) */
    PetscCall(PetscSNPrintf(advice, len, "The step's finite-strain iteration (contact formulation %s) met -nonlinear_rtol %.1e, so this is not a loose solve and tightening the tolerances will not help: %scheck that the units are consistent (SI throughout) and that the material values and -v0 are what you meant.", type, (double)nm->nl.rtol,
                           nm->deform.warned ? "cells were compressed below half their volume (warned above); " : ""));
  } else if ((active_set || iterative) && !nm->cert.on) {
    PetscCall(PetscSNPrintf(advice, len, "The step's solve (contact formulation %s: %s) is iterative and, with -step_certificate 0, stops at -contact_tol %.1e of ||b||; its residual is what the balance shows. Rerun without -step_certificate 0 (each step is then solved until its residual is at round-off), with -contact_formulation condensed (exact factorizations) or with a tighter -contact_tol (%.0e: 100 times tighter; the balance residual falls with it).", type, active_set ? "projected CG on the free dofs" : "CG on K~", (double)tol, (double)(1e-2 * tol)));
  } else if (active_set || iterative) {
    PetscCall(PetscSNPrintf(advice, len, "The step's solve (contact formulation %s: %s) is iterative and its steps were accepted by their certificate (%" PetscInt_FMT " at their residual's round-off floor, the largest %.3g round-offs): rerun with -contact_formulation condensed (exact factorizations), and check that the units are consistent (SI throughout).", type, active_set ? "projected CG on the free dofs" : "CG on K~", nm->cert.floor_steps, (double)nm->cert.floor_max));
  } else if (residual > 1e4 * tol) {
    PetscCall(PetscSNPrintf(advice, len, "The step's solve (contact formulation %s) factors K~ exactly, so a residual this far above the solver tolerance -contact_tol %.1e is not a loose solve: check that the units are consistent (SI throughout: the mesh in metres, -E in Pa, -rho in kg/m^3, loads in N/m^2 and m/s^2) and that the material values are what you meant; tightening the tolerances will not help.", type, (double)tol));
  } else {
    PetscCall(PetscSNPrintf(advice, len, "The step's solve (contact formulation %s) was not exact: tighten -contact_tol (now %.1e) or the -contact_snes tolerances (and check that the units are consistent, SI throughout).", type, (double)tol));
  }
  PetscFunctionReturn(0);
}

/* E^{n+1} - E^n = W_ext + W_c + W_f (+ W_obstacle + W_d), each term recorded; the residual is the
 * scheme's identity. */
PetscErrorCode MMEnergyStep(MMNewmark nm)
{
  MMContactOperators ops;
  MMHistory         *h = &nm->hist;
  MMState           *s = &nm->state;
  PetscReal          E_old = h->total, w_ext, w_c = s->work_contact, w_f = 0, w_obs = 0, w_d, w_ext_D, w_D;
  PetscScalar        Ldu;
  MMContactNodes     cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  PetscCall(PetscLogEventBegin(MM_TS_Energy, 0, 0, 0, 0));
  PetscCall(MMNewmarkStepIncrement(nm, s->u, s->work));
  PetscCall(VecDot(ops.load, s->work, &Ldu)); /* L^{n+1}: L^n too when the loads are constant */
  w_ext = PetscRealPart(Ldu);
  if (nm->loads->in_time) { /* 1/2 (L^n + L^{n+1}).du (docs/method.md section 10) */
    PetscScalar L0du;
    PetscCall(VecDot(nm->loads->load_old, s->work, &L0du));
    w_ext = 0.5 * (PetscRealPart(L0du) + w_ext);
  }
  /* the loads' and the support's work on the moving Dirichlet dofs, and the reactions at t^{n+1} */
  PetscCall(MMLoadsStepWork(nm->loads, s->u, s->a, s->u_old, s->a_old, &w_ext_D, &w_D));
  w_ext += w_ext_D;
  if (nm->material->finite) PetscCall(MMNonlinearDampingWork(nm, s->work, h->time, s->dt, &w_d));
  else PetscCall(MMDampingWork(&nm->damping, s->work, s->dt, &w_d));
  /* W_c was computed on this very state by the contact-work guard (MMEnergyContactWork) */
  if (cn.enabled) PetscCall(TrapezoidalWork(nm, cn.is_tangent, s->work, &w_f));
  {
    PetscReal wn, wt, dwc, dwn, dwt;
    /* h->time is already t^{n+1} */
    PetscCall(ObstacleWork(nm, h->time - s->dt, h->time, &wn, &wt));
    /* W_c took the friction corners' share from W_f (MMEnergyContactWork) */
    PetscCall(MMContactCornersWork(nm->contact, h->time - s->dt, h->time, s->work, &dwc, &dwn, &dwt));
    wn += dwn;
    wt += dwt;
    w_f -= wt + dwc;
    h->work_obstacle += wn + wt;
    w_obs = wn + wt;
  }
  h->dt = s->dt;
  PetscCall(TotalEnergy(nm, h));
  PetscCall(CheckFinite(nm, h, w_ext, w_c, w_f));
  h->work_ext += w_ext;
  h->work_contact += w_c;
  h->work_friction += w_f;
  h->work_damping += w_d;
  h->work_dirichlet += w_D;
  h->work_frame += s->work_frame;
  /* relative to the run's energy scale, so that a body coming to rest does not inflate it */
  h->energy_scale     = PetscMax(h->energy_scale, PetscAbsReal(h->total));
  h->balance_residual = PetscAbsReal(h->total - E_old - s->work_frame - w_ext - w_c - w_f - w_obs - w_d - w_D) / PetscMax(h->energy_scale, PETSC_SMALL * PETSC_SMALL);
  h->max_balance      = PetscMax(h->max_balance, h->balance_residual);
  if (h->balance_residual > nm->audit_tol) {
    char advice[768];

    PetscCall(AuditAdvice(nm, h->balance_residual, advice, sizeof(advice)));
    SETERRQ(PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_NOT_CONVERGED, "Energy audit failed at step %" PetscInt_FMT " (t = %g): balance residual %.3e > -audit_tol %.1e. %s The output up to the previous step is intact", h->step, (double)h->time, (double)h->balance_residual, (double)nm->audit_tol, advice);
  }
  s->work_frame      = 0;
  h->cfl              = cn.enabled ? nm->material->c_p_max * s->dt / cn.h_c : 0;
  PetscCall(ContactDiagnostics(nm, s->u, s->react, s->v, PETSC_TRUE, h));
  PetscCall(MMFrictionGetConvergence(nm->friction, &h->friction_its, NULL, NULL, &h->contraction));
  h->max_penetration_run = PetscMax(h->max_penetration_run, h->max_penetration);
  PetscCall(MMRigidBodyDiagnostics(nm, h));
  PetscCall(PetscLogEventEnd(MM_TS_Energy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
