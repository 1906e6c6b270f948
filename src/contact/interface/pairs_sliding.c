/* Contact pairs under large sliding (docs/method.md section 11, "Large sliding"): the slave frames of
 * the slave's own normals, the pairing found again at each step's start (the closest point at u^n, the
 * facet's normal at the predicted end) and at its end where a node ended inside the master, the change
 * of variables that carries the state across a new pairing, and the pairing's checkpoint record. The
 * pairs' set-up, projection and transform N are in pairs.c. */
#include "mesh.h"
#include "../contactimpl.h"

/* Under large sliding each slave node's frame is that of its own outward normal (the mean of its slave
 * facets' normals, weighted by their measures), not its reference master facet's: the node meets the
 * master with its own surface wherever it slides to, and its massless nu is along the rows it will have
 * there (c_0 = nu_c.nu near 1 in contact, TakeRow). Sums over the ranks that share a vertex. */
static PetscErrorCode SlaveFrames(MMContact ct)
{
  DM                 dm = ct->dm;
  const PetscInt     dim = ct->dim;
  PetscSection       ls, cs;
  Vec                X, nl, ng;
  const PetscScalar *xc, *ga;
  PetscScalar       *na;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMGetLocalVector(dm, &nl));
  PetscCall(DMGetGlobalVector(dm, &ng));
  PetscCall(VecZeroEntries(nl));
  PetscCall(VecGetArrayRead(X, &xc));
  PetscCall(VecGetArray(nl, &na));
  for (PetscInt p = 0; p < ct->pairs.n; ++p) {
    MMFacetList fl;
    PetscCall(MMMeshGetFacets(dm, ct->pb.obstacles[ct->pb.n_rigid + p].slave, &fl));
    for (PetscInt j = 0; j < fl.n; ++j) {
      PetscInt  v[MM_MAX_DIM], off;
      PetscReal f[MM_FACET_REALS], measure, len, n[MM_MAX_DIM];
      PetscCall(MMFacetGeometry(dm, &fl, j, cs, xc, v, f, &measure));
      PetscCall(MMContactPairsFacetNormal(dm, dim, fl.cell[j], f, n, &len));
      for (PetscInt d = 0; d < dim; ++d) n[d] *= measure / len; /* weighted by the facet's measure */
      for (PetscInt a = 0; a < dim; ++a) {
        PetscCall(PetscSectionGetOffset(ls, v[a], &off));
        for (PetscInt d = 0; d < dim; ++d) na[off + d] += n[d];
      }
    }
    PetscCall(MMFacetListDestroy(&fl));
  }
  PetscCall(VecRestoreArray(nl, &na));
  PetscCall(VecRestoreArrayRead(X, &xc));
  PetscCall(VecZeroEntries(ng));
  PetscCall(DMLocalToGlobal(dm, nl, ADD_VALUES, ng));
  PetscCall(DMGlobalToLocal(dm, ng, INSERT_VALUES, nl));
  PetscCall(VecGetArray(nl, &na));
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    PetscReal n[MM_MAX_DIM] = {0, 0, 0}, F[MM_MAX_DIM][MM_MAX_DIM], len = 0;
    PetscInt  off;
    if (ct->obstacle[k] < ct->pb.n_rigid || ct->second[k]) continue;
    PetscCall(PetscSectionGetOffset(ls, ct->vertex[k], &off));
    for (PetscInt d = 0; d < dim; ++d) len += PetscRealPart(na[off + d] * na[off + d]);
    len = PetscSqrtReal(len);
    for (PetscInt d = 0; d < dim; ++d) n[d] = -PetscRealPart(na[off + d]) / len; /* the frame's n is the obstacle's: minus the body's */
    MMContactFrameFromNormal(dim, n, F);
    for (PetscInt a = 0; a < MM_MAX_DIM; ++a)
      for (PetscInt b = 0; b < MM_MAX_DIM; ++b) ct->node_frame[9 * k + 3 * a + b] = F[a][b];
    /* a node whose reference master facet faces away from it: the far row of TakeRow, with its
     * reference gap as its slack, until the first step's start pairs it */
    {
      PetscReal c0 = 0;
      for (PetscInt d = 0; d < dim; ++d) c0 += ct->pairs.nuc[MM_MAX_DIM * k + d] * F[0][d];
      if (c0 <= 0.5) {
        ct->pairs.far[k]   = PETSC_TRUE;
        ct->pairs.far_d[k] = PetscRealPart(ga[k]);
        for (PetscInt d = 0; d < dim; ++d) ct->pairs.nuc[MM_MAX_DIM * k + d] = F[0][d];
      }
    }
  }
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscCall(VecRestoreArray(nl, &na));
  PetscCall(DMRestoreGlobalVector(dm, &ng));
  PetscCall(DMRestoreLocalVector(dm, &nl));
  PetscFunctionReturn(0);
}

/* -contact_pairs_sliding: large sliding finds the pairing again on the current configuration at each
 * step (docs/method.md section 11, "Large sliding"). Its transform of the state keeps the energy
 * identity and the momentum exact for the finite-strain step only, whose right-hand side carries the
 * last reaction as a force; and it keeps the slave node's frame, so the tangential relative
 * variables of friction would need M* rebuilt with a moving mass: frictionless pairs only. */
PetscErrorCode MMContactPairsResolveSliding(MMContact ct)
{
  MMContactPairs *pr       = &ct->pairs;
  PetscBool       friction = PETSC_FALSE, condensed;
  MPI_Comm        comm     = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < pr->n; ++p) friction = (PetscBool)(friction || ct->pb.obstacles[ct->pb.n_rigid + p].mu > 0);
  /* the full and active-set formulations keep copies of K~ on its first pattern, which N's changes */
  PetscCall(PetscStrcmp(ct->type, "condensed", &condensed));
  switch (ct->opt.pairs_sliding) {
  case MM_PAIRS_SLIDING_AUTO:
    pr->large = (PetscBool)(ct->material->finite && !friction && condensed);
    break;
  case MM_PAIRS_SLIDING_SMALL:
    pr->large = PETSC_FALSE;
    break;
  case MM_PAIRS_SLIDING_LARGE:
    PetscCheck(ct->material->finite, comm, PETSC_ERR_SUP, "-contact_pairs_sliding large needs a finite-strain law (-elasticity svk or neohookean): the linear model is the small-displacement one, and its step does not carry the transform of the reactions");
    PetscCheck(condensed, comm, PETSC_ERR_SUP, "-contact_pairs_sliding large needs -contact_formulation condensed (here %s): the others keep K~ on the pattern of the first pairing", ct->type);
    PetscCheck(!friction, comm, PETSC_ERR_SUP, "-contact_pairs_sliding large is frictionless only (every -contact_pair_NAME_mu 0): with friction the slave nodes' tangential dofs are relative too and carry mass, which a new pairing would move. Use -contact_pairs_sliding small");
    pr->large = PETSC_TRUE;
    break;
  }
  pr->depth = ct->opt.pairs_depth;
  if (pr->large) PetscCall(SlaveFrames(ct));
  PetscFunctionReturn(0);
}

/* Large sliding (docs/method.md section 11, "Large sliding"). Every master facet vertex's displacement,
 * gathered on every rank from w (a master node is neither a contact node nor a slave: its w is its
 * Cartesian displacement); a vertex held by Dirichlet data counts as not moving. */
static PetscErrorCode GatherMasterDisplacements(MMContact ct, Vec w)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim;

  PetscFunctionBeginUser;
  if (!pr->to_um) {
    PetscInt total = 0, *idx;
    IS       is;
    PetscCall(PetscMalloc1(pr->n + 1, &pr->um_off));
    for (PetscInt p = 0; p < pr->n; ++p) {
      pr->um_off[p] = total;
      total += pr->nf[p] * dim * dim;
    }
    pr->um_off[pr->n] = total;
    PetscCall(PetscMalloc1(total, &idx));
    for (PetscInt p = 0; p < pr->n; ++p)
      for (PetscInt f = 0; f < pr->nf[p]; ++f)
        for (PetscInt j = 0; j < dim; ++j)
          for (PetscInt d = 0; d < dim; ++d) {
            const PetscInt m = pr->df[p][f * MM_MAX_DIM + j];
            idx[pr->um_off[p] + (f * dim + j) * dim + d] = m < 0 ? 0 : m + d; /* a held vertex's entry is not read */
          }
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, total, idx, PETSC_OWN_POINTER, &is));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, total, &pr->um));
    PetscCall(VecScatterCreate(w, is, pr->um, NULL, &pr->to_um));
    PetscCall(ISDestroy(&is));
    PetscCall(VecDuplicate(w, &pr->y));
  }
  PetscCall(VecScatterBegin(pr->to_um, w, pr->um, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(pr->to_um, w, pr->um, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

/* Pair p's master facets in the current configuration: the reference records (their centroid keys
 * too, so that ties are broken as at set-up) with each vertex moved, and each facet's current
 * outward normal (oriented as the reference one). */
static void CurrentMasterSurface(MMContactPairs *pr, PetscInt dim, PetscInt p, const PetscScalar um[], PetscReal xc[])
{
  for (PetscInt f = 0; f < pr->nf[p]; ++f) {
    const PetscReal *xr = &pr->xf[p][f * MM_FACET_REALS];
    PetscReal       *x  = &xc[f * MM_FACET_REALS], *n = &x[dim * dim], len = 0, dot = 0;
    for (PetscInt i = 0; i < MM_FACET_REALS; ++i) x[i] = xr[i];
    for (PetscInt j = 0; j < dim; ++j) {
      if (pr->df[p][f * MM_MAX_DIM + j] < 0) continue;
      for (PetscInt d = 0; d < dim; ++d) x[j * dim + d] += PetscRealPart(um[pr->um_off[p] + (f * dim + j) * dim + d]);
    }
    MMContactPairsFacetCross(dim, x, n);
    for (PetscInt d = 0; d < dim; ++d) {
      len += n[d] * n[d];
      dot += n[d] * xr[dim * dim + d];
    }
    len = PetscSqrtReal(len) * (dot < 0 ? -1 : 1);
    for (PetscInt d = 0; d < dim; ++d) n[d] /= len;
  }
}

typedef struct {
  Mat N, Ninv; /* the old pairing's */
} OldPairing;

/* x <- N_new^{-1} N_old x (a displacement, velocity or acceleration) or x <- N_new^T N_old^{-T} x (a
 * force): the same Cartesian field in the new relative variables. The one carry of every w-frame
 * vector to a new pairing (held.c); fctx: the OldPairing. */
static PetscErrorCode ChangeVariables(MMContact ct, void *fctx, PetscBool force, Vec x)
{
  Vec y       = ct->pairs.y;
  Mat Nold    = ((OldPairing *)fctx)->N;
  Mat Ninvold = ((OldPairing *)fctx)->Ninv;

  PetscFunctionBeginUser;
  if (force) {
    PetscCall(MatMultTranspose(Ninvold, x, y));
    PetscCall(MatMultTranspose(ct->transform.N, y, x));
  } else {
    PetscCall(MatMult(Nold, x, y));
    PetscCall(MatMult(ct->transform.Ninv, y, x));
  }
  PetscFunctionReturn(0);
}

/* K_w = N^T K_y N and M*_w = N^T M*_y N for the new N, and K~ built anew (its pattern follows N's):
 * the formulation's factor, kept factor and Delassus columns go with it. */
static PetscErrorCode RebuildOperators(MMContact ct)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&ct->K));
  PetscCall(MatDestroy(&ct->mass.Mstar));
  PetscCall(MatPtAP(ct->pairs.Ky, ct->transform.N, MAT_INITIAL_MATRIX, 2.0, &ct->K));
  PetscCall(MatPtAP(ct->pairs.My, ct->transform.N, MAT_INITIAL_MATRIX, 2.0, &ct->mass.Mstar));
  PetscCall(MatDestroy(&ct->qp.A));
  PetscCall(MatDestroy(&ct->kept.A));
  PetscCall(MatDestroy(&ct->frame_KpN)); /* its pattern follows N */
  ct->kept.dt = -1;
  ct->Kt_dt   = -1;
  PetscFunctionReturn(0);
}

/* Pair p's master surface (facets xc) and the slave node k at x: its closest facet, the weights of the
 * closest point and the distance along that facet's normal (negative inside the master) */
static PetscInt ProjectNode(MMContactPairs *pr, PetscInt dim, PetscInt p, const PetscReal xc[], const PetscReal x[], PetscReal phi[], PetscReal *dist)
{
  const PetscInt   fb = MMContactPairsClosestFacet(dim, pr->nf[p], xc, x, phi);
  const PetscReal *f  = &xc[fb * MM_FACET_REALS];

  *dist = 0;
  for (PetscInt d = 0; d < dim; ++d) {
    PetscReal xp = 0;
    for (PetscInt j = 0; j < dim; ++j) xp += phi[j] * f[j * dim + d];
    *dist += f[dim * dim + d] * (x[d] - xp);
  }
  return fb;
}

/* Every slave node's position X_s + u_s (u: w-frame) and every pair's master surface, current for u */
static PetscErrorCode Positions(MMContact ct, Vec u, PetscReal **xc, PetscReal x[])
{
  MMContactPairs    *pr  = &ct->pairs;
  const PetscInt     dim = ct->dim;
  const PetscInt    *in;
  const PetscScalar *ya, *um;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(GatherMasterDisplacements(ct, u));
  PetscCall(VecGetArrayRead(pr->um, &um));
  for (PetscInt p = 0; p < pr->n; ++p) CurrentMasterSurface(pr, dim, p, um, xc[p]);
  PetscCall(VecRestoreArrayRead(pr->um, &um));
  /* u_s = F^T y_s, y = N u the contact-frame components */
  PetscCall(MatMult(ct->transform.N, u, pr->y));
  PetscCall(VecGetOwnershipRange(pr->y, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(pr->y, &ya));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal *F = &ct->node_frame[9 * k];
    if (ct->obstacle[k] < ct->pb.n_rigid || ct->second[k]) continue;
    for (PetscInt d = 0; d < dim; ++d) {
      x[MM_MAX_DIM * k + d] = pr->xs[MM_MAX_DIM * k + d];
      for (PetscInt a = 0; a < dim; ++a) x[MM_MAX_DIM * k + d] += F[3 * a + d] * PetscRealPart(ya[in[k] - rstart + a]);
    }
  }
  PetscCall(VecRestoreArrayRead(pr->y, &ya));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscFunctionReturn(0);
}

/* The row that turned farthest from its node's nu, beyond 60 degrees: c_0 = nu_c.nu and its pair */
typedef struct {
  double c0;
  int    p;
} Turned;

/* Stops the run, on every rank, if a row near the master turned beyond 60 degrees from its node's nu */
static PetscErrorCode TurnedTooFar(MMContact ct, Turned *worst)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, worst, 1, MPI_DOUBLE_INT, MPI_MINLOC, PetscObjectComm((PetscObject)ct->dm)));
  PetscCheck(worst->c0 > 0.5, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_NOT_CONVERGED, "Contact pair %s: a slave node near its master facet faces it at %.3g degrees from the node's normal at t = 0, beyond what large sliding carries (60 degrees): the slave node's frame is fixed at t = 0, so a body that turns this far on its master is out of reach (frames that follow the slave are not done: docs/method.md section 11, \"Large sliding\")", ct->pb.obstacles[ct->pb.n_rigid + worst->p].name, PetscAcosReal(PetscMax(PetscMin(worst->c0, 1.0), -1.0)) * 180 / PETSC_PI);
  PetscFunctionReturn(0);
}

/* A slave node at the step's start: its distance d to the master surface, its displacement relative to
 * the facet's material point, u_s - sum_j phi_j u_mj, and how far the step's predictor moves it from
 * that point */
typedef struct {
  PetscReal d, ru[MM_MAX_DIM], travel; /* travel: how far the predictor moves the node from that point */
} RowStart;

/* Slave node k's row on facet fb of pair p, with weights phi and the facet's current outward normal n:
 * w_0 = nu_c.(u_s - sum_j phi_j u_mj) <= g = n.(X_s - sum_j phi_j X_mj), nu_c = -n, which reads
 * n.(x_s - sum_j phi_j x_mj) >= 0 on the positions. A node whose facet faces away from its frame's nu
 * by more than 60 degrees, farther from the master at the step's start (st, when given) than twice the
 * predictor's travel (a node off the contact, whose closest facet is one it will not meet there), takes
 * the frame's nu as its row's direction and the bound that leaves it its distance d as slack at u^n:
 * the row cannot close within the step, and N stays well conditioned (c_0 = 1). MMContactPairsRefine()
 * stops a run where such a node ends the step nearer than half that distance. Counts in cnt the nodes whose row changed, and of those the ones that
 * changed facet. */
static PetscErrorCode TakeRow(MMContact ct, PetscInt p, PetscInt k, PetscInt fb, const PetscReal phi[], const PetscReal nf[], const RowStart *st, PetscScalar ga[], PetscScalar g0a[], PetscInt cnt[2], Turned *worst)
{
  MMContactPairs  *pr  = &ct->pairs;
  const PetscInt   dim = ct->dim;
  const PetscReal *F = &ct->node_frame[9 * k], *fr = &pr->xf[p][fb * MM_FACET_REALS], *n = nf;
  PetscReal        g = 0, c0 = 0, nfar[MM_MAX_DIM];
  PetscBool        same = (PetscBool)(fb == pr->facet[k]);

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; ++d) c0 -= n[d] * F[d];
  pr->far[k] = (PetscBool)(c0 <= 0.5 && st && st->d > 2 * st->travel + 1e-3 * ct->h_c);
  if (pr->far[k]) {
    for (PetscInt d = 0; d < dim; ++d) nfar[d] = -F[d];
    n = nfar;
    g            = st->d;
    pr->far_d[k] = st->d;
    for (PetscInt d = 0; d < dim; ++d) g -= n[d] * st->ru[d];
  } else {
    /* the row's direction against the frame's massless nu: a facet turned this far is beyond the
     * method's setting (the frame is the reference one); the caller stops the run (TurnedTooFar) */
    if (c0 <= 0.5) {
      if (c0 < worst->c0) {
        worst->c0 = c0;
        worst->p  = (int)p;
      }
      PetscFunctionReturn(0);
    }
    for (PetscInt d = 0; d < dim; ++d) {
      PetscReal xr = 0;
      for (PetscInt j = 0; j < dim; ++j) xr += phi[j] * fr[j * dim + d];
      g += n[d] * (pr->xs[MM_MAX_DIM * k + d] - xr);
    }
  }
  ga[k] = g0a[k] = g; /* a far row's bound moves with its distance; N does not */
  for (PetscInt j = 0; j < dim; ++j) same = (PetscBool)(same && phi[j] == pr->phi[MM_MAX_DIM * k + j]);
  for (PetscInt d = 0; d < dim; ++d) same = (PetscBool)(same && -n[d] == pr->nuc[MM_MAX_DIM * k + d]);
  if (same) PetscFunctionReturn(0);
  cnt[0]++;
  cnt[1] += fb != pr->facet[k];
  MMContactPairsSetPairing(pr, dim, p, k, fb, phi);
  for (PetscInt d = 0; d < dim; ++d) pr->nuc[MM_MAX_DIM * k + d] = -n[d];
  PetscFunctionReturn(0);
}

/* After rows changed: N rebuilt, every w-frame vector carried to the new variables (the Cartesian
 * state unchanged), K and M* rebuilt from the contact-frame ones */
static PetscErrorCode NewPairing(MMContact ct)
{
  OldPairing old;

  PetscFunctionBeginUser;
  old.N    = ct->transform.N;
  old.Ninv = ct->transform.Ninv;
  PetscCall(MMContactPairsBuildN(ct));
  PetscCall(MMContactHeldTransform(ct, PETSC_TRUE, ChangeVariables, &old));
  PetscCall(MatDestroy(&old.N));
  PetscCall(MatDestroy(&old.Ninv));
  PetscCall(RebuildOperators(ct));
  PetscFunctionReturn(0);
}

/*@
  MMContactSlidePairs - Finds the contact pairs' pairing again at a step's start (large sliding)
  and, where it changed, rebuilds N, K and M* and carries the w-frame vectors to the new variables

  Collective

  Input Parameters:
+ ct - the contact object
. u  - the state u^n (w-frame)
- up - the step's predictor

  Output Parameter:
. changed - the pairing changed (all ranks)

  Note:
  Each slave node takes the closest point of the master surface as it is at the step's start (u = u^n):
  its facet and weights, so that x_s - sum_j phi_j x_mj is the node's distance d along the facet's normal
  (0 for a node on the facet), and the row's value at u^n is d n_c.n whatever the row's normal n_c. That
  normal is the facet's at the step's predicted end (up, the step's predictor u + dt v + dt^2/4 a), where
  the row closes; MMContactPairsRefine() corrects it where the step ends inside the master. The row is
  w_0 = nu_c.(u_s - sum_j phi_j u_mj) <= g = n_c.(X_s - sum_j phi_j X_mj), nu_c = -n_c. Where a row
  changed, N is rebuilt, and with it K and M*; every w-frame vector, the load, the lift and the held ones
  (held.c), is carried to the new variables, so that the Cartesian state is unchanged. The ranks find
  the same pairing: the master surface and its displacements are gathered on each.
  (docs/method.md section 11, "Large sliding")

  Level: intermediate

.seealso: `MMContactPairsRefine()`, `MMContactPairsGetRecord()`, `MMContactPairsRestore()`
@*/
PetscErrorCode MMContactSlidePairs(MMContact ct, Vec u, Vec up, PetscBool *changed)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim;
  PetscScalar    *ga, *g0a;
  PetscReal     **xc, **xe, *x, *phi, pen = 0;
  PetscInt       *fb, cnt[2] = {0, 0}; /* slave nodes whose row changed, and that changed facet */
  RowStart       *st;
  Turned          worst = {1.0, 0};
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!ct->enabled || !pr->large) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_PairsSlide, 0, 0, 0, 0));
  PetscCall(PetscMalloc6(pr->n, &xc, pr->n, &xe, MM_MAX_DIM * (ct->n_local + 1), &x, MM_MAX_DIM * (ct->n_local + 1), &phi, ct->n_local + 1, &fb, ct->n_local + 1, &st));
  for (PetscInt p = 0; p < pr->n; ++p) PetscCall(PetscMalloc2(pr->nf[p] * MM_FACET_REALS, &xc[p], pr->nf[p] * MM_FACET_REALS, &xe[p]));
  PetscCall(Positions(ct, u, xc, x));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   p = ct->obstacle[k] - ct->pb.n_rigid;
    const PetscReal *f, *fr;
    if (p < 0 || ct->second[k]) continue;
    fb[k] = ProjectNode(pr, dim, p, xc[p], &x[MM_MAX_DIM * k], &phi[MM_MAX_DIM * k], &st[k].d);
    pen   = PetscMax(pen, -st[k].d);
    f     = &xc[p][fb[k] * MM_FACET_REALS];
    fr    = &pr->xf[p][fb[k] * MM_FACET_REALS];
    for (PetscInt d = 0; d < dim; ++d) {
      st[k].ru[d] = x[MM_MAX_DIM * k + d] - pr->xs[MM_MAX_DIM * k + d];
      for (PetscInt j = 0; j < dim; ++j) st[k].ru[d] -= phi[MM_MAX_DIM * k + j] * (f[j * dim + d] - fr[j * dim + d]);
    }
  }
  PetscCall(Positions(ct, up, xe, x));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt   p = ct->obstacle[k] - ct->pb.n_rigid;
    const PetscReal *f, *fr;
    PetscReal        t2 = 0;
    if (p < 0 || ct->second[k]) continue;
    f  = &xe[p][fb[k] * MM_FACET_REALS];
    fr = &pr->xf[p][fb[k] * MM_FACET_REALS];
    for (PetscInt d = 0; d < dim; ++d) {
      PetscReal r = x[MM_MAX_DIM * k + d] - pr->xs[MM_MAX_DIM * k + d] - st[k].ru[d];
      for (PetscInt j = 0; j < dim; ++j) r -= phi[MM_MAX_DIM * k + j] * (f[j * dim + d] - fr[j * dim + d]);
      t2 += r * r;
    }
    st[k].travel = PetscSqrtReal(t2);
  }
  PetscCall(VecGetArray(ct->gap, &ga));
  PetscCall(VecGetArray(ct->gap0, &g0a));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt p = ct->obstacle[k] - ct->pb.n_rigid;
    if (p < 0 || ct->second[k]) continue;
    PetscCall(TakeRow(ct, p, k, fb[k], &phi[MM_MAX_DIM * k], &xe[p][fb[k] * MM_FACET_REALS + dim * dim], &st[k], ga, g0a, cnt, &worst));
  }
  PetscCall(VecRestoreArray(ct->gap0, &g0a));
  PetscCall(VecRestoreArray(ct->gap, &ga));
  for (PetscInt p = 0; p < pr->n; ++p) PetscCall(PetscFree2(xc[p], xe[p]));
  PetscCall(PetscFree6(xc, xe, x, phi, fb, st));
  PetscCall(TurnedTooFar(ct, &worst));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &pen, 1, MPIU_REAL, MPIU_MAX, comm));
  pr->penetration = PetscMax(pr->penetration, pen);
  if (cnt[0]) {
    pr->repairs++;
    pr->facet_changes += cnt[1];
    PetscCall(NewPairing(ct));
    *changed = PETSC_TRUE;
  }
  PetscCall(PetscLogEventEnd(MMCONTACT_PairsSlide, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  MMContactPairsRefine - After a solved step under large sliding, gives the rows whose slave node ended
  inside the master's surface as it is at the step's end the pairing of that end, for the step to be
  solved again from its start

  Collective

  Input Parameters:
+ ct - the contact object
- w  - the solved step's end (w-frame)

  Output Parameter:
. changed - some row changed (all ranks): solve the step again

  Note:
  A node deeper than -contact_pairs_depth h_c' inside the master surface at w takes the normal of its
  facet there (its weights from the step's start kept, so that its row's value at u^n stays its start
  distance), or, if it ended over another facet, that facet with the weights of its end point. N, K and
  M* are rebuilt and the state carried as at a step's start. The row's normal at the step's predicted end
  misses the true end's by the predictor's error, and a node that crosses into a concave crease within
  the step penetrates the facet beyond it (docs/method.md section 11, "Large sliding").

  Level: intermediate

.seealso: `MMContactSlidePairs()`
@*/
PetscErrorCode MMContactPairsRefine(MMContact ct, Vec w, PetscBool *changed)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim;
  PetscScalar    *ga, *g0a;
  PetscReal     **xe, *x;
  PetscInt        cnt[2] = {0, 0};
  Turned          worst = {1.0, 0};

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!ct->enabled || !pr->large || pr->depth < 0) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MMCONTACT_PairsSlide, 0, 0, 0, 0));
  PetscCall(PetscMalloc2(pr->n, &xe, MM_MAX_DIM * (ct->n_local + 1), &x));
  for (PetscInt p = 0; p < pr->n; ++p) PetscCall(PetscMalloc1(pr->nf[p] * MM_FACET_REALS, &xe[p]));
  PetscCall(Positions(ct, w, xe, x));
  PetscCall(VecGetArray(ct->gap, &ga));
  PetscCall(VecGetArray(ct->gap0, &g0a));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt p = ct->obstacle[k] - ct->pb.n_rigid;
    PetscReal      phi[MM_MAX_DIM] = {0, 0, 0}, dist;
    PetscInt       fb;
    if (p < 0 || ct->second[k]) continue;
    fb = ProjectNode(pr, dim, p, xe[p], &x[MM_MAX_DIM * k], phi, &dist);
    /* a far row (TakeRow) that ended nearer than half its start's distance: its direction was not the
     * facet's, and TakeRow refuses it */
    if (-dist <= pr->depth * ct->h_c && !(pr->far[k] && dist < 0.5 * pr->far_d[k])) continue;
    if (fb == pr->facet[k])
      for (PetscInt j = 0; j < dim; ++j) phi[j] = pr->phi[MM_MAX_DIM * k + j];
    PetscCall(TakeRow(ct, p, k, fb, phi, &xe[p][fb * MM_FACET_REALS + dim * dim], NULL, ga, g0a, cnt, &worst));
  }
  PetscCall(VecRestoreArray(ct->gap0, &g0a));
  PetscCall(VecRestoreArray(ct->gap, &ga));
  for (PetscInt p = 0; p < pr->n; ++p) PetscCall(PetscFree(xe[p]));
  PetscCall(PetscFree2(xe, x));
  PetscCall(TurnedTooFar(ct, &worst));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ct->dm)));
  if (cnt[0]) {
    pr->resolves++;
    pr->facet_changes += cnt[1];
    PetscCall(NewPairing(ct));
    *changed = PETSC_TRUE;
  }
  PetscCall(PetscLogEventEnd(MMCONTACT_PairsSlide, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* ---- Checkpoints of large sliding (docs/method.md section 9 and section 11, "Large sliding") ----
 * The state w is relative to the pairing of its step: the checkpoint keeps, per slave node, its facet
 * (by the facet's reference centroid key, which does not depend on the partition), weights, row
 * direction nu_c and gap, MM_CONTACT_PAIR_RECORD reals. */
static PetscBool PairSlides(MMContact ct, PetscInt k)
{
  return (PetscBool)(ct->enabled && ct->pairs.large && ct->obstacle[k] >= ct->pb.n_rigid && !ct->second[k]);
}

/*@
  MMContactPairsGetRecord - Gives a contact row's large-sliding pairing record for a checkpoint

  Not collective

  Input Parameters:
+ ct - the contact object
- k  - the owned contact row

  Output Parameters:
+ has - the row is a sliding pair's (else rec is not set)
- rec - its record, MM_CONTACT_PAIR_RECORD reals

  Level: developer

.seealso: `MMContactPairsRestore()`, `MMContactPairsGetCounters()`
@*/
PetscErrorCode MMContactPairsGetRecord(MMContact ct, PetscInt k, PetscBool *has, PetscScalar rec[])
{
  MMContactPairs    *pr  = &ct->pairs;
  const PetscInt     dim = ct->dim;
  const PetscScalar *ga;

  PetscFunctionBeginUser;
  *has = PairSlides(ct, k);
  if (!*has) PetscFunctionReturn(0);
  {
    const PetscInt   p   = ct->obstacle[k] - ct->pb.n_rigid;
    const PetscReal *key = &pr->xf[p][pr->facet[k] * MM_FACET_REALS + dim * dim + dim];
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) {
      rec[d]                  = d < dim ? key[d] : 0;
      rec[MM_MAX_DIM + d]     = pr->phi[MM_MAX_DIM * k + d];
      rec[2 * MM_MAX_DIM + d] = pr->nuc[MM_MAX_DIM * k + d];
    }
  }
  PetscCall(VecGetArrayRead(ct->gap, &ga));
  rec[3 * MM_MAX_DIM] = ga[k];
  PetscCall(VecRestoreArrayRead(ct->gap, &ga));
  PetscFunctionReturn(0);
}

/* Pair p's facet whose reference centroid key is key, -1 if none */
static PetscInt FacetOfKey(MMContactPairs *pr, PetscInt dim, PetscInt p, const PetscScalar key[])
{
  for (PetscInt f = 0; f < pr->nf[p]; ++f) {
    const PetscReal *c    = &pr->xf[p][f * MM_FACET_REALS + dim * dim + dim];
    PetscBool        same = PETSC_TRUE;
    for (PetscInt d = 0; d < dim; ++d) same = (PetscBool)(same && c[d] == PetscRealPart(key[d]));
    if (same) return f;
  }
  return -1;
}

/*@
  MMContactPairsRestore - Restores each slave node's pairing from a checkpoint's records (-restart)
  and builds N, K and M* for it

  Collective

  Input Parameters:
+ ct  - the contact object, set up
- rec - the owned rows' records, as MMContactPairsGetRecord() wrote them

  Output Parameter:
. changed - the pairing differs from the set-up's (all ranks)

  Note:
  -restart: each slave node (rec: n_local records, as MMContactPairsGetRecord wrote them) takes the
  checkpoint's pairing, and N, K and M* are built for it as a new pairing builds them
  (MMContactSlidePairs); *changed: the pairing differs from the set-up's (all ranks). The state and the
  forces the stepper carries are read from the checkpoint in these variables: nothing is transformed.

  Level: developer

.seealso: `MMContactPairsGetRecord()`, `MMContactSlidePairs()`
@*/
PetscErrorCode MMContactPairsRestore(MMContact ct, const PetscScalar rec[], PetscBool *changed)
{
  MMContactPairs *pr  = &ct->pairs;
  const PetscInt  dim = ct->dim, bs = MM_CONTACT_PAIR_RECORD;
  PetscInt        cnt[2] = {0, 0}; /* changed, not found */
  PetscScalar    *ga, *g0a;
  MPI_Comm        comm = PetscObjectComm((PetscObject)ct->dm);

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!ct->enabled || !pr->large) PetscFunctionReturn(0);
  PetscCall(VecGetArray(ct->gap, &ga));
  PetscCall(VecGetArray(ct->gap0, &g0a));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscScalar *r = &rec[bs * k];
    const PetscInt     p = ct->obstacle[k] - ct->pb.n_rigid;
    PetscReal          phi[MM_MAX_DIM];
    PetscInt           fb;
    PetscBool          same;
    if (!PairSlides(ct, k)) continue;
    fb = FacetOfKey(pr, dim, p, r);
    if (fb < 0) {
      cnt[1]++;
      continue;
    }
    same = (PetscBool)(fb == pr->facet[k] && ga[k] == PetscRealPart(r[3 * MM_MAX_DIM]));
    for (PetscInt d = 0; d < dim; ++d) {
      phi[d] = PetscRealPart(r[MM_MAX_DIM + d]);
      same   = (PetscBool)(same && phi[d] == pr->phi[MM_MAX_DIM * k + d] && PetscRealPart(r[2 * MM_MAX_DIM + d]) == pr->nuc[MM_MAX_DIM * k + d]);
    }
    if (same) continue;
    cnt[0]++;
    MMContactPairsSetPairing(pr, dim, p, k, fb, phi);
    for (PetscInt d = 0; d < dim; ++d) pr->nuc[MM_MAX_DIM * k + d] = PetscRealPart(r[2 * MM_MAX_DIM + d]);
    ga[k] = g0a[k] = PetscRealPart(r[3 * MM_MAX_DIM]);
  }
  PetscCall(VecRestoreArray(ct->gap0, &g0a));
  PetscCall(VecRestoreArray(ct->gap, &ga));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!cnt[1], comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint pairs %" PetscInt_FMT " slave nodes with master facets this mesh does not have: it is of another mesh, or damaged. Restart with the mesh and -contact_pairs of the run that wrote it", cnt[1]);
  if (!cnt[0]) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&ct->transform.N));
  PetscCall(MatDestroy(&ct->transform.Ninv));
  PetscCall(MMContactPairsBuildN(ct));
  PetscCall(RebuildOperators(ct));
  PetscCall(MMContactHeldInvalidate(ct));
  *changed = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@
  MMContactPairsGetCounters - Gives the run's large-sliding counters for the summary and a
  checkpoint

  Not collective

  Input Parameter:
. ct - the contact object

  Output Parameter:
. c - steps that paired anew, facet changes, the deepest penetration

  Note:
  The run's large-sliding counters (the summary's): steps that paired anew, facet changes, the deepest penetration

  Level: developer

.seealso: `MMContactPairsSetCounters()`
@*/
PetscErrorCode MMContactPairsGetCounters(MMContact ct, PetscReal c[3])
{
  PetscFunctionBeginUser;
  c[0] = ct->pairs.repairs;
  c[1] = ct->pairs.facet_changes;
  c[2] = ct->pairs.penetration;
  PetscFunctionReturn(0);
}

/*@
  MMContactPairsSetCounters - Sets the run's large-sliding counters, from a checkpoint

  Not collective

  Input Parameters:
+ ct - the contact object
- c  - steps that paired anew, facet changes, the deepest penetration

  Level: developer

.seealso: `MMContactPairsGetCounters()`
@*/
PetscErrorCode MMContactPairsSetCounters(MMContact ct, const PetscReal c[3])
{
  PetscFunctionBeginUser;
  ct->pairs.repairs       = (PetscInt)c[0];
  ct->pairs.facet_changes = (PetscInt)c[1];
  ct->pairs.penetration   = c[2];
  PetscFunctionReturn(0);
}
