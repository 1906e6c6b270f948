/* -contact_formulation auto: the formulation whose whole run, set-up and steps, a fitted cost model
 * predicts cheapest (docs/scaling.md, "The formulation chosen by cost"). Each formulation that auto
 * may choose predicts its own times (ops->cost: a power law in the dofs, c_p dt / h_c', friction,
 * the ranks and the law, fitted on runs of 1 and 2 ranks that scripts/cost_model_collect.py
 * measures); one that cannot carry the problem predicts an infinite set-up. The factorizing
 * formulation's set-up grows faster than its steps, so the run's length (the plan of -ts_dt,
 * -ts_max_time and -ts_max_steps) decides between the two where neither wins both. */
#include "../contactimpl.h"
#include "../impls/cost_constants.h"

void MMCostEvaluate(const MMCostModel *m, const MMCostInput *in, MMCost *cost)
{
  const PetscReal ln = PetscLogReal(in->dofs), lc = PetscLogReal(1 + in->cfl), lr = PetscLogReal(PetscMax(in->ranks, 1));
  const PetscReal f = in->friction ? 1.0 : 0.0, g = in->finite ? 1.0 : 0.0;

  cost->step  = PetscExpReal(m->s[0] + m->s[1] * ln + m->s[2] * lc + f * (m->s[3] + m->s[4] * lc) + g * (m->s[6] + m->s[7] * ln + m->s[10] * lc) + lr * (m->s[5] + m->s[8] * ln + m->s[9] * lc));
  cost->setup = PetscExpReal(m->u[0] + m->u[1] * ln + lr * (m->u[2] + m->u[3] * ln));
  cost->direct = PETSC_FALSE;
}

/* A registered formulation's predicted cost, from a scratch object of its type (NULL ops->cost:
 * auto never chooses it, *has false). */
static PetscErrorCode Predict(MMContact ct, const char name[], const MMCostInput *in, PetscBool *has, MMCost *cost)
{
  extern PetscFunctionList MMContactList;
  PetscErrorCode (*create)(MMContact) = NULL;
  struct _p_MMContact scratch;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&scratch, sizeof(scratch)));
  scratch.comm = ct->comm;
  PetscCall(PetscFunctionListFind(MMContactList, name, &create));
  PetscCall((*create)(&scratch));
  *has = (PetscBool)(scratch.ops->cost != NULL);
  if (*has) PetscCall((*scratch.ops->cost)(ct, in, cost));
  if (scratch.ops->destroy) PetscCall((*scratch.ops->destroy)(&scratch));
  PetscFunctionReturn(0);
}

/* What both choices predict from: the global dofs n_dofs, c_p dt / h (h: h_c' for the formulations,
 * the smallest cell for the linear path), the run's steps, the friction, the law and the ranks. */
static PetscErrorCode CostInput(MMContact ct, PetscInt n_dofs, PetscReal h, MMCostInput *in)
{
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(in, sizeof(*in)));
  PetscCallMPI(MPI_Comm_size(ct->comm, &size));
  in->dim      = ct->dim;
  in->dofs     = PetscMax((PetscReal)n_dofs, 1);
  in->cfl      = h > 0 ? ct->material->c_p_max * ct->pb.dt / h : 1;
  if (!(in->cfl >= 0 && in->cfl < 1e6)) in->cfl = 1; /* a dt refused later (-ts_dt <= 0, inf) predicts nothing */
  in->steps    = PetscMax(ct->pb.steps, 1);
  in->friction = (PetscBool)(ct->pb.mu_max > 0);
  in->n_fc     = ct->n_fc;
  in->finite   = ct->material->finite;
  in->ranks    = size;
  PetscFunctionReturn(0);
}

/* Sets ct->opt.contact_formulation to the cheapest predicted whole run over the registered
 * formulations, or to a direct one (condensed) predicted within MM_COST_DIRECT_MARGIN of it: the fit's
 * scatter, where the measured runs of tiny and mid-sized 2D cases went either way (docs/scaling.md,
 * "The linear path chosen by cost"); and ct->auto_why to what was predicted. Needs h_c' and the friction corners: after
 * the contact dofs are built. n_dofs: the global dofs, Dirichlet dofs excluded. */
PetscErrorCode MMContactChooseFormulation(MMContact ct, PetscInt n_dofs)
{
  extern PetscFunctionList MMContactList;
  const char  **names;
  int           n;
  MMCostInput   in;
  MMCost        c[MM_MAX_FORMULATIONS] = {{0}};
  PetscReal     total[MM_MAX_FORMULATIONS], best, second = PETSC_INFINITY;
  int           b = 0;
  char          second_name[MM_TYPE_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(CostInput(ct, n_dofs, ct->h_c, &in));
  PetscCall(PetscFunctionListGet(MMContactList, &names, &n));
  PetscCheck(n <= MM_MAX_FORMULATIONS, ct->comm, PETSC_ERR_SUP, "More than %d contact formulations are registered", MM_MAX_FORMULATIONS);
  for (int i = 0; i < MM_MAX_FORMULATIONS; ++i) total[i] = PETSC_INFINITY;
  for (int i = 0; i < n && names[i]; ++i) {
    PetscBool has = PETSC_FALSE;
    PetscCall(Predict(ct, names[i], &in, &has, &c[i]));
    total[i] = has ? c[i].setup + in.steps * c[i].step : PETSC_INFINITY;
    if (total[i] < total[b]) b = i;
  }
  /* a direct formulation within the model's scatter of the cheapest is taken (MMCost.direct) */
  for (int i = 0; i < n && names[i]; ++i)
    if (c[i].direct && !c[b].direct && total[i] <= (1 + MM_COST_DIRECT_MARGIN) * total[b]) b = i;
  best = total[b];
  PetscCall(PetscStrncpy(ct->opt.contact_formulation, names[b], sizeof(ct->opt.contact_formulation)));
  for (int i = 0; i < n && names[i]; ++i)
    if (i != b && total[i] < second) {
      second = total[i];
      PetscCall(PetscStrncpy(second_name, names[i], sizeof(second_name)));
    }
  PetscCall(PetscFree(names));
  PetscCheck(best < PETSC_INFINITY, ct->comm, PETSC_ERR_PLIB, "No contact formulation can carry this problem");
  if (second < best) PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: %.0f steps predicted %.3g s, %s %.3g s; a direct solve within %.0f%%)", (double)in.steps, (double)best, second_name, (double)second, (double)(100 * MM_COST_DIRECT_MARGIN)));
  else if (second < PETSC_INFINITY) PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: %.0f steps predicted %.3g s, %s %.3g s)", (double)in.steps, (double)best, second_name, (double)second));
  else PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: the only formulation for this problem)"));
  PetscFunctionReturn(0);
}

/* Without contact (-contact 0, -iterative_dofs -1): K~ factored or solved by CG, whichever the linear
 * path's model predicts the faster whole run (docs/scaling.md, "The linear path chosen by cost"). Its
 * c_p dt / h takes the smallest cell's diameter, which sets K~'s conditioning and so the CG's
 * iterations; fitted like the formulations' on runs of 1 and 2 ranks (scripts/cost_model_collect.py
 * --linear). Sets ct->prefer_iterative and ct->auto_why. */
PetscErrorCode MMContactChooseLinearPath(MMContact ct, PetscInt n_dofs)
{
  static const MMCostModel factor[2] = {MM_COST_FACTOR_2D, MM_COST_FACTOR_3D}, cg[2] = {MM_COST_CG_2D, MM_COST_CG_3D}; /* scripts/cost_model_fit.py --write */
  MMCostInput in;
  MMCost      f, c;
  PetscReal   tf, tc;

  PetscFunctionBeginUser;
  PetscCall(CostInput(ct, n_dofs, ct->h_min, &in));
  in.friction = PETSC_FALSE; /* no contact: the linear path's models have no friction */
  in.n_fc     = 0;
  MMCostEvaluate(&factor[ct->dim - 2], &in, &f);
  MMCostEvaluate(&cg[ct->dim - 2], &in, &c);
  tf                   = f.setup + in.steps * f.step;
  tc                   = c.setup + in.steps * c.step;
  ct->prefer_iterative = (PetscBool)(tc * (1 + MM_COST_DIRECT_MARGIN) < tf); /* the factor within the margin: exact by construction */
  PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: %.0f steps predicted %.3g s by %s, %.3g s by %s%s)", (double)in.steps, (double)(ct->prefer_iterative ? tc : tf), ct->prefer_iterative ? "CG" : "the factor", (double)(ct->prefer_iterative ? tf : tc), ct->prefer_iterative ? "the factor" : "CG", !ct->prefer_iterative && tc < tf ? "; a direct solve within the margin" : ""));
  PetscFunctionReturn(0);
}
