/* Options nobody reads, and -help without a mesh.
 *
 * A misspelled option is silently ignored by PETSc: -mu_ 0.2 runs frictionless. So, once every
 * object has read its options, any option still unread stops the run before the first step, with the
 * closest valid name. The valid names are what -help would print: the help text of every object is
 * replayed into memory instead of the terminal. */
#include <ctype.h>
#include <strings.h>
#include <stdarg.h>
#include "ts.h"
#include "appimpl.h"
#include "contact.h"
#include "friction.h"
#include "fem.h"
#include "io.h"

/* Options that PETSc reads at start-up or after the time loop (TSSolve's -ts_view_solution,
 * PetscFinalize's -options_left): valid, but not yet read when the check runs. */
static const char *const LateOptions[] = {"-ts_view_solution", "-options_left", "-options_view", "-malloc_dump", "-malloc_view", "-memory_view", "-objects_dump", "-log_view", "-log_view_memory", "-log_summary", "-log_trace", "-info", "-history", "-help", "-version", "-options_file", "-options_file_yaml", "-malloc_debug", "-on_error_abort", "-start_in_debugger", "-on_error_attach_debugger", "-check_pointer_intensity", "-viewer_binary_skip_info"};

/* The viewers PETSc reads when a solve ends (KSPSolve's -ksp_converged_reason and -ksp_view, SNESSolve's
 * -snes_converged_reason and -snes_view), for each solver's prefix: valid, but the first solve comes
 * after the check. The error messages of the solves themselves suggest some of them. */
static const char *const SolverPrefixes[] = {"contact_", "contact0_", "friction_", "contact_K_", "mass_", "sliding_", "contact_as_"};
static const char *const SolveTimeViewers[] = {"ksp_converged_reason", "ksp_view", "ksp_view_pre", "ksp_view_final_residual", "ksp_view_mat", "ksp_view_pmat", "ksp_view_rhs", "ksp_view_solution", "snes_converged_reason", "snes_view", "snes_view_pre", "snes_view_solution"};

/* The valid names, parsed from the help text, and which of them take a value. */
static struct {
  char     **name;
  PetscBool *takes_value;
  PetscInt   n, cap;
} Collected;

static PetscErrorCode AddName(const char name[], size_t len, PetscBool takes_value)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < Collected.n; ++i)
    if (strlen(Collected.name[i]) == len && !strncasecmp(Collected.name[i], name, len)) {
      Collected.takes_value[i] = (PetscBool)(Collected.takes_value[i] || takes_value);
      PetscFunctionReturn(0);
    }
  if (Collected.n == Collected.cap) {
    Collected.cap = PetscMax(64, 2 * Collected.cap);
    PetscCall(PetscRealloc(sizeof(char *) * Collected.cap, &Collected.name));
    PetscCall(PetscRealloc(sizeof(PetscBool) * Collected.cap, &Collected.takes_value));
  }
  PetscCall(PetscMalloc1(len + 1, &Collected.name[Collected.n]));
  PetscCall(PetscStrncpy(Collected.name[Collected.n], name, len + 1));
  Collected.takes_value[Collected.n] = takes_value;
  Collected.n++;
  PetscFunctionReturn(0);
}

static PetscErrorCode FreeNames(void)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < Collected.n; ++i) PetscCall(PetscFree(Collected.name[i]));
  PetscCall(PetscFree(Collected.name));
  PetscCall(PetscFree(Collected.takes_value));
  Collected.n = Collected.cap = 0;
  PetscFunctionReturn(0);
}

/* Help lines start with blanks and the option's name. An option with a value shows it in angle
 * brackets right after the name, "  -ts_dt <0.001 : 0.001>: ...", a flag after a colon,
 * "  -quiet: <FALSE : FALSE> ...", a viewer its syntax, "  -ts_monitor ascii[:...]". */
static PetscErrorCode ParseHelp(const char text[])
{
  PetscFunctionBeginUser;
  for (const char *p = text; p && *p;) {
    size_t len = 0;
    while (*p == ' ' || *p == '\t') ++p;
    if (*p == '-' && isalpha((unsigned char)p[1])) {
      while (isalnum((unsigned char)p[len + 1]) || p[len + 1] == '_') ++len;
      PetscCall(AddName(p, len + 1, (PetscBool)(p[len + 1] == ' ' && p[len + 2] == '<')));
    }
    p = strchr(p, '\n');
    if (p) ++p;
  }
  PetscFunctionReturn(0);
}

/* Every solver object mmcontact creates, by its prefix, read from the options: with -help set this
 * prints their options. Objects a run does not create (the friction loop at mu = 0) are included, so
 * that their options are known as valid names. */
static PetscErrorCode SolverObjectsFromOptions(MPI_Comm comm)
{
  const char *snes_prefix[] = {"contact_", "contact0_", "friction_"};
  const char *ksp_prefix[]  = {"contact_K_", "mass_", "sliding_", "contact_as_"};
  TS          ts;

  PetscFunctionBeginUser;
  PetscCall(TSCreate(comm, &ts));
  PetscCall(MMNewmarkSetDefaults(ts));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSDestroy(&ts));
  for (size_t i = 0; i < sizeof(snes_prefix) / sizeof(snes_prefix[0]); ++i) {
    SNES snes;
    PetscCall(SNESCreate(comm, &snes));
    PetscCall(SNESSetOptionsPrefix(snes, snes_prefix[i]));
    PetscCall(SNESSetType(snes, i < 2 ? SNESVINEWTONRSLS : SNESSHELL));
    PetscCall(SNESSetFromOptions(snes));
    PetscCall(SNESDestroy(&snes));
  }
  for (size_t i = 0; i < sizeof(ksp_prefix) / sizeof(ksp_prefix[0]); ++i) {
    KSP ksp;
    PetscCall(KSPCreate(comm, &ksp));
    PetscCall(KSPSetOptionsPrefix(ksp, ksp_prefix[i]));
    /* each solve's default (K~'s in 2D) */
    if (i == 0) PetscCall(MMKSPSetDirectSPD(ksp, 2));
    else if (i == 1) PetscCall(MMKSPSetExactCG(ksp));
    else if (i == 2) PetscCall(MMKSPSetDirect(ksp));
    else PetscCall(KSPSetType(ksp, KSPCG));
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPDestroy(&ksp));
  }
  /* MUMPS's options of K~'s factor (3D) and of the full formulation's VI factor: their help */
  PetscCall(MMFactorReadOptions(comm, "contact_K_", MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY));
  PetscCall(MMFactorReadOptions(comm, "contact_", MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY));
  PetscFunctionReturn(0);
}

/* Every component that reads its own options, read from the options on scratch objects: with -help
 * set this prints their options, and the replay learns their names. */
static PetscErrorCode ComponentsFromOptions(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  {
    MMOperators op;
    PetscCall(MMFECreate(comm, &op));
    PetscCall(MMFESetFromOptions(op));
    PetscCall(MMFEDestroy(&op));
  }
  {
    MMOutput     out;
    MMCheckpoint ckpt;
    MMProgress   progress;
    PetscCall(PetscMemzero(&out, sizeof(out)));
    PetscCall(PetscMemzero(&ckpt, sizeof(ckpt)));
    PetscCall(PetscMemzero(&progress, sizeof(progress)));
    PetscCall(MMOutputSetFromOptions(comm, &out));
    PetscCall(MMCheckpointSetFromOptions(comm, &ckpt));
    PetscCall(MMProgressSetFromOptions(comm, &progress));
    PetscCall(MMCheckpointDestroy(&ckpt));
  }
  {
    MMContact  ct;
    MMFriction fr;
    PetscCall(MMContactCreate(comm, &ct));
    PetscCall(MMContactSetFromOptions(ct));
    PetscCall(MMContactDestroy(&ct));
    PetscCall(MMFrictionCreate(comm, &fr));
    PetscCall(MMFrictionSetFromOptions(fr));
    PetscCall(MMFrictionDestroy(&fr));
  }
  {
    MMNewmark nm;
    PetscCall(MMNewmarkCreate(comm, &nm));
    PetscCall(MMNewmarkSetFromOptions(nm));
    PetscCall(MMNewmarkDestroy(&nm));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsHelpWithoutMesh(MPI_Comm comm, PetscBool *done)
{
  PetscBool help, mesh;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mesh", &mesh));
  if (!help || mesh) PetscFunctionReturn(0);
  PetscCall(ComponentsFromOptions(comm));
  PetscCall(SolverObjectsFromOptions(comm));
  PetscCall(PetscPrintf(comm, "\nThe options of the mesh (-dm_*, -petscpartitioner_type) are listed when -help is given with -mesh FILE.\n"));
  *done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Marks the solve-time viewers given as read, or (add_names) adds all of them to the valid names. */
static PetscErrorCode SolveTimeViewerOptions(PetscBool add_names)
{
  PetscFunctionBeginUser;
  for (size_t p = 0; p < sizeof(SolverPrefixes) / sizeof(SolverPrefixes[0]); ++p)
    for (size_t v = 0; v < sizeof(SolveTimeViewers) / sizeof(SolveTimeViewers[0]); ++v) {
      char      name[PETSC_MAX_OPTION_NAME];
      PetscBool set;
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", SolverPrefixes[p], SolveTimeViewers[v]));
      if (add_names) PetscCall(AddName(name, strlen(name), PETSC_FALSE));
      else PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
    }
  PetscFunctionReturn(0);
}

/* The valid option names: the help text of the application and of every object, replayed into
 * memory (PETSc prints help on rank 0, so only rank 0 knows them; only rank 0 prints the error).
 * Without dm, the mesh's options are left out: replaying them on a DM in use could change it. */
static PetscErrorCode CollectValidNames(MPI_Comm comm, DM dm)
{
  FILE     *saved = PETSC_STDOUT, *saved_stdout = stdout, *mem;
  char     *text  = NULL;
  size_t    size  = 0;
  PetscBool had_help;
  MMOptions scratch;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &had_help));
  if (!had_help) PetscCall(PetscOptionsSetValue(NULL, "-help", NULL));
  /* help already printed for a prefix is not printed again: forget what was printed */
  PetscCall(PetscOptionsHelpPrintedDestroy(&PetscOptionsHelpPrintedSingleton));
  mem = open_memstream(&text, &size);
  PetscCheck(mem, PETSC_COMM_SELF, PETSC_ERR_MEM, "Cannot open a memory stream for the help text");
  /* PetscFunctionListPrintTypes writes the "(one of)" lines to stdout itself */
  PETSC_STDOUT = mem;
  stdout       = mem;
  PetscCall(MMOptionsProcess(comm, &scratch));
  PetscCall(MMOptionsDestroy(&scratch));
  PetscCall(ComponentsFromOptions(comm));
  PetscCall(SolverObjectsFromOptions(comm));
  /* the run stops after the unused-option report: the mesh's options may be replayed on its DM */
  if (dm) PetscCall(DMSetFromOptions(dm));
  PETSC_STDOUT = saved;
  stdout       = saved_stdout;
  fclose(mem);
  if (!had_help) PetscCall(PetscOptionsClearValue(NULL, "-help"));
  PetscCall(ParseHelp(text));
  free(text);
  for (size_t i = 0; i < sizeof(LateOptions) / sizeof(LateOptions[0]); ++i) PetscCall(AddName(LateOptions[i], strlen(LateOptions[i]), PETSC_FALSE));
  PetscCall(SolveTimeViewerOptions(PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* Edit distance between two option names, case-insensitive. */
static PetscInt EditDistance(const char a[], const char b[])
{
  const size_t la = strlen(a), lb = strlen(b);
  PetscInt     row[256], d = 0;

  if (lb >= sizeof(row) / sizeof(row[0])) return PETSC_MAX_INT;
  for (size_t j = 0; j <= lb; ++j) row[j] = (PetscInt)j;
  for (size_t i = 1; i <= la; ++i) {
    PetscInt diag = row[0];
    row[0] = (PetscInt)i;
    for (size_t j = 1; j <= lb; ++j) {
      const PetscInt up = row[j], sub = diag + (tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]));
      row[j] = PetscMin(PetscMin(row[j - 1] + 1, up + 1), sub);
      diag   = up;
    }
  }
  d = row[lb];
  return d;
}

/* What to tell the user about one unread option. */
static PetscErrorCode DescribeUnused(const char name[], const char value[], char msg[], size_t len)
{
  const char *eq = strchr(name, '=');
  PetscInt    best = PETSC_MAX_INT;
  const char *closest = NULL;
  char        key[PETSC_MAX_OPTION_NAME];

  PetscFunctionBeginUser;
  /* PETSc takes "-E=1000" as an option named "E=1000" without a value */
  PetscCall(PetscSNPrintf(key, sizeof(key), "-%.*s", eq ? (int)(eq - name) : (int)strlen(name), name));
  for (PetscInt i = 0; i < Collected.n; ++i) {
    const PetscInt d = EditDistance(key, Collected.name[i]);
    if (d < best) {
      best    = d;
      closest = Collected.name[i];
    }
  }
  if (eq && best == 0) PetscCall(PetscSNPrintf(msg, len, "  -%s: options take the form \"%s %s\", with a blank, not \"=\"\n", name, key, eq + 1));
  else if (best == 0) PetscCall(PetscSNPrintf(msg, len, "  -%s%s%s: a valid option, but nothing in this run reads it (friction options need -mu > 0, contact_as_ options the active-set formulation, mat_mumps_ options a MUMPS factor: K~ in 3D, the full formulation's VI)\n", name, value ? " " : "", value ? value : ""));
  else if (closest && best <= PetscMax(2, (PetscInt)strlen(key) / 3)) PetscCall(PetscSNPrintf(msg, len, "  -%s%s%s: unknown; did you mean %s?\n", name, value ? " " : "", value ? value : "", closest));
  else PetscCall(PetscSNPrintf(msg, len, "  -%s%s%s: unknown, and no valid option is close to it (-help lists them)\n", name, value ? " " : "", value ? value : ""));
  PetscFunctionReturn(0);
}

/* The options given without a value, from the database's text "-a 1 -b -c x ": a name followed by
 * another name or by nothing. A value that itself looks like a name ("-x -y") is read as none: it is
 * only looked at if the option takes a value, and then is refused with the rest. */
static PetscErrorCode ValuelessOptions(PetscInt *n, char ***names)
{
  char   *all, **tok;
  int     ntok;
  PetscInt k = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  PetscCall(PetscStrToArray(all, ' ', &ntok, &tok));
  PetscCall(PetscCalloc1(ntok + 1, names));
  for (int i = 0; i < ntok; ++i) {
    const PetscBool name = (PetscBool)(tok[i][0] == '-' && (isalpha((unsigned char)tok[i][1]) || tok[i][1] == '_'));
    const PetscBool next = (PetscBool)(i + 1 < ntok && tok[i + 1][0] == '-' && (isalpha((unsigned char)tok[i + 1][1]) || tok[i + 1][1] == '_'));
    if (name && (i + 1 == ntok || next)) PetscCall(PetscStrallocpy(tok[i], &(*names)[k++]));
  }
  PetscCall(PetscStrToArrayDestroy(ntok, tok));
  PetscCall(PetscFree(all));
  *n = k;
  PetscFunctionReturn(0);
}

/* An option that takes a value, given without one ("-ts_dt" followed by another option, or last),
 * keeps its default in silence, even over an options file's value: refused, by name. mmcontact's own
 * options are checked as they are read (options.c); this catches the solvers' and the stepper's. */
PetscErrorCode MMOptionsCheckValueless(MPI_Comm comm)
{
  PetscInt n = 0;
  char   **names, bad[PETSC_MAX_OPTION_NAME] = "";

  PetscFunctionBeginUser;
  PetscCall(ValuelessOptions(&n, &names));
  if (n) PetscCall(CollectValidNames(comm, NULL));
  for (PetscInt i = 0; i < n && !bad[0]; ++i)
    for (PetscInt j = 0; j < Collected.n; ++j)
      if (Collected.takes_value[j] && !strcasecmp(Collected.name[j], names[i])) PetscCall(PetscStrncpy(bad, names[i], sizeof(bad)));
  for (PetscInt i = 0; i < n; ++i) PetscCall(PetscFree(names[i]));
  PetscCall(PetscFree(names));
  PetscCall(FreeNames());
  /* only rank 0 has the help text */
  PetscCallMPI(MPI_Bcast(bad, sizeof(bad), MPI_CHAR, 0, comm));
  PetscCheck(!bad[0], comm, PETSC_ERR_USER_INPUT, "%s was given without a value: write \"%s VALUE\", or leave the option out for its default (-help shows its values)", bad, bad);
  PetscFunctionReturn(0);
}

PetscErrorCode MMOptionsCheckUnused(MPI_Comm comm, const MMOptions *opt, DM dm)
{
  PetscInt n, nunused;
  char   **names, **values;
  char    *report;
  size_t   cap = 512;

  PetscFunctionBeginUser;
  if (opt->allow_unused) PetscFunctionReturn(0);
  /* read now what is read only after the time loop, so that it does not count as unused */
  for (size_t i = 0; i < sizeof(LateOptions) / sizeof(LateOptions[0]); ++i) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, LateOptions[i], &set));
  }
  PetscCall(SolveTimeViewerOptions(PETSC_FALSE));
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  if (!n) {
    PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
    PetscFunctionReturn(0);
  }
  nunused = n;
  PetscCall(CollectValidNames(comm, dm));
  cap += (size_t)n * 512;
  PetscCall(PetscCalloc1(cap, &report));
  for (PetscInt i = 0; i < n; ++i) {
    char line[512];
    PetscCall(DescribeUnused(names[i], values[i], line, sizeof(line)));
    PetscCall(PetscStrlcat(report, line, cap));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCall(FreeNames());
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%" PetscInt_FMT " option%s set but never read, so the run would ignore %s:\n%sFix the spelling, or pass -allow_unused_options to run anyway", nunused, nunused > 1 ? "s are" : " is", nunused > 1 ? "them" : "it", report);
}
