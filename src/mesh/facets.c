/* The facet physical groups of a mesh that is never interpolated (README "Large meshes").
 *
 * P1 elements need cells and vertices only; the facet groups (contact surfaces, tractions,
 * Dirichlet boundaries) need their facets' vertices, areas and cells. PETSc's gmsh reader finds the
 * face of a facet element (a Physical Curve in 2D, Surface in 3D) only on a mesh it interpolates,
 * and DMPlexInterpolate, creating every face and edge, was the largest part of the set-up and of its
 * memory at a million dofs (docs/scaling.md, "The figures behind the code's choices"). So the mesh is read without
 * faces and edges, and the facet elements are read from the file here (ASCII gmsh 2.2 and 4.1). On
 * rank 0 each one marks one cell it bounds: per group, a cell label whose value has bit k set when
 * the cell's face opposite its k-th vertex (cone position) is in the group, and bit
 * MM_FACET_INTERIOR + k when another cell shares that face. The marks go with the cells through the
 * distribution. Each rank then labels the vertices of its marked facets with the group's name and
 * physical tag (completed over ranks), which is what Dirichlet conditions and node sets need, and
 * MMMeshGetFacets lists a group's facets from the marks. A file this reader does not parse (binary)
 * is read by PETSc's reader, interpolated on rank 0, and its facets are its labelled faces. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mesh.h"

#define MM_FACET_NAME 256
#define MM_FACET_INTERIOR 8 /* bit of "another cell shares the face": above the dim + 1 face bits */

/* Rank 0's reading of the file: the named facet groups, and each (facet, group) pair's nodes. */
typedef struct {
  PetscInt   ngroups;
  char     (*name)[MM_FACET_NAME];
  PetscInt  *tag;      /* per group: its physical tag */
  PetscInt   n;        /* (facet, group) pairs */
  PetscSegBuffer seg;  /* while reading: the pairs as they come */
  PetscInt  *pair;     /* then: per pair, 1 + dim entries, its group and its dim node tags */
} FacetFile;

static PetscErrorCode AddPair(FacetFile *f, PetscInt dim, PetscInt g, const long nodes[])
{
  PetscInt *p;

  PetscFunctionBeginUser;
  PetscCall(PetscSegBufferGetInts(f->seg, 1 + dim, &p));
  p[0] = g;
  for (PetscInt a = 0; a < dim; ++a) p[1 + a] = (PetscInt)nodes[a];
  ++f->n;
  PetscFunctionReturn(0);
}

/* Pair i's group, and its node a. */
static inline PetscInt PairGroup(const FacetFile *f, PetscInt dim, PetscInt i)
{
  return f->pair[i * (1 + dim)];
}

static inline PetscInt PairNode(const FacetFile *f, PetscInt dim, PetscInt i, PetscInt a)
{
  return f->pair[i * (1 + dim) + 1 + a];
}

static PetscInt GroupOfTag(const FacetFile *f, long tag)
{
  for (PetscInt g = 0; g < f->ngroups; ++g)
    if (f->tag[g] == tag) return g;
  return -1;
}

/* $PhysicalNames: the groups of dimension dim-1 with a name ("dim tag "name"" per line). */
static PetscErrorCode ReadPhysicalNames(FILE *in, PetscInt dim, FacetFile *f, char **line, size_t *len, PetscBool *ok)
{
  long n = 0;

  PetscFunctionBeginUser;
  *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%ld", &n) == 1 && n >= 0);
  if (!*ok) PetscFunctionReturn(0);
  PetscCall(PetscCalloc2(n, &f->name, n, &f->tag));
  for (long i = 0; i < n && *ok; ++i) {
    int   gdim;
    long  tag;
    char *q0, *q1;
    *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%d %ld", &gdim, &tag) == 2 && (q0 = strchr(*line, '"')) && (q1 = strrchr(*line, '"')) && q1 > q0);
    if (!*ok || gdim != dim - 1) continue;
    PetscCall(PetscStrncpy(f->name[f->ngroups], q0 + 1, PetscMin((size_t)(q1 - q0), (size_t)MM_FACET_NAME)));
    f->tag[f->ngroups++] = tag;
  }
  PetscFunctionReturn(0);
}

/* $Entities (4.1): the physical tags of each entity of dimension dim-1, as (entity, group) pairs
 * appended to eg, two entries each. */
static PetscErrorCode ReadEntities(FILE *in, PetscInt dim, const FacetFile *f, PetscSegBuffer eg, PetscInt *nent, char **line, size_t *len, PetscBool *ok)
{
  long count[4];

  PetscFunctionBeginUser;
  *nent = 0;
  *ok   = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%ld %ld %ld %ld", &count[0], &count[1], &count[2], &count[3]) == 4);
  for (int d = 0; d < 4 && *ok; ++d)
    for (long i = 0; i < count[d] && *ok; ++i) {
      char *p, *e;
      long  etag, nphys;
      *ok = (PetscBool)(getline(line, len, in) > 0);
      if (!*ok || d != dim - 1) continue;
      p    = *line;
      etag = strtol(p, &e, 10);
      for (int k = 0; k < (d == 0 ? 3 : 6); ++k) {
        p = e;
        (void)strtod(p, &e);
      }
      p     = e;
      nphys = strtol(p, &e, 10);
      *ok   = (PetscBool)(e != p && nphys >= 0);
      for (long k = 0; k < nphys && *ok; ++k) {
        PetscInt g, *pair;
        p = e;
        g = GroupOfTag(f, strtol(p, &e, 10));
        *ok = (PetscBool)(e != p);
        if (g < 0) continue;
        PetscCall(PetscSegBufferGetInts(eg, 2, &pair));
        pair[0] = (PetscInt)etag;
        pair[1] = g;
        ++*nent;
      }
    }
  PetscFunctionReturn(0);
}

/* A facet element line: its nodes after the first skip values (4.1: the element tag; 2.2: the tag,
 * type, tag count and tags). */
static PetscBool ParseNodes(const char *p, PetscInt skip, PetscInt dim, long nodes[])
{
  char *e;
  for (PetscInt k = 0; k < skip + dim; ++k) {
    long v = strtol(p, &e, 10);
    if (e == p) return PETSC_FALSE;
    if (k >= skip) nodes[k - skip] = v;
    p = e;
  }
  return PETSC_TRUE;
}

/* $Elements, 4.1: blocks "entityDim entityTag type count", the facets' in the groups kept. */
static PetscErrorCode ReadElements41(FILE *in, PetscInt dim, FacetFile *f, PetscInt nent, const PetscInt eg[], char **line, size_t *len, PetscBool *ok)
{
  long nblocks, nelem, lo, hi;
  const int facet_type = dim == 3 ? 2 : 1; /* 3-node triangle, 2-node line */

  PetscFunctionBeginUser;
  *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%ld %ld %ld %ld", &nblocks, &nelem, &lo, &hi) == 4);
  for (long b = 0; b < nblocks && *ok; ++b) {
    int  edim, type;
    long etag, n;
    PetscBool kept = PETSC_FALSE;
    *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%d %ld %d %ld", &edim, &etag, &type, &n) == 4);
    if (!*ok) break;
    if (edim == dim - 1)
      for (PetscInt i = 0; i < nent; ++i) kept = (PetscBool)(kept || eg[2 * i] == etag);
    /* a facet group of another element type (second order): PETSc's reader handles it */
    if (kept && type != facet_type) *ok = PETSC_FALSE;
    for (long i = 0; i < n && *ok; ++i) {
      long nodes[3];
      *ok = (PetscBool)(getline(line, len, in) > 0);
      if (!*ok || !kept) continue;
      *ok = ParseNodes(*line, 1, dim, nodes);
      for (PetscInt k = 0; k < nent && *ok; ++k)
        if (eg[2 * k] == etag) PetscCall(AddPair(f, dim, eg[2 * k + 1], nodes));
    }
  }
  PetscFunctionReturn(0);
}

/* $Elements, 2.2: "number type ntags tags... nodes" per line; the first tag is the physical one. */
static PetscErrorCode ReadElements22(FILE *in, PetscInt dim, FacetFile *f, char **line, size_t *len, PetscBool *ok)
{
  long      nelem;
  const int facet_type = dim == 3 ? 2 : 1;

  PetscFunctionBeginUser;
  *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%ld", &nelem) == 1);
  for (long i = 0; i < nelem && *ok; ++i) {
    long     id, ntags, phys = -1, nodes[3];
    int      type;
    PetscInt g;
    *ok = (PetscBool)(getline(line, len, in) > 0 && sscanf(*line, "%ld %d %ld %ld", &id, &type, &ntags, &phys) >= 3);
    if (!*ok || type != facet_type || ntags < 1 || (g = GroupOfTag(f, phys)) < 0) continue;
    *ok = ParseNodes(*line, 3 + ntags, dim, nodes);
    if (*ok) PetscCall(AddPair(f, dim, g, nodes));
  }
  PetscFunctionReturn(0);
}

/* Rank 0: the named facet groups and their facets, from an ASCII gmsh 2.2 or 4.1 file. */
static PetscErrorCode ReadFacetFile(const char file[], PetscInt dim, FacetFile *f, PetscBool *ok)
{
  FILE     *in = fopen(file, "r");
  char     *line = NULL;
  size_t    len = 0;
  double    version = 0;
  int       binary = 1;
  PetscInt       nent = 0, *eg = NULL;
  PetscSegBuffer egs;
  PetscBool      names = PETSC_FALSE, elements = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscSegBufferCreate(sizeof(PetscInt), 64, &egs));
  PetscCall(PetscSegBufferCreate(sizeof(PetscInt), 1024 * (1 + dim), &f->seg));
  *ok = (PetscBool)(in != NULL);
  while (*ok && !elements && getline(&line, &len, in) > 0) {
    if (!strncmp(line, "$MeshFormat", 11)) {
      *ok = (PetscBool)(getline(&line, &len, in) > 0 && sscanf(line, "%lf %d", &version, &binary) == 2 && !binary && (version == 2.2 || version == 4.1));
    } else if (!strncmp(line, "$PhysicalNames", 14)) {
      PetscCall(ReadPhysicalNames(in, dim, f, &line, &len, ok));
      names = PETSC_TRUE;
    } else if (!strncmp(line, "$Entities", 9)) {
      PetscCall(ReadEntities(in, dim, f, egs, &nent, &line, &len, ok));
      PetscCall(PetscFree(eg));
      PetscCall(PetscSegBufferExtractAlloc(egs, &eg));
    } else if (!strncmp(line, "$Elements", 9)) {
      if (!names) break; /* no named group: nothing to label */
      if (version == 4.1) PetscCall(ReadElements41(in, dim, f, nent, eg, &line, &len, ok));
      else PetscCall(ReadElements22(in, dim, f, &line, &len, ok));
      elements = PETSC_TRUE;
    }
  }
  *ok = (PetscBool)(*ok && version > 0 && (elements || !names));
  free(line);
  if (in) (void)fclose(in);
  PetscCall(PetscFree(eg));
  PetscCall(PetscSegBufferDestroy(&egs));
  PetscCall(PetscSegBufferExtractAlloc(f->seg, &f->pair));
  PetscCall(PetscSegBufferDestroy(&f->seg));
  PetscFunctionReturn(0);
}

static PetscErrorCode MarkName(const char group[], char mark[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(mark, len, "%s%s", MM_MESH_FACET_MARK, group));
  PetscFunctionReturn(0);
}

/* Rank 0: each facet's first cell on the serial mesh (the first whose cone holds all its vertices),
 * marked in the group's cell label with the bit of the cone position of the vertex off the facet,
 * and its interior bit when a second cell holds it too: each facet is listed once, on one rank. vtag
 * is each serial vertex's node tag in the file. *bad is the first facet (pair) on no cell, -1 if
 * none. */
static PetscErrorCode MarkCells(DM dm, PetscInt dim, const FacetFile *f, const PetscInt vtag[], PetscInt *bad)
{
  PetscInt  vStart, vEnd, nv, cStart, cEnd, *sorted, *vert;
  DMLabel  *mark;
  PetscInt **bits;

  PetscFunctionBeginUser;
  *bad = -1;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  nv = vEnd - vStart;
  PetscCall(PetscMalloc2(nv, &sorted, nv, &vert));
  for (PetscInt k = 0; k < nv; ++k) {
    sorted[k] = vtag[k];
    vert[k]   = vStart + k;
  }
  PetscCall(PetscSortIntWithArray(nv, sorted, vert));
  PetscCall(PetscMalloc2(f->ngroups, &mark, f->ngroups, &bits));
  for (PetscInt g = 0; g < f->ngroups; ++g) {
    char name[MM_FACET_NAME + 64];
    PetscCall(MarkName(f->name[g], name, sizeof(name)));
    PetscCall(DMGetLabel(dm, name, &mark[g]));
    PetscCall(PetscCalloc1(cEnd - cStart, &bits[g]));
  }
  for (PetscInt i = 0; i < f->n && *bad < 0; ++i) {
    PetscInt        v[3], ns, found = 0, first = -1, foff = -1;
    const PetscInt *sup;
    for (PetscInt a = 0; a < dim; ++a) {
      PetscInt loc;
      PetscCall(PetscFindInt(PairNode(f, dim, i, a), nv, sorted, &loc));
      v[a] = loc >= 0 ? vert[loc] : -1;
    }
    if (v[0] >= 0) {
      PetscCall(DMPlexGetSupportSize(dm, v[0], &ns));
      PetscCall(DMPlexGetSupport(dm, v[0], &sup));
    } else ns = 0;
    for (PetscInt s = 0; s < ns && found < 2; ++s) {
      const PetscInt *cone;
      PetscInt        hits = 0, off = -1;
      PetscCall(DMPlexGetCone(dm, sup[s], &cone));
      for (PetscInt k = 0; k <= dim; ++k) {
        PetscBool in = PETSC_FALSE;
        for (PetscInt a = 0; a < dim; ++a) in = (PetscBool)(in || cone[k] == v[a]);
        if (in) ++hits;
        else off = k;
      }
      if (hits != dim) continue;
      if (!found) {
        first = sup[s] - cStart;
        foff  = off;
        bits[PairGroup(f, dim, i)][first] |= (PetscInt)1 << off;
      } else bits[PairGroup(f, dim, i)][first] |= (PetscInt)1 << (MM_FACET_INTERIOR + foff);
      ++found;
    }
    if (!found) *bad = i;
  }
  for (PetscInt g = 0; g < f->ngroups; ++g) {
    for (PetscInt c = cStart; c < cEnd; ++c)
      if (bits[g][c - cStart]) PetscCall(DMLabelSetValue(mark[g], c, bits[g][c - cStart]));
    PetscCall(PetscFree(bits[g]));
  }
  PetscCall(PetscFree2(mark, bits));
  PetscCall(PetscFree2(sorted, vert));
  PetscFunctionReturn(0);
}

/*@
  MMMeshFacetsRead - Reads the facet groups of the file and marks their cells on the serial mesh,
  read without faces

  Collective

  Input Parameters:
+ comm - the communicator of the run
. dm   - the serial mesh, on rank 0
. file - the mesh file
- vtag - rank 0's node tag of each serial vertex, NULL when the file's nodes could not be read

  Output Parameters:
+ groups - on every rank, the groups' names and physical tags
- ok     - false when the file cannot be read here (binary, or another format)

  Note:
  Reads the facet groups of the file and marks their cells on the serial mesh dm, read without faces
  (rank 0 holds it). vtag: rank 0's node tag of each serial vertex, NULL when the file's nodes could
  not be read. On every rank: the groups' names and tags in *groups, and *ok false when the file
  cannot be read here (binary, or another format): the caller reads it with PETSc's reader then.

  Level: developer

.seealso: `MMMeshRead()`, `MMMeshFacetsLabelVertices()`, `MMMeshFacetsDestroy()`
@*/
PetscErrorCode MMMeshFacetsRead(MPI_Comm comm, DM dm, const char file[], const PetscInt vtag[], MMMeshFacets *groups, PetscBool *ok)
{
  PetscMPIInt rank;
  PetscInt    dim, bad = -1, badnodes[3] = {-1, -1, -1}, badgroup = -1, flag[2];
  FacetFile   f = {0};
  PetscBool   read = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(DMGetDimension(dm, &dim));
  if (!rank && vtag) PetscCall(ReadFacetFile(file, dim, &f, &read));
  flag[0] = read;
  flag[1] = f.ngroups;
  PetscCallMPI(MPI_Bcast(flag, 2, MPIU_INT, 0, comm));
  *ok               = (PetscBool)flag[0];
  groups->ngroups   = *ok ? flag[1] : 0;
  PetscCall(PetscCalloc2(groups->ngroups, &groups->name, groups->ngroups, &groups->tag));
  if (*ok && !rank)
    for (PetscInt g = 0; g < groups->ngroups; ++g) {
      PetscCall(PetscStrncpy(groups->name[g], f.name[g], sizeof(groups->name[g])));
      groups->tag[g] = f.tag[g];
    }
  PetscCallMPI(MPI_Bcast(groups->name, (PetscMPIInt)(groups->ngroups * sizeof(groups->name[0])), MPI_CHAR, 0, comm));
  PetscCallMPI(MPI_Bcast(groups->tag, (PetscMPIInt)groups->ngroups, MPIU_INT, 0, comm));
  for (PetscInt g = 0; g < groups->ngroups; ++g) {
    char name[MM_FACET_NAME + 64];
    PetscCall(MarkName(groups->name[g], name, sizeof(name)));
    PetscCall(DMCreateLabel(dm, name));
  }
  if (*ok && !rank) {
    PetscCall(MarkCells(dm, dim, &f, vtag, &bad));
    if (bad >= 0) {
      badgroup = PairGroup(&f, dim, bad);
      for (PetscInt a = 0; a < dim; ++a) badnodes[a] = PairNode(&f, dim, bad, a);
    }
  }
  PetscCall(PetscFree2(f.name, f.tag));
  PetscCall(PetscFree(f.pair));
  PetscCallMPI(MPI_Bcast(&badgroup, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(badnodes, 3, MPIU_INT, 0, comm));
  if (badgroup >= 0) {
    char nodes[128];
    if (dim == 2) PetscCall(PetscSNPrintf(nodes, sizeof(nodes), "%" PetscInt_FMT " %" PetscInt_FMT, badnodes[0], badnodes[1]));
    else PetscCall(PetscSNPrintf(nodes, sizeof(nodes), "%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT, badnodes[0], badnodes[1], badnodes[2]));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Mesh file \"%s\" (-mesh): a facet of the physical group \"%s\" (nodes %s) is not a face of any %s. A facet group must lie on faces of the mesh's cells: regenerate the mesh from its .geo (gmsh -%" PetscInt_FMT ")", file, groups->name[badgroup], nodes, dim == 3 ? "tetrahedron" : "triangle", dim);
  }
  PetscFunctionReturn(0);
}

/* Appends facet (cell c, vertex k off it, interior) to the list, growing it. */
static PetscErrorCode FacetsAppend(MMFacetList *fl, PetscInt c, PetscInt k, PetscBool interior)
{
  PetscFunctionBeginUser;
  if (fl->n == fl->cap) {
    PetscInt  cap = PetscMax(64, 2 * fl->cap), *cell, *off;
    PetscBool *in;
    PetscCall(PetscMalloc3(cap, &cell, cap, &off, cap, &in));
    PetscCall(PetscArraycpy(cell, fl->cell, fl->n));
    PetscCall(PetscArraycpy(off, fl->off, fl->n));
    PetscCall(PetscArraycpy(in, fl->interior, fl->n));
    PetscCall(PetscFree3(fl->cell, fl->off, fl->interior));
    fl->cell     = cell;
    fl->off      = off;
    fl->interior = in;
    fl->cap      = cap;
  }
  fl->cell[fl->n]     = c;
  fl->off[fl->n]      = k;
  fl->interior[fl->n] = interior;
  ++fl->n;
  PetscFunctionReturn(0);
}

/*@
  MMMeshLabelPoints - Gives every (point, value) pair of a label on this rank

  Not collective

  Input Parameter:
. label - the label

  Output Parameters:
+ n    - the number of pairs
. pts  - the points
- vals - their values

  Note:
  Free pts and vals together with PetscFree2().

  Level: developer

.seealso: `MMMeshGetFacets()`
@*/
PetscErrorCode MMMeshLabelPoints(DMLabel label, PetscInt *n, PetscInt **pts, PetscInt **vals)
{
  IS              vis;
  PetscInt        nval, total = 0;
  const PetscInt *v;

  PetscFunctionBeginUser;
  PetscCall(DMLabelGetValueIS(label, &vis));
  PetscCall(ISGetLocalSize(vis, &nval));
  PetscCall(ISGetIndices(vis, &v));
  for (PetscInt i = 0; i < nval; ++i) {
    PetscInt size;
    PetscCall(DMLabelGetStratumSize(label, v[i], &size));
    total += size;
  }
  PetscCall(PetscMalloc2(total, pts, total, vals));
  *n = 0;
  for (PetscInt i = 0; i < nval; ++i) {
    IS              pis;
    PetscInt        np;
    const PetscInt *p;
    PetscCall(DMLabelGetStratumIS(label, v[i], &pis));
    if (!pis) continue;
    PetscCall(ISGetLocalSize(pis, &np));
    PetscCall(ISGetIndices(pis, &p));
    for (PetscInt j = 0; j < np; ++j) {
      (*pts)[*n]    = p[j];
      (*vals)[*n] = v[i];
      ++*n;
    }
    PetscCall(ISRestoreIndices(pis, &p));
    PetscCall(ISDestroy(&pis));
  }
  PetscCall(ISRestoreIndices(vis, &v));
  PetscCall(ISDestroy(&vis));
  PetscFunctionReturn(0);
}

/* The facets of a mesh read without faces, from the group's cell marks. */
static PetscErrorCode FacetsFromMarks(DM dm, DMLabel mark, MMFacetList *fl)
{
  PetscInt  n, dim, *pts, *vals;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(MMMeshLabelPoints(mark, &n, &pts, &vals));
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt k = 0; k <= dim; ++k)
      if (vals[i] >> k & 1) PetscCall(FacetsAppend(fl, pts[i], k, (PetscBool)(vals[i] >> (MM_FACET_INTERIOR + k) & 1)));
  PetscCall(PetscFree2(pts, vals));
  PetscFunctionReturn(0);
}

/*@
  MMMeshFacetsLabelVertices - Labels each facet group on the vertices of its marked facets, on the
  distributed mesh read without faces

  Collective on dm

  Input Parameters:
+ groups - the facet groups MMMeshFacetsRead() gave
- dm     - the distributed mesh

  Note:
  On the distributed mesh read without faces: each group's label (its name, its physical tag) on the
  vertices of its marked facets, completed over ranks (a vertex on the partition may sit on a rank
  that holds none of its facets). The marks stay: MMMeshGetFacets reads them.

  Level: developer

.seealso: `MMMeshDistribute()`, `MMMeshFacetsRead()`, `MMMeshGetFacets()`
@*/
PetscErrorCode MMMeshFacetsLabelVertices(MMMeshFacets *groups, DM dm)
{
  PetscInt dim;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  for (PetscInt g = 0; g < groups->ngroups; ++g) {
    char        name[MM_FACET_NAME + 64];
    DMLabel     mark, label;
    MMFacetList fl = {0};

    PetscCall(MarkName(groups->name[g], name, sizeof(name)));
    PetscCall(DMGetLabel(dm, name, &mark));
    PetscCall(DMCreateLabel(dm, groups->name[g]));
    PetscCall(DMGetLabel(dm, groups->name[g], &label));
    PetscCall(FacetsFromMarks(dm, mark, &fl));
    for (PetscInt i = 0; i < fl.n; ++i) {
      const PetscInt *cone;
      PetscCall(DMPlexGetCone(dm, fl.cell[i], &cone));
      for (PetscInt a = 0; a <= dim; ++a)
        if (a != fl.off[i]) PetscCall(DMLabelSetValue(label, cone[a], groups->tag[g]));
    }
    PetscCall(MMFacetListDestroy(&fl));
    PetscCall(DMPlexLabelComplete(dm, label));
  }
  PetscFunctionReturn(0);
}

/* The facets of an interpolated mesh (a file PETSc's reader read): the label's faces, each with its
 * first cell and the position, in MMMeshCellVertices' order, of that cell's vertex off the face. */
static PetscErrorCode FacetsFromFaces(DM dm, DMLabel label, MMFacetList *fl)
{
  PetscInt n, dim, depth, *pts, *vals;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(MMMeshLabelPoints(label, &n, &pts, &vals));
  for (PetscInt j = 0; j < n; ++j) {
    PetscInt        h, nsup, v[MM_MAX_DIM + 1], *cl = NULL, ncl, k = -1;
    const PetscInt *sup;
    PetscCall(DMPlexGetPointHeight(dm, pts[j], &h));
    if (h != 1) continue;
    PetscCall(DMPlexGetSupportSize(dm, pts[j], &nsup));
    PetscCall(DMPlexGetSupport(dm, pts[j], &sup));
    if (!nsup) continue;
    PetscCall(MMMeshCellVertices(dm, depth, dim, sup[0], v));
    PetscCall(DMPlexGetTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &cl));
    for (PetscInt a = 0; a <= dim && k < 0; ++a) {
      PetscBool in = PETSC_FALSE;
      for (PetscInt q = 0; q < ncl; ++q) in = (PetscBool)(in || cl[2 * q] == v[a]);
      if (!in) k = a;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[j], PETSC_TRUE, &ncl, &cl));
    PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Face %" PetscInt_FMT " holds every vertex of its cell", pts[j]);
    PetscCall(FacetsAppend(fl, sup[0], k, (PetscBool)(nsup > 1)));
  }
  PetscCall(PetscFree2(pts, vals));
  PetscFunctionReturn(0);
}

/*@
  MMMeshGetFacets - Lists the facets of a physical group on this rank, each once over all ranks

  Logically collective on dm

  Input Parameters:
+ dm   - the mesh
- name - the physical group's name

  Output Parameter:
. fl - the list

  Note:
  The facets of physical group name on this rank, each listed once over all ranks (a face between
  two ranks' cells on one of them): cell, position of the cell's vertex off the facet (in
  MMMeshCellVertices' order), and whether a second cell shares it. Empty for a group of cells or of
  nodes. Free with MMFacetListDestroy.

  The facets come from the group's cell marks on a mesh read without faces, else from its label's
  faces; an unknown name of an interpolated mesh is refused by MMMeshGetLabel().

  Level: intermediate

.seealso: `MMFacetListDestroy()`, `MMFacetGeometry()`, `MMMeshFacetsAddNodal()`
@*/
PetscErrorCode MMMeshGetFacets(DM dm, const char name[], MMFacetList *fl)
{
  char      mname[MM_FACET_NAME + 64];
  PetscBool marked;
  PetscInt  depth;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(fl, sizeof(*fl)));
  PetscCall(MarkName(name, mname, sizeof(mname)));
  PetscCall(DMHasLabel(dm, mname, &marked));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMGetDimension(dm, &fl->dim));
  fl->depth = depth;
  if (marked) {
    DMLabel mark;
    PetscCall(DMGetLabel(dm, mname, &mark));
    PetscCall(FacetsFromMarks(dm, mark, fl));
  } else if (depth > 1) {
    DMLabel label;
    PetscCall(MMMeshGetLabel(dm, name, &label));
    PetscCall(FacetsFromFaces(dm, label, fl));
  }
  PetscFunctionReturn(0);
}

/*@
  MMFacetListDestroy - Frees a facet list

  Not collective

  Input Parameter:
. fl - the list

  Level: intermediate

.seealso: `MMMeshGetFacets()`
@*/
PetscErrorCode MMFacetListDestroy(MMFacetList *fl)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(fl->cell, fl->off, fl->interior));
  fl->n = fl->cap = 0;
  PetscFunctionReturn(0);
}

/*@
  MMFacetGeometry - Gives a facet's vertices, their coordinates and its measure

  Not collective

  Input Parameters:
+ dm - the mesh
. fl - the facet list
. i  - the facet's index in the list
. cs - the coordinate section
- xc - the local coordinates

  Output Parameters:
+ v       - its dim vertices, local points: the cell's, in MMMeshCellVertices() order, without the
            one off the facet
. x       - their coordinates, dim x dim, or NULL
- measure - its length (2D) or area (3D)

  Note:
  Facet i's dim vertices (local points; the cell's, in order, without the one off it), their
  coordinates x (dim x dim, from the local coordinates xc of the coordinate section cs), and its
  measure (length in 2D, area in 3D). x may be NULL.

  Level: developer

.seealso: `MMMeshGetFacets()`, `MMMeshFacetsAddNodal()`, `MMMeshCellVertices()`
@*/
PetscErrorCode MMFacetGeometry(DM dm, const MMFacetList *fl, PetscInt i, PetscSection cs, const PetscScalar xc[], PetscInt v[], PetscReal x[], PetscReal *measure)
{
  const PetscInt dim = fl->dim;
  PetscInt       w[MM_MAX_DIM + 1], n = 0;
  PetscReal      y[MM_MAX_DIM * MM_MAX_DIM];

  PetscFunctionBeginUser;
  PetscCall(MMMeshCellVertices(dm, fl->depth, dim, fl->cell[i], w));
  for (PetscInt a = 0; a <= dim; ++a) {
    PetscInt off;
    if (a == fl->off[i]) continue;
    PetscCall(PetscSectionGetOffset(cs, w[a], &off));
    for (PetscInt d = 0; d < dim; ++d) y[n * dim + d] = PetscRealPart(xc[off + d]);
    v[n++] = w[a];
  }
  if (dim == 2) *measure = PetscSqrtReal(PetscSqr(y[2] - y[0]) + PetscSqr(y[3] - y[1]));
  else {
    const PetscReal a[3] = {y[3] - y[0], y[4] - y[1], y[5] - y[2]}, b[3] = {y[6] - y[0], y[7] - y[1], y[8] - y[2]};
    *measure = 0.5 * PetscSqrtReal(PetscSqr(a[1] * b[2] - a[2] * b[1]) + PetscSqr(a[2] * b[0] - a[0] * b[2]) + PetscSqr(a[0] * b[1] - a[1] * b[0]));
  }
  if (x) PetscCall(PetscArraycpy(x, y, dim * dim));
  PetscFunctionReturn(0);
}

/*@
  MMMeshFacetsDestroy - Frees the facet groups' names and tags

  Not collective

  Input Parameter:
. groups - the facet groups

  Level: developer

.seealso: `MMMeshFacetsRead()`, `MMMeshDistribute()`
@*/
PetscErrorCode MMMeshFacetsDestroy(MMMeshFacets *groups)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(groups->name, groups->tag));
  groups->ngroups = 0;
  PetscFunctionReturn(0);
}

/*@
  MMMeshFacetsAddNodal - Adds value |F| / dim at every vertex of every facet F of a list: a P1
  surface integral to the nodes

  Not collective

  Input Parameters:
+ dm    - the mesh
. fl    - the facet list
. dmv   - the DM whose local section gives each vertex's offset in a
. ncomp - the number of components
- value - the ncomp values

  Output Parameter:
. a - the local array added to

  Note:
  a[off(v) + c] += value[c] |F| / dim for every vertex v of every facet F of the list (int_F phi_v
  for P1 on a simplex facet), off(v) the vertex's offset in dmv's local section: contact areas (a
  scalar DM, value 1) and traction loads (the displacement DM, the traction). Each facet is listed
  on one rank: the caller sums a over ranks (DMLocalToGlobal with ADD).

  Level: developer

.seealso: `MMMeshGetFacets()`, `MMFacetGeometry()`
@*/
PetscErrorCode MMMeshFacetsAddNodal(DM dm, const MMFacetList *fl, DM dmv, PetscInt ncomp, const PetscReal value[], PetscScalar a[])
{
  PetscSection       cs;
  Vec                X;
  const PetscScalar *xc;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &xc));
  for (PetscInt i = 0; i < fl->n; ++i) {
    PetscInt  v[MM_MAX_DIM];
    PetscReal measure;
    PetscCall(MMFacetGeometry(dm, fl, i, cs, xc, v, NULL, &measure));
    for (PetscInt k = 0; k < fl->dim; ++k) {
      PetscInt off, end;
      PetscCall(DMPlexGetPointLocal(dmv, v[k], &off, &end));
      for (PetscInt c = 0; c < ncomp; ++c) a[off + c] += value[c] * measure / fl->dim;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &xc));
  PetscFunctionReturn(0);
}
