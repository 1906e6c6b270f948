/* SIGTERM and SIGINT: batch schedulers send SIGTERM before they kill a job, and users press
 * Ctrl-C. The run finishes the step it is in, writes a checkpoint, closes its output and exits with
 * MM_EXIT_RESTARTABLE and a message that says how to continue (docs/method.md section 9).
 *
 * The handler only records the signal, the one thing a handler may safely do; every rank looks at
 * it after each step, together, so that all stop after the same step. A second signal is not
 * caught (SA_RESETHAND): it ends the process at once, as without this handler. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <unistd.h>
#include "sys.h"

static volatile sig_atomic_t mm_signal = 0;
static int                   stopped_by = 0; /* the signal the run stopped on, the same on every rank; 0: none */

static void RecordSignal(int sig)
{
  mm_signal = sig;
}

/* TS post-step: stop after this step if any rank has been signalled. */
static PetscErrorCode StopOnSignal(TS ts)
{
  int sig = (int)mm_signal, any;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&sig, &any, 1, MPI_INT, MPI_MAX, PetscObjectComm((PetscObject)ts)));
  if (any) {
    TSConvergedReason reason;
    PetscCall(TSGetConvergedReason(ts, &reason));
    if (reason == TS_CONVERGED_ITERATING) {
      stopped_by = any;
      PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
    }
  }
  PetscFunctionReturn(0);
}

/*@
  MMSignalsSetUp - Installs the SIGTERM and SIGINT handler and the TS post-step that stops the run
  after the step in which one arrived

  Logically collective on ts

  Input Parameter:
. ts - the time stepper

  Note:
  After PETSc's initialization, whose own handlers would abort the run on these signals.

  The post-step reduces the recorded signal over the TS's communicator, so that every rank stops
  after the same step (TS_CONVERGED_USER).

  Level: intermediate

.seealso: `MMSignalsGetStop()`, `MMSignalsReport()`
@*/
PetscErrorCode MMSignalsSetUp(TS ts)
{
  struct sigaction sa;

  PetscFunctionBeginUser;
  memset(&sa, 0, sizeof(sa));
  sa.sa_handler = RecordSignal;
  sa.sa_flags   = SA_RESETHAND | SA_RESTART;
  sigemptyset(&sa.sa_mask);
  PetscCheck(!sigaction(SIGTERM, &sa, NULL) && !sigaction(SIGINT, &sa, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "Could not install the SIGTERM and SIGINT handlers");
  PetscCall(TSSetPostStep(ts, StopOnSignal));
  PetscFunctionReturn(0);
}

/*@
  MMSignalsGetStop - Gives the signal that stopped the run after a step

  Not collective

  Output Parameter:
. signal_number - the signal, the same on every rank; 0 if none did

  Level: intermediate

.seealso: `MMSignalsSetUp()`, `MMSignalsReport()`
@*/
PetscErrorCode MMSignalsGetStop(int *signal_number)
{
  PetscFunctionBeginUser;
  *signal_number = stopped_by;
  PetscFunctionReturn(0);
}

/*@
  MMSignalsReport - Prints, when a signal stopped the run, where its state is and the command that
  continues it

  Collective

  Input Parameters:
+ comm       - the communicator printed on (rank 0 prints)
. step       - the last step taken
. time       - its time
- output_dir - the output directory, which holds checkpoint.h5

  Note:
  Prints nothing when no signal stopped the run.

  Level: intermediate

.seealso: `MMSignalsGetStop()`, `MMSignalsSetUp()`
@*/
PetscErrorCode MMSignalsReport(MPI_Comm comm, PetscInt step, PetscReal time, const char output_dir[])
{
  PetscFunctionBeginUser;
  if (!stopped_by) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(comm, "mmcontact: stopped by %s after step %" PetscInt_FMT " (t = %.10g). The state is in %s/checkpoint.h5 and the output up to this step is complete. Continue the run, on any number of ranks, with the same options and\n  -restart %s\n", stopped_by == SIGTERM ? "SIGTERM" : stopped_by == SIGINT ? "SIGINT" : "a signal", step, (double)time, output_dir, output_dir));
  PetscFunctionReturn(0);
}

/*@
  MMSignalsDieWithLauncher - Under an MPI launcher, has the kernel kill the process when its
  launcher dies

  Not collective

  Note:
  A rank whose launcher dies (SIGKILL to mpiexec, a node daemon lost) would go on for a second or
  two, still writing its output, before Open MPI notices. Under mpiexec the kernel kills it with its
  parent instead (PR_SET_PDEATHSIG), so that nothing is written after the job is gone. Only under a
  launcher: a run started from a shell must outlive that shell (nohup). Called before MPI starts,
  while the environment is the launcher's.

  Level: developer

.seealso: `MMSignalsSetUp()`, `MMMPIEnvironmentSet()`
@*/
PetscErrorCode MMSignalsDieWithLauncher(void)
{
  const pid_t parent = getppid();

  if (!getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMIX_RANK") && !getenv("PMI_RANK")) return 0;
  if (prctl(PR_SET_PDEATHSIG, SIGKILL)) return 0; /* not Linux: the old behaviour */
  /* the launcher may have died before the call */
  if (getppid() != parent) _exit(MM_EXIT_RESTARTABLE);
  return 0;
}
