/* The deformation audit: the model is linear, small-strain elasticity (docs/method.md section 1),
 * and its answer means nothing for a body turned inside out or strained far beyond a few percent,
 * nor for a body turned by a large rotation (below).
 * Nothing else would say so: the contact audit checks the contact nodes, which may stay put while
 * the rest of the body passes through the obstacle, and the energy identity holds for any
 * displacement. So after every step each cell's deformation gradient F = I + grad u (constant on a
 * P1 simplex) is checked:
 * - det F <= 0, a cell turned inside out: the run stops (MM_ERR_PHYSICS);
 * - its largest principal strain |eps|, eps = sym(grad u), above -max_strain: the run stops;
 * - above -strain_warn: one warning, with the step, the cell and the value.
 * One pass over the cells with a few dozen flops each, on the displacement already in memory. */
#include "newmarkimpl.h"
#include "fem.h"
#include "sys.h"

/* The strain's largest principal value in magnitude: the spectral norm of the symmetric e. */
static PetscReal PrincipalStrain(PetscInt dim, const PetscReal e[MM_MAX_DIM][MM_MAX_DIM])
{
  if (dim == 2) {
    const PetscReal m = 0.5 * (e[0][0] + e[1][1]), r = PetscSqrtReal(0.25 * PetscSqr(e[0][0] - e[1][1]) + PetscSqr(e[0][1]));
    return PetscMax(PetscAbsReal(m + r), PetscAbsReal(m - r));
  } else {
    /* eigenvalues of a symmetric 3x3 matrix in closed form (trigonometric) */
    const PetscReal p1 = PetscSqr(e[0][1]) + PetscSqr(e[0][2]) + PetscSqr(e[1][2]);
    const PetscReal q  = (e[0][0] + e[1][1] + e[2][2]) / 3;
    const PetscReal p2 = PetscSqr(e[0][0] - q) + PetscSqr(e[1][1] - q) + PetscSqr(e[2][2] - q) + 2 * p1;
    const PetscReal p  = PetscSqrtReal(p2 / 6);
    PetscReal       b[3][3], r, phi, l1, l3;

    if (p == 0) return PetscAbsReal(q);
    for (PetscInt i = 0; i < 3; ++i)
      for (PetscInt j = 0; j < 3; ++j) b[i][j] = (e[i][j] - (i == j ? q : 0)) / p;
    r   = 0.5 * (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]));
    phi = r <= -1 ? PETSC_PI / 3 : r >= 1 ? 0 : PetscAcosReal(r) / 3;
    l1  = q + 2 * p * PetscCosReal(phi);
    l3  = q + 2 * p * PetscCosReal(phi + 2 * PETSC_PI / 3);
    return PetscMax(PetscAbsReal(l1), PetscAbsReal(l3));
  }
}

/* The worst cell of this rank: the smallest det F (relative) and the largest strain, with places. */
typedef struct {
  PetscReal detF, strain, rotation; /* rotation: the largest |W|^2, W = skew(grad u) (linear law) */
  PetscReal at_det[MM_MAX_DIM], at_strain[MM_MAX_DIM], at_rotation[MM_MAX_DIM];
} Worst;

/* Once: where each cell's vertices are in the local displacement and coordinate vectors. */
static PetscErrorCode CellTable(MMNewmark nm)
{
  MMDeformation *d  = &nm->deform;
  DM             dm = nm->dm, cdm;
  const PetscInt dim = nm->dim;
  const MMCells *cells;
  PetscSection   ls, cs;
  PetscInt       cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetCells(nm->op, &cells));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &cs));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  d->ncells = cEnd - cStart;
  PetscCall(PetscMalloc2((dim + 1) * d->ncells, &d->cell_u, (dim + 1) * d->ncells, &d->cell_x));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    /* any vertex order: det F and the strain do not depend on it (simplices: MMCellsCreate checked) */
    const PetscInt *v = &cells->vertex[(dim + 1) * (c - cStart)];
    for (PetscInt a = 0; a <= dim; ++a) {
      PetscCall(PetscSectionGetOffset(ls, v[a], &d->cell_u[(dim + 1) * (c - cStart) + a]));
      PetscCall(PetscSectionGetOffset(cs, v[a], &d->cell_x[(dim + 1) * (c - cStart) + a]));
    }
  }
  PetscFunctionReturn(0);
}

/* A cell's grad u = D J^{-1} and det F = det(I + grad u), with J = [X_k - X_0] and D = [U_k - U_0]
 * (columns k = 1..dim); false for a degenerate cell (refused when the mesh is read). Inlined with
 * dim a constant (ScanCellsDim), so that its small loops unroll: this runs on every cell after
 * every step (docs/scaling.md, "The figures behind the code's choices"). The inverse of J is its adjugate over det J: one division per cell. */
static inline PetscBool CellGradient(const PetscInt dim, const PetscScalar *u, const PetscScalar *x, const PetscInt *uo, const PetscInt *xo, PetscReal G[MM_MAX_DIM][MM_MAX_DIM], PetscReal *detF)
{
  PetscReal J[MM_MAX_DIM][MM_MAX_DIM], D[MM_MAX_DIM][MM_MAX_DIM], A[MM_MAX_DIM][MM_MAX_DIM], detJ, s;

  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt k = 0; k < dim; ++k) {
      J[i][k] = PetscRealPart(x[xo[k + 1] + i] - x[xo[0] + i]);
      D[i][k] = PetscRealPart(u[uo[k + 1] + i] - u[uo[0] + i]);
    }
  if (dim == 2) {
    A[0][0] = J[1][1];
    A[0][1] = -J[0][1];
    A[1][0] = -J[1][0];
    A[1][1] = J[0][0];
    detJ = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  } else {
    for (PetscInt i = 0; i < 3; ++i)
      for (PetscInt j = 0; j < 3; ++j) {
        const PetscInt i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        A[i][j] = J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1];
      }
    detJ = J[0][0] * A[0][0] + J[0][1] * A[1][0] + J[0][2] * A[2][0];
  }
  if (detJ == 0) return PETSC_FALSE;
  s = 1 / detJ;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      G[i][j] = 0;
      for (PetscInt k = 0; k < dim; ++k) G[i][j] += D[i][k] * A[k][j];
      G[i][j] *= s;
    }
  if (dim == 2) *detF = (1 + G[0][0]) * (1 + G[1][1]) - G[0][1] * G[1][0];
  else
    *detF = (1 + G[0][0]) * ((1 + G[1][1]) * (1 + G[2][2]) - G[1][2] * G[2][1]) - G[0][1] * (G[1][0] * (1 + G[2][2]) - G[1][2] * G[2][0]) + G[0][2] * (G[1][0] * G[2][1] - (1 + G[1][1]) * G[2][0]);
  return PETSC_TRUE;
}

static inline void RecordPlace(const PetscInt dim, const PetscScalar *x, const PetscInt *xo, PetscReal at[])
{
  for (PetscInt i = 0; i < dim; ++i) {
    at[i] = 0;
    for (PetscInt a = 0; a <= dim; ++a) at[i] += PetscRealPart(x[xo[a] + i]) / (dim + 1);
  }
}

/* The pass over this rank's cells, dim a constant once inlined: the smallest det F and the largest
 * strain, each with its cell's reference centroid. */
static inline void ScanCellsDim(const PetscInt dim, const PetscBool finite, const MMDeformation *d, const PetscScalar *u, const PetscScalar *x, Worst *w)
{
  for (PetscInt c = 0; c < d->ncells; ++c) {
    const PetscInt *uo = &d->cell_u[(dim + 1) * c], *xo = &d->cell_x[(dim + 1) * c];
    PetscReal       G[MM_MAX_DIM][MM_MAX_DIM], e[MM_MAX_DIM][MM_MAX_DIM], detF, strain = 0, rot = 0;

    if (!CellGradient(dim, u, x, uo, xo, G, &detF)) continue;
    /* the linear law: |W|^2 = sum_{i<j} W_ij^2 of the skew part, the square of the rotation angle,
     * and exactly the volume change det(I + W) - 1 that the law makes of a rotation it keeps unstrained */
    if (!finite)
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt j = i + 1; j < dim; ++j) rot += 0.25 * PetscSqr(G[i][j] - G[j][i]);
    if (rot > w->rotation) {
      w->rotation = rot;
      RecordPlace(dim, x, xo, w->at_rotation);
    }
    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt j = 0; j < dim; ++j) {
        e[i][j] = 0.5 * (G[i][j] + G[j][i]);
        /* the finite-strain laws: the Green strain E = (F^T F - I)/2, which a rotation leaves zero */
        if (finite)
          for (PetscInt k = 0; k < dim; ++k) e[i][j] += 0.5 * G[k][i] * G[k][j];
        strain += e[i][j] * e[i][j];
      }
    /* the largest principal value is at most the Frobenius norm: the eigenvalues (with their
     * trigonometry in 3D) only for the cells that could exceed the largest strain found so far */
    strain = PetscSqrtReal(strain);
    if (strain > w->strain || PetscIsInfOrNanReal(strain)) strain = PrincipalStrain(dim, e);
    if (detF < w->detF) {
      w->detF = detF;
      RecordPlace(dim, x, xo, w->at_det);
    }
    if (strain > w->strain || PetscIsInfOrNanReal(strain)) {
      w->strain = strain;
      RecordPlace(dim, x, xo, w->at_strain);
    }
  }
}

static PetscErrorCode ScanCells(MMNewmark nm, Vec ucart_local, Worst *w)
{
  MMDeformation     *d = &nm->deform;
  Vec                xl;
  const PetscScalar *u, *x;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(w, sizeof(*w))); /* the places too: a body at rest has no cell above strain 0 */
  w->detF   = PETSC_MAX_REAL;
  w->strain = 0;
  if (!d->cell_u) PetscCall(CellTable(nm));
  PetscCall(DMGetCoordinatesLocal(nm->dm, &xl));
  PetscCall(VecGetArrayRead(ucart_local, &u));
  PetscCall(VecGetArrayRead(xl, &x));
  if (nm->dim == 2) ScanCellsDim(2, nm->material->finite, d, u, x, w);
  else ScanCellsDim(3, nm->material->finite, d, u, x, w);
  PetscCall(VecRestoreArrayRead(xl, &x));
  PetscCall(VecRestoreArrayRead(ucart_local, &u));
  PetscFunctionReturn(0);
}

/* The place of the worst value over all ranks: the rank with the extreme sends its place. */
static PetscErrorCode GlobalWorst(MPI_Comm comm, PetscReal *value, PetscReal at[], PetscBool smallest)
{
  struct {
    double      v;
    PetscMPIInt rank;
  } mine, all;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &mine.rank));
  mine.v = smallest ? -(double)*value : (double)*value;
  PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  *value = smallest ? -(PetscReal)all.v : (PetscReal)all.v;
  PetscCallMPI(MPI_Bcast(at, MM_MAX_DIM, MPIU_REAL, all.rank, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormatPlace(PetscInt dim, const PetscReal at[], char s[], size_t len)
{
  PetscFunctionBeginUser;
  if (dim == 2) PetscCall(PetscSNPrintf(s, len, "(%.4g, %.4g)", (double)at[0], (double)at[1]));
  else PetscCall(PetscSNPrintf(s, len, "(%.4g, %.4g, %.4g)", (double)at[0], (double)at[1], (double)at[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckFiniteStrain(MMNewmark nm, const Worst *w, char place[]);
static PetscErrorCode CheckInsideOutFinite(MMNewmark nm, const Worst *w, const char place[]);
static PetscErrorCode CheckSmallStrain(MMNewmark nm, const Worst *w);

/*@
  MMDeformationCheck - Audits each cell's deformation after a step (and on the initial state):
  stops, warns once, or records the largest strain

  Collective

  Input Parameter:
. nm - the stepper's context

  Level: intermediate

.seealso: `MMDeformationView()`
@*/
PetscErrorCode MMDeformationCheck(MMNewmark nm)
{
  DM             dm   = nm->dm;
  MPI_Comm       comm = PetscObjectComm((PetscObject)dm);
  MMDeformation *d    = &nm->deform;
  const MMHistory *h  = &nm->hist;
  Vec            g, l;
  Worst          w;
  char           place[96];

  PetscFunctionBeginUser;
  if (!nm->deformation_audit) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(MM_TS_Deformation, 0, 0, 0, 0));
  PetscCall(DMGetGlobalVector(dm, &g));
  PetscCall(DMGetLocalVector(dm, &l));
  PetscCall(MMFEToCartesian(nm->op, nm->state.u, g));
  PetscCall(VecZeroEntries(l));
  PetscCall(DMGlobalToLocal(dm, g, INSERT_VALUES, l));
  /* the constrained dofs are zero in l: only nonzero Dirichlet data need inserting (a projection) */
  /* the data of the state's time: loads.t1, which a restart sets before the history's time */
  if (nm->pb.dirichlet_nonzero) PetscCall(MMLoadsInsertBoundaryValues(nm->loads, l, nm->loads->t1));
  PetscCall(ScanCells(nm, l, &w));
  PetscCall(DMRestoreLocalVector(dm, &l));
  PetscCall(DMRestoreGlobalVector(dm, &g));
  PetscCall(GlobalWorst(comm, &w.detF, w.at_det, PETSC_TRUE));
  PetscCall(GlobalWorst(comm, &w.strain, w.at_strain, PETSC_FALSE));
  if (!nm->material->finite) PetscCall(GlobalWorst(comm, &w.rotation, w.at_rotation, PETSC_FALSE));
  PetscCall(PetscLogEventEnd(MM_TS_Deformation, 0, 0, 0, 0));
  if (w.strain > d->max_strain) {
    d->max_strain = w.strain;
    d->step       = h->step;
    for (PetscInt i = 0; i < MM_MAX_DIM; ++i) d->where[i] = w.at_strain[i];
  }
  PetscCall(FormatPlace(nm->dim, w.at_det, place, sizeof(place)));
  if (nm->material->finite) PetscCall(CheckInsideOutFinite(nm, &w, place));
  PetscCheck(w.detF > 0, comm, MM_ERR_PHYSICS, "At step %" PetscInt_FMT " (t = %g) the cell at %s has turned inside out (det F = %.3g): the body passes through itself, and the result is meaningless. The impact or the load is far too strong for a small-strain model: check -v0, the loads and the units (SI), or use a finite-strain law (-elasticity svk or neohookean). The output up to the previous step is intact", h->step, (double)h->time, place, (double)w.detF);
  if (nm->material->finite) PetscCall(CheckFiniteStrain(nm, &w, place));
  else PetscCall(CheckSmallStrain(nm, &w));
  PetscFunctionReturn(0);
}

/* The finite-strain laws hold at any strain, but are sensible only while a cell keeps at least half
 * its volume: below, SVK softens to a collapse under compression and neither law is a material */
static PetscErrorCode CheckFiniteStrain(MMNewmark nm, const Worst *w, char place[])
{
  MMDeformation *d = &nm->deform;

  PetscFunctionBeginUser;
  if (w->detF < 0.5 && !d->warned) {
    const MMMaterial *mat = nm->material;
    PetscBool         svk = PETSC_FALSE;
    for (PetscInt b = 0; b < mat->n_bodies; ++b) svk = (PetscBool)(svk || mat->body[b].elasticity == MM_ELASTICITY_SVK);
    d->warned = PETSC_TRUE;
    PetscCall(PetscPrintf(nm->comm, "mmcontact warning: at step %" PetscInt_FMT " (t = %g) the cell at %s is compressed to J = det F = %.4g of its volume, below 0.5: %s, and no elasticity law is a good model of a real material (warned once)\n", nm->hist.step, (double)nm->hist.time, place, (double)w->detF,
                          svk ? "a St. Venant-Kirchhoff material softens there towards collapse" : "the neo-Hookean law's energy grows without bound as J -> 0, so the cell resists"));
  }
  PetscFunctionReturn(0);
}

/* A finite-strain cell crushed flat or inside out (det F <= 0) is not a small-strain model's failure
 * but its law's limit (docs/reference.md, "Large rotations and finite strain"): St. Venant-Kirchhoff's
 * stress stays bounded as J = det F -> 0 (its energy is of the Green strain, finite at J = 0), so a
 * hard enough landing crushes a cell flat; the neo-Hookean energy grows without bound as J -> 0
 * and holds the cell open where svk is crushed, so it reaches J <= 0 only through a step too long
 * for the impact. */
static PetscErrorCode CheckInsideOutFinite(MMNewmark nm, const Worst *w, const char place[])
{
  const MMMaterial *mat = nm->material;
  PetscBool         svk = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (w->detF > 0) PetscFunctionReturn(0);
  for (PetscInt b = 0; b < mat->n_bodies; ++b) svk = (PetscBool)(svk || mat->body[b].elasticity == MM_ELASTICITY_SVK);
  if (svk) SETERRQ(nm->comm, MM_ERR_PHYSICS, "At step %" PetscInt_FMT " (t = %g) the cell at %s is crushed flat or inside out (det F = %.3g): this is the St. Venant-Kirchhoff law's limit, not a small strain's: its stress stays finite as a cell's volume goes to zero, so a hard impact can flatten it. Use -elasticity neohookean, whose energy grows without bound as det F -> 0 (or a gentler -v0 or load). The output up to the previous step is intact", nm->hist.step, (double)nm->hist.time, place, (double)w->detF);
  SETERRQ(nm->comm, MM_ERR_PHYSICS, "At step %" PetscInt_FMT " (t = %g) the cell at %s is crushed flat or inside out (det F = %.3g): the neo-Hookean energy grows without bound as det F -> 0, so the cell got there within one step: the step is too long for this impact (a smaller -ts_dt follows it further), or the impact is far beyond the material: check -v0 against the wave speeds, the loads and the units (SI). The output up to the previous step is intact", nm->hist.step, (double)nm->hist.time, place, (double)w->detF);
}

/* The linear law: its strain is the small-strain model's, and it strains a rotated body: a rigid
 * rotation by theta has sym(grad u) = (cos theta - 1) I, so the law pulls the body back towards
 * sym(grad u) = 0, grad u = W skew, and swells it by det(I + W) - 1 = |W|^2 = theta^2 (a cube spun
 * at |omega0| 4 grows 53% in volume by t = 0.18). The strain audit cannot see it (the strain stays
 * small): the rotation is warned of once, where theta^2, the volume change it makes, passes
 * -strain_warn. */
static PetscErrorCode WarnRotation(MMNewmark nm, const Worst *w)
{
  MMDeformation *d = &nm->deform;
  char           place[96];

  PetscFunctionBeginUser;
  if (d->warned_rotation || w->rotation <= nm->strain_warn) PetscFunctionReturn(0);
  d->warned_rotation = PETSC_TRUE;
  PetscCall(FormatPlace(nm->dim, w->at_rotation, place, sizeof(place)));
  PetscCall(PetscPrintf(nm->comm, "mmcontact warning: at step %" PetscInt_FMT " (t = %g) the cell at %s has turned by %.3g rad: the linear law strains a rotated body and swells it by the square of the angle, here a volume change of %.3g, above -strain_warn %g. For large rotations use -elasticity svk (or neohookean), finite strain, which a rotation leaves unstrained (warned once)\n", nm->hist.step, (double)nm->hist.time, place, (double)PetscSqrtReal(w->rotation), (double)w->rotation, (double)nm->strain_warn));
  PetscFunctionReturn(0);
}

/* The linear law: its strain is the small-strain model's */
static PetscErrorCode CheckSmallStrain(MMNewmark nm, const Worst *wp)
{
  MMDeformation   *d    = &nm->deform;
  const MMHistory *h    = &nm->hist;
  MPI_Comm         comm = nm->comm;
  Worst            w    = *wp;
  char             place[96];

  PetscFunctionBeginUser;
  PetscCall(FormatPlace(nm->dim, w.at_strain, place, sizeof(place)));
  PetscCheck(w.strain <= nm->max_strain, comm, MM_ERR_PHYSICS, "At step %" PetscInt_FMT " (t = %g) the cell at %s has a strain of %.3g, above -max_strain %g: a small-strain model means nothing there. Check -v0, the loads and the units (SI), use a finite-strain law (-elasticity svk or neohookean), or raise -max_strain. The output up to the previous step is intact", h->step, (double)h->time, place, (double)w.strain, (double)nm->max_strain);
  if (w.strain > nm->strain_warn && !d->warned) {
    d->warned = PETSC_TRUE;
    PetscCall(PetscPrintf(comm, "mmcontact warning: at step %" PetscInt_FMT " (t = %g) the cell at %s has a strain of %.4g, above -strain_warn %g: from here on the small-strain model is an approximation; -elasticity svk (or neohookean) holds at finite strain (warned once; the summary gives the largest)\n", h->step, (double)h->time, place, (double)w.strain, (double)nm->strain_warn));
  }
  PetscCall(WarnRotation(nm, &w));
  PetscFunctionReturn(0);
}

/*@
  MMDeformationView - Prints the closing summary's line of the deformation audit: the largest strain
  of the run

  Collective

  Input Parameters:
+ nm     - the stepper's context
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `MMDeformationCheck()`, `MMNonlinearView()`
@*/
PetscErrorCode MMDeformationView(MMNewmark nm, PetscViewer viewer)
{
  const MMDeformation *d = &nm->deform;
  char                 place[96];
  PetscBool            ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!nm->deformation_audit || !ascii) PetscFunctionReturn(0);
  PetscCall(FormatPlace(nm->dim, d->where, place, sizeof(place)));
  /* -strain_warn and -max_strain apply to the linear law only: a finite-strain run's strain is the Green strain */
  if (nm->material->finite) PetscCall(PetscViewerASCIIPrintf(viewer, "  largest strain %.3e (Green strain) at step %" PetscInt_FMT ", in the cell at %s\n", (double)d->max_strain, d->step, place));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  largest strain %.3e at step %" PetscInt_FMT ", in the cell at %s (-strain_warn %g, -max_strain %g)\n", (double)d->max_strain, d->step, place, (double)nm->strain_warn, (double)nm->max_strain));
  PetscFunctionReturn(0);
}

PetscErrorCode MMDeformationDestroy(MMDeformation *d)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(d->cell_u, d->cell_x));
  PetscFunctionReturn(0);
}
