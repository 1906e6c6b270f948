/* -restart continues the output of the run it restarts (docs/method.md section 9): history.csv and
 * solution.h5/.xmf are cut at the checkpoint's step, in -output_dir, and the run appends to them.
 *
 * - history.csv keeps its header and its rows up to N, the checkpoint's step; they must be those of
 *   the cadence, steps 0, e, 2e, ... up to N with e = -history_every (and the last step of an
 *   earlier run, which may fall between), or the restart is refused. Written whole to
 *   history.csv.tmp and renamed.
 * - solution.h5 is rewritten: PETSc writes the vertices in the order of the partition, which a
 *   restart on another number of ranks does not share, so the checkpoint's snapshots are copied
 *   vertex by vertex (matched by the serial vertex numbers the file carries) into a new file in
 *   this run's order, with this run's mesh. The XDMF index of those snapshots is written first (it
 *   still matches the old file), then the new file is renamed over the old one: at every moment
 *   the index and the file agree.
 * - The snapshots are read from the checkpoint's copy of solution.h5, checkpoint_snapshots.h5, when
 *   there is one: a run killed while writing solution.h5 can leave it unreadable. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <petscviewerhdf5.h>
#include "io.h"
#include "outputimpl.h"
#include "fem.h"

#define MM_TMP ".tmp"

/* The step number a history row starts with, or -1 if the line is not a whole row. */
static long long RowStep(const char *line, ssize_t len)
{
  char     *after;
  long long step;

  if (len < 2 || line[len - 1] != '\n') return -1;
  step = strtoll(line, &after, 10);
  return (after == line || *after != ',') ? -1 : step;
}

/* rank 0: the source history, streamed line by line (a long run's history can be large) into
 * history.csv.tmp through the checkpoint's row, then renamed into place and opened for appending.
 * Its header must be this run's and its rows every step 0, e, 2e, ... up to N in order, e =
 * -history_every, with at most the last step of an earlier run in between (a row written at its end,
 * output.c): otherwise it is another run's history, and the restart is refused. */
PetscErrorCode MMOutputRestartHistory(MMOutput *o, MMFileStatus *st)
{
  const MMCheckpoint *c = o->ckpt;
  const PetscInt last = c->restart_step;
  char           src[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN], *line = NULL;
  size_t         cap = 0;
  ssize_t        len;
  MMLine         header;
  FILE          *f;
  const PetscInt every = o->history_every;
  PetscInt       due = 0, prev = -1; /* the next step of the cadence; the last row kept */
  int            fd;

  PetscFunctionBeginUser;
  PetscCall(MMOutputCSVHeaderLine(o, &header));
  PetscCall(PetscSNPrintf(src, sizeof(src), "%s/history.csv", c->source_dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", o->csv_name, MM_TMP));
  if (!(f = fopen(src, "r"))) {
    PetscCall(MMOutputFailed(st, "read %s, the history the restart continues", src));
    PetscFunctionReturn(0);
  }
  if ((fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) < 0) {
    PetscCall(MMOutputFailed(st, "create %s", tmp));
    (void)fclose(f);
    PetscFunctionReturn(0);
  }
  len = getline(&line, &cap, f);
  if (len != (ssize_t)header.n || memcmp(line, header.s, header.n)) {
    st->err = -1;
    PetscCall(PetscSNPrintf(st->what, sizeof(st->what), "The history %s has other columns than this run's: it is not of the run that wrote %s (another dimension or other obstacles)", src, c->file));
  } else if (MMOutputWriteAll(fd, line, (size_t)len)) PetscCall(MMOutputFailed(st, "write %s", tmp));
  while (!st->err && due <= last && (len = getline(&line, &cap, f)) > 0) {
    const long long step = RowStep(line, len);
    if (step <= prev || step > last || step > due) break; /* out of order, past the checkpoint, or a row of the cadence missing */
    if (MMOutputWriteAll(fd, line, (size_t)len)) PetscCall(MMOutputFailed(st, "write %s", tmp));
    prev = (PetscInt)step;
    if (step == due) due += every;
  }
  /* rows past the cadence's last step before N: an earlier run's last row */
  while (!st->err && due > last && prev < last && (len = getline(&line, &cap, f)) > 0) {
    const long long step = RowStep(line, len);
    if (step <= prev || step > last) break;
    if (MMOutputWriteAll(fd, line, (size_t)len)) PetscCall(MMOutputFailed(st, "write %s", tmp));
    prev = (PetscInt)step;
  }
  free(line); /* getline's buffer */
  (void)fclose(f);
  if (!st->err && due <= last) {
    st->err = -1;
    PetscCall(PetscSNPrintf(st->what, sizeof(st->what), "The history %s has no row for step %" PetscInt_FMT " (its rows in order end at step %" PetscInt_FMT "; the checkpoint %s is at step %" PetscInt_FMT ", -history_every %" PetscInt_FMT "): it is not the history of the run that wrote the checkpoint, or that run had another -history_every", src, due, prev, c->file, last, every));
  }
  if (close(fd) && !st->err) PetscCall(MMOutputFailed(st, "close %s", tmp));
  if (st->err) {
    (void)unlink(tmp);
    PetscFunctionReturn(0);
  }
  if (rename(tmp, o->csv_name)) PetscCall(MMOutputFailed(st, "rename %s to %s", tmp, o->csv_name));
  else if ((o->csv_fd = open(o->csv_name, O_WRONLY | O_APPEND | O_CLOEXEC)) < 0) PetscCall(MMOutputFailed(st, "open %s", o->csv_name));
  PetscFunctionReturn(0);
}

/* The snapshots of the run being continued: its solution.h5, read by every rank on its own. */
typedef struct {
  hid_t     file;
  char      name[PETSC_MAX_PATH_LEN];
  PetscInt  nv, *row; /* vertices; per serial vertex number, its row in the file */
  PetscReal *slab;    /* one snapshot of one field, all vertices */
} MMOldFields;

/* The dataset's size per time index (or in all, without one) and its number of time indices. */
static PetscErrorCode DatasetShape(MPI_Comm comm, MMOldFields *of, const char path[], hid_t *dset, PetscInt *ntime, PetscInt *per)
{
  hid_t   space;
  hsize_t dims[4];
  int     rank;

  PetscFunctionBeginUser;
  *dset = H5Dopen2(of->file, path, H5P_DEFAULT);
  PetscCheck(*dset >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s has no dataset %s: it is not the output of the run that wrote the checkpoint, or of an mmcontact without restarts", of->name, path);
  space = H5Dget_space(*dset);
  rank  = H5Sget_simple_extent_ndims(space);
  PetscCheck(rank >= 1 && rank <= 3, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has %d dimensions", of->name, path, rank);
  (void)H5Sget_simple_extent_dims(space, dims, NULL);
  (void)H5Sclose(space);
  *ntime = (PetscInt)dims[0];
  *per   = 1;
  for (int i = 1; i < rank; ++i) *per *= (PetscInt)dims[i];
  PetscFunctionReturn(0);
}

static PetscErrorCode OldFieldsOpen(const MMOutput *o, MMOldFields *of)
{
  const MMCheckpoint *c = o->ckpt;
  MPI_Comm  comm = PETSC_COMM_WORLD;
  hid_t     dset;
  PetscInt  n, per;
  PetscReal *serial;

  PetscFunctionBeginUser;
  /* the checkpoint's copy while there is one: solution.h5 itself may have been spoiled by a kill */
  PetscCall(PetscSNPrintf(of->name, sizeof(of->name), "%s/%s", c->source_dir, MM_SNAPSHOT_COPY));
  if (access(of->name, R_OK)) PetscCall(PetscSNPrintf(of->name, sizeof(of->name), "%s/solution.h5", c->source_dir));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL)); /* HDF5's own printing stays on */
  of->file = H5Fopen(of->name, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCall(PetscPopErrorHandler());
  PetscCheck(of->file >= 0, comm, PETSC_ERR_FILE_OPEN, "Could not open %s, the snapshots the restart continues: it is missing or not an HDF5 file", of->name);
  PetscCall(DatasetShape(comm, of, "/vertex_fields/serial_vertex_nodal", &dset, &n, &per));
  of->nv = n;
  PetscCheck(n == c->nv_global && per == 1, comm, PETSC_ERR_FILE_UNEXPECTED, "%s has %" PetscInt_FMT " vertices, the mesh has %" PetscInt_FMT ": it is not the output of the run that wrote the checkpoint", of->name, n, c->nv_global);
  PetscCall(PetscMalloc1(n, &serial));
  PetscCall(PetscMalloc2(n, &of->row, n * 6, &of->slab)); /* the widest field: the stress tensor */
  PetscCheck(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, serial) >= 0, comm, PETSC_ERR_FILE_READ, "Could not read the serial vertex numbers of %s", of->name);
  (void)H5Dclose(dset);
  /* the field holds each vertex's position in the mesh file: back to serial-mesh numbers */
  {
    PetscInt nfile = 0, *serial_of;
    for (PetscInt k = 0; k < n; ++k) nfile = PetscMax(nfile, c->vertex_file[k] + 1);
    PetscCall(PetscMalloc1(nfile, &serial_of));
    for (PetscInt p = 0; p < nfile; ++p) serial_of[p] = -1;
    for (PetscInt k = 0; k < n; ++k) serial_of[c->vertex_file[k]] = k;
    for (PetscInt i = 0; i < n; ++i) of->row[i] = -1;
    for (PetscInt i = 0; i < n; ++i) {
      const PetscInt p = (PetscInt)serial[i], s = p >= 0 && p < nfile ? serial_of[p] : -1;
      PetscCheck(s >= 0 && of->row[s] < 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: its serial_vertex numbers are not those of the mesh's vertices: it is not the output of the run that wrote the checkpoint", of->name);
      of->row[s] = i;
    }
    PetscCall(PetscFree(serial_of));
  }
  PetscCall(PetscFree(serial));
  PetscFunctionReturn(0);
}

/* Snapshot k of a vertex field, all vertices, into of->slab (nv * per values). */
static PetscErrorCode OldFieldsRead(MMOldFields *of, const char path[], PetscInt k, PetscInt want_per)
{
  MPI_Comm comm = PETSC_COMM_WORLD;
  hid_t    dset, fspace, mspace;
  hsize_t  start[3] = {(hsize_t)k, 0, 0}, count[3] = {1, 0, 0};
  PetscInt ntime, per;
  int      rank;

  PetscFunctionBeginUser;
  PetscCall(DatasetShape(comm, of, path, &dset, &ntime, &per));
  PetscCheck(k < ntime, comm, PETSC_ERR_FILE_UNEXPECTED, "%s holds %" PetscInt_FMT " snapshots of %s, the checkpoint counts more: it is not the output of the run that wrote the checkpoint", of->name, ntime, path);
  PetscCheck(per == of->nv * want_per, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has %" PetscInt_FMT " values per snapshot, expected %" PetscInt_FMT, of->name, path, per, of->nv * want_per);
  fspace = H5Dget_space(dset);
  rank   = H5Sget_simple_extent_ndims(fspace);
  (void)H5Sget_simple_extent_dims(fspace, count, NULL);
  count[0] = 1;
  (void)H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
  {
    hsize_t m = (hsize_t)per;
    mspace    = H5Screate_simple(1, &m, NULL);
  }
  PetscCheck(rank >= 1 && H5Dread(dset, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, of->slab) >= 0, comm, PETSC_ERR_FILE_READ, "Could not read snapshot %" PetscInt_FMT " of %s from %s", k, path, of->name);
  (void)H5Sclose(mspace);
  (void)H5Sclose(fspace);
  (void)H5Dclose(dset);
  PetscFunctionReturn(0);
}

/* The old snapshot in of->slab into this run's vector on dm (nc values per vertex), vertex by vertex. */
static PetscErrorCode FillFromOld(const MMOutput *o, MMOldFields *of, DM dm, PetscInt nc, Vec f)
{
  PetscSection gs;
  PetscInt     vStart, vEnd, rstart;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(VecGetOwnershipRange(f, &rstart, NULL));
  PetscCall(VecGetArray(f, &a));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt goff, row;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (goff < 0) continue;
    row = of->row[o->ckpt->vertex_orig[v - vStart]];
    for (PetscInt c = 0; c < nc; ++c) a[goff - rstart + c] = of->slab[row * nc + c];
  }
  PetscCall(VecRestoreArray(f, &a));
  PetscFunctionReturn(0);
}

/* The checkpoint's times against the old file's: the snapshots are of the checkpoint's run. */
static PetscErrorCode CheckOldTimes(const MMOutput *o, MMOldFields *of, PetscInt n, const PetscReal times[])
{
  hid_t    dset;
  PetscInt ntime, per;
  PetscReal *t;

  PetscFunctionBeginUser;
  if (!n) PetscFunctionReturn(0);
  PetscCall(DatasetShape(PETSC_COMM_WORLD, of, "/time", &dset, &ntime, &per));
  PetscCheck(ntime >= n && per == 1, PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "%s holds %" PetscInt_FMT " snapshot times, the checkpoint %s counts %" PetscInt_FMT ": it is not the output of the run that wrote the checkpoint", of->name, ntime, o->ckpt->file, n);
  PetscCall(PetscMalloc1(ntime, &t));
  PetscCheck(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t) >= 0, PETSC_COMM_WORLD, PETSC_ERR_FILE_READ, "Could not read /time from %s", of->name);
  (void)H5Dclose(dset);
  for (PetscInt k = 0; k < n; ++k) PetscCheck(t[k] == times[k], PETSC_COMM_WORLD, PETSC_ERR_FILE_UNEXPECTED, "Snapshot %" PetscInt_FMT " of %s is at t = %.16g, the checkpoint %s has it at t = %.16g: it is not the output of the run that wrote the checkpoint", k, of->name, (double)t[k], o->ckpt->file, (double)times[k]);
  PetscCall(PetscFree(t));
  PetscFunctionReturn(0);
}

/* solution.h5 of this run: the mesh, then the checkpoint's snapshots copied from the old file. */
PetscErrorCode MMOutputRestartFields(MMOutput *o)
{
  const PetscInt dim       = o->dim;
  MMSnapshotField f[MM_SNAPSHOT_FIELDS];
  MMOldFields    of        = {0};
  MMFileStatus   st        = {0};
  char           tmp[PETSC_MAX_PATH_LEN];
  PetscInt       n;
  PetscReal     *times;
  PetscMPIInt    rank;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  MMOutputSnapshotFields(o, dim, f);
  PetscCall(MMCheckpointSnapshots(o->ckpt, &n, &times));
  PetscCall(OldFieldsOpen(o, &of));
  PetscCall(CheckOldTimes(o, &of, n, times));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s%s", o->h5_name, MM_TMP));
  PetscCall(MMOutputCheckSpace(o->dir, tmp, "the snapshots up to the checkpoint", o->mesh_bytes + n * o->snapshot_bytes));
  PetscCall(MMOutputHDF5Create(PETSC_COMM_WORLD, tmp, &o->h5));
  PetscCall(PetscViewerPushFormat(o->h5, PETSC_VIEWER_HDF5_XDMF));
  PetscCall(MMOutputHDF5Begin());
  ierr = DMView(o->dm, o->h5);
  PetscCall(MMOutputHDF5End(ierr, "write", tmp));
  for (PetscInt k = 0; k < n; ++k) {
    /* the vertex fields by the vertices' serial numbers; the cells of this partition are not the
     * old run's, so the cell stress is computed again from the copied displacement (exact: it is
     * a function of the cell's vertices' displacements) */
    for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) {
      char path[PETSC_MAX_PATH_LEN];
      if (!f[i].dm) continue;
      PetscCall(PetscSNPrintf(path, sizeof(path), "/vertex_fields/%s", f[i].dataset));
      PetscCall(OldFieldsRead(&of, path, k, f[i].ncomp));
      PetscCall(FillFromOld(o, &of, f[i].dm, f[i].ncomp, f[i].vec));
    }
    PetscCall(MMStressCompute(&o->stress, o->op, o->material, o->dm_out, o->disp_cart, PETSC_FALSE));
    if (!o->static_written) PetscCall(MMOutputWriteStaticFields(o));
    PetscCall(MMOutputHDF5Begin());
    ierr = MMOutputViewSnapshot(o, o->h5, k, times[k]);
    PetscCall(MMOutputHDF5End(ierr, "write", tmp));
  }
  (void)H5Fclose(of.file);
  PetscCall(PetscFree2(of.row, of.slab));
  PetscCall(MMOutputFlushFields(o));
  o->times     = times;
  o->n_written = n;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  for (PetscInt k = 0; !rank && k < n; ++k) PetscCall(MMOutputIndexAddGrid(o, dim, k, times[k]));
  if (n) PetscCall(MMOutputWriteIndexFile(o));
  if (!rank && rename(tmp, o->h5_name)) PetscCall(MMOutputFailed(&st, "rename %s to %s", tmp, o->h5_name));
  PetscCall(MMOutputCheckRank0(&st));
  { /* a failed write names the file by its new name */
    hid_t     fid;
    MPI_File *fh = NULL;
    PetscCall(PetscViewerHDF5GetFileId(o->h5, &fid));
    if (H5Fget_vfd_handle(fid, H5P_DEFAULT, (void **)&fh) >= 0 && fh) PetscCall(MMErrorsNameMPIIOFile(*fh, o->h5_name));
  }
  PetscCall(MMOutputCopySnapshots(o)); /* the checkpoint this run continues now counts on this file */
  PetscFunctionReturn(0);
}
