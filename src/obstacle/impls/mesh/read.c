/* The facets of a meshed obstacle from its gmsh file (ASCII 2.2 or 4.1): every 2-node line (2D) or
 * 3-node triangle (3D) of the file, in the file's orientation, with the nodes they use. Rank 0 reads,
 * every rank gets a copy: the obstacle is a surface, small beside the body, and each rank measures
 * its own contact nodes against all of it. What the file lacks or holds in a form this reader does
 * not take (binary, second order, no facet, a facet off the plane in 2D) is refused with the fix. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "surfaceimpl.h"

/* What rank 0 found: a message (empty: read), or the counts and arrays. */
typedef struct {
  char           why[512];
  long           maxtag;
  PetscInt      *pos;   /* node tag -> index in the file's node list, -1 if none */
  PetscReal     *xyz;   /* the file's nodes */
  long           nnodes;
  PetscSegBuffer facets; /* dim node tags per facet */
  PetscInt       nf, higher;
} Reading;

static PetscErrorCode ReadNodes(FILE *in, double version, Reading *r, char **line, size_t *len)
{
  long  blocks = 1, total = 0, lo = 0, hi = 0, k = 0;
  long *tags;

  PetscFunctionBeginUser;
  if (getline(line, len, in) <= 0) goto bad;
  if (version < 4) {
    if (sscanf(*line, "%ld", &total) != 1) goto bad;
  } else if (sscanf(*line, "%ld %ld %ld %ld", &blocks, &total, &lo, &hi) != 4) goto bad;
  if (total < 0 || total > 100000000) goto bad;
  PetscCall(PetscMalloc1(3 * total + 1, &r->xyz));
  PetscCall(PetscMalloc1(total + 1, &tags));
  if (version < 4) {
    for (k = 0; k < total; ++k) {
      double x[3];
      if (getline(line, len, in) <= 0 || sscanf(*line, "%ld %lf %lf %lf", &tags[k], &x[0], &x[1], &x[2]) != 4) break;
      for (int d = 0; d < 3; ++d) r->xyz[3 * k + d] = x[d];
    }
  } else {
    for (long b = 0; b < blocks && k <= total; ++b) {
      int  edim, etag, param;
      long nb;
      if (getline(line, len, in) <= 0 || sscanf(*line, "%d %d %d %ld", &edim, &etag, &param, &nb) != 4 || k + nb > total) break;
      for (long i = 0; i < nb; ++i) {
        if (getline(line, len, in) <= 0) break;
        tags[k + i] = strtol(*line, NULL, 10);
      }
      for (long i = 0; i < nb; ++i) {
        double x[3];
        if (getline(line, len, in) <= 0 || sscanf(*line, "%lf %lf %lf", &x[0], &x[1], &x[2]) != 3) break;
        for (int d = 0; d < 3; ++d) r->xyz[3 * (k + i) + d] = x[d];
      }
      k += nb;
    }
  }
  if (k != total) {
    PetscCall(PetscFree(tags));
    goto bad;
  }
  r->nnodes = total;
  r->maxtag = 0;
  for (long i = 0; i < total; ++i) r->maxtag = PetscMax(r->maxtag, tags[i]);
  if (r->maxtag > 8 * total + 1000000) {
    PetscCall(PetscFree(tags));
    PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its node tags run to %ld for %ld nodes: renumber them (gmsh -renumber, or Mesh.RenumberNodes)", r->maxtag, total));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(r->maxtag + 1, &r->pos));
  for (long t = 0; t <= r->maxtag; ++t) r->pos[t] = -1;
  for (long i = 0; i < total; ++i)
    if (tags[i] >= 0) r->pos[tags[i]] = (PetscInt)i;
  PetscCall(PetscFree(tags));
  PetscFunctionReturn(0);
bad:
  PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its $Nodes section could not be read"));
  PetscFunctionReturn(0);
}

/* One element of type type with its node tags from p on: kept when it is a facet. */
static PetscErrorCode KeepElement(Reading *r, PetscInt dim, int type, const char *p)
{
  const int facet = dim == 3 ? 2 : 1, second = dim == 3 ? 9 : 8; /* 3-node triangle, 2-node line; their 6- and 3-node */
  PetscInt *t;
  char     *e;

  PetscFunctionBeginUser;
  if (type == second) r->higher++;
  if (type != facet) PetscFunctionReturn(0);
  PetscCall(PetscSegBufferGetInts(r->facets, dim, &t));
  for (PetscInt a = 0; a < dim; ++a) {
    t[a] = (PetscInt)strtol(p, &e, 10);
    if (e == p) t[a] = -1;
    p = e;
  }
  r->nf++;
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadElements(FILE *in, double version, PetscInt dim, Reading *r, char **line, size_t *len)
{
  long blocks = 1, total = 0, lo, hi;

  PetscFunctionBeginUser;
  if (getline(line, len, in) <= 0) goto bad;
  if (version < 4) {
    if (sscanf(*line, "%ld", &total) != 1) goto bad;
    for (long i = 0; i < total; ++i) {
      long  id, ntags;
      int   type;
      char *p, *e;
      if (getline(line, len, in) <= 0 || sscanf(*line, "%ld %d %ld", &id, &type, &ntags) != 3) goto bad;
      p = *line;
      for (long k = 0; k < 3 + ntags; ++k) {
        (void)strtol(p, &e, 10);
        p = e;
      }
      PetscCall(KeepElement(r, dim, type, p));
    }
    PetscFunctionReturn(0);
  }
  if (sscanf(*line, "%ld %ld %ld %ld", &blocks, &total, &lo, &hi) != 4) goto bad;
  for (long b = 0; b < blocks; ++b) {
    int  edim, etag, type;
    long nb;
    if (getline(line, len, in) <= 0 || sscanf(*line, "%d %d %d %ld", &edim, &etag, &type, &nb) != 4) goto bad;
    for (long i = 0; i < nb; ++i) {
      char *e;
      if (getline(line, len, in) <= 0) goto bad;
      (void)strtol(*line, &e, 10); /* the element's tag */
      PetscCall(KeepElement(r, dim, type, e));
    }
  }
  PetscFunctionReturn(0);
bad:
  PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its $Elements section could not be read"));
  PetscFunctionReturn(0);
}

/* A section read whole is followed by its end line: a file cut inside the section's last line (a
 * node tag cut short, read as another node) is refused, not read as another surface. */
static PetscErrorCode SectionEnd(FILE *in, const char end[], Reading *r, char **line, size_t *len)
{
  size_t n;

  PetscFunctionBeginUser;
  if (r->why[0]) PetscFunctionReturn(0);
  PetscCall(PetscStrlen(end, &n));
  if (getline(line, len, in) <= 0 || strncmp(*line, end, n)) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it has no %s line where its section ends: the file is cut short or damaged; mesh the surface again", end));
  PetscFunctionReturn(0);
}

/* Rank 0: the file's nodes and facets, or why not. */
static PetscErrorCode ReadFile(const char file[], PetscInt dim, Reading *r)
{
  FILE  *in = fopen(file, "r");
  char  *line = NULL;
  size_t len = 0;
  double version = 0;
  int    binary = 0;

  PetscFunctionBeginUser;
  if (!in) {
    PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it cannot be opened (%s): give the path of a .msh file (gmsh -%" PetscInt_FMT " file.geo writes one)", strerror(errno), dim - 1));
    PetscFunctionReturn(0);
  }
  while (!r->why[0] && getline(&line, &len, in) > 0) {
    if (!strncmp(line, "$MeshFormat", 11)) {
      if (getline(&line, &len, in) <= 0 || sscanf(line, "%lf %d", &version, &binary) != 2) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its $MeshFormat line could not be read"));
      else if (binary) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it is a binary gmsh file: save it as ASCII (gmsh option -bin 0, or Mesh.Binary = 0)"));
      else if (version != 2.2 && version != 4.1) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it is gmsh format %g: save it as format 4.1 or 2.2 (gmsh -format msh41)", version));
    } else if (!strncmp(line, "$Nodes", 6)) {
      PetscCall(ReadNodes(in, version, r, &line, &len));
      PetscCall(SectionEnd(in, "$EndNodes", r, &line, &len));
    } else if (!strncmp(line, "$Elements", 9)) {
      PetscCall(ReadElements(in, version, dim, r, &line, &len));
      PetscCall(SectionEnd(in, "$EndElements", r, &line, &len));
    }
  }
  free(line);
  (void)fclose(in);
  if (r->why[0]) PetscFunctionReturn(0);
  if (!version) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it is not a gmsh .msh file (no $MeshFormat section)"));
  else if (!r->nf && r->higher) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its %s are second order: mesh it at order 1 (gmsh -order 1)", dim == 3 ? "triangles" : "lines"));
  else if (!r->nf) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "it has no %s: the obstacle's surface is its 2-node lines in 2D, its 3-node triangles in 3D (mesh the surface with gmsh -%" PetscInt_FMT ", and put it in a physical group if the file has others)", dim == 3 ? "3-node triangle" : "2-node line", dim - 1));
  PetscFunctionReturn(0);
}

/* The facets' vertices: the file's nodes they use, renumbered in the order met; a tag with no node,
 * or (2D) a node off the plane z = 0, is refused. */
static PetscErrorCode Compact(Reading *r, PetscInt dim, const PetscInt tags[], MMSurface *s)
{
  PetscInt *index;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(r->nnodes + 1, &index));
  for (long i = 0; i < r->nnodes; ++i) index[i] = -1;
  s->nf = r->nf;
  s->nv = 0;
  PetscCall(PetscMalloc1(dim * r->nf, &s->f));
  for (PetscInt k = 0; k < dim * r->nf && !r->why[0]; ++k) {
    const PetscInt t = tags[k];
    const PetscInt i = t >= 0 && t <= r->maxtag ? r->pos[t] : -1;
    if (i < 0) {
      PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "facet %" PetscInt_FMT " uses node %" PetscInt_FMT ", which is not in its $Nodes", k / dim + 1, t));
      break;
    }
    if (index[i] < 0) index[i] = s->nv++;
    s->f[k] = index[i];
  }
  PetscCall(PetscCalloc1(3 * s->nv + 3, &s->x));
  for (long i = 0; i < r->nnodes && !r->why[0]; ++i) {
    if (index[i] < 0) continue;
    for (PetscInt d = 0; d < 3; ++d) s->x[3 * index[i] + d] = r->xyz[3 * i + d];
    if (dim == 2 && s->x[3 * index[i] + 2] != 0) PetscCall(PetscSNPrintf(r->why, sizeof(r->why), "its node %ld is at z = %g: a 2D obstacle's lines lie in the plane z = 0", i + 1, (double)s->x[3 * index[i] + 2]));
    if (dim == 2) s->x[3 * index[i] + 2] = 0;
  }
  PetscCall(PetscFree(index));
  PetscFunctionReturn(0);
}

/*
  MMSurfaceRead - the facets of an obstacle's gmsh file, on every rank of comm.

  option names the file in a refusal (-obstacle_NAME_mesh).
*/
PetscErrorCode MMSurfaceRead(MPI_Comm comm, const char option[], const char file[], PetscInt dim, MMSurface *s)
{
  PetscMPIInt rank;
  Reading     r;
  PetscInt    n[2] = {0, 0}, *tags = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&r, sizeof(r)));
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->dim = dim;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    PetscCall(PetscSegBufferCreate(sizeof(PetscInt), 3 * 1024, &r.facets));
    PetscCall(ReadFile(file, dim, &r));
    PetscCall(PetscSegBufferExtractAlloc(r.facets, &tags));
    PetscCall(PetscSegBufferDestroy(&r.facets));
    if (!r.why[0]) PetscCall(Compact(&r, dim, tags, s));
    PetscCall(PetscFree(r.pos));
    PetscCall(PetscFree(r.xyz));
    PetscCall(PetscFree(tags));
  }
  PetscCallMPI(MPI_Bcast(r.why, sizeof(r.why), MPI_CHAR, 0, comm));
  PetscCheck(!r.why[0], comm, PETSC_ERR_USER_INPUT, "%s %s: %s", option, file, r.why);
  n[0] = s->nv;
  n[1] = s->nf;
  PetscCallMPI(MPI_Bcast(n, 2, MPIU_INT, 0, comm));
  if (rank) {
    s->nv = n[0];
    s->nf = n[1];
    PetscCall(PetscMalloc1(3 * s->nv + 3, &s->x));
    PetscCall(PetscMalloc1(dim * s->nf, &s->f));
  }
  PetscCallMPI(MPI_Bcast(s->x, (PetscMPIInt)(3 * s->nv), MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(s->f, (PetscMPIInt)(dim * s->nf), MPIU_INT, 0, comm));
  PetscFunctionReturn(0);
}
