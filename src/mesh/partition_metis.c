/* A PetscPartitioner of type "metis" that calls serial METIS.

   Debian's PETSc 3.18 ships no usable METIS/ParMETIS partitioner, so this one
   gathers the whole cell graph on rank 0, runs METIS_PartGraphKway there and
   scatters the part of every cell back to the rank that owns it. Gathering is
   cheap here because meshes are read on rank 0 anyway (the other ranks hold no
   cells when DMPlexDistribute() first partitions).

   Vertex weights (vertSection, present when part->usevwgt is true, the PETSc
   default) are passed to METIS; target part weights (targetSection) are
   ignored, every part gets the same share.

   The cell graph (cells sharing a face) is built here from the cells' vertices
   (MMPartitionerMetisSetDM), not by PETSc: the mesh is never interpolated
   (src/mesh/facets.c), and PETSc's graph of a mesh without faces
   (DMPlexCreateNeighborCSR, a meet per pair of cells sharing a vertex) was most of a
   large mesh's set-up, sorting the faces by their vertices a small part of it (the figures:
   docs/scaling.md, "The figures behind the code's choices"). */
#include <petsc/private/partitionerimpl.h>
#include <metis.h>
#include "partition_metis.h"
#include "mesh.h"

typedef struct {
  DM dm; /* the mesh being partitioned (borrowed) */
} MetisPartitioner;

/* The whole graph in METIS' own integer type, which may differ from PetscInt. */
typedef struct {
  idx_t  nvtxs;
  idx_t *xadj, *adjncy, *vwgt;
} MetisGraph;

/* Every rank learns how many vertices each rank owns; the global numbering of
   the adjacency lists is contiguous by rank in that order. */
static PetscErrorCode GatherLayout(MPI_Comm comm, PetscInt n, PetscMPIInt counts[], PetscMPIInt displs[], PetscInt *nglobal)
{
  PetscMPIInt size, mn, r;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMPIIntCast(n, &mn));
  PetscCallMPI(MPI_Allgather(&mn, 1, MPI_INT, counts, 1, MPI_INT, comm));
  *nglobal = 0;
  for (r = 0; r < size; ++r) {
    PetscCall(PetscMPIIntCast(*nglobal, &displs[r]));
    *nglobal += counts[r];
  }
  PetscFunctionReturn(0);
}

/* Degrees rather than offsets are gathered, so rank 0 can rebuild xadj without
   shifting each rank's local CSR offsets. Weights default to 1. */
static PetscErrorCode LocalDegreesAndWeights(PetscInt n, const PetscInt start[], PetscSection vertSection, PetscInt deg[], PetscInt wgt[])
{
  PetscInt v;

  PetscFunctionBegin;
  for (v = 0; v < n; ++v) {
    deg[v] = start[v + 1] - start[v];
    wgt[v] = 1;
    if (vertSection) PetscCall(PetscSectionGetDof(vertSection, v, &wgt[v]));
  }
  PetscFunctionReturn(0);
}

/* Collective; adjacency is gathered into gadj (allocated here, on rank 0 only). */
static PetscErrorCode GatherAdjacency(MPI_Comm comm, PetscInt n, const PetscInt start[], const PetscInt adjacency[], PetscInt *gnedges, PetscInt **gadj)
{
  PetscMPIInt rank, size, mne, *counts = NULL, *displs = NULL, r;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  /* start may be NULL on ranks without vertices */
  PetscCall(PetscMPIIntCast(n ? start[n] - start[0] : 0, &mne));
  if (rank == 0) PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCallMPI(MPI_Gather(&mne, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
  *gnedges = 0;
  *gadj    = NULL;
  if (rank == 0) {
    for (r = 0; r < size; ++r) {
      PetscCall(PetscMPIIntCast(*gnedges, &displs[r]));
      *gnedges += counts[r];
    }
    PetscCall(PetscMalloc1(*gnedges, gadj));
  }
  PetscCallMPI(MPI_Gatherv(mne ? adjacency + start[0] : NULL, mne, MPIU_INT, *gadj, counts, displs, MPIU_INT, 0, comm));
  PetscCall(PetscFree2(counts, displs));
  PetscFunctionReturn(0);
}

/* Copies into idx_t arrays on rank 0, since idx_t may be 32 or 64 bit independently of PetscInt. */
static PetscErrorCode BuildMetisGraph(PetscInt nglobal, const PetscInt gdeg[], const PetscInt gwgt[], PetscInt gnedges, const PetscInt gadj[], MetisGraph *g)
{
  PetscInt v, e;

  PetscFunctionBegin;
  g->nvtxs = (idx_t)nglobal;
  PetscCall(PetscMalloc3(nglobal + 1, &g->xadj, gnedges, &g->adjncy, nglobal, &g->vwgt));
  g->xadj[0] = 0;
  for (v = 0; v < nglobal; ++v) {
    g->xadj[v + 1] = g->xadj[v] + (idx_t)gdeg[v];
    g->vwgt[v]     = (idx_t)gwgt[v];
  }
  for (e = 0; e < gnedges; ++e) g->adjncy[e] = (idx_t)gadj[e];
  PetscFunctionReturn(0);
}

/* Collective; the assembled graph is only valid on rank 0. */
static PetscErrorCode GatherGraph(MPI_Comm comm, PetscInt n, const PetscInt start[], const PetscInt adjacency[], PetscSection vertSection, const PetscMPIInt counts[], const PetscMPIInt displs[], PetscInt nglobal, MetisGraph *g)
{
  PetscMPIInt rank, mn;
  PetscInt   *deg, *wgt, *gdeg = NULL, *gwgt = NULL, *gadj = NULL, gnedges = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMPIIntCast(n, &mn));
  PetscCall(PetscMalloc2(n, &deg, n, &wgt));
  PetscCall(LocalDegreesAndWeights(n, start, vertSection, deg, wgt));
  if (rank == 0) PetscCall(PetscMalloc2(nglobal, &gdeg, nglobal, &gwgt));
  PetscCallMPI(MPI_Gatherv(deg, mn, MPIU_INT, gdeg, counts, displs, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Gatherv(wgt, mn, MPIU_INT, gwgt, counts, displs, MPIU_INT, 0, comm));
  PetscCall(GatherAdjacency(comm, n, start, adjacency, &gnedges, &gadj));
  if (rank == 0) PetscCall(BuildMetisGraph(nglobal, gdeg, gwgt, gnedges, gadj, g));
  PetscCall(PetscFree(gadj));
  PetscCall(PetscFree2(gdeg, gwgt));
  PetscCall(PetscFree2(deg, wgt));
  PetscFunctionReturn(0);
}

static PetscErrorCode DestroyMetisGraph(MetisGraph *g)
{
  PetscFunctionBegin;
  PetscCall(PetscFree3(g->xadj, g->adjncy, g->vwgt));
  PetscFunctionReturn(0);
}

static const char *MetisErrorName(int status)
{
  switch (status) {
  case METIS_ERROR_INPUT:
    return "METIS_ERROR_INPUT";
  case METIS_ERROR_MEMORY:
    return "METIS_ERROR_MEMORY";
  default:
    return "METIS_ERROR";
  }
}

/* With fewer vertices than parts METIS 5.1 still returns METIS_OK but puts
   every vertex in the same part, and edgeless graphs or a single part need no
   METIS at all: those cases get contiguous blocks of vertices instead. A METIS
   failure is returned in *status rather than raised, so rank 0 can share it. */
static PetscErrorCode RunMetis(const MetisGraph *g, PetscInt nparts, PetscInt assignment[], PetscInt *edgeCut, int *status)
{
  idx_t nvtxs = g->nvtxs, ncon = 1, np = (idx_t)nparts, objval = 0, options[METIS_NOPTIONS], *part, v;

  PetscFunctionBegin;
  *edgeCut = 0;
  *status  = METIS_OK;
  if (nparts == 1 || nvtxs <= np || g->xadj[nvtxs] == 0) {
    for (v = 0; v < nvtxs; ++v) assignment[v] = (PetscInt)(((PetscInt64)v * nparts) / nvtxs);
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(nvtxs, &part));
  *status = METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  if (*status == METIS_OK) *status = METIS_PartGraphKway(&nvtxs, &ncon, g->xadj, g->adjncy, g->vwgt, NULL, NULL, &np, NULL, NULL, options, &objval, part);
  for (v = 0; v < nvtxs; ++v) assignment[v] = (PetscInt)part[v];
  *edgeCut = (PetscInt)objval;
  PetscCall(PetscFree(part));
  PetscFunctionReturn(0);
}

/* Collective; gassign (nglobal entries) is only filled on rank 0. */
static PetscErrorCode PartitionOnRoot(PetscPartitioner part, PetscInt nparts, PetscInt n, const PetscInt start[], const PetscInt adjacency[], PetscSection vertSection, const PetscMPIInt counts[], const PetscMPIInt displs[], PetscInt nglobal, PetscInt gassign[])
{
  MPI_Comm    comm;
  PetscMPIInt rank;
  MetisGraph  g      = {0, NULL, NULL, NULL};
  int         status = METIS_OK;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetComm((PetscObject)part, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(GatherGraph(comm, n, start, adjacency, vertSection, counts, displs, nglobal, &g));
  if (rank == 0) PetscCall(RunMetis(&g, nparts, gassign, &part->edgeCut, &status));
  PetscCall(DestroyMetisGraph(&g));
  /* Broadcast first so that every rank fails together instead of deadlocking in the scatter */
  PetscCallMPI(MPI_Bcast(&status, 1, MPI_INT, 0, comm));
  PetscCheck(status == METIS_OK, comm, PETSC_ERR_LIB, "METIS_PartGraphKway() failed with %s (%d) on a graph of %" PetscInt_FMT " vertices and %" PetscInt_FMT " parts", MetisErrorName(status), status, nglobal, nparts);
  PetscCallMPI(MPI_Bcast(&part->edgeCut, 1, MPIU_INT, 0, comm));
  PetscFunctionReturn(0);
}

/* PETSc wants the local vertices listed part by part, with partSection holding
   how many of them go to each part; a counting sort keeps them in order. */
static PetscErrorCode BuildPartition(PetscInt nparts, PetscInt n, const PetscInt assignment[], PetscSection partSection, IS *partition)
{
  PetscInt *offsets, *points, v, p;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(nparts + 1, &offsets));
  PetscCall(PetscMalloc1(n, &points));
  for (v = 0; v < n; ++v) {
    PetscCheck(assignment[v] >= 0 && assignment[v] < nparts, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Vertex %" PetscInt_FMT " assigned to invalid part %" PetscInt_FMT, v, assignment[v]);
    ++offsets[assignment[v] + 1];
  }
  for (p = 0; p < nparts; ++p) {
    PetscCall(PetscSectionSetDof(partSection, p, offsets[p + 1]));
    offsets[p + 1] += offsets[p];
  }
  for (v = 0; v < n; ++v) points[offsets[assignment[v]]++] = v;
  PetscCall(PetscFree(offsets));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, points, PETSC_OWN_POINTER, partition));
  PetscFunctionReturn(0);
}

/* One face of a cell: its vertices sorted (the last unused in 2D) and the cell. */
typedef struct {
  PetscInt v[3], cell;
} Face;

static int CompareFaces(const void *a, const void *b)
{
  const Face *f = (const Face *)a, *g = (const Face *)b;
  for (int k = 0; k < 3; ++k)
    if (f->v[k] != g->v[k]) return f->v[k] < g->v[k] ? -1 : 1;
  return 0;
}

/* The dim + 1 faces of cell c (its vertices sorted, each face's without one of them). */
static PetscErrorCode CellFaces(DM dm, PetscInt depth, PetscInt dim, PetscInt c, PetscInt cStart, Face f[])
{
  PetscInt v[MM_MAX_DIM + 1];

  PetscFunctionBegin;
  PetscCall(MMMeshCellVertices(dm, depth, dim, c, v));
  PetscCall(PetscSortInt(dim + 1, v));
  for (PetscInt k = 0; k <= dim; ++k) {
    for (PetscInt a = 0, b = 0; a <= dim; ++a)
      if (a != k) f[k].v[b++] = v[a];
    if (dim == 2) f[k].v[2] = -1;
    f[k].cell = c - cStart;
  }
  PetscFunctionReturn(0);
}

/* The local cells' graph (cells sharing a face), numbered from offset: every face of every cell,
   sorted by its vertices, in buckets of its smallest vertex; a face found twice joins two cells.
   A face shared with another rank's cell is not seen: the mesh is partitioned serial, on rank 0. */
static PetscErrorCode CellGraph(DM dm, PetscInt offset, PetscInt *n, PetscInt **start, PetscInt **adj)
{
  PetscInt dim, depth, cStart, cEnd, vStart, vEnd, nf, *bucket, *deg, *fill;
  Face    *sorted, f[MM_MAX_DIM + 1];

  PetscFunctionBegin;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  *n = cEnd - cStart;
  nf = (dim + 1) * *n;
  /* the faces bucketed by their smallest vertex, in two passes over the cells (counts, then places)
   * so that they are held once: 8M faces at 1M dofs */
  PetscCall(PetscMalloc1(nf, &sorted));
  PetscCall(PetscCalloc1(vEnd - vStart + 1, &bucket));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscCall(CellFaces(dm, depth, dim, c, cStart, f));
    for (PetscInt k = 0; k <= dim; ++k) ++bucket[f[k].v[0] - vStart + 1];
  }
  for (PetscInt i = 0; i < vEnd - vStart; ++i) bucket[i + 1] += bucket[i];
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscCall(CellFaces(dm, depth, dim, c, cStart, f));
    for (PetscInt k = 0; k <= dim; ++k) sorted[bucket[f[k].v[0] - vStart]++] = f[k];
  }
  /* bucket[i] is now the end of vertex i's faces; each bucket is short (the faces at one vertex) */
  for (PetscInt i = vEnd - vStart; i > 0; --i) bucket[i] = bucket[i - 1];
  bucket[0] = 0;
  for (PetscInt i = 0; i < vEnd - vStart; ++i) qsort(&sorted[bucket[i]], (size_t)(bucket[i + 1] - bucket[i]), sizeof(Face), CompareFaces);
  PetscCall(PetscCalloc1(*n + 1, start));
  PetscCall(PetscCalloc1(PetscMax(*n, 1), &deg));
  for (PetscInt i = 0; i + 1 < nf; ++i)
    if (!CompareFaces(&sorted[i], &sorted[i + 1])) {
      ++deg[sorted[i].cell];
      ++deg[sorted[i + 1].cell];
    }
  for (PetscInt c = 0; c < *n; ++c) (*start)[c + 1] = (*start)[c] + deg[c];
  PetscCall(PetscMalloc1(PetscMax((*start)[*n], 1), adj));
  fill = deg;
  for (PetscInt c = 0; c < *n; ++c) fill[c] = (*start)[c];
  for (PetscInt i = 0; i + 1 < nf; ++i)
    if (!CompareFaces(&sorted[i], &sorted[i + 1])) {
      (*adj)[fill[sorted[i].cell]++]     = sorted[i + 1].cell + offset;
      (*adj)[fill[sorted[i + 1].cell]++] = sorted[i].cell + offset;
    }
  PetscCall(PetscFree(deg));
  PetscCall(PetscFree(bucket));
  PetscCall(PetscFree(sorted));
  PetscFunctionReturn(0);
}

static PetscErrorCode PetscPartitionerPartition_Metis(PetscPartitioner part, PetscInt nparts, PetscInt numVertices, PetscInt start[], PetscInt adjacency[], PetscSection vertSection, PetscSection targetSection, PetscSection partSection, IS *partition)
{
  MetisPartitioner *mp = (MetisPartitioner *)part->data;
  MPI_Comm          comm;
  PetscMPIInt       rank, size, *counts, *displs;
  PetscInt          nglobal = 0, *assignment, *gassign = NULL, *own_start = NULL, *own_adj = NULL;

  PetscFunctionBegin;
  if (targetSection) PetscCall(PetscInfo(part, "Partitioner %s ignores target partition weights\n", MM_PARTITIONER_METIS));
  PetscCall(PetscObjectGetComm((PetscObject)part, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCall(GatherLayout(comm, numVertices, counts, displs, &nglobal));
  if (!start) {
    PetscInt n = 0;
    PetscCheck(mp->dm, comm, PETSC_ERR_ORDER, "Call MMPartitionerMetisSetDM() before distributing the mesh");
    PetscCall(CellGraph(mp->dm, displs[rank], &n, &own_start, &own_adj));
    PetscCheck(n == numVertices, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cell graph of %" PetscInt_FMT " cells for %" PetscInt_FMT " graph vertices", n, numVertices);
    start     = own_start;
    adjacency = own_adj;
  }
  if (rank == 0) PetscCall(PetscMalloc1(nglobal, &gassign));
  PetscCall(PetscMalloc1(numVertices, &assignment));
  PetscCall(PartitionOnRoot(part, nparts, numVertices, start, adjacency, vertSection, counts, displs, nglobal, gassign));
  PetscCall(PetscFree(own_start));
  PetscCall(PetscFree(own_adj));
  PetscCallMPI(MPI_Scatterv(gassign, counts, displs, MPIU_INT, assignment, counts[rank], MPIU_INT, 0, comm));
  PetscCall(BuildPartition(nparts, numVertices, assignment, partSection, partition));
  PetscCall(PetscFree(assignment));
  PetscCall(PetscFree(gassign));
  PetscCall(PetscFree2(counts, displs));
  PetscFunctionReturn(0);
}

static PetscErrorCode PetscPartitionerDestroy_Metis(PetscPartitioner part)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(part->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode PetscPartitionerCreate_Metis(PetscPartitioner part)
{
  MetisPartitioner *mp;

  PetscFunctionBegin;
  PetscCall(PetscNew(&mp));
  part->data           = mp;
  part->noGraph        = PETSC_TRUE; /* CellGraph builds it */
  part->ops->partition = PetscPartitionerPartition_Metis;
  part->ops->destroy   = PetscPartitionerDestroy_Metis;
  PetscFunctionReturn(0);
}

/* The mesh the partitioner will be given by DMPlexDistribute: PETSc passes the partitioner no mesh. */
PetscErrorCode MMPartitionerMetisSetDM(PetscPartitioner part, DM dm)
{
  PetscBool is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)part, MM_PARTITIONER_METIS, &is));
  if (is) ((MetisPartitioner *)part->data)->dm = dm;
  PetscFunctionReturn(0);
}

PetscErrorCode MMPartitionerRegisterMetis(void)
{
  PetscFunctionBegin;
  /* PetscPartitionerRegister() does not initialize the package itself; doing it
     here registers the finalizer that frees the type list at PetscFinalize(). */
  PetscCall(PetscPartitionerInitializePackage());
  PetscCall(PetscPartitionerRegister(MM_PARTITIONER_METIS, PetscPartitionerCreate_Metis));
  PetscFunctionReturn(0);
}
