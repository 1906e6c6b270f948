/* -initial_state static with the finite-strain laws (docs/method.md section 13, "The static start in
 * finite strain"): the static equilibrium under the loads at t = 0,
 *
 *   f(u) = L(0) + f_c,   f_c the frictionless contact forces: u_n <= g, f_c,n <= 0, f_c,n (u_n - g) = 0,
 *
 * f the law's internal force P(F) (src/fem/elasticity.c), the loads dead as in the dynamic step (a
 * pressure keeps its reference normal). Reached by load stepping, f(u) = lambda L(0) + f_c with lambda
 * from 0 to 1 (the Dirichlet data scaled with it), each level by Newton: each iterate is the static
 * contact problem of the tangent at the iterate for the increment (contact's MMContactSolveStaticStep,
 * the dynamic step's problem with no mass), so that the contact law holds exactly at every iterate.
 * A level is done when its residual meets the step certificate (certificate.c): its work over the load
 * step, its resultant and moment within the round-off of the terms it sums, the cells' forces taken
 * in magnitude (a slender part's internal force is a small difference of large element forces). A
 * level whose Newton fails (too many iterations, growth, a failed solve) is tried again with half the
 * increment; one that converges in a few iterations doubles the next. */
#include "newmarkimpl.h"
#include "fem.h"

#define MM_STATIC_EASY_ITS 4     /* a level solved in at most this many iterations doubles the next increment */
#define MM_STATIC_MIN_INC  1e-6  /* the smallest load increment before the start is given up */
#define MM_STATIC_GROWTH   1e3   /* a residual this many times the level's smallest: Newton diverges */
#define MM_STATIC_LIST     32    /* load steps listed in the summary */

typedef struct {
  Vec       r, scale, f, b, dw, react_new, react_start;
  PetscInt  levels, cuts, its_total, its[MM_STATIC_LIST]; /* load steps solved, cut; Newton iterations, and per step */
  PetscReal ratio; /* the last iterate's residual in round-offs of its terms */
} MMStaticFinite;

/* r = lambda L - f(u) + react and its round-off scale |lambda L| + |react| + sum_e |f_e|; el->l1 is
 * left holding the Cartesian state, for the tangent */
static PetscErrorCode Residual(MMNewmark nm, MMStaticFinite *sf, Vec u, PetscReal lambda, Vec react)
{
  MMContactOperators ops;
  MMElasticity      *el = &nm->nl.el;
  const PetscScalar *la, *fa;
  PetscScalar       *sa;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetOperators(nm->contact, &ops));
  PetscCall(MMElasticityLocal(el, nm->op, nm->loads, u, 0.0, el->l1));
  PetscCall(MMLoadsScaleBoundaryValues(nm->loads, el->l1, lambda));
  PetscCall(MMElasticitySetStepStart(el, nm->op, el->l1)); /* the step from u to u: the force P(F) */
  PetscCall(MMElasticityForce(el, nm->op, nm->material, el->l1, sf->f));
  PetscCall(MMElasticityForceMagnitude(el, nm->op, nm->material, el->l1, sf->scale));
  PetscCall(VecAXPBYPCZ(sf->r, lambda, -1.0, 0.0, ops.load, sf->f));
  PetscCall(VecAXPY(sf->r, 1.0, react));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArrayRead(ops.load, &la));
  PetscCall(VecGetArrayRead(react, &fa));
  PetscCall(VecGetArray(sf->scale, &sa));
  for (PetscInt i = 0; i < n; ++i) sa[i] += PetscAbsReal(lambda * PetscRealPart(la[i])) + PetscAbsScalar(fa[i]);
  PetscCall(VecRestoreArray(sf->scale, &sa));
  PetscCall(VecRestoreArrayRead(react, &fa));
  PetscCall(VecRestoreArrayRead(ops.load, &la));
  PetscFunctionReturn(0);
}

/* Newton at the load level lambda from the state s->u (and its contact forces s->react), s->u_old the
 * level's start (the certificate's work is over the load step). *ok false: not converged, the state
 * is left where Newton stopped. */
static PetscErrorCode SolveLevel(MMNewmark nm, MMStaticFinite *sf, PetscReal lambda, PetscBool *ok, PetscInt *its)
{
  MMState  *s = &nm->state;
  PetscReal res = 0, res_prev = PETSC_MAX_REAL, res_min = PETSC_MAX_REAL;
  PetscInt  stalls = 0;

  PetscFunctionBeginUser;
  *ok = PETSC_FALSE;
  for (*its = 0;; ++(*its)) {
    MMStepCertificate c;
    PetscInt          vi;
    PetscBool         failed;

    PetscCall(Residual(nm, sf, s->u, lambda, s->react));
    PetscCall(VecNorm(sf->r, NORM_2, &res));
    if (*its == 0) { /* the level's start has not moved: no work to measure, and the load has changed */
      PetscCall(PetscMemzero(&c, sizeof(c)));
      c.ratio = PETSC_MAX_REAL;
    } else PetscCall(MMCertificateOfResidual(nm, sf->r, sf->scale, s->u, &c));
    sf->ratio = c.ratio;
    res_min   = PetscMin(res_min, res);
    PetscCall(PetscInfo(NULL, "static start, load factor %g, Newton iteration %" PetscInt_FMT ": residual %.3e, %.3g round-offs of its terms (work %.3e of %.3e, resultant %.3e of %.3e, moment %.3e of %.3e)\n", (double)lambda, *its, (double)res, (double)c.ratio, (double)c.energy, (double)c.energy_tol, (double)c.force, (double)c.force_tol, (double)c.torque, (double)c.torque_tol));
    if (c.ratio <= 1) {
      *ok = PETSC_TRUE;
      break;
    }
    /* Newton's residual falls quadratically until the round-off of its terms: flat twice running
     * within a thousand round-offs, it is at its floor (as the dynamic step's, certificate.c) */
    stalls = (*its > 0 && res > 0.5 * res_prev) ? stalls + 1 : 0;
    if (stalls >= 2 && c.ratio <= MM_CERT_FLOOR_ROUNDOFFS) {
      MMCertificateAtFloor(&nm->cert, c.ratio);
      *ok = PETSC_TRUE;
      break;
    }
    /* the first iterates of a large increment may overshoot: growth counts from the third on */
    if (*its >= nm->nl.static_max_it || PetscIsInfOrNanReal(res) || (*its >= 3 && res > MM_STATIC_GROWTH * res_min)) break;
    res_prev = res;
    /* the Newton step: the contact problem of the tangent at u for the increment, b = lambda L - f(u) */
    PetscCall(VecWAXPY(sf->b, -1.0, s->react, sf->r));
    PetscCall(MMNonlinearBuildTangent(nm, nm->nl.el.l1, 0.0));
    PetscCall(VecZeroEntries(sf->dw));
    PetscCall(MMContactSolveStaticStep(nm->contact, nm->nl.Ks, sf->b, s->u, (PetscBool)(!sf->levels && *its == 0), sf->dw, sf->react_new, &vi, &failed));
    if (failed) break;
    PetscCall(VecAXPY(s->u, 1.0, sf->dw));
    PetscCall(VecCopy(sf->react_new, s->react));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode StaticFiniteView(MMNewmark nm, const MMStaticFinite *sf)
{
  char     list[MM_STATIC_LIST * 4 + 8] = "";
  size_t   len                          = 0;
  PetscInt shown                        = PetscMin(sf->levels, MM_STATIC_LIST);

  PetscFunctionBeginUser;
  if (nm->pb.quiet) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < shown && len + 5 < sizeof(list); ++k) {
    size_t n;
    PetscCall(PetscSNPrintfCount(list + len, sizeof(list) - len, "%s%" PetscInt_FMT, &n, k ? " " : "", sf->its[k]));
    len += n - 1; /* the count includes the terminating null */
  }
  PetscCall(PetscPrintf(nm->comm, "mmcontact: -initial_state static (finite strain): %" PetscInt_FMT " load steps (%" PetscInt_FMT " cut), %" PetscInt_FMT " Newton iterations (per load step: %s%s), final residual %.3g round-offs of its terms\n", sf->levels, sf->cuts, sf->its_total, list,
                        sf->levels > shown ? " ..." : "", (double)sf->ratio));
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkStaticFinite - Solves the finite-strain static contact problem under the loads at t = 0
  by load stepping and Newton

  Collective

  Input Parameter:
. nm - the stepper's context, its finite-strain step set up (MMNonlinearSetUp())

  Output Parameters:
+ u     - the static state (w-frame)
- react - its contact forces on the contact-normal dofs, zero elsewhere

  Note:
  -initial_state static with -elasticity svk or neohookean (docs/method.md section 13). u and react
  must be the state's s->u and s->react; s->u_old and s->react_old serve as the load levels' starts.
  A start that cannot be reached stops the run with one line naming the load factor reached.

  Level: developer

.seealso: `MMContactSolveStatic()`, `MMContactSolveStaticStep()`, `MMNewmarkInitialState()`
@*/
PetscErrorCode MMNewmarkStaticFinite(MMNewmark nm, Vec u, Vec react)
{
  MMState       *s = &nm->state;
  MMStaticFinite sf;
  PetscReal      lambda = 0, inc = 1.0 / nm->nl.static_steps;

  PetscFunctionBeginUser;
  PetscCheck(u == s->u && react == s->react, nm->comm, PETSC_ERR_ARG_WRONG, "MMNewmarkStaticFinite works on the state's u and react");
  PetscCall(PetscLogEventBegin(MM_TS_StaticFinite, 0, 0, 0, 0));
  PetscCall(PetscMemzero(&sf, sizeof(sf)));
  {
    Vec *v[] = {&sf.r, &sf.scale, &sf.f, &sf.b, &sf.dw, &sf.react_new, &sf.react_start};
    for (size_t i = 0; i < sizeof(v) / sizeof(v[0]); ++i) PetscCall(VecDuplicate(u, v[i]));
  }
  nm->nl.el.consistent = PETSC_TRUE; /* Newton's quadratic convergence needs the whole dP/dF */
  PetscCall(VecZeroEntries(u));       /* from rest */
  PetscCall(VecZeroEntries(react));
  while (lambda < 1) {
    const PetscReal target = (1 - (lambda + inc) <= 1e-12) ? 1.0 : lambda + inc;
    PetscBool       ok;
    PetscInt        its;

    PetscCall(VecCopy(u, s->u_old));
    PetscCall(VecCopy(react, sf.react_start));
    PetscCall(SolveLevel(nm, &sf, target, &ok, &its));
    if (ok) {
      if (sf.levels < MM_STATIC_LIST) sf.its[sf.levels] = its;
      sf.levels++;
      sf.its_total += its;
      lambda = target;
      if (its <= MM_STATIC_EASY_ITS) inc *= 2;
      inc = PetscMin(inc, 1 - lambda);
      continue;
    }
    /* back to the last level reached, with half the increment */
    PetscCall(VecCopy(s->u_old, u));
    PetscCall(VecCopy(sf.react_start, react));
    inc *= 0.5;
    sf.cuts++;
    PetscCheck(inc >= MM_STATIC_MIN_INC || lambda > 0, nm->comm, PETSC_ERR_NOT_CONVERGED,
               "-initial_state static: the finite-strain static problem did not converge at any load level, down to %g of the loads at t = 0: it is not well posed (a rigid motion held neither by a Dirichlet condition nor by the contact nodes in contact: a free body, one free to slide along a frictionless obstacle, or loads that pull it off its support; the static start is frictionless). Hold it with -dirichlet, or start from -initial_state given",
               (double)inc);
    PetscCheck(inc >= MM_STATIC_MIN_INC, nm->comm, PETSC_ERR_NOT_CONVERGED,
               "-initial_state static: the finite-strain static problem did not converge beyond load factor %g of the loads at t = 0 (Newton's residual at %.3g round-offs of its terms with the load increment cut to %g): under these loads the body may buckle, snap or lose its support (the static start is frictionless). Check the loads and supports, or start from -initial_state given with the loads ramped in time (-..._amplitude ramp)",
               (double)lambda, (double)sf.ratio, (double)inc);
  }
  /* the dynamic step's iteration matrix: with -nonlinear_tangent auto its tangent at u0, whose
   * geometric term is kept only where it is positive (K~ must stay definite); reference and step
   * keep their own */
  nm->nl.el.consistent = PETSC_FALSE;
  if (nm->nl.policy == MM_TANGENT_AUTO) {
    PetscCall(MMElasticityLocal(&nm->nl.el, nm->op, nm->loads, u, 0.0, nm->nl.el.l1));
    PetscCall(MMNonlinearBuildTangent(nm, nm->nl.el.l1, 0.0));
  } else nm->nl.use_tangent = PETSC_FALSE;
  PetscCall(StaticFiniteView(nm, &sf));
  {
    Vec *v[] = {&sf.r, &sf.scale, &sf.f, &sf.b, &sf.dw, &sf.react_new, &sf.react_start};
    for (size_t i = 0; i < sizeof(v) / sizeof(v[0]); ++i) PetscCall(VecDestroy(v[i]));
  }
  PetscCall(PetscLogEventEnd(MM_TS_StaticFinite, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
