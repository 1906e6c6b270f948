/* The consistent initial state of the stepper (docs/method.md section 3): u0 and v0 from the
 * problem, the contact dofs projected by the quasi-static contact problem (or the static or static
 * sliding state), the initial reaction, and a0 from the equation of motion. */
#include "newmarkimpl.h"
#include "fem.h"

/* The internal force of the state u at t = 0: K u + lift, or the finite-strain law's P(F) (docs/method.md section 13) */
static PetscErrorCode InternalForce(MMNewmark nm, Vec u, Vec f)
{
  MMContactOperators ops;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  if (nm->material->finite) {
    MMElasticity *el = &nm->nl.el;
    PetscCall(MMElasticityLocal(el, nm->op, nm->loads, u, 0.0, el->l1));
    PetscCall(MMElasticitySetStepStart(el, nm->op, el->l1));
    PetscCall(MMElasticityForce(el, nm->op, nm->material, el->l1, f));
    PetscFunctionReturn(0);
  }
  PetscCall(MatMult(ops.K, u, f));
  PetscCall(VecAXPY(f, 1.0, ops.lift));
  PetscFunctionReturn(0);
}

/* Affine initial displacement u0 = a + B x */
static PetscErrorCode InitialDisplacement(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ptr)
{
  const MMNewmarkProblem *o = (const MMNewmarkProblem *)ptr;
  for (PetscInt c = 0; c < dim; ++c) {
    u[c] = o->u0_offset[c];
    for (PetscInt d = 0; d < dim; ++d) u[c] += o->u0_gradient[c * dim + d] * x[d];
  }
  return 0;
}

/* Initial velocity: translation plus rigid rotation omega x (x - c) */
static PetscErrorCode InitialVelocity(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar *v, void *ptr)
{
  const MMNewmarkProblem *o = (const MMNewmarkProblem *)ptr;
  const PetscReal *w = o->omega, *c = o->omega_center;
  const PetscReal  r[3] = {x[0] - c[0], x[1] - c[1], dim == 3 ? x[2] - c[2] : 0};

  if (dim == 2) {
    v[0] = o->v0[0] - w[0] * r[1];
    v[1] = o->v0[1] + w[0] * r[0];
  } else {
    v[0] = o->v0[0] + w[1] * r[2] - w[2] * r[1];
    v[1] = o->v0[1] + w[2] * r[0] - w[0] * r[2];
    v[2] = o->v0[2] + w[0] * r[1] - w[1] * r[0];
  }
  return 0;
}

static PetscErrorCode ProjectInitialField(MMNewmark nm, PetscErrorCode (*f)(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar *, void *), Vec w)
{
  Vec   ucart;
  void *fctx = &nm->pb;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(nm->dm, &ucart));
  PetscCall(MMFEInterpolate(nm->op, f, fctx, ucart));
  PetscCall(MMFEFromCartesian(nm->op, ucart, w));
  PetscCall(DMRestoreGlobalVector(nm->dm, &ucart));
  PetscFunctionReturn(0);
}

/* A per-vertex table of dim values (local vertex order, src/fem/material.c) as a Cartesian global
 * vector: the Dirichlet dofs drop out */
static PetscErrorCode VertexTableCartesian(MMNewmark nm, const PetscReal table[], Vec g)
{
  DM             dm  = nm->dm;
  const PetscInt dim = nm->dim;
  PetscSection   ls;
  PetscInt       vStart, vEnd;
  PetscScalar   *a;
  Vec            l;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(dm, &l));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArray(l, &a));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ls, v, &off));
    for (PetscInt d = 0; d < dim; ++d) a[off + d] = table[(v - vStart) * dim + d];
  }
  PetscCall(VecRestoreArray(l, &a));
  PetscCall(DMLocalToGlobal(dm, l, INSERT_VALUES, g));
  PetscCall(DMRestoreLocalVector(dm, &l));
  PetscFunctionReturn(0);
}

/* -bodies: each vertex's translation is the v0 of its body (src/fem/material.c), and -omega's rigid
 * rotation is added to every body. */
static PetscErrorCode BodiesInitialVelocity(MMNewmark nm, Vec w)
{
  DM               dm  = nm->dm;
  MMNewmarkProblem rotation = nm->pb; /* the rotation alone: InitialVelocity without -v0 */
  Vec              ucart, tglob;

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) rotation.v0[d] = 0;
  PetscCall(DMGetGlobalVector(dm, &ucart));
  PetscCall(DMGetGlobalVector(dm, &tglob));
  PetscCall(MMFEInterpolate(nm->op, InitialVelocity, &rotation, ucart));
  PetscCall(VertexTableCartesian(nm, nm->material->vertex_v0, tglob));
  PetscCall(VecAXPY(ucart, 1.0, tglob));
  PetscCall(MMFEFromCartesian(nm->op, ucart, w));
  PetscCall(DMRestoreGlobalVector(dm, &tglob));
  PetscCall(DMRestoreGlobalVector(dm, &ucart));
  PetscFunctionReturn(0);
}

/* -omega0: adds each vertex's omega0 x (x - x_cm) of its body (src/fem/material.c) to w; only when
 * given, so that a run without it keeps every bit (docs/method.md section 2, "Bodies"). */
static PetscErrorCode AddRotationAboutCentres(MMNewmark nm, Vec w)
{
  Vec tglob, tw;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(nm->dm, &tglob));
  PetscCall(VecDuplicate(w, &tw));
  PetscCall(VertexTableCartesian(nm, nm->material->vertex_omega0, tglob));
  PetscCall(MMFEFromCartesian(nm->op, tglob, tw));
  PetscCall(VecAXPY(w, 1.0, tw));
  PetscCall(VecDestroy(&tw));
  PetscCall(DMRestoreGlobalVector(nm->dm, &tglob));
  PetscFunctionReturn(0);
}

/* a0 from M* a0 = L - lift - K u0 - C v0 + f_c0 on the dofs with inertia. */
static PetscErrorCode InitialAcceleration(MMNewmark nm)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  IS                 is, all = NULL;
  Mat                Mss;
  Vec                r, rs, as;
  KSP                ksp;
  MMContactNodes     cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  is = cn.is_star;
  if (!MMNewmarkHasMasslessDofs(nm)) {
    PetscInt n, rstart;
    PetscCall(VecGetLocalSize(s->u, &n));
    PetscCall(VecGetOwnershipRange(s->u, &rstart, NULL));
    PetscCall(ISCreateStride(PetscObjectComm((PetscObject)s->u), n, rstart, 1, &all));
    is = all;
  }
  PetscCall(VecDuplicate(s->u, &r));
  PetscCall(InternalForce(nm, s->u, r));
  PetscCall(VecAYPX(r, -1.0, ops.load));
  PetscCall(VecAXPY(r, 1.0, s->react));
  PetscCall(MMDampingAddForce(&nm->damping, s->v, -1.0, r));
  PetscCall(MatCreateSubMatrix(ops.Mstar, is, is, MAT_INITIAL_MATRIX, &Mss));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)s->u), &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "mass_"));
  PetscCall(KSPSetOperators(ksp, Mss, Mss));
  PetscCall(MMKSPSetExactCG(ksp));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(VecZeroEntries(s->a));
  PetscCall(VecGetSubVector(r, is, &rs));
  PetscCall(VecGetSubVector(s->a, is, &as));
  {
    /* CG's norms square the right-hand side: solved for r/|r|_inf, so that loads near the overflow
     * limit still give a0 (and the run stops later, where the state itself overflows) */
    PetscReal scale;
    PetscCall(VecNorm(rs, NORM_INFINITY, &scale));
    if (scale > 0 && !PetscIsInfOrNanReal(scale)) PetscCall(VecScale(rs, 1.0 / scale));
    PetscCall(KSPSolve(ksp, rs, as));
    if (scale > 0 && !PetscIsInfOrNanReal(scale)) PetscCall(VecScale(as, scale));
  }
  PetscCall(VecRestoreSubVector(s->a, is, &as));
  PetscCall(VecRestoreSubVector(r, is, &rs));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&Mss));
  PetscCall(VecDestroy(&r));
  PetscCall(ISDestroy(&all));
  PetscFunctionReturn(0);
}

/* -initial_state static_sliding: the body rests on the plane, its base on it, so it slides along the
 * plane with the tangential part of -v0; a normal part would lift it off or push it in at once
 * (README "Options"). The normal part is dropped, and said. */
static PetscErrorCode TangentialInitialVelocity(MMNewmark nm)
{
  const PetscInt dim = nm->dim;
  PetscReal      vn  = 0, p[MM_MAX_DIM], n[MM_MAX_DIM];
  PetscBool      plane;

  PetscFunctionBeginUser;
  PetscCall(MMObstacleGetPlane(&nm->pb.obstacles[0], p, n, &plane)); /* the single plane static_sliding needs */
  for (PetscInt d = 0; d < dim; ++d) vn += nm->pb.v0[d] * n[d];
  if (vn == 0) PetscFunctionReturn(0);
  for (PetscInt d = 0; d < dim; ++d) nm->pb.v0[d] -= vn * n[d];
  if (!nm->pb.quiet) PetscCall(PetscPrintf(PetscObjectComm((PetscObject)nm->dm), "mmcontact: -initial_state static_sliding slides along the plane: the normal part %g of -v0 is dropped\n", (double)vn));
  PetscFunctionReturn(0);
}

/* With a finite-strain law the projection by K leaves the massless rows' own equation f(u) = L off
 * by the law's nonlinearity (the neo-Hookean ball under gravity: a contact force of 1e-4 of its
 * weight and a Coulomb residual of 5e-3 at step 0, no node touching); chord steps with K take it to
 * round-off: until a step moves the contact dofs by no more than the round-off of u0 and the gaps. */
static PetscErrorCode ProjectInitialFinite(MMNewmark nm)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  MMContactNodes     cn;
  PetscReal          change = PETSC_MAX_REAL, scale;
  PetscInt           it;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  PetscCall(VecNorm(s->u, NORM_INFINITY, &scale));
  scale = PetscMax(scale, cn.h_c); /* a body at rest: the gaps' scale */
  for (it = 0; it < 50 && change > 16 * PETSC_MACHINE_EPSILON * scale; ++it) {
    PetscCall(InternalForce(nm, s->u, s->work));
    PetscCall(VecAXPY(s->work, -1.0, ops.load));
    PetscCall(MMContactProjectInitialCorrect(nm->contact, s->u, s->work, &change));
  }
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkInitialState - Computes the consistent initial state: u0 and v0, the contact dofs
  projected, the initial reaction and a0

  Collective

  Input Parameter:
. nm - the stepper's context, set up

  Note:
  The consistent initial state: u0, v0 from the problem, the contact dofs projected by the
  quasi-static contact problem, the initial reaction, and a0 from the equation of motion.

  Level: intermediate

.seealso: `MMNewmarkSetUp()`, `MMEnergyInitial()`, `MMNewmarkCreateTS()`
@*/
PetscErrorCode MMNewmarkInitialState(MMNewmark nm)
{
  MMContactOperators ops;
  MMState           *s = &nm->state;
  MMContactNodes     cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(DMCreateGlobalVector(nm->dm, &s->u));
  {
    Vec *copies[] = {&s->v, &s->a, &s->u_old, &s->v_old, &s->a_old, &s->react, &s->react_old, &s->work, &s->u_next, &s->du};
    for (size_t i = 0; i < sizeof(copies) / sizeof(copies[0]); ++i) PetscCall(VecDuplicate(s->u, copies[i]));
    PetscCall(MMNewmarkSchemeSetUp(nm)); /* the step's offset, for the contact solves */
  }
  nm->cert.on = (PetscBool)(nm->cert.on && nm->law->certified);
  {
    MMContactNodes cn0;
    PetscCall(MMContactGetNodes(nm->contact, &cn0));
    /* the step's increment (step_laws.c, nonlinear.c): not with friction corners, whose second bound is of T2 w */
    nm->increments = (PetscBool)(nm->increments && !cn0.n_fc);
  }
  PetscCall(MMCertificateSetUp(nm));
  PetscCall(MMContactGetNodes(nm->contact, &cn));
  if (nm->material->finite) {
    PetscCheck(nm->pb.initial_state != MM_INITIAL_STATIC_SLIDING, nm->comm, PETSC_ERR_SUP, "-initial_state static_sliding solves a linear sliding state: with -elasticity svk or neohookean use -initial_state static (the finite-strain static state, frictionless) or given");
    PetscCall(MMNonlinearSetUp(nm));
  }
  if (nm->pb.initial_state == MM_INITIAL_STATIC_SLIDING) PetscCall(TangentialInitialVelocity(nm));
  if (nm->material->named) PetscCall(BodiesInitialVelocity(nm, s->v));
  else PetscCall(ProjectInitialField(nm, InitialVelocity, s->v));
  if (nm->material->spin) PetscCall(AddRotationAboutCentres(nm, s->v));
  PetscCall(MMDampingSetUp(&nm->damping, nm->contact, nm->material, cn.is_massless, s->v));
  PetscCall(VecZeroEntries(s->react));
  if (nm->pb.initial_state == MM_INITIAL_STATIC_SLIDING) PetscCall(MMInitialStaticSliding(nm, s->u, s->react));
  else if (nm->pb.initial_state == MM_INITIAL_STATIC) {
    /* u0 is the static solution: an affine u0 given with it would be ignored */
    PetscCheck(!nm->pb.u0_given, PetscObjectComm((PetscObject)nm->dm), PETSC_ERR_USER_INPUT, "-initial_state static computes u0 from the loads at t = 0: drop -u0_offset and -u0_gradient, or use -initial_state given");
    if (nm->material->finite) PetscCall(MMNewmarkStaticFinite(nm, s->u, s->react));
    else PetscCall(MMContactSolveStatic(nm->contact, s->u, s->react));
  } else {
    PetscCall(ProjectInitialField(nm, InitialDisplacement, s->u));
    PetscCall(MMContactProjectInitial(nm->contact, s->u));
    if (nm->material->finite) PetscCall(ProjectInitialFinite(nm));
  }
  /* f_c0 = K u0 + lift - L (+ C v0) on the massless dofs: their quasi-static equation (the
   * finite-strain static start's too: its Newton's contact forces are the tangent's, f_c0 the law's) */
  if (MMNewmarkHasMasslessDofs(nm) && (nm->pb.initial_state == MM_INITIAL_GIVEN || (nm->material->finite && nm->pb.initial_state == MM_INITIAL_STATIC))) {
    Vec rc, fc;
    PetscCall(InternalForce(nm, s->u, s->work));
    PetscCall(VecAXPY(s->work, -1.0, ops.load));
    PetscCall(MMDampingAddForce(&nm->damping, s->v, 1.0, s->work));
    PetscCall(VecGetSubVector(s->work, cn.is_massless, &fc));
    PetscCall(VecGetSubVector(s->react, cn.is_massless, &rc));
    PetscCall(VecCopy(fc, rc));
    PetscCall(VecRestoreSubVector(s->react, cn.is_massless, &rc));
    PetscCall(VecRestoreSubVector(s->work, cn.is_massless, &fc));
  }
  PetscCall(InitialAcceleration(nm));
  PetscCall(VecCopy(s->u, s->u_next));
  PetscFunctionReturn(0);
}
