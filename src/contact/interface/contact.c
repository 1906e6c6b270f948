/* The contact object's interface: its life cycle (create, view, destroy), the registry of contact
 * formulations, the step matrix K~ for a dt, the step's contact solve in the chosen formulation
 * (through its ops table, contactimpl.h), and the consistent initial contact dofs.
 *
 * Each step solves the bound-constrained QP  min 1/2 w.K~w - b.w  s.t.  w_c <= g: with SNESVI
 * (vinewtonrsls by default, prefix -contact_), condensed on the contact dofs (the default,
 * impls/condensed/) or on all dofs (impls/full/), or by the active-set method on all dofs
 * (impls/active_set/). Without contact each step is one K~ solve (impls/none/, through kt.c). */
#include "../contactimpl.h"
#include "fem.h"

PetscFunctionList        MMContactList              = NULL; /* options.c reads every formulation's options */
static PetscBool         MMContactRegisterAllCalled = PETSC_FALSE;

/*@
  MMContactCreate - Creates an empty contact object

  Collective

  Input Parameter:
. comm - the run's communicator

  Output Parameter:
. ct - the new contact object

  Note:
  An empty contact object: MMContactSetFromOptions reads its options, MMContactSetUp builds the
  contact set and the formulation.

  Level: beginner

.seealso: `MMContactSetFromOptions()`, `MMContactSetUp()`, `MMContactDestroy()`
@*/
PetscErrorCode MMContactCreate(MPI_Comm comm, MMContact *ct)
{
  PetscFunctionBeginUser;
  PetscCall(MMContactInitializePackage());
  PetscCall(PetscNew(ct));
  (*ct)->comm = comm;
  PetscFunctionReturn(0);
}

/*@
  MMContactRegister - Adds a contact formulation to those -contact_formulation chooses from

  Not collective

  Input Parameters:
+ name   - the formulation's name
- create - the function that sets the ops table of the MMContact it is given

  Note:
  Adds a contact formulation: create sets the ops table of the MMContact it is given.

  Level: developer

.seealso: `MMContactRegisterAll()`
@*/
PetscErrorCode MMContactRegister(const char name[], PetscErrorCode (*create)(MMContact))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&MMContactList, name, create));
  PetscFunctionReturn(0);
}

/*@
  MMContactRegisterAll - Registers the contact formulations condensed, full and active_set, once

  Not collective

  Level: developer

.seealso: `MMContactRegister()`
@*/
PetscErrorCode MMContactRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (MMContactRegisterAllCalled) PetscFunctionReturn(0);
  MMContactRegisterAllCalled = PETSC_TRUE;
  PetscCall(MMContactRegister("condensed", MMContactCreate_Condensed));
  PetscCall(MMContactRegister("full", MMContactCreate_Full));
  PetscCall(MMContactRegister("active_set", MMContactCreate_ActiveSet));
  PetscFunctionReturn(0);
}

/* The global dofs, Dirichlet dofs excluded */
static PetscErrorCode GlobalDofs(MMContact ct, PetscInt *n)
{
  PetscSection gs;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(ct->dm, &gs));
  PetscCall(PetscSectionGetConstrainedStorageSize(gs, n));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, n, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ct->dm)));
  PetscFunctionReturn(0);
}

/* ct->ops of -contact_formulation, or of "none" (K~ solves alone) without contact. auto is resolved
 * by the cost model (cost.c) with contact, and without it K~'s solver (factor or CG) by the linear
 * path's cost model, or by -iterative_dofs when given (README "Large meshes"; docs/scaling.md, "The
 * linear path chosen by cost"). With contact it runs after the contact dofs are built: the model
 * needs h_c' and the friction corners; without, it needs the smallest cell's diameter. */
PetscErrorCode MMContactSetType(MMContact ct)
{
  PetscErrorCode (*create)(MMContact) = NULL;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MMContactRegisterAll());
  PetscCall(GlobalDofs(ct, &n));
  ct->prefer_iterative = (PetscBool)(ct->opt.iterative_dofs > 0 && n >= ct->opt.iterative_dofs);
  if (!ct->enabled && ct->opt.iterative_dofs < 0) PetscCall(MMContactChooseLinearPath(ct, n));
  PetscCall(PetscStrcmp(ct->opt.contact_formulation, "auto", &ct->auto_type));
  if (ct->auto_type && ct->enabled) PetscCall(MMContactChooseFormulation(ct, n));
  PetscCall(PetscFunctionListFind(MMContactList, ct->opt.contact_formulation, &create));
  PetscCheck(create || ct->auto_type, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_USER_INPUT, "-contact_formulation %s is not a contact formulation: use auto (the default), condensed, full or active_set", ct->opt.contact_formulation);
  if (!ct->enabled) create = MMContactCreate_None;
  PetscCall(PetscStrncpy(ct->type, ct->enabled ? ct->opt.contact_formulation : "none", sizeof(ct->type)));
  PetscCall((*create)(ct));
  PetscFunctionReturn(0);
}

/*@
  MMContactGetNormalReactions - Gives the normal reactions of the last contact solve, one per
  contact row

  Collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. s - the normal reactions rho_n

  Note:
  s = the normal reactions rho_n of the last solve, one per contact node (a threshold loop's), from the
  reactions every formulation that solves for them keeps in ct->rho

  Level: intermediate

.seealso: `MMContactSetFrictionThresholds()`
@*/
PetscErrorCode MMContactGetNormalReactions(MMContact ct, Vec s)
{
  PetscFunctionBeginUser;
  PetscCheck(ct->rho, ct->comm, PETSC_ERR_SUP, "The contact formulation %s keeps no reactions", ct->type);
  PetscCall(VecStrideGather(ct->rho, 0, s, INSERT_VALUES));
  PetscFunctionReturn(0);
}

/* K~, the KSP that holds its factor or PC (ksp: the formulation's own) and its dt swapped with the
 * kept ones (-contact_K_keep); what else the formulation built on K~ it swaps itself. */
PetscErrorCode MMContactSwapKeptOperator(MMContact ct, KSP *ksp)
{
  MMKtKept *k = &ct->kept;
  Mat       A = ct->qp.A;
  KSP       s = *ksp;
  PetscReal dt = ct->Kt_dt;

  PetscFunctionBeginUser;
  ct->qp.A  = k->A;
  *ksp      = k->ksp;
  ct->Kt_dt = k->dt;
  k->A      = A;
  k->ksp    = s;
  k->dt     = dt;
  PetscFunctionReturn(0);
}

/* What the arithmetic cannot carry in K~ = ck K + cm M*, refused before a factorization fails on it
 * with a raw trace (-rho 1e-300 and -ts_dt 1e-300 stopped in pc_schursplit.c with status 56):
 * - 4/dt^2 M* overflows (dt below about 1e-150);
 * - the mass term, which alone holds the rigid motions (K's kernel), below the round-off of the
 *   stiffness: K~ is then singular in floating point. ck k / (cm m) is about (c_p dt / h)^2 / 4,
 *   so this is c_p dt / h_c' beyond about 1e7 (the factorization broke at 9e8 on D1, and from 1e5 on
 *   the energy audit already stops the run: the solves lose digits to the conditioning);
 * - the stiffness below the round-off of the mass term (c_p dt / h_c' below about 1e-7): the
 *   elastic forces would not enter the step.
 * k and m are the largest diagonal entries of ck K and cm M*, m_min the smallest positive one of
 * cm M* (the contact normals have none). */
static PetscErrorCode CheckStepMatrixArithmetic(MMContact ct, PetscReal dt, PetscReal ck, PetscReal cm)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)ct->dm);
  const PetscReal    room = 1e2 * PETSC_MACHINE_EPSILON; /* a factor 100 from where the round-off takes all */
  Vec                d;
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          k[2] = {0, 0}, m_min = PETSC_MAX_REAL, cfl = ct->enabled ? ct->material->c_p_max * dt / ct->h_c : -1;
  char               ratio[64] = "";

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(ct->K, &d, NULL));
  PetscCall(VecGetLocalSize(d, &n));
  PetscCall(MatGetDiagonal(ct->K, d));
  PetscCall(VecGetArrayRead(d, &a));
  for (PetscInt i = 0; i < n; ++i) k[0] = PetscMax(k[0], PetscAbsReal(PetscRealPart(a[i])));
  PetscCall(VecRestoreArrayRead(d, &a));
  PetscCall(MatGetDiagonal(ct->mass.Mstar, d));
  PetscCall(VecGetArrayRead(d, &a));
  for (PetscInt i = 0; i < n; ++i) {
    const PetscReal mi = PetscRealPart(a[i]);
    k[1] = PetscMax(k[1], mi);
    if (mi > 0) m_min = PetscMin(m_min, mi);
  }
  PetscCall(VecRestoreArrayRead(d, &a));
  PetscCall(VecDestroy(&d));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, k, 2, MPIU_REAL, MPIU_MAX, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &m_min, 1, MPIU_REAL, MPIU_MIN, comm));
  if (cfl >= 0) PetscCall(PetscSNPrintf(ratio, sizeof(ratio), " (c_p dt / h_c' = %.3g)", (double)cfl));
  /* -E 1e308 and -rho 1e308 (overflow) and -rho 1e-310 (underflow) were refused with the operators (fem.c) */
  PetscCheck(!PetscIsInfOrNanReal(cm) && !PetscIsInfOrNanReal(cm * k[1]), comm, PETSC_ERR_USER_INPUT, "-ts_dt %.6g is too small for double precision: the step matrix's mass term 4/dt^2 M overflows%s. Give a dt near h_c' / c_p, the time a wave takes to cross a contact cell", (double)dt, ratio);
  PetscCheck(ck * k[0] <= cm * m_min / room, comm, PETSC_ERR_USER_INPUT, "The step matrix K + 4/dt^2 M cannot be formed in double precision with dt = %.6g, -E %.6g, -rho %.6g%s: the mass term, which alone holds the rigid motions, is %.2g of the stiffness, below its round-off, and K + 4/dt^2 M is singular in floating point. Check the units (SI throughout: the mesh in metres, -E in Pa, -rho in kg/m^3), or reduce -ts_dt to about h_c' / c_p",
             (double)dt, (double)ct->pb.E, (double)ct->pb.rho, ratio, (double)(cm * m_min / (ck * k[0])));
  PetscCheck(ck * k[0] >= room * cm * k[1], comm, PETSC_ERR_USER_INPUT, "The step matrix K + 4/dt^2 M cannot be formed in double precision with dt = %.6g, -E %.6g, -rho %.6g%s: the stiffness is %.2g of the mass term, below its round-off, so the elastic forces would not enter the step. Check the units (SI throughout: the mesh in metres, -E in Pa, -rho in kg/m^3), or give a dt near h_c' / c_p",
             (double)dt, (double)ct->pb.E, (double)ct->pb.rho, ratio, (double)(ck * k[0] / (cm * k[1])));
  PetscFunctionReturn(0);
}

/* K~ = ck K + cb B + cm M* from A = K (a copy, K's pattern: fem's K or the finite-strain step's
 * iteration stiffness); with B = K, (ck + cb) K as one scaling (docs/method.md section 3). Every
 * formulation's K~ is built here. */
static PetscErrorCode StepMatrixAssemble(MMContact ct, const MMStepMatrix *sm, Mat K, Mat A)
{
  PetscFunctionBeginUser;
  if (sm->B && sm->B == K) PetscCall(MatScale(A, sm->ck + sm->cb));
  else {
    if (sm->ck != 1) PetscCall(MatScale(A, sm->ck));
    if (sm->B) PetscCall(MatAXPY(A, sm->cb, sm->B, SUBSET_NONZERO_PATTERN));
  }
  PetscCall(MatAXPY(A, sm->cm, ct->mass.Mstar, SUBSET_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetStepMatrix - Sets the step matrix K~ = ck K + cb B + cm M* for a dt, and the
  formulation's factor, Delassus operator or PC on it

  Collective

  Input Parameters:
+ ct - the contact object
- sm - the step matrix's dt, coefficients and stiffness

  Note:
  K~ for sm->dt, its coefficients the stepper's (MMDampingGetStepMatrix), assembled only when dt
  changes; the formulation then builds on it what it needs (a factor and the Delassus operator, a
  PC, nothing).

  Level: intermediate

.seealso: `MMContactSolve()`, `MMContactSetStepOffset()`
@*/
PetscErrorCode MMContactSetStepMatrix(MMContact ct, const MMStepMatrix *sm)
{
  const PetscReal dt = sm->dt;
  const Mat       K  = sm->K ? sm->K : ct->K;

  PetscFunctionBeginUser;
  if (ct->qp.A && ct->Kt_dt == dt && ct->Kt_version == sm->version) PetscFunctionReturn(0);
  /* the kept factors are of fem's K: a tangent's K~ is built anew */
  if (ct->qp.A && ct->ops->swapkept && ct->opt.keep_factor && !sm->K) {
    PetscBool hit;
    PetscCall(PetscLogEventBegin(MMCONTACT_KtReuse, 0, 0, 0, 0));
    PetscCall((*ct->ops->swapkept)(ct, dt, &hit));
    PetscCall(PetscLogEventEnd(MMCONTACT_KtReuse, 0, 0, 0, 0));
    if (hit) PetscFunctionReturn(0);
    /* else the current buffers are the older kept ones, or none yet: K~ for dt is built in them */
  }
  PetscCall(PetscLogEventBegin(MMCONTACT_Assemble, 0, 0, 0, 0));
  if (!ct->qp.b) {
    PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &ct->qp.A));
    PetscCall(MatCreateVecs(ct->qp.A, &ct->qp.b, NULL));
    ct->qp.rtol_b = ct->tol;
    if (ct->ops->setup) PetscCall((*ct->ops->setup)(ct));
  } else if (!ct->qp.A) PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &ct->qp.A));
  else PetscCall(MatCopy(K, ct->qp.A, SAME_NONZERO_PATTERN));
  /* B is K or K with the massless dofs condensed out, no larger: ck + cb bounds the stiffness */
  PetscCall(CheckStepMatrixArithmetic(ct, dt, sm->ck + sm->cb, sm->cm));
  PetscCall(StepMatrixAssemble(ct, sm, K, ct->qp.A));
  /* K~ is SPD for every dt: K is semi-definite with the rigid motions as its kernel, and M* is
   * positive on every rigid motion (docs/method.md, "Mass redistribution": G(M*) = G(M)). Said
   * once and for all, so that MUMPS factors it as SPD (SYM = 1: LDL^T without pivoting), faster
   * and smaller than as symmetric indefinite (the figures: docs/scaling.md, "The figures behind the code's choices") */
  PetscCall(MatSetOption(ct->qp.A, MAT_SPD, PETSC_TRUE));
  PetscCall(MatSetOption(ct->qp.A, MAT_SPD_ETERNAL, PETSC_TRUE));
  ct->Kt_dt      = dt;
  ct->Kt_version = sm->version;
  if (ct->ops->setoperator) PetscCall((*ct->ops->setoperator)(ct));
  PetscCall(PetscLogEventEnd(MMCONTACT_Assemble, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetStepOffset - Gives contact the time scheme's share of the step: the offset, the scale
  and the step velocity

  Logically collective

  Input Parameters:
+ ct - the contact object
- so - the step's offset (copied, its vector and context borrowed)

  Note:
  The step's offset and scale from the stepper (include/contact.h): the trapezoidal scheme is the
  stepper's, and contact takes the tangential bounds and slip velocities from these alone.

  Level: intermediate

.seealso: `MMContactGetStepOffset()`, `MMContactStepVelocity()`, `MMContactSetStepMatrix()`
@*/
PetscErrorCode MMContactSetStepOffset(MMContact ct, const MMStepOffset *so)
{
  PetscFunctionBeginUser;
  ct->step = *so;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetStepOffset - Gives the step's offset the stepper last set

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. so - the step's offset

  Level: developer

.seealso: `MMContactSetStepOffset()`
@*/
PetscErrorCode MMContactGetStepOffset(MMContact ct, MMStepOffset *so)
{
  PetscFunctionBeginUser;
  *so = ct->step;
  PetscFunctionReturn(0);
}

/*@
  MMContactStepVelocity - Computes the velocity of w over the step with the stepper's function

  Collective

  Input Parameters:
+ ct - the contact object, its step offset set
- w  - the w-frame state

  Output Parameter:
. sigma - its velocity over the step

  Note:
  sigma = the velocity of w over the step, as the stepper computes it

  Level: developer

.seealso: `MMContactSetStepOffset()`
@*/
PetscErrorCode MMContactStepVelocity(MMContact ct, Vec w, Vec sigma)
{
  PetscFunctionBeginUser;
  PetscCheck(ct->step.velocity, PetscObjectComm((PetscObject)w), PETSC_ERR_ORDER, "The stepper has not handed contact the step's offset (MMContactSetStepOffset)");
  PetscCall((*ct->step.velocity)(ct->step.ctx, w, sigma));
  PetscFunctionReturn(0);
}

/* react = K~ w - b on the contact dofs: recomputed from w whatever the formulation, so that the
 * energy audit checks the solve. */
PetscErrorCode MMContactForce(MMContact ct, Vec b, Vec w, Vec react)
{

  PetscFunctionBeginUser;
  PetscCall(MatMult(ct->qp.A, w, react));
  PetscCall(VecAXPY(react, -1.0, b));
  /* off the contact nodes the residual is solver noise, not a force */
  PetscCall(VecISSet(react, ct->is_interior, 0.0));
  if (ct->ncomp == 1) PetscCall(VecISSet(react, ct->is_tangent, 0.0));
  PetscFunctionReturn(0);
}

/* The reactions rho and their bounds, one block of ncomp per contact node: the layout the friction
 * loop and the diagnostics read, whatever the formulation. Frictionless until thresholds are set:
 * rho_t in [0, 0]. */
PetscErrorCode MMContactCreateReactions(MMContact ct)
{

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)ct->dm), ct->ncomp * ct->n_local, PETSC_DETERMINE, &ct->rho));
  PetscCall(VecSetBlockSize(ct->rho, ct->ncomp));
  PetscCall(VecZeroEntries(ct->rho));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_lo));
  PetscCall(VecDuplicate(ct->rho, &ct->rho_hi));
  PetscCall(VecSet(ct->rho_lo, 0.0));
  PetscCall(VecSet(ct->rho_hi, 0.0));
  PetscCall(VecStrideSet(ct->rho_hi, 0, PETSC_INFINITY));
  PetscFunctionReturn(0);
}

/*@
  MMContactSolve - Solves the step's contact problem K~ w = b + f_c, w_c <= g, in the chosen
  formulation

  Collective

  Input Parameters:
+ ct - the contact object, its step matrix set
. b  - the right-hand side
- w  - the initial guess, the solution on return (w-frame)

  Output Parameter:
. react - the contact force f_c on the contact dofs (w-frame)

  Note:
  Solves the step problem K~ w = b + f_c with w_c <= g; w holds the initial guess on entry.
  react returns f_c, the obstacle's force on the body (w-frame), on the contact dofs only.

  Level: beginner

.seealso: `MMContactSetStepMatrix()`, `MMContactSolveContactDofs()`, `MMContactSolveCoulomb()`
@*/
PetscErrorCode MMContactSolve(MMContact ct, Vec b, Vec w, Vec react)
{

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_Solve, 0, 0, 0, 0));
  ct->kt.its = 0;
  PetscCall((*ct->ops->solve)(ct, b, w, react));
  PetscCall(PetscLogEventEnd(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactSolveContactDofs - Solves the step's contact problem for the friction loop, at least the
  contact dofs exactly

  Collective

  Input Parameters:
+ ct    - the contact object
. b     - the right-hand side
. w     - the initial guess, updated on return
- react - the contact force, updated on return

  Note:
  The friction loop's solve: at least the contact dofs of w and react are updated, exactly. The
  condensed formulation updates only those, with no full-size solve, and MMContactRecover completes
  w once the loop has converged; the active-set formulation solves on all dofs, warm-started.

  Level: intermediate

.seealso: `MMContactRecover()`, `MMContactSolve()`, `MMContactSetFrictionThresholds()`
@*/
PetscErrorCode MMContactSolveContactDofs(MMContact ct, Vec b, Vec w, Vec react)
{

  PetscFunctionBeginUser;
  PetscCheck(ct->ops->solvecontactdofs, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_PLIB, "The contact formulation %s cannot solve the contact dofs alone", ct->type);
  PetscCall(PetscLogEventBegin(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscCall((*ct->ops->solvecontactdofs)(ct, b, w, react));
  PetscCall(PetscLogEventEnd(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactRecover - Completes the step solution and the contact force from the last contact-dof
  solve

  Collective

  Input Parameters:
+ ct    - the contact object
. b     - the right-hand side
. w     - the solution, completed on return
- react - the contact force, completed on return

  Note:
  The whole step solution and contact force from the last contact-dof solve.

  Level: intermediate

.seealso: `MMContactSolveContactDofs()`, `MMContactSolveCoulomb()`
@*/
PetscErrorCode MMContactRecover(MMContact ct, Vec b, Vec w, Vec react)
{

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMCONTACT_Recover, 0, 0, 0, 0));
  PetscCall((*ct->ops->recover)(ct, b, w, react));
  PetscCall(PetscLogEventEnd(MMCONTACT_Recover, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetFrictionThresholds - Sets the friction thresholds of the formulation's next Tresca
  solves (the active-set formulation)

  Collective

  Input Parameters:
+ ct - the contact object
- s  - the thresholds, one per contact row

  Note:
  Friction thresholds s (one per contact node) for the next Tresca solves of a threshold loop: the
  formulation's own Tresca conditions (active set). The condensed formulation solves Coulomb's
  problem in contact space instead (MMContactSolveCoulomb).

  Level: intermediate

.seealso: `MMContactGetNormalReactions()`, `MMContactSolveContactDofs()`
@*/
PetscErrorCode MMContactSetFrictionThresholds(MMContact ct, Vec s)
{

  PetscFunctionBeginUser;
  PetscCheck(ct->ops->setthresholds, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_PLIB, "The contact formulation %s has no threshold solves", ct->type);
  PetscCall((*ct->ops->setthresholds)(ct, s));
  PetscFunctionReturn(0);
}

/*@
  MMContactHasDelassus - Tells whether the formulation builds the Delassus operator on a candidate
  set

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. has - PETSC_TRUE when a friction solver can work in contact space (MMContactSolveCoulomb())

  Note:
  Whether the formulation builds the Delassus operator on a candidate set, so that a friction
  solver can work in contact space.

  Level: intermediate

.seealso: `MMContactSolveCoulomb()`, `MMContactHasCoulombDofs()`
@*/
PetscErrorCode MMContactHasDelassus(MMContact ct, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = (PetscBool)(ct->ops && ct->ops->solvecoulomb);
  PetscFunctionReturn(0);
}

/*@
  MMContactSolveCoulomb - Solves the step's Coulomb problem in contact space with a friction solver

  Collective

  Input Parameters:
+ ct    - the contact object
. b     - the right-hand side
. w     - the solution, its contact dofs set on return
. react - the contact force, its contact dofs set on return
. fn    - the friction solver of the contact-space problem
- fctx  - its context

  Output Parameter:
. ok - fn's verdict

  Note:
  The step's Coulomb problem solved in contact space by fn: the contact dofs of w and react,
  exactly (MMContactRecover completes w). *ok is fn's verdict.

  Level: intermediate

.seealso: `MMContactHasDelassus()`, `MMContactRecover()`, `MMContactSolveCoulombDofs()`
@*/
PetscErrorCode MMContactSolveCoulomb(MMContact ct, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok)
{

  PetscFunctionBeginUser;
  PetscCheck(ct->ops->solvecoulomb, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_PLIB, "The contact formulation %s has no Delassus operator for a contact-space solve", ct->type);
  PetscCall(PetscLogEventBegin(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscCall((*ct->ops->solvecoulomb)(ct, b, w, react, fn, fctx, ok));
  PetscCall(PetscLogEventEnd(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactHasCoulombDofs - Tells whether the formulation solves the step's Coulomb problem itself
  on all dofs

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. has - PETSC_TRUE for the active-set formulation

  Note:
  Whether the formulation solves the step's Coulomb problem itself on all dofs (no Delassus
  operator: the active-set formulation).

  Level: intermediate

.seealso: `MMContactSolveCoulombDofs()`, `MMContactHasDelassus()`
@*/
PetscErrorCode MMContactHasCoulombDofs(MMContact ct, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = (PetscBool)(ct->ops && ct->ops->solvecoulombdofs);
  PetscFunctionReturn(0);
}

/*@
  MMContactSolveCoulombDofs - Solves the step's Coulomb problem with the formulation's own solve on
  all dofs

  Collective

  Input Parameters:
+ ct    - the contact object
. b     - the right-hand side
. w     - the solution, whole on return
. react - the contact force, whole on return
. s     - the thresholds, a warm start on entry, mu r_n of the answer on return
- rtol  - the tolerance, relative to the force scale

  Output Parameters:
+ its - the solver's iterations
- ok  - PETSC_FALSE when it did not converge

  Note:
  The step's Coulomb problem by the formulation's own solve on all dofs: w and react whole, s (the
  thresholds, a warm start on entry) mu r_n of the answer on return, to rtol of the force scale;
  *its the solver's iterations,
  *ok false when it did not converge.

  Level: intermediate

.seealso: `MMContactHasCoulombDofs()`, `MMContactSolveCoulomb()`
@*/
PetscErrorCode MMContactSolveCoulombDofs(MMContact ct, Vec b, Vec w, Vec react, Vec s, PetscReal rtol, PetscInt *its, PetscBool *ok)
{

  PetscFunctionBeginUser;
  PetscCheck(ct->ops->solvecoulombdofs, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_PLIB, "The contact formulation %s has no Coulomb solve of its own", ct->type);
  PetscCall(PetscLogEventBegin(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscCall((*ct->ops->solvecoulombdofs)(ct, b, w, react, s, rtol, its, ok));
  PetscCall(PetscLogEventEnd(MMCONTACT_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The corner nodes (docs/method.md section 8): how many carry a row per obstacle, and on how many
 * both rows were active at the last step, each wall taking its share of the force. */
static PetscErrorCode CornerView(MMContact ct, PetscViewer viewer)
{
  PetscInt both[2] = {0, 0};

  PetscFunctionBeginUser;
  if (!ct->n_corners) PetscFunctionReturn(0);
  for (PetscInt k = 1; k < ct->n_local; ++k)
    if (ct->second[k]) {
      both[0] += ct->was_active[k] && ct->was_active[k - 1];
      both[1] += ct->was_active[k];
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, both, 2, MPIU_INT, MPI_SUM, ct->comm));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  corners: %" PetscInt_FMT " contact nodes constrained against two obstacles, a row for each; at the last step %" PetscInt_FMT " in contact with both, %" PetscInt_FMT " with the second\n", ct->n_corners, both[0], both[1]));
  PetscFunctionReturn(0);
}

/* The friction corners (docs/method.md section 12): how many, and on how many the second obstacle
 * pushed at the last step (with the first too, or alone). */
static PetscErrorCode FrictionCornerView(MMContact ct, PetscViewer viewer)
{
  PetscInt both[2] = {0, 0};

  PetscFunctionBeginUser;
  if (!ct->n_fc) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < ct->n_local; ++k)
    if (ct->fc_obstacle[k] >= 0 && ct->fc_r[ct->dim * k] > 0) {
      both[0] += ct->was_active[k];
      both[1] += 1;
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, both, 2, MPIU_INT, MPI_SUM, ct->comm));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  friction corners: %" PetscInt_FMT " contact nodes against two obstacles, each obstacle with its own Coulomb law; at the last step %" PetscInt_FMT " in contact with both, %" PetscInt_FMT " pushed by the second\n", ct->n_fc, both[0], both[1]));
  PetscFunctionReturn(0);
}

/*@
  MMContactView - Prints the contact lines of the closing summary

  Collective

  Input Parameters:
+ ct     - the contact object
- viewer - the viewer

  Note:
  The contact lines of the closing summary: the formulation's, then the corners'.

  Level: intermediate

.seealso: `MMContactSetUpView()`, `MMContactMassView()`
@*/
PetscErrorCode MMContactView(MMContact ct, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (ct->ops && ct->ops->view) PetscCall((*ct->ops->view)(ct, viewer));
  if (ct->enabled) PetscCall(CornerView(ct, viewer));
  if (ct->enabled) PetscCall(FrictionCornerView(ct, viewer));
  if (ct->enabled) PetscCall(MMContactFramesView(ct, viewer));
  if (ct->enabled) PetscCall(MMContactMassFreeView(ct, viewer));
  if (ct->enabled && ct->pairs.large) {
    PetscBool ascii;
    PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
    if (ascii) {
      PetscCall(PetscViewerASCIIPrintf(viewer, "  contact pairs, large sliding: pairing changed at %" PetscInt_FMT " step starts, %" PetscInt_FMT " moves of a slave node to another facet; deepest penetration of the current master surface at a step's start %.3e (%.3e h_c')\n", ct->pairs.repairs, ct->pairs.facet_changes,
                                       (double)ct->pairs.penetration, (double)(ct->pairs.penetration / ct->h_c)));
      if (ct->pairs.depth >= 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  contact pairs: %" PetscInt_FMT " extra solves of a step, with the rows of the nodes that ended inside the master taken where they ended (-contact_pairs_depth %g)\n", ct->pairs.resolves, (double)ct->pairs.depth));
    }
  }
  PetscFunctionReturn(0);
}

/* A given initial state that penetrates the obstacle is a wrong case (a plane on the wrong side, a
 * body placed inside it): projecting it would store elastic energy that launches the body. Refuse a
 * penetration deeper than -initial_penetration_tol h_c', naming the deepest node. */
static PetscErrorCode CheckInitialPenetration(MMContact ct, Vec w)
{
  DM                 dm  = ct->dm;
  PetscInt           dim = ct->dim, rstart, deepest = -1;
  const PetscInt    *in;
  const PetscScalar *wa, *ga;
  struct {
    double depth;
    int    rank;
  } loc = {-PETSC_MAX_REAL, 0}, glob;
  PetscReal   x[MM_MAX_DIM] = {0, 0, 0};
  PetscInt    glob_obstacle = 0;
  PetscMPIInt rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)dm);

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  loc.rank = rank;
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal depth = PetscRealPart(wa[in[k] - rstart] - ga[k]);
    if (depth > loc.depth) {
      loc.depth = depth;
      deepest   = k;
    }
  }
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  if (glob.depth <= ct->opt.initial_penetration_tol * ct->h_c) PetscFunctionReturn(0);
  if (rank == glob.rank) {
    PetscSection cs;
    Vec          X;
    PetscInt     off;
    const PetscScalar *xa;
    PetscCall(DMGetCoordinateSection(dm, &cs));
    PetscCall(DMGetCoordinatesLocal(dm, &X));
    PetscCall(PetscSectionGetOffset(cs, ct->vertex[deepest], &off));
    PetscCall(VecGetArrayRead(X, &xa));
    for (PetscInt d = 0; d < dim; ++d) x[d] = PetscRealPart(xa[off + d]);
    PetscCall(VecRestoreArrayRead(X, &xa));
  }
  PetscCallMPI(MPI_Bcast(x, MM_MAX_DIM, MPIU_REAL, glob.rank, comm));
  if (rank == glob.rank) glob_obstacle = ct->obstacle[deepest];
  PetscCallMPI(MPI_Bcast(&glob_obstacle, 1, MPIU_INT, glob.rank, comm));
  /* C's formatting, not PETSc's, which writes 0 as "0." */
  char where[128];
  if (dim == 2) snprintf(where, sizeof(where), "(%g, %g)", (double)x[0], (double)x[1]);
  else snprintf(where, sizeof(where), "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]);
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "The initial state penetrates the obstacle \"%s\": the deepest contact node, at %s, is %g inside it (-initial_penetration_tol %g h_c' = %g). Check that obstacle's position, its -obstacle_..._side, the direction of a plane's normal (it points out of the obstacle, towards the body), and -u0_offset/-u0_gradient",
          ct->pb.obstacles[glob_obstacle].name, where, glob.depth, (double)ct->opt.initial_penetration_tol, (double)(ct->opt.initial_penetration_tol * ct->h_c));
}

/* The initial projection's upper bounds on the massless dofs: the gaps on the normal ones, none on a
 * friction corner's tau_1 (docs/method.md section 12), in the order set.c lists them. */
static PetscErrorCode MasslessUpperBounds(MMContact ct, Vec upper)
{
  const PetscScalar *ga;
  PetscScalar       *ua;
  PetscInt           p = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  PetscCall(VecGetArray(upper, &ua));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    ua[p++] = ga[k];
    if (ct->fc_obstacle && ct->fc_obstacle[k] >= 0) ua[p++] = PETSC_INFINITY;
  }
  PetscCall(VecRestoreArray(upper, &ua));
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscFunctionReturn(0);
}

/*@
  MMContactProjectInitial - Checks the initial penetration and makes the initial massless dofs
  consistent: their quasi-static problem solved with the other dofs fixed

  Collective

  Input Parameters:
+ ct - the contact object
- w  - the initial state (w-frame), its massless dofs set on return

  Note:
  Consistent initial contact dofs (docs/method.md section 3, Initial state): with the other dofs fixed, the
  massless dofs solve the quasi-static problem A_cc u_c = L_c - A_c* u*, u_c <= g on the normal ones.

  Level: intermediate

.seealso: `MMContactProjectInitialCorrect()`, `MMContactSolveStatic()`
@*/
PetscErrorCode MMContactProjectInitial(MMContact ct, Vec w)
{
  Vec        r, rc, wc;
  PetscInt   its;

  PetscFunctionBeginUser;
  if (ct->enabled) PetscCall(CheckInitialPenetration(ct, w));
  if (!ct->mass.massless) PetscFunctionReturn(0);
  PetscCall(MatCreateSubMatrix(ct->K, ct->is_massless, ct->is_massless, MAT_INITIAL_MATRIX, &ct->qp0.A));
  PetscCall(MatCreateVecs(ct->qp0.A, &ct->qp0.b, NULL));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->lower0));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->upper0));
  PetscCall(VecSet(ct->lower0, PETSC_NINFINITY));
  PetscCall(MasslessUpperBounds(ct, ct->upper0));
  ct->qp0.rtol_b = ct->tol;
  PetscCall(MMQPCreate(PetscObjectComm((PetscObject)ct->dm), "contact0_", &ct->qp0, 0, &ct->snes0));
  PetscCall(SNESVISetVariableBounds(ct->snes0, ct->lower0, ct->upper0));

  /* b0 = (L - lift - K w*)_c with the contact dofs zeroed in w* */
  PetscCall(VecDuplicate(w, &r));
  PetscCall(VecCopy(w, r));
  PetscCall(VecISSet(r, ct->is_massless, 0.0));
  PetscCall(VecDuplicate(w, &rc));
  PetscCall(MatMult(ct->K, r, rc));
  PetscCall(VecAYPX(rc, -1.0, ct->load));
  PetscCall(VecAXPY(rc, -1.0, ct->lift));
  PetscCall(VecGetSubVector(rc, ct->is_massless, &wc));
  PetscCall(VecCopy(wc, ct->qp0.b));
  PetscCall(VecRestoreSubVector(rc, ct->is_massless, &wc));

  PetscCall(VecGetSubVector(w, ct->is_massless, &wc));
  PetscCall(VecPointwiseMin(wc, wc, ct->upper0));
  PetscCall(MMQPSolve(ct->snes0, &ct->qp0, wc, &its));
  PetscCall(VecRestoreSubVector(w, ct->is_massless, &wc));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&rc));
  PetscFunctionReturn(0);
}

/*@
  MMContactProjectInitialCorrect - Corrects the initial projection for a finite-strain law by one
  bound-constrained chord step with K

  Collective

  Input Parameters:
+ ct  - the contact object, after MMContactProjectInitial()
. w   - the initial state, its massless dofs corrected on return
- res - the law's residual f(w) - L

  Output Parameter:
. change - the largest change of a dof

  Note:
  A finite-strain law's correction of the projection above: the massless rows' quasi-static equation
  is f(w) = L there, with f the law's internal force, not K w. Given its residual res = f(w) - L (all
  dofs), one chord step with the reference stiffness K, for the increment d: the bound-constrained
  solve of K_cc d = -res_c, w_c + d <= the gap. Solved for the increment, so that the solver's
  tolerance is relative to the residual left, not to K w; its fixed point has res_c = 0 off contact
  and the reaction on the bound. *change is the largest |d|.

  Level: intermediate

.seealso: `MMContactProjectInitial()`
@*/
PetscErrorCode MMContactProjectInitialCorrect(MMContact ct, Vec w, Vec res, PetscReal *change)
{
  Vec      wc, rc, d, upper;
  PetscInt its;

  PetscFunctionBeginUser;
  *change = 0;
  if (!ct->mass.massless || !ct->qp0.A) PetscFunctionReturn(0);
  PetscCall(VecGetSubVector(w, ct->is_massless, &wc));
  PetscCall(VecGetSubVector(res, ct->is_massless, &rc));
  PetscCall(VecAXPBY(ct->qp0.b, -1.0, 0.0, rc));
  PetscCall(VecRestoreSubVector(res, ct->is_massless, &rc));
  PetscCall(VecDuplicate(wc, &d));
  PetscCall(VecDuplicate(wc, &upper));
  PetscCall(VecWAXPY(upper, -1.0, wc, ct->upper0));
  PetscCall(SNESVISetVariableBounds(ct->snes0, ct->lower0, upper));
  PetscCall(VecZeroEntries(d));
  PetscCall(VecPointwiseMin(d, d, upper));
  PetscCall(MMQPSolve(ct->snes0, &ct->qp0, d, &its));
  PetscCall(SNESVISetVariableBounds(ct->snes0, ct->lower0, ct->upper0));
  PetscCall(VecNorm(d, NORM_INFINITY, change));
  PetscCall(VecAXPY(wc, 1.0, d));
  PetscCall(VecDestroy(&d));
  PetscCall(VecDestroy(&upper));
  PetscCall(VecRestoreSubVector(w, ct->is_massless, &wc));
  PetscFunctionReturn(0);
}

/*@
  MMContactDestroy - Destroys a contact object

  Collective

  Input Parameter:
. pct - the contact object (may be NULL)

  Note:
  The formulation frees its data (ops->destroy), then the contact set's own.

  Level: beginner

.seealso: `MMContactCreate()`
@*/
PetscErrorCode MMContactDestroy(MMContact *pct)
{
  MMContact ct = *pct;

  PetscFunctionBeginUser;
  if (!ct) PetscFunctionReturn(0);
  if (ct->ops && ct->ops->destroy) PetscCall((*ct->ops->destroy)(ct));
  PetscCall(SNESDestroy(&ct->snes0));
  PetscCall(KSPDestroy(&ct->kept.ksp));
  PetscCall(SNESDestroy(&ct->snes0));
  PetscCall(MatDestroy(&ct->kept.A));
  PetscCall(KSPDestroy(&ct->kept.ksp));
  PetscCall(MMKtDestroy(&ct->kt));
  PetscCall(VecDestroy(&ct->rho));
  PetscCall(VecDestroy(&ct->rho_lo));
  PetscCall(VecDestroy(&ct->rho_hi));
  PetscCall(ISDestroy(&ct->is_cond));
  PetscCall(VecDestroy(&ct->z));
  PetscCall(MatDestroy(&ct->qp.A));
  PetscCall(VecDestroy(&ct->qp.b));
  PetscCall(MatDestroy(&ct->qp0.A));
  PetscCall(VecDestroy(&ct->qp0.b));
  PetscCall(VecDestroy(&ct->lower));
  PetscCall(VecDestroy(&ct->upper));
  PetscCall(VecDestroy(&ct->lower0));
  PetscCall(VecDestroy(&ct->upper0));
  PetscCall(VecDestroy(&ct->gap));
  PetscCall(VecDestroy(&ct->gap_step));
  PetscCall(VecDestroy(&ct->gap0));
  PetscCall(VecDestroy(&ct->mu));
  PetscCall(PetscFree(ct->slide_ref));
  PetscCall(PetscFree(ct->node_frame));
  PetscCall(PetscFree2(ct->all_gap0, ct->all_nu));
  PetscCall(PetscFree(ct->obstacle));
  PetscCall(MMContactPairsDestroy(&ct->pairs));
  PetscCall(MMContactFramesDestroy(&ct->frames));
  PetscCall(MMContactHeldDestroy(&ct->held));
  PetscCall(MatDestroy(&ct->mass.Mstar));
  PetscCall(MatDestroy(&ct->frame_Kp));
  PetscCall(VecDestroy(&ct->Kt_rowabs));
  PetscCall(MatDestroy(&ct->frame_KpN));
  PetscCall(MMContactTransformDestroy(&ct->transform));
  PetscCall(MatDestroy(&ct->K));
  PetscCall(VecDestroy(&ct->load));
  PetscCall(VecDestroy(&ct->lift));
  PetscCall(ISDestroy(&ct->mass.massless));
  PetscCall(MMContactMassFreeDestroy(&ct->mass));
  PetscCall(PetscFree2(ct->second, ct->corner_ab));
  PetscCall(PetscFree(ct->force_obstacle));
  PetscCall(VecDestroy(&ct->area));
  PetscCall(ISDestroy(&ct->is_normal));
  PetscCall(ISDestroy(&ct->is_massless));
  PetscCall(PetscFree(ct->fc_obstacle));
  PetscCall(PetscFree4(ct->fc_ab, ct->fc_gap0, ct->fc_gap, ct->fc_slide));
  PetscCall(PetscFree2(ct->fc_r, ct->fc_r_old));
  PetscCall(VecDestroy(&ct->fc_geom));
  PetscCall(VecDestroy(&ct->fc_mu));
  PetscCall(VecDestroy(&ct->fc_q));
  PetscCall(VecDestroy(&ct->fc_x));
  PetscCall(ISDestroy(&ct->is_tangent));
  PetscCall(ISDestroy(&ct->is_star));
  PetscCall(ISDestroy(&ct->is_interior));
  PetscCall(PetscFree(ct->was_active));
  PetscCall(PetscFree2(ct->slipping, ct->slip_dir));
  PetscCall(PetscFree(ct->scalar_index));
  PetscCall(PetscFree(ct->vertex));
  PetscCall(PetscFree(*pct));
  PetscFunctionReturn(0);
}

/*@
  MMContactGetStepKSP - Gives the solvers of K~ for the start-up report

  Not collective

  Input Parameter:
. ct - the contact object, set up

  Output Parameters:
+ krylov - the KSP whose method solves with K~
- pc_ksp - the KSP whose PC does

  Note:
  The solvers of K~, for the start-up report: krylov is the KSP whose method solves with K~, pc_ksp
  the one whose PC does (the formulation's getstepksp).

  Level: developer

.seealso: `MMContactGetSolverText()`, `MMContactStepIsIterative()`
@*/
PetscErrorCode MMContactGetStepKSP(MMContact ct, KSP *krylov, KSP *pc_ksp)
{
  PetscFunctionBeginUser;
  PetscCall((*ct->ops->getstepksp)(ct, krylov, pc_ksp));
  PetscFunctionReturn(0);
}
