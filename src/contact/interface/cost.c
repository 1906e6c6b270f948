/* -contact_formulation auto: the formulation whose whole run, set-up and steps, a fitted cost model
 * predicts cheapest (docs/scaling.md, "The formulation chosen by cost"). Each formulation that auto
 * may choose predicts its own times (ops->cost: a power law in the dofs, c_p dt / h_c', friction,
 * the ranks and the law, fitted on runs of 1 and 2 ranks that scripts/cost_model_collect.py
 * measures); one that cannot carry the problem predicts an infinite set-up. The factorizing
 * formulation's set-up grows faster than its steps, so the run's length (the plan of -ts_dt,
 * -ts_max_time and -ts_max_steps) decides between the two where neither wins both. */
#include "../contactimpl.h"

void MMCostEvaluate(const MMCostModel *m, const MMCostInput *in, MMCost *cost)
{
  const PetscReal ln = PetscLogReal(in->dofs), lc = PetscLogReal(1 + in->cfl), lr = PetscLogReal(PetscMax(in->ranks, 1));
  const PetscReal f = in->friction ? 1.0 : 0.0, g = in->finite ? 1.0 : 0.0;

  cost->step  = PetscExpReal(m->s[0] + m->s[1] * ln + m->s[2] * lc + f * (m->s[3] + m->s[4] * lc) + g * (m->s[6] + m->s[7] * ln) + lr * (m->s[5] + m->s[8] * ln));
  cost->setup = PetscExpReal(m->u[0] + m->u[1] * ln + lr * (m->u[2] + m->u[3] * ln));
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

/* Sets ct->opt.contact_formulation to the cheapest predicted whole run over the registered
 * formulations, and ct->auto_why to what was predicted. Needs h_c' and the friction corners: after
 * the contact dofs are built. n_dofs: the global dofs, Dirichlet dofs excluded. */
PetscErrorCode MMContactChooseFormulation(MMContact ct, PetscInt n_dofs)
{
  extern PetscFunctionList MMContactList;
  const char  **names;
  int           n;
  MMCostInput   in;
  PetscReal     best = PETSC_INFINITY, second = PETSC_INFINITY;
  char          second_name[MM_TYPE_LEN] = "";

  PetscFunctionBeginUser;
  in.dim      = ct->dim;
  in.dofs     = PetscMax((PetscReal)n_dofs, 1);
  in.cfl      = ct->h_c > 0 ? ct->material->c_p_max * ct->pb.dt / ct->h_c : 1;
  if (!(in.cfl >= 0 && in.cfl < 1e6)) in.cfl = 1; /* a dt refused later (-ts_dt <= 0, inf) predicts nothing */
  in.steps    = PetscMax(ct->pb.steps, 1);
  in.friction = (PetscBool)(ct->pb.mu_max > 0);
  in.n_fc     = ct->n_fc;
  in.finite   = ct->material->finite;
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(ct->comm, &size));
    in.ranks = size;
  }
  PetscCall(PetscFunctionListGet(MMContactList, &names, &n));
  for (int i = 0; i < n && names[i]; ++i) {
    PetscBool has = PETSC_FALSE;
    MMCost    c;
    PetscReal total;
    PetscCall(Predict(ct, names[i], &in, &has, &c));
    if (!has) continue;
    total = c.setup + in.steps * c.step;
    if (total < best) {
      if (best < PETSC_INFINITY) PetscCall(PetscStrncpy(second_name, ct->opt.contact_formulation, sizeof(second_name)));
      second = best;
      best   = total;
      PetscCall(PetscStrncpy(ct->opt.contact_formulation, names[i], sizeof(ct->opt.contact_formulation)));
    } else if (total < second) {
      second = total;
      PetscCall(PetscStrncpy(second_name, names[i], sizeof(second_name)));
    }
  }
  PetscCall(PetscFree(names));
  PetscCheck(best < PETSC_INFINITY, ct->comm, PETSC_ERR_PLIB, "No contact formulation can carry this problem");
  if (second < PETSC_INFINITY) PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: %.0f steps predicted %.3g s, %s %.3g s)", (double)in.steps, (double)best, second_name, (double)second));
  else PetscCall(PetscSNPrintf(ct->auto_why, sizeof(ct->auto_why), " (auto: the only formulation for this problem)"));
  PetscFunctionReturn(0);
}
