/* What the user sees while the program runs: the start-up header (the case, the mesh, the material,
 * the time step and the solvers, read from the objects that were built) and a progress line every
 * -progress_every seconds of wall time, not every step, so that a long run's log stays short.
 * Both go to rank 0 through PetscPrintf; -quiet turns both off. */
#include <stdlib.h>
#include <petsc/private/pcimpl.h> /* pc->setupcalled */
#include "io.h"
#include "sys.h"
#include "contact.h"
#include "mesh.h"
#include "fem.h"

/* Rayleigh damping is on. */
static PetscBool DampingOn(const MMProgress *pg)
{
  return (PetscBool)(pg->damping->alpha != 0 || pg->damping->beta != 0);
}

/*@
  MMProgressSetUp - Gives the progress object what the start-up report and the progress lines
  describe, borrowed

  Logically collective

  Input Parameters:
+ p        - the progress object
. opt      - the problem as io needs it (MMOptionsGetIOProblem())
. op       - fem's operators
. material - the bodies' material
. hist     - the stepper's history row
. state    - the stepper's state
. contact  - the contact object
- damping  - the stepper's damping

  Level: intermediate

.seealso: `MMProgressSetFromOptions()`, `MMProgressHeader()`, `MMProgressMonitorSet()`
@*/
PetscErrorCode MMProgressSetUp(MMProgress *pg, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, const MMHistory *hist, const MMState *state, MMContact contact, const MMDamping *damping)
{
  PetscFunctionBeginUser;
  pg->opt       = opt;
  pg->op        = op;
  pg->material  = material;
  pg->hist      = hist;
  pg->state     = state;
  pg->contact   = contact;
  pg->damping   = damping;
  PetscFunctionReturn(0);
}

/* The options files of the run, as given on the command line. PETSc reads -options_file while it
 * starts and keeps only the options inside, not the option itself, so the arguments are read
 * again here. "command line" when there is none. */
static PetscErrorCode CaseName(char name[], size_t len)
{
  int    argc;
  char **args;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(name, "", len));
  PetscCall(PetscGetArgs(&argc, &args));
  for (int i = 1; i + 1 < argc; ++i) {
    PetscBool file, yaml;

    PetscCall(PetscStrcmp(args[i], "-options_file", &file));
    PetscCall(PetscStrcmp(args[i], "-options_file_yaml", &yaml));
    if (!file && !yaml) continue;
    if (name[0]) PetscCall(PetscStrlcat(name, ", ", len));
    PetscCall(PetscStrlcat(name, args[++i], len));
  }
  if (!name[0]) PetscCall(PetscStrncpy(name, "command line", len));
  PetscFunctionReturn(0);
}

/* The obstacles by name and shape, e.g. "2 obstacles: floor (plane), bowl (sphere)". */
static PetscErrorCode ObstacleList(const MMIOProblem *opt, char list[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(list, len, "%" PetscInt_FMT " obstacle%s:", opt->n_obstacles, opt->n_obstacles == 1 ? "" : "s"));
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) {
    char one[128];

    PetscCall(PetscSNPrintf(one, sizeof(one), "%s %s (%s)", b ? "," : "", opt->obstacles[b].name, opt->obstacles[b].type));
    PetscCall(PetscStrlcat(list, one, len));
  }
  PetscFunctionReturn(0);
}

/* "frictionless", or the Coulomb coefficient, or its range when the obstacles have their own. */
static PetscErrorCode FrictionText(const MMIOProblem *opt, char text[], size_t len)
{
  PetscReal lo = opt->mu_max;

  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < opt->n_obstacles; ++b) lo = PetscMin(lo, opt->obstacles[b].mu);
  if (opt->mu_max == 0) PetscCall(PetscStrncpy(text, "frictionless", len));
  else if (lo == opt->mu_max) PetscCall(PetscSNPrintf(text, len, "Coulomb friction, mu = %.6g", (double)lo));
  else PetscCall(PetscSNPrintf(text, len, "Coulomb friction, mu = %.6g to %.6g by obstacle", (double)lo, (double)opt->mu_max));
  PetscFunctionReturn(0);
}

/* The ordering MUMPS used for a factor it computed (INFOG(7)), e.g. ", SCOTCH ordering": the
 * ordering packages of the MUMPS library loaded at run time decide the fill (docs/scaling.md,
 * "Libraries: BLAS, threads and the MUMPS ordering"), so the header says which one ran. Empty for another package or
 * before the analysis. */
static PetscErrorCode MumpsFactorOrderingText(Mat F, MatSolverType package, char text[], size_t len)
{
  const char *names[] = {"AMD", "user", "AMF", "SCOTCH", "PORD", "METIS", "QAMD"};
  PetscBool   mumps;
  PetscInt    ord;

  PetscFunctionBeginUser;
  text[0] = 0;
  if (!F || !package) PetscFunctionReturn(0);
  PetscCall(PetscStrcmp(package, MATSOLVERMUMPS, &mumps));
  if (!mumps) PetscFunctionReturn(0);
  PetscCall(MatMumpsGetInfog(F, 7, &ord)); /* set by the analysis */
  if (ord >= 0 && ord < (PetscInt)(sizeof(names) / sizeof(names[0]))) PetscCall(PetscSNPrintf(text, len, ", %s ordering", names[ord]));
  PetscFunctionReturn(0);
}

/* The same for a factor PC's matrix, once factored. */
static PetscErrorCode MumpsOrderingText(PC pc, MatSolverType package, char text[], size_t len)
{
  PetscBool done;
  Mat       F;

  PetscFunctionBeginUser;
  text[0] = 0;
  if (!pc->setupcalled) PetscFunctionReturn(0); /* PCFactorGetMatrix() refuses a PC not yet set up */
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(MatAssembled(F, &done)); /* numerically factored: the analysis has run */
  if (!done) PetscFunctionReturn(0);
  PetscCall(MumpsFactorOrderingText(F, package, text, len));
  PetscFunctionReturn(0);
}

/* The K~ solver as the objects have it after set-up, e.g. "preonly + cholesky (mumps, SCOTCH
 * ordering), prefix contact_K_": the Krylov method, the PC and, for a factorization, the package
 * that computes it. */
static PetscErrorCode SolverText(KSP krylov, KSP pc_ksp, char text[], size_t len)
{
  PC            pc;
  KSPType       ktype;
  PCType        ptype;
  MatSolverType package = NULL;
  const char   *kprefix, *pprefix;
  PetscBool     factor, same, redundant, split, vifactor;
  char          pctext[200], ordering[32] = "";
  PetscMPIInt   size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)krylov), &size));
  PetscCall(KSPGetType(krylov, &ktype));
  PetscCall(KSPGetOptionsPrefix(krylov, &kprefix));
  PetscCall(KSPGetOptionsPrefix(pc_ksp, &pprefix));
  /* a redundant PC (2D on several ranks): the factorization it holds on every rank */
  PetscCall(MMKSPGetFactorPC(pc_ksp, &pc, &redundant));
  PetscCall(PCGetType(pc, &ptype));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, PCILU, PCICC, ""));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCVIFACTOR, &vifactor));
  if (factor) PetscCall(PCFactorGetMatSolverType(pc, &package));
  if (factor && package) PetscCall(MumpsOrderingText(pc, package, ordering, sizeof(ordering)));
  if (vifactor) {
    Mat F;
    PetscCall(MMPCVIFactorGetFactor(pc, &F, &package));
    PetscCall(MumpsFactorOrderingText(F, package, ordering, sizeof(ordering)));
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCSCHURSPLIT, &split));
  PetscCall(PetscSNPrintf(pctext, sizeof(pctext), "%s%s%s%s%s%s%s%s", vifactor ? "cholesky" : ptype, package ? " (" : "", package ? package : "", ordering, package ? ")" : "", redundant ? " of the whole K~ on every rank (redundant)" : "",
                          vifactor ? " of the whole K~, the VI's active rows the identity's (vifactor)" : "",
                          split ? (size > 1 ? " (each rank's interior by PETSc's Cholesky, the ranks' interface by its dense Schur complement)" : " (PETSc's Cholesky; one rank, no interface)") : ""));
  PetscCall(PetscStrcmp(kprefix, pprefix, &same));
  PetscCall(PetscSNPrintf(text, len, "%s + %s, prefix%s %s%s%s", ktype, pctext, same ? "" : "es", kprefix, same ? "" : " and ", same ? "" : pprefix));
  PetscFunctionReturn(0);
}

/* Line 1, the case and the mesh: cells, vertices, dofs (the free ones, the unknowns of the steps)
 * and ranks. */
static PetscErrorCode HeaderMesh(MMProgress *pg)
{
  MPI_Comm    comm = PETSC_COMM_WORLD;
  char        name[PETSC_MAX_PATH_LEN], fixed[64] = "";
  PetscInt    ncells, nvertices, ndofs, dim;
  PetscMPIInt size;
  DM          dm;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetDM(pg->op, &dm));
  PetscCall(MMFEGetDimension(pg->op, &dim));
  PetscCall(CaseName(name, sizeof(name)));
  PetscCall(MMMeshGetSizes(dm, &ncells, &nvertices));
  PetscCall(VecGetSize(pg->state->u, &ndofs));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (ndofs < dim * nvertices) PetscCall(PetscSNPrintf(fixed, sizeof(fixed), " (and %" PetscInt_FMT " fixed by -dirichlet)", dim * nvertices - ndofs));
  PetscCall(PetscPrintf(comm, "mmcontact: case %s; mesh %s, %" PetscInt_FMT "D: %" PetscInt_FMT " cells, %" PetscInt_FMT " vertices, %" PetscInt_FMT " dofs%s; %d rank%s\n", name, pg->opt->mesh_file, dim, ncells, nvertices, ndofs, fixed, size, size == 1 ? "" : "s"));
  PetscFunctionReturn(0);
}

/* The material line's mention of a finite-strain law (nothing for the linear model's) */
static const char *LawText(MMElasticityType law)
{
  static const char *const text[] = {"", "; St. Venant-Kirchhoff (-elasticity svk, finite strain)", "; neo-Hookean (-elasticity neohookean, finite strain)"};
  return text[law];
}

/* -bodies: one line per body, its cells, material, wave speeds and mass; the CFL number takes the
 * largest c_p (docs/method.md section 2, "Bodies"). */
static PetscErrorCode HeaderBodies(MMProgress *pg)
{
  const MMMaterial *mat = pg->material;

  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  material: %" PetscInt_FMT " bod%s (-bodies); the largest wave speed, c_p = %.4g, sets c_p dt / h_c'\n", mat->n_bodies, mat->n_bodies > 1 ? "ies" : "y", (double)mat->c_p_max));
  for (PetscInt b = 0; b < mat->n_bodies; ++b) {
    const MMBody *body = &mat->body[b];
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    body %s (group %s): %" PetscInt_FMT " cells; E = %.6g, nu = %.6g, rho = %.6g; waves c_p = %.4g, c_s = %.4g; mass %.10g%s\n", body->name, body->group, body->ncells, (double)body->E, (double)body->nu, (double)body->rho, (double)body->c_p, (double)body->c_s, (double)body->mass, LawText(body->elasticity)));
  }
  PetscFunctionReturn(0);
}

/* Lines 2 and 3, the material and the time step: the wave speeds and the contact CFL number of
 * Theorem 4.2, c_p dt / h_c'; and the Rayleigh damping when there is one. */
static PetscErrorCode HeaderPhysics(MMProgress *pg, TS ts)
{
  MPI_Comm        comm = PETSC_COMM_WORLD;
  const MMIOProblem *opt = pg->opt;
  const PetscReal c_s  = PetscSqrtReal(pg->material->body[0].mu / opt->rho); /* fem's PetscDS constant MM_C_MU */
  PetscReal       dt, t_end, h_c;
  PetscInt        max_steps;
  char            steps[64] = "", cfl[128];
  MMContactNodes  cn;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(pg->contact, &cn));
  h_c = cn.h_c;
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetMaxSteps(ts, &max_steps));
  if (max_steps < PETSC_MAX_INT) PetscCall(PetscSNPrintf(steps, sizeof(steps), " or %" PetscInt_FMT " steps", max_steps));
  if (h_c > 0) PetscCall(PetscSNPrintf(cfl, sizeof(cfl), "h_c' = %.4g, c_p dt / h_c' = %.3g", (double)h_c, (double)(pg->material->c_p_max * dt / h_c)));
  else if (cn.h_min > 0) PetscCall(PetscSNPrintf(cfl, sizeof(cfl), "no contact boundary; smallest cell h = %.4g, c_p dt / h = %.3g", (double)cn.h_min, (double)(pg->material->c_p_max * dt / cn.h_min)));
  else PetscCall(PetscStrncpy(cfl, "no contact boundary", sizeof(cfl)));
  if (!pg->material->named) PetscCall(PetscPrintf(comm, "  material: E = %.6g, nu = %.6g, rho = %.6g; waves c_p = %.4g, c_s = %.4g%s\n", (double)opt->E, (double)opt->nu, (double)opt->rho, (double)pg->material->c_p_max, (double)c_s, LawText(pg->material->body[0].elasticity)));
  else PetscCall(HeaderBodies(pg));
  PetscCall(PetscPrintf(comm, "  time: dt = %.6g to t = %.6g%s; %s\n", (double)dt, (double)t_end, steps, cfl));
  if (DampingOn(pg)) {
    char ratio[128] = "";
    if (pg->damping->ratio_set) PetscCall(PetscSNPrintf(ratio, sizeof(ratio), " (-damping_ratio %.6g at %.6g and %.6g Hz)", (double)pg->damping->ratio, (double)pg->damping->freq[0], (double)pg->damping->freq[1]));
    /* B is K unless the massless dofs were condensed out of it (docs/method.md section 3) */
    MMContactOperators ops;
    PetscCall(MMContactGetOperators(pg->contact, &ops));
    const char *B = (pg->damping->B && pg->damping->B != ops.K) ? "B (K without the massless contact-normal dofs)" : "K";
    PetscCall(PetscPrintf(comm, "  damping: Rayleigh C = alpha M* + beta %s, alpha = %.10g 1/s, beta = %.10g s%s\n", B, (double)pg->damping->alpha, (double)pg->damping->beta, ratio));
  }
  PetscFunctionReturn(0);
}

/* Lines 4 and 5, contact and solvers: the contact nodes and obstacles, the mass, friction, the
 * contact formulation and the K~ solver. */
static PetscErrorCode HeaderContact(MMProgress *pg, KSP krylov, KSP pc_ksp)
{
  MPI_Comm         comm = PETSC_COMM_WORLD;
  const MMIOProblem *opt  = pg->opt;
  char             obstacles[512], friction[128], solver[256], progress[64] = "no progress lines";
  const char      *type, *choice, *products;
  MMContactNodes   cn;
  MMMassType       mass_type;
  PetscBool        lumped;

  PetscFunctionBeginUser;
  PetscCall(MMFEIsMassLumped(pg->op, &lumped));
  PetscCall(ObstacleList(opt, obstacles, sizeof(obstacles)));
  PetscCall(FrictionText(opt, friction, sizeof(friction)));
  PetscCall(SolverText(krylov, pc_ksp, solver, sizeof(solver)));
  PetscCall(MMContactGetNodes(pg->contact, &cn));
  /* the active-set CG's products (src/contact/impls/active_set/block_operator.c) */
  PetscCall(MMContactGetSolverText(pg->contact, &type, &choice, &products));
  PetscCall(MMContactGetMassType(pg->contact, &mass_type));
  if (pg->every > 0) PetscCall(PetscSNPrintf(progress, sizeof(progress), "progress every %.6g s", (double)pg->every));
  if (cn.enabled && cn.n_corners) PetscCall(PetscPrintf(comm, "  contact: %" PetscInt_FMT " contact nodes (%" PetscInt_FMT " of them against two obstacles: %" PetscInt_FMT " rows) against %s; %s %s mass; %s\n", cn.n_global - cn.n_corners, cn.n_corners, cn.n_global, obstacles, lumped ? "lumped" : "consistent", MMMassTypes[mass_type], friction));
  else if (cn.enabled && cn.n_fc) PetscCall(PetscPrintf(comm, "  contact: %" PetscInt_FMT " contact nodes (%" PetscInt_FMT " of them against two obstacles, each with its own Coulomb law) against %s; %s %s mass; %s\n", cn.n_global, cn.n_fc, obstacles, lumped ? "lumped" : "consistent", MMMassTypes[mass_type], friction));
  else if (cn.enabled) PetscCall(PetscPrintf(comm, "  contact: %" PetscInt_FMT " contact nodes against %s; %s %s mass; %s\n", cn.n_global, obstacles, lumped ? "lumped" : "consistent", MMMassTypes[mass_type], friction));
  for (PetscInt p = 0; cn.enabled && p < opt->n_obstacles - opt->n_rigid; ++p) {
    const MMObstacle *ob = &opt->obstacles[opt->n_rigid + p];
    PetscInt          nodes, n2n, facets;
    PetscCall(MMContactGetPairCounts(pg->contact, p, &nodes, &n2n, &facets));
    PetscCall(PetscPrintf(comm, "  pair %s: slave %s, %" PetscInt_FMT " nodes (%" PetscInt_FMT " facing a master node: node to node), on %" PetscInt_FMT " facets of master %s; mu = %g; %s sliding\n", ob->name, ob->slave, nodes, n2n, facets, ob->master, (double)ob->mu, cn.pairs_sliding ? "large" : "small"));
  }
  if (!cn.enabled) PetscCall(PetscPrintf(comm, "  contact: off (-contact 0), 0 contact nodes: linear elastodynamics; %s mass\n", lumped ? "lumped" : "consistent"));
  PetscCall(PetscPrintf(comm, "  solvers: contact formulation %s%s; K~ by %s%s; %s\n", type, choice, solver, products, progress));
  PetscCall(MMContactMassView(pg->contact, PETSC_VIEWER_STDOUT_(comm))); /* line 6: the mass */
  PetscFunctionReturn(0);
}

/*@
  MMProgressHeader - Prints the start-up report, once everything is set up and before the first step

  Collective

  Input Parameters:
+ p      - the progress object, set up
. ts     - the time stepper
. krylov - the K~ solver (MMContactGetStepKSP())
- pc_ksp - the KSP whose PC factors or preconditions K~

  Level: intermediate

.seealso: `MMProgressSetUp()`, `MMContactSetUpView()`
@*/
PetscErrorCode MMProgressHeader(MMProgress *pg, TS ts, KSP krylov, KSP pc_ksp)
{
  PetscFunctionBeginUser;
  PetscCall(HeaderMesh(pg));
  PetscCall(HeaderPhysics(pg, ts));
  PetscCall(HeaderContact(pg, krylov, pc_ksp));
  PetscFunctionReturn(0);
}

/* A wall-clock duration, short: "12.3 s", "4m05s", "2h07m"; "?" when unknown. */
static PetscErrorCode Duration(PetscReal s, char text[], size_t len)
{
  PetscFunctionBeginUser;
  if (s < 0 || s >= PETSC_MAX_REAL) PetscCall(PetscStrncpy(text, "?", len));
  else if (s < 60) PetscCall(PetscSNPrintf(text, len, "%.1f s", (double)s));
  else if (s < 3600) PetscCall(PetscSNPrintf(text, len, "%dm%02ds", (int)(s / 60), (int)s % 60));
  else if (s < 3600 * 1e6) PetscCall(PetscSNPrintf(text, len, "%lldh%02dm", (long long)(s / 3600), (int)((long long)(s / 60) % 60)));
  else PetscCall(PetscSNPrintf(text, len, "%.3g h", (double)(s / 3600))); /* beyond a million hours an int would wrap */
  PetscFunctionReturn(0);
}

/* How far the run is, in [0, 1], and the wall time left: the elapsed wall time times what is left
 * over what this run has done, by simulated time and, if -ts_max_steps is set, by steps; the limit
 * that ends the run first is the one that counts. */
static void Estimate(const MMProgress *p, PetscReal t_end, PetscInt max_steps, PetscReal wall, PetscInt step, PetscReal t, PetscReal *done, PetscReal *eta)
{
  *done = t / t_end;
  *eta  = t > p->t_start ? wall * PetscMax(t_end - t, 0) / (t - p->t_start) : PETSC_MAX_REAL;
  if (max_steps < PETSC_MAX_INT && max_steps > 0) {
    *done = PetscMax(*done, (PetscReal)step / max_steps);
    if (step > p->step_start) *eta = PetscMin(*eta, wall * (PetscReal)(max_steps - step) / (step - p->step_start));
  }
  *done = PetscMin(*done, 1);
}

/* The line itself, e.g.
 *   t = 0.12 of 0.3 (40.0%), step 60 | wall 1.0 s, ETA 1.5 s | energy 1.2e+00, balance 3.1e-15 | active 5, slipping 2, friction its 4.5
 * The percentage is of the whole run: with -ts_max_steps it follows the step count ("step 60 of
 * 100 (60.0%)") if that ends the run first. The friction iterations are the mean over the steps
 * since the previous line. */
static PetscErrorCode PrintLine(MMProgress *pg, TS ts, PetscReal wall)
{
  const MMHistory  *h = pg->hist;
  const MMProgress *p = pg;
  PetscReal         t_end, done, eta;
  PetscInt          max_steps;
  char              where[128], wall_text[32], eta_text[32], friction[64] = "", contact[160] = "";
  MMContactNodes    cn;

  PetscFunctionBeginUser;
  PetscCall(TSGetMaxTime(ts, &t_end));
  PetscCall(TSGetMaxSteps(ts, &max_steps));
  Estimate(p, t_end, max_steps, wall, h->step, h->time, &done, &eta);
  if (max_steps < PETSC_MAX_INT) PetscCall(PetscSNPrintf(where, sizeof(where), "t = %.6g of %.6g, step %" PetscInt_FMT " of %" PetscInt_FMT " (%.1f%%)", (double)h->time, (double)t_end, h->step, max_steps, (double)(100 * done)));
  else PetscCall(PetscSNPrintf(where, sizeof(where), "t = %.6g of %.6g (%.1f%%), step %" PetscInt_FMT, (double)h->time, (double)t_end, (double)(100 * done), h->step));
  PetscCall(Duration(wall, wall_text, sizeof(wall_text)));
  PetscCall(Duration(eta, eta_text, sizeof(eta_text)));
  PetscCall(MMContactGetNodes(pg->contact, &cn));
  if (pg->opt->mu_max > 0) PetscCall(PetscSNPrintf(friction, sizeof(friction), ", friction its %.1f", p->steps ? (double)p->friction_its / p->steps : 0.0));
  /* without contact (-contact 0) there is no contact set to report */
  if (cn.enabled) PetscCall(PetscSNPrintf(contact, sizeof(contact), " | active %" PetscInt_FMT ", slipping %" PetscInt_FMT "%s", h->active, h->slipping, friction));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s | wall %s, ETA %s | energy %.10e, balance %.2e%s\n", where, wall_text, eta_text, (double)h->total, (double)h->balance_residual, contact));
  PetscFunctionReturn(0);
}

/* The wall clock of the progress lines. MMCONTACT_TEST_CLOCK=S (an environment variable, for the
 * tests and never for a real run) replaces it by a clock that advances S seconds per step, so that
 * which steps print a line, and the ETA they print, do not depend on the speed of the machine. */
static PetscErrorCode ProgressClock(PetscInt step, PetscLogDouble *now)
{
  static int       read = 0;
  static PetscReal per_step = 0;

  PetscFunctionBeginUser;
  if (!read) {
    const char *env = getenv("MMCONTACT_TEST_CLOCK");
    read            = 1;
    if (env) per_step = atof(env);
  }
  if (per_step > 0) *now = (PetscLogDouble)(per_step * step);
  else PetscCall(PetscTime(now));
  PetscFunctionReturn(0);
}

/*@
  MMProgressMonitor - TS monitor that counts the steps and prints a progress line every
  -progress_every seconds of wall time

  Not collective

  Input Parameters:
+ ts   - the time stepper
. step - the step just taken
. time - its time
. u    - the solution vector (unused)
- ctx  - the progress object (MMProgress *)

  Note:
  TS monitor: counts the step, and prints a line when -progress_every seconds of wall time have
  passed since the last one. Nothing is communicated: only rank 0 prints, and every rank holds the
  same history row (the monitor runs after MMEnergyStep has filled it).

  Level: intermediate

.seealso: `MMProgressMonitorSet()`
@*/
PetscErrorCode MMProgressMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ptr)
{
  MMProgress    *p   = (MMProgress *)ptr;
  PetscLogDouble now;

  PetscFunctionBeginUser;
  PetscCall(ProgressClock(step, &now));
  if (!p->started) {
    p->started    = PETSC_TRUE;
    p->wall_start = p->wall_last = now;
    p->t_start    = time;
    p->step_start = p->step_last = step;
    PetscFunctionReturn(0);
  }
  if (step <= p->step_last) PetscFunctionReturn(0);
  p->step_last = step;
  p->friction_its += p->hist->friction_its;
  p->steps++;
  if (now - p->wall_last < p->every) PetscFunctionReturn(0);
  PetscCall(PrintLine(p, ts, (PetscReal)(now - p->wall_start)));
  p->wall_last    = now;
  p->friction_its = 0;
  p->steps        = 0;
  PetscFunctionReturn(0);
}

/*@
  MMProgressSetFromOptions - Reads -progress_every, with its check

  Collective

  Input Parameters:
+ comm - the run's communicator
- p    - the progress object, zeroed

  Level: intermediate

.seealso: `MMProgressSetUp()`, `MMProgressMonitorSet()`
@*/
PetscErrorCode MMProgressSetFromOptions(MPI_Comm comm, MMProgress *p)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact progress", "MMProgress");
  p->every = 5;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-progress_every", "Print a progress line (time, wall time and ETA, energy balance, contact and friction) every this many seconds of wall time, >= 0 (0: none)", &p->every));
  PetscOptionsEnd();
  PetscCheck(p->every >= 0, comm, PETSC_ERR_USER_INPUT, "-progress_every %.6g must be >= 0: it is the wall time in seconds between progress lines (0 turns them off)", (double)p->every);
  PetscFunctionReturn(0);
}

/*@
  MMProgressMonitorSet - Adds the progress line's TS monitor, after the others, unless
  -progress_every 0

  Collective

  Input Parameters:
+ p  - the progress object, set up
- ts - the time stepper

  Note:
  The progress line, unless -progress_every 0 (the caller leaves it out under -quiet): a TS monitor
  after the others (after -ts_monitor, which still works, and after the history row).

  Level: intermediate

.seealso: `MMProgressMonitor()`, `TSMonitorSet()`
@*/
PetscErrorCode MMProgressMonitorSet(MMProgress *pg, TS ts)
{
  PetscFunctionBeginUser;
  if (pg->every == 0) PetscFunctionReturn(0);
  PetscCall(TSMonitorSet(ts, MMProgressMonitor, pg, NULL));
  PetscFunctionReturn(0);
}
