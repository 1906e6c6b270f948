/* What PETSc's gmsh reader does not say about a mesh file, checked against the file itself
 * (README "What is checked before the run", "Fields"):
 * - a path that is a directory, or a file that starts with a UTF-8 byte order mark (the reader
 *   would call the first a missing file and stop on the second with a message about sections);
 * - a node with a non-finite coordinate (the orientation check would call its cells inverted);
 * - each vertex's position among the file's nodes. The reader of gmsh 4 files keeps only the nodes
 *   that cells use, in file order, so with an unused node the serial mesh's vertex k is not the
 *   file's node k: the positions are found by walking both lists (same coordinates, same order).
 *   The reader of gmsh 2 files keeps every node, and an unused one has no mass: refused, named. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "mesh.h"
#include "msh_binary.h"

/*@
  MMMeshCheckFile - Refuses a mesh path that is a directory, a missing or unreadable file, or a file
  that starts with a UTF-8 byte order mark

  Collective

  Input Parameters:
+ comm - the communicator of the run (rank 0 looks at the file)
- file - the mesh file (-mesh)

  Note:
  Before the reader: the path is a readable file without a byte order mark.

  Runs before PETSc's reader, which would call a directory a missing file and stop on a byte order
  mark with a message about sections. A missing file given by a relative path is named with the
  current directory it was looked for in.

  Level: developer

.seealso: `MMMeshRead()`, `MMMeshFileNodes()`
@*/
PetscErrorCode MMMeshCheckFile(MPI_Comm comm, const char file[])
{
  struct stat   st;
  int           err = 0, isdir = 0, bom = 0;
  PetscMPIInt   rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    FILE         *f;
    unsigned char head[3] = {0, 0, 0};
    if (stat(file, &st)) err = errno;
    else if (S_ISDIR(st.st_mode)) isdir = 1;
    else if (!(f = fopen(file, "rb"))) err = errno;
    else {
      bom = fread(head, 1, 3, f) == 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF;
      (void)fclose(f);
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&isdir, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&bom, 1, MPI_INT, 0, comm));
  PetscCheck(!isdir, comm, PETSC_ERR_USER_INPUT, "-mesh %s is a directory: give the .msh file in it (make meshes writes meshes/NAME.msh from meshes/NAME.geo)", file);
  if (err == ENOENT && file[0] != '/') {
    /* a relative path is the current directory's, not the options file's: say which file was tried */
    char cwd[PETSC_MAX_PATH_LEN] = "?";
    if (!getcwd(cwd, sizeof(cwd))) PetscCall(PetscStrncpy(cwd, "(the current directory)", sizeof(cwd)));
    SETERRQ(comm, PETSC_ERR_FILE_OPEN, "Mesh file \"%s\" (-mesh) does not exist: a relative path is taken from the current directory, not from the options file's, so the file tried was %s/%s. Run from the directory the path is relative to, give an absolute path, or generate the mesh from its .geo (make meshes, or gmsh -2/-3 file.geo)", file, cwd, file);
  }
  PetscCheck(err != ENOENT, comm, PETSC_ERR_FILE_OPEN, "Mesh file \"%s\" (-mesh) does not exist. Generate it from its .geo (make meshes, or gmsh -2/-3 file.geo) or fix the path", file);
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Mesh file \"%s\" (-mesh) cannot be read: %s. Fix its permissions or the path", file, strerror(err));
  PetscCheck(!bom, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh) starts with a UTF-8 byte order mark (bytes EF BB BF), which gmsh never writes and PETSc's reader cannot read: save it without one, or regenerate it with gmsh", file);
  PetscFunctionReturn(0);
}

/* The nodes of a binary .msh 2.2 (after "$Nodes": the count in ASCII, then per node an int tag and
 * three doubles) or 4.1 (size_t counts, then per entity block its int header and size_t count, the
 * size_t tags, then the coordinates); the file's data size must be 8, its byte order this machine's.
 * Returns the number of nodes read; *total the number announced. */
static long ReadBinaryNodes(FILE *f, double version, long *total, PetscReal **xyz, PetscInt **tag)
{
  char line[256];
  long k = 0, blocks = 0, lo, hi;

  if (version < 4) {
    if (!fgets(line, sizeof(line), f) || sscanf(line, "%ld", total) != 1 || *total < 0) return -1;
  } else if (!MMMshBinaryLong(f, 8, &blocks) || !MMMshBinaryLong(f, 8, total) || !MMMshBinaryLong(f, 8, &lo) || !MMMshBinaryLong(f, 8, &hi) || *total < 0) return -1;
  if (PetscMalloc2(3 * *total, xyz, *total, tag)) return -1;
  if (version < 4) {
    for (k = 0; k < *total; ++k) {
      long   t;
      double x[3];
      if (!MMMshBinaryLong(f, 4, &t) || fread(x, sizeof(double), 3, f) != 3) break;
      (*tag)[k] = (PetscInt)t;
      for (int d = 0; d < 3; ++d) (*xyz)[3 * k + d] = x[d];
    }
    return k;
  }
  for (long b = 0; b < blocks; ++b) {
    long edim, etag, param, nb;
    if (!MMMshBinaryLong(f, 4, &edim) || !MMMshBinaryLong(f, 4, &etag) || !MMMshBinaryLong(f, 4, &param) || !MMMshBinaryLong(f, 8, &nb) || param || k + nb > *total) return k;
    for (long i = 0; i < nb; ++i) {
      long t;
      if (!MMMshBinaryLong(f, 8, &t)) return k;
      (*tag)[k + i] = (PetscInt)t;
    }
    for (long i = 0; i < nb; ++i) {
      double x[3];
      if (fread(x, sizeof(double), 3, f) != 3) return k;
      for (int d = 0; d < 3; ++d) (*xyz)[3 * (k + i) + d] = x[d];
    }
    k += nb;
  }
  return k;
}

/* The file's nodes, in file order, from a .msh (format 2.2 or 4.1, ASCII or binary): coordinates and
 * tags. *n = -1 when the file is not understood: nothing to compare then. */
static PetscErrorCode ReadNodes(const char file[], PetscInt *n, PetscReal **xyz, PetscInt **tag)
{
  FILE  *f = fopen(file, "r");
  char   line[1024];
  double version = 0;
  int    binary = 1;
  long   total = -1, k = 0;

  PetscFunctionBeginUser;
  *n   = -1;
  *xyz = NULL;
  *tag = NULL;
  if (!f) PetscFunctionReturn(0);
  while (fgets(line, sizeof(line), f)) {
    if (!strncmp(line, "$MeshFormat", 11)) {
      if (!fgets(line, sizeof(line), f) || sscanf(line, "%lf %d", &version, &binary) != 2) break;
    } else if (!strncmp(line, "$Nodes", 6)) {
      long blocks = 0;
      if (binary) {
        k = ReadBinaryNodes(f, version, &total, xyz, tag);
        break;
      }
      if (!fgets(line, sizeof(line), f)) break;
      if (version < 4 ? sscanf(line, "%ld", &total) != 1 : sscanf(line, "%ld %ld", &blocks, &total) != 2) break;
      PetscCall(PetscMalloc2(3 * total, xyz, total, tag));
      if (version < 4) {
        for (k = 0; k < total && fgets(line, sizeof(line), f); ++k) {
          long   t;
          double x[3];
          if (sscanf(line, "%ld %lf %lf %lf", &t, &x[0], &x[1], &x[2]) != 4) break;
          (*tag)[k] = (PetscInt)t;
          for (int d = 0; d < 3; ++d) (*xyz)[3 * k + d] = x[d];
        }
      } else {
        for (long b = 0; b < blocks; ++b) {
          int  edim, etag, param;
          long nb;
          if (!fgets(line, sizeof(line), f) || sscanf(line, "%d %d %d %ld", &edim, &etag, &param, &nb) != 4 || k + nb > total) break;
          for (long i = 0; i < nb && fgets(line, sizeof(line), f); ++i) (*tag)[k + i] = (PetscInt)strtol(line, NULL, 10);
          for (long i = 0; i < nb && fgets(line, sizeof(line), f); ++i) {
            double x[3];
            if (sscanf(line, "%lf %lf %lf", &x[0], &x[1], &x[2]) != 3) break;
            for (int d = 0; d < 3; ++d) (*xyz)[3 * (k + i) + d] = x[d];
          }
          k += nb;
        }
      }
      break;
    }
  }
  (void)fclose(f);
  if (total >= 0 && k == total) *n = (PetscInt)total;
  else if (*xyz) PetscCall(PetscFree2(*xyz, *tag));
  PetscFunctionReturn(0);
}

static PetscBool SameCoordinate(PetscReal a, PetscReal b)
{
  if (PetscIsNanReal(a) || PetscIsNanReal(b)) return (PetscBool)(PetscIsNanReal(a) && PetscIsNanReal(b));
  return (PetscBool)(PetscAbsReal(a - b) <= 1e-12 * (1 + PetscAbsReal(a)));
}

/* rank 0, on the serial mesh: the position in the file of each vertex, by walking both lists. */
static PetscErrorCode MatchVertices(DM dm, PetscInt dim, PetscInt nfile, const PetscReal xyz[], PetscInt pos[], PetscBool *ok)
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           nx, nv, j = 0;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetLocalSize(X, &nx));
  nv = nx / dim;
  PetscCall(VecGetArrayRead(X, &x));
  *ok = PETSC_TRUE;
  for (PetscInt k = 0; k < nv && *ok; ++k) {
    PetscBool same = PETSC_FALSE;
    for (; j < nfile && !same; ++j) {
      same = PETSC_TRUE;
      for (PetscInt d = 0; d < dim; ++d) same = (PetscBool)(same && SameCoordinate(PetscRealPart(x[k * dim + d]), xyz[3 * j + d]));
      if (same) pos[k] = j;
    }
    *ok = same;
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

/*@
  MMMeshFileNodes - Checks the serial mesh's nodes against the file, and finds each serial vertex's
  position among the file's nodes

  Collective

  Input Parameters:
+ comm - the communicator of the run
. dm   - the serial mesh, on rank 0, its coordinates unchanged
- file - the mesh file it was read from

  Output Parameters:
+ pos  - on every rank, the file position of each serial vertex (the identity when the file cannot
         be compared); free with PetscFree()
- vtag - on rank 0, each serial vertex's node tag in the file; NULL on the other ranks and when the
         file cannot be compared

  Note:
  On the serial mesh (rank 0 holds it), before any change of its coordinates: refuses non-finite
  coordinates and unused gmsh 2 nodes, and gives every rank the file position of each serial vertex
  (*pos, nv entries; the identity when the file cannot be compared), and rank 0 its node tag in the
  file (*vtag; NULL on the other ranks and when the file cannot be compared).

  The reader of gmsh 4 files keeps only the nodes that cells use, in file order, so with an unused
  node the serial mesh's vertex k is not the file's node k: the positions are found by walking both
  lists (same coordinates, same order). A refused node is named by its tag in the file when known,
  else by its position from 1.

  Level: developer

.seealso: `MMMeshRead()`, `MMMeshCheckFile()`
@*/
PetscErrorCode MMMeshFileNodes(MPI_Comm comm, DM dm, const char file[], PetscInt **pos, PetscInt **vtag)
{
  PetscMPIInt rank;
  PetscInt    dim, vStart, vEnd, nv, nfile = -1, bad = -1, lone = -1, *tag = NULL;
  PetscReal  *xyz = NULL, where[3] = {0, 0, 0};
  PetscBool   ok = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(DMGetCoordinateDim(dm, &dim));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  nv = vEnd - vStart;
  PetscCallMPI(MPI_Bcast(&nv, 1, MPIU_INT, 0, comm));
  PetscCall(PetscMalloc1(nv, pos));
  for (PetscInt k = 0; k < nv; ++k) (*pos)[k] = k;
  *vtag = NULL;
  if (rank == 0) {
    Vec                X;
    const PetscScalar *x;
    PetscCall(ReadNodes(file, &nfile, &xyz, &tag));
    if (nfile >= 0) PetscCall(MatchVertices(dm, dim, nfile, xyz, *pos, &ok));
    if (!ok) for (PetscInt k = 0; k < nv; ++k) (*pos)[k] = k;
    PetscCall(DMGetCoordinatesLocal(dm, &X));
    PetscCall(VecGetArrayRead(X, &x));
    for (PetscInt k = 0; k < nv && bad < 0; ++k)
      for (PetscInt d = 0; d < dim; ++d)
        if (PetscIsInfOrNanReal(PetscRealPart(x[k * dim + d]))) bad = k;
    for (PetscInt v = vStart; v < vEnd && lone < 0; ++v) {
      PetscInt ns;
      PetscCall(DMPlexGetSupportSize(dm, v, &ns));
      if (!ns) {
        lone = v - vStart;
        for (PetscInt d = 0; d < dim; ++d) where[d] = PetscRealPart(x[lone * dim + d]);
      }
    }
    PetscCall(VecRestoreArrayRead(X, &x));
    /* name nodes by their tag in the file when it is known, else by their position from 1 */
    if (bad >= 0) bad = tag && ok ? tag[(*pos)[bad]] : (*pos)[bad] + 1;
    if (lone >= 0) lone = tag && ok ? tag[(*pos)[lone]] : (*pos)[lone] + 1;
    if (tag && ok) {
      PetscCall(PetscMalloc1(nv, vtag));
      for (PetscInt k = 0; k < nv; ++k) (*vtag)[k] = tag[(*pos)[k]];
    }
    PetscCall(PetscFree2(xyz, tag));
  }
  PetscCallMPI(MPI_Bcast(&bad, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&lone, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(where, 3, MPIU_REAL, 0, comm));
  PetscCheck(bad < 0, comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh): node %" PetscInt_FMT " has a non-finite coordinate (NaN or inf). Fix that node in the file, or regenerate the mesh from its .geo", file, bad);
  if (lone >= 0) {
    char at[128];
    if (dim == 2) PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g)", (double)where[0], (double)where[1]));
    else PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g, %g)", (double)where[0], (double)where[1], (double)where[2]));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh): node %" PetscInt_FMT " at %s belongs to no element, so it has no mass and no stiffness. Remove it: gmsh writes such nodes for points outside every physical group with Mesh.SaveAll; save without it, or in format 4.1, whose reader skips them", file, lone, at);
  }
  PetscCallMPI(MPI_Bcast(*pos, (PetscMPIInt)nv, MPIU_INT, 0, comm));
  PetscFunctionReturn(0);
}
