/* What the other components read of the contact object, and its per-node state for a checkpoint
 * (src/io/checkpoint.c): each through a function, the formulation's part through its ops. */
#include "../contactimpl.h"

PetscErrorCode MMContactGetNodes(MMContact ct, MMContactNodes *nodes)
{
  PetscFunctionBeginUser;
  nodes->enabled      = ct->enabled;
  nodes->moving       = ct->moving;
  nodes->dim          = ct->dim;
  nodes->n_local      = ct->n_local;
  nodes->n_global     = ct->n_global;
  nodes->ncomp        = ct->ncomp;
  nodes->n_corners    = ct->n_corners;
  nodes->n_fc         = ct->n_fc;
  nodes->h_c          = ct->h_c;
  nodes->dt           = ct->Kt_dt;
  nodes->is_normal    = ct->is_normal;
  nodes->is_tangent   = ct->is_tangent;
  nodes->is_star      = ct->is_star;
  nodes->is_interior  = ct->is_interior;
  nodes->is_massless  = ct->is_massless;
  nodes->gap          = ct->gap;
  nodes->mu           = ct->mu;
  nodes->node_frame   = ct->node_frame;
  nodes->obstacle     = ct->obstacle;
  nodes->vertex       = ct->vertex;
  nodes->scalar_index = ct->scalar_index;
  nodes->second       = ct->second;
  nodes->fc_obstacle  = ct->fc_obstacle;
  nodes->pairs_sliding = ct->pairs.large;
  for (PetscInt i = 0; i < MM_MAX_DIM; ++i)
    for (PetscInt j = 0; j < MM_MAX_DIM; ++j) nodes->frame[i][j] = ct->frame[i][j];
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactGetRHS(MMContact ct, Vec *b)
{
  PetscFunctionBeginUser;
  *b = ct->qp.b;
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactGetObstacleForce(MMContact ct, PetscInt b, PetscReal force[])
{
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) force[d] = ct->enabled ? ct->force_obstacle[MM_MAX_DIM * b + d] : 0.0;
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactGetSolverText(MMContact ct, const char **type, const char **choice, const char **products)
{
  PetscFunctionBeginUser;
  *type     = ct->type;
  *choice   = ct->auto_type && ct->enabled ? ct->auto_why : "";
  *products = "";
  if (ct->ops->getproducts) PetscCall((*ct->ops->getproducts)(ct, products));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactGetPairCounts(MMContact ct, PetscInt p, PetscInt *slave_nodes, PetscInt *node_to_node, PetscInt *master_facets)
{
  PetscFunctionBeginUser;
  *slave_nodes   = ct->pairs.count[2 * p];
  *node_to_node  = ct->pairs.count[2 * p + 1];
  *master_facets = ct->pairs.nf[p];
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactGetCandidateCounts(MMContact ct, PetscInt *n_set, PetscInt *resolves)
{
  PetscFunctionBeginUser;
  *n_set = *resolves = 0;
  if (ct->ops->getcandidatecounts) PetscCall((*ct->ops->getcandidatecounts)(ct, n_set, resolves));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactSetCandidateResolves(MMContact ct, PetscInt resolves)
{
  PetscFunctionBeginUser;
  if (ct->ops->setcandidateresolves) PetscCall((*ct->ops->setcandidateresolves)(ct, resolves));
  PetscFunctionReturn(0);
}

/* Whether slot c is row k's: a first row leaves a following second row its slots */
static PetscBool NodeStateOwned(MMContact ct, PetscInt k, PetscInt c)
{
  const PetscBool second_slot = (PetscBool)(c == MM_CONTACT_STATE_SECOND_ACTIVE || c == MM_CONTACT_STATE_SECOND_RHO || c == MM_CONTACT_STATE_SECOND_AS);

  if (ct->second[k]) return second_slot;
  return (PetscBool)!(k + 1 < ct->n_local && ct->second[k + 1] && second_slot);
}

PetscErrorCode MMContactGetNodeState(MMContact ct, PetscInt k, PetscInt *vertex, PetscScalar state[], PetscBool owned[])
{
  const PetscScalar *ra = NULL;

  PetscFunctionBeginUser;
  *vertex = ct->vertex[k];
  for (PetscInt c = 0; c < MM_CONTACT_NODE_STATE; ++c) {
    state[c] = 0;
    owned[c] = NodeStateOwned(ct, k, c);
  }
  if (ct->rho) PetscCall(VecGetArrayRead(ct->rho, &ra));
  if (ct->second[k]) {
    /* a corner's second row (frictionless): its states in its vertex's unused friction slots */
    state[MM_CONTACT_STATE_SECOND_ACTIVE] = (PetscScalar)ct->was_active[k];
    if (ra) state[MM_CONTACT_STATE_SECOND_RHO] = ra[k];
  } else {
    state[0] = 1;
    state[2] = ct->slipping ? (PetscScalar)ct->slipping[k] : 0;
    state[3] = (PetscScalar)ct->was_active[k];
    if (ct->slip_dir) {
      state[4] = ct->slip_dir[2 * k];
      state[5] = ct->slip_dir[2 * k + 1];
    }
    for (PetscInt c = 0; ra && c < ct->ncomp; ++c) state[6 + c] = ra[k * ct->ncomp + c];
  }
  if (ra) PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  if (ct->ops->getnodestate) PetscCall((*ct->ops->getnodestate)(ct, k, ct->second[k], state));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactSetNodeState(MMContact ct, PetscInt k, const PetscScalar state[], PetscBool *second)
{
  PetscScalar *ra = NULL;

  PetscFunctionBeginUser;
  *second           = ct->second[k];
  ct->was_active[k] = (PetscBool)(PetscRealPart(state[ct->second[k] ? MM_CONTACT_STATE_SECOND_ACTIVE : 3]) != 0);
  if (ct->rho) PetscCall(VecGetArray(ct->rho, &ra));
  if (ct->second[k]) {
    if (ra) ra[k] = state[MM_CONTACT_STATE_SECOND_RHO];
  } else {
    if (ct->slipping) ct->slipping[k] = (PetscBool)(PetscRealPart(state[2]) != 0);
    if (ct->slip_dir) {
      ct->slip_dir[2 * k]     = PetscRealPart(state[4]);
      ct->slip_dir[2 * k + 1] = PetscRealPart(state[5]);
    }
    for (PetscInt c = 0; ra && c < ct->ncomp; ++c) ra[k * ct->ncomp + c] = state[6 + c];
  }
  if (ra) PetscCall(VecRestoreArray(ct->rho, &ra));
  if (ct->ops->setnodestate) PetscCall((*ct->ops->setnodestate)(ct, k, ct->second[k], state));
  PetscFunctionReturn(0);
}
