/* An obstacle's options, read by the obstacle itself under its prefix -obstacle_NAME_ (a contact
 * pair's under -contact_pair_NAME_), as a KSP reads -ksp_...: its type, the parameters its shape
 * declares (obstacleimpl.h), the side of the body, its friction coefficient and its motion. Each
 * obstacle has its own heading in -help. */
#include "../obstacleimpl.h"
#include "sys.h"

/* The shape's parameters, each into its place in the shape's data. */
static PetscErrorCode ReadParameters(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMObstacle *ob)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ob->ops->nparams; ++i) {
    const MMObstacleParameter *p   = &ob->ops->params[i];
    MMObstacleValue           *val = (MMObstacleValue *)((char *)ob->data + p->offset);
    char                       name[64], key[512];
    PetscBool                  set;

    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s", p->name));
    if (p->kind != MM_OBSTACLE_LENGTH) {
      PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, name, p->help, MM_MAX_DIM, val->v, &val->n));
      continue;
    }
    PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_%s", ob->name, p->name));
    PetscCall(MMOptionsCheckValue(comm, key, MM_VALUE_REAL));
    PetscCall(PetscOptionsReal(name, p->help, NULL, val->v[0], &val->v[0], &set));
    PetscCall(MMOptionsCheckFinite(comm, key, val->v, 1));
    val->n = set ? 1 : -1;
  }
  PetscFunctionReturn(0);
}

/* Which side of the shape the body is on. */
static PetscErrorCode ReadSide(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMObstacle *ob)
{
  char      side[32] = "outside", key[512];
  PetscBool out, in;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-side", "sphere, circle, cylinder: outside (the body outside the shape: a bump) or inside (the body inside it: a bowl, a rail, a cavity); mesh: outside (the body on the side the facets' normals point to) or inside (the other side)", side, sizeof(side), NULL));
  PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%s_side", ob->name));
  PetscCall(PetscStrcmp(side, "outside", &out));
  PetscCall(PetscStrcmp(side, "inside", &in));
  PetscCheck(out || in, comm, PETSC_ERR_USER_INPUT, "%s %s: use outside or inside", key, side);
  ob->inside = in;
  PetscFunctionReturn(0);
}

/*@
  MMObstacleSetFromOptions - Reads obstacle NAME of -obstacles under its prefix -obstacle_NAME_

  Collective

  Input Parameters:
+ comm - the communicator
. name - the obstacle's name
- mu   - the default of its _mu (-mu)

  Output Parameter:
. ob - the obstacle

  Note:
  Obstacle NAME of -obstacles: its type and the shape's parameters (checked, and the other shapes'
  refused, by MMObstacleCheck once the dimension is known), its side, mu (default mu) and motion.

  Each obstacle has its own heading in -help. -obstacle_NAME_type defaults to plane; an unknown type
  is refused with the list of the registered ones.

  Level: intermediate

.seealso: `MMObstacleCheck()`, `MMObstacleSetPairFromOptions()`, `MMObstacleCreatePlane()`, `MMObstacleDestroy()`
@*/
PetscErrorCode MMObstacleSetFromOptions(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu)
{
  char type[32] = "plane", types[256], help[512], prefix[128], title[128];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(ob->name, name, sizeof(ob->name)));
  ob->nvelocity = -1;
  ob->stop      = PETSC_MAX_REAL;
  ob->mu        = mu;
  ob->prefixed  = PETSC_TRUE;
  PetscCall(MMObstacleTypesList(types, sizeof(types)));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "obstacle_%s_", name));
  PetscCall(PetscSNPrintf(title, sizeof(title), "mmcontact: obstacle %s", name));
  PetscOptionsBegin(comm, prefix, title, "MMObstacle");
  PetscCall(PetscSNPrintf(help, sizeof(help), "Shape of this obstacle: %s (default plane)", types));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-type", help, type, sizeof(type), NULL));
  PetscCall(MMObstacleSetType(ob, comm, type));
  PetscCall(ReadParameters(PetscOptionsObject, comm, ob));
  if (ob->ops->setfromoptions) PetscCall((*ob->ops->setfromoptions)(PetscOptionsObject, comm, ob));
  PetscCall(ReadSide(PetscOptionsObject, comm, ob));
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-mu", "Coulomb friction coefficient against this obstacle, >= 0 (default -mu)", &ob->mu));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-mu", &ob->mu_given));
  PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, "-velocity", "Constant translation velocity of the obstacle between -obstacle_NAME_start and -obstacle_NAME_stop, d entries (default 0: fixed)", MM_MAX_DIM, ob->velocity, &ob->nvelocity));
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-start", "Time at which the obstacle starts moving, >= 0 (default 0)", &ob->start));
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-stop", "Time at which the obstacle stops, after -obstacle_NAME_start (default: never)", &ob->stop));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/*@
  MMObstacleSetPairFromOptions - Reads contact pair NAME of -contact_pairs under its prefix
  -contact_pair_NAME_

  Collective

  Input Parameters:
+ comm - the communicator
. name - the pair's name
- mu   - the default of its _mu (-mu)

  Output Parameter:
. ob - the pair, type "pair"

  Note:
  Contact pair NAME of -contact_pairs, kept after the rigid obstacles so that each contact node's
  constraint has one index, force column and mu (docs/method.md section 11): its slave and master
  surfaces (physical names) and its friction coefficient (default mu).

  Both surfaces are required, and mu must be >= 0.

  Level: intermediate

.seealso: `MMObstacleSetFromOptions()`, `MMObstacleView()`
@*/
PetscErrorCode MMObstacleSetPairFromOptions(MMObstacle *ob, MPI_Comm comm, const char name[], PetscReal mu)
{
  char      prefix[128], title[128];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(ob->name, name, sizeof(ob->name)));
  PetscCall(PetscStrncpy(ob->type, "pair", sizeof(ob->type)));
  ob->pair = PETSC_TRUE;
  ob->stop = PETSC_MAX_REAL;
  ob->mu   = mu;
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "contact_pair_%s_", name));
  PetscCall(PetscSNPrintf(title, sizeof(title), "mmcontact: contact pair %s", name));
  PetscOptionsBegin(comm, prefix, title, "MMObstacle");
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-slave", "Physical name of the pair's slave surface (a Physical Curve in 2D, Surface in 3D): its nodes carry the constraints and lose their normal mass", ob->slave, sizeof(ob->slave), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Contact pair %s has no slave surface: give -contact_pair_%s_slave NAME, a physical group of the mesh (the finer of the two surfaces)", ob->name, ob->name);
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-master", "Physical name of the pair's master surface: the facets the slave nodes are projected on", ob->master, sizeof(ob->master), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Contact pair %s has no master surface: give -contact_pair_%s_master NAME, a physical group of the mesh on the other body", ob->name, ob->name);
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-mu", "Coulomb friction coefficient between the pair's surfaces, >= 0 (default -mu)", &ob->mu));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-mu", &ob->mu_given));
  PetscCheck(ob->mu >= 0, comm, PETSC_ERR_USER_INPUT, "-contact_pair_%s_mu %g: a friction coefficient is >= 0", ob->name, (double)ob->mu);
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
