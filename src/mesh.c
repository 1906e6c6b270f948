/* Reading a gmsh mesh into DMPlex, naming its physical groups, and distributing it. */
#include "mesh.h"
#include "options.h"
#include "partition_metis.h"

/* Labels DMPlex makes itself: not physical groups the user named. */
static PetscBool IsInternalLabel(const char name[])
{
  const char *internal[] = {"depth", "celltype", "Cell Sets", "Face Sets", "Vertex Sets", "Edge Sets", "marker", "boundary"};
  for (size_t i = 0; i < sizeof(internal) / sizeof(internal[0]); ++i) {
    PetscBool same;
    if (PetscStrcmp(name, internal[i], &same) || same) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* Gets the label of a physical group by name; an unknown name lists the ones the mesh has. */
PetscErrorCode MMMeshGetLabel(DM dm, const char name[], DMLabel *label)
{
  PetscBool has;

  PetscFunctionBeginUser;
  PetscCall(DMHasLabel(dm, name, &has));
  if (!has) {
    char     known[4096] = "";
    PetscInt nl;

    PetscCall(DMGetNumLabels(dm, &nl));
    for (PetscInt l = 0; l < nl; ++l) {
      const char *lname;
      PetscCall(DMGetLabelName(dm, l, &lname));
      if (IsInternalLabel(lname)) continue;
      PetscCall(PetscStrlcat(known, " \"", sizeof(known)));
      PetscCall(PetscStrlcat(known, lname, sizeof(known)));
      PetscCall(PetscStrlcat(known, "\"", sizeof(known)));
    }
    SETERRQ(PetscObjectComm((PetscObject)dm), PETSC_ERR_USER_INPUT, "The mesh has no physical group named \"%s\". Its physical names are:%s. Fix the option or add the Physical group to the .geo", name, known[0] ? known : " (none: name the groups with Physical Curve/Surface/Volume(\"name\") in the .geo)");
  }
  PetscCall(DMGetLabel(dm, name, label));
  PetscFunctionReturn(0);
}

/* A rigid rotation of the coordinates: angle in 2D, rotation vector in 3D (Rodrigues). */
static PetscErrorCode RotateCoordinates(DM dm, const PetscReal rot[], const PetscReal center[])
{
  PetscInt     dim, n;
  PetscReal    R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec          X;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDim(dm, &dim));
  if (dim == 2) {
    const PetscReal c = PetscCosReal(rot[0]), s = PetscSinReal(rot[0]);
    R[0] = c; R[1] = -s; R[3] = s; R[4] = c;
  } else {
    const PetscReal th = PetscSqrtReal(PetscSqr(rot[0]) + PetscSqr(rot[1]) + PetscSqr(rot[2]));
    if (th == 0) PetscFunctionReturn(0);
    const PetscReal k[3] = {rot[0] / th, rot[1] / th, rot[2] / th}, c = PetscCosReal(th), s = PetscSinReal(th);
    for (PetscInt i = 0; i < 3; ++i)
      for (PetscInt j = 0; j < 3; ++j) R[i * 3 + j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
    R[1] -= s * k[2]; R[2] += s * k[1]; R[3] += s * k[2]; R[5] -= s * k[0]; R[6] -= s * k[1]; R[7] += s * k[0];
  }
  PetscCall(DMGetCoordinates(dm, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArray(X, &x));
  for (PetscInt p = 0; p < n / dim; ++p) {
    PetscReal y[3] = {0, 0, 0};
    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt j = 0; j < dim; ++j) y[i] += R[i * 3 + j] * (PetscRealPart(x[p * dim + j]) - center[j]);
    for (PetscInt i = 0; i < dim; ++i) x[p * dim + i] = center[i] + y[i];
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(DMSetCoordinates(dm, X));
  PetscFunctionReturn(0);
}

PetscErrorCode MMMeshLoad(MPI_Comm comm, MMOptions *opt, DM *dm)
{
  PetscBool exists, rotate = PETSC_FALSE;
  DM        dist;

  PetscFunctionBeginUser;
  PetscCheck(opt->mesh_file[0], comm, PETSC_ERR_USER_INPUT, "No mesh given: set -mesh FILE.msh (a gmsh mesh with named physical groups; `make meshes` builds the ones in meshes/)");
  PetscCall(PetscTestFile(opt->mesh_file, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "Mesh file \"%s\" (-mesh) does not exist or is not readable. Generate it from its .geo (make meshes, or gmsh -2/-3 file.geo) or fix the path", opt->mesh_file);
  /* physical names become label names, so every option can refer to groups by name */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(DMPlexCreateFromFile(comm, opt->mesh_file, "mmcontact", PETSC_TRUE, dm));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  {
    PetscInt dim;
    /* the vector options' lengths, the rotation's among them, need the dimension */
    PetscCall(DMGetDimension(*dm, &dim));
    PetscCall(MMOptionsCheckDimension(comm, opt, dim));
  }
  for (PetscInt d = 0; d < MM_MAX_DIM; ++d) rotate = (PetscBool)(rotate || opt->mesh_rotation[d] != 0);
  if (rotate) PetscCall(RotateCoordinates(*dm, opt->mesh_rotation, opt->mesh_rotation_center));

  PetscCall(MMPartitionerRegisterMetis());
  {
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(*dm, &part));
    PetscCall(PetscPartitionerSetType(part, MM_PARTITIONER_METIS));
    PetscCall(PetscPartitionerSetFromOptions(part));
  }
  PetscCall(DMPlexDistribute(*dm, 0, NULL, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscCall(DMSetFromOptions(*dm));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscFunctionReturn(0);
}
