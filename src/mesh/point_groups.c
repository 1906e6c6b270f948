/* The Physical Point groups of a gmsh file, as vertex labels named after the groups (the nodes of
 * -point_force, README "Loads in time").
 *
 * The mesh is read without faces (src/mesh/facets.c), and PETSc's reader labels a Physical Point's
 * vertex only with -dm_plex_gmsh_mark_vertices, which would also put every node of every facet and
 * cell group in its label. So the point elements (gmsh type 15) are read here, on rank 0, from an
 * ASCII 2.2 or 4.1 file, and each group's vertices labelled on the serial mesh, before the
 * distribution carries the labels to the ranks. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh.h"

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

/* On the serial mesh (rank 0 holds it; vtag its vertices' node tags in the file, NULL when they
 * could not be read): a label per named Physical Point group on its vertices, value its physical
 * tag. A file this cannot read (binary) has no point labels. */
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
        if (getline(&line, &len, in) <= 0 || sscanf(line, "%lf %d", &version, &binary) != 2 || binary) break;
      } else if (!strncmp(line, "$PhysicalNames", 14)) ReadNames(in, &g, &line, &len);
      else if (!strncmp(line, "$Entities", 9)) ReadPointEntities(in, &g, &pairs, &npairs, &line, &len);
      else if (!strncmp(line, "$Elements", 9)) {
        if (g.n) PetscCall(ReadPointElements(in, dm, version, &g, pairs, npairs, vtag, vEnd - vStart, &line, &len));
        break;
      }
    }
    free(pairs);
    free(line);
    if (in) (void)fclose(in);
  }
  PetscFunctionReturn(0);
}
