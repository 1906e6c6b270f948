/* The step of the finite-strain laws (docs/method.md section 13): the energy-momentum scheme
 *
 *   M* (v^{n+1} - v^n) = dt [ (L^n + L^{n+1})/2 + lambda - f_alg(u^n, u^{n+1}) - alpha M* du/dt ],
 *   u^{n+1} - u^n = du = dt/2 (v^n + v^{n+1}),
 *
 * with f_alg the algorithmic internal force (src/fem/elasticity.c, with Rayleigh's beta its viscous
 * stress too), lambda the step's mean contact force, under the contact and friction laws at t^{n+1} as in
 * the linear scheme. Eliminating v^{n+1}, one problem for w = u^{n+1}:
 *
 *   (4/dt^2 + 2 alpha/dt) M* w + 2 f_alg(u^n, w) = b_nl + 2 lambda,
 *   b_nl = M* ((4/dt^2 + 2 alpha/dt) u^n + 4/dt v^n) + L^n + L^{n+1}.
 *
 * The mean, not the end value of the linear scheme's trapezoidal pair (f_c^n + f_c^{n+1})/2: on the
 * massless rows that pair obeys f_c^{n+1} = 2 (f_alg - L_mid) - f_c^n, which for the linear law keeps
 * the quasi-static equation at every t^n, but for a nonlinear or viscous f_alg carries an undamped
 * (-1)^n mode in the reactions. For the linear law 2 f_alg = K (u^n + w) + 2 lift, and the motion is
 * the trapezoidal step's.
 *
 * It is solved by a modified Newton iteration whose every iterate is one linear contact problem of
 * the step matrix K~ = K_s + 4/dt^2 M*: K~ w^{k+1} + r = b_nl + K_s w^k - 2 f_alg(u^n, w^k), solved by the
 * contact formulation and the friction solver exactly as a linear step. At its fixed point the
 * nonlinear step holds with the contact and Coulomb laws exact. K_s is the reference stiffness K
 * (whose factor and Delassus columns serve the whole run) until an iteration contracts too slowly,
 * large rotations for instance; then the tangent at the iterate replaces it. */
#include "newmarkimpl.h"
#include "fem.h"
#include "friction.h"
#include "sys.h"

const char *const MMTangentPolicies[] = {"auto", "reference", "step", "MMTangentPolicy", "MM_TANGENT_", NULL};

PetscErrorCode MMNonlinearSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMNonlinear *nl)
{
  PetscFunctionBeginUser;
  nl->policy = MM_TANGENT_AUTO;
  PetscCall(MMOptionsEnum(PetscOptionsObject, comm, "-nonlinear_tangent", "The iteration matrix of the finite-strain step (-elasticity svk, neohookean): auto (the reference stiffness K until an iteration contracts by less than -nonlinear_refresh_ratio, then the tangent at the iterate), reference (K all run) or step (the tangent at the step's start, every step)", MMTangentPolicies, (PetscEnum *)&nl->policy));
  nl->rtol = 1e-11;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-nonlinear_rtol", "The finite-strain step's iteration stops when its force residual is below this times the step's force scale (the internal force, the loads, the reactions, 2/dt M* v), > 0", &nl->rtol));
  nl->rtol_audit = 1e-8;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-nonlinear_audit_rtol", "Between this and -nonlinear_rtol, the finite-strain step also stops when its residual's work and momenta over the step are below 1e-12 of the energy and momentum scales, what the audits cannot see (>= -nonlinear_rtol; equal to it: off)", &nl->rtol_audit));
  nl->max_it = 30;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-nonlinear_max_it", "Most iterations of the finite-strain step (>= 1); past them the step is rejected and retried with a smaller dt", &nl->max_it));
  nl->anderson = 5;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-nonlinear_anderson", "Anderson acceleration of the finite-strain step's iteration: how many past iterates it mixes (0: none, plain modified Newton; at most 16)", &nl->anderson));
  PetscCheck(nl->anderson >= 0 && nl->anderson <= MM_ANDERSON_MAX, comm, PETSC_ERR_USER_INPUT, "-nonlinear_anderson %" PetscInt_FMT " must be in [0, %d]", nl->anderson, MM_ANDERSON_MAX);
  nl->clamp = PETSC_FALSE;
  PetscCall(MMOptionsBool(PetscOptionsObject, comm, "-nonlinear_tangent_clamp", "A rebuilt iteration matrix's compressed cells made semi-definite (their tangent's negative eigenvalues set to 0): always (true), or (false, the default) only after a step iterated with the tangent as it is was rejected, for the rest of the run. The tangent as it is contracts faster (the slender cantilever: 5.2 iterations per step against 7.3), and K~ = K_t + 4/dt^2 M* stays definite while the mass term covers the compressed cells' negative stiffness", &nl->clamp));
  nl->refresh = PETSC_DEFAULT;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-nonlinear_refresh_ratio", "-nonlinear_tangent auto: rebuild the iteration matrix at the iterate when an iteration reduces the residual by less than this factor (once per step; again when the residual grows), in (0, 1) (default 0.5 for the condensed formulation, whose rebuild refactors K~ and recomputes every Delassus column, 0.1 otherwise)", &nl->refresh));
  nl->static_steps = 4;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-static_load_steps", "-initial_state static with -elasticity svk or neohookean: the first load increment is 1/this of the loads at t = 0; then halved on a failed Newton solve, doubled after an easy one (>= 1)", &nl->static_steps));
  nl->static_max_it = 25;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-static_max_it", "-initial_state static with -elasticity svk or neohookean: most Newton iterations per load level, past them the load increment is halved (>= 2)", &nl->static_max_it));
  PetscCheck(nl->static_steps >= 1, comm, PETSC_ERR_USER_INPUT, "-static_load_steps %" PetscInt_FMT " must be >= 1", nl->static_steps);
  PetscCheck(nl->static_max_it >= 2, comm, PETSC_ERR_USER_INPUT, "-static_max_it %" PetscInt_FMT " must be >= 2", nl->static_max_it);
  PetscCheck(nl->rtol > 0, comm, PETSC_ERR_USER_INPUT, "-nonlinear_rtol %g must be > 0", (double)nl->rtol);
  PetscCheck(nl->rtol_audit >= nl->rtol && nl->rtol_audit < 1, comm, PETSC_ERR_USER_INPUT, "-nonlinear_audit_rtol %g must be in [-nonlinear_rtol %g, 1): the residual below which the audits decide whether the finite-strain step is done", (double)nl->rtol_audit, (double)nl->rtol);
  PetscCheck(nl->max_it >= 1, comm, PETSC_ERR_USER_INPUT, "-nonlinear_max_it %" PetscInt_FMT " must be >= 1", nl->max_it);
  PetscCheck(nl->refresh == PETSC_DEFAULT || (nl->refresh > 0 && nl->refresh < 1), comm, PETSC_ERR_USER_INPUT, "-nonlinear_refresh_ratio %g must be in (0, 1)", (double)nl->refresh);
  PetscFunctionReturn(0);
}

/* What the finite-strain step does not support yet, refused before the run starts */
static PetscErrorCode CheckSupported(MMNewmark nm)
{
  MPI_Comm comm = nm->comm;

  PetscFunctionBeginUser;
  PetscCheck(!nm->loads->moving, comm, PETSC_ERR_SUP, "-elasticity svk and neohookean do not take moving Dirichlet boundaries yet (a -dirichlet_NAME_velocity or a value with an amplitude): fix the boundary, or use -elasticity linear");
  PetscFunctionReturn(0);
}

/* The stepper's w-frame data, registered once with contact, which turns it when its frames turn
 * (-contact_frames follow) and carries it to a new pairing (large sliding): the state u, v, a and
 * the reaction, the loads' parts in time and the last step's load, and the iteration stiffness
 * (docs/developer.md, "The contact frame") */
static PetscErrorCode RegisterFrameData(MMNewmark nm)
{
  MMState *s  = &nm->state;
  MMLoads *ld = nm->loads;

  PetscFunctionBeginUser;
  {
    Vec *kin[] = {&s->u, &s->v, &s->a};
    for (size_t i = 0; i < sizeof(kin) / sizeof(kin[0]); ++i) PetscCall(MMContactFramesAddVec(nm->contact, MM_FRAME_KINEMATIC, kin[i]));
  }
  PetscCall(MMContactFramesAddVec(nm->contact, MM_FRAME_FORCE, &s->react));
  PetscCall(MMContactFramesAddVec(nm->contact, MM_FRAME_SETUP_FORCE, &ld->load_old));
  for (PetscInt k = 0; ld->part && k < ld->nparts; ++k) PetscCall(MMContactFramesAddVec(nm->contact, MM_FRAME_SETUP_FORCE, &ld->part[k]));
  PetscCall(MMContactFramesAddMat(nm->contact, &nm->nl.Ks));
  PetscFunctionReturn(0);
}

PetscErrorCode MMNonlinearSetUp(MMNewmark nm)
{
  MMNonlinear *nl = &nm->nl;

  PetscFunctionBeginUser;
  PetscCall(CheckSupported(nm));
  if (nl->refresh == PETSC_DEFAULT) {
    PetscBool delassus;
    /* a rebuild costs the condensed formulation about 13 linear steps (a refactor and every candidate
     * column), the others a tangent assembly: measured on the D2 ball, docs/method.md section 13 */
    PetscCall(MMContactHasDelassus(nm->contact, &delassus));
    nl->refresh = delassus ? 0.5 : 0.1;
  }
  {
    PetscReal lo[MM_MAX_DIM], hi[MM_MAX_DIM], D = 0;
    PetscCall(DMGetBoundingBox(nm->dm, lo, hi)); /* the mesh's size: the angular momentum's length scale */
    for (PetscInt d = 0; d < nm->dim; ++d) D += PetscSqr(hi[d] - lo[d]);
    nl->size = PetscSqrtReal(D);
  }
  PetscCall(MMElasticitySetUp(&nl->el, nm->op));
  if (nm->loads->n_bc) PetscCall(MMLoadsSetElasticity(nm->loads, &nl->el));
  PetscCall(VecDuplicate(nm->state.u, &nl->bnl));
  PetscCall(VecDuplicate(nm->state.u, &nl->f));
  PetscCall(VecDuplicate(nm->state.u, &nl->c));
  PetscCall(VecDuplicate(nm->state.u, &nl->c_prev));
  PetscCall(VecDuplicate(nm->state.u, &nl->c_scale));
  PetscCall(MMAndersonSetUp(&nl->aa, nl->anderson, nm->state.u));
  PetscCall(RegisterFrameData(nm));
  PetscFunctionReturn(0);
}

PetscErrorCode MMNonlinearDestroy(MMNonlinear *nl)
{
  PetscFunctionBeginUser;
  PetscCall(MMElasticityDestroy(&nl->el));
  PetscCall(MatDestroy(&nl->Ks));
  PetscCall(VecDestroy(&nl->Ks_at));
  PetscCall(VecDestroy(&nl->bnl));
  PetscCall(VecDestroy(&nl->f));
  PetscCall(VecDestroy(&nl->c));
  PetscCall(VecDestroy(&nl->c_prev));
  PetscCall(VecDestroy(&nl->c_scale));
  PetscCall(MatDestroy(&nl->Kabs));
  PetscCall(MMAndersonDestroy(&nl->aa));
  PetscFunctionReturn(0);
}

/* The forces the stepper carries across a new pairing (besides the reaction): the load, the lift, and
 * with loads in time the last step's load and the load parts; at most 3 + nparts. A checkpoint of large
 * sliding keeps them as they are, in the pairing's variables (MMNewmarkGetCarriedForces). */
static PetscErrorCode CarriedForces(MMNewmark nm, PetscInt *nf, Vec force[])
{
  MMContactOperators ops;
  MMLoads           *ld = nm->loads;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  *nf          = 0;
  force[(*nf)++] = ops.load;
  force[(*nf)++] = ops.lift;
  if (ld->load_old) force[(*nf)++] = ld->load_old;
  for (PetscInt k = 0; ld->part && k < ld->nparts; ++k) force[(*nf)++] = ld->part[k];
  PetscFunctionReturn(0);
}

/* What the stepper built on N, dropped after a new pairing, to be built again: the tangent (K's pattern
 * follows N); M* is contact's new one (the momentum functionals, M* N^{-1} Q^T e, follow the frame
 * state: momenta.c) */
static PetscErrorCode DropPairingOperators(MMNewmark nm)
{
  MMContactOperators ops;
  MMNonlinear       *nl = &nm->nl;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatDestroy(&nl->Ks));
  nl->use_tangent = PETSC_FALSE;
  nm->damping.Mstar = ops.Mstar; /* borrowed (no damping with these laws) */
  PetscFunctionReturn(0);
}

/* Contact pairs with large sliding (docs/method.md section 11, "Large sliding"): before the step, the
 * pairing found again on u^n. When it changed, contact rebuilt N, K, M* (and K~ at the next step
 * matrix) and carried the stepper's registered vectors (RegisterFrameData: the state, the last
 * reaction, which b_nl carries, and the loads) to the new variables; what the stepper built on N is
 * dropped, to be built again. */
PetscErrorCode MMNonlinearSlidePairs(MMNewmark nm, PetscReal dt)
{
  MMState  *s = &nm->state;
  PetscBool changed;

  PetscFunctionBeginUser;
  /* the pairing of the step's predictor u + dt v + dt^2/4 a (newmark.c), dt the step's first try */
  PetscCall(MMNewmarkPredictEnd(nm, dt, s->u_next));
  PetscCall(MMContactSlidePairs(nm->contact, s->u, s->u_next, &changed));
  if (!changed) PetscFunctionReturn(0);
  PetscCall(DropPairingOperators(nm));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetCarriedForces - Gives, for a checkpoint of large sliding, the forces the stepper
  carries across pairings

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameters:
+ n - their number, 0 without large sliding
- f - the forces, in the order a restart reads them back; room for MMNewmarkCountCarriedForces() vectors

  Note:
  For a checkpoint of large sliding: the forces the stepper carries across pairings (CarriedForces),
  in the order a restart reads them back; *n = 0 without large sliding, whose forces are the
  set-up's. f holds at least 3 + the load parts (MMNewmarkCountCarriedForces).

  Level: developer

.seealso: `MMNewmarkCountCarriedForces()`, `MMNewmarkRestorePairs()`
@*/
PetscErrorCode MMNewmarkGetCarriedForces(MMNewmark nm, PetscInt *n, Vec f[])
{
  MMContactNodes cn;

  PetscFunctionBeginUser;
  *n = 0;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  if (!cn.enabled || !cn.pairs_sliding) PetscFunctionReturn(0);
  PetscCall(CarriedForces(nm, n, f));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkCountCarriedForces - Returns how many forces MMNewmarkGetCarriedForces() may give

  Not collective

  Input Parameter:
. nm - the stepper's context

  Level: developer

.seealso: `MMNewmarkGetCarriedForces()`
@*/
PetscInt MMNewmarkCountCarriedForces(MMNewmark nm)
{
  return 3 + (nm->loads->part ? nm->loads->nparts : 0);
}

/*@
  MMNewmarkRestorePairs - Restores, on -restart of large sliding, the checkpoint's contact pairing

  Collective

  Input Parameters:
+ nm   - the stepper's context
. rec  - per owned contact row the pairing record, or NULL (MMCheckpointGetPairs())
- file - the checkpoint file, for the messages

  Note:
  -restart of large sliding (docs/method.md section 9): contact takes the checkpoint's pairing (rec,
  per owned contact row; NULL: none, refused when this run slides) and rebuilds N, K and M*; the
  stepper drops what it built on the set-up's N. The state and the carried forces are read from the
  checkpoint in the new variables: nothing turns.

  Level: developer

.seealso: `MMCheckpointGetPairs()`, `MMNewmarkGetCarriedForces()`, `MMNewmarkRestoreFrames()`
@*/
PetscErrorCode MMNewmarkRestorePairs(MMNewmark nm, const PetscScalar rec[], const char file[])
{
  MMContactNodes cn;
  PetscBool      changed;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  if (!cn.enabled || !cn.pairs_sliding) PetscFunctionReturn(0);
  PetscCheck(rec, nm->comm, PETSC_ERR_USER_INPUT, "-restart %s: the checkpoint has no pairing of the contact pairs (\"pairs\"): it was written by an mmcontact that did not restart large sliding, and its state is relative to a pairing it does not hold. Continue it with that mmcontact, or run again without -restart", file);
  PetscCall(MMContactPairsRestore(nm->contact, rec, &changed));
  if (changed) PetscCall(DropPairingOperators(nm));
  PetscFunctionReturn(0);
}

/* The stored energy of the state u (w-frame) with the Dirichlet data of time t */
PetscErrorCode MMNonlinearElasticEnergy(MMNewmark nm, Vec u, PetscReal t, PetscReal *energy)
{
  MMElasticity *el = &nm->nl.el;

  PetscFunctionBeginUser;
  PetscCall(MMElasticityLocal(el, nm->op, nm->loads, u, t, el->l1));
  PetscCall(MMElasticityEnergy(el, nm->op, nm->material, el->l1, energy));
  PetscFunctionReturn(0);
}

/* K~ = K_s + 4/dt^2 M*, with K_s the current iteration stiffness */
PetscErrorCode MMNonlinearStepMatrix(MMNewmark nm, PetscReal dt, MMStepMatrix *sm)
{
  MMContactOperators ops;
  MMNonlinear       *nl = &nm->nl;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMDampingGetStepMatrix(&nm->damping, ops.K, dt, sm));
  /* Rayleigh's beta: the viscous stress's iteration matrix is 2 beta/dt K_s, the iteration stiffness
   * scaled, so that it turns with the body as K_s does (Correction) */
  sm->ck += sm->cb;
  sm->cb      = 0;
  sm->B       = NULL;
  sm->K       = nl->use_tangent ? nl->Ks : NULL;
  sm->version = nl->use_tangent ? nl->version : 0;
  PetscFunctionReturn(0);
}

/* K_s <- the tangent at the local state l (Cartesian, with the Dirichlet data of time t), and where it
 * was taken: the iteration matrix is state the next steps depend on, which a checkpoint keeps. Also
 * the static start's Newton matrix (static_finite.c). */
PetscErrorCode MMNonlinearBuildTangent(MMNewmark nm, Vec l, PetscReal t)
{
  MMContactOperators ops;
  MMNonlinear       *nl = &nm->nl;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  if (!nl->Ks) PetscCall(MatDuplicate(ops.K, MAT_DO_NOT_COPY_VALUES, &nl->Ks));
  {
    Mat Kc; /* the Cartesian tangent, turned into the w-frame (and N^T Kc N with contact pairs) by contact */
    PetscCall(MMContactFrameMatrixBegin(nm->contact, nl->Ks, &Kc));
    nl->el.clamp = nl->clamp;
    PetscCall(MMElasticityAssembleTangent(&nl->el, nm->op, nm->material, l, Kc));
    PetscCall(MMContactFrameMatrixEnd(nm->contact, Kc, nl->Ks));
  }
  if (!nl->Ks_at) PetscCall(DMCreateGlobalVector(nm->dm, &nl->Ks_at));
  PetscCall(DMLocalToGlobal(nm->dm, l, INSERT_VALUES, nl->Ks_at)); /* the owned values, exactly */
  nl->Ks_time     = t;
  nl->use_tangent = PETSC_TRUE;
  nl->version++;
  PetscFunctionReturn(0);
}

/* K_s <- the tangent at the local state l of time t, and K~ rebuilt on it */
static PetscErrorCode RebuildTangent(MMNewmark nm, PetscReal dt, Vec l, PetscReal t)
{
  MMNonlinear *nl = &nm->nl;
  MMStepMatrix sm;

  PetscFunctionBeginUser;
  PetscCall(MMNonlinearBuildTangent(nm, l, t));
  nl->rebuilds++;
  PetscCall(MMNonlinearStepMatrix(nm, dt, &sm));
  PetscCall(MMContactSetStepMatrix(nm->contact, &sm));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetTangentPoint - Gives where the finite-strain iteration matrix K_s is the tangent, for
  a checkpoint

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameters:
+ at - the Cartesian displacement, or NULL while K_s is K (owned by the context)
- t  - the time of its Dirichlet data

  Note:
  For a checkpoint (docs/method.md section 9): where the iteration matrix K_s is the tangent, the
  Cartesian displacement and time it was taken at; NULL while K_s is the reference K, and with
  -nonlinear_tangent step, whose every step builds its own

  Level: developer

.seealso: `MMNewmarkRestoreTangent()`, `MMCheckpointGetTangent()`
@*/
PetscErrorCode MMNewmarkGetTangentPoint(MMNewmark nm, Vec *at, PetscReal *t)
{
  const MMNonlinear *nl = &nm->nl;

  PetscFunctionBeginUser;
  *at = NULL;
  *t  = 0;
  if (!nm->material->finite || !nl->use_tangent || nl->policy == MM_TANGENT_STEP) PetscFunctionReturn(0);
  *at = nl->Ks_at;
  *t  = nl->Ks_time;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkRestoreTangent - Rebuilds, on -restart, the finite-strain iteration matrix at the
  checkpoint's point

  Collective

  Input Parameters:
+ nm - the stepper's context
. at - the checkpoint's point, or NULL (MMCheckpointGetTangent())
- t  - its time

  Note:
  -restart: K_s the tangent at the checkpoint's point (MMNewmarkGetTangentPoint), built as the run
  that wrote it built it, so that the steps that follow iterate with the same matrix; K~ is built on
  it with the step matrix of the first step (MMNewmarkGetStepMatrix). Call after the pairing and the
  frames are restored: K_s is in their variables.

  Level: developer

.seealso: `MMNewmarkGetTangentPoint()`, `MMNewmarkGetStepMatrix()`
@*/
PetscErrorCode MMNewmarkRestoreTangent(MMNewmark nm, Vec at, PetscReal t)
{
  MMElasticity *el = &nm->nl.el;

  PetscFunctionBeginUser;
  /* -nonlinear_tangent reference or step at the restart: K, or each step's own tangent */
  if (!at || !nm->material->finite || nm->nl.policy != MM_TANGENT_AUTO) PetscFunctionReturn(0);
  PetscCall(VecZeroEntries(el->l1));
  PetscCall(DMGlobalToLocal(nm->dm, at, INSERT_VALUES, el->l1));
  PetscCall(MMLoadsInsertBoundaryValues(nm->loads, el->l1, t));
  PetscCall(MMNonlinearBuildTangent(nm, el->l1, t));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetTangentClampStep - Gives the step from which the finite-strain tangent is clamped because
  a step iterated with it unclamped was rejected, for a checkpoint

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameter:
. step - that step, 0 when the run has not fallen back (or its law is linear)

  Note:
  The fallback (ForgetFailedTangent) is state the next steps depend on: a checkpoint keeps its step,
  and -restart sets it back (MMNewmarkSetTangentClampStep) before the tangent is rebuilt.

  Level: developer

.seealso: `MMNewmarkSetTangentClampStep()`, `MMNewmarkRestoreTangent()`
@*/
PetscErrorCode MMNewmarkGetTangentClampStep(MMNewmark nm, PetscInt *step)
{
  PetscFunctionBeginUser;
  *step = nm->material->finite ? nm->nl.clamp_step : 0;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkSetTangentClampStep - Restores, on -restart, the checkpointed run's fallback to the clamped tangent

  Not collective

  Input Parameters:
+ nm   - the stepper's context
- step - the step it fell back at (MMNewmarkGetTangentClampStep), 0: none

  Level: developer

.seealso: `MMNewmarkGetTangentClampStep()`
@*/
PetscErrorCode MMNewmarkSetTangentClampStep(MMNewmark nm, PetscInt step)
{
  PetscFunctionBeginUser;
  nm->nl.clamp_step = step;
  if (step > 0) nm->nl.clamp = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* b_nl = M* (4/dt^2 u^n + 4/dt v^n) + L^n + L^{n+1} - r^n (= + f_c^n, the stored reaction), and the step's force scale: the largest of
 * |L^n + L^{n+1}|, |r^n| and 2/dt |M* v^n| (the force that would stop the body in one step), so that a
 * body in free flight, whose internal force is zero, still has a scale for its residual. For the
 * increment (docs/method.md section 13, "The step's unknown"), b_nl - K~ u^n without the
 * (4/dt^2 + 2 alpha/dt) M* u^n that the two cancel; its K_s u^n goes with the correction (Correction). */
static PetscErrorCode FixedRHS(MMNewmark nm, PetscReal dt, PetscBool increment, Vec bnl, PetscReal *fscale)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  PetscReal          n[3];

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, s->v, s->work));
  PetscCall(VecNorm(s->work, NORM_2, &n[0]));
  PetscCall(VecNorm(s->react_old, NORM_2, &n[1]));
  PetscCall(VecWAXPY(s->work, 1.0, ops.load, nm->loads->in_time ? nm->loads->load_old : ops.load));
  PetscCall(VecNorm(s->work, NORM_2, &n[2]));
  *fscale = PetscMax(2.0 / dt * n[0], PetscMax(2 * n[1], n[2])); /* 2 lambda^n: the solve's units */
  /* with Rayleigh's alpha, the damping force alpha M* (w - u^n)/dt, twice: its w part is in K~ */
  if (increment) PetscCall(VecAXPBY(s->work, 4.0 / dt, 0.0, s->v));
  else PetscCall(VecAXPBYPCZ(s->work, 4.0 / (dt * dt) + 2.0 * nm->damping.alpha / dt, 4.0 / dt, 0.0, s->u, s->v));
  PetscCall(MatMult(ops.Mstar, s->work, bnl));
  PetscCall(VecAXPY(bnl, 1.0, ops.load));
  PetscCall(VecAXPY(bnl, 1.0, nm->loads->in_time ? nm->loads->load_old : ops.load));
  PetscFunctionReturn(0);
}

/* c = (1 + 2 beta/dt) K_s x - 2 f_alg(u^n, w), from the local u^n in el.l0; *scale = |2 f_alg|. x is w, or
 * the increment du = w - u^n when the iteration solves for it. With Rayleigh's beta, f_alg carries
 * the step's viscous stress and K~ its iteration matrix 2 beta/dt K_s. */
static PetscErrorCode Correction(MMNewmark nm, PetscReal t1, Vec w, Vec x, Vec c, PetscReal *scale)
{
  MMContactOperators ops;
  MMNonlinear       *nl = &nm->nl;
  MMElasticity      *el = &nl->el;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMElasticityLocal(el, nm->op, nm->loads, w, t1, el->l1));
  PetscCall(MMElasticityForce(el, nm->op, nm->material, el->l1, nl->f));
  PetscCall(VecScale(nl->f, 2.0));
  PetscCall(VecNorm(nl->f, NORM_2, scale));
  PetscCall(MatMult(nl->use_tangent ? nl->Ks : ops.K, x, c));
  PetscCall(VecAXPBY(c, -1.0, 1.0 + 2.0 * el->visc, nl->f)); /* el->visc = beta/dt of this step */
  PetscFunctionReturn(0);
}

/* |K|, K's entries in magnitude (w-frame), built on first use: the round-off scale of a force
 * computed from a displacement (ForceRoundoffScale). Any row length (contact pairs and high-valence
 * vertices lengthen K's rows; a fixed buffer of 256 refused them). */
static PetscErrorCode AbsoluteStiffness(MMNewmark nm, Mat *Kabs)
{
  MMContactOperators ops;
  MMNonlinear       *nl = &nm->nl;

  PetscFunctionBeginUser;
  if (!nl->Kabs) {
    PetscScalar *a   = NULL; /* a row's magnitudes, grown to the longest row met */
    PetscInt     cap = 0, rstart, rend;
    PetscCall(MMContactGetOperators(nm->contact, &ops));
    PetscCall(MatDuplicate(ops.K, MAT_DO_NOT_COPY_VALUES, &nl->Kabs));
    PetscCall(MatGetOwnershipRange(ops.K, &rstart, &rend));
    for (PetscInt row = rstart; row < rend; ++row) {
      const PetscInt    *cols;
      const PetscScalar *vals;
      PetscInt           nc;
      PetscCall(MatGetRow(ops.K, row, &nc, &cols, &vals));
      if (nc > cap) {
        PetscCall(PetscFree(a));
        cap = 2 * nc;
        PetscCall(PetscMalloc1(cap, &a));
      }
      for (PetscInt j = 0; j < nc; ++j) a[j] = PetscAbsScalar(vals[j]);
      PetscCall(MatSetValues(nl->Kabs, 1, &row, nc, cols, a, INSERT_VALUES));
      PetscCall(MatRestoreRow(ops.K, row, &nc, &cols, &vals));
    }
    PetscCall(PetscFree(a));
    PetscCall(MatAssemblyBegin(nl->Kabs, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(nl->Kabs, MAT_FINAL_ASSEMBLY));
  }
  *Kabs = nl->Kabs;
  PetscFunctionReturn(0);
}

/* The round-off of 2 f_alg(u^n, w) per entry: the cells' forces in magnitude, and the rounding of
 * the displacement they are computed from, |K| |w| (a strain is a difference of displacements that
 * a slender part's rotation makes large: on the cantilever the second is a thousand times the
 * first), with Rayleigh's beta (1 + 2 beta/dt) times. A stalled iterate's certificate measures
 * against it (docs/method.md section 13, "The step's iteration"). From el.l1, the local w. */
static PetscErrorCode ForceRoundoffScale(MMNewmark nm, Vec w, Vec scale)
{
  MMNonlinear *nl = &nm->nl;
  Mat          Kabs = NULL;

  PetscFunctionBeginUser;
  PetscCall(AbsoluteStiffness(nm, &Kabs));
  PetscCall(VecCopy(w, nm->state.work));
  PetscCall(VecAbs(nm->state.work));
  PetscCall(MatMult(Kabs, nm->state.work, scale));
  PetscCall(MMElasticityForceMagnitude(&nl->el, nm->op, nm->material, nl->el.l1, nm->state.work));
  PetscCall(VecAXPBY(scale, 2.0, 2.0 * (1.0 + 2.0 * nl->el.visc), nm->state.work));
  PetscFunctionReturn(0);
}

/* The step's tolerance: -nonlinear_rtol, or with iterative K~ solves, which stop at their tolerance
 * times ||b||, ten times the residual that leaves in the force scale S: no iteration can go below it
 * (a step accepted there has its whole residual checked: Accepted) */
static PetscErrorCode Tolerance(MMNewmark nm, Vec b, PetscReal S, PetscReal *tol)
{
  PetscBool iterative;
  PetscReal ctol, bnorm;

  PetscFunctionBeginUser;
  *tol = nm->nl.rtol;
  PetscCall(MMContactStepIsIterative(nm->contact, &iterative));
  if (!iterative) PetscFunctionReturn(0);
  PetscCall(MMContactGetSolveTolerance(nm->contact, &ctol, NULL));
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  *tol = PetscMax(*tol, 10 * ctol * bnorm / S);
  PetscFunctionReturn(0);
}

/* Whether the step's residual r (w-frame) is below what the audits can see: its work over the step at
 * most 1e-12 of the energy scale, and its resultant and moment over the step at most 1e-12 of the
 * momentum and angular-momentum scales (m V and m V D, V = sqrt(2 E / m), D the mesh's size), so that
 * hundreds of steps keep a free body's momenta to 1e-9 */
static PetscErrorCode BelowTheAudits(MMNewmark nm, Vec w, Vec r, PetscReal dt, PetscBool *below)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  const PetscReal    E = nm->hist.energy_scale;
  PetscScalar        work;
  PetscReal          F[3], T[3], P, m;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  m = ops.mass_star[0];
  *below = PETSC_FALSE;
  if (!(E > 0 && m > 0)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(s->work, -1.0, s->u, w));
  PetscCall(VecDot(s->work, r, &work));
  if (PetscAbsScalar(work) > 1e-12 * E) PetscFunctionReturn(0);
  PetscCall(MMMomentaOfForce(nm, w, r, F, T));
  P = PetscSqrtReal(2 * E * m);
  *below = (PetscBool)(dt * PetscSqrtReal(PetscSqr(F[0]) + PetscSqr(F[1]) + PetscSqr(F[2])) <= 1e-12 * P && dt * PetscSqrtReal(PetscSqr(T[0]) + PetscSqr(T[1]) + PetscSqr(T[2])) <= 1e-12 * P * nm->nl.size);
  PetscFunctionReturn(0);
}

/* Whether a step whose residual met its tolerance is done. With iterative solves, the tolerance is
 * theirs (Tolerance), and their own residual, which c^k - c^{k+1} does not see, is in the step's:
 * the whole residual b_nl + H + f_c - K~ w must be below what the audits see (BelowTheAudits), else
 * the solves are tightened a hundredfold and the iteration goes on (the caller restores their
 * tolerance after the step). The free svk cube on the active set with -mass standard kept its
 * balance at 6e-11 and its angular momentum to 1.4e-10 without this (docs/method.md section 13). */
static PetscErrorCode Accepted(MMNewmark nm, Vec w, Vec H, PetscReal dt, Vec b, PetscReal S, PetscReal *tol, PetscBool *done)
{
  MMNonlinear *nl = &nm->nl;
  PetscBool    iterative;
  PetscReal    ctol;
  Vec          r;

  PetscFunctionBeginUser;
  *done = PETSC_TRUE;
  PetscCall(MMContactStepIsIterative(nm->contact, &iterative));
  if (!iterative) PetscFunctionReturn(0);
  PetscCall(MMContactGetSolveTolerance(nm->contact, &ctol, NULL));
  if (ctol <= MM_SOLVE_TOL_MIN) PetscFunctionReturn(0); /* as tight as the solves go: the audits judge it */
  PetscCall(VecWAXPY(nl->f, 1.0, nl->bnl, H));
  PetscCall(MMCertificateResidualOfIterate(nm, nl->f, w, &r));
  PetscCall(BelowTheAudits(nm, w, r, dt, done));
  if (*done) PetscFunctionReturn(0);
  PetscCall(MMContactSetSolveTolerance(nm->contact, PetscMax(1e-2 * ctol, MM_SOLVE_TOL_MIN)));
  PetscCall(Tolerance(nm, b, S, tol));
  PetscCall(PetscInfo(NULL, "finite-strain step %" PetscInt_FMT ": its whole residual is above what the audits see; the solves go to %.1e\n", nm->hist.step + 1, (double)PetscMax(1e-2 * ctol, MM_SOLVE_TOL_MIN)));
  PetscFunctionReturn(0);
}

/* The step's contact force is its mean over the step, lambda (docs/method.md section 13, "The contact force
 * of the step"): the solve's f_c is 2 lambda, in the same cone. Stored as both ends' reaction, so that every
 * trapezoidal work of the audits, 1/2 (f^n + f^{n+1}).du, is lambda.du, the work the step balanced. */
static PetscErrorCode KeepMeanContactForce(MMState *s)
{
  PetscFunctionBeginUser;
  PetscCall(VecScale(s->react, 0.5));
  PetscCall(VecCopy(s->react, s->react_old));
  PetscFunctionReturn(0);
}

/* The iteration of one step from the predictor w; x is the unknown of its solves: w, or the
 * increment du = w - u^n (s->du), w then formed from it */
static PetscErrorCode Iterate(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, Vec x, PetscBool *solved)
{
  MMNonlinear *nl = &nm->nl;
  MMState     *s  = &nm->state;
  PetscReal    scale, fscale = 0, res = PETSC_MAX_REAL, res_prev = PETSC_MAX_REAL, tol = nl->rtol;
  PetscInt     stalls = 0;
  PetscBool    rebuilt = PETSC_FALSE;

  PetscFunctionBeginUser;
  *solved = PETSC_FALSE;
  nl->el.visc = nm->damping.beta / dt;
  PetscCall(FixedRHS(nm, dt, (PetscBool)(x != w), nl->bnl, &fscale));
  PetscCall(MMElasticityLocal(&nl->el, nm->op, nm->loads, s->u, t0, nl->el.l0));
  PetscCall(MMElasticitySetStepStart(&nl->el, nm->op, nl->el.l0));
  if (nl->policy == MM_TANGENT_STEP) PetscCall(RebuildTangent(nm, dt, nl->el.l0, t0));
  PetscCall(Correction(nm, t0 + dt, w, x, nl->c, &scale));
  PetscCall(MMAndersonReset(&nl->aa));
  for (nl->its = 1; nl->its <= nl->max_it; ++nl->its) {
    Vec H = nl->c_prev;
    PetscCall(VecWAXPY(b, 1.0, nl->bnl, nl->c));
    PetscCall(MMFrictionSolve(nm->friction, nm->hist.step, nm->hist.time, b, x, s->react, solved));
    nl->friction_failed = (PetscBool)!*solved; /* the rejection says which failed (newmark.c) */
    if (!*solved) PetscFunctionReturn(0);
    if (x != w) PetscCall(VecWAXPY(w, 1.0, s->u_old, x));
    PetscCall(Correction(nm, t0 + dt, w, x, H, &scale));
    /* the residual of the nonlinear step at w: the correction there, H(c), less the one its solve used, c */
    PetscCall(VecAXPY(nl->c, -1.0, H));
    PetscCall(VecNorm(nl->c, NORM_2, &res));
    PetscCall(VecAXPY(nl->c, 1.0, H));
    res /= PetscMax(PetscMax(scale, fscale), PETSC_SMALL * PETSC_SMALL);
    nl->residual = res;
    if (nl->its == 1) PetscCall(Tolerance(nm, b, PetscMax(PetscMax(scale, fscale), PETSC_SMALL * PETSC_SMALL), &tol));
    PetscCall(PetscInfo(NULL, "finite-strain step %" PetscInt_FMT " iteration %" PetscInt_FMT ": residual %.3e\n", nm->hist.step + 1, nl->its, (double)res));
    if (res <= tol) {
      PetscBool done;
      PetscCall(Accepted(nm, w, H, dt, b, PetscMax(PetscMax(scale, fscale), PETSC_SMALL * PETSC_SMALL), &tol, &done));
      if (done) break;
      PetscCall(MMAndersonUpdate(&nl->aa, nl->c, H));
      res_prev = PETSC_MAX_REAL; /* tighter solves: a new contraction, no stall to compare with */
      continue;
    }
    /* short of the tolerance, a residual that no audit can see ends the step too */
    if (res <= nl->rtol_audit) {
      PetscBool below;
      Vec       r; /* the whole residual: with an iterative solve, its own residual is not in c - H */
      PetscCall(VecWAXPY(nl->f, 1.0, nl->bnl, H));
      PetscCall(MMCertificateResidualOfIterate(nm, nl->f, w, &r));
      PetscCall(BelowTheAudits(nm, w, r, dt, &below));
      if (below) {
        tol = res;
        break;
      }
    }
    /* stalled within ten times the tolerance: the round-off floor of the force (the discrete gradient's quotient, the
     * contact solves' tolerance) is reached. With iterative solves the tolerance is theirs (Tolerance), which
     * an iteration matrix far from the tangent makes large: the whole residual is checked as at the
     * tolerance (Accepted), and the iteration goes on with tighter solves where it is above the audits */
    if (res <= 10 * tol && res > 0.5 * res_prev) {
      PetscBool done;
      PetscCall(Accepted(nm, w, H, dt, b, PetscMax(PetscMax(scale, fscale), PETSC_SMALL * PETSC_SMALL), &tol, &done));
      if (done) {
        tol = res;
        break;
      }
      PetscCall(MMAndersonUpdate(&nl->aa, nl->c, H));
      res_prev = PETSC_MAX_REAL;
      continue;
    }
    /* stalled farther from it: the step is done when its whole residual meets its certificate
     * (certificate.c): a slender part's internal force is a small difference of large element forces,
     * and its relative residual cannot go below their rounding. Flat twice running within a thousand
     * round-offs, it is at its floor: accepted there (and counted), never cut for it (docs/method.md
     * section 13, "The step's iteration"); a slow fall still far from it goes on (a new tangent) */
    stalls = res > 0.5 * res_prev ? stalls + 1 : 0;
    if (stalls) {
      MMStepCertificate cert;
      PetscCall(ForceRoundoffScale(nm, w, nl->c_scale));
      PetscCall(VecWAXPY(nl->f, 1.0, nl->bnl, H));
      PetscCall(MMCertificateOfIterate(nm, nl->f, w, nl->c_scale, &cert));
      PetscCall(PetscInfo(NULL, "finite-strain step %" PetscInt_FMT " stalled at %.3e: its residual's defects are %.3g round-offs of their terms, its size %.3g\n", nm->hist.step + 1, (double)res, (double)cert.ratio, (double)cert.size));
      /* and only where the residual itself is at the round-off of its terms: a stalled iteration's
       * residual can be large and still do no work over the step (on the slender cantilever with
       * -nonlinear_tangent step, 2.7e-5 of the force scale with no work, then 5e-2) */
      if (cert.size <= MM_CERT_ROUNDOFFS && (cert.ratio <= 1 || (stalls >= 2 && cert.ratio <= MM_CERT_FLOOR_ROUNDOFFS))) {
        /* at or below 1 the step meets its certificate: exact, at a residual -nonlinear_rtol cannot see */
        if (cert.ratio > 1) MMCertificateAtFloor(&nm->cert, cert.ratio);
        tol = res;
        break;
      }
    }
    if (nl->policy == MM_TANGENT_AUTO && (res > res_prev || (!rebuilt && res > nl->refresh * res_prev))) {
      /* a slow contraction: the iteration matrix is far from the tangent (large rotations). Once per
       * step: a tangent rebuilt again where the contraction stays slow (compressed cells, whose matrix
       * is stiffer than the force: elasticity.c) would only reset the acceleration, which is what
       * converges then (issue 50). A residual that grows rebuilds it again. */
      rebuilt = PETSC_TRUE;
      PetscCall(RebuildTangent(nm, dt, nl->el.l1, t0 + dt));
      PetscCall(Correction(nm, t0 + dt, w, x, nl->c, &scale));
      PetscCall(MMAndersonReset(&nl->aa));
      res_prev = PETSC_MAX_REAL;
      stalls   = 0;
      continue;
    }
    PetscCall(MMAndersonUpdate(&nl->aa, nl->c, H));
    res_prev = res;
  }
  *solved = (PetscBool)(res <= tol);
  PetscFunctionReturn(0);
}

/* A step that failed after rebuilding its iteration matrix took the tangent at one of its iterates,
 * which may be far from any state of the motion (a diverging iteration's): the retry starts from the
 * tangent at the step's start u^n instead (el.l0, Iterate), K~ rebuilt on it by the retry's
 * MMNewmarkSetStep. Kept, such a tangent made the svk ball's retries stall with a right-hand side
 * 1e10 times the forces' size, and a step with balance 0.15 was accepted (issue 50). A tangent with
 * its compressed cells as they are (-nonlinear_tangent_clamp 0) may have made K~ indefinite: from
 * here on the run clamps them (docs/method.md section 13, "The iteration matrix"). */
static PetscErrorCode ForgetFailedTangent(MMNewmark nm, PetscReal t0)
{
  MMNonlinear *nl = &nm->nl;

  PetscFunctionBeginUser;
  if (!nl->clamp) {
    nl->clamp      = PETSC_TRUE;
    nl->clamp_step = nm->hist.step + 1;
    PetscCall(PetscInfo(NULL, "finite-strain step %" PetscInt_FMT " was rejected with the unclamped tangent: the tangent is clamped from here on\n", nl->clamp_step));
  }
  if (nl->policy != MM_TANGENT_AUTO) PetscFunctionReturn(0); /* reference keeps K; step builds its own */
  PetscCall(MMNonlinearBuildTangent(nm, nm->nl.el.l0, t0));
  PetscFunctionReturn(0);
}

/* One step: w holds the predictor on entry, u^{n+1} on success; b is contact's right-hand side vector.
 * *solved false: the friction solver or the iteration did not converge (the caller rejects the step).
 * With -step_increments every iterate solves for the increment du = w - u^n (docs/method.md section
 * 13, "The step's unknown"), its bounds and the step's offset taken from u^n as the linear step's
 * (step_laws.c): the right-hand side is then of the forces' size, without the 4/dt^2 M* u^n whose
 * rounding, and an iterative solve's tolerance relative to it, the step's residual would keep. */
PetscErrorCode MMNonlinearSolve(MMNewmark nm, PetscReal t0, PetscReal dt, Vec b, Vec w, PetscBool *solved)
{
  MMNonlinear *nl = &nm->nl;
  MMState     *s  = &nm->state;
  PetscReal    ctol;
  PetscInt     rebuilds;

  PetscFunctionBeginUser;
  s->has_du = PETSC_FALSE;
  rebuilds  = nl->rebuilds;
  PetscCall(MMContactGetSolveTolerance(nm->contact, &ctol, NULL));
  if (!nm->increments) PetscCall(Iterate(nm, t0, dt, b, w, w, solved));
  else {
    PetscCall(VecWAXPY(s->du, -1.0, s->u_old, w)); /* the predictor's increment */
    s->has_du = PETSC_TRUE; /* the iterate's certificate measures du's residual (certificate.c) */
    PetscCall(MMNewmarkSchemeIncrement(nm, dt, PETSC_TRUE));
    PetscCall(MMContactShiftBounds(nm->contact, s->u_old, PETSC_TRUE));
    PetscCall(Iterate(nm, t0, dt, b, w, s->du, solved));
    PetscCall(MMContactShiftBounds(nm->contact, s->u_old, PETSC_FALSE));
    PetscCall(MMNewmarkSchemeIncrement(nm, dt, PETSC_FALSE));
    s->has_du = *solved;
  }
  if (!*solved && (nl->rebuilds > rebuilds || (nl->use_tangent && !nl->clamp))) PetscCall(ForgetFailedTangent(nm, t0));
  PetscCall(MMContactSetSolveTolerance(nm->contact, ctol)); /* tightened for this step only (Accepted) */
  nl->its_total += PetscMin(nl->its, nl->max_it);
  nl->steps++;
  if (*solved) PetscCall(KeepMeanContactForce(s));
  PetscFunctionReturn(0);
}

/* W_d = -(alpha du.M* du + beta sum |T| dE : D : dE)/dt <= 0, the damping's work over the step from u_old to u
 * (docs/method.md section 13): computed from the strains, apart from the force the step balanced */
PetscErrorCode MMNonlinearDampingWork(MMNewmark nm, Vec du, PetscReal t1, PetscReal dt, PetscReal *w)
{
  MMContactOperators ops;
  MMDamping         *d  = &nm->damping;
  MMElasticity      *el = &nm->nl.el;
  PetscScalar        duMdu = 0;
  PetscReal          diss  = 0;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  *w = 0;
  if (!MMDampingOn(d)) PetscFunctionReturn(0);
  if (d->alpha != 0) {
    PetscCall(MatMult(ops.Mstar, du, nm->nl.f)); /* du is the state's work vector */
    PetscCall(VecDot(du, nm->nl.f, &duMdu));
  }
  if (d->beta != 0) {
    PetscCall(MMElasticityLocal(el, nm->op, nm->loads, nm->state.u, t1, el->l1));
    PetscCall(MMElasticityDissipation(el, nm->op, nm->material, el->l1, &diss));
  }
  *w = -(d->alpha * PetscRealPart(duMdu) + d->beta * diss) / dt;
  PetscFunctionReturn(0);
}

/* -contact_frames follow (docs/method.md section 8, "Frames that follow the contact point"): at the
 * step's start the frames of the nodes near a curved obstacle follow their position at the step's predicted midpoint (handed by the law's begin, step_laws.c, from scheme.c). The
 * Cartesian state is unchanged: contact turns the frame components of the stepper's registered data
 * by R (RegisterFrameData: u, v, a, the reactions, the load parts, the iteration stiffness); the
 * momentum functionals follow the frame state (momenta.c). M* does not turn with them, it is rebuilt
 * (the massless dofs lie along the new normals), so the kinetic energy 1/2 v.M* v moves by W_frame =
 * 1/2 v.(M*_new - M*_old) v: booked in the balance (work_frame), not hidden in its residual. The
 * elastic energy, a function of the Cartesian displacement, does not move. */
PetscErrorCode MMNonlinearFollowFrames(MMNewmark nm, PetscReal t, PetscReal dt, Vec midpoint)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  PetscInt           turned;
  PetscReal          kinetic_old = nm->hist.kinetic; /* 1/2 v.M*_old v of the last accepted step (no moving Dirichlet data here) */

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactFramesUpdate(nm->contact, s->u, midpoint, t + 0.5 * dt, &turned));
  if (!turned) PetscFunctionReturn(0);
  {
    PetscScalar vMv;
    PetscCall(MatMult(ops.Mstar, s->v, s->work));
    PetscCall(VecDot(s->v, s->work, &vMv));
    s->work_frame += 0.5 * PetscRealPart(vMv) - kinetic_old;
  }
  PetscFunctionReturn(0);
}

/* After a solved step, at most 3 times a step; *again: the caller solves the step again from its start.
 * - Large sliding: the slave nodes that ended inside the master surface (deeper than
 *   -contact_pairs_depth h_c') take the row of where they ended (MMContactPairsRefine). The state,
 *   still the step's start, is carried to the new variables with its Cartesian value unchanged, and
 *   M* does not change (docs/method.md section 11, "Large sliding").
 * - Frames that follow: the nodes that ended inside their obstacle (deeper than -contact_frames_depth
 *   h_c') take the frame and bound of where they ended (MMContactFramesRefine). The state turns with
 *   the frames; the kinetic energy the rebuilt M* moves, 1/2 v.(M*_new - M*_old) v, is booked as at a
 *   step's start (work_frame).
 * The step's reaction, already its mean (KeepMeanContactForce), goes with it as the retry's warm start. */
PetscErrorCode MMNonlinearRefineStep(MMNewmark nm, PetscReal t0, PetscReal dt, Vec w, PetscInt tries, PetscBool *again)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  PetscInt           turned;
  PetscScalar        before, after;
  PetscBool          paired;

  PetscFunctionBeginUser;
  *again = PETSC_FALSE;
  if (tries > 3) PetscFunctionReturn(0);
  PetscCall(MMContactPairsRefine(nm->contact, w, &paired));
  if (paired) {
    PetscCall(DropPairingOperators(nm));
    *again = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, s->v, s->work));
  PetscCall(VecDot(s->v, s->work, &before));
  PetscCall(MMContactFramesRefine(nm->contact, w, t0 + dt, &turned));
  if (!turned) PetscFunctionReturn(0);
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MatMult(ops.Mstar, s->v, s->work));
  PetscCall(VecDot(s->v, s->work, &after));
  s->work_frame += 0.5 * PetscRealPart(after - before);
  *again = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkRestoreFrames - Restores, on -restart, the contact frames of a run whose frames followed
  the contact point

  Collective

  Input Parameters:
+ nm       - the stepper's context
. rec      - per owned contact row the checkpoint's frame record, or NULL (MMCheckpointGetFrames())
- counters - the frames' counters

  Note:
  -restart of a run whose frames followed (docs/method.md section 9): contact takes the checkpoint's
  frames and gaps (rec, per owned contact row; NULL: the checkpoint has none, the set-up frames
  stay) and turns its operators with the stepper's registered set-up data (the load parts, the
  iteration stiffness). The state, read from the checkpoint, is
  already in these frames: it does not turn, and no kinetic energy moves (M* is the checkpointed
  run's).

  Level: developer

.seealso: `MMCheckpointGetFrames()`, `MMNewmarkRestorePairs()`, `MMNewmarkRestoreTangent()`
@*/
PetscErrorCode MMNewmarkRestoreFrames(MMNewmark nm, const PetscScalar rec[], const PetscReal counters[])
{
  PetscInt turned;

  PetscFunctionBeginUser;
  if (!rec) PetscFunctionReturn(0);
  PetscCall(MMContactFramesRestore(nm->contact, rec, counters, &turned));
  PetscFunctionReturn(0);
}

/*@
  MMNonlinearView - Prints the closing summary's line of the finite-strain step: iterations per step
  and iteration-matrix rebuilds

  Collective

  Input Parameters:
+ nm     - the stepper's context
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `MMDeformationView()`, `TSView()`
@*/
PetscErrorCode MMNonlinearView(MMNewmark nm, PetscViewer viewer)
{
  const MMNonlinear *nl = &nm->nl;
  PetscBool          ascii;
  char               clamp[96] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!nm->material->finite || !ascii) PetscFunctionReturn(0);

  if (nl->clamp_step) PetscCall(PetscSNPrintf(clamp, sizeof(clamp), ", clamped from step %" PetscInt_FMT " (a step with the unclamped tangent was rejected)", nl->clamp_step));
  else if (nl->clamp) PetscCall(PetscStrncpy(clamp, ", clamped (-nonlinear_tangent_clamp)", sizeof(clamp)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  finite strain: %.2f iterations per step (%" PetscInt_FMT " over %" PetscInt_FMT " steps), iteration matrix %s, %" PetscInt_FMT " tangent rebuilds%s\n", (double)nl->its_total / (double)PetscMax(nl->steps, 1), nl->its_total, nl->steps,
                                   MMTangentPolicies[nl->policy], nl->rebuilds, clamp));
  PetscFunctionReturn(0);
}
