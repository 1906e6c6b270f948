/* -friction_dump DIR: each step's Coulomb problem on the candidate set, as data (docs/method.md
 * section 6, "The step's problem in the Friction Contact Library's form").
 *
 * DIR/step_NNNNNN.h5 holds, for the last solve of step N (the set may grow and be solved again):
 *   W (m x m, m = nc n, row-major), q (m), mu (n)   in fclib's form u = W r + q:
 *     W = (2/dt) W_ours, q = -(2/dt) q_ours, so that u is the local velocity and W stays symmetric;
 *   r (m)  our reactions (normal first, then the tangents of each node's frame), r0 (m) the warm
 *          start our solver began from (the previous step's reactions);
 *   attributes: spacedim (= nc), n, step, time, dt, solver, its, solve_time (s), residual.
 * The set's problem is replicated on every rank: rank 0 writes it. */
#include <errno.h>
#include <sys/stat.h>
#include <hdf5.h>
#include "../frictionimpl.h"

static void AttrReal(hid_t f, const char name[], double v)
{
  hid_t sp = H5Screate(H5S_SCALAR), a = H5Acreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
  (void)H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
  (void)H5Aclose(a);
  (void)H5Sclose(sp);
}

static void AttrText(hid_t f, const char name[], const char v[])
{
  hid_t sp = H5Screate(H5S_SCALAR), t = H5Tcopy(H5T_C_S1), a;
  (void)H5Tset_size(t, strlen(v) + 1);
  a = H5Acreate2(f, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
  (void)H5Awrite(a, t, v);
  (void)H5Aclose(a);
  (void)H5Tclose(t);
  (void)H5Sclose(sp);
}

static herr_t Dataset(hid_t f, const char name[], int rank, const hsize_t dims[], const double v[])
{
  hid_t  sp = H5Screate_simple(rank, dims, NULL), d = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = d < 0 ? -1 : H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (d >= 0) (void)H5Dclose(d);
  (void)H5Sclose(sp);
  return st;
}

/* The directory, created if missing, at set-up: a wrong path stops the run before its first step. */
PetscErrorCode MMFrictionDumpSetUp(MMFriction fr)
{
  const char *dir = fr->dump;
  PetscMPIInt rank;
  int         err = 0;
  struct stat s;

  PetscFunctionBeginUser;
  if (!dir[0]) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank && mkdir(dir, 0777) && errno != EEXIST) err = errno;
  if (!rank && !err && (stat(dir, &s) || !S_ISDIR(s.st_mode))) err = ENOTDIR;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  PetscCheck(!err, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-friction_dump %s: cannot create the directory: %s", dir, strerror(err));
  PetscFunctionReturn(0);
}

PetscErrorCode MMFrictionDump(MMFriction fr, const MMCoulombProblem *p, const PetscScalar x0[], const PetscScalar x[], const MMCoulombResult *res, PetscLogDouble seconds)
{
  const PetscInt  m   = p->nc * p->n;
  PetscReal       dt, scale;
  char            name[PETSC_MAX_PATH_LEN];
  PetscReal      *W, *q, *mu, *r, *r0;
  PetscMPIInt     rank;
  hid_t           f;
  herr_t          st = 0;
  hsize_t         dW[2] = {(hsize_t)m, (hsize_t)m}, dq = (hsize_t)m, dmu = (hsize_t)p->n;
  MMContactNodes  cn;
  MMStepOffset    so;

  PetscFunctionBeginUser;
  PetscCall(MMContactGetNodes(fr->contact, &cn));
  PetscCall(MMContactGetStepOffset(fr->contact, &so));
  dt    = cn.dt;
  scale = so.scale; /* 2/dt: the FCLib form's velocities from our displacements */
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank || !m) PetscFunctionReturn(0);
  PetscCall(PetscMalloc5((size_t)m * m, &W, m, &q, p->n, &mu, m, &r, m, &r0));
  /* W is symmetric: its column-major array is its row-major one */
  for (size_t k = 0; k < (size_t)m * m; ++k) W[k] = scale * PetscRealPart(p->W[k]);
  for (PetscInt k = 0; k < m; ++k) {
    q[k] = -scale * PetscRealPart(p->q[k]);
    r[k]  = PetscRealPart(x[k]);
    r0[k] = PetscRealPart(x0[k]);
  }
  for (PetscInt k = 0; k < p->n; ++k) mu[k] = p->mu[k];
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/step_%06" PetscInt_FMT ".h5", fr->dump, fr->step + 1));
  f = H5Fcreate(name, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-friction_dump: could not create %s", name);
  st |= Dataset(f, "W", 2, dW, W);
  st |= Dataset(f, "q", 1, &dq, q);
  st |= Dataset(f, "mu", 1, &dmu, mu);
  st |= Dataset(f, "r", 1, &dq, r);
  st |= Dataset(f, "r0", 1, &dq, r0);
  AttrReal(f, "spacedim", (double)p->nc);
  AttrReal(f, "n", (double)p->n);
  AttrReal(f, "step", (double)(fr->step + 1));
  AttrReal(f, "time", (double)(fr->time + dt));
  AttrReal(f, "dt", (double)dt);
  AttrReal(f, "its", (double)res->its);
  AttrReal(f, "solve_time", (double)seconds);
  AttrReal(f, "residual", (double)res->residual);
  AttrText(f, "solver", fr->type);
  st |= H5Fclose(f);
  PetscCall(PetscFree5(W, q, mu, r, r0));
  PetscCheck(st >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "-friction_dump: could not write %s", name);
  PetscFunctionReturn(0);
}
