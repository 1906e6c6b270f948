/* One run per output directory (README "Output": the lock).
 *
 * Two runs writing into one -output_dir would mix their histories, snapshots and checkpoints, and
 * the one that survives would report the other's data as its own. So rank 0 of a run holds
 * OUTPUT_DIR/.mmcontact.lock from the start of set-up to its exit: the file names the holder
 * (host and pid), and the holder keeps a flock(2) on it. The kernel drops that lock when the
 * process dies however it dies, so a lock file left by a dead run (SIGKILL, a crash) holds no
 * flock and is taken over: stale locks need no guessing from a pid. Where the file system has no
 * flock (some network file systems), a lock file naming a live process of this host, or any process
 * of another host, is respected.
 *
 * A second run is refused before it touches anything in the directory. The run that takes the lock
 * owns the directory: it first removes the lock files of Open MPI that a killed run left (below), and
 * at its exit removes the directory it created if nothing was written into it (a refused input,
 * a refused -restart). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include "io.h"
#include "outputimpl.h"
#include "sys.h"

#define MM_LOCK_NAME ".mmcontact.lock"

static int  lock_fd = -1; /* rank 0: the held lock file */
static char lock_path[PETSC_MAX_PATH_LEN];
static char made_dir[PETSC_MAX_PATH_LEN]; /* rank 0: the output directory, if this run created it */
static size_t made_from;                  /* the length of its first component this run created */

/* The holder named in an existing lock file: "host pid". */
static void ReadHolder(int fd, char host[], size_t hlen, long *pid)
{
  char   buf[512] = "";
  ssize_t n        = pread(fd, buf, sizeof(buf) - 1, 0);

  host[0] = 0;
  *pid    = -1;
  if (n <= 0) return;
  buf[n] = 0;
  if (sscanf(buf, "host %255s pid %ld", host, pid) != 2) {
    host[0] = 0;
    *pid    = -1;
  }
  (void)hlen;
}

/* Without flock: whether the holder the file names may still be running. */
static PetscBool HolderMayLive(const char host[], long pid)
{
  char me[256] = "";

  if (pid <= 0) return PETSC_FALSE;
  (void)gethostname(me, sizeof(me));
  if (strcmp(host, me)) return PETSC_TRUE; /* another host: cannot tell */
  return (PetscBool)(kill((pid_t)pid, 0) == 0 || errno == EPERM);
}

/* rank 0: takes the lock, or says who holds it (st->err < 0, with the message). */
static PetscErrorCode TakeLock(const char dir[], MMFileStatus *st, PetscBool *held_by_other)
{
  char host[256] = "", me[256] = "";
  long pid;

  PetscFunctionBeginUser;
  *held_by_other = PETSC_FALSE;
  PetscCall(PetscSNPrintf(lock_path, sizeof(lock_path), "%s/%s", dir, MM_LOCK_NAME));
  (void)gethostname(me, sizeof(me));
  for (int attempt = 0; attempt < 8; ++attempt) {
    struct stat sf, sp;
    int         fd = open(lock_path, O_RDWR | O_CREAT | O_CLOEXEC, 0666), locked;
    char        line[512];

    if (fd < 0) {
      PetscCall(MMOutputFailed(st, "create the lock file %s", lock_path));
      PetscFunctionReturn(0);
    }
    locked = flock(fd, LOCK_EX | LOCK_NB);
    if (locked && errno == EWOULDBLOCK) {
      ReadHolder(fd, host, sizeof(host), &pid);
      (void)close(fd);
      *held_by_other = PETSC_TRUE;
      break;
    }
    if (locked) { /* no flock on this file system: the file's content decides */
      ReadHolder(fd, host, sizeof(host), &pid);
      if (HolderMayLive(host, pid) && !(pid == (long)getpid() && !strcmp(host, me))) {
        (void)close(fd);
        *held_by_other = PETSC_TRUE;
        break;
      }
    }
    /* the file may have been removed by its holder's exit between open and flock: retry on the new one */
    if (fstat(fd, &sf) || stat(lock_path, &sp) || sf.st_ino != sp.st_ino || sf.st_dev != sp.st_dev) {
      (void)close(fd);
      continue;
    }
    (void)PetscSNPrintf(line, sizeof(line), "host %s pid %ld\n", me, (long)getpid());
    if (ftruncate(fd, 0) || pwrite(fd, line, strlen(line), 0) != (ssize_t)strlen(line)) {
      PetscCall(MMOutputFailed(st, "write the lock file %s", lock_path));
      (void)close(fd);
      PetscFunctionReturn(0);
    }
    lock_fd = fd;
    PetscFunctionReturn(0);
  }
  st->err = -1;
  if (*held_by_other && pid > 0)
    PetscCall(PetscSNPrintf(st->what, sizeof(st->what), "The output directory %s is in use by another mmcontact run: process %ld on host %s holds %s. Wait for it to end, or give this run another -output_dir. (If that process is gone, remove %s.)", dir, pid, host[0] ? host : "?", lock_path, lock_path));
  else PetscCall(PetscSNPrintf(st->what, sizeof(st->what), "The output directory %s is in use by another mmcontact run (%s is locked). Wait for it to end, or give this run another -output_dir", dir, lock_path));
  PetscFunctionReturn(0);
}

/* What a killed run leaves that no run reads, in the directory whose lock is held: NAME-JOBID-PID.lock,
 * the lock of Open MPI's sharedfp/lockedfile component beside each HDF5 file it had open
 * (src/sys/mpi_env.c: an earlier version of mmcontact, or a user's OMPI_MCA_io=ompio). Its name is
 * new each run, so it would stay for good. */
static PetscBool IsDebris(const char n[])
{
  static const char *const h5[] = {"solution.h5-", "checkpoint.h5-", "checkpoint.h5.tmp-", "checkpoint_snapshots.h5-"};
  const size_t             len  = strlen(n);

  if (len < 5 || strcmp(n + len - 5, ".lock")) return PETSC_FALSE;
  for (size_t i = 0; i < sizeof(h5) / sizeof(h5[0]); ++i) {
    const size_t k = strlen(h5[i]);
    unsigned     jobid;
    int          pid, used = 0;

    if (strncmp(n, h5[i], k)) continue;
    if (sscanf(n + k, "%u-%d.lock%n", &jobid, &pid, &used) == 2 && (size_t)used == len - k) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* rank 0, the lock held: removes the debris of a killed run */
static void RemoveDebris(const char dir[])
{
  DIR           *d = opendir(dir);
  struct dirent *e;
  char           path[PETSC_MAX_PATH_LEN];

  if (!d) return;
  while ((e = readdir(d)))
    if (IsDebris(e->d_name) && snprintf(path, sizeof(path), "%s/%s", dir, e->d_name) < (int)sizeof(path)) (void)unlink(path);
  (void)closedir(d);
}

/* The length of the first component of path that does not exist yet, 0 if it exists whole. */
static size_t FirstMissing(const char path[])
{
  char        p[PETSC_MAX_PATH_LEN];
  size_t      len;
  struct stat s;

  if (!stat(path, &s)) return 0;
  (void)snprintf(p, sizeof(p), "%s", path);
  len = strlen(p);
  for (size_t i = 1; i <= len; ++i) {
    if (p[i] != '/' && p[i] != 0) continue;
    p[i] = 0;
    if (stat(p, &s)) return i;
    p[i] = '/';
  }
  return len;
}

/* The directories this run created, deepest first, each if empty (rmdir removes no other). */
static void RemoveMadeDirectories(void)
{
  size_t len = strlen(made_dir);

  while (made_from && len >= made_from) {
    made_dir[len] = 0;
    if (rmdir(made_dir) && errno != ENOENT) break; /* not empty: the run wrote into it */
    while (len > 0 && made_dir[len - 1] != '/') --len; /* up to the parent */
    while (len > 0 && made_dir[len - 1] == '/') --len;
  }
  made_from = 0;
}

/* At exit, including the exit of a refused input after the lock was taken. */
static void ReleaseAtExit(void)
{
  if (lock_fd < 0) return;
  (void)unlink(lock_path);
  (void)close(lock_fd);
  lock_fd = -1;
  RemoveMadeDirectories();
}

/*@
  MMOutputLock - Creates the output directory and takes its lock, so that one run writes there at a
  time

  Collective

  Input Parameter:
. dir - the output directory (-output_dir)

  Note:
  Early in set-up, before anything in the directory is read or moved: creates the directory and
  takes its lock on rank 0; every rank stops if another run holds it.

  Level: intermediate

.seealso: `MMOutputUnlock()`, `MMOutputOpen()`
@*/
PetscErrorCode MMOutputLock(const char dir[])
{
  MMFileStatus st = {0};
  PetscMPIInt  rank;
  PetscBool    other = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank == 0) {
    made_from = FirstMissing(dir);
    PetscCall(PetscStrncpy(made_dir, dir, sizeof(made_dir)));
    PetscCall(MMOutputMakeDirectories(dir, &st));
    if (!st.err) PetscCall(TakeLock(dir, &st, &other));
    if (lock_fd < 0) made_from = 0; /* not ours to remove */
    else RemoveDebris(dir);
    if (lock_fd >= 0) {
      PetscCheck(!atexit(ReleaseAtExit), PETSC_COMM_SELF, PETSC_ERR_SYS, "Could not register the lock's release");
      PetscCall(MMErrorsAtAbort(ReleaseAtExit));
    }
  }
  PetscCallMPI(MPI_Bcast(&other, 1, MPIU_BOOL, 0, PETSC_COMM_WORLD));
  if (other) {
    PetscCallMPI(MPI_Bcast(st.what, sizeof(st.what), MPI_CHAR, 0, PETSC_COMM_WORLD));
    SETERRQ(PETSC_COMM_WORLD, MM_ERR_LOCKED, "%s", st.what);
  }
  PetscCall(MMOutputCheckRank0(&st));
  PetscFunctionReturn(0);
}

/*@
  MMOutputUnlock - Releases the output directory's lock once the run's output is closed

  Not collective

  Level: intermediate

.seealso: `MMOutputLock()`, `MMOutputClose()`
@*/
PetscErrorCode MMOutputUnlock(void)
{
  PetscFunctionBeginUser;
  ReleaseAtExit();
  PetscFunctionReturn(0);
}
