/* The Newmark context's life cycle: it owns the stepper's state, history row, damping and audits,
 * and borrows the lower components it steps (fem's operators, material and loads, contact, friction). */
#include "newmarkimpl.h"

PetscLogEvent MM_TS_Energy, MM_TS_Momenta, MM_TS_Deformation, MM_TS_Certificate, MM_TS_StaticFinite;

/*@
  MMTSInitializePackage - Registers the TS type newmark, the TSAdapt type growback and ts's log
  events, once

  Not collective

  Level: developer

.seealso: `MMNewmarkCreate()`, `MMIOInitializePackage()`
@*/
PetscErrorCode MMTSInitializePackage(void)
{
  static PetscBool initialized = PETSC_FALSE;
  PetscClassId     id;

  PetscFunctionBeginUser;
  if (initialized) PetscFunctionReturn(0);
  initialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("MM stepper", &id));
  PetscCall(PetscLogEventRegister("MMEnergy", id, &MM_TS_Energy));
  PetscCall(PetscLogEventRegister("MMMomenta", id, &MM_TS_Momenta));
  PetscCall(PetscLogEventRegister("MMDeformation", id, &MM_TS_Deformation));
  PetscCall(PetscLogEventRegister("MMStepCertificate", id, &MM_TS_Certificate));
  PetscCall(PetscLogEventRegister("MMStaticFinite", id, &MM_TS_StaticFinite));
  PetscCall(MMNewmarkRegister());
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkCreate - Creates the Newmark stepper's context, which owns the state, the history row,
  the damping and the audits

  Collective

  Input Parameter:
. comm - the run's communicator

  Output Parameter:
. nm - the new context

  Level: beginner

.seealso: `MMNewmarkSetFromOptions()`, `MMNewmarkSetUp()`, `MMNewmarkCreateTS()`, `MMNewmarkDestroy()`
@*/
PetscErrorCode MMNewmarkCreate(MPI_Comm comm, MMNewmark *nm)
{
  PetscFunctionBeginUser;
  PetscCall(MMTSInitializePackage());
  PetscCall(PetscNew(nm));
  (*nm)->comm = comm;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkSetProblem - Gives the stepper the problem's data: the initial state, the obstacles
  (borrowed) and the values its messages quote

  Logically collective

  Input Parameters:
+ nm - the stepper's context
- pb - the problem, copied (MMOptionsGetNewmarkProblem())

  Level: intermediate

.seealso: `MMNewmarkSetUp()`, `MMNewmarkInitialState()`
@*/
PetscErrorCode MMNewmarkSetProblem(MMNewmark nm, const MMNewmarkProblem *pb)
{
  PetscFunctionBeginUser;
  nm->pb = *pb;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkSetUp - Gives the stepper the lower components it steps, borrowed until
  MMNewmarkDestroy()

  Logically collective

  Input Parameters:
+ nm       - the stepper's context
. op       - fem's operators, in the contact frame
. material - the bodies' material
. loads    - the loads
- contact  - the contact object, set up

  Level: intermediate

.seealso: `MMNewmarkSetProblem()`, `MMNewmarkInitialState()`, `MMNewmarkSetFriction()`
@*/
PetscErrorCode MMNewmarkSetUp(MMNewmark nm, MMOperators op, MMMaterial *material, MMLoads *loads, MMContact contact)
{
  PetscFunctionBeginUser;
  nm->op       = op;
  nm->material = material;
  PetscCall(MMFEGetDM(op, &nm->dm));
  PetscCall(MMFEGetDimension(op, &nm->dim));
  nm->loads    = loads;
  nm->contact  = contact;
  nm->law      = MMStepLawGetOps(material); /* the step's law (step_laws.c) */
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkSetFriction - Gives the stepper the friction solver, set up after the initial state on
  its reaction

  Logically collective

  Input Parameters:
+ nm       - the stepper's context
- friction - the friction solver, set up (borrowed)

  Level: intermediate

.seealso: `MMNewmarkInitialState()`, `MMFrictionSetUp()`
@*/
PetscErrorCode MMNewmarkSetFriction(MMNewmark nm, MMFriction friction)
{
  PetscFunctionBeginUser;
  nm->friction = friction;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetState - Gives the stepper's state: u, v, a and the reactions, at the step and at the
  previous one

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameter:
. state - the state, owned by the context

  Level: intermediate

.seealso: `MMNewmarkGetHistory()`, `MMNewmarkGetDamping()`
@*/
PetscErrorCode MMNewmarkGetState(MMNewmark nm, MMState **state)
{
  PetscFunctionBeginUser;
  *state = &nm->state;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetHistory - Gives the stepper's history row and its running sums

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameter:
. hist - the history row, owned by the context

  Level: intermediate

.seealso: `MMNewmarkGetState()`, `MMOutputMonitor()`
@*/
PetscErrorCode MMNewmarkGetHistory(MMNewmark nm, MMHistory **hist)
{
  PetscFunctionBeginUser;
  *hist = &nm->hist;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkGetDamping - Gives the stepper's Rayleigh damping

  Not collective

  Input Parameter:
. nm - the stepper's context

  Output Parameter:
. damping - the damping, owned by the context

  Level: intermediate

.seealso: `MMDampingOn()`, `MMDampingGetStepMatrix()`
@*/
PetscErrorCode MMNewmarkGetDamping(MMNewmark nm, MMDamping **damping)
{
  PetscFunctionBeginUser;
  *damping = &nm->damping;
  PetscFunctionReturn(0);
}

/*@
  MMNewmarkDestroy - Destroys the stepper's context and what it owns

  Collective

  Input Parameter:
. nm - the stepper's context

  Level: beginner

.seealso: `MMNewmarkCreate()`
@*/
PetscErrorCode MMNewmarkDestroy(MMNewmark *nm)
{
  MMState *s;

  PetscFunctionBeginUser;
  if (!*nm) PetscFunctionReturn(0);
  s = &(*nm)->state;
  {
    Vec *vecs[] = {&s->u, &s->v, &s->a, &s->u_old, &s->v_old, &s->a_old, &s->react, &s->react_old, &s->work, &s->u_next, &s->du};
    for (size_t i = 0; i < sizeof(vecs) / sizeof(vecs[0]); ++i) PetscCall(VecDestroy(vecs[i]));
  }
  PetscCall(MMDampingDestroy(&(*nm)->damping));
  PetscCall(MMDeformationDestroy(&(*nm)->deform));
  PetscCall(MMMomentaDestroy(&(*nm)->momenta));
  PetscCall(MMNonlinearDestroy(&(*nm)->nl));
  PetscCall(MMNewmarkSchemeDestroy(*nm));
  PetscCall(MMCertificateDestroy(&(*nm)->cert));
  PetscCall(PetscFree(*nm));
  PetscFunctionReturn(0);
}
