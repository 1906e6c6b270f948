/* The Physical Point groups of a gmsh file, as vertex labels named after the groups (the nodes of
 * -point_force, README "Loads in time").
 *
 * The mesh is read without faces (src/mesh/facets.c), and PETSc's reader labels a Physical Point's
 * vertex only with -dm_plex_gmsh_mark_vertices, which would also put every node of every facet and
 * cell group in its label. So the point elements (gmsh type 15) are read here, on rank 0, from a
 * 2.2 or 4.1 file, ASCII or binary (gmsh -bin: data size 8, this machine's byte order), and each
 * group's vertices labelled on the serial mesh, before the distribution carries the labels to the
 * ranks. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh.h"
#include "msh_binary.h"

#define MM_POINT_GROUP_MAX 64 /* named Physical Point groups read; more are left unlabelled */

typedef struct {
  PetscInt n;
  char     name[MM_POINT_GROUP_MAX][256];
  long     tag[MM_POINT_GROUP_MAX];
} PointGroups;

static PetscInt GroupOf(const PointGroups *g, long tag)
{
  for (PetscInt i = 0; i < g->n; ++i)
    if (g->tag[i] == tag) return i;
  return -1;
}

/* $PhysicalNames: the named groups of dimension 0. */
static void ReadNames(FILE *in, PointGroups *g, char **line, size_t *len)
{
  long n = 0;

  if (getline(line, len, in) <= 0 || sscanf(*line, "%ld", &n) != 1) return;
  for (long i = 0; i < n; ++i) {
    int   gdim;
    long  tag;
    char *q0, *q1;
    if (getline(line, len, in) <= 0) return;
    if (sscanf(*line, "%d %ld", &gdim, &tag) != 2 || gdim != 0 || g->n >= MM_POINT_GROUP_MAX) continue;
    if (!(q0 = strchr(*line, '"')) || !(q1 = strrchr(*line, '"')) || q1 <= q0) continue;
    snprintf(g->name[g->n], sizeof(g->name[0]), "%.*s", (int)(q1 - q0 - 1), q0 + 1);
    g->tag[g->n++] = tag;
  }
}

/* $Entities (4.1): the (point entity, named group) pairs, two entries each; an entity may be in
 * several groups. */
static void ReadPointEntities(FILE *in, const PointGroups *g, long **pairs, long *npairs, char **line, size_t *len)
{
  long np = 0, rest[3];

  if (getline(line, len, in) <= 0 || sscanf(*line, "%ld %ld %ld %ld", &np, &rest[0], &rest[1], &rest[2]) != 4) return;
  for (long i = 0; i < np; ++i) {
    char *p, *e;
    long  etag, nphys;
    if (getline(line, len, in) <= 0) return;
    etag = strtol(*line, &e, 10);
    for (int k = 0; k < 3; ++k) {
      p = e;
      (void)strtod(p, &e);
    }
    nphys = strtol(e, &e, 10);
    for (long k = 0; k < nphys; ++k) {
      const long tag = strtol(e, &e, 10);
      if (GroupOf(g, tag) < 0) continue;
      *pairs                   = (long *)realloc(*pairs, 2 * (*npairs + 1) * sizeof(long));
      (*pairs)[2 * *npairs]     = etag;
      (*pairs)[2 * *npairs + 1] = GroupOf(g, tag);
      ++*npairs;
    }
  }
}

/* The nodes of each gmsh element type (the first-order and second-order ones a .msh may hold);
 * 0 for a type this does not know, which ends the reading. */
static long NodesOfType(long type)
{
  static const long n[] = {0, 2, 3, 4, 4, 8, 6, 5, 3, 6, 9, 10, 27, 18, 14, 1, 8, 20, 15, 13};
  return type > 0 && type < (long)(sizeof(n) / sizeof(n[0])) ? n[type] : 0;
}

/* Binary $Entities (4.1): the point entities' named groups, as ReadPointEntities. */
static void ReadBinaryPointEntities(FILE *in, const PointGroups *g, long **pairs, long *npairs)
{
  long np, rest;

  if (!MMMshBinaryLong(in, 8, &np)) return;
  for (int k = 0; k < 3; ++k)
    if (!MMMshBinaryLong(in, 8, &rest)) return;
  for (long i = 0; i < np; ++i) {
    long   etag, nphys;
    double x[3];
    if (!MMMshBinaryLong(in, 4, &etag) || fread(x, sizeof(double), 3, in) != 3 || !MMMshBinaryLong(in, 8, &nphys)) return;
    for (long k = 0; k < nphys; ++k) {
      long tag;
      if (!MMMshBinaryLong(in, 4, &tag)) return;
      if (GroupOf(g, tag) < 0) continue;
      *pairs                    = (long *)realloc(*pairs, 2 * (*npairs + 1) * sizeof(long));
      (*pairs)[2 * *npairs]     = etag;
      (*pairs)[2 * *npairs + 1] = GroupOf(g, tag);
      ++*npairs;
    }
  }
}

/* Binary $Nodes, passed over (their tags are known from the mesh's reading): 1 when done. */
static int SkipBinaryNodes(FILE *in, double version)
{
  char line[256];
  long total, blocks, lo, hi;

  if (version < 4) return fgets(line, sizeof(line), in) && sscanf(line, "%ld", &total) == 1 && !fseek(in, total * (4 + 3 * (long)sizeof(double)), SEEK_CUR);
  if (!MMMshBinaryLong(in, 8, &blocks) || !MMMshBinaryLong(in, 8, &total) || !MMMshBinaryLong(in, 8, &lo) || !MMMshBinaryLong(in, 8, &hi)) return 0;
  for (long b = 0; b < blocks; ++b) {
    long edim, etag, param, nb;
    if (!MMMshBinaryLong(in, 4, &edim) || !MMMshBinaryLong(in, 4, &etag) || !MMMshBinaryLong(in, 4, &param) || !MMMshBinaryLong(in, 8, &nb) || param) return 0;
    if (fseek(in, nb * (8 + 3 * (long)sizeof(double)), SEEK_CUR)) return 0;
  }
  return 1;
}

/* Labels serial vertex of file node `node` with group gi (rank 0). */
static PetscErrorCode LabelNode(DM dm, const PointGroups *g, PetscInt gi, long node, const PetscInt vtag[], PetscInt nv)
{
  PetscInt vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  for (PetscInt k = 0; k < nv; ++k)
    if (vtag[k] == node) PetscCall(DMSetLabelValue(dm, g->name[gi], vStart + k, (PetscInt)g->tag[gi]));
  PetscFunctionReturn(0);
}

/* $Elements: the point elements (type 15) of the named groups, their node labelled. */
static PetscErrorCode ReadPointElements(FILE *in, DM dm, double version, const PointGroups *g, const long *pairs, long npairs, const PetscInt vtag[], PetscInt nv, char **line, size_t *len)
{
  PetscFunctionBeginUser;
  if (version == 4.1) {
    long nblocks, nelem, lo, hi;
    if (getline(line, len, in) <= 0 || sscanf(*line, "%ld %ld %ld %ld", &nblocks, &nelem, &lo, &hi) != 4) PetscFunctionReturn(0);
    for (long b = 0; b < nblocks; ++b) {
      int  edim, type;
      long etag, n;
      if (getline(line, len, in) <= 0 || sscanf(*line, "%d %ld %d %ld", &edim, &etag, &type, &n) != 4) PetscFunctionReturn(0);
      for (long i = 0; i < n; ++i) {
        long id, node;
        if (getline(line, len, in) <= 0) PetscFunctionReturn(0);
        if (edim != 0 || type != 15 || sscanf(*line, "%ld %ld", &id, &node) != 2) continue;
        for (long k = 0; k < npairs; ++k)
          if (pairs[2 * k] == etag) PetscCall(LabelNode(dm, g, (PetscInt)pairs[2 * k + 1], node, vtag, nv));
      }
    }
  } else {
    long nelem;
    if (getline(line, len, in) <= 0 || sscanf(*line, "%ld", &nelem) != 1) PetscFunctionReturn(0);
    for (long i = 0; i < nelem; ++i) {
      long id, ntags, phys, node;
      int  type;
      char *e;
      if (getline(line, len, in) <= 0) PetscFunctionReturn(0);
      if (sscanf(*line, "%ld %d %ld %ld", &id, &type, &ntags, &phys) != 4 || type != 15 || GroupOf(g, phys) < 0) continue;
      e = *line;
      for (long k = 0; k < 3 + ntags; ++k) (void)strtol(e, &e, 10);
      node = strtol(e, NULL, 10);
      PetscCall(LabelNode(dm, g, GroupOf(g, phys), node, vtag, nv));
    }
  }
  PetscFunctionReturn(0);
}

/* Binary $Elements: the point elements of the named groups, as ReadPointElements. 4.1: size_t
 * counts, per entity block an int header and a size_t count, per element size_t tag and nodes; 2.2:
 * the count in ASCII, then per run of one type an int header (type, count, tags) and per element
 * ints (number, tags, nodes). */
static PetscErrorCode ReadBinaryPointElements(FILE *in, DM dm, double version, const PointGroups *g, const long *pairs, long npairs, const PetscInt vtag[], PetscInt nv)
{
  PetscFunctionBeginUser;
  if (version == 4.1) {
    long nblocks, nelem, lo, hi;
    if (!MMMshBinaryLong(in, 8, &nblocks) || !MMMshBinaryLong(in, 8, &nelem) || !MMMshBinaryLong(in, 8, &lo) || !MMMshBinaryLong(in, 8, &hi)) PetscFunctionReturn(0);
    for (long b = 0; b < nblocks; ++b) {
      long edim, etag, type, n, nn, rec[2];
      if (!MMMshBinaryLong(in, 4, &edim) || !MMMshBinaryLong(in, 4, &etag) || !MMMshBinaryLong(in, 4, &type) || !MMMshBinaryLong(in, 8, &n) || !(nn = NodesOfType(type))) PetscFunctionReturn(0);
      if (edim != 0 || type != 15) {
        if (fseek(in, n * (1 + nn) * 8, SEEK_CUR)) PetscFunctionReturn(0);
        continue;
      }
      for (long i = 0; i < n; ++i) {
        if (!MMMshBinaryLong(in, 8, &rec[0]) || !MMMshBinaryLong(in, 8, &rec[1])) PetscFunctionReturn(0);
        for (long k = 0; k < npairs; ++k)
          if (pairs[2 * k] == etag) PetscCall(LabelNode(dm, g, (PetscInt)pairs[2 * k + 1], rec[1], vtag, nv));
      }
    }
  } else {
    char line[256];
    long nelem, done = 0;
    if (!fgets(line, sizeof(line), in) || sscanf(line, "%ld", &nelem) != 1) PetscFunctionReturn(0);
    while (done < nelem) {
      long type, n, ntags, nn;
      if (!MMMshBinaryLong(in, 4, &type) || !MMMshBinaryLong(in, 4, &n) || !MMMshBinaryLong(in, 4, &ntags) || !(nn = NodesOfType(type)) || ntags < 0 || ntags > 64) PetscFunctionReturn(0);
      for (long i = 0; i < n; ++i) {
        long rec[66];
        for (long k = 0; k < 1 + ntags + nn; ++k)
          if (!MMMshBinaryLong(in, 4, &rec[PetscMin(k, 65)])) PetscFunctionReturn(0);
        if (type == 15 && ntags >= 1 && GroupOf(g, rec[1]) >= 0) PetscCall(LabelNode(dm, g, GroupOf(g, rec[1]), rec[1 + ntags], vtag, nv));
      }
      done += n;
    }
  }
  PetscFunctionReturn(0);
}

/*@
  MMMeshPointGroupsRead - Labels each named Physical Point group of the file on the serial mesh's
  vertices, value its physical tag

  Not collective (rank 0 reads the file and labels its mesh; the other ranks return at once)

  Input Parameters:
+ comm - the communicator of the run
. dm   - the serial mesh, on rank 0
. file - the mesh file
- vtag - rank 0's node tag of each serial vertex, NULL when they could not be read

  Note:
  On the serial mesh (rank 0 holds it; vtag its vertices' node tags in the file, NULL when they
  could not be read): a label per named Physical Point group on its vertices, value its physical
  tag. A file this cannot read has no point labels (the options naming them are refused later).

  Level: developer

.seealso: `MMMeshRead()`, `MMMeshDistribute()`
@*/
PetscErrorCode MMMeshPointGroupsRead(MPI_Comm comm, DM dm, const char file[], const PetscInt vtag[])
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank || !vtag) PetscFunctionReturn(0);
  {
    FILE       *in   = fopen(file, "r");
    char       *line = NULL;
    size_t      len  = 0;
    double      version = 0;
    int         binary  = 1;
    long       *pairs = NULL, npairs = 0;
    PetscInt    vStart, vEnd;
    PointGroups g;

    g.n = 0;
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    while (in && getline(&line, &len, in) > 0) {
      if (!strncmp(line, "$MeshFormat", 11)) {
        if (getline(&line, &len, in) <= 0 || sscanf(line, "%lf %d", &version, &binary) != 2) break;
      } else if (!strncmp(line, "$PhysicalNames", 14)) ReadNames(in, &g, &line, &len);
      else if (!strncmp(line, "$Entities", 9)) {
        if (!binary) ReadPointEntities(in, &g, &pairs, &npairs, &line, &len);
        else if (g.n) ReadBinaryPointEntities(in, &g, &pairs, &npairs);
        else break; /* no named point groups: nothing to read */
      } else if (binary && !strncmp(line, "$Nodes", 6)) {
        if (!SkipBinaryNodes(in, version)) break;
      } else if (!strncmp(line, "$Elements", 9)) {
        if (g.n && binary) PetscCall(ReadBinaryPointElements(in, dm, version, &g, pairs, npairs, vtag, vEnd - vStart));
        else if (g.n) PetscCall(ReadPointElements(in, dm, version, &g, pairs, npairs, vtag, vEnd - vStart, &line, &len));
        break;
      }
    }
    free(pairs);
    free(line);
    if (in) (void)fclose(in);
  }
  PetscFunctionReturn(0);
}
