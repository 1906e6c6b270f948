/* The contact boundary handed down to fem for the mass (MMFEAssembleOperators): the dofs M* drops
 * and each owned contact row's vertex and frame (docs/method.md section 2). */
#include "../contactimpl.h"

PetscErrorCode MMContactGetMassBoundary(MMContact ct, MMMassBoundary *mb)
{
  PetscFunctionBeginUser;
  mb->massless     = ct->enabled ? ct->is_massless : NULL;
  mb->n            = ct->n_local;
  mb->vertex       = ct->vertex;
  mb->scalar_index = ct->scalar_index;
  mb->second       = ct->second;
  mb->frame        = ct->node_frame;
  mb->fc_obstacle  = ct->fc_obstacle;
  PetscFunctionReturn(0);
}
