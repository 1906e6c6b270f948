/* The same text as README.md's "-help intro" block (tests/test_help_readme.py keeps them identical) */
static char help[] = "mmcontact: elastic bodies hitting and sliding on rigid obstacles and on each other, by the modified\n"
                     "mass method (Doyen & Ern, SIAM J. Numer. Anal. 2011): P1 elastodynamics on a gmsh mesh of\n"
                     "triangles (plane strain) or tetrahedra, one body or several of their own material (-bodies);\n"
                     "trapezoidal Newmark with optional Rayleigh damping (-damping_ratio); unilateral contact enforced\n"
                     "exactly at every contact node against planes, spheres/circles and cylinders, fixed or moving\n"
                     "(-obstacles), and between two bodies of the mesh (-contact_pairs); Coulomb friction (-mu) solved\n"
                     "to round-off by semismooth Newton (the default) or the threshold fixed point; gravity, tractions\n"
                     "and moving Dirichlet boundaries, each with an amplitude in time; an exact discrete energy balance\n"
                     "and the contact law audited every step; HDF5/XDMF fields with the stress and von Mises, a CSV\n"
                     "history, checkpoints and restart on any number of ranks. Run:\n"
                     "  mpiexec -n 2 ./mmcontact -options_file options/d1_friction.opts\n"
                     "README.md describes every option, the output and the exit status.\n\n";

#include "mesh.h"
#include "fem.h"
#include "contact.h"
#include "ts.h"
#include "friction.h"
#include "io.h"
#include "sys.h"
#include "appimpl.h"
#include <sys/resource.h>

/* A set-up phase under its own event (MMAppEvents), so that -log_view shows where the set-up goes */
#define MMPhase(event, call) \
  do { \
    PetscCall(PetscLogEventBegin((event), 0, 0, 0, 0)); \
    PetscCall(call); \
    PetscCall(PetscLogEventEnd((event), 0, 0, 0, 0)); \
  } while (0)

/* The mesh: read, the options that depend on its dimension checked, then rotated and distributed. */
static PetscErrorCode LoadMesh(MPI_Comm comm, MMCtx *ctx)
{
  MMDamping   *damping;
  MMMeshFacets facets;
  PetscInt     dim;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetDamping(ctx->nm, &damping));
  PetscCall(MMMeshRead(comm, ctx->opt.mesh_file, &ctx->dm, &facets, &ctx->ckpt.vertex_file));
  /* the vector options' lengths, the rotation's among them, need the dimension */
  PetscCall(DMGetDimension(ctx->dm, &dim));
  PetscCall(MMOptionsCheckDimension(comm, &ctx->opt, dim, MMDampingOn(damping))); /* Rayleigh damping refuses a moving boundary */
  PetscCall(MMMeshDistribute(ctx->opt.mesh_rotation, ctx->opt.mesh_rotation_center, &facets, &ctx->dm, &ctx->ckpt.vertex_orig));
  PetscFunctionReturn(0);
}

/* -restart: the checkpoint's state, and the obstacles and loads at its time (for the initial
 * diagnostics and the energy of the restored state). */
static PetscErrorCode Restart(MMCtx *ctx, TS ts)
{
  MMState  *state;
  PetscBool restarted;
  PetscReal t;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMCheckpointLoad(&ctx->ckpt, ts));
  PetscCall(MMCheckpointGetRestart(&ctx->ckpt, &restarted, NULL, &t));
  if (!restarted) PetscFunctionReturn(0);
  {
    const PetscScalar *rec;
    const PetscReal   *counters;
    Vec                at;
    PetscReal          t_at;
    /* frames that follow the contact point: the checkpoint's state is in its frames, restored first */
    PetscCall(MMCheckpointGetFrames(&ctx->ckpt, &rec, &counters));
    PetscCall(MMNewmarkRestoreFrames(ctx->nm, rec, counters));
    /* large sliding: the state is relative to the checkpoint's pairing, N, K and M* built for it */
    PetscCall(MMCheckpointGetPairs(&ctx->ckpt, &rec, &counters));
    PetscCall(MMNewmarkRestorePairs(ctx->nm, rec, ctx->ckpt.file));
    if (rec) PetscCall(MMContactPairsSetCounters(ctx->contact, counters));
    /* finite strain: the iteration matrix the next steps start from, in the restored variables */
    PetscCall(MMCheckpointGetTangent(&ctx->ckpt, &at, &t_at));
    PetscCall(MMNewmarkRestoreTangent(ctx->nm, at, t_at));
  }
  PetscCall(MMContactSetTime(ctx->contact, t, state->dt)); /* nothing without contact */
  PetscCall(MMLoadsSetTime(&ctx->loads, t, t));
  if (!ctx->opt.quiet) PetscCall(MMCheckpointView(&ctx->ckpt, PETSC_VIEWER_STDOUT_WORLD));
  PetscFunctionReturn(0);
}

/* Every component created and set from its options, before the mesh is read: an option error comes
 * first, as it always did. -help without a mesh stops here. */
static PetscErrorCode SetFromOptions(MPI_Comm comm, MMCtx *ctx, PetscBool *help_only)
{
  PetscFunctionBeginUser;
  PetscCall(MMOptionsProcess(comm, &ctx->opt));
  PetscCall(MMOptionsHelpWithoutMesh(comm, help_only));
  if (*help_only) PetscFunctionReturn(0);
  PetscCall(MMFECreate(comm, &ctx->op));
  PetscCall(MMFESetFromOptions(ctx->op));
  PetscCall(MMContactCreate(comm, &ctx->contact));
  PetscCall(MMContactSetFromOptions(ctx->contact));
  PetscCall(MMFrictionCreate(comm, &ctx->friction));
  PetscCall(MMFrictionSetFromOptions(ctx->friction));
  {
    PetscReal tol;
    PetscCall(MMFrictionGetCoulombTolerance(ctx->friction, &tol));
    PetscCall(MMContactSetCoulombTolerance(ctx->contact, tol));
  }
  PetscCall(MMNewmarkSetFromOptions(ctx->nm));
  PetscCall(MMOutputSetFromOptions(comm, &ctx->out));
  PetscCall(MMCheckpointSetFromOptions(comm, &ctx->ckpt));
  PetscCall(MMProgressSetFromOptions(comm, &ctx->progress));
  PetscFunctionReturn(0);
}

/* The mesh, fem's Cartesian operators and loads, the contact set and its frame (the w-frame K, M*). */
static PetscErrorCode SetUpOperators(MPI_Comm comm, MMCtx *ctx)
{
  MMDamping       *damping;
  MMFEProblem      pb;
  MMContactProblem cp;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetDamping(ctx->nm, &damping));
  MMPhase(MMAppEvents.mesh_load, LoadMesh(comm, ctx));
  PetscCall(MMFESetDM(ctx->op, ctx->dm));
  PetscCall(MMOptionsGetFEProblem(&ctx->opt, &pb));
  pb.damped = MMDampingOn(damping); /* a Dirichlet value's amplitude is refused with damping */
  MMPhase(MMAppEvents.fe_setup, MMFESetUp(ctx->op, &ctx->material, &pb));
  PetscCall(MMOptionsGetContactProblem(&ctx->opt, &cp));
  PetscCall(MMNewmarkGetPlan(ctx->nm, &cp.dt, &cp.steps));
  MMPhase(MMAppEvents.contact_setup, MMContactSetUp(ctx->contact, ctx->op, &ctx->material, &cp));
  /* the static sliding state's plane is the single obstacle's (src/ts/sliding.c reads it) */
  PetscCall(MMContactGetPlane(ctx->contact, ctx->opt.obstacle_point, ctx->opt.obstacle_normal));
  PetscCall(MMFEAssembleOperators(ctx->op, &ctx->material, &pb));
  PetscCall(MMContactSetUpFrame(ctx->contact, ctx->op, &ctx->material)); /* w-frame K, M*, loads */
  PetscCall(MMFEAssembleOperatorsEnd(ctx->op));
  {
    MMContactOperators ops; /* M*'s massless dofs: the reactions' inertia has none there */
    PetscCall(MMContactGetOperators(ctx->contact, &ops));
    MMPhase(MMAppEvents.loads_setup, MMLoadsSetUp(&ctx->loads, ctx->op, &ctx->material, &pb, ops.massless, ops.load, ops.lift));
  }
  PetscFunctionReturn(0);
}

/* The stepper and its initial state, friction, the TS, -restart, the step matrix for the first dt
 * (its coefficients from the stepper, K~ built by contact), the initial audits. */
static PetscErrorCode SetUpStepper(MMCtx *ctx, TS *ts)
{
  MMState   *state;
  MMHistory *hist;
  MMDamping *damping;
  PetscReal  dt;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMNewmarkGetHistory(ctx->nm, &hist));
  PetscCall(MMNewmarkGetDamping(ctx->nm, &damping));
  {
    MMNewmarkProblem tp;
    PetscCall(MMOptionsGetNewmarkProblem(&ctx->opt, &tp));
    PetscCall(MMNewmarkSetProblem(ctx->nm, &tp));
  }
  PetscCall(MMNewmarkSetUp(ctx->nm, ctx->op, &ctx->material, &ctx->loads, ctx->contact));
  MMPhase(MMAppEvents.initial_state, MMNewmarkInitialState(ctx->nm));
  MMPhase(MMAppEvents.friction_setup, MMFrictionSetUp(ctx->friction, ctx->contact, ctx->opt.mu_max, ctx->material.E_max, state->react));
  PetscCall(MMNewmarkSetFriction(ctx->nm, ctx->friction));
  PetscCall(MMNewmarkCreateTS(ctx->nm, ts));
  PetscCall(MMOptionsGetIOProblem(&ctx->opt, &ctx->iopb));
  PetscCall(MMCheckpointSetUp(&ctx->ckpt, &ctx->iopb, ctx->op, &ctx->material, hist, state, damping, ctx->contact, ctx->friction, &ctx->out));
  PetscCall(Restart(ctx, *ts));
  PetscCall(TSGetTimeStep(*ts, &dt));
  MMPhase(MMAppEvents.step_matrix, MMNewmarkSetStep(ctx->nm, dt)); /* after -restart, its iteration matrix */
  hist->dt = dt;
  {
    PetscBool restarted;
    PetscCall(MMCheckpointGetRestart(&ctx->ckpt, &restarted, NULL, NULL));
    MMPhase(MMAppEvents.energy_initial, MMEnergyInitial(ctx->nm, restarted));
  }
  MMPhase(MMAppEvents.deformation_check, MMDeformationCheck(ctx->nm));
  PetscCall(MMCheckpointRestoreHistory(&ctx->ckpt));
  PetscFunctionReturn(0);
}

/* The output and progress set up, the unread options refused, and the start-up report. */
static PetscErrorCode SetUpReport(MPI_Comm comm, MMCtx *ctx, TS ts)
{
  MMState   *state;
  MMHistory *hist;
  MMDamping *damping;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetState(ctx->nm, &state));
  PetscCall(MMNewmarkGetHistory(ctx->nm, &hist));
  PetscCall(MMNewmarkGetDamping(ctx->nm, &damping));
  PetscCall(MMOutputSetUp(&ctx->out, &ctx->iopb, ctx->op, &ctx->material, hist, state, ctx->contact, &ctx->loads, &ctx->ckpt));
  /* every object has read its options: refuse the unread ones before any output is touched, and
   * before the start-up report, which would otherwise announce a run that is then refused */
  PetscCall(MMOptionsCheckUnused(comm, &ctx->opt, ctx->dm));
  /* after: its replay of the help text reads every option */
  PetscCall(MMOptionsCheckValueless(comm));
  PetscCall(MMProgressSetUp(&ctx->progress, &ctx->iopb, ctx->op, &ctx->material, hist, state, ctx->contact, damping));
  if (!ctx->opt.quiet) {
    KSP krylov, pc_ksp;
    PetscCall(MMContactGetStepKSP(ctx->contact, &krylov, &pc_ksp));
    PetscCall(MMProgressHeader(&ctx->progress, ts, krylov, pc_ksp));
  }
  PetscFunctionReturn(0);
}

/* The viewer an option -NAME_view names (ascii, ascii:FILE, ...), its format pushed, as
 * PetscObjectViewFromOptions reads it for PETSc's objects; NULL when the option is not given. */
static PetscErrorCode ViewerFromOptions(const char option[], PetscViewer *viewer)
{
  PetscViewerFormat format;
  PetscBool         set;

  PetscFunctionBeginUser;
  *viewer = NULL;
  PetscCall(PetscOptionsGetViewer(PETSC_COMM_WORLD, NULL, NULL, option, viewer, &format, &set));
  if (set) PetscCall(PetscViewerPushFormat(*viewer, format));
  else *viewer = NULL;
  PetscFunctionReturn(0);
}

static PetscErrorCode ViewerEnd(PetscViewer *viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerFlush(*viewer));
  PetscCall(PetscViewerPopFormat(*viewer));
  PetscCall(PetscViewerDestroy(viewer));
  PetscFunctionReturn(0);
}

/* -contact_view, -friction_view, -obstacle_view, -ts_view: each object's configuration once the
 * run is set up, before the first step (docs/reference.md, "Viewing the set-up"). */
static PetscErrorCode ViewSetUp(MMCtx *ctx, TS ts)
{
  PetscViewer viewer;

  PetscFunctionBeginUser;
  PetscCall(ViewerFromOptions("-obstacle_view", &viewer));
  if (viewer) {
    for (PetscInt b = 0; b < ctx->opt.n_obstacles; ++b) PetscCall(MMObstacleView(&ctx->opt.obstacles[b], viewer));
    PetscCall(ViewerEnd(&viewer));
  }
  PetscCall(ViewerFromOptions("-contact_view", &viewer));
  if (viewer) {
    PetscCall(MMContactSetUpView(ctx->contact, viewer));
    PetscCall(ViewerEnd(&viewer));
  }
  PetscCall(ViewerFromOptions("-friction_view", &viewer));
  if (viewer) {
    PetscCall(MMFrictionView(ctx->friction, viewer));
    PetscCall(ViewerEnd(&viewer));
  }
  PetscCall(TSViewFromOptions(ts, NULL, "-ts_view")); /* TSSolve views it again when it ends, as PETSc does */
  PetscFunctionReturn(0);
}

/* The output files opened (the earlier results set aside only once the input is valid) and the
 * per-step monitors. */
static PetscErrorCode SetUpOutput(MMCtx *ctx, TS ts)
{
  PetscFunctionBeginUser;
  MMPhase(MMAppEvents.output_open, MMOutputOpen(&ctx->out));
  PetscCall(TSMonitorSet(ts, MMOutputMonitor, &ctx->out, NULL));
  PetscCall(TSMonitorSet(ts, MMCheckpointMonitor, &ctx->ckpt, NULL));
  if (!ctx->opt.quiet) PetscCall(MMProgressMonitorSet(&ctx->progress, ts));
  PetscCall(MMSignalsSetUp(ts));
  PetscFunctionReturn(0);
}

/* The run's set-up, in the order of docs/developer.md ("Components"). */
static PetscErrorCode SetupProblem(MMCtx *ctx, TS *ts, PetscBool *help_only)
{
  MPI_Comm comm = PETSC_COMM_WORLD;

  PetscFunctionBeginUser;
  PetscCall(SetFromOptions(comm, ctx, help_only));
  if (*help_only) PetscFunctionReturn(0);
  /* before anything in the output directory is read or moved: one run per directory. A data check
   * writes nothing, and takes no lock */
  if (!ctx->opt.check_input) PetscCall(MMOutputLock(ctx->out.dir));
  PetscCall(SetUpOperators(comm, ctx));
  PetscCall(SetUpStepper(ctx, ts));
  PetscCall(SetUpReport(comm, ctx, *ts));
  PetscCall(ViewSetUp(ctx, *ts));
  /* -check_input: the case is built and valid; its report, and a stop before any output is touched */
  if (ctx->opt.check_input) {
    PetscCall(MMDataCheckReport(ctx, *ts));
    PetscFunctionReturn(0);
  }
  PetscCall(SetUpOutput(ctx, *ts));
  PetscFunctionReturn(0);
}

/* The run's own line of the report: its set-up and time loop, memory, and the audits' extremes. */
static PetscErrorCode RunView(MMCtx *ctx, PetscLogDouble setup, PetscLogDouble wall, PetscViewer viewer)
{
  MMHistory       *h;
  PetscInt         steps, step0;
  struct rusage    ru;
  PetscReal        peak, total;
  MMContactNodes   cn;

  PetscFunctionBeginUser;
  PetscCall(MMNewmarkGetHistory(ctx->nm, &h));
  PetscCall(MMContactGetNodes(ctx->contact, &cn));
  PetscCall(MMCheckpointGetRestart(&ctx->ckpt, NULL, &step0, NULL));
  steps = h->step - step0; /* this run's */
  getrusage(RUSAGE_SELF, &ru);
  peak = ru.ru_maxrss / 1024.0; /* kB on Linux */
  PetscCall(MPIU_Allreduce(&peak, &total, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &peak, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(PetscViewerASCIIPrintf(viewer, "mmcontact summary: setup %.3f s; %" PetscInt_FMT " steps to t = %g in %.3f s wall (%.4f s/step); peak memory %.1f MiB/rank (%.1f MiB over all ranks); largest balance residual %.3e%s", (double)setup, steps, (double)h->time, (double)wall, steps ? (double)(wall / steps) : 0.0, (double)peak, (double)total, (double)h->max_balance, cn.enabled ? "; " : "\n"));
  /* without contact (-contact 0) there is no penetration to report */
  if (cn.enabled) PetscCall(PetscViewerASCIIPrintf(viewer, "largest penetration %.3e (h_c' %.3e)\n", (double)h->max_penetration_run, (double)cn.h_c));
  PetscFunctionReturn(0);
}

/* The run report: each component's view, in the order of the set-up. */
static PetscErrorCode Report(MMCtx *ctx, PetscLogDouble setup, PetscLogDouble wall)
{
  PetscViewer viewer = PETSC_VIEWER_STDOUT_WORLD;

  PetscFunctionBeginUser;
  if (ctx->opt.quiet) PetscFunctionReturn(0);
  PetscCall(RunView(ctx, setup, wall, viewer));
  PetscCall(MMContactMassView(ctx->contact, viewer));
  PetscCall(MMContactView(ctx->contact, viewer));
  PetscCall(MMDeformationView(ctx->nm, viewer));
  PetscCall(MMNonlinearView(ctx->nm, viewer));
  PetscCall(MMCertificateView(ctx->nm, viewer));
  PetscCall(MMOutputView(&ctx->out, viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy(MMCtx *ctx, TS *ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSDestroy(ts));
  PetscCall(MMNewmarkDestroy(&ctx->nm));
  PetscCall(MMFrictionDestroy(&ctx->friction));
  PetscCall(MMContactDestroy(&ctx->contact));
  PetscCall(MMLoadsDestroy(&ctx->loads));
  PetscCall(MMFEDestroy(&ctx->op));
  PetscCall(MMMaterialDestroy(&ctx->material));
  PetscCall(DMDestroy(&ctx->dm));
  PetscCall(MMOptionsDestroy(&ctx->opt));
  PetscCall(MMCheckpointDestroy(&ctx->ckpt));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MMCtx          ctx;
  MMState       *state;
  MMHistory     *hist;
  TS             ts;
  PetscLogDouble ts0, t0, t1;
  PetscBool      help_only;
  int            stopped;

  PetscFunctionBeginUser;
  {
    const int status = MMOptionsCheckFiles(argc, argv);
    if (status) return status;
  }
  PetscCall(MMSignalsDieWithLauncher());
  PetscCall(MMMPIEnvironmentSet());
  PetscCall(MMThreadsSetDefault());
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(MMErrorsSetUp());
  PetscCall(PetscMemzero(&ctx, sizeof(ctx)));
  PetscCall(MMAppInitializePackage());
  PetscCall(MMIOInitializePackage());
  PetscCall(MMTSInitializePackage());
  PetscCall(MMNewmarkCreate(PETSC_COMM_WORLD, &ctx.nm));
  PetscCall(MMNewmarkGetState(ctx.nm, &state));
  PetscCall(MMNewmarkGetHistory(ctx.nm, &hist));

  PetscCall(PetscTime(&ts0));
  PetscCall(PetscLogStagePush(MMAppEvents.setup));
  PetscCall(SetupProblem(&ctx, &ts, &help_only));
  PetscCall(PetscLogStagePop());
  if (help_only) {
    PetscCall(MMNewmarkDestroy(&ctx.nm));
    PetscCall(MMOptionsDestroy(&ctx.opt));
    PetscCall(PetscFinalize());
    return 0;
  }
  if (ctx.opt.check_input) {
    PetscCall(MMDataCheckDestroy(&ctx));
    PetscCall(Destroy(&ctx, &ts));
    PetscCall(PetscFinalize());
    return 0;
  }

  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogStagePush(MMAppEvents.solve));
  PetscCall(TSSolve(ts, state->u_next));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscTime(&t1));
  PetscCall(MMCheckpointWriteFinal(&ctx.ckpt, ts));

  PetscCall(MMOutputWriteFinal(&ctx.out));
  PetscCall(MMOutputClose(&ctx.out, &ctx.ckpt, hist->step));
  PetscCall(Report(&ctx, t0 - ts0, t1 - t0));
  PetscCall(MMOutputDestroy(&ctx.out));
  PetscCall(MMSignalsReport(PETSC_COMM_WORLD, hist->step, hist->time, ctx.out.dir));
  PetscCall(MMOutputUnlock());
  PetscCall(MMSignalsGetStop(&stopped));
  PetscCall(Destroy(&ctx, &ts));
  PetscCall(PetscFinalize());
  return stopped ? MM_EXIT_RESTARTABLE : 0;
}
