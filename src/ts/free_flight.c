/* The stepper's side of the mass in free flight (-mass_free_flight, docs/method.md section 2, "The
 * mass in free flight"): when M* is the standard mass M and when it is -mass's, decided at a step's
 * start from the scheme's prediction, corrected after the step's solve if a node touched anyway, and
 * the kinetic energy each switch moves booked in the balance (W_frame). Contact rebuilds M* and K~
 * (src/contact/frame/mass_free.c). Finite-strain laws only: their step uses v^n, not a^n. */
#include "newmarkimpl.h"
#include "fem.h"
#include <petscblaslapack.h>

/* The rigid modes about the current positions x = X + u, in the w-frame: the functionals of the
 * scheme's momenta P and J (docs/method.md section 4, "Momentum"). A rotation's mode is linear in
 * the position, so it is the mode at X (MMFERigidModesCartesian) plus the mode at u. A body without
 * Dirichlet dofs: every owned vertex has its dim components in order. */
static PetscErrorCode CurrentRigidModes(MMNewmark nm, PetscInt nr, Vec R[])
{
  const PetscInt     dim       = nm->dim;
  const PetscReal    origin[3] = {0, 0, 0};
  Vec                cart[MM_MAX_RIGID], uc;
  const PetscScalar *u;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(nm->dm, &uc));
  for (PetscInt k = 0; k < nr; ++k) PetscCall(DMGetGlobalVector(nm->dm, &cart[k]));
  PetscCall(MMFERigidModesCartesian(nm->op, origin, 1.0, nr, cart));
  PetscCall(MMFEToCartesian(nm->op, nm->state.u, uc));
  PetscCall(VecGetLocalSize(uc, &n));
  PetscCall(VecGetArrayRead(uc, &u));
  for (PetscInt m = dim; m < nr; ++m) {
    PetscScalar *r;
    PetscCall(VecGetArray(cart[m], &r));
    for (PetscInt b = 0; b < n; b += dim) {
      PetscReal x[MM_MAX_DIM] = {0, 0, 0}, T[MM_MAX_DIM][MM_MAX_RIGID];
      for (PetscInt d = 0; d < dim; ++d) x[d] = PetscRealPart(u[b + d]);
      MMFERigidModeMatrix(dim, x, T);
      for (PetscInt c = 0; c < dim; ++c) r[b + c] += T[c][m];
    }
    PetscCall(VecRestoreArray(cart[m], &r));
  }
  PetscCall(VecRestoreArrayRead(uc, &u));
  for (PetscInt k = 0; k < nr; ++k) {
    PetscCall(MMFEFromCartesian(nm->op, cart[k], R[k]));
    PetscCall(DMRestoreGlobalVector(nm->dm, &cart[k]));
  }
  PetscCall(DMRestoreGlobalVector(nm->dm, &uc));
  PetscFunctionReturn(0);
}

/* p_k = R_k.(M* v), all ranks */
static PetscErrorCode Momenta(MMNewmark nm, PetscInt nr, Vec R[], Vec v, PetscReal p[])
{
  MMContactOperators ops;
  PetscScalar        dots[MM_MAX_RIGID];

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, v, nm->state.work));
  PetscCall(VecMDot(nm->state.work, nr, R, dots));
  for (PetscInt k = 0; k < nr; ++k) p[k] = PetscRealPart(dots[k]);
  PetscFunctionReturn(0);
}

/* The scheme's momenta P and J kept through the switch to M (-mass redistributed): v gains the rigid velocity R y with
 * (R^T M R) y = p_old - R^T M v. M and M* weigh a rigid velocity alike (-mass redistributed keeps
 * M's moments, docs/method.md section 2), not the body's vibration nor the massless rows' backward
 * difference (newmark.c), which M* never weighed: without it P and J would jump at the switch by what
 * those velocities carry in M (2% of J on a coarse cube after its bounce). */
static PetscErrorCode KeepMomenta(MMNewmark nm, PetscInt nr, Vec R[], const PetscReal p_old[], Vec v)
{
  MMContactOperators ops;
  PetscScalar        dots[MM_MAX_RIGID];
  PetscReal          p[MM_MAX_RIGID], G[MM_MAX_RIGID * MM_MAX_RIGID], y[MM_MAX_RIGID], sv[MM_MAX_RIGID], work[16 * MM_MAX_RIGID], rcond = 1e-12;
  PetscBLASInt       bn, one = 1, rank, lwork = 16 * MM_MAX_RIGID, info;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(Momenta(nm, nr, R, v, p));
  for (PetscInt k = 0; k < nr; ++k) {
    y[k] = p_old[k] - p[k];
    PetscCall(MatMult(ops.Mstar, R[k], nm->state.work));
    PetscCall(VecMDot(nm->state.work, nr, R, dots));
    for (PetscInt l = 0; l < nr; ++l) G[k * nr + l] = PetscRealPart(dots[l]);
  }
  PetscCall(PetscBLASIntCast(nr, &bn));
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKgelss", LAPACKgelss_(&bn, &bn, &one, G, &bn, y, &bn, sv, &rcond, &rank, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCheck(info == 0, nm->comm, PETSC_ERR_LIB, "LAPACK gelss failed with info %d", (int)info);
  for (PetscInt k = 0; k < nr; ++k) PetscCall(VecAXPY(v, y[k], R[k]));
  PetscFunctionReturn(0);
}

/* M* switched, the kinetic energy it moves booked: 1/2 v.(M*_new - M*_old) v with v the step's start
 * velocity. Going free, the massless rows' reactions (their quasi-static pair, zero in contact's
 * complementarity when no node touches) are zeroed: on a row with mass they would act as a force in
 * the next step's mean; the balance books the step with what it is solved with. */
static PetscErrorCode SwitchMass(MMNewmark nm, PetscBool is_free, Vec v)
{
  MMContactOperators ops;
  MMContactNodes     cn;
  MMState           *s = &nm->state;
  PetscScalar        before, after;
  MMMassType         type;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, v, s->work));
  PetscCall(VecDot(v, s->work, &before));
  if (is_free) PetscCall(VecISSet(s->react, cn.is_massless, 0.0));
  PetscCall(MMContactGetMassType(nm->contact, &type));
  /* -mass redistributed's M* carries M's moments, so its momenta are the body's; the modified one's
   * lack the removed mass, and keeping them would slow the body down */
  if (is_free && !nm->pb.dirichlet && type == MM_MASS_REDISTRIBUTED) {
    const PetscInt nr = MMFENumRigidModes(nm->dim);
    Vec            R[MM_MAX_RIGID];
    PetscReal      p_old[MM_MAX_RIGID];
    for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDuplicate(v, &R[k]));
    PetscCall(CurrentRigidModes(nm, nr, R));
    PetscCall(Momenta(nm, nr, R, v, p_old));
    PetscCall(MMContactMassSetFree(nm->contact, is_free));
    PetscCall(KeepMomenta(nm, nr, R, p_old, v));
    for (PetscInt k = 0; k < nr; ++k) PetscCall(VecDestroy(&R[k]));
  } else PetscCall(MMContactMassSetFree(nm->contact, is_free));
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, v, s->work));
  PetscCall(VecDot(v, s->work, &after));
  s->work_frame += 0.5 * PetscRealPart(after - before);
  PetscFunctionReturn(0);
}

/* At a step's start: free (M) while every contact row's predicted end stays more than h_c' from its
 * bound, -mass's M* once one comes within h_c'; free again only past 2 h_c', so that a node resting
 * near its bound does not switch at every step. */
PetscErrorCode MMNonlinearFreeFlight(MMNewmark nm, PetscReal t, PetscReal dt)
{
  PetscBool on, is_free, want;
  PetscReal slack, h_c;

  PetscFunctionBeginUser;
  PetscCall(MMContactMassFreeFlight(nm->contact, &on, &is_free));
  if (!on) PetscFunctionReturn(0);
  PetscCall(MMNewmarkPredictEnd(nm, dt, nm->state.work));
  PetscCall(MMContactMassReach(nm->contact, nm->state.work, t + dt, &slack, &h_c));
  want = (PetscBool)(slack > (is_free ? 1.0 : 2.0) * h_c);
  if (want != is_free) PetscCall(SwitchMass(nm, want, nm->state.v));
  PetscFunctionReturn(0);
}

/* After a step's solve with M: a row that reached its bound (within 1e-10 h_c', the candidate set's
 * own test of a touching node, docs/method.md section 3) touched with its mass. The step is then
 * solved again from its start with -mass's M* (touched). */
PetscErrorCode MMNonlinearFreeFlightTouched(MMNewmark nm, Vec w, PetscReal t, PetscBool *touched)
{
  PetscBool on, is_free;
  PetscReal slack, h_c;

  PetscFunctionBeginUser;
  *touched = PETSC_FALSE;
  PetscCall(MMContactMassFreeFlight(nm->contact, &on, &is_free));
  if (!on || !is_free) PetscFunctionReturn(0);
  PetscCall(MMContactMassReach(nm->contact, w, t, &slack, &h_c));
  if (slack > 1e-10 * h_c) PetscFunctionReturn(0);
  *touched = PETSC_TRUE;
  PetscCall(VecCopy(nm->state.react_old, nm->state.react));
  PetscCall(SwitchMass(nm, PETSC_FALSE, nm->state.v_old));
  PetscFunctionReturn(0);
}
