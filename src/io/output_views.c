/* What the XDMF index points ParaView at: each snapshot's field as a dataset of its own,
 * /viz/snapshots/K/NAME, an HDF5 virtual dataset (a view, no data of its own) of row K of the field's
 * time series under /vertex_fields or /cell_fields.
 *
 * Why not the XDMF HyperSlab DataItem the index used before: ParaView's Xdmf3 readers (Xdmf3ReaderS,
 * Xdmf3ReaderT, the default for .xmf since ParaView 5.x) ask a HyperSlab for its number type before
 * reading it, get none (XdmfArray::populateItem never sets one for a HyperSlab, whatever its
 * NumberType says) and skip the field: "Skipping unrecognized array type [None]". A plain HDF
 * DataItem is read by both the Xdmf3 readers and the legacy XDMFReader (README "Fields").
 *
 * The view also gives every field the same components in both readers:
 * - a vector has 3 (in 2D the z column is no source's: HDF5 returns the fill value, 0), as VTK's
 *   vectors have (Warp By Vector, Glyph);
 * - the symmetric stress, stored as 6 components xx, xy, xz, yy, yz, zz, is shown as the full 3 x 3
 *   tensor (XDMF "Tensor", 9 components, row by row): the legacy reader expands an XDMF Tensor6 to 9,
 *   but Xdmf3 keeps its 6 in XDMF's order, which ParaView labels in VTK's (XX, YY, ZZ, XY, YZ, XZ),
 *   so its "YY" would be xy.
 * Collective: creating a dataset changes the file's structure. */
#include <petscviewerhdf5.h>
#include "outputimpl.h"

#define H5Call(call) PetscCheck((call) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5's %s failed", #call)

/* the stored component of each of the 9 of the full tensor, row by row */
static const int MMSymmetricOfFull[9] = {0, 1, 2, 1, 3, 4, 2, 4, 5};

PetscInt MMOutputViewComponents(PetscInt ncomp)
{
  return ncomp == 6 ? 9 : ncomp > 1 ? 3 : 1;
}

PetscErrorCode MMOutputViewPath(PetscInt k, const char name[], char path[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, len, "/viz/snapshots/%" PetscInt_FMT "/%s", k, name));
  PetscFunctionReturn(0);
}

/* The mapping of the view's column j (all of it when the field is a scalar) to row k of the source
 * dataset src, whose shape is [k + 1, n(, ncomp)]. */
static PetscErrorCode MapColumn(hid_t dcpl, const char src[], PetscInt k, PetscInt n, PetscInt ncomp, PetscInt nview, PetscInt j)
{
  const PetscInt i         = ncomp == 6 ? MMSymmetricOfFull[j] : j;
  hsize_t        vdims[2]  = {(hsize_t)n, (hsize_t)nview}, vstart[2] = {0, (hsize_t)j}, vcount[2] = {(hsize_t)n, 1};
  hsize_t        sdims[3]  = {(hsize_t)k + 1, (hsize_t)n, (hsize_t)ncomp}, sstart[3] = {(hsize_t)k, 0, (hsize_t)i}, scount[3] = {1, (hsize_t)n, 1};
  const int      vrank     = nview > 1 ? 2 : 1, srank = ncomp > 1 ? 3 : 2;
  hid_t          vspace, sspace;

  PetscFunctionBeginUser;
  if (i >= ncomp) PetscFunctionReturn(0); /* a 2D vector's z: the fill value */
  vspace = H5Screate_simple(vrank, vdims, NULL);
  H5Call(vspace);
  sspace = H5Screate_simple(srank, sdims, NULL);
  H5Call(sspace);
  H5Call(H5Sselect_hyperslab(vspace, H5S_SELECT_SET, vstart, NULL, vcount, NULL));
  H5Call(H5Sselect_hyperslab(sspace, H5S_SELECT_SET, sstart, NULL, scount, NULL));
  H5Call(H5Pset_virtual(dcpl, vspace, ".", src, sspace)); /* ".": this file, whatever its name */
  H5Call(H5Sclose(sspace));
  H5Call(H5Sclose(vspace));
  PetscFunctionReturn(0);
}

/* The view of snapshot k of field f, n its vertices or cells. */
static PetscErrorCode CreateView(hid_t file, PetscInt k, const MMSnapshotField *f, PetscInt n)
{
  const PetscInt nview    = MMOutputViewComponents(f->ncomp);
  hsize_t        dims[2]  = {(hsize_t)n, (hsize_t)nview};
  const double   zero     = 0;
  char           src[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN];
  hid_t          space, dcpl, lcpl, dset;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(src, sizeof(src), "/%s/%s", f->dm ? "vertex_fields" : "cell_fields", f->dataset));
  PetscCall(MMOutputViewPath(k, f->name, path, sizeof(path)));
  dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Call(dcpl);
  H5Call(H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &zero));
  for (PetscInt j = 0; j < nview; ++j) PetscCall(MapColumn(dcpl, src, k, n, f->ncomp, nview, j));
  lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Call(lcpl);
  H5Call(H5Pset_create_intermediate_group(lcpl, 1));
  space = H5Screate_simple(nview > 1 ? 2 : 1, dims, NULL);
  H5Call(space);
  dset = H5Dcreate2(file, path, H5T_NATIVE_DOUBLE, space, lcpl, dcpl, H5P_DEFAULT);
  H5Call(dset);
  H5Call(H5Dclose(dset));
  H5Call(H5Sclose(space));
  H5Call(H5Pclose(lcpl));
  H5Call(H5Pclose(dcpl));
  PetscFunctionReturn(0);
}

/* The views of snapshot k, field i having n[i] vertices or cells. */
static PetscErrorCode CreateSnapshotViews(hid_t file, const MMSnapshotField f[MM_SNAPSHOT_FIELDS], const PetscInt n[MM_SNAPSHOT_FIELDS], PetscInt k)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) PetscCall(CreateView(file, k, &f[i], n[i]));
  PetscFunctionReturn(0);
}

/* The views of snapshot k, once its fields are in the file. */
PetscErrorCode MMOutputCreateViews(PetscViewer viewer, const MMSnapshotField f[MM_SNAPSHOT_FIELDS], PetscInt k)
{
  hid_t    file;
  PetscInt n[MM_SNAPSHOT_FIELDS];

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) {
    PetscCall(VecGetSize(f[i].vec, &n[i]));
    n[i] /= f[i].ncomp;
  }
  PetscCall(CreateSnapshotViews(file, f, n, k));
  PetscFunctionReturn(0);
}

/* The snapshots whose views are measured: enough to spread the global heap's collections (4 kB and
 * up) and the groups' blocks over several snapshots */
#define MM_VIEW_SAMPLES 8

static PetscErrorCode FileSize(hid_t file, hsize_t *size)
{
  PetscFunctionBeginUser;
  H5Call(H5Fflush(file, H5F_SCOPE_LOCAL));
  H5Call(H5Fget_filesize(file, size));
  PetscFunctionReturn(0);
}

/* The bytes the views of one snapshot add to solution.h5, for the output plan (output_plan.c), nv
 * and nc the mesh's vertices and cells, k0 the first snapshot. What a view costs is HDF5's own
 * layout (its object header, its mapping in the global heap, its link in the snapshot's group), so
 * it is measured, not modelled: the views of MM_VIEW_SAMPLES snapshots after k0 are made by the
 * writer's own code in a file HDF5 keeps in memory (the core driver without a backing store, so
 * that nothing reaches the disk: -check_input writes nothing, README "Checking a case before a
 * batch job"), and their mean growth of the file is the answer. A view maps no data, so its cost
 * does not depend on the source datasets, which this file does not have. Not collective. */
PetscErrorCode MMOutputViewBytes(const MMSnapshotField f[MM_SNAPSHOT_FIELDS], PetscInt nv, PetscInt nc, PetscInt k0, PetscReal *bytes)
{
  PetscInt n[MM_SNAPSHOT_FIELDS];
  hid_t    fapl, file;
  hsize_t  first, last;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < MM_SNAPSHOT_FIELDS; ++i) n[i] = f[i].dm ? nv : nc;
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Call(fapl);
  /* grown a byte at a time: its size is then what HDF5 allocated, not the driver's blocks of memory */
  H5Call(H5Pset_fapl_core(fapl, 1, 0));
  file = H5Fcreate("mmcontact-planned-views.h5", H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Call(file);
  /* the first snapshot's views make /viz/snapshots, which the mesh's /viz/topology has begun: once */
  PetscCall(CreateSnapshotViews(file, f, n, k0));
  PetscCall(FileSize(file, &first));
  for (PetscInt s = 1; s <= MM_VIEW_SAMPLES; ++s) PetscCall(CreateSnapshotViews(file, f, n, k0 + s));
  PetscCall(FileSize(file, &last));
  H5Call(H5Fclose(file));
  H5Call(H5Pclose(fapl));
  *bytes = (PetscReal)(last - first) / MM_VIEW_SAMPLES;
  PetscFunctionReturn(0);
}
