/* What the other components read of the contact object, and its per-node state for a checkpoint
 * (src/io/checkpoint.c): each through a function, the formulation's part through its ops. */
#include "../contactimpl.h"

/*@
  MMContactGetNodes - Gives what the other components read of the contact set, as it is now

  Not collective

  Input Parameter:
. ct - the contact object, set up

  Output Parameter:
. nodes - the contact set: its arrays and objects are the contact object's, valid until it is destroyed

  Level: intermediate

.seealso: `MMContactGetOperators()`, `MMContactGetNodeState()`
@*/
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
  nodes->h_min        = ct->h_min;
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

/*@
  MMContactGetRHS - Gives the vector of the step problem's right-hand side b

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. b - contact's vector, which the stepper fills (borrowed)

  Level: developer

.seealso: `MMContactSolve()`, `MMContactSetStepMatrix()`
@*/
PetscErrorCode MMContactGetRHS(MMContact ct, Vec *b)
{
  PetscFunctionBeginUser;
  *b = ct->qp.b;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetObstacleForce - Gives the contact force on an obstacle at the last step

  Not collective

  Input Parameters:
+ ct - the contact object
- b  - the obstacle's index

  Output Parameter:
. force - its Cartesian components, MM_MAX_DIM entries, zero without contact

  Level: intermediate

.seealso: `MMContactDiagnostics()`
@*/
PetscErrorCode MMContactGetObstacleForce(MMContact ct, PetscInt b, PetscReal force[])
{
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) force[d] = ct->enabled ? ct->force_obstacle[MM_MAX_DIM * b + d] : 0.0;
  PetscFunctionReturn(0);
}

/*@
  MMContactGetSolverText - Gives the start-up report's strings of the solver: the formulation, why
  it was chosen and how the CG multiplies by K~

  Not collective

  Input Parameter:
. ct - the contact object, set up

  Output Parameters:
+ type     - the formulation
. choice   - "" or why -contact_formulation auto chose it
- products - how the CG multiplies by K~, "" without CG

  Level: developer

.seealso: `MMContactSetUpView()`, `MMContactGetStepKSP()`
@*/
PetscErrorCode MMContactGetSolverText(MMContact ct, const char **type, const char **choice, const char **products)
{
  PetscFunctionBeginUser;
  *type     = ct->type;
  *choice   = (ct->auto_type && ct->enabled) || (!ct->enabled && ct->opt.iterative_dofs < 0) ? ct->auto_why : "";
  *products = "";
  if (ct->ops->getproducts) PetscCall((*ct->ops->getproducts)(ct, products));
  PetscFunctionReturn(0);
}

/*@
  MMContactGetPairCounts - Gives a contact pair's counts for the start-up report

  Not collective

  Input Parameters:
+ ct - the contact object, set up
- p  - the pair's index among the contact pairs

  Output Parameters:
+ slave_nodes   - its slave nodes
. node_to_node  - those facing a master node
- master_facets - its master facets

  Level: developer

.seealso: `MMContactSetUpView()`
@*/
PetscErrorCode MMContactGetPairCounts(MMContact ct, PetscInt p, PetscInt *slave_nodes, PetscInt *node_to_node, PetscInt *master_facets)
{
  PetscFunctionBeginUser;
  *slave_nodes   = ct->pairs.count[2 * p];
  *node_to_node  = ct->pairs.count[2 * p + 1];
  *master_facets = ct->pairs.nf[p];
  PetscFunctionReturn(0);
}

/*@
  MMContactGetCandidateCounts - Gives the candidate set's size at the last step and its re-solves
  over the run

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameters:
+ n_set    - the candidate set's size, 0 without one
- resolves - the VI re-solves over the run, 0 without a candidate set

  Level: developer

.seealso: `MMContactSetCandidateResolves()`, `MMContactDiagnostics()`
@*/
PetscErrorCode MMContactGetCandidateCounts(MMContact ct, PetscInt *n_set, PetscInt *resolves)
{
  PetscFunctionBeginUser;
  *n_set = *resolves = 0;
  if (ct->ops->getcandidatecounts) PetscCall((*ct->ops->getcandidatecounts)(ct, n_set, resolves));
  PetscFunctionReturn(0);
}

/*@
  MMContactSetCandidateResolves - Sets the run's count of re-solves on the candidate set (a
  restart's), for a formulation that has one

  Not collective

  Input Parameters:
+ ct       - the contact object
- resolves - the count

  Level: developer

.seealso: `MMContactGetCandidateCounts()`
@*/
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

/*@
  MMContactGetNodeState - Gives a contact row's state for a checkpoint

  Not collective

  Input Parameters:
+ ct - the contact object
- k  - the owned contact row

  Output Parameters:
+ vertex - its mesh point
. state  - MM_CONTACT_NODE_STATE values
- owned  - which of the slots row k writes

  Level: developer

.seealso: `MMContactSetNodeState()`
@*/
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

/*@
  MMContactSetNodeState - Restores a contact row's state from a checkpoint

  Not collective

  Input Parameters:
+ ct    - the contact object
. k     - the owned contact row
- state - its MM_CONTACT_NODE_STATE values

  Output Parameter:
. second - the row is a corner node's second row

  Level: developer

.seealso: `MMContactGetNodeState()`
@*/
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
