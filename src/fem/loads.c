/* Loads in time, moving Dirichlet boundaries and the support reactions (docs/method.md section 10).
 *
 * The load is a sum of parts, each a fixed vector times an amplitude in time, L(t) = sum_k a_k(t) L_k:
 * gravity is part 0, then the tractions, the pressures and the point forces, in the order of
 * -traction, -pressure and -point_force (PartName). The parts are assembled once; a step only sums
 * them.
 * A Dirichlet boundary moves as u_D(t) = value + velocity t. Its reaction, the force the support
 * exerts on the body, is R_D = (M* a + K u - L)_D on the constrained dofs: it needs the rows of K and
 * M on those dofs, which the global operators (free dofs only) do not hold, so they are assembled
 * once on a copy of the mesh without constraints. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "femimpl.h"
#include "mesh.h"
#include "assembly_p1.h"

/* ---------------------------------------------------------------- amplitudes */

static PetscReal AmplitudeConstant(const MMAmplitude *a, PetscReal t)
{
  return 1.0;
}

/* 0 at t = 0, 1 at t = T, then 1 */
static PetscReal AmplitudeRamp(const MMAmplitude *a, PetscReal t)
{
  return t <= 0 ? 0.0 : (t >= a->T ? 1.0 : t / a->T);
}

/* sin(pi t / T) on [0, T], 0 outside: one pulse */
static PetscReal AmplitudeHalfSine(const MMAmplitude *a, PetscReal t)
{
  return t <= 0 || t >= a->T ? 0.0 : PetscSinReal(PETSC_PI * t / a->T);
}

/* Linear between the rows, constant beyond the first and last (Abaqus *AMPLITUDE, code_aster
 * DEFI_FONCTION with constant prolongation). */
static PetscReal AmplitudeTable(const MMAmplitude *a, PetscReal t)
{
  PetscInt lo = 0, hi = a->n - 1;

  if (t <= a->t[0]) return a->f[0];
  if (t >= a->t[hi]) return a->f[hi];
  while (hi - lo > 1) {
    const PetscInt mid = (lo + hi) / 2;
    if (a->t[mid] <= t) lo = mid;
    else hi = mid;
  }
  return a->f[lo] + (a->f[hi] - a->f[lo]) * (t - a->t[lo]) / (a->t[hi] - a->t[lo]);
}

/* The table's rows, read on rank 0: "time,factor" per line; blank lines and lines starting with #
 * are skipped, and a first line that does not start with a number is taken for a header. A first
 * line that starts with a number is data, refused if it is not two numbers ("0;1", "0,1,2"):
 * skipped, the load would start at the second row's factor. A UTF-8 byte order mark (some
 * Windows editors write one) is refused as the options and mesh readers do: before a first row
 * of numbers it made that row look like a header. Returns a message in msg (empty: fine). */
static void ReadTableRows(const char file[], PetscInt *n, PetscReal **t, PetscReal **f, char msg[], size_t len)
{
  FILE    *fp = fopen(file, "r");
  char     line[1024];
  PetscInt cap = 0, lineno = 0;
  PetscBool first = PETSC_TRUE, numeric;

  *n   = 0;
  *t   = *f = NULL;
  msg[0] = 0;
  if (!fp) {
    snprintf(msg, len, "cannot be read: %s", strerror(errno));
    return;
  }
  while (fgets(line, sizeof(line), fp)) {
    char  *p = line, *end;
    double x, y;

    ++lineno;
    if (lineno == 1 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB && (unsigned char)p[2] == 0xBF) {
      snprintf(msg, len, "starts with a UTF-8 byte order mark (bytes EF BB BF): save it as UTF-8 without a byte order mark (or plain ASCII)");
      break;
    }
    while (*p == ' ' || *p == '\t') ++p;
    if (!*p || *p == '\n' || *p == '\r' || *p == '#') continue;
    x = strtod(p, &end);
    numeric = (PetscBool)(end != p);
    if (numeric) {
      p = end;
      while (*p == ' ' || *p == '\t') ++p;
      if (*p == ',') {
        ++p;
        y = strtod(p, &end);
        if (end != p) {
          p = end;
          while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
          if (!*p) {
            if (*n == cap) {
              cap = PetscMax(16, 2 * cap);
              *t  = (PetscReal *)realloc(*t, cap * sizeof(PetscReal));
              *f  = (PetscReal *)realloc(*f, cap * sizeof(PetscReal));
            }
            (*t)[*n] = x;
            (*f)[*n] = y;
            if (PetscIsInfOrNanReal((*t)[*n]) || PetscIsInfOrNanReal((*f)[*n])) {
              snprintf(msg, len, "line %d holds a value that is not finite", (int)lineno);
              break;
            }
            if (*n && (*t)[*n] <= (*t)[*n - 1]) {
              snprintf(msg, len, "line %d: time %g is not after the previous row's %g; the times must increase strictly", (int)lineno, x, (double)(*t)[*n - 1]);
              break;
            }
            ++*n;
            first = PETSC_FALSE;
            continue;
          }
        }
      }
    }
    if (first && !numeric) { /* a header */
      first = PETSC_FALSE;
      continue;
    }
    line[strcspn(line, "\r\n")] = 0;
    snprintf(msg, len, "line %d \"%.60s\" is not two numbers time,factor", (int)lineno, line);
    break;
  }
  fclose(fp);
  if (!msg[0] && *n < 2) snprintf(msg, len, "has %d row%s; a table needs at least two (time,factor) rows", (int)*n, *n == 1 ? "" : "s");
}

/* Reads the table on rank 0 and gives it to every rank; a bad table stops every rank with the
 * same message. */
static PetscErrorCode ReadTable(MPI_Comm comm, const char option[], const char file[], MMAmplitude *a)
{
  PetscMPIInt rank;
  char        msg[512] = "";
  PetscInt    n        = 0;
  PetscReal  *t = NULL, *f = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) ReadTableRows(file, &n, &t, &f, msg, sizeof(msg));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  if (msg[0]) {
    free(t);
    free(f);
  }
  PetscCheck(!msg[0], comm, PETSC_ERR_USER_INPUT, "%s_amplitude_table %s: the file %s. Give a CSV of rows time,factor with the times increasing (README \"Loads in time\")", option, file, msg);
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  a->n = n;
  PetscCall(PetscMalloc2(n, &a->t, n, &a->f));
  if (!rank) {
    PetscCall(PetscArraycpy(a->t, t, n));
    PetscCall(PetscArraycpy(a->f, f, n));
    free(t);
    free(f);
  }
  PetscCallMPI(MPI_Bcast(a->t, n, MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(a->f, n, MPIU_REAL, 0, comm));
  PetscFunctionReturn(0);
}

/* The kinds, by name: each checks its data and sets its function. */
typedef PetscErrorCode (*MMAmplitudeCreate)(MPI_Comm, const char[], const MMAmplitudeOptions *, MMAmplitude *);

static PetscErrorCode CreateConstant(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  PetscFunctionBeginUser;
  PetscCheck(!o->time_set && !o->table[0], comm, PETSC_ERR_USER_INPUT, "%s_amplitude_%s is given but the amplitude is constant: give %s_amplitude %s, or drop the option", option, o->time_set ? "time" : "table", option, o->time_set ? "ramp or halfsine" : "table");
  a->value    = AmplitudeConstant;
  a->constant = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateTimed(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  PetscFunctionBeginUser;
  PetscCheck(o->time_set, comm, PETSC_ERR_USER_INPUT, "%s_amplitude %s needs its time: give %s_amplitude_time T (> 0)", option, o->kind, option);
  PetscCheck(o->time > 0, comm, PETSC_ERR_USER_INPUT, "%s_amplitude_time %g must be > 0", option, (double)o->time);
  PetscCheck(!o->table[0], comm, PETSC_ERR_USER_INPUT, "%s_amplitude_table is given with %s_amplitude %s: a table is its own kind, give %s_amplitude table without _amplitude_time, or drop the table", option, option, o->kind, option);
  a->T = o->time;
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateRamp(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  PetscFunctionBeginUser;
  PetscCall(CreateTimed(comm, option, o, a));
  a->value = AmplitudeRamp;
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateHalfSine(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  PetscFunctionBeginUser;
  PetscCall(CreateTimed(comm, option, o, a));
  a->value = AmplitudeHalfSine;
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateTable(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  PetscFunctionBeginUser;
  PetscCheck(o->table[0], comm, PETSC_ERR_USER_INPUT, "%s_amplitude table needs its file: give %s_amplitude_table FILE.csv (rows time,factor)", option, option);
  PetscCheck(!o->time_set, comm, PETSC_ERR_USER_INPUT, "%s_amplitude_time is given with a table amplitude, which takes its times from the file: drop it", option);
  PetscCall(ReadTable(comm, option, o->table, a));
  a->value = AmplitudeTable;
  PetscFunctionReturn(0);
}

static PetscFunctionList AmplitudeList = NULL;

static PetscErrorCode AmplitudeFinalize(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&AmplitudeList));
  PetscFunctionReturn(0);
}

static PetscErrorCode AmplitudeRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (AmplitudeList) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListAdd(&AmplitudeList, "constant", CreateConstant));
  PetscCall(PetscFunctionListAdd(&AmplitudeList, "ramp", CreateRamp));
  PetscCall(PetscFunctionListAdd(&AmplitudeList, "halfsine", CreateHalfSine));
  PetscCall(PetscFunctionListAdd(&AmplitudeList, "table", CreateTable));
  PetscCall(PetscRegisterFinalize(AmplitudeFinalize));
  PetscFunctionReturn(0);
}

/* The amplitude of option (the load's option prefix: -gravity, -traction_NAME, -pressure_NAME,
 * -point_force_NAME) from its kind. */
static PetscErrorCode AmplitudeCreate(MPI_Comm comm, const char option[], const MMAmplitudeOptions *o, MMAmplitude *a)
{
  MMAmplitudeCreate create;

  PetscFunctionBeginUser;
  PetscCall(AmplitudeRegisterAll());
  PetscCall(PetscFunctionListFind(AmplitudeList, o->kind, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "%s_amplitude %s: unknown amplitude. Use constant (the default), ramp or halfsine (with %s_amplitude_time T) or table (with %s_amplitude_table FILE.csv)", option, o->kind, option, option);
  PetscCall(create(comm, option, o, a));
  PetscFunctionReturn(0);
}

/*@
  MMAmplitudeValue - Returns an amplitude's value at a time

  Not collective

  Input Parameters:
+ a - the amplitude
- t - the time

  Level: developer

.seealso: `MMAmplitudeOptionsRead()`, `MMLoadsSetTime()`
@*/
PetscReal MMAmplitudeValue(const MMAmplitude *a, PetscReal t)
{
  return a->value(a, t);
}

/* OPTION_NAME_amplitude... for a NAME that OPTION (-traction, -pressure, -point_force) does not
 * list would be an unused option; say what it is and how to fix it. */
static PetscErrorCode CheckAmplitudeNamesOf(MPI_Comm comm, const char option[], const char what[], PetscInt n, const char *const names[])
{
  char       *all, *p, prefix[64];
  const size_t plen = strlen(option) + 1;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%s_", option));
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (p = strstr(all, prefix); p; p = strstr(p + 1, prefix)) {
    const char *name = p + plen, *amp = strstr(name, "_amplitude"), *sp = strchr(name, ' ');
    PetscBool   known = PETSC_FALSE;
    if (p != all && p[-1] != ' ') continue;
    if (!amp || (sp && amp > sp)) continue;
    for (PetscInt b = 0; b < n; ++b) known = (PetscBool)(known || (strlen(names[b]) == (size_t)(amp - name) && !strncmp(names[b], name, amp - name)));
    PetscCheck(known, comm, PETSC_ERR_USER_INPUT, "%.*s: \"%.*s\" is not a %s (%s lists %s): add it to %s with its %s%.*s_value, or correct the name", (int)(sp ? sp - p : (ptrdiff_t)strlen(p)), p, (int)(amp - name), name, what, option, n ? names[0] : "none", option, prefix, (int)(amp - name), name);
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckAmplitudeNames(MPI_Comm comm, const MMFEProblem *opt)
{
  const PetscInt n = PetscMax(PetscMax(opt->n_traction, opt->n_pressure), opt->n_point_force);
  const char   **names;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n + 1, &names));
  for (PetscInt b = 0; b < opt->n_traction; ++b) names[b] = opt->traction[b].name;
  PetscCall(CheckAmplitudeNamesOf(comm, "-traction", "traction boundary", opt->n_traction, names));
  for (PetscInt b = 0; b < opt->n_pressure; ++b) names[b] = opt->pressure[b].name;
  PetscCall(CheckAmplitudeNamesOf(comm, "-pressure", "pressure boundary", opt->n_pressure, names));
  for (PetscInt b = 0; b < opt->n_point_force; ++b) names[b] = opt->point_force[b].name;
  PetscCall(CheckAmplitudeNamesOf(comm, "-point_force", "point force group", opt->n_point_force, names));
  PetscCall(PetscFree(names));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the constrained dofs */

/* The displacement field on a copy of the mesh without constraints: every dof is in its global
 * vectors, in the same local layout as the constrained DM (as the output's). */
static PetscErrorCode CreateFullDM(MMLoads *ld)
{
  PetscFE fe;

  PetscFunctionBeginUser;
  PetscCall(DMClone(ld->op->dm, &ld->dm_full));
  PetscCall(PetscFECreateLagrange(PetscObjectComm((PetscObject)ld->op->dm), ld->op->dim, ld->op->dim, PETSC_TRUE, 1, PETSC_DETERMINE, &fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "displacement"));
  PetscCall(DMSetField(ld->dm_full, 0, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  PetscCall(DMCreateDS(ld->dm_full));
  PetscFunctionReturn(0);
}

/* The owned constrained dofs, in dm_full's global numbering, and for each the boundary it counts in:
 * a dof that two boundaries constrain (a corner node of both) counts once, in the first listed in
 * -dirichlet. */
static PetscErrorCode ConstrainedDofs(MMLoads *ld, const MMFEProblem *pb)
{
  DM              dm = ld->op->dm;
  const PetscInt  dim = ld->op->dim;
  PetscSection    ls, gsf;
  PetscInt        vStart, vEnd, *owner, n = 0, *idx;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(ld->dm_full, &gsf));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(dim * (vEnd - vStart), &owner));
  for (PetscInt i = 0; i < dim * (vEnd - vStart); ++i) owner[i] = -1;
  for (PetscInt b = 0; b < pb->n_dirichlet; ++b) {
    const MMDirichlet *bc = &pb->dirichlet[b];
    DMLabel            label;
    PetscInt           np, *pts, *vals;

    PetscCall(MMMeshGetLabel(dm, bc->name, &label));
    PetscCall(MMMeshLabelPoints(label, &np, &pts, &vals));
    for (PetscInt i = 0; i < np; ++i) {
      PetscInt *closure = NULL, ncl;
      PetscCall(DMPlexGetTransitiveClosure(dm, pts[i], PETSC_TRUE, &ncl, &closure));
      for (PetscInt j = 0; j < ncl; ++j) {
        const PetscInt v = closure[2 * j];
        if (v < vStart || v >= vEnd) continue;
        for (PetscInt c = 0; c < bc->ncomp; ++c)
          if (owner[dim * (v - vStart) + bc->comps[c]] < 0) owner[dim * (v - vStart) + bc->comps[c]] = b;
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[i], PETSC_TRUE, &ncl, &closure));
    }
    PetscCall(PetscFree2(pts, vals));
  }
  /* the dofs PETSc constrains, owned here */
  for (int pass = 0; pass < 2; ++pass) {
    n = 0;
    for (PetscInt v = vStart; v < vEnd; ++v) {
      PetscInt        goff, ncdof;
      const PetscInt *cidx;
      PetscCall(PetscSectionGetOffset(gsf, v, &goff));
      if (goff < 0) continue;
      PetscCall(PetscSectionGetConstraintDof(ls, v, &ncdof));
      if (!ncdof) continue;
      PetscCall(PetscSectionGetConstraintIndices(ls, v, &cidx));
      for (PetscInt j = 0; j < ncdof; ++j) {
        if (pass) {
          idx[n]      = goff + cidx[j];
          ld->Dcomp[n] = cidx[j];
          ld->Dbc[n]   = PetscMax(owner[dim * (v - vStart) + cidx[j]], 0);
        }
        ++n;
      }
    }
    if (!pass) {
      PetscCall(PetscMalloc1(n, &idx));
      PetscCall(PetscMalloc1(n, &ld->Dcomp));
      PetscCall(PetscMalloc1(n, &ld->Dbc));
    }
  }
  ld->nD = n;
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)dm), n, idx, PETSC_COPY_VALUES, &ld->isD));
  PetscCall(PetscFree(idx));
  PetscCall(PetscFree(owner));
  PetscFunctionReturn(0);
}

/* The rows D of the Cartesian K and M (M lumped by row sums when -mass_lumped), all columns. */
static PetscErrorCode AssembleRowsD(MMLoads *ld)
{
  Mat      K, M;
  IS       cols;
  PetscInt rstart, rend;

  PetscFunctionBeginUser;
  PetscCall(MMCreateMatrixP1(ld->dm_full, &K));
  PetscCall(MatDuplicate(K, MAT_DO_NOT_COPY_VALUES, &M));
  PetscCall(MMAssembleP1(ld->dm_full, ld->material, K, M));
  if (ld->op->lumped) {
    Vec rs;
    PetscCall(MatCreateVecs(M, NULL, &rs));
    PetscCall(MatGetRowSum(M, rs));
    PetscCall(MatZeroEntries(M));
    PetscCall(MatDiagonalSet(M, rs, INSERT_VALUES));
    PetscCall(VecDestroy(&rs));
  }
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  PetscCall(ISCreateStride(PetscObjectComm((PetscObject)K), rend - rstart, rstart, 1, &cols));
  PetscCall(MatCreateSubMatrix(K, ld->isD, cols, MAT_INITIAL_MATRIX, &ld->KD));
  PetscCall(MatCreateSubMatrix(M, ld->isD, cols, MAT_INITIAL_MATRIX, &ld->MD));
  PetscCall(ISDestroy(&cols));
  PetscCall(MatDestroy(&K));
  PetscCall(MatDestroy(&M));
  PetscCall(MatCreateVecs(ld->KD, &ld->full, &ld->rD));
  PetscCall(VecDuplicate(ld->full, &ld->full2));
  PetscCall(VecDuplicate(ld->rD, &ld->rD0));
  PetscCall(VecDuplicate(ld->rD, &ld->uD0));
  PetscCall(VecDuplicate(ld->rD, &ld->uD1));
  PetscCall(VecDuplicate(ld->rD, &ld->vD));
  PetscFunctionReturn(0);
}

/* The Cartesian field on every dof (dm_full) from the free dofs w, with the Dirichlet data of time t
 * on the constrained dofs when with_bc, zero there otherwise. w may be NULL (zero). */
static PetscErrorCode FullField(MMLoads *ld, Vec w, PetscReal t, PetscBool with_bc, Vec full)
{
  DM  dm = ld->op->dm;
  Vec g, l;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm, &g));
  PetscCall(DMGetLocalVector(dm, &l));
  if (w) PetscCall(MMFEToCartesian(ld->op, w, g));
  else PetscCall(VecZeroEntries(g));
  PetscCall(VecZeroEntries(l));
  PetscCall(DMGlobalToLocal(dm, g, INSERT_VALUES, l));
  if (with_bc) PetscCall(MMLoadsInsertBoundaryValues(ld, l, t));
  PetscCall(MMInsertMapLocalToGlobal(ld->dm_full, &ld->to_full, l, full));
  PetscCall(DMRestoreLocalVector(dm, &l));
  PetscCall(DMRestoreGlobalVector(dm, &g));
  PetscFunctionReturn(0);
}

/* The free dofs of a dm_full vector of forces, in the w-frame. */
static PetscErrorCode FreePart(MMLoads *ld, Vec full, Vec w)
{
  DM  dm = ld->op->dm;
  Vec g, l;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm, &g));
  PetscCall(DMGetLocalVector(dm, &l));
  PetscCall(DMGlobalToLocal(ld->dm_full, full, INSERT_VALUES, l));
  PetscCall(VecZeroEntries(g));
  PetscCall(MMInsertMapLocalToGlobal(dm, &ld->to_free, l, g));
  PetscCall(MMFEForceFromCartesian(ld->op, g, w));
  PetscCall(DMRestoreLocalVector(dm, &l));
  PetscCall(DMRestoreGlobalVector(dm, &g));
  PetscFunctionReturn(0);
}

/* A copy of the w-frame vector x with the massless (contact-normal) dofs zeroed: M* has no entries
 * there, in the rows D too. */
static PetscErrorCode WithInertia(MMLoads *ld, Vec x, Vec y)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(x, y));
  if (ld->massless) PetscCall(VecISSet(y, ld->massless, 0.0));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- the load parts */

/* Part k at amplitude 1 on every dof (dm_full, Cartesian) into full: k = 0 gravity, m_i g at each
 * vertex (the lumped mass is exact for a constant g), then the tractions, pressures and point forces
 * (PartName). */
static PetscErrorCode LoadPartFull(MMLoads *ld, const MMFEProblem *pb, PetscInt k, Vec full)
{
  DM       dm = ld->op->dm;
  Vec      floc;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(dm, &floc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecZeroEntries(full));
  if (k == 0) {
    Vec                mloc;
    const PetscScalar *m;
    PetscScalar       *f;
    PetscInt           vStart, vEnd;

    PetscCall(DMGetLocalVector(ld->op->dm_scalar, &mloc));
    PetscCall(MMFEVertexMasses(ld->op, ld->material, mloc));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    PetscCall(VecGetArrayRead(mloc, &m));
    PetscCall(VecGetArray(floc, &f));
    for (PetscInt v = vStart; v < vEnd; ++v) {
      PetscInt off, soff;
      PetscCall(DMPlexGetPointLocal(dm, v, &off, NULL));
      PetscCall(DMPlexGetPointLocal(ld->op->dm_scalar, v, &soff, NULL));
      for (PetscInt c = 0; c < ld->op->dim; ++c) f[off + c] = m[soff] * pb->gravity[c];
    }
    PetscCall(VecRestoreArray(floc, &f));
    PetscCall(VecRestoreArrayRead(mloc, &m));
    PetscCall(DMRestoreLocalVector(ld->op->dm_scalar, &mloc));
    /* the vertex masses are summed over ranks already */
    PetscCall(DMLocalToGlobal(ld->dm_full, floc, INSERT_VALUES, full));
  } else {
    const PetscInt nt = pb->n_traction, np = pb->n_pressure;
    if (k <= nt) PetscCall(MMFEAddTraction(ld->op, &pb->traction[k - 1], floc));
    else if (k <= nt + np) PetscCall(MMFEAddPressure(ld->op, &pb->pressure[k - 1 - nt], floc));
    else PetscCall(MMFEAddPointForce(ld->op, &pb->point_force[k - 1 - nt - np], floc));
    PetscCall(DMLocalToGlobal(ld->dm_full, floc, ADD_VALUES, full));
  }
  PetscCall(DMRestoreLocalVector(dm, &floc));
  PetscFunctionReturn(0);
}

/* Part k's option prefix (-gravity, -traction_NAME, -pressure_NAME, -point_force_NAME) and its
 * amplitude's options. */
static PetscErrorCode PartName(const MMFEProblem *opt, PetscInt k, char option[], size_t len, const MMAmplitudeOptions **amp)
{
  const PetscInt nt = opt->n_traction, np = opt->n_pressure;

  PetscFunctionBeginUser;
  if (k == 0) {
    PetscCall(PetscStrncpy(option, "-gravity", len));
    *amp = opt->gravity_amplitude;
  } else if (k <= nt) {
    PetscCall(PetscSNPrintf(option, len, "-traction_%s", opt->traction[k - 1].name));
    *amp = &opt->traction[k - 1].amplitude;
  } else if (k <= nt + np) {
    PetscCall(PetscSNPrintf(option, len, "-pressure_%s", opt->pressure[k - 1 - nt].name));
    *amp = &opt->pressure[k - 1 - nt].amplitude;
  } else {
    PetscCall(PetscSNPrintf(option, len, "-point_force_%s", opt->point_force[k - 1 - nt - np].name));
    *amp = &opt->point_force[k - 1 - nt - np].amplitude;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateParts(MMLoads *ld, const MMFEProblem *pb)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)ld->op->dm);

  PetscFunctionBeginUser;
  ld->nparts = 1 + pb->n_traction + pb->n_pressure + pb->n_point_force;
  PetscCall(PetscCalloc1(ld->nparts, &ld->amp));
  for (PetscInt k = 0; k < ld->nparts; ++k) {
    char                option[300];
    const MMAmplitudeOptions *amp = NULL;
    PetscCall(PartName(pb, k, option, sizeof(option), &amp));
    PetscCall(AmplitudeCreate(comm, option, amp, &ld->amp[k]));
  }
  for (PetscInt k = 0; k < ld->nparts; ++k) ld->in_time = (PetscBool)(ld->in_time || !ld->amp[k].constant);
  PetscCheck(!ld->in_time || !pb->static_sliding, comm, PETSC_ERR_USER_INPUT, "-initial_state static_sliding balances the loads of t = 0 for all time: it needs constant loads. Drop the -gravity_amplitude, -traction_NAME_amplitude, -pressure_NAME_amplitude and -point_force_NAME_amplitude options, or use -initial_state given");
  if (!ld->in_time && !pb->n_dirichlet) PetscFunctionReturn(0);
  if (ld->in_time) {
    PetscCall(PetscMalloc1(ld->nparts, &ld->part));
    PetscCall(VecDuplicate(ld->load, &ld->load_old));
  }
  if (pb->n_dirichlet) PetscCall(PetscMalloc1(ld->nparts, &ld->partD));
  /* a load in time on a body without Dirichlet boundaries still builds its parts on dm_full */
  if (!ld->dm_full) PetscCall(CreateFullDM(ld));
  for (PetscInt k = 0; k < ld->nparts; ++k) {
    Vec full;
    PetscCall(DMGetGlobalVector(ld->dm_full, &full));
    PetscCall(LoadPartFull(ld, pb, k, full));
    if (ld->in_time) {
      PetscCall(VecDuplicate(ld->load, &ld->part[k]));
      PetscCall(FreePart(ld, full, ld->part[k]));
    }
    if (pb->n_dirichlet) {
      Vec sub;
      PetscCall(VecDuplicate(ld->rD, &ld->partD[k]));
      PetscCall(VecGetSubVector(full, ld->isD, &sub));
      PetscCall(VecCopy(sub, ld->partD[k]));
      PetscCall(VecRestoreSubVector(full, ld->isD, &sub));
    }
    PetscCall(DMRestoreGlobalVector(ld->dm_full, &full));
  }
  PetscFunctionReturn(0);
}

/* L_D(t) = sum_k a_k(t) L_k on D, into y. */
static PetscErrorCode LoadD(MMLoads *ld, PetscReal t, Vec y)
{

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(y));
  for (PetscInt k = 0; k < ld->nparts; ++k) PetscCall(VecAXPY(y, MMAmplitudeValue(&ld->amp[k], t), ld->partD[k]));
  PetscFunctionReturn(0);
}

/* The boundary velocity on D, uD(1) - uD(0), and vD . M_DD vD for the kinetic energy. */
static PetscErrorCode SetUpMoving(MMLoads *ld, const MMFEProblem *pb)
{
  Vec         sub, y;
  PetscScalar vMv;

  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < pb->n_dirichlet; ++b)
    for (PetscInt c = 0; c < pb->dirichlet[b].nvelocity; ++c) ld->moving = (PetscBool)(ld->moving || pb->dirichlet[b].velocity[c] != 0);
  ld->moving = (PetscBool)(ld->moving || ld->dirichlet_amplitude);
  if (!ld->moving) PetscFunctionReturn(0);
  PetscCall(FullField(ld, NULL, 1.0, PETSC_TRUE, ld->full));
  PetscCall(VecGetSubVector(ld->full, ld->isD, &sub));
  PetscCall(VecCopy(sub, ld->vD));
  PetscCall(VecRestoreSubVector(ld->full, ld->isD, &sub));
  PetscCall(FullField(ld, NULL, 0.0, PETSC_TRUE, ld->full));
  PetscCall(VecGetSubVector(ld->full, ld->isD, &sub));
  PetscCall(VecAXPY(ld->vD, -1.0, sub));
  PetscCall(VecRestoreSubVector(ld->full, ld->isD, &sub));
  PetscCall(VecZeroEntries(ld->full));
  PetscCall(VecISCopy(ld->full, ld->isD, SCATTER_FORWARD, ld->vD));
  PetscCall(VecDuplicate(ld->rD, &y));
  PetscCall(MatMult(ld->MD, ld->full, y));
  PetscCall(VecDot(ld->vD, y, &vMv));
  ld->vMv_DD = PetscRealPart(vMv);
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

/* The amplitudes of the Dirichlet values. A value that is not affine in t has an acceleration: with
 * the lumped mass (M_fD = 0) it reaches the free dofs only through K_fD u_D(t), and the boundary
 * nodes' own inertia is left out of the system, their motion being the support's (docs/method.md
 * section 10); the consistent mass would need a_D in M*_fD a_D, which is not carried. */
static PetscErrorCode DirichletAmplitudes(MMLoads *ld, const MMFEProblem *opt)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)ld->op->dm);
  char      prefix[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(opt->n_dirichlet, &ld->bc_amp));
  ld->n_bc = opt->n_dirichlet;
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b) {
    MMDirichlet *bc = &opt->dirichlet[b];
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "-dirichlet_%s", bc->name));
    PetscCall(AmplitudeCreate(comm, prefix, &bc->amplitude, &ld->bc_amp[b]));
    if (ld->bc_amp[b].constant) continue;
    PetscCheck(ld->op->lumped, comm, PETSC_ERR_SUP, "%s_amplitude %s needs -mass_lumped: with the consistent mass the boundary's acceleration drives the free dofs through M_fD, which is not in the scheme (a constant -dirichlet_%s_velocity works with either mass)", prefix, bc->amplitude.kind, bc->name);
    PetscCheck(!opt->damped, comm, PETSC_ERR_SUP, "%s_amplitude with Rayleigh damping is not supported: the damping force of a moving boundary is not in the scheme. Drop one of the two", prefix);
    bc->amp                 = &ld->bc_amp[b];
    ld->dirichlet_amplitude = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* The Dirichlet data on dm's local vectors as a table, u_D(t) = bv0 + t bv1 on the constrained local
 * dofs, when no value has an amplitude: each boundary's data value + velocity t (fem.c) is affine in
 * t. DMPlexInsertBoundaryValues projects the data point by point, one small MatMult per point, several
 * calls a step: a large share of a run with many constrained vertices (the figures: docs/scaling.md,
 * "The figures behind the code's choices"). The table is read off two such projections, at t = 0
 * and t = 1. */
static PetscErrorCode TabulateBoundaryValues(MMLoads *ld, const MMFEProblem *pb)
{
  DM                 dm = ld->op->dm;
  PetscSection       sec;
  PetscInt           pStart, pEnd, n = 0;
  Vec                l0, l1;
  const PetscScalar *a0, *a1;

  PetscFunctionBeginUser;
  ld->bv_n = -1;
  if (!pb->n_dirichlet || ld->dirichlet_amplitude) PetscFunctionReturn(0);
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(PetscSectionGetChart(sec, &pStart, &pEnd));
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt cdof;
    PetscCall(PetscSectionGetConstraintDof(sec, p, &cdof));
    n += cdof;
  }
  PetscCall(PetscMalloc3(n, &ld->bv_idx, n, &ld->bv0, n, &ld->bv1));
  PetscCall(DMGetLocalVector(dm, &l0));
  PetscCall(DMGetLocalVector(dm, &l1));
  PetscCall(VecZeroEntries(l0));
  PetscCall(VecZeroEntries(l1));
  PetscCall(DMPlexInsertBoundaryValues(dm, PETSC_TRUE, l0, 0.0, NULL, NULL, NULL));
  PetscCall(DMPlexInsertBoundaryValues(dm, PETSC_TRUE, l1, 1.0, NULL, NULL, NULL));
  PetscCall(VecGetArrayRead(l0, &a0));
  PetscCall(VecGetArrayRead(l1, &a1));
  n = 0;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    const PetscInt *cind;
    PetscInt        cdof, off;
    PetscCall(PetscSectionGetConstraintDof(sec, p, &cdof));
    if (!cdof) continue;
    PetscCall(PetscSectionGetOffset(sec, p, &off));
    PetscCall(PetscSectionGetConstraintIndices(sec, p, &cind));
    for (PetscInt j = 0; j < cdof; ++j, ++n) {
      ld->bv_idx[n] = off + cind[j];
      ld->bv0[n]    = PetscRealPart(a0[off + cind[j]]);
      ld->bv1[n]    = PetscRealPart(a1[off + cind[j]]) - ld->bv0[n];
    }
  }
  PetscCall(VecRestoreArrayRead(l1, &a1));
  PetscCall(VecRestoreArrayRead(l0, &a0));
  PetscCall(DMRestoreLocalVector(dm, &l1));
  PetscCall(DMRestoreLocalVector(dm, &l0));
  ld->bv_n = n;
  PetscFunctionReturn(0);
}

/*@
  MMLoadsInsertBoundaryValues - Inserts the Dirichlet data of a time into the constrained dofs of a
  local vector

  Not collective

  Input Parameters:
+ ld - the loads
. l  - a local vector of the operators' DM, its constrained dofs set on return
- t  - the time

  Note:
  The Dirichlet data of time t into the constrained dofs of a local vector of the operators' DM: from
  the table where the data are affine in t, else (amplitudes, or during MMLoadsSetUp) by DMPlex's
  projection.

  Level: intermediate

.seealso: `MMLoadsInsertDirichletVelocity()`, `MMElasticityLocal()`
@*/
PetscErrorCode MMLoadsInsertBoundaryValues(MMLoads *ld, Vec l, PetscReal t)
{
  PetscScalar *a;

  PetscFunctionBeginUser;
  if (ld->bv_n < 0 || !ld->bv_idx) {
    PetscCall(DMPlexInsertBoundaryValues(ld->op->dm, PETSC_TRUE, l, t, NULL, NULL, NULL));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArray(l, &a));
  for (PetscInt i = 0; i < ld->bv_n; ++i) a[ld->bv_idx[i]] = ld->bv0[i] + t * ld->bv1[i];
  PetscCall(VecRestoreArray(l, &a));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsScaleBoundaryValues - Scales the Dirichlet data inserted in a local vector

  Not collective

  Input Parameters:
+ ld - the loads, their Dirichlet data tabulated (no amplitude)
. l  - a local vector with the Dirichlet data inserted (MMLoadsInsertBoundaryValues())
- s  - the factor

  Note:
  The finite-strain static start's load factor (docs/method.md section 13): its load levels take the
  Dirichlet data in the same proportion as the forces

  Level: developer

.seealso: `MMLoadsInsertBoundaryValues()`
@*/
PetscErrorCode MMLoadsScaleBoundaryValues(MMLoads *ld, Vec l, PetscReal s)
{
  PetscScalar *a;

  PetscFunctionBeginUser;
  if (s == 1.0 || !ld->n_bc || !ld->bv_n) PetscFunctionReturn(0); /* no Dirichlet data */
  PetscCheck(ld->bv_n > 0 && ld->bv_idx, PETSC_COMM_SELF, PETSC_ERR_SUP, "The Dirichlet data are not tabulated (a value with an amplitude): they cannot be scaled");
  PetscCall(VecGetArray(l, &a));
  for (PetscInt i = 0; i < ld->bv_n; ++i) a[ld->bv_idx[i]] *= s;
  PetscCall(VecRestoreArray(l, &a));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsSetUp - Sets up the loads' parts in time and the Dirichlet data's rows on the operators

  Collective

  Input Parameters:
+ ld       - the loads
. op       - the operators (borrowed), after the contact frame
. mat      - the bodies' material
. pb       - the problem
. massless - M*'s dofs without inertia (borrowed), or NULL
. load     - the w-frame load (contact's, borrowed: MMContactGetOperators), set at each step's time
- lift     - the w-frame lift (likewise), set at each step's time with moving Dirichlet data

  Note:
  The loads' parts and the Dirichlet data's rows on the operators op (borrowed), after
  MMFEAssembleOperators and the contact frame; massless (borrowed): M*'s dofs without inertia,
  NULL if none, where the reactions' accelerations are zero. fem's own load and lift stay
  Cartesian: the loads in time write L(t) = sum a_k(t) L_k from their w-frame parts into contact's
  load, which rounds as the parts do (docs/developer.md, "The contact frame").

  Level: intermediate

.seealso: `MMLoadsSetTime()`, `MMLoadsDestroy()`, `MMFEAssembleOperators()`
@*/
PetscErrorCode MMLoadsSetUp(MMLoads *ld, MMOperators op, const MMMaterial *mat, const MMFEProblem *pb, IS massless, Vec load, Vec lift)
{

  PetscFunctionBeginUser;
  ld->op       = op;
  ld->material = mat;
  ld->massless = massless;
  ld->load     = load;
  ld->lift     = lift;
  PetscCall(CheckAmplitudeNames(PetscObjectComm((PetscObject)ld->op->dm), pb));
  if (pb->n_dirichlet) PetscCall(DirichletAmplitudes(ld, pb));
  PetscCall(TabulateBoundaryValues(ld, pb));
  if (pb->n_dirichlet) {
    PetscCall(CreateFullDM(ld));
    PetscCall(ConstrainedDofs(ld, pb));
    PetscCall(AssembleRowsD(ld));
    PetscCall(PetscCalloc1(MM_MAX_DIM * pb->n_dirichlet, &ld->reaction));
  }
  PetscCall(CreateParts(ld, pb));
  if (pb->n_dirichlet) PetscCall(SetUpMoving(ld, pb));
  PetscCall(MMLoadsSetTime(ld, 0.0, 0.0));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- per step */

/*@
  MMLoadsSetTime - Sets the loads of a step from t0 to t1: op's load and lift, and the Dirichlet
  data's energy

  Collective

  Input Parameters:
+ ld - the loads, set up
. t0 - the step's start time
- t1 - its end time (t0 = t1 between steps)

  Note:
  The loads of a step from t0 to t1 (between steps t0 = t1, the current time): the w-frame load =
  L(t1) and load_old = L(t0); with moving Dirichlet data the w-frame lift = K_fD u_D(t1) and op.energy_dirichlet =
  1/2 u_D.A_DD u_D at t1, both from the rows D of K, the operator the reaction uses, so that the
  energy identity closes with the reaction's work (docs/method.md section 10).

  Level: intermediate

.seealso: `MMLoadsSetUp()`, `MMLoadsStepWork()`
@*/
PetscErrorCode MMLoadsSetTime(MMLoads *ld, PetscReal t0, PetscReal t1)
{

  PetscFunctionBeginUser;
  ld->t0 = t0;
  ld->t1 = t1;
  if (ld->in_time) {
    PetscCall(VecZeroEntries(ld->load));
    PetscCall(VecZeroEntries(ld->load_old));
    for (PetscInt k = 0; k < ld->nparts; ++k) {
      PetscCall(VecAXPY(ld->load, MMAmplitudeValue(&ld->amp[k], t1), ld->part[k]));
      PetscCall(VecAXPY(ld->load_old, MMAmplitudeValue(&ld->amp[k], t0), ld->part[k]));
    }
  }
  if (ld->moving) {
    Vec         sub;
    PetscScalar e;
    PetscCall(FullField(ld, NULL, t1, PETSC_TRUE, ld->full));
    PetscCall(VecGetSubVector(ld->full, ld->isD, &sub));
    PetscCall(VecCopy(sub, ld->uD1));
    PetscCall(VecRestoreSubVector(ld->full, ld->isD, &sub));
    PetscCall(MatMult(ld->KD, ld->full, ld->rD));
    PetscCall(VecDot(ld->uD1, ld->rD, &e));
    ld->op->energy_dirichlet = 0.5 * PetscRealPart(e);
    PetscCall(MatMultTranspose(ld->KD, ld->uD1, ld->full2));
    PetscCall(FreePart(ld, ld->full2, ld->lift));
  }
  PetscFunctionReturn(0);
}

/* R_D = (M* a + K u - L)_D at time t, the support's force on the body on each constrained dof. */
/* The finite-strain laws' internal force P(F) on the constrained dofs, the state's own (not the step's
 * algorithmic force: the reaction reported at a time, exact at rest; docs/method.md section 13) */
static PetscErrorCode FiniteStrainForceD(MMLoads *ld, Vec u, PetscReal t, Vec RD)
{
  Vec sub;

  PetscFunctionBeginUser;
  PetscCall(MMElasticityLocal(ld->el, ld->op, ld, u, t, ld->el->l1));
  PetscCall(MMElasticityForceLocal(ld->el, ld->op, ld->material, ld->el->l1));
  PetscCall(VecZeroEntries(ld->full));
  PetscCall(DMLocalToGlobal(ld->dm_full, ld->el->lf, ADD_VALUES, ld->full));
  PetscCall(VecGetSubVector(ld->full, ld->isD, &sub));
  PetscCall(VecCopy(sub, RD));
  PetscCall(VecRestoreSubVector(ld->full, ld->isD, &sub));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsSetElasticity - Makes the Dirichlet supports' reactions come from the finite-strain force
  instead of K_D

  Not collective

  Input Parameters:
+ ld - the loads
- el - the finite-strain elasticity (borrowed)

  Level: intermediate

.seealso: `MMLoadsReactions()`, `MMElasticityForceLocal()`
@*/
PetscErrorCode MMLoadsSetElasticity(MMLoads *ld, MMElasticity *el)
{
  PetscFunctionBeginUser;
  ld->el = el;
  PetscFunctionReturn(0);
}

static PetscErrorCode Reaction(MMLoads *ld, Vec u, Vec a, PetscReal t, Vec R)
{
  Vec      aw;

  PetscFunctionBeginUser;
  if (ld->el) PetscCall(FiniteStrainForceD(ld, u, t, R));
  else {
    PetscCall(FullField(ld, u, t, PETSC_TRUE, ld->full));
    PetscCall(MatMult(ld->KD, ld->full, R));
  }
  PetscCall(VecDuplicate(a, &aw));
  PetscCall(WithInertia(ld, a, aw));
  /* the data are affine in t: their acceleration is zero */
  PetscCall(FullField(ld, aw, t, PETSC_FALSE, ld->full2));
  PetscCall(VecDestroy(&aw));
  PetscCall(MatMultAdd(ld->MD, ld->full2, R, R));
  PetscCall(LoadD(ld, t, ld->rD0));
  PetscCall(VecAXPY(R, -1.0, ld->rD0));
  PetscFunctionReturn(0);
}

/* The resultant of R per boundary and Cartesian component, over all ranks. */
static PetscErrorCode SumReactions(MMLoads *ld, Vec R)
{
  const PetscScalar *r;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(ld->reaction, MM_MAX_DIM * ld->n_bc));
  PetscCall(VecGetArrayRead(R, &r));
  for (PetscInt i = 0; i < ld->nD; ++i) ld->reaction[MM_MAX_DIM * ld->Dbc[i] + ld->Dcomp[i]] += PetscRealPart(r[i]);
  PetscCall(VecRestoreArrayRead(R, &r));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ld->reaction, MM_MAX_DIM * ld->n_bc, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ld->op->dm)));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsReactions - Computes the Dirichlet supports' reactions of the state at the current time

  Collective

  Input Parameters:
+ ld - the loads
. u  - the displacement
- a  - the acceleration

  Note:
  The reactions of the current state u, a, at the current time (the initial row, a restart's).

  Level: intermediate

.seealso: `MMLoadsStepWork()`, `MMLoadsSetElasticity()`
@*/
PetscErrorCode MMLoadsReactions(MMLoads *ld, Vec u, Vec a)
{
  Vec      R;

  PetscFunctionBeginUser;
  if (!ld->n_bc) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ld->rD, &R));
  PetscCall(Reaction(ld, u, a, ld->t1, R));
  PetscCall(SumReactions(ld, R));
  PetscCall(VecDestroy(&R));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsStepWork - Computes an accepted step's works on the constrained dofs, and the reactions at
  its end

  Collective

  Input Parameters:
+ ld    - the loads
. u     - the displacement at the step's end
. a     - the acceleration at its end
. u_old - the displacement at its start
- a_old - the acceleration at its start

  Output Parameters:
+ w_ext_D - the loads' work on the moving Dirichlet dofs (part of W_ext)
- w_D     - the supports' work W_D

  Note:
  The accepted step's works on the constrained dofs, and the reactions at its end (the state u, a at
  its end, u_old, a_old at its start): with the data
  moving by du_D = u_D(t1) - u_D(t0), the loads there do 1/2 (L_D^n + L_D^{n+1}).du_D (part of
  W_ext) and the support 1/2 (R_D^n + R_D^{n+1}).du_D (W_D). R_D^n is recomputed from the step's
  start, so nothing but the running sum is carried between steps (or in a checkpoint).

  Level: intermediate

.seealso: `MMLoadsReactions()`, `MMLoadsSetTime()`
@*/
PetscErrorCode MMLoadsStepWork(MMLoads *ld, Vec u, Vec a, Vec u_old, Vec a_old, PetscReal *w_ext_D, PetscReal *w_D)
{
  Vec         R1, R0, L0, du, sub;
  PetscScalar wr, wl;

  PetscFunctionBeginUser;
  *w_ext_D = *w_D = 0;
  if (!ld->n_bc) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ld->rD, &R1));
  PetscCall(Reaction(ld, u, a, ld->t1, R1));
  PetscCall(SumReactions(ld, R1));
  if (ld->moving) {
    PetscCall(VecDuplicate(ld->rD, &R0));
    PetscCall(VecDuplicate(ld->rD, &L0));
    PetscCall(VecDuplicate(ld->rD, &du));
    PetscCall(FullField(ld, NULL, ld->t0, PETSC_TRUE, ld->full));
    PetscCall(VecGetSubVector(ld->full, ld->isD, &sub));
    PetscCall(VecCopy(sub, ld->uD0));
    PetscCall(VecRestoreSubVector(ld->full, ld->isD, &sub));
    PetscCall(VecWAXPY(du, -1.0, ld->uD0, ld->uD1));
    /* with amplitudes the boundary's velocity changes: the output shows the step's mean */
    if (ld->dirichlet_amplitude && ld->t1 > ld->t0) PetscCall(VecAXPBY(ld->vD, 1.0 / (ld->t1 - ld->t0), 0.0, du));
    PetscCall(Reaction(ld, u_old, a_old, ld->t0, R0));
    PetscCall(VecAXPY(R0, 1.0, R1));
    PetscCall(VecDot(R0, du, &wr));
    PetscCall(LoadD(ld, ld->t0, L0));
    PetscCall(LoadD(ld, ld->t1, R0));
    PetscCall(VecAXPY(L0, 1.0, R0));
    PetscCall(VecDot(L0, du, &wl));
    *w_D     = 0.5 * PetscRealPart(wr);
    *w_ext_D = 0.5 * PetscRealPart(wl);
    PetscCall(VecDestroy(&R0));
    PetscCall(VecDestroy(&L0));
    PetscCall(VecDestroy(&du));
  }
  PetscCall(VecDestroy(&R1));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsDirichletKinetic - Computes the kinetic energy the constrained dofs add to 1/2 v_f.M*_ff
  v_f

  Collective

  Input Parameters:
+ ld - the loads
- v  - the velocity

  Output Parameter:
. ek - the constrained dofs' share of the kinetic energy

  Note:
  The kinetic energy the constrained dofs add to 1/2 v_f.M*_ff v_f: with v = (v_f, v_D),
  1/2 v.M* v = 1/2 v_f.M*_ff v_f + v_D.M_Df v_f + 1/2 v_D.M_DD v_D = ... + v_D.(M_D v) - 1/2 v_D.M_DD v_D.

  Level: developer

.seealso: `MMLoadsStepWork()`
@*/
PetscErrorCode MMLoadsDirichletKinetic(MMLoads *ld, Vec v, PetscReal *ek)
{
  Vec         vw;
  PetscScalar vMv;

  PetscFunctionBeginUser;
  *ek = 0;
  /* with amplitudes the boundary nodes' inertia is the support's, out of the system (lumped mass:
   * M_fD = 0, so nothing couples them to the free dofs) */
  if (!ld->moving || ld->dirichlet_amplitude) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(v, &vw));
  PetscCall(WithInertia(ld, v, vw));
  PetscCall(FullField(ld, vw, 0.0, PETSC_FALSE, ld->full2));
  PetscCall(VecDestroy(&vw));
  PetscCall(VecISCopy(ld->full2, ld->isD, SCATTER_FORWARD, ld->vD));
  PetscCall(MatMult(ld->MD, ld->full2, ld->rD0));
  PetscCall(VecDot(ld->vD, ld->rD0, &vMv));
  *ek = PetscRealPart(vMv) - 0.5 * ld->vMv_DD;
  PetscFunctionReturn(0);
}

/*@
  MMLoadsInsertDirichletVelocity - Sets the constrained dofs of a whole velocity field to the
  boundary's velocity, when the Dirichlet data move

  Collective

  Input Parameters:
+ ld    - the loads
- whole - the whole velocity field, its constrained dofs set on return

  Note:
  The whole velocity field's constrained dofs (the output's dm_out shares dm_full's layout): the
  boundary's velocity.

  Level: developer

.seealso: `MMLoadsInsertBoundaryValues()`
@*/
PetscErrorCode MMLoadsInsertDirichletVelocity(MMLoads *ld, Vec whole)
{
  PetscFunctionBeginUser;
  if (ld->moving) PetscCall(VecISCopy(whole, ld->isD, SCATTER_FORWARD, ld->vD));
  PetscFunctionReturn(0);
}

/*@
  MMLoadsDestroy - Frees what the loads hold

  Collective

  Input Parameter:
. ld - the loads

  Level: intermediate

.seealso: `MMLoadsSetUp()`
@*/
PetscErrorCode MMLoadsDestroy(MMLoads *ld)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < ld->nparts; ++k) {
    if (ld->part) PetscCall(VecDestroy(&ld->part[k]));
    if (ld->partD) PetscCall(VecDestroy(&ld->partD[k]));
    PetscCall(PetscFree2(ld->amp[k].t, ld->amp[k].f));
  }
  PetscCall(PetscFree(ld->part));
  PetscCall(PetscFree(ld->partD));
  PetscCall(PetscFree(ld->amp));
  for (PetscInt b = 0; b < ld->n_bc; ++b) PetscCall(PetscFree2(ld->bc_amp[b].t, ld->bc_amp[b].f));
  PetscCall(PetscFree(ld->bc_amp));
  PetscCall(PetscFree3(ld->bv_idx, ld->bv0, ld->bv1));
  PetscCall(VecDestroy(&ld->load_old));
  {
    Vec *vecs[] = {&ld->full, &ld->full2, &ld->rD, &ld->rD0, &ld->uD0, &ld->uD1, &ld->vD};
    for (size_t i = 0; i < sizeof(vecs) / sizeof(vecs[0]); ++i) PetscCall(VecDestroy(vecs[i]));
  }
  PetscCall(MatDestroy(&ld->KD));
  PetscCall(MatDestroy(&ld->MD));
  PetscCall(ISDestroy(&ld->isD));
  PetscCall(PetscFree(ld->Dcomp));
  PetscCall(PetscFree(ld->Dbc));
  PetscCall(PetscFree(ld->reaction));
  PetscCall(DMDestroy(&ld->dm_full));
  PetscCall(MMInsertMapDestroy(&ld->to_full));
  PetscCall(MMInsertMapDestroy(&ld->to_free));
  PetscFunctionReturn(0);
}
