/* Checkpoints: the complete state of a run in one HDF5 file, OUTPUT_DIR/checkpoint.h5
 * (docs/method.md section 9). Every field is keyed by the serial mesh's vertex numbers, so the file
 * does not depend on the number of ranks that wrote it. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <petscviewerhdf5.h>
#include "friction.h"
#include "io.h"
#include "ts.h"
#include "fem.h"
#include "outputimpl.h"

#define MM_CKPT_FILE "checkpoint.h5"
#define MM_CKPT_TMP  ".tmp" /* written whole, then renamed over the last good one */
#define MM_CKPT_NODE MM_CONTACT_NODE_STATE /* per vertex: the contact row's state (MMContactGetNodeState) */
#define MM_CKPT_FRAMES_RUN 4 /* frames that follow: W_frame, and the frames' counters (MMContactFramesGetCounters) */
#define MM_CKPT_MASS_FREE 4  /* the mass in free flight: M* is M (1 or 0), the switches to M and back, W_frame */
#define MM_CKPT_VERSION 5 /* 4: the redistributed mass (mass type + 3 if lumped); the Rayleigh damping (alpha, beta, W_d and vC);
                           * 5: the per-cell material's checksums (-bodies) */

/* The scalars of a run, in the "run" vector of the file, in this order. */
typedef enum {
  MM_RUN_VERSION,
  MM_RUN_DIM,
  MM_RUN_VERTICES,
  MM_RUN_CELLS,
  MM_RUN_CONTACT_NODES,
  MM_RUN_COORDINATES, /* a checksum of the vertex coordinates */
  MM_RUN_MU,
  MM_RUN_RANKS,
  MM_RUN_TIME,
  MM_RUN_DT_NEXT,
  MM_RUN_DT_LAST,
  MM_RUN_STEP,
  MM_RUN_WORK_EXT,
  MM_RUN_WORK_CONTACT,
  MM_RUN_WORK_FRICTION,
  MM_RUN_WORK_OBSTACLE,
  MM_RUN_MAX_BALANCE,
  MM_RUN_MAX_PENETRATION,
  MM_RUN_ENERGY_SCALE,
  MM_RUN_RESOLVES,
  MM_RUN_SNAPSHOTS,
  MM_RUN_E,
  MM_RUN_NU,
  MM_RUN_RHO,
  MM_RUN_MASS,    /* the mass type, plus 3 if lumped */
  MM_RUN_DT_USER, /* -ts_dt */
  MM_RUN_WORK_DAMPING,
  MM_RUN_DAMPING_ALPHA, /* the Rayleigh damping, part of the fingerprint */
  MM_RUN_DAMPING_BETA,
  MM_RUN_ADAPT,   /* the growback adaptor's state, MM_ADAPT_STATE entries */
  MM_RUN_WORK_DIRICHLET = MM_RUN_ADAPT + MM_ADAPT_STATE, /* the moving Dirichlet boundaries' work */
  MM_RUN_MATERIAL,      /* the per-cell lambda, mu and rho's checksums, 3 entries (MMMaterialChecksum) */
  MM_RUN_BODIES = MM_RUN_MATERIAL + 3, /* the number of bodies (-bodies; 1 without) */
  MM_RUN_NUM
} MMRunEntry;
_Static_assert(MM_RUN_NUM <= sizeof(((MMCheckpoint *)0)->run) / sizeof(PetscReal), "MMCheckpoint.run holds the run record");

/* Rayleigh damping is on: its trapezoidal velocity vC is part of the state. */
static PetscBool DampingOn(const MMCheckpoint *ck)
{
  return (PetscBool)(ck->damping->alpha != 0 || ck->damping->beta != 0);
}

/*@
  MMCheckpointSetUp - Gives the checkpoint the objects it writes and restores, borrowed until it is
  destroyed (as KSPSetOperators() does)

  Logically collective

  Input Parameters:
+ c        - the checkpoint object
. opt      - the problem as io needs it (MMOptionsGetIOProblem())
. op       - fem's operators
. material - the bodies' material
. hist     - the stepper's history row
. state    - the stepper's state
. damping  - the stepper's damping
. contact  - the contact object
. friction - the friction solver
- out      - the output object

  Level: intermediate

.seealso: `MMCheckpointSetFromOptions()`, `MMCheckpointLoad()`, `MMCheckpointWrite()`
@*/
PetscErrorCode MMCheckpointSetUp(MMCheckpoint *c, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, MMHistory *hist, MMState *state, MMDamping *damping, MMContact contact, MMFriction friction, MMOutput *out)
{
  PetscFunctionBeginUser;
  c->opt      = opt;
  c->op       = op;
  c->material = material;
  PetscCall(MMFEGetDM(op, &c->dm));
  PetscCall(MMFEGetDimension(op, &c->dim));
  c->hist     = hist;
  c->state    = state;
  c->damping  = damping;
  c->contact  = contact;
  c->friction = friction;
  c->out      = out;
  PetscFunctionReturn(0);
}

/* Where each owned vertex's dofs are: its serial-mesh number, and per component its index in the
 * local part of a global vector, -1 for a Dirichlet (constrained) component. Packing and loading
 * share it, so that the two stay each other's inverse. */
static PetscErrorCode OwnedDofMap(MMCheckpoint *ck, PetscInt *n, PetscInt **serial, PetscInt **loc)
{
  const PetscInt dim = ck->dim;
  PetscSection   gs, ls;
  PetscInt       vStart, vEnd, rstart;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(ck->dm, &gs));
  PetscCall(DMGetLocalSection(ck->dm, &ls));
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(ck->state->u, &rstart, NULL));
  PetscCall(PetscMalloc2(vEnd - vStart, serial, dim * (vEnd - vStart), loc));
  *n = 0;
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt        goff, cdof, j = 0, *l = *loc + dim * *n;
    PetscBool       fixed[MM_MAX_DIM] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
    const PetscInt *cind;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
    PetscCall(PetscSectionGetConstraintIndices(ls, v, &cind));
    for (PetscInt c = 0; c < cdof; ++c) fixed[cind[c]] = PETSC_TRUE;
    for (PetscInt d = 0; d < dim; ++d) l[d] = fixed[d] ? -1 : goff - rstart + j++;
    (*serial)[(*n)++] = ck->vertex_orig[v - vStart];
  }
  PetscFunctionReturn(0);
}

/* w (the free dofs, in each node's frame) into packed, dim entries per serial-mesh vertex. The
 * frames are functions of the reference geometry, or (frames that follow the contact point) of the
 * normal the checkpoint records per node (PackFrames), so frame components are the same on any
 * partition, and no rotation rounds them. */
static PetscErrorCode PackDofs(MMCheckpoint *ck, Vec w, Vec packed)
{
  const PetscInt     dim = ck->dim;
  const PetscScalar *wa;
  PetscInt           n, *serial, *loc;

  PetscFunctionBeginUser;
  PetscCall(OwnedDofMap(ck, &n, &serial, &loc));
  PetscCall(VecGetArrayRead(w, &wa));
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt d = 0; d < dim; ++d)
      if (loc[i * dim + d] >= 0) PetscCall(VecSetValue(packed, serial[i] * dim + d, wa[loc[i * dim + d]], INSERT_VALUES));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(PetscFree2(serial, loc));
  PetscCall(VecAssemblyBegin(packed));
  PetscCall(VecAssemblyEnd(packed));
  PetscFunctionReturn(0);
}

/* The per-node contact state: the friction thresholds, and what the contact object keeps per row
 * (MMContactGetNodeState: the 3D stick/slip states and slip directions, the last active set and
 * the condensed reactions, which warm-start the next step). */
static PetscErrorCode PackContact(MMCheckpoint *ck, Vec src, Vec packed)
{
  const PetscScalar *sa = NULL;
  PetscInt           vStart, vEnd;
  Vec                thresholds;
  MMContactNodes     cn;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(MMFrictionGetThresholds(ck->friction, &thresholds));
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  if (cn.enabled) {
    if (thresholds) PetscCall(VecGetArrayRead(thresholds, &sa));
    for (PetscInt k = 0; k < cn.n_local; ++k) {
      PetscScalar rec[MM_CKPT_NODE];
      PetscBool   owned[MM_CKPT_NODE];
      PetscInt    vertex;
      PetscCall(MMContactGetNodeState(ck->contact, k, &vertex, rec, owned));
      rec[1] = sa ? sa[k] : 0;
      for (PetscInt c = 0; c < MM_CKPT_NODE; ++c)
        if (owned[c]) PetscCall(VecSetValue(packed, MM_CKPT_NODE * ck->vertex_orig[vertex - vStart] + c, rec[c], INSERT_VALUES));
    }
    if (sa) PetscCall(VecRestoreArrayRead(thresholds, &sa));
  }
  PetscCall(VecAssemblyBegin(packed));
  PetscCall(VecAssemblyEnd(packed));
  PetscFunctionReturn(0);
}

/* A per-contact-node record of len entries (get: the node's, when it has one) packed by the node's
 * serial vertex, as the checkpoint keeps it whatever the partition. */
static PetscErrorCode PackNodeRecords(MMCheckpoint *ck, Vec packed, PetscInt len, PetscErrorCode (*get)(MMContact, PetscInt, PetscBool *, PetscScalar[]))
{
  PetscInt       vStart, vEnd;
  MMContactNodes cn;
  PetscScalar    rec[64];

  PetscFunctionBeginUser;
  PetscCheck(len <= 64, PETSC_COMM_SELF, PETSC_ERR_PLIB, "A contact node record of %" PetscInt_FMT " entries", len);
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  for (PetscInt k = 0; k < cn.n_local; ++k) {
    PetscBool has;
    PetscCall(get(ck->contact, k, &has, rec));
    for (PetscInt c = 0; has && c < len; ++c) PetscCall(VecSetValue(packed, len * ck->vertex_orig[cn.vertex[k] - vStart] + c, rec[c], INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(packed));
  PetscCall(VecAssemblyEnd(packed));
  PetscFunctionReturn(0);
}

/* Frames that follow the contact point (-contact_frames follow, docs/method.md section 8): each
 * following contact node's frame normal and gap (MMContactFramesGetRecord). The state is packed in
 * these frames, which the record restores bit for bit; a run with fixed frames writes none. */
static PetscErrorCode PackFrames(MMCheckpoint *ck, Vec src, Vec packed)
{
  PetscFunctionBeginUser;
  PetscCall(PackNodeRecords(ck, packed, MM_CONTACT_FRAME_RECORD, MMContactFramesGetRecord));
  PetscFunctionReturn(0);
}

/* Large sliding (docs/method.md section 11): each sliding slave node's pairing (MMContactPairsGetRecord),
 * which the state w is relative to. */
static PetscErrorCode PackPairs(MMCheckpoint *ck, Vec src, Vec packed)
{
  PetscFunctionBeginUser;
  PetscCall(PackNodeRecords(ck, packed, MM_CONTACT_PAIR_RECORD, MMContactPairsGetRecord));
  PetscFunctionReturn(0);
}

/* Contact pairs under large sliding: the checkpoint has their pairing and the forces the stepper carries. */
static PetscBool PairsSlide(const MMCheckpoint *ck)
{
  MMContactNodes cn;

  if (MMContactGetNodes(ck->contact, &cn)) return PETSC_FALSE;
  return (PetscBool)(cn.enabled && cn.pairs_sliding);
}

/* The contact frames follow the contact point: the checkpoint has their records. */
static PetscBool FramesFollow(const MMCheckpoint *ck)
{
  PetscBool follow = PETSC_FALSE;

  if (MMContactFramesFollow(ck->contact, &follow)) return PETSC_FALSE;
  return follow;
}

/* A checksum of the geometry that does not depend on the partition (up to rounding). */
static PetscErrorCode CoordinateChecksum(MMCheckpoint *ck, PetscReal *sum)
{
  PetscSection       gs, cs;
  Vec                X;
  const PetscScalar *x;
  PetscInt           vStart, vEnd;

  PetscFunctionBeginUser;
  *sum = 0;
  PetscCall(DMGetGlobalSection(ck->dm, &gs));
  PetscCall(DMGetCoordinateSection(ck->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(ck->dm, &X));
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, xoff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    for (PetscInt d = 0; d < ck->dim; ++d) *sum += (d + 1) * PetscRealPart(x[xoff + d]) * (1 + ck->vertex_orig[v - vStart] % 97);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ck->dm)));
  PetscFunctionReturn(0);
}

/* How far two checksums of one geometry may differ: summed in another order (another partition),
 * the N terms' sum moves by at most gamma_N = N eps times the sum of their magnitudes. A fixed
 * relative tolerance would not do: the terms cancel on a mesh centred at the origin, and their
 * magnitudes scale with the units. */
static PetscErrorCode CoordinateChecksumTolerance(MMCheckpoint *ck, PetscReal *tol)
{
  Vec       X;
  PetscReal abssum = 0;
  PetscInt  n;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinates(ck->dm, &X));
  PetscCall(VecGetSize(X, &n));
  PetscCall(VecNorm(X, NORM_1, &abssum));
  /* each term is (d + 1) x (1 + v % 97) <= 3 * 97 |x| */
  *tol = (PetscReal)n * PETSC_MACHINE_EPSILON * 3 * 97 * abssum;
  PetscFunctionReturn(0);
}

static PetscErrorCode RunRecord(MMCheckpoint *ck, TS ts, PetscReal run[])
{
  const MMHistory *h = ck->hist;
  PetscMPIInt      size;
  PetscInt         cStart, cEnd, ncells;
  PetscReal        dt;
  MMContactNodes   cn;
  MMMassType       mass_type; /* -mass, the contact frame's */
  PetscBool        lumped;    /* -mass_lumped, fem's */

  PetscFunctionBeginUser;
  PetscCall(MMFEIsMassLumped(ck->op, &lumped));
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  PetscCall(MMContactGetMassType(ck->contact, &mass_type));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ck->dm), &size));
  PetscCall(DMPlexGetHeightStratum(ck->dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart; /* no overlap: every cell is on one rank */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ck->dm)));
  PetscCall(TSGetTimeStep(ts, &dt));
  run[MM_RUN_VERSION]         = MM_CKPT_VERSION;
  run[MM_RUN_DIM]             = ck->dim;
  run[MM_RUN_VERTICES]        = ck->nv_global;
  run[MM_RUN_CELLS]           = ncells;
  run[MM_RUN_CONTACT_NODES]   = cn.enabled ? cn.n_global : 0;
  PetscCall(CoordinateChecksum(ck, &run[MM_RUN_COORDINATES]));
  run[MM_RUN_MU]              = ck->opt->mu;
  run[MM_RUN_RANKS]           = size;
  run[MM_RUN_TIME]            = h->time;
  run[MM_RUN_DT_NEXT]         = dt;
  run[MM_RUN_DT_LAST]         = ck->state->dt;
  run[MM_RUN_STEP]            = h->step;
  run[MM_RUN_WORK_EXT]        = h->work_ext;
  run[MM_RUN_WORK_CONTACT]    = h->work_contact;
  run[MM_RUN_WORK_FRICTION]   = h->work_friction;
  run[MM_RUN_WORK_OBSTACLE]   = h->work_obstacle;
  run[MM_RUN_MAX_BALANCE]     = h->max_balance;
  run[MM_RUN_MAX_PENETRATION] = h->max_penetration_run;
  run[MM_RUN_ENERGY_SCALE]    = h->energy_scale;
  run[MM_RUN_RESOLVES]        = h->resolves;
  run[MM_RUN_SNAPSHOTS]       = ck->out->n_written;
  run[MM_RUN_E]               = ck->opt->E;
  run[MM_RUN_NU]              = ck->opt->nu;
  run[MM_RUN_RHO]             = ck->opt->rho;
  run[MM_RUN_MASS]            = mass_type + (lumped ? 3 : 0);
  run[MM_RUN_DT_USER]         = ck->state->dt_user;
  run[MM_RUN_WORK_DAMPING]    = h->work_damping;
  run[MM_RUN_DAMPING_ALPHA]   = ck->damping->alpha;
  run[MM_RUN_DAMPING_BETA]    = ck->damping->beta;
  PetscCall(MMAdaptGrowBackGetState(ts, &run[MM_RUN_ADAPT]));
  run[MM_RUN_WORK_DIRICHLET]  = h->work_dirichlet;
  PetscCall(MMMaterialChecksum(ck->material, ck->op, &run[MM_RUN_MATERIAL]));
  run[MM_RUN_BODIES]          = ck->material->n_bodies;
  PetscFunctionReturn(0);
}

/* ---- What the state means: the physics a checkpoint records (docs/reference.md, "Checkpoint and restart") ----
 * The run's law and material per body, mass, damping, Dirichlet data and contact data (obstacles,
 * contact boundary, pairs, the pairs' sliding, friction coefficients), each as the option that sets
 * it and its value, stored as string attributes of the "run" dataset. A restart refuses any
 * difference, naming the option and both values. The solvers, the contact formulation and their
 * tolerances change how a step is solved, not what the state is, and may change at a restart; so
 * may -ts_dt and -ts_max_time; the loads (gravity, tractions, pressures, point forces) are not
 * recorded either: the state u, v, a is the same in any of them, and a continuation under other
 * loads is a new question the energy audit books from the restart on. */
#define MM_PHYS_LEN 512
#define MM_PHYS_COUNT "physics_entries" /* the attribute that says a checkpoint records its physics */

typedef struct {
  char option[MM_PHYS_LEN];
  char value[MM_PHYS_LEN];
} MMPhysicsEntry;

typedef struct {
  PetscInt        n, cap;
  MMPhysicsEntry *e;
} MMPhysics;

static PetscErrorCode PhysicsAdd(MMPhysics *ph, const char option[], const char value[])
{
  PetscFunctionBeginUser;
  if (ph->n == ph->cap) {
    MMPhysicsEntry *e;
    ph->cap = PetscMax(2 * ph->cap, 32);
    PetscCall(PetscMalloc1(ph->cap, &e));
    if (ph->n) PetscCall(PetscArraycpy(e, ph->e, ph->n));
    PetscCall(PetscFree(ph->e));
    ph->e = e;
  }
  PetscCall(PetscStrncpy(ph->e[ph->n].option, option, MM_PHYS_LEN));
  PetscCall(PetscStrncpy(ph->e[ph->n].value, value[0] ? value : "(none)", MM_PHYS_LEN)); /* HDF5 holds no empty string */
  ph->n++;
  PetscFunctionReturn(0);
}

/* option = NAME's option: fmt with one %s for the name (-body_%s_E), or fmt itself without a name (-E) */
static PetscErrorCode PhysicsAddNamed(MMPhysics *ph, const char fmt[], const char name[], const char value[])
{
  char option[MM_PHYS_LEN];

  PetscFunctionBeginUser;
  if (name) PetscCall(PetscSNPrintf(option, sizeof(option), fmt, name));
  else PetscCall(PetscStrncpy(option, fmt, sizeof(option)));
  PetscCall(PhysicsAdd(ph, option, value));
  PetscFunctionReturn(0);
}

/* x in the fewest digits that read back as x: a value that differs in any bit is another value, and
 * the message quotes 0.3 as the user wrote it */
static PetscErrorCode ExactReal(PetscReal x, char buf[], size_t len)
{
  PetscFunctionBeginUser;
  for (int digits = 15; digits <= 17; ++digits) {
    PetscCall(PetscSNPrintf(buf, len, "%.*g", digits, (double)x));
    if (strtod(buf, NULL) == (double)x) break;
  }
  PetscFunctionReturn(0);
}

/* n reals, comma-separated, each exactly (ExactReal) */
static PetscErrorCode PhysicsAddReals(MMPhysics *ph, const char fmt[], const char name[], PetscInt n, const PetscReal x[])
{
  char value[MM_PHYS_LEN] = "", one[64];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; ++i) {
    if (i) PetscCall(PetscStrlcat(value, ",", sizeof(value)));
    PetscCall(ExactReal(x[i], one, sizeof(one)));
    PetscCall(PetscStrlcat(value, one, sizeof(value)));
  }
  PetscCall(PhysicsAddNamed(ph, fmt, name, value));
  PetscFunctionReturn(0);
}

/* The law and material per body: -elasticity -E -nu -rho, or with -bodies each body's */
static PetscErrorCode PhysicsMaterial(MMCheckpoint *ck, MMPhysics *ph)
{
  const MMMaterial *m = ck->material;
  char              list[MM_PHYS_LEN] = "";

  PetscFunctionBeginUser;
  if (!m->named) {
    const MMBody *b = &m->body[0];
    PetscCall(PhysicsAdd(ph, "-elasticity", MMElasticityTypes[b->elasticity]));
    PetscCall(PhysicsAddReals(ph, "-E", NULL, 1, &b->E));
    PetscCall(PhysicsAddReals(ph, "-nu", NULL, 1, &b->nu));
    PetscCall(PhysicsAddReals(ph, "-rho", NULL, 1, &b->rho));
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 0; k < m->n_bodies; ++k) {
    if (k) PetscCall(PetscStrlcat(list, ",", sizeof(list)));
    PetscCall(PetscStrlcat(list, m->body[k].name, sizeof(list)));
  }
  PetscCall(PhysicsAdd(ph, "-bodies", list));
  for (PetscInt k = 0; k < m->n_bodies; ++k) {
    const MMBody *b = &m->body[k];
    PetscCall(PhysicsAddNamed(ph, "-body_%s_group", b->name, b->group ? b->group : ""));
    PetscCall(PhysicsAddNamed(ph, "-body_%s_elasticity", b->name, MMElasticityTypes[b->elasticity]));
    PetscCall(PhysicsAddReals(ph, "-body_%s_E", b->name, 1, &b->E));
    PetscCall(PhysicsAddReals(ph, "-body_%s_nu", b->name, 1, &b->nu));
    PetscCall(PhysicsAddReals(ph, "-body_%s_rho", b->name, 1, &b->rho));
  }
  PetscFunctionReturn(0);
}

/* The mass, the damping and the Dirichlet boundaries (which dofs the state holds, and their data) */
static PetscErrorCode PhysicsMassDampingDirichlet(MMCheckpoint *ck, MMPhysics *ph)
{
  const MMIOProblem *o = ck->opt;
  MMMassType         mass;
  PetscBool          lumped;
  char               list[MM_PHYS_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(MMFEIsMassLumped(ck->op, &lumped));
  PetscCall(MMContactGetMassType(ck->contact, &mass));
  PetscCall(PhysicsAdd(ph, "-mass", MMMassTypes[mass]));
  PetscCall(PhysicsAdd(ph, "-mass_lumped", lumped ? "true" : "false"));
  PetscCall(PhysicsAddReals(ph, "-damping_mass", NULL, 1, &ck->damping->alpha));
  PetscCall(PhysicsAddReals(ph, "-damping_stiffness", NULL, 1, &ck->damping->beta));
  for (PetscInt k = 0; k < o->n_dirichlet; ++k) {
    if (k) PetscCall(PetscStrlcat(list, ",", sizeof(list)));
    PetscCall(PetscStrlcat(list, o->dirichlet[k].name, sizeof(list)));
  }
  PetscCall(PhysicsAdd(ph, "-dirichlet", list));
  for (PetscInt k = 0; k < o->n_dirichlet; ++k) {
    const MMDirichlet *bc = &o->dirichlet[k];
    PetscReal          comps[MM_MAX_DIM];
    char               amp[MM_PHYS_LEN];
    for (PetscInt c = 0; c < bc->ncomp; ++c) comps[c] = bc->comps[c];
    PetscCall(PhysicsAddReals(ph, "-dirichlet_%s_components", bc->name, bc->ncomp, comps));
    PetscCall(PhysicsAddReals(ph, "-dirichlet_%s_value", bc->name, bc->ncomp, bc->values));
    PetscCall(PhysicsAddReals(ph, "-dirichlet_%s_velocity", bc->name, bc->ncomp, bc->velocity));
    PetscCall(PetscSNPrintf(amp, sizeof(amp), "%s %.17g %s", bc->amplitude.kind, (double)bc->amplitude.time, bc->amplitude.table));
    PetscCall(PhysicsAddNamed(ph, "-dirichlet_%s_amplitude", bc->name, amp));
  }
  PetscFunctionReturn(0);
}

/* One rigid obstacle of -obstacles: its shape, position, motion and friction coefficient */
static PetscErrorCode PhysicsObstacle(MMCheckpoint *ck, MMPhysics *ph, const MMObstacle *ob)
{
  const PetscInt dim = ck->dim;
  /* the parameters of the first shapes, every one for every shape (0 where it has none), as
   * checkpoints have always held them; then those of a later shape, its own */
  const char *legacy[] = {"point", "normal", "center", "axis", "radius"}, *names[16];
  PetscInt    n;
  char        key[64], text[MM_PHYS_LEN];
  PetscReal   v[MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(PhysicsAddNamed(ph, "-obstacle_%s_type", ob->name, ob->type));
  for (size_t i = 0; i < PETSC_STATIC_ARRAY_LENGTH(legacy); ++i) {
    const PetscInt m = i == 4 ? 1 : dim;
    PetscCall(MMObstacleGetParameter(ob, legacy[i], m, v, NULL));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%%s_%s", legacy[i]));
    PetscCall(PhysicsAddReals(ph, key, ob->name, m, v));
  }
  PetscCall(MMObstacleGetParameterNames(ob, PETSC_STATIC_ARRAY_LENGTH(names), &n, names));
  for (PetscInt i = 0; i < n; ++i) {
    PetscBool old = PETSC_FALSE;
    for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(legacy); ++k) old = (PetscBool)(old || !strcmp(names[i], legacy[k]));
    if (old) continue;
    PetscCall(MMObstacleGetParameter(ob, names[i], dim, v, NULL));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-obstacle_%%s_%s", names[i]));
    PetscCall(PhysicsAddReals(ph, key, ob->name, dim, v));
  }
  PetscCall(MMObstacleDescribe(ob, text, sizeof(text)));
  if (text[0]) PetscCall(PhysicsAddNamed(ph, "-obstacle_%s_mesh", ob->name, text));
  PetscCall(PhysicsAddNamed(ph, "-obstacle_%s_side", ob->name, ob->inside ? "inside" : "outside"));
  PetscCall(PhysicsAddReals(ph, "-obstacle_%s_mu", ob->name, 1, &ob->mu));
  PetscCall(PhysicsAddReals(ph, "-obstacle_%s_velocity", ob->name, dim, ob->velocity));
  PetscCall(PhysicsAddReals(ph, "-obstacle_%s_start", ob->name, 1, &ob->start));
  PetscCall(PhysicsAddReals(ph, "-obstacle_%s_stop", ob->name, 1, &ob->stop));
  PetscFunctionReturn(0);
}

/* The contact data: on or off, the contact boundary, the rigid obstacles, the pairs and their sliding */
static PetscErrorCode PhysicsContact(MMCheckpoint *ck, MMPhysics *ph)
{
  const MMIOProblem *o = ck->opt;
  MMContactNodes     cn;
  char               list[MM_PHYS_LEN] = "", plist[MM_PHYS_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  PetscCall(PhysicsAdd(ph, "-contact", cn.enabled ? "1" : "0"));
  if (!cn.enabled) PetscFunctionReturn(0);
  PetscCall(PhysicsAdd(ph, "-contact_boundary", o->contact_name));
  for (PetscInt b = 0; b < o->n_obstacles; ++b) {
    char *l = b < o->n_rigid ? list : plist;
    if (b < o->n_rigid && !o->obstacles_named) continue;
    if (l[0]) PetscCall(PetscStrlcat(l, ",", MM_PHYS_LEN));
    PetscCall(PetscStrlcat(l, o->obstacles[b].name, MM_PHYS_LEN));
  }
  PetscCall(PhysicsAdd(ph, "-obstacles", list));
  PetscCall(PhysicsAdd(ph, "-contact_pairs", plist));
  for (PetscInt b = 0; b < o->n_obstacles; ++b) {
    const MMObstacle *ob = &o->obstacles[b];
    if (ob->pair) {
      PetscCall(PhysicsAddNamed(ph, "-contact_pair_%s_slave", ob->name, ob->slave));
      PetscCall(PhysicsAddNamed(ph, "-contact_pair_%s_master", ob->name, ob->master));
      PetscCall(PhysicsAddReals(ph, "-contact_pair_%s_mu", ob->name, 1, &ob->mu));
    } else if (o->obstacles_named) PetscCall(PhysicsObstacle(ck, ph, ob));
    else {
      /* the plane of -obstacle_point and -obstacle_normal, with -mu */
      PetscReal point[MM_MAX_DIM], normal[MM_MAX_DIM];
      PetscBool plane;
      PetscCall(MMObstacleGetPlane(ob, point, normal, &plane));
      PetscCall(PhysicsAddReals(ph, "-obstacle_point", NULL, ck->dim, point));
      PetscCall(PhysicsAddReals(ph, "-obstacle_normal", NULL, ck->dim, normal));
      PetscCall(PhysicsAddReals(ph, "-mu", NULL, 1, &ob->mu));
    }
  }
  /* the pairing's meaning: found once on the reference mesh, or again at each step (the state is relative to it) */
  if (plist[0]) PetscCall(PhysicsAdd(ph, "-contact_pairs_sliding", cn.pairs_sliding ? "large" : "small"));
  PetscFunctionReturn(0);
}

/* This run's physics, in the order a restart compares it: each list (-bodies, -obstacles ...) before its members */
static PetscErrorCode PhysicsList(MMCheckpoint *ck, MMPhysics *ph)
{
  PetscFunctionBeginUser;
  ph->n = ph->cap = 0;
  ph->e = NULL;
  PetscCall(PhysicsMaterial(ck, ph));
  PetscCall(PhysicsMassDampingDirichlet(ck, ph));
  PetscCall(PhysicsContact(ck, ph));
  PetscFunctionReturn(0);
}

/* The physics as attributes of the "run" dataset, and their count */
static PetscErrorCode WritePhysics(MMCheckpoint *ck, PetscViewer viewer)
{
  MMPhysics ph;
  PetscInt  n;

  PetscFunctionBeginUser;
  PetscCall(PhysicsList(ck, &ph));
  for (PetscInt i = 0; i < ph.n; ++i) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "run", ph.e[i].option, PETSC_STRING, ph.e[i].value));
  n = ph.n;
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "run", MM_PHYS_COUNT, PETSC_INT, &n));
  PetscCall(PetscFree(ph.e));
  PetscFunctionReturn(0);
}

/* -restart: the checkpoint's physics against this run's, each difference refused naming the option
 * and both values. A checkpoint without them (written before they were recorded) is continued with a
 * warning: its run record still checks the mesh, E, nu, rho, the cells' material, mass, damping and -mu. */
static PetscErrorCode CheckPhysics(MMCheckpoint *ck, PetscViewer viewer)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)ck->dm);
  MMPhysics ph;
  PetscBool recorded;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "run", MM_PHYS_COUNT, &recorded));
  if (!recorded) {
    PetscCall(PetscPrintf(comm, "mmcontact warning: the checkpoint %s does not record its elasticity law, obstacles, contact pairs and Dirichlet data (written by an older mmcontact): continued with this run's, which must be those of the run that wrote it\n", ck->file));
    PetscFunctionReturn(0);
  }
  PetscCall(PhysicsList(ck, &ph));
  for (PetscInt i = 0; i < ph.n; ++i) {
    const MMPhysicsEntry *e = &ph.e[i];
    char                 *theirs = NULL, given[MM_PHYS_LEN];
    PetscBool             has, same;
    PetscCall(PetscViewerHDF5HasAttribute(viewer, "run", e->option, &has));
    if (has) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "run", e->option, PETSC_STRING, NULL, &theirs));
    else PetscCall(PetscStrallocpy("(not set)", &theirs));
    PetscCall(PetscStrcmp(theirs, e->value, &same));
    if (!same) {
      char written[MM_PHYS_LEN];
      PetscCall(PetscStrncpy(written, theirs, sizeof(written)));
      PetscCall(PetscStrncpy(given, e->value, sizeof(given)));
      PetscCall(PetscFree(theirs));
      PetscCall(PetscFree(ph.e));
      SETERRQ(comm, PETSC_ERR_USER_INPUT, "-restart %s: the checkpoint was written with %s %s, this run has %s %s: its state would mean another problem. Restart with %s %s, as the run that wrote it", ck->file, e->option, written, e->option, given, e->option, written);
    }
    PetscCall(PetscFree(theirs));
  }
  PetscCall(PetscFree(ph.e));
  PetscFunctionReturn(0);
}

/* A vector held on rank 0, for the run's scalars and the snapshot times. */
static PetscErrorCode RootVector(MPI_Comm comm, const char name[], PetscInt n, const PetscReal vals[], Vec *v)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : n, n, v));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  if (!rank) {
    PetscScalar *a;
    PetscCall(VecGetArray(*v, &a));
    for (PetscInt i = 0; i < n; ++i) a[i] = vals[i];
    PetscCall(VecRestoreArray(*v, &a));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ViewPacked(MMCheckpoint *ck, PetscViewer viewer, const char name[], PetscInt bs, Vec src, PetscErrorCode (*pack)(MMCheckpoint *, Vec, Vec))
{
  Vec packed;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)ck->dm), PETSC_DECIDE, bs * ck->nv_global, &packed));
  PetscCall(PetscObjectSetName((PetscObject)packed, name));
  PetscCall(VecZeroEntries(packed));
  PetscCall((*pack)(ck, src, packed));
  PetscCall(VecView(packed, viewer));
  PetscCall(VecDestroy(&packed));
  PetscFunctionReturn(0);
}

/* The vertices of the whole mesh, counted once. */
static PetscErrorCode CountVertices(MMCheckpoint *ck)
{
  PetscInt vStart, vEnd, n = 0;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  for (PetscInt v = vStart; v < vEnd; ++v) n = PetscMax(n, ck->vertex_orig[v - vStart] + 1);
  PetscCall(MPIU_Allreduce(&n, &ck->nv_global, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)ck->dm)));
  PetscFunctionReturn(0);
}

/* The checkpoint's datasets into the file tmp. A failed write returns its error, for the caller's
 * MMOutputHDF5End to name the file. */
/* The mass in free flight (-mass_free_flight, src/contact/frame/mass_free.c): whether M* is M, the
 * run's switches and W_frame so far; written only then, as every other checkpoint keeps its datasets */
static PetscErrorCode WriteMassFree(MMCheckpoint *ck, PetscViewer viewer)
{
  PetscBool on, is_free;
  PetscInt  sw[2];
  PetscReal vals[MM_CKPT_MASS_FREE];
  Vec       mv;

  PetscFunctionBeginUser;
  PetscCall(MMContactMassFreeFlight(ck->contact, &on, &is_free));
  if (!on) PetscFunctionReturn(0);
  PetscCall(MMContactMassFreeGetSwitches(ck->contact, sw));
  vals[0] = is_free ? 1 : 0;
  vals[1] = (PetscReal)sw[0];
  vals[2] = (PetscReal)sw[1];
  vals[3] = ck->hist->work_frame;
  PetscCall(RootVector(PetscObjectComm((PetscObject)ck->dm), "mass_free", MM_CKPT_MASS_FREE, vals, &mv));
  PetscCall(VecView(mv, viewer));
  PetscCall(VecDestroy(&mv));
  PetscFunctionReturn(0);
}

/* The state of the stepper besides u, v, a: the finite-strain iteration matrix's point, and under large
 * sliding the pairing, its counters and the forces carried across pairings (docs/method.md section 9). */
static PetscErrorCode WriteStepperState(MMCheckpoint *ck, TS ts, PetscViewer viewer)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)ck->dm);
  MMNewmark nm;
  Vec       at;
  PetscReal t;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkFromTS(ts, &nm));
  PetscCall(WriteMassFree(ck, viewer));
  PetscCall(MMNewmarkGetTangentPoint(nm, &at, &t));
  if (at) {
    PetscCall(ViewPacked(ck, viewer, "tangent_point", ck->dim, at, PackDofs));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "tangent_point", "time", PETSC_REAL, &t));
  }
  {
    PetscInt step; /* the tangent clamped since a rejection (src/ts/nonlinear.c) */
    PetscCall(MMNewmarkGetTangentClampStep(nm, &step));
    if (step > 0) {
      PetscReal val = (PetscReal)step;
      Vec       cv;
      PetscCall(RootVector(comm, "tangent_clamp_step", 1, &val, &cv));
      PetscCall(VecView(cv, viewer));
      PetscCall(VecDestroy(&cv));
    }
  }
  {
    /* the step certificate's state: the last residual the next step sums with its own, and the
     * solves' tolerance it has tightened to (src/ts/certificate.c): the next step as the run's */
    Vec       r;
    PetscReal tol;
    PetscCall(MMNewmarkGetCertificateResidual(nm, &r));
    if (r) {
      PetscCall(MMContactGetSolveTolerance(ck->contact, &tol, NULL));
      PetscCall(ViewPacked(ck, viewer, "certificate_residual", ck->dim, r, PackDofs));
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "certificate_residual", "contact_tol", PETSC_REAL, &tol));
    }
  }
  if (PairsSlide(ck)) {
    Vec      *f;
    PetscInt  n;
    PetscReal counters[3];
    Vec       cv;
    PetscCall(PetscMalloc1(MMNewmarkCountCarriedForces(nm), &f));
    PetscCall(MMNewmarkGetCarriedForces(nm, &n, f));
    PetscCall(ViewPacked(ck, viewer, "pairs", MM_CONTACT_PAIR_RECORD, NULL, PackPairs));
    for (PetscInt i = 0; i < n; ++i) {
      char name[32];
      PetscCall(PetscSNPrintf(name, sizeof(name), "pairs_force_%" PetscInt_FMT, i));
      PetscCall(ViewPacked(ck, viewer, name, ck->dim, f[i], PackDofs));
    }
    PetscCall(PetscFree(f));
    PetscCall(MMContactPairsGetCounters(ck->contact, counters));
    PetscCall(RootVector(comm, "pairs_run", 3, counters, &cv));
    PetscCall(VecView(cv, viewer));
    PetscCall(VecDestroy(&cv));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteCheckpointFile(MMCheckpoint *ck, TS ts, PetscViewer viewer, const PetscReal run[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)ck->dm);
  MMState    *s    = ck->state;
  Vec         rv, tv;

  PetscFunctionBeginUser;
  PetscCall(RootVector(comm, "run", MM_RUN_NUM, run, &rv));
  PetscCall(VecView(rv, viewer));
  PetscCall(VecDestroy(&rv));
  PetscCall(WritePhysics(ck, viewer));
  PetscCall(RootVector(comm, "snapshot_times", PetscMax(ck->out->n_written, 1), ck->out->n_written ? ck->out->times : run, &tv));
  PetscCall(VecView(tv, viewer));
  PetscCall(VecDestroy(&tv));
  PetscCall(ViewPacked(ck, viewer, "u", ck->dim, s->u, PackDofs));
  PetscCall(ViewPacked(ck, viewer, "v", ck->dim, s->v, PackDofs));
  PetscCall(ViewPacked(ck, viewer, "a", ck->dim, s->a, PackDofs));
  if (DampingOn(ck)) PetscCall(ViewPacked(ck, viewer, "vC", ck->dim, ck->damping->vC, PackDofs));
  PetscCall(ViewPacked(ck, viewer, "react", ck->dim, s->react, PackDofs));
  PetscCall(ViewPacked(ck, viewer, "contact", MM_CKPT_NODE, NULL, PackContact));
  if (FramesFollow(ck)) {
    /* only then: every other checkpoint keeps its datasets */
    PetscReal fr[MM_CKPT_FRAMES_RUN];
    Vec       fv;
    fr[0] = ck->hist->work_frame;
    PetscCall(MMContactFramesGetCounters(ck->contact, &fr[1]));
    PetscCall(ViewPacked(ck, viewer, "frames", MM_CONTACT_FRAME_RECORD, NULL, PackFrames));
    PetscCall(RootVector(comm, "frames_run", MM_CKPT_FRAMES_RUN, fr, &fv));
    PetscCall(VecView(fv, viewer));
    PetscCall(VecDestroy(&fv));
  }
  PetscCall(WriteStepperState(ck, ts, viewer));
  PetscFunctionReturn(0);
}

/* The bytes WriteCheckpointFile writes: its datasets' values, and HDF5's own at the output plan's
 * 3.6 kB a dataset (src/io/output_plan.c); the physics' attributes (WritePhysics) are counted as
 * one dataset's overhead, the stepper's state (WriteStepperState) at its sizes. */
static PetscErrorCode CheckpointBytes(MMCheckpoint *ck, TS ts, PetscReal *bytes)
{
  const PetscBool frames = FramesFollow(ck);
  const PetscReal nv = (PetscReal)ck->nv_global, dim = (PetscReal)ck->dim;
  PetscReal       datasets = 8 + (DampingOn(ck) ? 1 : 0) + (frames ? 2 : 0);
  PetscReal       values   = MM_RUN_NUM + PetscMax(ck->out->n_written, 1) + nv * ((4 + (DampingOn(ck) ? 1 : 0)) * dim + MM_CKPT_NODE);
  MMNewmark       nm;
  Vec             at;
  PetscReal       t;

  PetscFunctionBeginUser;
  if (frames) values += nv * MM_CONTACT_FRAME_RECORD + MM_CKPT_FRAMES_RUN;
  {
    PetscBool free_on;
    PetscCall(MMContactMassFreeFlight(ck->contact, &free_on, NULL));
    if (free_on) {
      values += MM_CKPT_MASS_FREE;
      datasets += 1;
    }
  }
  PetscCall(MMNewmarkFromTS(ts, &nm));
  PetscCall(MMNewmarkGetTangentPoint(nm, &at, &t));
  if (at) {
    values += nv * dim;
    datasets += 1;
  }
  {
    PetscInt step;
    PetscCall(MMNewmarkGetTangentClampStep(nm, &step));
    if (step > 0) {
      values += 1;
      datasets += 1;
    }
  }
  PetscCall(MMNewmarkGetCertificateResidual(nm, &at));
  if (at) {
    values += nv * dim;
    datasets += 1;
  }
  if (PairsSlide(ck)) {
    const PetscInt nf = MMNewmarkCountCarriedForces(nm);
    values += nv * (MM_CONTACT_PAIR_RECORD + nf * dim) + 3;
    datasets += 2 + nf;
  }
  *bytes = values * sizeof(PetscScalar) + datasets * 3.6e3;
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointWrite - Writes the state after the current step to OUTPUT_DIR/checkpoint.h5,
  atomically

  Collective

  Input Parameters:
+ c  - the checkpoint object, set up
- ts - the time stepper

  Note:
  The state after the current step, to OUTPUT_DIR/checkpoint.h5: written whole to a temporary file
  and renamed over the last one, so that a crash while writing leaves the last good checkpoint. A
  failed write (a full disk) stops the run naming the temporary file, exit status 74.

  Level: intermediate

.seealso: `MMCheckpointMonitor()`, `MMCheckpointWriteFinal()`, `MMCheckpointLoad()`
@*/
PetscErrorCode MMCheckpointWrite(MMCheckpoint *ck, TS ts)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)ck->dm);
  PetscReal      run[MM_RUN_NUM];
  char           name[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  PetscMPIInt    rank;
  int            err = 0;
  PetscViewer    viewer;
  PetscReal      bytes = 0;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMIOEvents.checkpoint, 0, 0, 0, 0));
  if (!ck->nv_global) PetscCall(CountVertices(ck));
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/%s", ck->out->dir, MM_CKPT_FILE));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", name, MM_CKPT_TMP));
  PetscCall(RunRecord(ck, ts, run));
  PetscCall(MMOutputCopySnapshots(ck->out)); /* before the checkpoint that counts on it */
  PetscCall(CheckpointBytes(ck, ts, &bytes));
  PetscCall(MMOutputCheckSpace(ck->out->dir, tmp, "the checkpoint", bytes + MMOutputIndexRoom(ck->out)));
  PetscCall(MMOutputHDF5Create(comm, tmp, &viewer));
  PetscCall(MMOutputHDF5Begin());
  ierr = WriteCheckpointFile(ck, ts, viewer, run);
  PetscCall(MMOutputHDF5End(ierr, "write", tmp));
  PetscCall(MMOutputHDF5Close(&viewer, tmp));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && rename(tmp, name)) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "Could not rename %s to %s: %s. The previous checkpoint, if any, is intact", tmp, name, strerror(err));
  ck->written++;
  ck->last_step = ck->hist->step;
  PetscCall(PetscLogEventEnd(MMIOEvents.checkpoint, 0, 0, 0, 0));
  /* a restart continues from here: the index lists every snapshot up to it */
  PetscCall(MMOutputSyncIndex(ck->out));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointSetFromOptions - Reads the checkpoints' options (docs/method.md section 9), each with
  its check

  Collective

  Input Parameters:
+ comm - the run's communicator
- c    - the checkpoint object, zeroed

  Level: intermediate

.seealso: `MMCheckpointSetUp()`, `MMCheckpointDestroy()`
@*/
PetscErrorCode MMCheckpointSetFromOptions(MPI_Comm comm, MMCheckpoint *c)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact checkpoints", "MMCheckpoint");
  c->every = 0;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-checkpoint_every", "Write the complete state to OUTPUT_DIR/checkpoint.h5 every k steps, replacing the previous one atomically (0: only at the end of the run)", &c->every));
  c->restart[0] = 0;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-restart", "Continue the run of a checkpoint: its checkpoint.h5, or the output directory that holds it, on any number of ranks. The history.csv and solution.h5/.xmf of that directory, cut at the checkpoint's step, are continued in -output_dir. Give the options of the run that wrote it: another mesh, or another law, material, mass, damping, Dirichlet or contact data (the checkpoint records them) is refused", c->restart, sizeof(c->restart), NULL));
  PetscOptionsEnd();
  PetscCheck(c->every >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_every %" PetscInt_FMT " must be >= 0 (0: a checkpoint at the end only)", c->every);
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointMonitor - TS monitor that writes a checkpoint every -checkpoint_every steps

  Collective

  Input Parameters:
+ ts   - the time stepper
. step - the step just taken
. time - its time
. u    - the solution vector (unused)
- ctx  - the checkpoint object (MMCheckpoint *)

  Level: intermediate

.seealso: `MMCheckpointWrite()`, `MMCheckpointWriteFinal()`, `TSMonitorSet()`
@*/
PetscErrorCode MMCheckpointMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ptr)
{
  MMCheckpoint  *ck    = (MMCheckpoint *)ptr;
  const PetscInt every = ck->every;

  PetscFunctionBeginUser;
  if (every > 0 && step > 0 && step % every == 0 && step != ck->last_step) PetscCall(MMCheckpointWrite(ck, ts));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointDestroy - Frees what the checkpoint object holds

  Collective

  Input Parameter:
. c - the checkpoint object

  Level: intermediate

.seealso: `MMCheckpointSetFromOptions()`
@*/
PetscErrorCode MMCheckpointDestroy(MMCheckpoint *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c->vertex_orig));
  PetscCall(PetscFree(c->vertex_file));
  PetscCall(PetscFree(c->node));
  PetscCall(PetscFree(c->frames));
  PetscCall(PetscFree(c->pairs));
  PetscCall(VecDestroy(&c->tangent));
  PetscCall(PetscFree(c->snapshot_times));
  PetscFunctionReturn(0);
}

/* ---- Restart: the state of a checkpoint into this run (docs/method.md section 9) ---- */

/* -restart names the file or the output directory that holds checkpoint.h5; the directory of the
 * file is where the history and the snapshots to continue are read from. */
static PetscErrorCode ResolveRestartPath(MMCheckpoint *c)
{
  MPI_Comm      comm = PetscObjectComm((PetscObject)c->dm);
  struct stat   st;
  int           isdir = 0, exists = 0;
  char         *slash;

  PetscFunctionBeginUser;
  if (!stat(c->restart, &st)) {
    exists = 1;
    isdir  = S_ISDIR(st.st_mode);
  }
  if (isdir) PetscCall(PetscSNPrintf(c->file, sizeof(c->file), "%s/%s", c->restart, MM_CKPT_FILE));
  else PetscCall(PetscStrncpy(c->file, c->restart, sizeof(c->file)));
  PetscCall(MMOutputCheckHDF5Path(comm, "-restart", c->file, ""));
  if (isdir) exists = !stat(c->file, &st);
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "-restart %s: %s does not exist. Give the checkpoint file, or the output directory of the run to continue (its checkpoint.h5 is written every -checkpoint_every steps and at the end)", c->restart, c->file);
  PetscCall(PetscStrncpy(c->source_dir, c->file, sizeof(c->source_dir)));
  slash = strrchr(c->source_dir, '/');
  if (slash) *slash = 0;
  else PetscCall(PetscStrncpy(c->source_dir, ".", sizeof(c->source_dir)));
  PetscFunctionReturn(0);
}

/* A dataset of the checkpoint into v (named). A file cut short or not HDF5 stops with its name. */
static PetscErrorCode LoadVector(MMCheckpoint *ck, PetscViewer viewer, const char name[], Vec v)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = VecLoad(v, viewer);
  PetscCall(PetscPopErrorHandler());
  PetscCheck(!ierr, PetscObjectComm((PetscObject)ck->dm), PETSC_ERR_FILE_READ, "Could not read \"%s\" from the checkpoint %s: the file is incomplete or not a checkpoint of mmcontact. The checkpoint is written to checkpoint.h5.tmp and renamed only when whole, so an earlier checkpoint.h5 of the run is intact", name, ck->file);
  PetscFunctionReturn(0);
}

/* The run's scalars, on every rank. */
static PetscErrorCode LoadRunRecord(MMCheckpoint *ck, PetscViewer viewer, PetscReal run[])
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)ck->dm);
  Vec                rv, all;
  VecScatter         sc;
  PetscInt           n;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &rv));
  PetscCall(LoadVector(ck, viewer, "run", rv));
  PetscCall(VecGetSize(rv, &n));
  PetscCall(VecScatterCreateToAll(rv, &sc, &all));
  PetscCall(VecScatterBegin(sc, rv, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, rv, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &a));
  PetscCheck(n >= 1 && PetscRealPart(a[MM_RUN_VERSION]) == MM_CKPT_VERSION && n == MM_RUN_NUM, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint %s is of format %d with %" PetscInt_FMT " run entries; this mmcontact reads format %d with %d. Continue it with the mmcontact that wrote it", ck->file, n ? (int)PetscRealPart(a[0]) : 0, n, MM_CKPT_VERSION, (int)MM_RUN_NUM);
  for (PetscInt i = 0; i < MM_RUN_NUM; ++i) run[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&rv));
  PetscFunctionReturn(0);
}

/* The checkpoint must be of this problem: the same mesh (vertices, cells, coordinates), then the same
 * physics (CheckPhysics: law, material, mass, damping, Dirichlet and contact data, per option), and
 * from the run record the contact boundary, friction coefficient, material and mass. Each difference is named. */
static PetscErrorCode CheckFingerprint(MMCheckpoint *ck, TS ts, PetscViewer viewer, const PetscReal rec[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)ck->dm);
  const char *f    = ck->file;
  PetscReal   me[MM_RUN_NUM], tol = 0;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  PetscCall(RunRecord(ck, ts, me));
  PetscCheck(rec[MM_RUN_DIM] == me[MM_RUN_DIM], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s is of a %dD problem, this mesh %s is %dD: another dimension. Restart with the mesh and options of the run that wrote it", f, (int)rec[MM_RUN_DIM], ck->opt->mesh_file, (int)me[MM_RUN_DIM]);
  PetscCheck(rec[MM_RUN_VERTICES] == me[MM_RUN_VERTICES] && rec[MM_RUN_CELLS] == me[MM_RUN_CELLS], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s is of another mesh: %d vertices and %d cells, this mesh %s has %d and %d. Restart with the mesh of the run that wrote it", f, (int)rec[MM_RUN_VERTICES], (int)rec[MM_RUN_CELLS], ck->opt->mesh_file, (int)me[MM_RUN_VERTICES], (int)me[MM_RUN_CELLS]);
  PetscCall(CoordinateChecksumTolerance(ck, &tol));
  PetscCheck(PetscAbsReal(rec[MM_RUN_COORDINATES] - me[MM_RUN_COORDINATES]) <= tol, comm, PETSC_ERR_USER_INPUT, "The checkpoint %s is of another mesh: it has as many vertices and cells as %s, but other coordinates (checksums %.15g and %.15g). Restart with the mesh, and -mesh_rotation, of the run that wrote it", f, ck->opt->mesh_file, (double)rec[MM_RUN_COORDINATES], (double)me[MM_RUN_COORDINATES]);
  /* the physics, each option named; what follows checks a checkpoint that does not record it */
  PetscCall(CheckPhysics(ck, viewer));
  PetscCheck(rec[MM_RUN_CONTACT_NODES] == me[MM_RUN_CONTACT_NODES], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s is of another contact boundary: %d contact nodes, this run has %d (-contact_boundary %s, -contact %s). Restart with the contact options of the run that wrote it", f, (int)rec[MM_RUN_CONTACT_NODES], (int)me[MM_RUN_CONTACT_NODES], ck->opt->contact_name, cn.enabled ? "1" : "0");
  PetscCheck(rec[MM_RUN_MU] == me[MM_RUN_MU], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with -mu %.10g, this run has -mu %.10g: a different friction law. Restart with -mu %.10g", f, (double)rec[MM_RUN_MU], (double)me[MM_RUN_MU], (double)rec[MM_RUN_MU]);
  PetscCheck(rec[MM_RUN_E] == me[MM_RUN_E] && rec[MM_RUN_NU] == me[MM_RUN_NU] && rec[MM_RUN_RHO] == me[MM_RUN_RHO], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with -E %.10g -nu %.10g -rho %.10g, this run has -E %.10g -nu %.10g -rho %.10g: another material. Restart with the material of the run that wrote it", f, (double)rec[MM_RUN_E], (double)rec[MM_RUN_NU], (double)rec[MM_RUN_RHO], (double)me[MM_RUN_E], (double)me[MM_RUN_NU], (double)me[MM_RUN_RHO]);
  {
    PetscBool same = (PetscBool)(rec[MM_RUN_BODIES] == me[MM_RUN_BODIES]);
    for (PetscInt k = 0; k < 3; ++k) same = (PetscBool)(same && PetscAbsReal(rec[MM_RUN_MATERIAL + k] - me[MM_RUN_MATERIAL + k]) <= 1e-10 * PetscAbsReal(me[MM_RUN_MATERIAL + k]));
    PetscCheck(same, comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with another material in the cells: %d bod%s, and the checksums of lambda, mu, rho over the cells %.10g, %.10g, %.10g; this run has %d bod%s and %.10g, %.10g, %.10g: another material. Restart with the -bodies, -body_NAME_group, -body_NAME_E, -body_NAME_nu and -body_NAME_rho of the run that wrote it", f, (int)rec[MM_RUN_BODIES], (int)rec[MM_RUN_BODIES] == 1 ? "y" : "ies", (double)rec[MM_RUN_MATERIAL], (double)rec[MM_RUN_MATERIAL + 1], (double)rec[MM_RUN_MATERIAL + 2], (int)me[MM_RUN_BODIES], (int)me[MM_RUN_BODIES] == 1 ? "y" : "ies", (double)me[MM_RUN_MATERIAL], (double)me[MM_RUN_MATERIAL + 1], (double)me[MM_RUN_MATERIAL + 2]);
  }
  PetscCheck(rec[MM_RUN_MASS] == me[MM_RUN_MASS], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with the %s%s mass, this run has the %s%s mass. Restart with the -mass and -mass_lumped of the run that wrote it", f, MMMassTypes[(int)rec[MM_RUN_MASS] % 3], (int)rec[MM_RUN_MASS] / 3 ? " lumped" : "", MMMassTypes[(int)me[MM_RUN_MASS] % 3], (int)me[MM_RUN_MASS] / 3 ? " lumped" : "");
  PetscCheck(rec[MM_RUN_DAMPING_ALPHA] == me[MM_RUN_DAMPING_ALPHA] && rec[MM_RUN_DAMPING_BETA] == me[MM_RUN_DAMPING_BETA], comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with the Rayleigh damping alpha = %.10g, beta = %.10g, this run has alpha = %.10g, beta = %.10g: another damping. Restart with the -damping_mass and -damping_stiffness (or -damping_ratio and -damping_frequencies) of the run that wrote it", f, (double)rec[MM_RUN_DAMPING_ALPHA], (double)rec[MM_RUN_DAMPING_BETA], (double)me[MM_RUN_DAMPING_ALPHA], (double)me[MM_RUN_DAMPING_BETA]);
  PetscFunctionReturn(0);
}

/* From the packed dataset NAME (bs entries per serial-mesh vertex), the blocks of the n vertices
 * serial[] into vals (n bs entries): one scatter, whatever the partition that wrote the file. */
static PetscErrorCode LoadPacked(MMCheckpoint *ck, PetscViewer viewer, const char name[], PetscInt bs, PetscInt n, const PetscInt serial[], PetscScalar vals[])
{
  MPI_Comm   comm = PetscObjectComm((PetscObject)ck->dm);
  Vec        packed, local;
  IS         from;
  VecScatter sc;
  PetscInt  *idx, N;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &packed));
  PetscCall(LoadVector(ck, viewer, name, packed));
  PetscCall(VecGetSize(packed, &N));
  PetscCheck(N == bs * ck->nv_global, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint %s has %" PetscInt_FMT " entries in \"%s\", expected %" PetscInt_FMT ": the file is damaged", ck->file, N, name, bs * ck->nv_global);
  PetscCall(PetscMalloc1(n * bs, &idx));
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt c = 0; c < bs; ++c) idx[i * bs + c] = serial[i] * bs + c;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n * bs, idx, PETSC_OWN_POINTER, &from));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n * bs, vals, &local));
  PetscCall(VecScatterCreate(packed, from, local, NULL, &sc));
  PetscCall(VecScatterBegin(sc, packed, local, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, packed, local, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&local));
  PetscCall(ISDestroy(&from));
  PetscCall(VecDestroy(&packed));
  PetscFunctionReturn(0);
}

/* The inverse of PackDofs: the free dofs of the owned vertices from their serial-mesh blocks. */
static PetscErrorCode LoadDofs(MMCheckpoint *ck, PetscViewer viewer, const char name[], Vec w)
{
  const PetscInt dim = ck->dim;
  PetscInt       n, *serial, *loc;
  PetscScalar   *vals, *wa;

  PetscFunctionBeginUser;
  PetscCall(OwnedDofMap(ck, &n, &serial, &loc));
  PetscCall(PetscMalloc1(dim * n, &vals));
  PetscCall(LoadPacked(ck, viewer, name, dim, n, serial, vals));
  PetscCall(VecGetArray(w, &wa));
  for (PetscInt i = 0; i < n * dim; ++i)
    if (loc[i] >= 0) wa[loc[i]] = vals[i];
  PetscCall(VecRestoreArray(w, &wa));
  PetscCall(PetscFree(vals));
  PetscCall(PetscFree2(serial, loc));
  PetscFunctionReturn(0);
}

/* The per-contact-node records, kept until the history is restored (was_active is recomputed by
 * the initial diagnostics in between); each of this run's contact nodes must be one in the file. */
static PetscErrorCode LoadContactRecords(MMCheckpoint *ck, PetscViewer viewer)
{
  MMContactNodes nodes, *ct = &nodes;
  PetscInt       vStart, vEnd, *serial, bad = 0;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ck->contact, &nodes));
  if (!ct->enabled) PetscFunctionReturn(0);
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(ct->n_local, &serial));
  PetscCall(PetscMalloc1(MM_CKPT_NODE * ct->n_local, &ck->node));
  for (PetscInt k = 0; k < ct->n_local; ++k) serial[k] = ck->vertex_orig[ct->vertex[k] - vStart];
  PetscCall(LoadPacked(ck, viewer, "contact", MM_CKPT_NODE, ct->n_local, serial, ck->node));
  for (PetscInt k = 0; k < ct->n_local; ++k) bad += PetscRealPart(ck->node[MM_CKPT_NODE * k]) != 1;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ck->dm)));
  PetscCheck(!bad, PetscObjectComm((PetscObject)ck->dm), PETSC_ERR_USER_INPUT, "The checkpoint %s is of another contact boundary: %" PetscInt_FMT " of this run's %" PetscInt_FMT " contact nodes are not contact nodes there (-contact_boundary %s). Restart with the contact boundary of the run that wrote it", ck->file, bad, ct->n_global, ck->opt->contact_name);
  PetscCall(PetscFree(serial));
  PetscFunctionReturn(0);
}

/* Frames that follow the contact point: each contact node's record (PackFrames) and the run's
 * W_frame and counters, when the checkpoint has them; a checkpoint with them (the state in turned
 * frames) is refused by a run whose frames stay fixed. A checkpoint of fixed frames continued with
 * frames that follow starts from the set-up frames, a state of the fixed-frame run. */
static PetscErrorCode LoadFrameRecords(MMCheckpoint *ck, PetscViewer viewer)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)ck->dm);
  PetscBool      has, follow;
  PetscInt       vStart, vEnd, *serial;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(viewer, "frames", &has));
  PetscCall(MMContactFramesFollow(ck->contact, &follow));
  PetscCheck(!has || follow, comm, PETSC_ERR_USER_INPUT, "The checkpoint %s was written with contact frames that follow the contact point (-contact_frames follow, the default with -elasticity svk and neohookean on curved obstacles), and its state is in those frames; this run keeps them fixed. Restart with the -contact_frames and -elasticity of the run that wrote it", ck->file);
  if (!has) PetscFunctionReturn(0);
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(cn.n_local, &serial));
  PetscCall(PetscMalloc1(MM_CONTACT_FRAME_RECORD * cn.n_local + 1, &ck->frames));
  for (PetscInt k = 0; k < cn.n_local; ++k) serial[k] = ck->vertex_orig[cn.vertex[k] - vStart];
  PetscCall(LoadPacked(ck, viewer, "frames", MM_CONTACT_FRAME_RECORD, cn.n_local, serial, ck->frames));
  PetscCall(PetscFree(serial));
  {
    Vec                fv, all;
    VecScatter         sc;
    PetscInt           n;
    const PetscScalar *a;
    PetscCall(VecCreate(comm, &fv));
    PetscCall(LoadVector(ck, viewer, "frames_run", fv));
    PetscCall(VecGetSize(fv, &n));
    PetscCheck(n == MM_CKPT_FRAMES_RUN, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint %s has %" PetscInt_FMT " entries in \"frames_run\", expected %d: the file is damaged", ck->file, n, MM_CKPT_FRAMES_RUN);
    PetscCall(VecScatterCreateToAll(fv, &sc, &all));
    PetscCall(VecScatterBegin(sc, fv, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, fv, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(all, &a));
    for (PetscInt i = 0; i < MM_CKPT_FRAMES_RUN; ++i) ck->frames_run[i] = PetscRealPart(a[i]);
    PetscCall(VecRestoreArrayRead(all, &a));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&all));
    PetscCall(VecDestroy(&fv));
  }
  PetscFunctionReturn(0);
}

/* A vector of n reals held on rank 0 in the file, on every rank */
static PetscErrorCode LoadSmallVector(MMCheckpoint *ck, PetscViewer viewer, const char name[], PetscInt n, PetscReal vals[])
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)ck->dm);
  Vec                v, all;
  VecScatter         sc;
  PetscInt           N;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &v));
  PetscCall(LoadVector(ck, viewer, name, v));
  PetscCall(VecGetSize(v, &N));
  PetscCheck(N == n, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint %s has %" PetscInt_FMT " entries in \"%s\", expected %" PetscInt_FMT ": the file is damaged", ck->file, N, name, n);
  PetscCall(VecScatterCreateToAll(v, &sc, &all));
  PetscCall(VecScatterBegin(sc, v, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, v, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt i = 0; i < n; ++i) vals[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* The finite-strain iteration matrix's point, when the checkpoint has one (MMNewmarkRestoreTangent
 * builds the matrix once the pairing and frames are restored) */
static PetscErrorCode LoadTangentPoint(MMCheckpoint *ck, PetscViewer viewer)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(viewer, "tangent_point", &has));
  if (!has || !ck->material->finite) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ck->state->u, &ck->tangent));
  PetscCall(LoadDofs(ck, viewer, "tangent_point", ck->tangent));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "tangent_point", "time", PETSC_REAL, NULL, &ck->tangent_time));
  PetscFunctionReturn(0);
}

/* The mass in free flight: M* as the checkpointed run had it (a checkpoint without it, or of a run
 * without the switches, leaves M* as set up: the next step's start decides), its counts and W_frame */
static PetscErrorCode LoadMassFree(MMCheckpoint *ck, PetscViewer viewer)
{
  PetscBool on, has;
  PetscReal vals[MM_CKPT_MASS_FREE];
  PetscInt  sw[2];

  PetscFunctionBeginUser;
  PetscCall(MMContactMassFreeFlight(ck->contact, &on, NULL));
  PetscCall(PetscViewerHDF5HasDataset(viewer, "mass_free", &has));
  if (!on || !has) PetscFunctionReturn(0);
  PetscCall(LoadSmallVector(ck, viewer, "mass_free", MM_CKPT_MASS_FREE, vals));
  sw[0] = (PetscInt)vals[1];
  sw[1] = (PetscInt)vals[2];
  PetscCall(MMContactMassFreeRestore(ck->contact, (PetscBool)(vals[0] > 0.5), sw));
  ck->mass_free_work = vals[3];
  ck->mass_free_read = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The finite-strain tangent clamped since a rejection, when the checkpointed run was (nonlinear.c) */
static PetscErrorCode LoadTangentClamp(MMCheckpoint *ck, TS ts, PetscViewer viewer)
{
  MMNewmark nm;
  PetscBool has;
  PetscReal step;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(viewer, "tangent_clamp_step", &has));
  if (!has || !ck->material->finite) PetscFunctionReturn(0);
  PetscCall(LoadSmallVector(ck, viewer, "tangent_clamp_step", 1, &step));
  PetscCall(MMNewmarkFromTS(ts, &nm));
  PetscCall(MMNewmarkSetTangentClampStep(nm, (PetscInt)step));
  PetscFunctionReturn(0);
}

/* The step certificate's state, when the checkpoint has it and this run certifies its steps */
static PetscErrorCode LoadCertificate(MMCheckpoint *ck, TS ts, PetscViewer viewer)
{
  MMNewmark nm;
  Vec       r;
  PetscBool has;
  PetscReal tol;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkFromTS(ts, &nm));
  PetscCall(MMNewmarkGetCertificateResidual(nm, &r));
  PetscCall(PetscViewerHDF5HasDataset(viewer, "certificate_residual", &has));
  if (!has || !r) PetscFunctionReturn(0);
  PetscCall(LoadDofs(ck, viewer, "certificate_residual", r));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "certificate_residual", "contact_tol", PETSC_REAL, NULL, &tol));
  PetscCall(MMContactSetSolveTolerance(ck->contact, tol));
  PetscFunctionReturn(0);
}

/* Large sliding: each owned sliding node's pairing record, the run's counters, and the carried forces
 * straight into the stepper's vectors (they are in the checkpoint's pairing's variables, as the state) */
static PetscErrorCode LoadPairs(MMCheckpoint *ck, TS ts, PetscViewer viewer)
{
  PetscBool      has;
  PetscInt       vStart, vEnd, *serial, n;
  MMContactNodes cn;
  MMNewmark      nm;
  Vec           *f;

  PetscFunctionBeginUser;
  if (!PairsSlide(ck)) PetscFunctionReturn(0);
  PetscCall(PetscViewerHDF5HasDataset(viewer, "pairs", &has));
  if (!has) PetscFunctionReturn(0); /* refused by MMNewmarkRestorePairs */
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  PetscCall(DMPlexGetDepthStratum(ck->dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(cn.n_local, &serial));
  PetscCall(PetscMalloc1(MM_CONTACT_PAIR_RECORD * cn.n_local + 1, &ck->pairs));
  for (PetscInt k = 0; k < cn.n_local; ++k) serial[k] = ck->vertex_orig[cn.vertex[k] - vStart];
  PetscCall(LoadPacked(ck, viewer, "pairs", MM_CONTACT_PAIR_RECORD, cn.n_local, serial, ck->pairs));
  PetscCall(PetscFree(serial));
  PetscCall(LoadSmallVector(ck, viewer, "pairs_run", 3, ck->pairs_run));
  PetscCall(MMNewmarkFromTS(ts, &nm));
  PetscCall(PetscMalloc1(MMNewmarkCountCarriedForces(nm), &f));
  PetscCall(MMNewmarkGetCarriedForces(nm, &n, f));
  for (PetscInt i = 0; i < n; ++i) {
    char name[32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "pairs_force_%" PetscInt_FMT, i));
    PetscCall(LoadDofs(ck, viewer, name, f[i]));
  }
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointGetPairs - Gives the contact pairing's records of the checkpoint a restart read

  Not collective

  Input Parameter:
. c - the checkpoint object, loaded

  Output Parameters:
+ rec      - per owned contact row its record, or NULL without large sliding (owned by the checkpoint)
- counters - the pairing's counters

  Level: developer

.seealso: `MMNewmarkRestorePairs()`, `MMCheckpointGetFrames()`
@*/
PetscErrorCode MMCheckpointGetPairs(const MMCheckpoint *c, const PetscScalar **rec, const PetscReal **counters)
{
  PetscFunctionBeginUser;
  *rec      = c->restarted ? c->pairs : NULL;
  *counters = c->pairs_run;
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointGetTangent - Gives the point at which the checkpointed run's finite-strain iteration
  matrix was the tangent

  Not collective

  Input Parameter:
. c - the checkpoint object, loaded

  Output Parameters:
+ at - the Cartesian displacement, or NULL when the iteration matrix was K (owned by the checkpoint)
- t  - the time of its Dirichlet data

  Level: developer

.seealso: `MMNewmarkRestoreTangent()`, `MMNewmarkGetTangentPoint()`
@*/
PetscErrorCode MMCheckpointGetTangent(const MMCheckpoint *c, Vec *at, PetscReal *t)
{
  PetscFunctionBeginUser;
  *at = c->restarted ? c->tangent : NULL;
  *t  = c->tangent_time;
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointGetFrames - Gives the contact frames' records of the checkpoint a restart read

  Not collective

  Input Parameter:
. c - the checkpoint object, loaded

  Output Parameters:
+ rec      - per owned contact node its record, or NULL without them (owned by the checkpoint)
- counters - the run's W_frame and the frames' counters

  Level: developer

.seealso: `MMNewmarkRestoreFrames()`, `MMCheckpointGetPairs()`
@*/
PetscErrorCode MMCheckpointGetFrames(const MMCheckpoint *c, const PetscScalar **rec, const PetscReal **counters)
{
  PetscFunctionBeginUser;
  *rec      = c->restarted ? c->frames : NULL;
  *counters = c->frames_run + 1;
  PetscFunctionReturn(0);
}

/* The friction thresholds, and the contact object's per-row state (the last active set, 3D slip
 * states and directions, condensed reactions and the active-set warm start): what the next step's
 * solvers start from. */
static PetscErrorCode RestoreContactState(MMCheckpoint *ck)
{
  PetscScalar   *sa = NULL;
  Vec            thresholds;
  MMContactNodes cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ck->contact, &cn));
  if (!cn.enabled) PetscFunctionReturn(0);
  PetscCall(MMFrictionGetThresholds(ck->friction, &thresholds));
  if (thresholds) PetscCall(VecGetArray(thresholds, &sa));
  for (PetscInt k = 0; k < cn.n_local; ++k) {
    const PetscScalar *rec = &ck->node[MM_CKPT_NODE * k];
    PetscBool          second;
    PetscCall(MMContactSetNodeState(ck->contact, k, rec, &second));
    if (sa && !second) sa[k] = rec[1];
  }
  if (sa) PetscCall(VecRestoreArray(thresholds, &sa));
  PetscFunctionReturn(0);
}

/* The times of the snapshots up to the checkpoint, on every rank. */
static PetscErrorCode LoadSnapshotTimes(MMCheckpoint *c, PetscViewer viewer)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)c->dm);
  const PetscInt     n    = (PetscInt)c->run[MM_RUN_SNAPSHOTS];
  Vec                tv, all;
  VecScatter         sc;
  PetscInt           N;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(PetscMax(n, 1), &c->snapshot_times));
  if (!n) PetscFunctionReturn(0);
  PetscCall(VecCreate(comm, &tv));
  PetscCall(LoadVector(c, viewer, "snapshot_times", tv));
  PetscCall(VecGetSize(tv, &N));
  PetscCheck(N == n, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint %s lists %" PetscInt_FMT " snapshot times for %" PetscInt_FMT " snapshots: the file is damaged", c->file, N, n);
  PetscCall(VecScatterCreateToAll(tv, &sc, &all));
  PetscCall(VecScatterBegin(sc, tv, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, tv, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt i = 0; i < n; ++i) c->snapshot_times[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&tv));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointLoad - Restores the run from the checkpoint of -restart: the state, the stepper's
  time, step and dt, and the solvers' warm starts

  Collective

  Input Parameters:
+ c  - the checkpoint object, set up
- ts - the time stepper, created

  Note:
  -restart: the state, the stepper's time, step and dt, and the solvers' warm starts from the
  checkpoint, after the fingerprint is checked. Called once the TS exists, before the step matrix is
  factored (for the restored dt) and the initial energy is taken (of the restored state).

  Level: intermediate

.seealso: `MMCheckpointGetRestart()`, `MMCheckpointRestoreHistory()`, `MMCheckpointWrite()`
@*/
PetscErrorCode MMCheckpointLoad(MMCheckpoint *c, TS ts)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)c->dm);
  MMState       *s    = c->state;
  PetscViewer    viewer;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  if (!c->restart[0]) PetscFunctionReturn(0); /* no -restart */
  PetscCall(PetscLogEventBegin(MMIOEvents.checkpoint, 0, 0, 0, 0));
  PetscCall(ResolveRestartPath(c));
  if (!c->nv_global) PetscCall(CountVertices(c));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = PetscViewerHDF5Open(comm, c->file, FILE_MODE_READ, &viewer);
  PetscCall(PetscPopErrorHandler());
  PetscCheck(!ierr, comm, PETSC_ERR_FILE_OPEN, "Could not open the checkpoint %s: it is not a complete HDF5 file. A checkpoint is written to checkpoint.h5.tmp and renamed only when whole: give the directory's checkpoint.h5, or the directory itself", c->file);
  PetscCall(LoadRunRecord(c, viewer, c->run));
  PetscCall(CheckFingerprint(c, ts, viewer, c->run));
  PetscCall(LoadContactRecords(c, viewer));
  PetscCall(LoadFrameRecords(c, viewer));
  PetscCall(LoadDofs(c, viewer, "u", s->u));
  PetscCall(LoadDofs(c, viewer, "v", s->v));
  PetscCall(LoadDofs(c, viewer, "a", s->a));
  if (DampingOn(c)) PetscCall(LoadDofs(c, viewer, "vC", c->damping->vC));
  PetscCall(LoadDofs(c, viewer, "react", s->react));
  PetscCall(LoadTangentPoint(c, viewer));
  PetscCall(LoadPairs(c, ts, viewer));
  PetscCall(LoadCertificate(c, ts, viewer));
  PetscCall(LoadTangentClamp(c, ts, viewer));
  PetscCall(LoadMassFree(c, viewer));
  PetscCall(LoadSnapshotTimes(c, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(VecCopy(s->u, s->u_next));
  s->dt           = c->run[MM_RUN_DT_LAST];
  c->restart_step = (PetscInt)c->run[MM_RUN_STEP];
  c->restarted    = PETSC_TRUE;
  PetscCall(TSSetTime(ts, c->run[MM_RUN_TIME]));
  PetscCall(TSSetStepNumber(ts, c->restart_step));
  /* the same -ts_dt continues the run's own dt sequence; another one is the user's new dt */
  if (c->run[MM_RUN_DT_USER] == s->dt_user) {
    PetscCall(TSSetTimeStep(ts, c->run[MM_RUN_DT_NEXT]));
    PetscCall(MMAdaptGrowBackSetState(ts, &c->run[MM_RUN_ADAPT]));
  }
  PetscCall(TSGetTimeStep(ts, &c->dt_next));
  PetscCall(PetscLogEventEnd(MMIOEvents.checkpoint, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointGetRestart - Tells whether the run continues a checkpoint, and from which step and
  time

  Not collective

  Input Parameter:
. c - the checkpoint object

  Output Parameters:
+ restarted - PETSC_TRUE after MMCheckpointLoad() read a checkpoint (or NULL)
. step      - its step (or NULL)
- time      - its time (or NULL)

  Level: intermediate

.seealso: `MMCheckpointLoad()`
@*/
PetscErrorCode MMCheckpointGetRestart(const MMCheckpoint *c, PetscBool *restarted, PetscInt *step, PetscReal *time)
{
  PetscFunctionBeginUser;
  if (restarted) *restarted = c->restarted;
  if (step) *step = c->restarted ? c->restart_step : 0;
  if (time) *time = c->restarted ? c->run[MM_RUN_TIME] : 0;
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointWriteFinal - Writes the last step's checkpoint at the end of the run, unless the
  cadence wrote it

  Collective

  Input Parameters:
+ c  - the checkpoint object
- ts - the time stepper

  Level: intermediate

.seealso: `MMCheckpointWrite()`, `MMCheckpointMonitor()`
@*/
PetscErrorCode MMCheckpointWriteFinal(MMCheckpoint *c, TS ts)
{
  PetscFunctionBeginUser;
  if (c->last_step != c->hist->step || !c->written) PetscCall(MMCheckpointWrite(c, ts));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointView - Prints, after -restart, what was read and how the run continues

  Collective

  Input Parameters:
+ c      - the checkpoint object
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `MMCheckpointLoad()`
@*/
PetscErrorCode MMCheckpointView(const MMCheckpoint *c, PetscViewer viewer)
{
  const MMState *s = c->state;

  PetscFunctionBeginUser;
  if (!c->restarted) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "Restart from %s: step %" PetscInt_FMT ", t = %.10g, next dt %g (written on %d rank%s, continued on %d)\n", c->file, c->restart_step, (double)c->run[MM_RUN_TIME], (double)c->dt_next, (int)c->run[MM_RUN_RANKS], c->run[MM_RUN_RANKS] > 1 ? "s" : "", PetscGlobalSize));
  if (c->run[MM_RUN_DT_USER] != s->dt_user) PetscCall(PetscViewerASCIIPrintf(viewer, "  -ts_dt %g here, %g in the checkpoint's run: the steps from here on are of the new dt\n", (double)s->dt_user, (double)c->run[MM_RUN_DT_USER]));
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointRestoreHistory - Restores the history's running sums and maxima, the last active set
  and the contact solvers' warm starts as at the checkpoint

  Collective

  Input Parameter:
. c - the checkpoint object, loaded

  Note:
  After the step matrix and the initial energy of the restored state: the history's running sums and
  maxima, the last active set (for the switched count) and the contact solvers' warm starts, as at
  the checkpoint.

  Level: developer

.seealso: `MMCheckpointLoad()`, `MMEnergyInitial()`
@*/
PetscErrorCode MMCheckpointRestoreHistory(MMCheckpoint *c)
{
  MMHistory      *h   = c->hist;
  MMContactNodes  cn;
  const PetscReal *run = c->run;

  PetscFunctionBeginUser;
  if (!c->restarted) PetscFunctionReturn(0);
  PetscCall(MMContactGetNodes(c->contact, &cn));
  h->step                = c->restart_step;
  h->time                = run[MM_RUN_TIME];
  h->dt                  = run[MM_RUN_DT_LAST];
  h->cfl                 = cn.enabled ? c->material->c_p_max * h->dt / cn.h_c : 0;
  h->work_ext            = run[MM_RUN_WORK_EXT];
  h->work_contact        = run[MM_RUN_WORK_CONTACT];
  h->work_friction       = run[MM_RUN_WORK_FRICTION];
  h->work_obstacle       = run[MM_RUN_WORK_OBSTACLE];
  h->work_damping        = run[MM_RUN_WORK_DAMPING];
  h->work_dirichlet      = run[MM_RUN_WORK_DIRICHLET];
  h->max_balance         = run[MM_RUN_MAX_BALANCE];
  h->max_penetration_run = run[MM_RUN_MAX_PENETRATION];
  h->energy_scale        = run[MM_RUN_ENERGY_SCALE];
  h->resolves            = (PetscInt)run[MM_RUN_RESOLVES];
  if (c->frames) h->work_frame = c->frames_run[0]; /* frames that follow: W_frame so far */
  if (c->mass_free_read) h->work_frame = c->mass_free_work; /* the mass in free flight books there too */
  PetscCall(MMContactSetCandidateResolves(c->contact, h->resolves));
  /* here, not at the load: the condensed reactions and the active-set states are created with the
   * step matrix, and the initial diagnostics would overwrite the states (the last active set among them) */
  PetscCall(RestoreContactState(c));
  c->last_step = c->restart_step;
  c->written   = 1; /* the checkpoint of this step exists */
  PetscFunctionReturn(0);
}

/*@
  MMCheckpointSnapshotCount - Returns the number of snapshots of the checkpoint a restart continues
  (0 without one)

  Not collective

  Input Parameter:
. c - the checkpoint object

  Note:
  The snapshots of the checkpoint a restart continues (0 without one): the output plan numbers this
  run's from there (output_plan.c).

  Level: developer

.seealso: `MMCheckpointSnapshots()`, `MMOutputPlanMake()`
@*/
PetscInt MMCheckpointSnapshotCount(const MMCheckpoint *c)
{
  return c->restarted ? (PetscInt)c->run[MM_RUN_SNAPSHOTS] : 0;
}

/*@
  MMCheckpointSnapshots - Gives the snapshot count and times of the checkpoint, read with the state

  Not collective

  Input Parameter:
. c - the checkpoint object, loaded

  Output Parameters:
+ n     - the number of snapshots
- times - their times; the caller takes the array and frees it with PetscFree()

  Level: developer

.seealso: `MMCheckpointSnapshotCount()`, `MMOutputOpen()`
@*/
PetscErrorCode MMCheckpointSnapshots(MMCheckpoint *c, PetscInt *n, PetscReal **times)
{
  PetscFunctionBeginUser;
  *n                = (PetscInt)c->run[MM_RUN_SNAPSHOTS];
  *times            = c->snapshot_times;
  c->snapshot_times = NULL;
  PetscFunctionReturn(0);
}
