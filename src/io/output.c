/* Output: the per-step history (CSV), HDF5 fields for ParaView with their XDMF index, and the closing summary.
 *
 * Whatever stops the run, even SIGKILL, what is on disk stays readable and consistent:
 * - history.csv gets each row in one write(), so the rows on disk are whole rows;
 * - solution.h5 stays open for the whole run and is flushed after each snapshot; each checkpoint
 *   keeps a copy of it (checkpoint_snapshots.h5), since a kill while HDF5 writes can spoil the file;
 * - solution.xmf lists only snapshots flushed (at least half of them, all at checkpoints, at the end
 *   and when an error stops the run). It is written beside the old one and renamed over it, so a
 *   reader, or a kill in between, sees the old index or the new one, never part of one.
 * Any failed write, flush or close stops the run with the file's name and the system's reason.
 * Opening the output (at the end of set-up) first moves the last run's files into previous/. */
#define _GNU_SOURCE /* copy_file_range */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>
#include <petscsf.h>
#include <petscviewerhdf5.h>
#include "io.h"
#include "outputimpl.h"

/* the files a run writes (checkpoint.h5 by checkpoint.c): an earlier run's move to previous/ together */
static const char *const MMOutputFiles[] = {"history.csv", "solution.h5", "solution.xmf", "checkpoint.h5", MM_SNAPSHOT_COPY};
#define MM_PREVIOUS "previous"
#define MM_XMF_TMP  ".tmp" /* suffix of the XDMF index being written */

/* Records the failure of the call just made; errno is read before anything can change it. */
PetscErrorCode MMOutputFailed(MMFileStatus *st, const char fmt[], ...)
{
  int            err = errno ? errno : EIO;
  size_t         len;
  va_list        ap;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  ierr = PetscVSNPrintf(st->what, sizeof(st->what), fmt, &len, ap);
  va_end(ap);
  PetscCall(ierr);
  st->err = err;
  PetscFunctionReturn(0);
}

/* Rank 0 did the file system work: every rank learns how it went and stops with the same message,
 * instead of waiting in the next collective for a rank 0 that has stopped. */
PetscErrorCode MMOutputCheckRank0(MMFileStatus *st)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&st->err, 1, MPI_INT, 0, PETSC_COMM_WORLD));
  if (st->err) PetscCallMPI(MPI_Bcast(st->what, sizeof(st->what), MPI_CHAR, 0, PETSC_COMM_WORLD));
  /* err < 0: not a system call's failure, what says it all */
  PetscCheck(st->err >= 0, PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "%s", st->what);
  PetscCheck(!st->err, PETSC_COMM_WORLD, PETSC_ERR_FILE_WRITE, "Could not %s: %s", st->what, strerror(st->err));
  PetscFunctionReturn(0);
}

/* write(2) of the whole buffer: one call unless the system takes only part (a full disk, a signal).
 * 0, or -1 with errno set. */
int MMOutputWriteAll(int fd, const char *buf, size_t len)
{
  while (len) {
    ssize_t n = write(fd, buf, len);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return -1;
    buf += n;
    len -= (size_t)n;
  }
  return 0;
}

/* The system's reason for a failed HDF5 write. Through MPI-IO errno seldom carries it (the write
 * that failed may even have been another rank's), so when it does not, ask the file system: extend
 * the file by a block, as HDF5 was doing, note why that fails, and put the size back. 0: no reason. */
static int SystemReason(const char name[])
{
  static const char zeros[4096];
  struct stat       s;
  int               fd, err = 0;

  if ((fd = open(name, O_WRONLY | O_CLOEXEC)) < 0) return errno;
  if (fstat(fd, &s)) err = errno;
  else {
    if (lseek(fd, 0, SEEK_END) < 0 || MMOutputWriteAll(fd, zeros, sizeof(zeros))) err = errno;
    if (ftruncate(fd, s.st_size) && !err) err = errno;
  }
  (void)close(fd);
  return err;
}

/* PETSc reports a failed HDF5 call without the file's name and H5Fflush/H5Fclose give only a status:
 * run them with PETSc's error printing off, then stop with the file and the reason. Rank-local: the
 * I/O is independent, only the rank whose write failed knows, and its exit ends the job. */
static H5E_auto2_t hdf5_print;      /* HDF5's own error printing, off between Begin and End: */
static void       *hdf5_print_data; /* its stack dump would come before, and bury, the message */

PetscErrorCode MMOutputHDF5Begin(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  PetscCheck(H5Eget_auto2(H5E_DEFAULT, &hdf5_print, &hdf5_print_data) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "H5Eget_auto2 failed");
  PetscCheck(H5Eset_auto2(H5E_DEFAULT, NULL, NULL) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "H5Eset_auto2 failed");
  errno = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode MMOutputHDF5End(PetscErrorCode ierr, const char action[], const char name[])
{
  int         err = errno; /* first: the reason of the failed write, if one failed here */
  const char *text;
  char       *specific;

  PetscFunctionBeginUser;
  PetscCall(PetscPopErrorHandler());
  PetscCheck(H5Eset_auto2(H5E_DEFAULT, hdf5_print, hdf5_print_data) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "H5Eset_auto2 failed");
  if (!ierr) PetscFunctionReturn(0);
  if (!err) err = SystemReason(name);
  PetscCall(PetscErrorMessage(ierr, &text, &specific));
  SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not %s %s: %s (%s)", action, name, err ? strerror(err) : "the system gave no reason", specific && specific[0] ? specific : text);
}

/* An HDF5 file of the run created for writing, its name known to the handler of failed MPI-IO calls
 * (src/sys/errors.c), which stops the job from inside the call that failed. */
PetscErrorCode MMOutputHDF5Create(MPI_Comm comm, const char name[], PetscViewer *viewer)
{
  hid_t          fid;
  MPI_File      *fh = NULL;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(MMErrorsNameMPIIOFile(MPI_FILE_NULL, name));
  PetscCall(MMOutputHDF5Begin());
  ierr = PetscViewerHDF5Open(comm, name, FILE_MODE_WRITE, viewer);
  PetscCall(MMOutputHDF5End(ierr, "create", name));
  PetscCall(PetscViewerHDF5GetFileId(*viewer, &fid));
  if (H5Fget_vfd_handle(fid, H5P_DEFAULT, (void **)&fh) >= 0 && fh) PetscCall(MMErrorsNameMPIIOFile(*fh, name));
  PetscCall(MMErrorsNameMPIIOFile(MPI_FILE_NULL, NULL));
  PetscFunctionReturn(0);
}

/* Closes what MMOutputHDF5Create opened (a close can be where a deferred write fails). */
PetscErrorCode MMOutputHDF5Close(PetscViewer *viewer, const char name[])
{
  hid_t          fid;
  MPI_File      *fh = NULL, handle = MPI_FILE_NULL;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(*viewer, &fid));
  if (H5Fget_vfd_handle(fid, H5P_DEFAULT, (void **)&fh) >= 0 && fh) handle = *fh;
  PetscCall(MMOutputHDF5Begin());
  ierr = PetscViewerDestroy(viewer);
  PetscCall(MMOutputHDF5End(ierr, "close", name));
  if (handle != MPI_FILE_NULL) PetscCall(MMErrorsNameMPIIOFile(handle, NULL));
  PetscFunctionReturn(0);
}

/* The room asked of the file system beyond the output plan's bytes of a write: HDF5 places
 * metadata (chunk indices, heaps, object headers) in blocks of its own beyond the plan's
 * per-dataset average, and a page of tmpfs holds no two files' tails. Measured in
 * docs/full_disk.md. */
#define MM_SPACE_FACTOR 1.25
#define MM_SPACE_EXTRA  (64.0 * 1024)

/* Whether the output directory's file system has room for the next write to name (what: the
 * write, bytes: its size in the output plan, output_plan.c), asked by rank 0 before any rank starts
 * it: when it has not, every rank stops together with status 74, naming the file, and nothing of
 * the write is started. The HDF5 files are written by all ranks at once, inside collective HDF5
 * calls; a write that fails there anyway (another process filled the disk) ends the job from the
 * rank it failed on (src/sys/errors.c), without a hang but with Open MPI's abort banner. This
 * check makes the usual case, a disk this run fills, the collective stop. docs/full_disk.md */
PetscErrorCode MMOutputCheckSpace(const char dir[], const char name[], const char what[], PetscReal bytes)
{
  MMFileStatus   st = {0};
  struct statvfs fs;
  PetscMPIInt    rank;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMIOEvents.space, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank == 0 && statvfs(dir, &fs) == 0) { /* a file system that cannot say is not checked */
    const double need = MM_SPACE_FACTOR * bytes + MM_SPACE_EXTRA, avail = (double)fs.f_bavail * (double)fs.f_frsize;
    if (avail < need) {
      errno = ENOSPC;
      PetscCall(MMOutputFailed(&st, "write %s (%s needs about %.0f kB with HDF5's own data, the file system has %.0f kB free; nothing of it was written)", name, what, need / 1024, avail / 1024));
    }
  }
  PetscCall(MMOutputCheckRank0(&st));
  PetscCall(PetscLogEventEnd(MMIOEvents.space, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MMOutputLineAdd(MMLine *l, const char fmt[], ...)
{
  size_t         len;
  va_list        ap;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  ierr = PetscVSNPrintf(l->s + l->n, sizeof(l->s) - l->n, fmt, &len, ap);
  va_end(ap);
  PetscCall(ierr);
  PetscCall(PetscStrlen(l->s + l->n, &len));
  l->n += len;
  PetscCheck(l->n + 1 < sizeof(l->s), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Output text longer than %d characters", (int)sizeof(l->s) - 2);
  PetscFunctionReturn(0);
}

/* rank 0 writes the line to history.csv; all ranks stop if that failed */
static PetscErrorCode CSVWrite(MMOutput *o, const MMLine *l)
{
  MMFileStatus st = {0};

  PetscFunctionBeginUser;
  if (o->csv_fd >= 0) {
    const off_t end = lseek(o->csv_fd, 0, SEEK_CUR);
    if (MMOutputWriteAll(o->csv_fd, l->s, l->n)) {
      PetscCall(MMOutputFailed(&st, "write %s", o->csv_name));
      /* a full disk or a file-size limit may have taken part of the row: cut it, so that the file
       * ends on the last whole row and no cut number reads as a value */
      if (end >= 0) (void)ftruncate(o->csv_fd, end);
    }
  }
  PetscCall(MMOutputCheckRank0(&st));
  PetscFunctionReturn(0);
}

/* Whether a step's start may move kinetic energy, booked as W_frame: the contact frames follow the
 * contact point (-contact_frames follow on curved obstacles), or M* switches in free flight
 * (-mass_free_flight) */
static PetscBool WorkFrameColumn(const MMOutput *o)
{
  PetscBool follow = PETSC_FALSE, free_on = PETSC_FALSE;

  if (o->contact && MMContactFramesFollow(o->contact, &follow)) return PETSC_FALSE;
  if (o->contact && MMContactMassFreeFlight(o->contact, &free_on, NULL)) return PETSC_FALSE;
  return (PetscBool)(follow || free_on);
}

/* The obstacles with a force column: none without contact (-contact 0), where no obstacle is there. */
static PetscInt ObstacleColumns(const MMOutput *o)
{
  MMContactNodes cn;

  if (!o->contact || MMContactGetNodes(o->contact, &cn) || !cn.enabled) return 0;
  return o->opt->n_obstacles;
}

/* The header of history.csv: its columns depend on the dimension and the obstacles. */
PetscErrorCode MMOutputCSVHeaderLine(const MMOutput *o, MMLine *lp)
{
  const MMIOProblem *opt  = o->opt;
  const char      *axes = "xyz";
  PetscInt         dim  = o->dim;
  MMLine      l    = {.n = 0, .s = ""};

  PetscFunctionBeginUser;
  PetscCall(MMOutputLineAdd(&l, "step,time,dt,kinetic,elastic,total,work_ext,work_contact,work_friction,balance_residual,active,slipping,force_normal,force_tangential,max_penetration,coulomb_residual,vi_its,friction_its,cfl"));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",ucm_%c", axes[d]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",vcm_%c", axes[d]));
  if (dim == 2) PetscCall(MMOutputLineAdd(&l, ",L_z"));
  else PetscCall(MMOutputLineAdd(&l, ",L_x,L_y,L_z"));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",P_%c", axes[d]));
  if (dim == 2) PetscCall(MMOutputLineAdd(&l, ",J_z"));
  else PetscCall(MMOutputLineAdd(&l, ",J_x,J_y,J_z"));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",load_%c", axes[d]));
  PetscCall(MMOutputLineAdd(&l, ",switched,contraction,candidates,candidate_resolves,work_obstacle"));
  for (PetscInt b = 0; b < ObstacleColumns(o); ++b)
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",force_%s_%c", opt->obstacles[b].name, axes[d]));
  PetscCall(MMOutputLineAdd(&l, ",work_damping"));
  /* with Dirichlet boundaries: their work and each one's reaction (docs/method.md section 10) */
  if (opt->n_dirichlet) PetscCall(MMOutputLineAdd(&l, ",work_dirichlet"));
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b)
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",reaction_%s_%c", opt->dirichlet[b].name, axes[d]));
  /* the kinetic energy moved at steps' starts: frames that follow (docs/method.md section 8), M* in free flight (section 2) */
  if (WorkFrameColumn(o)) PetscCall(MMOutputLineAdd(&l, ",work_frame"));
  /* -probes: each group's mean displacement, then velocity (probes.c) */
  for (PetscInt g = 0; g < o->probes.n; ++g) {
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",probe_%s_u%c", o->probes.name[g], axes[d]));
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",probe_%s_v%c", o->probes.name[g], axes[d]));
  }
  PetscCall(MMOutputLineAdd(&l, "\n"));
  *lp = l;
  PetscFunctionReturn(0);
}

static PetscErrorCode CSVHeader(MMOutput *o)
{
  MMLine l;

  PetscFunctionBeginUser;
  PetscCall(MMOutputCSVHeaderLine(o, &l));
  PetscCall(CSVWrite(o, &l));
  PetscFunctionReturn(0);
}

/* A row on disk is a row the user keeps, whatever happens next: written whole, not buffered. The
 * probes' means are of the whole fields in disp_cart and vel_cart, which the caller filled. */
PetscErrorCode MMOutputWriteRow(MMOutput *o)
{
  const MMHistory *h   = o->hist;
  const MMIOProblem *opt = o->opt;
  PetscInt         dim = o->dim;
  MMLine           l   = {.n = 0, .s = ""};

  PetscFunctionBeginUser;
  PetscCall(MMOutputLineAdd(&l, "%" PetscInt_FMT ",%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.6e,%" PetscInt_FMT ",%" PetscInt_FMT ",%.16e,%.16e,%.6e,%.6e,%" PetscInt_FMT ",%" PetscInt_FMT ",%.6e", h->step, (double)h->time, (double)h->dt, (double)h->kinetic, (double)h->elastic, (double)h->total, (double)h->work_ext, (double)h->work_contact, (double)h->work_friction, (double)h->balance_residual, h->active, h->slipping, (double)h->force_normal, (double)h->force_tangential, (double)h->max_penetration, (double)h->coulomb_residual, h->vi_its, h->friction_its, (double)h->cfl));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->ucm[d]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->vcm[d]));
  if (dim == 2) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->L[2]));
  else PetscCall(MMOutputLineAdd(&l, ",%.16e,%.16e,%.16e", (double)h->L[0], (double)h->L[1], (double)h->L[2]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->P[d]));
  if (dim == 2) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->J[2]));
  else PetscCall(MMOutputLineAdd(&l, ",%.16e,%.16e,%.16e", (double)h->J[0], (double)h->J[1], (double)h->J[2]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->load[d]));
  PetscCall(MMOutputLineAdd(&l, ",%" PetscInt_FMT ",%.6e,%" PetscInt_FMT ",%" PetscInt_FMT ",%.16e", h->switched, (double)h->contraction, h->candidates, h->resolves, (double)h->work_obstacle));
  for (PetscInt b = 0; b < ObstacleColumns(o); ++b) {
    PetscReal force[MM_MAX_DIM];
    PetscCall(MMContactGetObstacleForce(o->contact, b, force));
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)force[d]));
  }
  PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->work_damping));
  if (opt->n_dirichlet) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->work_dirichlet));
  for (PetscInt b = 0; b < opt->n_dirichlet; ++b)
    for (PetscInt d = 0; d < dim; ++d) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)o->loads->reaction[MM_MAX_DIM * b + d]));
  if (WorkFrameColumn(o)) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)h->work_frame));
  PetscCall(MMProbesEvaluate(o));
  for (PetscInt k = 0; k < 2 * dim * o->probes.n; ++k) PetscCall(MMOutputLineAdd(&l, ",%.16e", (double)o->probes.mean[k]));
  PetscCall(MMOutputLineAdd(&l, "\n"));
  PetscCall(CSVWrite(o, &l));
  PetscFunctionReturn(0);
}

void MMOutputSnapshotFields(MMOutput *o, PetscInt dim, MMSnapshotField f[MM_SNAPSHOT_FIELDS])
{
  const MMSnapshotField all[MM_SNAPSHOT_FIELDS] = {
    {"displacement", "displacement_displacement", dim, o->disp_cart, o->dm_out},
    {"velocity", "velocity_displacement", dim, o->vel_cart, o->dm_out},
    {"contact_pressure", "contact_pressure_nodal", 1, o->pressure, o->dm_scalar},
    {"gap", "gap_nodal", 1, o->gap, o->dm_scalar},
    {"tangential_traction", "tangential_traction_displacement", dim, o->traction_t, o->dm_out},
    {"slip_velocity", "slip_velocity_displacement", dim, o->slip, o->dm_out},
    {"stress", "stress_stress", 6, o->stress.nodal, o->stress.dm},
    {"von_mises", "von_mises_nodal", 1, o->stress.von_mises, o->dm_scalar},
    {"stress_cell", "stress_cell", 6, o->stress.cell, NULL},
    {"von_mises_cell", "von_mises_cell", 1, o->stress.von_mises_cell, NULL},
  };
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) f[i] = all[i];
}

/* rank 0: the grid of snapshot k, at time t, added to the index text kept in memory. Each field is
 * the snapshot's view of it (output_views.c), a dataset that both of ParaView's XDMF readers read.
 * The output plan measures a grid with it (output_plan.c). */
PetscErrorCode MMOutputIndexAddGrid(MMOutput *o, PetscInt dim, PetscInt k, PetscReal t)
{
  const char    *h5base     = "solution.h5";
  const PetscInt nv = o->nv, nc = o->nc;
  MMLine         l = {.n = 0, .s = ""};
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];

  PetscFunctionBeginUser;
  MMOutputSnapshotFields(o, dim, f);
  PetscCall(MMOutputLineAdd(&l, "<Grid Name=\"step %" PetscInt_FMT "\" GridType=\"Uniform\">\n<Time Value=\"%.16e\"/>\n", k, (double)t));
  PetscCall(MMOutputLineAdd(&l, "<Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n</Topology>\n", dim == 2 ? "Triangle" : "Tetrahedron", nc, nc, dim + 1, h5base));
  PetscCall(MMOutputLineAdd(&l, "<Geometry GeometryType=\"%s\">\n<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n</Geometry>\n", dim == 2 ? "XY" : "XYZ", nv, dim, h5base));
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) {
    const PetscInt n = f[i].dm ? nv : nc, nview = MMOutputViewComponents(f[i].ncomp);
    char           path[PETSC_MAX_PATH_LEN], dims[64];

    PetscCall(MMOutputViewPath(k, f[i].name, path, sizeof(path)));
    if (nview > 1) PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT " %" PetscInt_FMT, n, nview));
    else PetscCall(PetscSNPrintf(dims, sizeof(dims), "%" PetscInt_FMT, n));
    PetscCall(MMOutputLineAdd(&l, "<Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", f[i].name, nview == 9 ? "Tensor" : nview > 1 ? "Vector" : "Scalar", f[i].dm ? "Node" : "Cell"));
    PetscCall(MMOutputLineAdd(&l, "<DataItem Dimensions=\"%s\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n</Attribute>\n", dims, h5base, path));
  }
  PetscCall(MMOutputLineAdd(&l, "<Attribute Name=\"contact_obstacle\" AttributeType=\"Scalar\" Center=\"Node\">\n<DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/contact_obstacle_nodal</DataItem>\n</Attribute>\n", nv, h5base));
  PetscCall(MMOutputLineAdd(&l, "</Grid>\n"));
  if (o->index_len + l.n + 1 > o->index_cap) {
    o->index_cap = 2 * (o->index_len + l.n + 1);
    PetscCall(PetscRealloc(o->index_cap, &o->index));
  }
  PetscCall(PetscMemcpy(o->index + o->index_len, l.s, l.n));
  o->index_len += l.n;
  PetscFunctionReturn(0);
}

/* The index text around its grids */
static const char MMIndexHead[] = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"2.99\">\n<Domain>\n"
                                  "<Grid Name=\"mmcontact\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
static const char MMIndexTail[] = "</Grid>\n</Domain>\n</Xdmf>\n";

/* The bytes of the index text around its grids, for the output plan (output_plan.c). */
size_t MMOutputIndexFrameBytes(void)
{
  return sizeof(MMIndexHead) - 1 + sizeof(MMIndexTail) - 1;
}

/* rank 0: the index text. Errors are collected by the stream (ferror). */
static void IndexPrint(FILE *f, const MMOutput *o)
{
  fputs(MMIndexHead, f);
  (void)fwrite(o->index, 1, o->index_len, f);
  fputs(MMIndexTail, f);
}

/* rank 0: the index text whole to tmp, renamed over solution.xmf: 0, or the errno of the step that
 * failed (*what: "create", "write", "close" or "rename"), tmp removed (part of an index, or none: of
 * no use to anyone). Plain C: the error handler runs it too (IndexAtStop). Not fsync'd: this guards
 * against the process dying, not the machine. */
static int IndexReplace(const MMOutput *o, const char tmp[], const char **what)
{
  FILE *f;
  int   err = 0;

  errno = 0;
  *what = "create";
  if (!(f = fopen(tmp, "w"))) err = errno ? errno : EIO;
  else {
    IndexPrint(f, o);
    if (ferror(f) || fflush(f)) {
      err   = errno ? errno : EIO;
      *what = "write";
      (void)fclose(f);
    } else if (fclose(f)) {
      err   = errno ? errno : EIO;
      *what = "close";
    } else if (rename(tmp, o->xmf_name)) {
      err   = errno ? errno : EIO;
      *what = "rename";
    }
  }
  if (err) (void)unlink(tmp);
  return err;
}

/* The XDMF index, rewritten on rank 0: whole to solution.xmf.tmp, then renamed over solution.xmf. */
PetscErrorCode MMOutputWriteIndexFile(MMOutput *o)
{
  MMFileStatus st = {0};
  char         tmp[PETSC_MAX_PATH_LEN];
  PetscMPIInt  rank;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMIOEvents.index, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", o->xmf_name, MM_XMF_TMP));
  if (rank == 0) {
    const char *what;
    if ((errno = IndexReplace(o, tmp, &what))) {
      if (!strcmp(what, "rename")) PetscCall(MMOutputFailed(&st, "rename %s to %s", tmp, o->xmf_name));
      else PetscCall(MMOutputFailed(&st, "%s %s", what, tmp));
    }
  }
  PetscCall(MMOutputCheckRank0(&st));
  o->n_indexed = o->n_written;
  PetscCall(PetscLogEventEnd(MMIOEvents.index, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The output whose index a run stopped by an error still writes: set on rank 0 while the files are
 * open (MMOutputOpenFiles to MMOutputDestroy). */
static MMOutput *index_at_stop = NULL;

/* Whatever error stops the run (status 64, 65, 74, src/sys/errors.c), the index lists every snapshot
 * flushed: between its rewrites (WriteIndex) it may list as few as half of them. Each is listed
 * only once flushed (MMOutputWriteSnapshot), and a full disk stops the run before the next write
 * of solution.h5 starts (MMOutputCheckSpace), with the room for this index kept
 * (MMOutputIndexRoom). Plain C, run by the error handler on rank 0. */
static void IndexAtStop(void)
{
  MMOutput   *o = index_at_stop;
  char        tmp[PETSC_MAX_PATH_LEN];
  const char *what;

  if (!o || o->n_indexed >= o->n_written) return;
  if (snprintf(tmp, sizeof(tmp), "%s%s", o->xmf_name, MM_XMF_TMP) >= (int)sizeof(tmp)) return;
  if (!IndexReplace(o, tmp, &what)) o->n_indexed = o->n_written;
}

/* From here on an error stop writes o's index (on rank 0, which holds its text). */
static PetscErrorCode IndexAtStopSet(MMOutput *o)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank) index_at_stop = o;
  PetscCall(MMErrorsAtStop(IndexAtStop));
  PetscFunctionReturn(0);
}

/* rank 0: the bytes of an index that lists one more snapshot, written beside the one on disk. Each
 * check of the free space before a write of solution.h5 or the checkpoint (MMOutputCheckSpace)
 * counts it, so that the index listing every snapshot that write completes still fits, even when
 * the next check stops the run (IndexAtStop writes it then). A grid's text is the same but for
 * its number's digits: twice the mean grid covers one more. */
PetscReal MMOutputIndexRoom(const MMOutput *o)
{
  const PetscReal grid = o->n_written ? (PetscReal)o->index_len / (PetscReal)o->n_written : 4096;
  return (PetscReal)(o->index_len + MMOutputIndexFrameBytes()) + 2 * grid;
}

/* The index gains the snapshot just flushed. The file is rewritten whole and renamed into place,
 * so that a reader never sees part of it: after every snapshot that would be O(N^2) bytes over a run of N snapshots. It is rewritten when the snapshots have doubled since the
 * last time (O(N) bytes in all), by MMOutputSyncIndex at every checkpoint and at the end of the
 * run, and by IndexAtStop when an error stops it: while the run goes on it lists at least half of
 * the snapshots written, all of them up to the last checkpoint (README "Output"). */
static PetscErrorCode WriteIndex(MMOutput *o)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank == 0) PetscCall(MMOutputIndexAddGrid(o, o->dim, o->n_written - 1, o->times[o->n_written - 1]));
  if (o->n_written >= 2 * o->n_indexed) PetscCall(MMOutputWriteIndexFile(o));
  PetscFunctionReturn(0);
}

/*@
  MMOutputSyncIndex - Rewrites the XDMF index so that it lists every snapshot written

  Collective

  Input Parameter:
. o - the output object

  Level: developer

.seealso: `MMOutputCopySnapshots()`, `MMCheckpointWrite()`
@*/
PetscErrorCode MMOutputSyncIndex(MMOutput *o)
{
  PetscFunctionBeginUser;
  if (o->n_indexed < o->n_written) PetscCall(MMOutputWriteIndexFile(o));
  PetscFunctionReturn(0);
}

/* Everything written to solution.h5 so far goes to disk: after this the index may list it. */
PetscErrorCode MMOutputFlushFields(MMOutput *o)
{
  hid_t  fid;
  herr_t status;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMIOEvents.flush, 0, 0, 0, 0));
  PetscCall(PetscViewerHDF5GetFileId(o->h5, &fid));
  errno  = 0;
  status = H5Fflush(fid, H5F_SCOPE_GLOBAL);
  if (status < 0) {
    int err = errno ? errno : SystemReason(o->h5_name);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not flush %s: %s (H5Fflush failed)", o->h5_name, err ? strerror(err) : "the system gave no reason");
  }
  PetscCall(PetscLogEventEnd(MMIOEvents.flush, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* rank 0: src copied whole to dst (through dst.tmp, renamed when whole), by the kernel where it can. */
static PetscErrorCode CopyFile(const char src[], const char dst[], MMFileStatus *st)
{
  char  tmp[PETSC_MAX_PATH_LEN], buf[1 << 16];
  int   in, out;
  off_t left;
  struct stat s;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", dst, MM_XMF_TMP));
  if ((in = open(src, O_RDONLY | O_CLOEXEC)) < 0 || fstat(in, &s)) {
    PetscCall(MMOutputFailed(st, "read %s to copy its snapshots", src));
    if (in >= 0) close(in);
    PetscFunctionReturn(0);
  }
  if ((out = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) < 0) {
    PetscCall(MMOutputFailed(st, "create %s", tmp));
    close(in);
    PetscFunctionReturn(0);
  }
  for (left = s.st_size; left > 0;) {
    ssize_t n = copy_file_range(in, NULL, out, NULL, (size_t)left, 0);
    if (n < 0 && (errno == ENOSYS || errno == EXDEV || errno == EINVAL || errno == EOPNOTSUPP)) { /* a file system without it */
      n = read(in, buf, sizeof(buf));
      if (n > 0 && MMOutputWriteAll(out, buf, (size_t)n)) n = -1;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    left -= n;
  }
  if (left > 0) PetscCall(MMOutputFailed(st, "copy %s to %s", src, tmp));
  if (close(out) && !st->err) PetscCall(MMOutputFailed(st, "close %s", tmp));
  close(in);
  if (!st->err && rename(tmp, dst)) PetscCall(MMOutputFailed(st, "rename %s to %s", tmp, dst));
  if (st->err) (void)unlink(tmp);
  PetscFunctionReturn(0);
}

/*@
  MMOutputCopySnapshots - Copies solution.h5 for the checkpoint, once every snapshot up to it is on
  disk

  Collective

  Input Parameter:
. o - the output object

  Note:
  solution.h5 is written in place, and HDF5 rewrites its index as it grows: a run killed while it
  writes a snapshot can leave the whole file unreadable. So a checkpoint keeps a copy of it, taken
  when every snapshot up to the checkpoint is on disk; -restart reads the earlier snapshots from the
  copy (docs/method.md section 9). Collective.

  Level: developer

.seealso: `MMCheckpointWrite()`, `MMOutputSyncIndex()`
@*/
PetscErrorCode MMOutputCopySnapshots(MMOutput *o)
{
  MMFileStatus st = {0};
  char         dst[PETSC_MAX_PATH_LEN];
  PetscMPIInt  rank;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MMIOEvents.copy, 0, 0, 0, 0));
  PetscCall(MMOutputFlushFields(o));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscSNPrintf(dst, sizeof(dst), "%s/%s", o->dir, MM_SNAPSHOT_COPY));
  if (!rank) PetscCall(CopyFile(o->h5_name, dst, &st));
  PetscCall(MMOutputCheckRank0(&st));
  PetscCall(PetscLogEventEnd(MMIOEvents.copy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* After a clean close solution.h5 is whole and holds every snapshot of the last checkpoint: the copy
 * is not needed any more, once that checkpoint c is of the last step. */
static PetscErrorCode DropSnapshotCopy(const MMOutput *o, const MMCheckpoint *c, PetscInt step)
{
  char        dst[PETSC_MAX_PATH_LEN];
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank || !c->written || c->last_step != step) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(dst, sizeof(dst), "%s/%s", o->dir, MM_SNAPSHOT_COPY));
  (void)unlink(dst);
  PetscFunctionReturn(0);
}

/* Each vertex's position among the mesh file's nodes (from 0): PETSc writes the vertices in the
 * partition's order, so this is what matches a vertex across runs on other rank counts, to the
 * file (and -restart's copy of the earlier snapshots). */
static PetscErrorCode SerialVertexField(const MMOutput *o, Vec f)
{
  const MMCheckpoint *c = o->ckpt;
  PetscSection gs;
  PetscInt     vStart, vEnd, rstart;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(o->dm_scalar, &gs));
  PetscCall(DMPlexGetDepthStratum(o->dm_scalar, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(f, &rstart, NULL));
  PetscCall(VecGetArray(f, &a));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff >= 0) a[goff - rstart] = (PetscScalar)c->vertex_file[c->vertex_orig[v - vStart]];
  }
  PetscCall(VecRestoreArray(f, &a));
  PetscFunctionReturn(0);
}

/* One dataset under group: v's entries in the order of its global vector, which for the output
 * DMs (one field, dofs on the vertices only) is the order of the XDMF geometry's vertices, and for
 * a cell field that of the topology's cells; with a time index when step >= 0. VecView of a DM
 * vector would write the field twice, in the section's layout under /fields and again under
 * /vertex_fields: the XDMF index and the restart read only the second, so only it is written, from
 * the same array through a vector without a DM. */
static PetscErrorCode ViewDataset(PetscViewer viewer, const char group[], const char name[], Vec v, PetscInt ncomp, PetscInt step)
{
  Vec                w;
  const PetscScalar *a;
  PetscInt           n, N;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetSize(v, &N));
  PetscCall(VecGetArrayRead(v, &a));
  PetscCall(VecCreateMPIWithArray(PetscObjectComm((PetscObject)v), ncomp, n, N, a, &w));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  PetscCall(PetscViewerHDF5PushGroup(viewer, group));
  PetscCall(MMOutputWriteDataset(viewer, w, step, ncomp > 1 ? "vector" : "scalar"));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&w));
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

/* /time[step] = t: one entry, written by rank 0. */
static PetscErrorCode ViewTime(PetscViewer viewer, PetscInt step, PetscReal t)
{
  Vec         stamp;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)viewer), &rank));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)viewer), rank ? 0 : 1, 1, &stamp));
  PetscCall(PetscObjectSetName((PetscObject)stamp, "time"));
  if (!rank) PetscCall(VecSetValue(stamp, 0, t, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(stamp));
  PetscCall(VecAssemblyEnd(stamp));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/"));
  PetscCall(MMOutputWriteDataset(viewer, stamp, step, NULL));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(VecDestroy(&stamp));
  PetscFunctionReturn(0);
}

/* Snapshot step at time t: /time, then each field once (a failed write returns its error, for the
 * caller's MMOutputHDF5End to name the file). */
PetscErrorCode MMOutputViewSnapshot(MMOutput *o, PetscViewer viewer, PetscInt step, PetscReal t)
{
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];
  PetscInt        dim;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(o->dm_scalar, &dim));
  MMOutputSnapshotFields(o, dim, f);
  PetscCall(ViewTime(viewer, step, t));
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) PetscCall(ViewDataset(viewer, f[i].dm ? "/vertex_fields" : "/cell_fields", f[i].dataset, f[i].vec, f[i].ncomp, step));
  PetscCall(MMOutputCreateViews(viewer, f, step));
  PetscFunctionReturn(0);
}

/* The fields without a time index, written once with the first snapshot: each contact node's
 * obstacle, fixed at set-up (docs/method.md section 8) and filled when the output opens, which every
 * snapshot's grid refers to, and each vertex's serial number. */
PetscErrorCode MMOutputWriteStaticFields(MMOutput *o)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(SerialVertexField(o, o->serial));
  PetscCall(MMOutputHDF5Begin());
  ierr = ViewDataset(o->h5, "/vertex_fields", "contact_obstacle_nodal", o->obstacle, 1, -1);
  if (!ierr) ierr = ViewDataset(o->h5, "/vertex_fields", "serial_vertex_nodal", o->serial, 1, -1);
  PetscCall(MMOutputHDF5End(ierr, "write", o->h5_name));
  o->static_written = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Room for snapshot n_written, and for the index that will list it; the first also writes the
 * fields written once, counted with the mesh. */
static PetscErrorCode CheckSnapshotSpace(const MMOutput *o)
{
  char what[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(what, sizeof(what), "snapshot %" PetscInt_FMT, o->n_written));
  PetscCall(MMOutputCheckSpace(o->dir, o->h5_name, what, o->snapshot_bytes + (o->static_written ? 0 : o->mesh_bytes) + MMOutputIndexRoom(o)));
  PetscFunctionReturn(0);
}

/* Writes the fields the caller filled as snapshot n_written at time t, flushes them, and only then
 * indexes them. */
PetscErrorCode MMOutputWriteSnapshot(MMOutput *o, PetscReal t)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(CheckSnapshotSpace(o));
  if (!o->static_written) PetscCall(MMOutputWriteStaticFields(o));
  /* /time is written ahead of the fields: the index, not /time, says what is complete */
  PetscCall(MMOutputHDF5Begin());
  ierr = MMOutputViewSnapshot(o, o->h5, o->n_written, t);
  PetscCall(MMOutputHDF5End(ierr, "write", o->h5_name));
  PetscCall(MMOutputFlushFields(o));
  PetscCall(PetscRealloc(sizeof(PetscReal) * (o->n_written + 1), &o->times));
  o->times[o->n_written++] = t;
  PetscCall(WriteIndex(o));
  PetscFunctionReturn(0);
}

/* rank 0, mkdir -p: each missing component of the path; then the path must be a directory */
PetscErrorCode MMOutputMakeDirectories(const char path[], MMFileStatus *st)
{
  char        dir[PETSC_MAX_PATH_LEN];
  size_t      len;
  struct stat s;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(dir, path, sizeof(dir)));
  PetscCall(PetscStrlen(dir, &len));
  for (size_t i = 1; i <= len; ++i) {
    if (dir[i] != '/' && dir[i] != 0) continue;
    dir[i] = 0;
    /* EEXIST may also be a file in the way: stat() below says so */
    if (mkdir(dir, 0777) && errno != EEXIST) {
      PetscCall(MMOutputFailed(st, "create the output directory %s", dir));
      PetscFunctionReturn(0);
    }
    if (i < len) dir[i] = '/';
  }
  if (stat(path, &s)) PetscCall(MMOutputFailed(st, "use the output directory %s", path));
  else if (!S_ISDIR(s.st_mode)) {
    errno = ENOTDIR;
    PetscCall(MMOutputFailed(st, "use the output directory %s", path));
  }
  PetscFunctionReturn(0);
}

/* rank 0: the last run's files move to DIR/previous/, replacing the set there, so that they survive
 * this run whatever happens to it. Symbolic links move as links: what they point to is not touched. */
PetscErrorCode MMOutputKeepPrevious(const char dir[], MMFileStatus *st)
{
  const PetscInt n = sizeof(MMOutputFiles) / sizeof(MMOutputFiles[0]);
  char           prev[PETSC_MAX_PATH_LEN], from[PETSC_MAX_PATH_LEN], to[PETSC_MAX_PATH_LEN];
  PetscBool      has[sizeof(MMOutputFiles) / sizeof(MMOutputFiles[0])], any = PETSC_FALSE;
  struct stat    s;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; ++i) {
    PetscCall(PetscSNPrintf(from, sizeof(from), "%s/%s", dir, MMOutputFiles[i]));
    has[i] = lstat(from, &s) == 0 ? PETSC_TRUE : PETSC_FALSE;
    any    = (PetscBool)(any || has[i]);
  }
  if (!any) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(prev, sizeof(prev), "%s/%s", dir, MM_PREVIOUS));
  if (mkdir(prev, 0777) && errno != EEXIST) {
    PetscCall(MMOutputFailed(st, "create %s for the earlier results", prev));
    PetscFunctionReturn(0);
  }
  /* the older set goes whole, so previous/ never mixes two runs */
  for (PetscInt i = 0; i < n; ++i) {
    PetscCall(PetscSNPrintf(to, sizeof(to), "%s/%s", prev, MMOutputFiles[i]));
    if (unlink(to) && errno != ENOENT) {
      PetscCall(MMOutputFailed(st, "remove the older %s", to));
      PetscFunctionReturn(0);
    }
  }
  for (PetscInt i = 0; i < n; ++i) {
    if (!has[i]) continue;
    PetscCall(PetscSNPrintf(from, sizeof(from), "%s/%s", dir, MMOutputFiles[i]));
    PetscCall(PetscSNPrintf(to, sizeof(to), "%s/%s", prev, MMOutputFiles[i]));
    if (rename(from, to)) {
      PetscCall(MMOutputFailed(st, "move the earlier %s to %s", from, to));
      PetscFunctionReturn(0);
    }
  }
  PetscFunctionReturn(0);
}

static PetscBool SameDirectory(const char a[], const char b[])
{
  char ra[PATH_MAX], rb[PATH_MAX];
  return (PetscBool)(realpath(a, ra) && realpath(b, rb) && !strcmp(ra, rb));
}

/* The output directory exists, holds none of this run's names (or, on -restart, the files it
 * continues), and history.csv is open on rank 0. */
static PetscErrorCode OpenDirectoryAndHistory(MMOutput *o)
{
  const MMCheckpoint *c  = o->ckpt;
  MMFileStatus        st = {0};
  PetscMPIInt  rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  o->csv_fd = -1;
  if (rank == 0) {
    PetscCall(MMOutputMakeDirectories(o->dir, &st));
    /* a restart continues the files of its checkpoint's directory: only another run's move away */
    if (!st.err && !(c->restarted && SameDirectory(o->dir, c->source_dir))) PetscCall(MMOutputKeepPrevious(o->dir, &st));
    if (!st.err && c->restarted) PetscCall(MMOutputRestartHistory(o, &st));
    else if (!st.err && (o->csv_fd = open(o->csv_name, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) < 0) PetscCall(MMOutputFailed(&st, "create %s", o->csv_name));
  }
  PetscCall(MMOutputCheckRank0(&st));
  PetscFunctionReturn(0);
}

/* Global vertex and cell counts, for the XDMF index. */
static PetscErrorCode CountMesh(MMOutput *o)
{
  DM              dm = o->dm;
  PetscSF         sf;
  PetscInt        vStart, vEnd, cStart, cEnd, nleaves, loc[2], glob[2];
  const PetscInt *leaves;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  loc[0] = vEnd - vStart;
  for (PetscInt l = 0; l < nleaves; ++l) {
    const PetscInt p = leaves ? leaves[l] : l;
    if (p >= vStart && p < vEnd) --loc[0];
  }
  loc[1] = cEnd - cStart;
  PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  o->nv = glob[0];
  o->nc = glob[1];
  PetscFunctionReturn(0);
}

/* solution.h5 with the mesh, on disk; the viewer stays open for the snapshots. */
static PetscErrorCode OpenFields(MMOutput *o)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(MMOutputCheckSpace(o->dir, o->h5_name, "the mesh", o->mesh_bytes));
  PetscCall(MMOutputHDF5Create(PETSC_COMM_WORLD, o->h5_name, &o->h5));
  PetscCall(PetscViewerPushFormat(o->h5, PETSC_VIEWER_HDF5_XDMF));
  PetscCall(MMOutputHDF5Begin());
  ierr = MMOutputWriteMesh(o->op, o->h5);
  PetscCall(MMOutputHDF5End(ierr, "write", o->h5_name));
  PetscCall(MMOutputFlushFields(o));
  PetscCall(CountMesh(o));
  PetscFunctionReturn(0);
}

/* The output vectors: Cartesian fields on a copy of the mesh without constraints, scalars per vertex. */
static PetscErrorCode CreateFieldVectors(MMOutput *o)
{
  PetscFE      fe;
  PetscSection s;
  const char  *names[] = {"displacement_x", "displacement_y", "displacement_z"};

  PetscFunctionBeginUser;
  PetscCall(DMClone(o->dm, &o->dm_out));
  PetscCall(PetscFECreateLagrange(PETSC_COMM_WORLD, o->dim, o->dim, PETSC_TRUE, 1, PETSC_DETERMINE, &fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "displacement"));
  PetscCall(DMSetField(o->dm_out, 0, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  PetscCall(DMCreateDS(o->dm_out));
  PetscCall(DMGetLocalSection(o->dm_out, &s));
  for (PetscInt c = 0; c < o->dim; ++c) PetscCall(PetscSectionSetComponentName(s, 0, c, names[c]));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->disp_cart));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->vel_cart));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->traction_t));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->slip));
  PetscCall(PetscObjectSetName((PetscObject)o->traction_t, "tangential_traction"));
  PetscCall(PetscObjectSetName((PetscObject)o->slip, "slip_velocity"));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->pressure));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->gap));
  PetscCall(PetscObjectSetName((PetscObject)o->disp_cart, "displacement"));
  PetscCall(PetscObjectSetName((PetscObject)o->vel_cart, "velocity"));
  PetscCall(PetscObjectSetName((PetscObject)o->pressure, "contact_pressure"));
  PetscCall(PetscObjectSetName((PetscObject)o->gap, "gap"));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->obstacle));
  PetscCall(PetscObjectSetName((PetscObject)o->obstacle, "contact_obstacle"));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->serial));
  PetscCall(PetscObjectSetName((PetscObject)o->serial, "serial_vertex"));
  PetscFunctionReturn(0);
}

/* The HDF5 files are opened through MPI-IO, and Open MPI 4.1's shared-file-pointer component
 * (sharedfp/lockedfile) copies the file name and a suffix into a buffer of 256 characters: a longer
 * name aborts the process inside the open (SIGABRT, "buffer overflow detected"), after the earlier
 * results have been moved to previous/. So the names are checked with the other options, as
 * given (a relative name reaches MPI-IO relative), with a margin for the suffix. */
#define MM_MPIIO_NAME_MAX 220

/*@
  MMOutputCheckHDF5Path - Refuses a path too long for the HDF5 files opened under it through MPI-IO

  Collective

  Input Parameters:
+ comm    - the run's communicator
. option  - the option that named the path, for the message
. path    - the path as given
- longest - the longest name that will be appended to it

  Level: developer

.seealso: `MMOutputSetFromOptions()`, `MMCheckpointSetFromOptions()`
@*/
PetscErrorCode MMOutputCheckHDF5Path(MPI_Comm comm, const char option[], const char path[], const char longest[])
{
  size_t len, extra;

  PetscFunctionBeginUser;
  PetscCall(PetscStrlen(path, &len));
  PetscCall(PetscStrlen(longest, &extra));
  PetscCheck(len + extra <= MM_MPIIO_NAME_MAX, comm, PETSC_ERR_USER_INPUT, "%s %s is %d characters long; the HDF5 files under it need names of at most %d characters (Open MPI's file open fails beyond), so it can have at most %d. Give a shorter path, for example a relative one or a symbolic link to the directory", option, path, (int)len, MM_MPIIO_NAME_MAX, (int)(MM_MPIIO_NAME_MAX - extra));
  PetscFunctionReturn(0);
}

/* -output_dir must name a directory whose files' names fit: checked with the options, long before
 * the output is opened. */
static PetscErrorCode CheckDirectory(MPI_Comm comm, const char dir[])
{
  size_t len;

  PetscFunctionBeginUser;
  PetscCall(PetscStrlen(dir, &len));
  PetscCheck(len > 0, comm, PETSC_ERR_USER_INPUT, "-output_dir is empty: name the directory for history.csv, solution.h5 and solution.xmf (\".\" for the current one)");
  /* room for the longest name written under it, and for Open MPI's file open (MMOutputCheckHDF5Path) */
  PetscCheck(len + sizeof("/" MM_PREVIOUS "/solution.xmf" MM_XMF_TMP) <= PETSC_MAX_PATH_LEN, comm, PETSC_ERR_USER_INPUT, "-output_dir %s is too long (%d characters at most)", dir, (int)(PETSC_MAX_PATH_LEN - sizeof("/" MM_PREVIOUS "/solution.xmf" MM_XMF_TMP)));
  PetscCall(MMOutputCheckHDF5Path(comm, "-output_dir", dir, "/checkpoint.h5.tmp"));
  PetscFunctionReturn(0);
}

/*@
  MMOutputSetFromOptions - Reads the output's options (README "Output"), each with its check

  Collective

  Input Parameters:
+ comm - the run's communicator
- o    - the output object, zeroed

  Level: intermediate

.seealso: `MMOutputSetUp()`, `MMOutputOpen()`, `MMOutputDestroy()`
@*/
PetscErrorCode MMOutputSetFromOptions(MPI_Comm comm, MMOutput *o)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact output", "MMOutput");
  PetscCall(PetscStrcpy(o->dir, "output"));
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-output_dir", "Directory for history.csv, solution.h5 and solution.xmf (created if missing; not empty)", o->dir, sizeof(o->dir), NULL));
  o->every = 10;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-output_every", "Write the HDF5 fields every k steps (0: only the initial and final state)", &o->every));
  o->interval = 0;
  PetscCall(MMOptionsReal(PetscOptionsObject, comm, "-output_interval", "Write the HDF5 fields at t = 0, T, 2T, ... (at the first step whose time reaches k T, to 1e-9 dt) and the final state; T > 0 replaces -output_every (0: by steps)", &o->interval));
  o->history_every = 1;
  PetscCall(MMOptionsInt(PetscOptionsObject, comm, "-history_every", "Write a history.csv row every N steps (step 0, N, 2N, ...) and at the last step, >= 1", &o->history_every));
  o->probe_list[0] = 0;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-probes", "Comma-separated physical groups whose mean displacement and velocity (weighted by the nodes' lumped mass) go to history.csv as probe_NAME_ux, ..., probe_NAME_vx, ...", o->probe_list, sizeof(o->probe_list), NULL));
  PetscOptionsEnd();
  PetscCheck(o->every >= 0, comm, PETSC_ERR_USER_INPUT, "-output_every %" PetscInt_FMT " must be >= 0", o->every);
  PetscCheck(o->interval >= 0, comm, PETSC_ERR_USER_INPUT, "-output_interval %g must be >= 0: it is the simulated time between snapshots (0: every -output_every steps)", (double)o->interval);
  PetscCheck(o->history_every >= 1, comm, PETSC_ERR_USER_INPUT, "-history_every %" PetscInt_FMT " must be >= 1: it is the number of steps between history rows", o->history_every);
  PetscCall(CheckDirectory(comm, o->dir));
  PetscFunctionReturn(0);
}

/*@
  MMOutputSetUp - Gives the output the objects it writes from, borrowed until it is destroyed (as
  KSPSetOperators() does)

  Logically collective

  Input Parameters:
+ o        - the output object
. opt      - the problem as io needs it (MMOptionsGetIOProblem())
. op       - fem's operators
. material - the bodies' material
. hist     - the stepper's history row
. state    - the stepper's state
. contact  - the contact object
. loads    - the loads
- ckpt     - the checkpoint, whose copy of solution.h5 a restart reads

  Level: intermediate

.seealso: `MMOutputSetFromOptions()`, `MMOutputOpen()`, `MMOutputMonitor()`
@*/
PetscErrorCode MMOutputSetUp(MMOutput *o, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, const MMHistory *hist, const MMState *state, MMContact contact, MMLoads *loads, MMCheckpoint *ckpt)
{
  PetscFunctionBeginUser;
  o->opt      = opt;
  o->op       = op;
  o->material = material;
  o->hist     = hist;
  o->state    = state;
  o->contact = contact;
  o->loads   = loads;
  o->ckpt      = ckpt;
  PetscCall(MMFEGetDM(op, &o->dm));
  PetscCall(MMFEGetDimension(op, &o->dim));
  PetscCall(MMFEGetScalarDM(op, &o->dm_scalar)); /* fem's: one scalar per vertex */
  PetscFunctionReturn(0);
}

/* Called last in set-up, once all input is valid: from here on the earlier results are in previous/.
 * history.csv is open and, unless the run restarts (output_restart.c), solution.h5 holds the mesh;
 * the field vectors exist. */
PetscErrorCode MMOutputOpenFiles(MMOutput *o)
{
  const char *dir = o->dir;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(o->csv_name, sizeof(o->csv_name), "%s/%s", dir, MMOutputFiles[0]));
  PetscCall(PetscSNPrintf(o->h5_name, sizeof(o->h5_name), "%s/%s", dir, MMOutputFiles[1]));
  PetscCall(PetscSNPrintf(o->xmf_name, sizeof(o->xmf_name), "%s/%s", dir, MMOutputFiles[2]));
  PetscCall(OpenDirectoryAndHistory(o));
  PetscCall(MMOutputPlanWrites(o));
  if (o->ckpt->restarted) {
    PetscCall(CountMesh(o));
    PetscCall(CreateFieldVectors(o));
  } else {
    PetscCall(CSVHeader(o));
    PetscCall(OpenFields(o));
    PetscCall(CreateFieldVectors(o));
  }
  PetscCall(IndexAtStopSet(o));
  PetscFunctionReturn(0);
}

/* Closing reports errors too: a close can be where a deferred write fails. */
static PetscErrorCode CloseFiles(MMOutput *o)
{
  MMFileStatus st = {0};

  PetscFunctionBeginUser;
  if (o->csv_fd >= 0 && close(o->csv_fd)) PetscCall(MMOutputFailed(&st, "close %s", o->csv_name));
  o->csv_fd = -1;
  PetscCall(MMOutputCheckRank0(&st));
  PetscCall(PetscViewerPopFormat(o->h5));
  PetscCall(MMOutputHDF5Close(&o->h5, o->h5_name));
  PetscFunctionReturn(0);
}

/*@
  MMOutputClose - Flushes and closes the output files at the end of the run

  Collective

  Input Parameters:
+ o    - the output object
. c    - the checkpoint of the last step
- step - the last step

  Note:
  Flushes and closes the files: the index lists every snapshot, and the checkpoint's copy of
  solution.h5 goes once the checkpoint c of the last step (step) no longer needs it.

  Level: intermediate

.seealso: `MMOutputOpen()`, `MMOutputWriteFinal()`, `MMOutputDestroy()`
@*/
PetscErrorCode MMOutputClose(MMOutput *o, const MMCheckpoint *c, PetscInt step)
{
  PetscFunctionBeginUser;
  PetscCall(MMOutputSyncIndex(o));
  PetscCall(CloseFiles(o));
  PetscCall(DropSnapshotCopy(o, c, step));
  PetscFunctionReturn(0);
}

/*@
  MMOutputView - Prints the output's line of the run report: the files and the snapshots written

  Collective

  Input Parameters:
+ o      - the output object
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `MMContactView()`, `MMDeformationView()`
@*/
PetscErrorCode MMOutputView(const MMOutput *o, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  output: %s, %s (%" PetscInt_FMT " snapshots), %s\n", o->csv_name, o->h5_name, o->n_written, o->xmf_name));
  PetscFunctionReturn(0);
}

/*@
  MMOutputDestroy - Frees what the output object holds

  Collective

  Input Parameter:
. o - the output object

  Level: intermediate

.seealso: `MMOutputSetFromOptions()`, `MMOutputClose()`
@*/
PetscErrorCode MMOutputDestroy(MMOutput *o)
{
  PetscFunctionBeginUser;
  if (index_at_stop == o) index_at_stop = NULL;
  PetscCall(MMStressDestroy(&o->stress)); /* fem's stress fields */
  PetscCall(MMProbesDestroy(&o->probes));
  PetscCall(VecDestroy(&o->disp_cart));
  PetscCall(VecDestroy(&o->vel_cart));
  PetscCall(VecDestroy(&o->pressure));
  PetscCall(VecDestroy(&o->obstacle));
  PetscCall(VecDestroy(&o->serial));
  PetscCall(VecDestroy(&o->gap));
  PetscCall(VecDestroy(&o->traction_t));
  PetscCall(VecDestroy(&o->slip));
  PetscCall(DMDestroy(&o->dm_out));
  PetscCall(MMInsertMapDestroy(&o->to_out));
  PetscCall(PetscFree(o->times));
  PetscCall(PetscFree(o->index));
  PetscFunctionReturn(0);
}
