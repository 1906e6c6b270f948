/* The contact module's step interface: the step matrix K~ for a dt, the step's contact solve in the
 * chosen formulation, and the consistent initial contact dofs.
 *
 * Each step solves the bound-constrained QP  min 1/2 w.K~w - b.w  s.t.  w_c <= g: with SNESVI
 * (vinewtonrsls by default, prefix -contact_), condensed on the contact dofs (the default) or on all
 * dofs, or by the active-set method on all dofs (contact_active_set.c); the friction loop wraps
 * MMContactSolveContactDofs, changing only the right-hand side and the tangential thresholds.
 * Without contact each step is one K~ solve (contact_kt.c). */
#include "contact_impl.h"

/* Bounds on the whole w vector: w_c <= g on the normal dofs, free elsewhere. */
static PetscErrorCode SetBounds(MMContact *ct, Vec lower, Vec upper)
{
  Vec sub;

  PetscFunctionBeginUser;
  PetscCall(VecSet(lower, PETSC_NINFINITY));
  PetscCall(VecSet(upper, PETSC_INFINITY));
  PetscCall(VecGetSubVector(upper, ct->is_normal, &sub));
  PetscCall(VecCopy(ct->gap, sub));
  PetscCall(VecRestoreSubVector(upper, ct->is_normal, &sub));
  PetscFunctionReturn(0);
}

/* K~ = K + 4/dt^2 M*, assembled only when dt changes, with what the formulation builds on it: the
 * factor and the Delassus operator (condensed), the bounds of the full VI, or the K~ solver and its
 * PC (active set, and without contact). */
PetscErrorCode MMContactSetStepMatrix(MMCtx *ctx, PetscReal dt)
{
  MMContact *ct        = &ctx->contact;
  PetscBool  condensed = (PetscBool)(ct->formulation == MM_CONTACT_CONDENSED && ct->enabled);
  PetscBool  full      = (PetscBool)(ct->formulation == MM_CONTACT_FULL && ct->enabled);

  PetscFunctionBeginUser;
  if (ct->qp.A && ct->Kt_dt == dt) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(ctx->log.assemble, 0, 0, 0, 0));
  if (!ct->qp.A) {
    PetscCall(MatDuplicate(ctx->op.K, MAT_COPY_VALUES, &ct->qp.A));
    PetscCall(MatCreateVecs(ct->qp.A, &ct->qp.b, NULL));
    ct->qp.rtol_b = ct->tol;
    if (!ct->enabled) PetscCall(MMKtCreate(ctx));
    else if (ct->formulation == MM_CONTACT_ACTIVE_SET) PetscCall(MMActiveSetSetUp(ctx));
    if (full) {
      PetscCall(VecDuplicate(ct->qp.b, &ct->lower));
      PetscCall(VecDuplicate(ct->qp.b, &ct->upper));
      PetscCall(MMQPCreate(PetscObjectComm((PetscObject)ctx->op.dm), "contact_", &ct->qp, 0, &ct->snes));
      PetscCall(SetBounds(ct, ct->lower, ct->upper));
      PetscCall(SNESVISetVariableBounds(ct->snes, ct->lower, ct->upper));
    }
  } else PetscCall(MatCopy(ctx->op.K, ct->qp.A, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(ct->qp.A, 4.0 / (dt * dt), ctx->op.Mstar, SUBSET_NONZERO_PATTERN));
  ct->Kt_dt = dt;
  if (condensed) {
    PetscCall(MMCondensedFactor(ctx));
    if (!ct->rho) PetscCall(MMCondensedCreateSolver(ctx));
  } else if (!ct->enabled) PetscCall(MMKtSetOperator(ctx, ct->qp.A));
  else if (ct->formulation == MM_CONTACT_ACTIVE_SET) PetscCall(MMActiveSetSetOperator(ctx));
  PetscCall(PetscLogEventEnd(ctx->log.assemble, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* react = K~ w - b on the contact dofs: recomputed from w whatever the formulation, so that the
 * energy audit checks the solve. */
static PetscErrorCode ContactForce(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(MatMult(ct->qp.A, w, react));
  PetscCall(VecAXPY(react, -1.0, b));
  /* off the contact nodes the residual is solver noise, not a force */
  PetscCall(VecISSet(react, ct->is_interior, 0.0));
  if (ct->ncomp == 1) PetscCall(VecISSet(react, ct->is_tangent, 0.0));
  PetscFunctionReturn(0);
}

/* Solves the step problem K~ w = b + f_c with w_c <= g; w holds the initial guess on entry.
 * react returns f_c, the obstacle's force on the body (w-frame), on the contact dofs only. */
/* The active-set formulation's contact force: -rho on the contact dofs, exactly. On its fixed dofs
 * rho is K~ w - b's own value; on its free contact dofs (a node off the obstacle, a slipping node's
 * tangential dofs) rho is the prescribed value and K~ w - b differs from it by the CG residual,
 * which is left to the energy audit, as on the interior dofs, instead of passing for a force. */
static PetscErrorCode ActiveSetContactForce(MMCtx *ctx, Vec react)
{
  MMContact *ct = &ctx->contact;
  Vec        rc;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(react));
  PetscCall(VecGetSubVector(react, ct->is_cond, &rc));
  PetscCall(VecAXPY(rc, -1.0, ct->rho));
  PetscCall(VecRestoreSubVector(react, ct->is_cond, &rc));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactSolve(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.contact_solve, 0, 0, 0, 0));
  ct->kt.its = 0;
  if (!ct->enabled) PetscCall(MMKtSolve(ctx, b, w));
  else if (ct->formulation == MM_CONTACT_CONDENSED) {
    PetscCall(MMCondensedSolveReactions(ctx, b));
    PetscCall(MMCondensedRecover(ctx, w));
  } else if (ct->formulation == MM_CONTACT_ACTIVE_SET) {
    PetscCall(MMActiveSetSolve(ctx, b, w));
    PetscCall(ActiveSetContactForce(ctx, react));
    PetscCall(PetscLogEventEnd(ctx->log.contact_solve, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  } else {
    PetscCall(VecCopy(b, ct->qp.b));
    PetscCall(MMQPSolve(ct->snes, &ct->qp, w, &ct->vi_its));
  }
  PetscCall(ContactForce(ctx, b, w, react));
  PetscCall(PetscLogEventEnd(ctx->log.contact_solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The friction loop's solve: at least the contact dofs of w and react are updated, exactly. The
 * condensed formulation updates only those, with no full-size solve, and MMContactRecover completes
 * w once the loop has converged; the active-set formulation solves on all dofs, warm-started. */
PetscErrorCode MMContactSolveContactDofs(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  PetscCheck(ct->enabled && ct->formulation != MM_CONTACT_FULL, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_PLIB, "The contact-dof solve needs the condensed or the active-set formulation");
  PetscCall(PetscLogEventBegin(ctx->log.contact_solve, 0, 0, 0, 0));
  if (ct->formulation == MM_CONTACT_ACTIVE_SET) {
    PetscCall(MMActiveSetSolve(ctx, b, w));
    PetscCall(ActiveSetContactForce(ctx, react));
  } else {
    PetscCall(MMCondensedSolveReactions(ctx, b));
    PetscCall(MMCondensedContactDofs(ctx, w, react));
  }
  PetscCall(PetscLogEventEnd(ctx->log.contact_solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The whole step solution and contact force from the last contact-dof solve: one full-size solve
 * (condensed), nothing left to do (active set: its solves give the whole w). */
PetscErrorCode MMContactRecover(MMCtx *ctx, Vec b, Vec w, Vec react)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ctx->log.contact_recover, 0, 0, 0, 0));
  if (ctx->contact.formulation == MM_CONTACT_ACTIVE_SET) PetscCall(ActiveSetContactForce(ctx, react));
  else {
    PetscCall(MMCondensedRecover(ctx, w));
    PetscCall(ContactForce(ctx, b, w, react));
  }
  PetscCall(PetscLogEventEnd(ctx->log.contact_recover, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Friction thresholds s (one per contact node) for the next Tresca solves of a threshold loop: the
 * active-set formulation's own Tresca conditions. The condensed formulation solves Coulomb's
 * problem in contact space instead (MMContactSolveCoulomb). */
PetscErrorCode MMContactSetFrictionThresholds(MMCtx *ctx, Vec s)
{
  PetscFunctionBeginUser;
  PetscCheck(ctx->contact.formulation == MM_CONTACT_ACTIVE_SET, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_PLIB, "Threshold solves are the active-set formulation's");
  PetscCall(MMActiveSetSetThresholds(ctx, s));
  PetscFunctionReturn(0);
}

/* Whether the formulation builds the Delassus operator on a candidate set, so that a friction
 * solver can work in contact space. */
PetscErrorCode MMContactHasDelassus(MMCtx *ctx, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = (PetscBool)(ctx->contact.enabled && ctx->contact.formulation == MM_CONTACT_CONDENSED);
  PetscFunctionReturn(0);
}

/* The step's Coulomb problem solved in contact space by fn: the contact dofs of w and react,
 * exactly (MMContactRecover completes w). *ok is fn's verdict. */
PetscErrorCode MMContactSolveCoulomb(MMCtx *ctx, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(MMContactHasDelassus(ctx, &has));
  PetscCheck(has, PetscObjectComm((PetscObject)ctx->op.dm), PETSC_ERR_PLIB, "A contact-space solve needs the condensed formulation");
  PetscCall(PetscLogEventBegin(ctx->log.contact_solve, 0, 0, 0, 0));
  PetscCall(MMCondensedSolveCoulomb(ctx, b, w, react, fn, fctx, ok));
  PetscCall(PetscLogEventEnd(ctx->log.contact_solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A given initial state that penetrates the obstacle is a wrong case (a plane on the wrong side, a
 * body placed inside it): projecting it would store elastic energy that launches the body. Refuse a
 * penetration deeper than -initial_penetration_tol h_c', naming the deepest node. */
static PetscErrorCode CheckInitialPenetration(MMCtx *ctx, Vec w)
{
  MMContact         *ct  = &ctx->contact;
  DM                 dm  = ctx->op.dm;
  PetscInt           dim = ctx->op.dim, rstart, deepest = -1;
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
  if (glob.depth <= ctx->opt.initial_penetration_tol * ct->h_c) PetscFunctionReturn(0);
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
          ctx->opt.obstacles[glob_obstacle].name, where, glob.depth, (double)ctx->opt.initial_penetration_tol, (double)(ctx->opt.initial_penetration_tol * ct->h_c));
}

/* Consistent initial contact dofs (docs/method.md section 3, Initial state): with the other dofs fixed, the
 * massless normal dofs solve the quasi-static problem A_cc u_c = L_c - A_c* u*, u_c <= g. */
PetscErrorCode MMContactProjectInitial(MMCtx *ctx, Vec w)
{
  MMContact *ct = &ctx->contact;
  Vec        r, rc, wc;
  PetscInt   its;

  PetscFunctionBeginUser;
  if (ct->enabled) PetscCall(CheckInitialPenetration(ctx, w));
  if (!ct->enabled || ctx->opt.mass_type != MM_MASS_MODIFIED) PetscFunctionReturn(0);
  PetscCall(MatCreateSubMatrix(ctx->op.K, ct->is_normal, ct->is_normal, MAT_INITIAL_MATRIX, &ct->qp0.A));
  PetscCall(MatCreateVecs(ct->qp0.A, &ct->qp0.b, NULL));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->lower0));
  PetscCall(VecDuplicate(ct->qp0.b, &ct->upper0));
  PetscCall(VecSet(ct->lower0, PETSC_NINFINITY));
  PetscCall(VecCopy(ct->gap, ct->upper0));
  ct->qp0.rtol_b = ct->tol;
  PetscCall(MMQPCreate(PetscObjectComm((PetscObject)ctx->op.dm), "contact0_", &ct->qp0, 0, &ct->snes0));
  PetscCall(SNESVISetVariableBounds(ct->snes0, ct->lower0, ct->upper0));

  /* b0 = (L - lift - K w*)_c with the contact dofs zeroed in w* */
  PetscCall(VecDuplicate(w, &r));
  PetscCall(VecCopy(w, r));
  PetscCall(VecISSet(r, ct->is_normal, 0.0));
  PetscCall(VecDuplicate(w, &rc));
  PetscCall(MatMult(ctx->op.K, r, rc));
  PetscCall(VecAYPX(rc, -1.0, ctx->op.load));
  PetscCall(VecAXPY(rc, -1.0, ctx->op.lift));
  PetscCall(VecGetSubVector(rc, ct->is_normal, &wc));
  PetscCall(VecCopy(wc, ct->qp0.b));
  PetscCall(VecRestoreSubVector(rc, ct->is_normal, &wc));

  PetscCall(VecGetSubVector(w, ct->is_normal, &wc));
  PetscCall(VecPointwiseMin(wc, wc, ct->gap));
  PetscCall(MMQPSolve(ct->snes0, &ct->qp0, wc, &its));
  PetscCall(VecRestoreSubVector(w, ct->is_normal, &wc));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&rc));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactDestroy(MMContact *ct)
{
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&ct->snes));
  PetscCall(SNESDestroy(&ct->snes0));
  PetscCall(KSPDestroy(&ct->ksp_K));
  PetscCall(MMCandidatesDestroy(&ct->cand));
  PetscCall(VecDestroy(&ct->q));
  PetscCall(VecDestroy(&ct->mu_c));
  PetscCall(MMKtDestroy(&ct->kt));
  PetscCall(MMActiveSetDestroy(&ct->as));
  PetscCall(VecDestroy(&ct->rho));
  PetscCall(VecDestroy(&ct->rho_lo));
  PetscCall(VecDestroy(&ct->rho_hi));
  PetscCall(VecDestroy(&ct->offset));
  PetscCall(VecDestroy(&ct->Wdiag));
  PetscCall(ISDestroy(&ct->is_cond));
  PetscCall(VecDestroy(&ct->z));
  PetscCall(VecDestroy(&ct->rhs_c));
  PetscCall(MatDestroy(&ct->qp.A));
  PetscCall(VecDestroy(&ct->qp.b));
  PetscCall(MatDestroy(&ct->qp0.A));
  PetscCall(VecDestroy(&ct->qp0.b));
  PetscCall(VecDestroy(&ct->lower));
  PetscCall(VecDestroy(&ct->upper));
  PetscCall(VecDestroy(&ct->lower0));
  PetscCall(VecDestroy(&ct->upper0));
  PetscCall(VecDestroy(&ct->gap));
  PetscCall(VecDestroy(&ct->gap0));
  PetscCall(VecDestroy(&ct->mu));
  PetscCall(PetscFree(ct->slide_ref));
  PetscCall(PetscFree(ct->node_frame));
  PetscCall(PetscFree(ct->obstacle));
  PetscCall(PetscFree(ct->force_obstacle));
  PetscCall(VecDestroy(&ct->area));
  PetscCall(ISDestroy(&ct->is_normal));
  PetscCall(ISDestroy(&ct->is_tangent));
  PetscCall(ISDestroy(&ct->is_star));
  PetscCall(ISDestroy(&ct->is_interior));
  PetscCall(PetscFree(ct->was_active));
  PetscCall(PetscFree2(ct->slipping, ct->slip_dir));
  PetscCall(PetscFree(ct->scalar_index));
  PetscCall(PetscFree(ct->vertex));
  PetscFunctionReturn(0);
}

/* The solvers of K~, for the start-up report: krylov is the KSP whose method solves with K~, pc_ksp
 * the one whose PC does. They are one KSP (prefix contact_K_), except in the active-set formulation,
 * whose CG on the free dofs (prefix contact_as_) applies the contact_K_ PC projected on them, and in
 * the full formulation, whose VI factors K~'s free block in each iteration with its own linear
 * solver (prefix contact_). */
PetscErrorCode MMContactGetStepKSP(MMCtx *ctx, KSP *krylov, KSP *pc_ksp)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (!ct->enabled) *krylov = ct->kt.ksp;
  else if (ct->formulation == MM_CONTACT_CONDENSED) *krylov = ct->ksp_K;
  else if (ct->formulation == MM_CONTACT_ACTIVE_SET) *krylov = ct->as.ksp;
  else PetscCall(SNESGetKSP(ct->snes, krylov));
  *pc_ksp = (ct->enabled && ct->formulation == MM_CONTACT_ACTIVE_SET) ? ct->kt.ksp : *krylov;
  PetscFunctionReturn(0);
}
