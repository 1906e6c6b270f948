/* The data check, -check_input (abaqus datacheck, MOOSE --check-input; README "Checking a case
 * before a batch job"). main.c builds the case exactly as for a run (the mesh, the operators, the
 * contact set, the initial state, K~ for dt) and refuses what a run refuses, with the same message
 * and status; it then stops before the output is opened: no directory, no lock, no file. What the
 * check adds to the start-up report is here: each physical group's node and element counts, the
 * planned steps and output size, and a first-contact estimate. */
#include <petscsf.h>
#include "mesh.h"
#include "appimpl.h"
#include "fem.h"
#include "contact.h"
#include "ts.h"
#include "io.h"

/* A size in bytes, in decimal units: "61.2 kB". */
static PetscErrorCode BytesText(PetscReal b, char text[], size_t len)
{
  const char *unit[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  PetscInt    u      = 0;

  PetscFunctionBeginUser;
  while (b >= 1000 && u < (PetscInt)PETSC_STATIC_ARRAY_LENGTH(unit) - 1) {
    b /= 1000;
    ++u;
  }
  PetscCall(PetscSNPrintf(text, len, u ? "%.3g %s" : "%.0f %s", (double)b, unit[u]));
  PetscFunctionReturn(0);
}

/* A physical group's size over all ranks: its cells, its facets (each once, MMMeshGetFacets) and its
 * nodes, the vertices of its points, each counted once, on the rank that owns it. A rank that holds
 * a vertex of the group may not own it: the marks are reduced onto the owners over the point SF. */
static PetscErrorCode GroupSizes(DM dm, const char name[], PetscInt sizes[3])
{
  DMLabel         label;
  PetscSF         sf;
  MMFacetList     fl;
  PetscInt        pStart, pEnd, cStart, cEnd, vStart, vEnd, depth, dim, n, nleaves, *pts, *vals, *mark, *owned;
  const PetscInt *leaves;

  PetscFunctionBeginUser;
  sizes[0] = sizes[1] = sizes[2] = 0;
  PetscCall(DMGetLabel(dm, name, &label));
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscCalloc2(pEnd, &mark, pEnd, &owned));
  /* the cells, and the vertices in the closure of every point of the group */
  PetscCall(MMMeshLabelPoints(label, &n, &pts, &vals));
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt *cl = NULL, ncl;
    if (pts[i] >= cStart && pts[i] < cEnd) ++sizes[0]; /* no overlap: a cell is on one rank */
    PetscCall(DMPlexGetTransitiveClosure(dm, pts[i], PETSC_TRUE, &ncl, &cl));
    for (PetscInt q = 0; q < ncl; ++q)
      if (cl[2 * q] >= vStart && cl[2 * q] < vEnd) mark[cl[2 * q]] = 1;
    PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[i], PETSC_TRUE, &ncl, &cl));
  }
  PetscCall(PetscFree2(pts, vals));
  /* the facets, and their vertices (a mesh read without faces carries them on its cells) */
  PetscCall(MMMeshGetFacets(dm, name, &fl));
  sizes[1] = fl.n;
  for (PetscInt i = 0; i < fl.n; ++i) {
    PetscInt v[MM_MAX_DIM + 1];
    PetscCall(MMMeshCellVertices(dm, depth, dim, fl.cell[i], v));
    for (PetscInt a = 0; a <= dim; ++a)
      if (a != fl.off[i]) mark[v[a]] = 1;
  }
  PetscCall(MMFacetListDestroy(&fl));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscArraycpy(owned, mark, pEnd));
  PetscCall(PetscSFReduceBegin(sf, MPIU_INT, mark, owned, MPI_MAX));
  PetscCall(PetscSFReduceEnd(sf, MPIU_INT, mark, owned, MPI_MAX));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  for (PetscInt l = 0; l < PetscMax(nleaves, 0); ++l) owned[leaves ? leaves[l] : l] = 0;
  for (PetscInt v = vStart; v < vEnd; ++v) sizes[2] += owned[v];
  PetscCall(PetscFree2(mark, owned));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sizes, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/* The options that name a group, e.g. " (-contact_boundary, -dirichlet)"; empty if none of these. */
static PetscErrorCode GroupRoles(MMCtx *ctx, const char name[], char text[], size_t len)
{
  MMContactNodes cn;
  const MMOptions *opt = &ctx->opt;
  char             roles[512] = "";
  PetscBool        same;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  PetscCall(PetscStrcmp(name, opt->contact_name, &same));
  if (same && cn.enabled && opt->n_rigid > 0) PetscCall(PetscStrlcat(roles, ", -contact_boundary", sizeof(roles)));
  for (PetscInt b = 0; b < opt->loads.n_dirichlet; ++b) {
    PetscCall(PetscStrcmp(name, opt->loads.dirichlet[b].name, &same));
    if (same) PetscCall(PetscStrlcat(roles, ", -dirichlet", sizeof(roles)));
  }
  for (PetscInt b = 0; b < opt->loads.n_traction; ++b) {
    PetscCall(PetscStrcmp(name, opt->loads.traction[b].name, &same));
    if (same) PetscCall(PetscStrlcat(roles, ", -traction", sizeof(roles)));
  }
  for (PetscInt b = 0; b < opt->loads.n_pressure; ++b) {
    PetscCall(PetscStrcmp(name, opt->loads.pressure[b].name, &same));
    if (same) PetscCall(PetscStrlcat(roles, ", -pressure", sizeof(roles)));
  }
  for (PetscInt b = 0; b < opt->loads.n_point_force; ++b) {
    PetscCall(PetscStrcmp(name, opt->loads.point_force[b].name, &same));
    if (same) PetscCall(PetscStrlcat(roles, ", -point_force", sizeof(roles)));
  }
  for (PetscInt b = 0; b < opt->n_bodies; ++b) {
    PetscCall(PetscStrcmp(name, opt->bodies[b].group, &same));
    if (same) {
      PetscCall(PetscStrlcat(roles, ", body ", sizeof(roles)));
      PetscCall(PetscStrlcat(roles, opt->bodies[b].name, sizeof(roles)));
    }
  }
  for (PetscInt p = opt->n_rigid; cn.enabled && p < opt->n_obstacles; ++p) {
    const MMObstacle *ob = &opt->obstacles[p];
    PetscBool         slave, master;
    PetscCall(PetscStrcmp(name, ob->slave, &slave));
    PetscCall(PetscStrcmp(name, ob->master, &master));
    if (slave || master) {
      PetscCall(PetscStrlcat(roles, ", pair ", sizeof(roles)));
      PetscCall(PetscStrlcat(roles, ob->name, sizeof(roles)));
      PetscCall(PetscStrlcat(roles, slave ? " slave" : " master", sizeof(roles)));
    }
  }
  if (roles[0]) PetscCall(PetscSNPrintf(text, len, " (%s)", roles + 2));
  else text[0] = 0;
  PetscFunctionReturn(0);
}

/* One line per physical group: its elements (cells, facets or points) and nodes. Every rank holds
 * every label, in the same order (DMPlexDistribute), so the loop is collective. */
static PetscErrorCode ReportGroups(MMCtx *ctx)
{
  DM       dm = ctx->dm;
  PetscInt nl;

  PetscFunctionBeginUser;
  PetscCall(DMGetNumLabels(dm, &nl));
  for (PetscInt l = 0; l < nl; ++l) {
    const char *name;
    PetscInt    sizes[3];
    char        roles[600];

    PetscCall(DMGetLabelName(dm, l, &name));
    if (!MMMeshIsPhysicalGroup(name)) continue;
    PetscCall(GroupSizes(dm, name, sizes));
    PetscCall(GroupRoles(ctx, name, roles, sizeof(roles)));
    if (sizes[0]) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  group %s: %" PetscInt_FMT " cells, %" PetscInt_FMT " nodes%s\n", name, sizes[0], sizes[2], roles));
    else if (sizes[1]) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  group %s: %" PetscInt_FMT " facets, %" PetscInt_FMT " nodes%s\n", name, sizes[1], sizes[2], roles));
    else PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  group %s: %" PetscInt_FMT " points, %" PetscInt_FMT " nodes%s\n", name, sizes[2], sizes[2], roles));
  }
  PetscFunctionReturn(0);
}

/* How the run writes its snapshots and rows, for the output line. */
static PetscErrorCode CadenceText(const MMOutput *o, char snap[], char rows[], size_t len)
{
  PetscFunctionBeginUser;
  if (o->interval > 0) PetscCall(PetscSNPrintf(snap, len, "at t = k %g and the last", (double)o->interval));
  else if (o->every > 0) PetscCall(PetscSNPrintf(snap, len, "every %" PetscInt_FMT " steps and the last", o->every));
  else PetscCall(PetscStrncpy(snap, "the first and the last", len));
  if (o->history_every > 1) PetscCall(PetscSNPrintf(rows, len, " (every %" PetscInt_FMT " steps and the last)", o->history_every));
  else rows[0] = 0;
  PetscFunctionReturn(0);
}

/* The planned steps and output, as the run's large-output warning has them (MMOutputPlanMake). */
static PetscErrorCode ReportPlan(MMCtx *ctx, TS ts, PetscReal *step0)
{
  MMOutputPlan plan;
  char         snap[32], h5_text[32], csv_text[32], xmf_text[32], total[32], every[96], rows[96];
  PetscBool    restarted;

  PetscFunctionBeginUser;
  PetscCall(MMOutputPlanMake(&ctx->out, ts, &plan));
  *step0 = plan.step0;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  plan: %.0f steps of dt = %.6g from t = %.6g (step %.0f) to t = %.6g%s\n", (double)plan.steps, (double)plan.dt, (double)plan.t0, (double)plan.step0, (double)plan.t_last, plan.by_steps ? " (-ts_max_steps ends the run before -ts_max_time)" : ""));
  PetscCall(BytesText(plan.snapshot_bytes, snap, sizeof(snap)));
  PetscCall(BytesText(plan.h5_bytes, h5_text, sizeof(h5_text)));
  PetscCall(BytesText(plan.csv_bytes, csv_text, sizeof(csv_text)));
  PetscCall(BytesText(plan.xmf_bytes, xmf_text, sizeof(xmf_text)));
  /* at a checkpoint solution.h5 is copied beside it (checkpoint_snapshots.h5, src/io/output.c) */
  PetscCall(BytesText(2 * plan.h5_bytes + plan.csv_bytes + plan.xmf_bytes, total, sizeof(total)));
  PetscCall(CadenceText(&ctx->out, every, rows, sizeof(every)));
  PetscCall(MMCheckpointGetRestart(&ctx->ckpt, &restarted, NULL, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  output: %.0f snapshots (%s) of %s each: %s in solution.h5 with the mesh, %s in solution.xmf; %.0f history rows: at most %s in history.csv%s; at most %s in %s with the checkpoint's copy of solution.h5%s (-check_input writes nothing)\n", (double)plan.snapshots, every, snap, h5_text, xmf_text, (double)plan.rows, csv_text, rows, total, ctx->out.dir, restarted ? ", beyond what the restart continues from its checkpoint's directory" : ""));
  PetscFunctionReturn(0);
}

/* Each node's initial acceleration with the standard lumped mass, a = M_L^{-1} (L - K u - lift - C v),
 * taken in Cartesian components (where M_L is diagonal) and brought back to the w-frame. The
 * modified mass leaves the contact-normal dofs massless (docs/method.md section 2): the state's a0 is
 * 0 there, and the initial projection puts them in quasi-static equilibrium, K u + lift = L on them,
 * so either would hide gravity from the estimate. Their elastic force is left out instead: with M_L
 * each node gets the acceleration its share of the load gives it (g for a body at rest under
 * gravity). */
static PetscErrorCode AccelerationEstimate(MMCtx *ctx, Vec a)
{
  MMContactOperators ops;
  MMState           *state;
  MMDamping         *damping;
  MMContactNodes     cn;
  const MMState     *s;
  Vec                r, f, m;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetLumpedMass(ctx->op, &m));
  PetscCall(MMContactGetOperators(ctx->contact, &ops));
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMNewmarkGetDamping(ctx->nm, &damping));
  s = state;
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  PetscCall(VecDuplicate(s->u, &r));
  PetscCall(VecDuplicate(m, &f));
  PetscCall(MatMult(ops.K, s->u, r));
  PetscCall(VecAXPY(r, 1.0, ops.lift));
  if (ops.massless) PetscCall(VecISSet(r, cn.is_normal, 0.0));
  PetscCall(VecAYPX(r, -1.0, ops.load));
  PetscCall(MMDampingAddForce(damping, s->v, -1.0, r));
  PetscCall(MMFEForceToCartesian(ctx->op, r, f));
  PetscCall(VecPointwiseDivide(f, f, m));
  PetscCall(MMFEFromCartesian(ctx->op, f, a));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&r));
  PetscFunctionReturn(0);
}

/* A point in C's formatting, not PETSc's, which writes 0 as "0." */
static void PointText(PetscInt dim, const PetscReal x[], char text[], size_t len)
{
  if (dim == 2) snprintf(text, len, "(%g, %g)", (double)x[0], (double)x[1]);
  else snprintf(text, len, "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]);
}

/* One line per obstacle and pair: the contact nodes it gets (the nearest obstacle of each node at the
 * reference position, as the contact_obstacle field shows) and its smallest gap at the start. */
static PetscErrorCode ReportObstacles(MMCtx *ctx, TS ts)
{
  MMState         *state;
  MMContactNodes   cn;
  const MMOptions *opt = &ctx->opt;
  PetscInt        *count;
  PetscReal       *gap, *x, t0;
  PetscInt         dim;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetDimension(ctx->op, &dim));
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  if (!cn.enabled) PetscFunctionReturn(0);
  PetscCall(TSGetTime(ts, &t0));
  PetscCall(PetscMalloc3(opt->n_obstacles, &count, opt->n_obstacles, &gap, MM_MAX_DIM * opt->n_obstacles, &x));
  PetscCall(MMContactObstacleGaps(ctx->contact, state->u, t0, count, gap, x));
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) {
    const PetscBool pair = (PetscBool)(b >= opt->n_rigid);
    char            where[128];
    if (gap[b] >= PETSC_MAX_REAL) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  gap to %s %s: 0 contact nodes\n", pair ? "pair" : "obstacle", opt->obstacles[b].name));
      continue;
    }
    PointText(dim, &x[MM_MAX_DIM * b], where, sizeof(where));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  gap to %s %s: %" PetscInt_FMT " contact nodes, smallest %.6g at the node %s\n", pair ? "pair" : "obstacle", opt->obstacles[b].name, count[b], (double)gap[b], where));
  }
  PetscCall(PetscFree3(count, gap, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReportFirstContact(MMCtx *ctx, TS ts, PetscReal step0)
{
  MMState       *state;
  MMContactNodes cn;
  MMFirstContact fc;
  PetscReal      t0, t_end, dt;
  Vec            a;
  PetscInt       dim;
  char           where[128], touching[160] = "";

  PetscFunctionBeginUser;
  PetscCall(MMFEGetDimension(ctx->op, &dim));
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  if (!cn.enabled) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  first contact: none, -contact 0\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(TSGetTime(ts, &t0));
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(VecDuplicate(state->u, &a));
  PetscCall(AccelerationEstimate(ctx, a));
  PetscCall(MMContactFirstContact(ctx->contact, state->u, state->v, a, t0, t_end, &fc));
  PetscCall(VecDestroy(&a));
  if (fc.touching) PetscCall(PetscSNPrintf(touching, sizeof(touching), "%" PetscInt_FMT " contact row%s touch%s at the start; of the others, ", fc.touching, fc.touching > 1 ? "s" : "", fc.touching > 1 ? "" : "es"));
  if (fc.obstacle < 0) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  first contact: %snone before t = %.6g (each node at its initial velocity and acceleration)\n", touching, (double)t_end));
    PetscFunctionReturn(0);
  }
  PointText(dim, fc.x, where, sizeof(where));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  first contact: %st ~ %.4g (step %.0f), the node at %s against %s: gap %.4g, approach speed %.4g and acceleration %.4g (each node at its initial velocity and acceleration)\n", touching, (double)fc.t, (double)(step0 + PetscMax(1, PetscCeilReal((fc.t - t0) / dt - 1e-10))), where,
                         ctx->opt.obstacles[fc.obstacle].name, (double)fc.gap, (double)fc.speed, (double)fc.accel));
  PetscFunctionReturn(0);
}

/* The data check's report, after the start-up report: the case was built and every check passed. */
PetscErrorCode MMDataCheckReport(MMCtx *ctx, TS ts)
{
  PetscReal step0;

  PetscFunctionBeginUser;
  /* as the output does when it opens: a group the mesh lacks is refused, and the plan counts the
   * probes' history columns */
  PetscCall(MMOutputSetUpProbes(&ctx->out));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mmcontact data check (-check_input): the physical groups of %s\n", ctx->opt.mesh_file));
  PetscCall(ReportGroups(ctx));
  PetscCall(ReportObstacles(ctx, ts));
  PetscCall(ReportPlan(ctx, ts, &step0));
  PetscCall(ReportFirstContact(ctx, ts, step0));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mmcontact data check: the case is valid; no step was taken and nothing was written\n"));
  PetscFunctionReturn(0);
}

/* What the output would have freed: its probes, the only part of it a data check sets up. */
PetscErrorCode MMDataCheckDestroy(MMCtx *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(MMOutputDestroy(&ctx->out));
  PetscFunctionReturn(0);
}
