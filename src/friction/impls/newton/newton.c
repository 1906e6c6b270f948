/* -friction_type newton, the default: the step's Coulomb problem solved at once by semismooth Newton
 * on Alart-Curnier's function in contact space (src/friction/interface/coulombnewton.c,
 * docs/method.md section 6). Its iterations do not depend on a contraction of the threshold map, so
 * it converges at the time steps users choose (c_p dt / h_c' of 4 and more). With the condensed
 * formulation it works on the candidate set's Delassus block; with the active-set formulation (no
 * Delassus operator) the formulation's own semismooth Newton on all dofs takes the Coulomb law
 * itself, its thresholds following the iterate (MMFrictionSolveDofs). */
#include "../../frictionimpl.h"

static PetscErrorCode SolveSet_Newton(MMFriction fr, const MMCoulombProblem *p, PetscScalar r[], MMCoulombResult *res)
{
  PetscFunctionBeginUser;
  PetscCall(MMCoulombNewton(p, &fr->work, fr->rtol, fr->maxit, r, res));
  res->inner_its   = res->its;
  res->contraction = 0;
  PetscFunctionReturn(0);
}

/* no threshold loop of its own: it solves the Coulomb law at once */
static const MMFrictionOps NewtonOps = {
  .solveset     = SolveSet_Newton,
  .solvedofs    = MMFrictionSolveDofs,
  .default_rtol = 1e-12, /* |Phi|_inf over the force scale: quadratic convergence makes a tight default cheap */
  .rtol_meaning = "Alart-Curnier residual over the force scale",
};

PetscErrorCode MMFrictionCreate_Newton(MMFriction fr)
{
  PetscFunctionBeginUser;
  fr->ops = &NewtonOps;
  PetscFunctionReturn(0);
}
