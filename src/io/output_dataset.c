/* One field of solution.h5 written as PETSc's VecView writes a vector to HDF5 (the same dataset
 * shape, chunks and attributes), so that VecLoad, the restart's reader, the XDMF index and ParaView
 * read it unchanged, without the two costs PETSc 3.18's VecView_MPI_HDF5 pays on every call:
 *   - an H5Fflush after each dataset, which MPI-IO turns into an fsync of the file. A snapshot has
 *     a dozen datasets, and the fsyncs are serial, as much as several time steps per snapshot
 *     (docs/scaling.md, "The figures behind the code's choices"). The snapshot
 *     is flushed once, whole, before the index lists it (MMOutputFlushFields), which is what the
 *     index's promise needs (docs/method.md section 9);
 *   - the fill values parallel HDF5 writes into each new chunk before the data overwrite them.
 * Collective, as the HDF5 calls that change the file's structure are. */
#include <petscviewerhdf5.h>
#include "outputimpl.h"

/* An HDF5 call that failed: its name; the caller's MMOutputHDF5End adds the file's */
#define H5Call(call) PetscCheck((call) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5's %s failed", #call)

/* PETSc's layout: [step,] N/bs entries [, bs components]; the time dimension unlimited, one step
 * per chunk, and the chunk capped as VecView_MPI_HDF5 caps it */
typedef struct {
  int     rank;
  hsize_t dims[3], maxdims[3], chunk[3], count[3], offset[3];
} DatasetShape;

static PetscErrorCode ShapeOf(Vec v, PetscInt step, DatasetShape *s)
{
  PetscInt bs, N, n, low;
  int      d = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetBlockSize(v, &bs));
  PetscCall(VecGetSize(v, &N));
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetOwnershipRange(v, &low, NULL));
  if (step >= 0) {
    s->dims[d]    = (hsize_t)step + 1;
    s->maxdims[d] = H5S_UNLIMITED;
    s->chunk[d]   = 1;
    s->count[d]   = 1;
    s->offset[d]  = (hsize_t)step;
    ++d;
  }
  s->dims[d] = s->maxdims[d] = (hsize_t)(N / bs);
  s->chunk[d]                = PetscMax(1, s->dims[d]);
  s->count[d]                = (hsize_t)(n / bs);
  s->offset[d]               = (hsize_t)(low / bs);
  ++d;
  if (bs > 1) {
    s->dims[d] = s->maxdims[d] = s->chunk[d] = s->count[d] = (hsize_t)bs;
    s->offset[d]                                           = 0;
    ++d;
  }
  s->rank = d;
  if (s->chunk[d - 1 - (bs > 1)] * (bs > 1 ? (hsize_t)bs : 1) > PETSC_HDF5_MAX_CHUNKSIZE / 64) {
    const hsize_t cap = (hsize_t)PetscSqrtReal((PetscReal)(PETSC_HDF5_MAX_CHUNKSIZE / 64));
    if (bs > 1) {
      for (int k = d - 2; k < d; ++k) s->chunk[k] = PetscMin(s->chunk[k], cap);
    } else s->chunk[d - 1] = PETSC_HDF5_MAX_CHUNKSIZE / 64;
  }
  PetscFunctionReturn(0);
}

/* The dataset grown to hold this step, or created with it; new chunks are not filled (every entry
 * of a step is written) */
static PetscErrorCode OpenOrCreate(hid_t group, const char name[], const DatasetShape *s, hid_t *dset, PetscBool *created)
{
  hid_t space, dcpl;

  PetscFunctionBeginUser;
  *created = (PetscBool)(H5Lexists(group, name, H5P_DEFAULT) < 1);
  if (!*created) {
    *dset = H5Dopen2(group, name, H5P_DEFAULT);
    H5Call(*dset);
    H5Call(H5Dset_extent(*dset, s->dims));
    PetscFunctionReturn(0);
  }
  space = H5Screate_simple(s->rank, s->dims, s->maxdims);
  H5Call(space);
  dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Call(dcpl);
  H5Call(H5Pset_chunk(dcpl, s->rank, s->chunk));
  H5Call(H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER));
  *dset = H5Dcreate2(group, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Call(*dset);
  H5Call(H5Pclose(dcpl));
  H5Call(H5Sclose(space));
  PetscFunctionReturn(0);
}

/* Each rank's entries into its rows of the step, independently (PETSc's default transfer) */
static PetscErrorCode WriteRows(hid_t dset, const DatasetShape *s, Vec v)
{
  hid_t              mem, file, dxpl;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  mem = H5Screate_simple(s->rank, s->count, NULL);
  H5Call(mem);
  file = H5Dget_space(dset);
  H5Call(file);
  H5Call(H5Sselect_hyperslab(file, H5S_SELECT_SET, s->offset, NULL, s->count, NULL));
  dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Call(dxpl);
#if defined(H5_HAVE_PARALLEL)
  H5Call(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_INDEPENDENT));
#endif
  PetscCall(VecGetArrayRead(v, &a));
  H5Call(H5Dwrite(dset, H5T_NATIVE_DOUBLE, mem, file, dxpl, a));
  PetscCall(VecRestoreArrayRead(v, &a));
  H5Call(H5Pclose(dxpl));
  H5Call(H5Sclose(file));
  H5Call(H5Sclose(mem));
  PetscFunctionReturn(0);
}

/* v (its block size the components) as the dataset of its name in the viewer's current group: its
 * entry of step, or the whole dataset when step < 0. Its attributes are written once, when it is
 * created: a time series's "timestepping", which PETSc's VecView gives it and VecLoad reads, and
 * "vector_field_type" = field_type unless NULL. */
PetscErrorCode MMOutputWriteDataset(PetscViewer viewer, Vec v, PetscInt step, const char field_type[])
{
  DatasetShape s;
  const char  *name;
  hid_t        file, group, dset;
  PetscBool    created, ts = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetName((PetscObject)v, &name));
  PetscCall(ShapeOf(v, step, &s));
  PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file, &group));
  PetscCall(OpenOrCreate(group, name, &s, &dset, &created));
  PetscCall(WriteRows(dset, &s, v));
  H5Call(H5Dclose(dset));
  H5Call(H5Gclose(group));
  if (created && step >= 0) PetscCall(PetscViewerHDF5WriteObjectAttribute(viewer, (PetscObject)v, "timestepping", PETSC_BOOL, &ts));
  if (created && field_type) PetscCall(PetscViewerHDF5WriteObjectAttribute(viewer, (PetscObject)v, "vector_field_type", PETSC_STRING, field_type));
  PetscFunctionReturn(0);
}
