/* The signed distance to a meshed obstacle's surface (docs/method.md section 8, "A meshed obstacle").
 *
 * g(x) = s |x - p|, p the closest point of the facets and s the side of x: the sign of (x - p).N,
 * N the normal of the feature p lies on, a facet's own normal inside it, and the pseudo-normal of an
 * edge (the sum of its two facets' normals) or a vertex (3D: the sum of its facets' normals each
 * weighted by its angle there; 2D: of its two segments') on them (Baerentzen and Aanaes, IEEE TVCG
 * 2005: with these the sign is right everywhere for a closed or bounded-away surface). Its gradient
 * is n = s (x - p)/|x - p|: the facet's normal in front of a facet, and around a convex edge or
 * corner the direction from it, turning continuously (the edge rounded with radius 0), so that
 * frames that follow the contact point turn with it. Along the line from p through x the distance
 * is exactly linear, which makes a node's bound along its own normal exact for motion along it.
 *
 * A bounding-volume tree of the facets finds p in about log(facets) box tests wherever x is: near
 * the surface, or a body's node far from it (a uniform grid searched ring by ring cost 90 us per
 * node there, on a 24k-triangle box, and the frames' queries of every step became most of it). */
#include "surfaceimpl.h"

static inline void Sub(const PetscReal a[], const PetscReal b[], PetscReal c[])
{
  for (int d = 0; d < 3; ++d) c[d] = a[d] - b[d];
}

static inline PetscReal Dot(const PetscReal a[], const PetscReal b[])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void Cross(const PetscReal a[], const PetscReal b[], PetscReal c[])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline PetscReal Normalize(PetscReal a[])
{
  const PetscReal l = PetscSqrtReal(Dot(a, a));
  if (l > 0)
    for (int d = 0; d < 3; ++d) a[d] /= l;
  return l;
}

/* Two unit normals within 1e-8 rad: the surface is flat where they meet (module comment). */
static inline PetscBool Flat(const PetscReal a[], const PetscReal b[])
{
  return (PetscBool)(PetscSqr(a[0] - b[0]) + PetscSqr(a[1] - b[1]) + PetscSqr(a[2] - b[2]) < 1e-16);
}

static inline const PetscReal *Vertex(const MMSurface *s, PetscInt f, PetscInt k)
{
  return &s->x[3 * s->f[s->dim * f + k]];
}

/* Facet f's unit normal in the file's orientation: 2D (t_y, -t_x), t = b - a, the right of the
 * line's direction (a counterclockwise boundary's outside); 3D (b - a) x (c - a). */
static PetscReal FacetNormal(const MMSurface *s, PetscInt f, PetscReal n[])
{
  PetscReal e1[3], e2[3];

  Sub(Vertex(s, f, 1), Vertex(s, f, 0), e1);
  if (s->dim == 2) {
    n[0] = e1[1];
    n[1] = -e1[0];
    n[2] = 0;
  } else {
    Sub(Vertex(s, f, 2), Vertex(s, f, 0), e2);
    Cross(e1, e2, n);
  }
  return Normalize(n);
}

/* The edges (3D: vertex pairs; 2D: single vertices) and the facets on each: a facet's k-th edge is
 * shared with at most one other facet, which must run it the other way (a consistently oriented
 * surface) and on which it has the same pseudo-normal. ekey: per facet-edge its sorted key; the
 * facet-edges sorted by key, equal keys adjacent. */
typedef struct {
  PetscInt a, b, fe; /* sorted vertex pair (2D: b = -1), and facet * dim + k */
} EdgeKey;

static int CompareEdge(const void *p, const void *q)
{
  const EdgeKey *x = (const EdgeKey *)p, *y = (const EdgeKey *)q;
  if (x->a != y->a) return x->a < y->a ? -1 : 1;
  if (x->b != y->b) return x->b < y->b ? -1 : 1;
  return x->fe < y->fe ? -1 : (x->fe > y->fe);
}

/* 3D: edge k of facet f runs from vertex k to k + 1; 2D: "edge" k is vertex k, left (k = 0) or
 * reached (k = 1) by the segment. */
static void EdgeOf(const MMSurface *s, PetscInt f, PetscInt k, EdgeKey *e)
{
  const PetscInt *v = &s->f[s->dim * f];
  e->fe = s->dim * f + k;
  if (s->dim == 2) {
    e->a = v[k];
    e->b = -1;
  } else {
    const PetscInt p = v[k], q = v[(k + 1) % 3];
    e->a = PetscMin(p, q);
    e->b = PetscMax(p, q);
  }
}

/* The edges' pseudo-normals and flatness, the rim's vertices made not flat, and the orientation
 * and manifold checks, in one pass over the sorted edges. */
static PetscErrorCode EdgeNormals(MPI_Comm comm, const char option[], MMSurface *s)
{
  const PetscInt dim = s->dim, ne = dim * s->nf;
  EdgeKey       *e;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(ne, &e));
  for (PetscInt f = 0; f < s->nf; ++f)
    for (PetscInt k = 0; k < dim; ++k) EdgeOf(s, f, k, &e[dim * f + k]);
  qsort(e, (size_t)ne, sizeof(EdgeKey), CompareEdge);
  for (PetscInt i = 0; i < ne;) {
    PetscInt j = i + 1;
    while (j < ne && e[j].a == e[i].a && e[j].b == e[i].b) ++j;
    PetscCheck(j - i <= 2, comm, PETSC_ERR_USER_INPUT, "%s: %" PetscInt_FMT " facets meet at the %s of facet %" PetscInt_FMT ": an obstacle's surface is a manifold, each %s shared by at most two facets; mesh each surface once (no duplicate or crossing surfaces)", option, j - i, dim == 3 ? "edge" : "vertex", e[i].fe / dim + 1, dim == 3 ? "edge" : "vertex");
    if (j - i == 2) {
      const PetscInt f0 = e[i].fe / dim, k0 = e[i].fe % dim, f1 = e[i + 1].fe / dim, k1 = e[i + 1].fe % dim;
      /* 3D: the two facets run their common edge in opposite directions; 2D: one segment leaves the
       * vertex (k = 0) that the other reaches (k = 1) */
      const PetscBool same = dim == 3 ? (PetscBool)(s->f[3 * f0 + k0] == s->f[3 * f1 + k1]) : (PetscBool)(k0 == k1);
      PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "%s: facets %" PetscInt_FMT " and %" PetscInt_FMT " face opposite sides (their common %s is run the same way): orient the surface consistently (gmsh: reverse the surface or curve, e.g. Reverse Surface{...}; or -Curve{...} in the loop)", option, f0 + 1, f1 + 1, dim == 3 ? "edge" : "vertex");
    }
    if (dim == 3) {
      PetscReal n[3] = {0, 0, 0};
      for (PetscInt m = i; m < j; ++m)
        for (int d = 0; d < 3; ++d) n[d] += s->fn[3 * (e[m].fe / 3) + d];
      (void)Normalize(n);
      for (PetscInt m = i; m < j; ++m) {
        for (int d = 0; d < 3; ++d) s->en[3 * e[m].fe + d] = n[d];
        s->eflat[e[m].fe] = (PetscBool)(j - i == 2 && Flat(&s->fn[3 * (e[i].fe / 3)], &s->fn[3 * (e[i + 1].fe / 3)]));
      }
    }
    /* the surface's rim: beyond it the distance is to the rim, its gradient radial */
    if (j - i == 1) {
      s->vflat[e[i].a] = PETSC_FALSE;
      if (dim == 3) s->vflat[e[i].b] = PETSC_FALSE;
    }
    i = j;
  }
  PetscCall(PetscFree(e));
  PetscFunctionReturn(0);
}

/* Vertex pseudo-normals: 3D the facets' normals weighted by their angles at the vertex; 2D the
 * segments' normals; and whether the facets are flat there. */
static void VertexNormals(MMSurface *s)
{
  const PetscInt dim = s->dim;
  for (PetscInt f = 0; f < s->nf; ++f)
    for (PetscInt k = 0; k < dim; ++k) {
      PetscReal w = 1;
      if (dim == 3) {
        PetscReal a[3], b[3];
        Sub(Vertex(s, f, (k + 1) % 3), Vertex(s, f, k), a);
        Sub(Vertex(s, f, (k + 2) % 3), Vertex(s, f, k), b);
        (void)Normalize(a);
        (void)Normalize(b);
        w = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, Dot(a, b))));
      }
      for (int d = 0; d < 3; ++d) s->vn[3 * s->f[dim * f + k] + d] += w * s->fn[3 * f + d];
    }
  for (PetscInt v = 0; v < s->nv; ++v) {
    (void)Normalize(&s->vn[3 * v]);
    s->vflat[v] = PETSC_TRUE;
  }
  for (PetscInt f = 0; f < s->nf; ++f)
    for (PetscInt k = 0; k < dim; ++k) {
      const PetscInt v = s->f[dim * f + k];
      s->vflat[v]      = (PetscBool)(s->vflat[v] && Flat(&s->fn[3 * f], &s->vn[3 * v]));
    }
}

/* The facets' bounding-volume tree: each node's box holds its facets' (the leaves' at most
 * MM_TREE_LEAF of them, contiguous in s->order); split at the median of the longest axis of the
 * facets' centroids, so its depth is log2(nf / MM_TREE_LEAF). */
#define MM_TREE_LEAF 4

static void FacetBox(const MMSurface *s, PetscInt f, PetscReal lo[], PetscReal hi[])
{
  for (int d = 0; d < 3; ++d) {
    lo[d] = PETSC_MAX_REAL;
    hi[d] = PETSC_MIN_REAL;
  }
  for (PetscInt k = 0; k < s->dim; ++k)
    for (int d = 0; d < 3; ++d) {
      lo[d] = PetscMin(lo[d], Vertex(s, f, k)[d]);
      hi[d] = PetscMax(hi[d], Vertex(s, f, k)[d]);
    }
}

typedef struct {
  const PetscReal *c; /* centroids, 3 per facet */
  int              axis;
} SortContext;

static SortContext sort_ctx;

static int CompareCentroid(const void *p, const void *q)
{
  const PetscReal a = sort_ctx.c[3 * *(const PetscInt *)p + sort_ctx.axis], b = sort_ctx.c[3 * *(const PetscInt *)q + sort_ctx.axis];
  return a < b ? -1 : (a > b);
}

/* Node n over s->order[start .. end): its box, and its children made when it holds more than a leaf. */
static PetscInt BuildNode(MMSurface *s, const PetscReal c[], PetscInt start, PetscInt end)
{
  const PetscInt n = s->nnodes++;
  PetscReal     *lo = &s->box[6 * n], *hi = lo + 3, clo[3], chi[3];
  int            axis = 0;

  for (int d = 0; d < 3; ++d) {
    lo[d] = clo[d] = PETSC_MAX_REAL;
    hi[d] = chi[d] = PETSC_MIN_REAL;
  }
  for (PetscInt i = start; i < end; ++i) {
    PetscReal flo[3], fhi[3];
    FacetBox(s, s->order[i], flo, fhi);
    for (int d = 0; d < 3; ++d) {
      lo[d]  = PetscMin(lo[d], flo[d]);
      hi[d]  = PetscMax(hi[d], fhi[d]);
      clo[d] = PetscMin(clo[d], c[3 * s->order[i] + d]);
      chi[d] = PetscMax(chi[d], c[3 * s->order[i] + d]);
    }
  }
  s->child[2 * n] = -1;
  s->range[2 * n] = start;
  s->range[2 * n + 1] = end;
  if (end - start <= MM_TREE_LEAF) return n;
  for (int d = 1; d < 3; ++d)
    if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
  sort_ctx.c    = c;
  sort_ctx.axis = axis;
  qsort(&s->order[start], (size_t)(end - start), sizeof(PetscInt), CompareCentroid);
  s->child[2 * n]     = BuildNode(s, c, start, start + (end - start) / 2);
  s->child[2 * n + 1] = BuildNode(s, c, start + (end - start) / 2, end);
  return n;
}

static PetscErrorCode BuildTree(MMSurface *s)
{
  PetscReal *c;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(3 * s->nf, &c));
  for (PetscInt f = 0; f < s->nf; ++f)
    for (int d = 0; d < 3; ++d) {
      c[3 * f + d] = 0;
      for (PetscInt k = 0; k < s->dim; ++k) c[3 * f + d] += Vertex(s, f, k)[d] / s->dim;
    }
  PetscCall(PetscMalloc4(s->nf, &s->order, 12 * s->nf + 6, &s->box, 4 * s->nf + 2, &s->child, 4 * s->nf + 2, &s->range));
  for (PetscInt f = 0; f < s->nf; ++f) s->order[f] = f;
  s->nnodes = 0;
  (void)BuildNode(s, c, 0, s->nf);
  s->size = 0;
  for (int d = 0; d < 3; ++d) s->size += PetscSqr(s->box[3 + d] - s->box[d]);
  s->size = PetscSqrtReal(s->size);
  PetscCall(PetscFree(c));
  PetscFunctionReturn(0);
}

/*
  MMSurfaceSetUp - the normals (flipped with flip: the body on the other side), pseudo-normals and
  grid of a surface read by MMSurfaceRead; a surface that is not a consistently oriented manifold,
  or has a facet of zero size, is refused, named by option.
*/
PetscErrorCode MMSurfaceSetUp(MPI_Comm comm, const char option[], PetscBool flip, MMSurface *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(3 * s->nf, &s->fn));
  PetscCall(PetscCalloc1(3 * s->nv + 3, &s->vn));
  PetscCall(PetscCalloc1(s->nv + 1, &s->vflat));
  if (s->dim == 3) PetscCall(PetscCalloc2(9 * s->nf, &s->en, 3 * s->nf, &s->eflat));
  for (PetscInt f = 0; f < s->nf; ++f) {
    const PetscReal len = FacetNormal(s, f, &s->fn[3 * f]);
    PetscCheck(len > 0, comm, PETSC_ERR_USER_INPUT, "%s: facet %" PetscInt_FMT " has zero %s: remesh the surface", option, f + 1, s->dim == 3 ? "area" : "length");
    if (flip)
      for (int d = 0; d < 3; ++d) s->fn[3 * f + d] = -s->fn[3 * f + d];
  }
  VertexNormals(s);
  PetscCall(EdgeNormals(comm, option, s));
  PetscCall(BuildTree(s));
  PetscFunctionReturn(0);
}

/* The closest point p of facet f to x and the pseudo-normal N of the feature it lies on; returns
 * |x - p|^2. Triangles: Ericson, Real-Time Collision Detection (2005), section 5.1.5, by regions. */
static PetscReal ClosestOnFacet(const MMSurface *s, PetscInt f, const PetscReal x[], PetscReal p[], const PetscReal **N, PetscBool *flat)
{
  const PetscReal *a = Vertex(s, f, 0), *b = Vertex(s, f, 1);
  PetscReal        ab[3], ax[3], r[3];

  Sub(b, a, ab);
  Sub(x, a, ax);
  *flat = PETSC_TRUE;
  if (s->dim == 2) {
    const PetscReal t = Dot(ax, ab) / Dot(ab, ab);
    if (t <= 0) {
      for (int d = 0; d < 3; ++d) p[d] = a[d];
      *N    = &s->vn[3 * s->f[2 * f]];
      *flat = s->vflat[s->f[2 * f]];
    } else if (t >= 1) {
      for (int d = 0; d < 3; ++d) p[d] = b[d];
      *N    = &s->vn[3 * s->f[2 * f + 1]];
      *flat = s->vflat[s->f[2 * f + 1]];
    } else {
      for (int d = 0; d < 3; ++d) p[d] = a[d] + t * ab[d];
      *N = &s->fn[3 * f];
    }
  } else {
    const PetscReal *c = Vertex(s, f, 2);
    PetscReal        ac[3], bx[3], cx[3], d1, d2, d3, d4, d5, d6, va, vb, vc, v, w, den;
    Sub(c, a, ac);
    d1 = Dot(ab, ax);
    d2 = Dot(ac, ax);
    if (d1 <= 0 && d2 <= 0) { /* vertex a */
      for (int d = 0; d < 3; ++d) p[d] = a[d];
      *N    = &s->vn[3 * s->f[3 * f]];
      *flat = s->vflat[s->f[3 * f]];
      goto done;
    }
    Sub(x, b, bx);
    d3 = Dot(ab, bx);
    d4 = Dot(ac, bx);
    if (d3 >= 0 && d4 <= d3) { /* vertex b */
      for (int d = 0; d < 3; ++d) p[d] = b[d];
      *N    = &s->vn[3 * s->f[3 * f + 1]];
      *flat = s->vflat[s->f[3 * f + 1]];
      goto done;
    }
    vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) { /* edge ab, edge 0 */
      v = d1 / (d1 - d3);
      for (int d = 0; d < 3; ++d) p[d] = a[d] + v * ab[d];
      *N    = &s->en[9 * f + 0];
      *flat = s->eflat[3 * f + 0];
      goto done;
    }
    Sub(x, c, cx);
    d5 = Dot(ab, cx);
    d6 = Dot(ac, cx);
    if (d6 >= 0 && d5 <= d6) { /* vertex c */
      for (int d = 0; d < 3; ++d) p[d] = c[d];
      *N    = &s->vn[3 * s->f[3 * f + 2]];
      *flat = s->vflat[s->f[3 * f + 2]];
      goto done;
    }
    vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) { /* edge ca, edge 2 */
      w = d2 / (d2 - d6);
      for (int d = 0; d < 3; ++d) p[d] = a[d] + w * ac[d];
      *N    = &s->en[9 * f + 6];
      *flat = s->eflat[3 * f + 2];
      goto done;
    }
    va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) { /* edge bc, edge 1 */
      w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      for (int d = 0; d < 3; ++d) p[d] = b[d] + w * (c[d] - b[d]);
      *N    = &s->en[9 * f + 3];
      *flat = s->eflat[3 * f + 1];
      goto done;
    }
    den = 1 / (va + vb + vc);
    v   = vb * den;
    w   = vc * den;
    for (int d = 0; d < 3; ++d) p[d] = a[d] + v * ab[d] + w * ac[d];
    *N = &s->fn[3 * f];
  }
done:
  Sub(x, p, r);
  return Dot(r, r);
}

/* The squared distance from x to tree node n's box. */
static inline PetscReal BoxDistance2(const MMSurface *s, const PetscReal x[], PetscInt n)
{
  const PetscReal *lo = &s->box[6 * n], *hi = lo + 3;
  PetscReal        r  = 0;
  for (int d = 0; d < 3; ++d) {
    if (x[d] < lo[d]) r += PetscSqr(lo[d] - x[d]);
    else if (x[d] > hi[d]) r += PetscSqr(x[d] - hi[d]);
  }
  return r;
}

/*
  MMSurfaceDistance - the signed distance g of x (x[2] ignored in 2D) and n = grad g (module comment).
*/
void MMSurfaceDistance(const MMSurface *s, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscReal        y[3] = {x[0], x[1], s->dim == 3 ? x[2] : 0}, best = PETSC_MAX_REAL, p[3], bp[3] = {0, 0, 0}, r[3], sg, len;
  const PetscReal *N = NULL, *bN = NULL;
  PetscBool        flat, bflat = PETSC_TRUE;
  PetscInt         stack[128], top = 0;

  /* depth first, the nearer child first, a node skipped when its box is farther than the best */
  stack[top++] = 0;
  while (top) {
    const PetscInt n = stack[--top];
    if (BoxDistance2(s, y, n) >= best) continue;
    if (s->child[2 * n] < 0) {
      for (PetscInt i = s->range[2 * n]; i < s->range[2 * n + 1]; ++i) {
        const PetscReal d2 = ClosestOnFacet(s, s->order[i], y, p, &N, &flat);
        if (d2 < best) {
          best  = d2;
          bN    = N;
          bflat = flat;
          for (int d = 0; d < 3; ++d) bp[d] = p[d];
        }
      }
    } else {
      const PetscInt a = s->child[2 * n], b = s->child[2 * n + 1];
      const PetscBool afirst = (PetscBool)(BoxDistance2(s, y, a) <= BoxDistance2(s, y, b));
      stack[top++] = afirst ? b : a; /* the farther one waits */
      stack[top++] = afirst ? a : b;
    }
  }
  Sub(y, bp, r);
  sg  = Dot(r, bN) < 0 ? -1.0 : 1.0;
  len = PetscSqrtReal(best);
  *g  = sg * len;
  if (len > 1e-14 * s->size && !bflat) {
    for (int d = 0; d < s->dim; ++d) n[d] = sg * r[d] / len;
  } else {
    for (int d = 0; d < s->dim; ++d) n[d] = bN[d];
  }
}

PetscErrorCode MMSurfaceDestroy(MMSurface *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(s->x));
  PetscCall(PetscFree(s->f));
  PetscCall(PetscFree(s->fn));
  PetscCall(PetscFree2(s->en, s->eflat));
  PetscCall(PetscFree(s->vflat));
  PetscCall(PetscFree(s->vn));
  PetscCall(PetscFree4(s->order, s->box, s->child, s->range));
  PetscFunctionReturn(0);
}
