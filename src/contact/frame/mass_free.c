/* The mass in free flight (-mass_free_flight, docs/method.md section 2, "The mass in free flight").
 *
 * -mass's M* drops the contact nodes' normal mass along directions fixed in the w-frame. A body that
 * turns carries those massless directions with its nodes while they stay where they were in space:
 * M*'s node blocks are not multiples of the identity, so sum_i v_i x (M* v)_i is not zero and the
 * finite-strain scheme, exact for the angular momentum with M, loses it with M* (6.7% on a cube
 * spinning in free flight, docs/method.md section 13). The modified mass is needed only where a node
 * can touch: with the finite-strain laws, whose step uses v^n and not a^n (docs/method.md section 13),
 * M* may change at a step's start with its kinetic energy booked (W_frame, as the frames that follow
 * book theirs). So M* is M while no contact node is within reach of an obstacle, and -mass's M* from
 * the step that brings one near until every node is well clear again. The contact dofs are the same
 * throughout; only M*, K~ and what is built on M* change. */
#include "frameimpl.h"
#include "../contactimpl.h"
#include "obstacle.h"

/* Whether the switches apply: a finite-strain law (the linear step's a^n would not balance a new M*),
 * a mass with massless dofs, rigid obstacles without corners or friction corners (a second row's N
 * and a pair's N are built on the massless rows, docs/method.md sections 11 and 12). Given and
 * inapplicable: refused, naming why. */
static PetscErrorCode FreeFlightApplies(MMContact ct, PetscBool *applies, const char **why)
{
  PetscInt fc = 0, fc_all;

  PetscFunctionBeginUser;
  *why = NULL;
  for (PetscInt k = 0; ct->fc_obstacle && k < ct->n_local; ++k) fc += ct->fc_obstacle[k] >= 0;
  PetscCall(MPIU_Allreduce(&fc, &fc_all, 1, MPIU_INT, MPI_SUM, ct->comm));
  if (!ct->material->finite) *why = "the linear law's step balances a^n with the M* of the step before (use -elasticity svk or neohookean)";
  else if (ct->mass.type == MM_MASS_STANDARD) *why = "-mass standard has no massless dofs";
  else if (ct->transform.N) *why = "contact pairs and corners (a node on two obstacles) build their transform on the massless rows";
  else if (fc_all) *why = "friction corners build their second law on the massless rows";
  *applies = (PetscBool)(ct->enabled && !*why);
  PetscFunctionReturn(0);
}

/* At set-up, before M* is built: the switches resolved, and the whole w-frame M kept for them (the
 * frames that follow keep it already: one matrix for both) */
PetscErrorCode MMContactMassFreeSetUp(MMContact ct)
{
  MMContactMass *mass = &ct->mass;
  PetscBool      applies;
  const char    *why;

  PetscFunctionBeginUser;
  PetscCall(FreeFlightApplies(ct, &applies, &why));
  PetscCheck(!(mass->free_flight_set && mass->free_flight && ct->enabled) || applies, ct->comm, PETSC_ERR_SUP, "-mass_free_flight does not apply here: %s. Drop -mass_free_flight", why);
  mass->free_on = (PetscBool)(mass->free_flight && applies);
  if (!mass->free_on) PetscFunctionReturn(0);
  if (ct->frames.M) {
    PetscCall(PetscObjectReference((PetscObject)ct->frames.M));
    mass->Mall = ct->frames.M;
  } else PetscCall(MatDuplicate(mass->M, MAT_COPY_VALUES, &mass->Mall));
  PetscFunctionReturn(0);
}

PetscErrorCode MMContactMassFreeDestroy(MMContactMass *mass)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&mass->Mall));
  PetscFunctionReturn(0);
}

/*@
  MMContactMassFreeFlight - Tells whether M* switches to the standard mass in free flight, and whether
  it is the standard mass now

  Not collective

  Input Parameter:
. ct - the contact object, its frame set up

  Output Parameters:
+ on     - the switches apply (-mass_free_flight resolved), or NULL
- is_free - M* is M now, or NULL

  Level: intermediate

.seealso: `MMContactMassSetFree()`, `MMContactMassReach()`
@*/
PetscErrorCode MMContactMassFreeFlight(MMContact ct, PetscBool *on, PetscBool *is_free)
{
  PetscFunctionBeginUser;
  if (on) *on = ct->mass.free_on;
  if (is_free) *is_free = ct->mass.is_free;
  PetscFunctionReturn(0);
}

/*@
  MMContactMassSetFree - Makes M* the standard mass M (free flight) or -mass's M* again

  Collective

  Input Parameters:
+ ct      - the contact object
- is_free - M* is to be M

  Note:
  M* is rebuilt from the whole w-frame M as at set-up (mass_star.c; -mass redistributed gives the
  normal mass back anew), K~ and its factor, the candidate columns and the preconditioner are
  rebuilt at the next MMContactSetStepMatrix, and what holders built on M* (the momenta's
  functionals) is stale. The caller books the kinetic energy that moves, 1/2 v.(M*_new - M*_old) v.

  Level: intermediate

.seealso: `MMContactMassFreeFlight()`, `MMContactMassReach()`
@*/
PetscErrorCode MMContactMassSetFree(MMContact ct, PetscBool is_free)
{
  MMContactMass *mass = &ct->mass;
  MMMassBoundary mb;

  PetscFunctionBeginUser;
  PetscCheck(mass->free_on, ct->comm, PETSC_ERR_ARG_WRONGSTATE, "The mass in free flight is off");
  if (is_free == mass->is_free) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_MassFree, 0, 0, 0, 0));
  mass->is_free = is_free;
  MMContactMassBoundary(ct, &mb);
  /* M*'s massless dofs: mass_star.c holds a reference to them while they have no mass */
  PetscCall(ISDestroy(&mass->massless));
  if (mb.massless) {
    PetscCall(PetscObjectReference((PetscObject)mb.massless));
    mass->massless = mb.massless;
  }
  PetscCall(MMContactMassRebuild(mass, ct->op, mass->Mall, ct->material, &mb));
  mass->switches[is_free ? 0 : 1]++;
  ct->Kt_dt   = 0;
  ct->kept.dt = 0;
  PetscCall(MMContactHeldInvalidate(ct));
  PetscCall(PetscLogEventEnd(MMCONTACT_MassFree, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactMassReach - The smallest distance, over the contact rows, from a predicted displacement to
  the row's bound at a time: how near the body comes to its obstacles

  Collective

  Input Parameters:
+ ct - the contact object
. w  - the predicted displacement (w-frame)
- t  - the time of the prediction (moving obstacles are where they are then)

  Output Parameters:
+ slack - min over the rows of g_k(t) - w_k (all ranks; PETSC_MAX_REAL without rows)
- h_c   - the contact cells' size h_c', the scale of the reach

  Note:
  The bound each row's contact solve enforces, w_nu <= g(t) = g_0 + c(t).nu (docs/method.md section 8):
  a row with slack is not held by it.

  Level: intermediate

.seealso: `MMContactMassSetFree()`
@*/
PetscErrorCode MMContactMassReach(MMContact ct, Vec w, PetscReal t, PetscReal *slack, PetscReal *h_c)
{
  const PetscInt     dim = ct->dim;
  const PetscInt    *in;
  const PetscScalar *wa, *g0;
  PetscInt           rstart;
  PetscReal          s = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(w, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(ct->gap0, &g0));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const MMObstacle *ob = &ct->pb.obstacles[ct->obstacle[k]];
    const PetscReal  *F  = &ct->node_frame[9 * k];
    PetscReal         c[MM_MAX_DIM] = {0, 0, 0}, g = PetscRealPart(g0[k]);
    MMObstacleDisplacement(ob, dim, t, c);
    for (PetscInt d = 0; d < dim; ++d) g += c[d] * F[d];
    s = PetscMin(s, g - PetscRealPart(wa[in[k] - rstart]));
  }
  PetscCall(VecRestoreArrayRead(ct->gap0, &g0));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(&s, slack, 1, MPIU_REAL, MPIU_MIN, ct->comm));
  *h_c = ct->h_c;
  PetscFunctionReturn(0);
}

/*@
  MMContactMassFreeGetSwitches - Gives the run's switches of M*: to M, and back to -mass's M*

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. switches - to M (0) and back (1)

  Level: developer

.seealso: `MMContactMassFreeRestore()`
@*/
PetscErrorCode MMContactMassFreeGetSwitches(MMContact ct, PetscInt switches[2])
{
  PetscFunctionBeginUser;
  switches[0] = ct->mass.switches[0];
  switches[1] = ct->mass.switches[1];
  PetscFunctionReturn(0);
}

/*@
  MMContactMassFreeRestore - Takes, on -restart, the checkpoint's mass: M* is M if it was, and the
  run's counts

  Collective

  Input Parameters:
+ ct       - the contact object
. is_free  - the checkpointed run's M* was M
- switches - its switches so far

  Level: developer

.seealso: `MMContactMassSetFree()`, `MMContactMassFreeGetSwitches()`
@*/
PetscErrorCode MMContactMassFreeRestore(MMContact ct, PetscBool is_free, const PetscInt switches[2])
{
  PetscFunctionBeginUser;
  if (!ct->mass.free_on) PetscFunctionReturn(0);
  PetscCall(MMContactMassSetFree(ct, is_free));
  ct->mass.switches[0] = switches[0];
  ct->mass.switches[1] = switches[1];
  PetscFunctionReturn(0);
}

/* Its line of the closing summary */
PetscErrorCode MMContactMassFreeView(MMContact ct, PetscViewer viewer)
{
  const MMContactMass *mass = &ct->mass;
  PetscBool            ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii || !mass->free_on) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  mass in free flight (-mass_free_flight): M* was M %" PetscInt_FMT " time%s, -mass %s again %" PetscInt_FMT " time%s as a contact node came within h_c' of its obstacle; M* is %s at the end\n", mass->switches[0], mass->switches[0] == 1 ? "" : "s", MMMassTypes[mass->type], mass->switches[1], mass->switches[1] == 1 ? "" : "s", mass->is_free ? "M" : "-mass's"));
  PetscFunctionReturn(0);
}
