/* The Newmark context's life cycle: it owns the stepper's state, history row, damping and audits,
 * and borrows the lower components it steps (fem's operators, material and loads, contact, friction). */
#include "newmarkimpl.h"

PetscLogEvent MM_TS_Energy, MM_TS_Momenta, MM_TS_Deformation;

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
  PetscCall(MMNewmarkRegister());
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkCreate(MPI_Comm comm, MMNewmark *nm)
{
  PetscFunctionBeginUser;
  PetscCall(MMTSInitializePackage());
  PetscCall(PetscNew(nm));
  (*nm)->comm = comm;
  PetscFunctionReturn(0);
}

/* The problem's data, copied: the initial state, the obstacles (borrowed), the audits' thresholds. */
PetscErrorCode MMNewmarkSetProblem(MMNewmark nm, const MMNewmarkProblem *pb)
{
  PetscFunctionBeginUser;
  nm->pb = *pb;
  PetscFunctionReturn(0);
}

/* The lower components, borrowed until MMNewmarkDestroy. */
PetscErrorCode MMNewmarkSetUp(MMNewmark nm, MMOperators *op, MMMaterial *material, MMLoads *loads, MMContact contact)
{
  PetscFunctionBeginUser;
  nm->op       = op;
  nm->material = material;
  nm->loads    = loads;
  nm->contact  = contact;
  nm->law      = MMStepLawGetOps(material); /* the step's law (step_laws.c) */
  PetscFunctionReturn(0);
}

/* Friction is set up after the initial state, on its reaction: handed over then. */
PetscErrorCode MMNewmarkSetFriction(MMNewmark nm, MMFriction friction)
{
  PetscFunctionBeginUser;
  nm->friction = friction;
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkGetState(MMNewmark nm, MMState **state)
{
  PetscFunctionBeginUser;
  *state = &nm->state;
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkGetHistory(MMNewmark nm, MMHistory **hist)
{
  PetscFunctionBeginUser;
  *hist = &nm->hist;
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkGetDamping(MMNewmark nm, MMDamping **damping)
{
  PetscFunctionBeginUser;
  *damping = &nm->damping;
  PetscFunctionReturn(0);
}

PetscErrorCode MMNewmarkDestroy(MMNewmark *nm)
{
  MMState *s;

  PetscFunctionBeginUser;
  if (!*nm) PetscFunctionReturn(0);
  s = &(*nm)->state;
  {
    Vec *vecs[] = {&s->u, &s->v, &s->a, &s->u_old, &s->v_old, &s->a_old, &s->react, &s->react_old, &s->work, &s->u_next};
    for (size_t i = 0; i < sizeof(vecs) / sizeof(vecs[0]); ++i) PetscCall(VecDestroy(vecs[i]));
  }
  PetscCall(MMDampingDestroy(&(*nm)->damping));
  PetscCall(MMDeformationDestroy(&(*nm)->deform));
  PetscCall(MMMomentaDestroy(&(*nm)->momenta));
  PetscCall(MMNonlinearDestroy(&(*nm)->nl));
  PetscCall(MMNewmarkSchemeDestroy(*nm));
  PetscCall(PetscFree(*nm));
  PetscFunctionReturn(0);
}
