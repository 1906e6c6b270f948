/* The elasticity laws of -elasticity (docs/method.md section 13): each a table of pointwise
 * functions of the displacement gradient G = grad u (F = I + G), per unit reference volume, in plane
 * strain in 2D.
 * - linear: the paper's small-strain model, sigma(eps) with eps = sym(G);
 * - svk: St. Venant-Kirchhoff, W = lambda/2 (tr E)^2 + mu E:E, E = (G + G^T + G^T G)/2;
 * - neohookean: W = mu (tr E - ln J) + lambda/2 (ln J)^2, J = det F (mu/2 (tr C - 3) - mu ln J + ...).
 * The algorithmic stress of a step from G0 to G1 makes its work on the step equal the energy change
 * exactly: the stress at the mean strain (linear and svk, whose energies are quadratic in the strain),
 * and Gonzalez's discrete gradient for neo-Hookean (docs/method.md section 13).
 *
 * Everything is formed from G, never from F or C minus the identity: at the strains of 1e-7 of a
 * small-amplitude run, C - I would keep 9 digits and the neo-Hookean energy, a difference of O(eps)
 * terms, none. */
#include "elasticityimpl.h"

typedef PetscReal Mat3[MM_MAX_DIM][MM_MAX_DIM];

static PetscReal Contract(PetscInt dim, const Mat3 A, const Mat3 B)
{
  PetscReal s = 0;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) s += A[i][j] * B[i][j];
  return s;
}

static PetscReal Trace(PetscInt dim, const Mat3 A)
{
  PetscReal s = 0;
  for (PetscInt i = 0; i < dim; ++i) s += A[i][i];
  return s;
}

/* E = (G + G^T + G^T G)/2 */
static void GreenStrain(PetscInt dim, const Mat3 G, Mat3 E)
{
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      E[i][j] = 0.5 * (G[i][j] + G[j][i]);
      for (PetscInt k = 0; k < dim; ++k) E[i][j] += 0.5 * G[k][i] * G[k][j];
    }
}

/* det(I + A) - 1 from the invariants of A, without cancelling against 1 */
static PetscReal DetIPlusMinusOne(PetscInt dim, const Mat3 A)
{
  if (dim == 2) return A[0][0] + A[1][1] + A[0][0] * A[1][1] - A[0][1] * A[1][0];
  {
    const PetscReal tr = A[0][0] + A[1][1] + A[2][2];
    const PetscReal i2 = A[0][0] * A[1][1] - A[0][1] * A[1][0] + A[1][1] * A[2][2] - A[1][2] * A[2][1] + A[0][0] * A[2][2] - A[0][2] * A[2][0];
    const PetscReal i3 = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) + A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    return tr + i2 + i3;
  }
}

/* x - log(1 + x), by its series where the difference would cancel */
static PetscReal XMinusLog1p(PetscReal x)
{
  if (PetscAbsReal(x) > 1e-2) return x - log1p(x);
  {
    PetscReal s = 0, p = x;
    for (PetscInt k = 2; k <= 10; ++k) {
      p *= x;
      s += ((k % 2) ? -1.0 : 1.0) * p / k;
    }
    return s;
  }
}

/* ---------------------------------------------------------------- the laws on E: W, S = dW/dE, D = dS/dE */

static PetscReal SVKEnergyE(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E)
{
  return 0.5 * lam * PetscSqr(Trace(dim, E)) + mu * Contract(dim, E, E);
}

static void SVKStressE(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E, Mat3 S)
{
  const PetscReal trE = Trace(dim, E);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) S[i][j] = 2 * mu * E[i][j] + (i == j ? lam * trE : 0);
}

static void SVKModuli(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E, MMTangent D)
{
  (void)E;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt l = 0; l < dim; ++l) D[i][j][k][l] = (i == j && k == l ? lam : 0) + ((i == k && j == l) ? mu : 0) + ((i == l && j == k) ? mu : 0);
}

/* C = I + 2E: its inverse, and ln J = 1/2 ln det C with det C - 1 formed from 2E */
static PetscReal LogJInverse(PetscInt dim, const Mat3 E, Mat3 Ci)
{
  Mat3 C, E2;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      E2[i][j] = 2 * E[i][j];
      C[i][j]  = (i == j ? 1 : 0) + E2[i][j];
    }
  (void)MMDetInverse(dim, (const PetscReal(*)[MM_MAX_DIM])C, Ci);
  return 0.5 * log1p(DetIPlusMinusOne(dim, E2));
}

/* W = mu (tr E - ln J) + lambda/2 (ln J)^2. With x = det C - 1 = tr 2E + i2(2E) + i3(2E) and
 * ln J = log1p(x)/2: tr E - ln J = -(i2 + i3)/2 + (x - log1p x)/2, no O(eps) terms cancelling */
static PetscReal NHEnergyE(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E)
{
  Mat3            E2;
  PetscReal       x, lnJ, trE_minus_lnJ;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) E2[i][j] = 2 * E[i][j];
  x   = DetIPlusMinusOne(dim, E2); /* tr 2E + the higher invariants */
  lnJ = 0.5 * log1p(x);
  if (dim == 2) trE_minus_lnJ = -0.5 * (E2[0][0] * E2[1][1] - E2[0][1] * E2[1][0]) + 0.5 * XMinusLog1p(x);
  else {
    const PetscReal i2 = E2[0][0] * E2[1][1] - E2[0][1] * E2[1][0] + E2[1][1] * E2[2][2] - E2[1][2] * E2[2][1] + E2[0][0] * E2[2][2] - E2[0][2] * E2[2][0];
    const PetscReal i3 = E2[0][0] * (E2[1][1] * E2[2][2] - E2[1][2] * E2[2][1]) - E2[0][1] * (E2[1][0] * E2[2][2] - E2[1][2] * E2[2][0]) + E2[0][2] * (E2[1][0] * E2[2][1] - E2[1][1] * E2[2][0]);
    trE_minus_lnJ = -0.5 * (i2 + i3) + 0.5 * XMinusLog1p(x);
  }
  return mu * trE_minus_lnJ + 0.5 * lam * lnJ * lnJ;
}

/* S = mu (I - C^{-1}) + lambda ln J C^{-1}, with I - C^{-1} = C^{-1} 2E */
static void NHStressE(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E, Mat3 S)
{
  Mat3            Ci;
  const PetscReal lnJ = LogJInverse(dim, E, Ci);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      PetscReal ce = 0;
      for (PetscInt k = 0; k < dim; ++k) ce += Ci[i][k] * 2 * E[k][j];
      S[i][j] = mu * ce + lam * lnJ * Ci[i][j];
    }
}

/* The moduli of the iteration matrix, kept positive semi-definite: mu - lambda ln J is clipped at 0 (a
 * cell stretched past J = exp(mu/lambda)), so that K_t + 4/dt^2 M* stays SPD; the step's force, and
 * so its solution, do not depend on it */
static void NHModuli(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E, MMTangent D)
{
  Mat3            Ci;
  const PetscReal lnJ = LogJInverse(dim, E, Ci), m = PetscMax(mu - lam * lnJ, 0);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt l = 0; l < dim; ++l) D[i][j][k][l] = lam * Ci[i][j] * Ci[k][l] + m * (Ci[i][k] * Ci[j][l] + Ci[i][l] * Ci[j][k]);
}

/* det(A + B) - det(A) without the cancellation of the two determinants: the expansion in B's columns */
static PetscReal DetIncrement(PetscInt dim, const Mat3 A, const Mat3 B)
{
  if (dim == 2) return A[0][0] * B[1][1] + B[0][0] * A[1][1] - A[0][1] * B[1][0] - B[0][1] * A[1][0] + B[0][0] * B[1][1] - B[0][1] * B[1][0];
  {
    PetscReal d = 0;
    for (PetscInt mask = 1; mask < 8; ++mask) {
      Mat3 M;
      for (PetscInt j = 0; j < 3; ++j)
        for (PetscInt i = 0; i < 3; ++i) M[i][j] = (mask >> j) & 1 ? B[i][j] : A[i][j];
      d += M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    }
    return d;
  }
}

/* W(E1) - W(E0) - S(E_m) : dE for neo-Hookean, each term a difference of O(|dE|) quantities formed
 * without cancelling the energies themselves */
static PetscReal NHRemainder(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 E0, const Mat3 E1, const Mat3 Em, const Mat3 dE)
{
  Mat3            Ci, C0, dC;
  const PetscReal lm = LogJInverse(dim, Em, Ci);
  Mat3            Cdummy;
  const PetscReal l0 = LogJInverse(dim, E0, Cdummy), l1 = LogJInverse(dim, E1, Cdummy);
  PetscReal       X, dl;

  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      C0[i][j] = (i == j ? 1 : 0) + 2 * E0[i][j];
      dC[i][j] = 2 * dE[i][j];
    }
  dl = 0.5 * log1p(DetIncrement(dim, C0, dC) / MMDetInverse(dim, (const PetscReal(*)[MM_MAX_DIM])C0, NULL));
  X  = Contract(dim, Ci, dE);
  /* W1 - W0 = mu (tr dE - dl) + lambda/2 dl (l1 + l0); S_m : dE = mu (tr dE - X) + lambda lm X */
  return mu * (X - dl) + lam * (0.5 * dl * (l1 + l0) - lm * X);
}

/* A hyperelastic law on E */
typedef struct {
  PetscReal (*remainder)(PetscInt, PetscReal, PetscReal, const Mat3, const Mat3, const Mat3, const Mat3); /* NULL: W quadratic in E, the mean strain's stress is exact */
  PetscReal (*energy)(PetscInt, PetscReal, PetscReal, const Mat3);
  void (*stress)(PetscInt, PetscReal, PetscReal, const Mat3, Mat3);
  void (*moduli)(PetscInt, PetscReal, PetscReal, const Mat3, MMTangent);
} HyperLaw;

static const HyperLaw SVKLaw = {NULL, SVKEnergyE, SVKStressE, SVKModuli};
static const HyperLaw NHLaw  = {NHRemainder, NHEnergyE, NHStressE, NHModuli};

/* Below |E1 - E0| = 1e-5 the discrete gradient's correction, O(|E1 - E0|) in stress, is dropped: its
 * quotient carries a round-off of about 1e-16 / |E1 - E0| of the stress, which would stall the step's
 * iteration, and the work it leaves out is O(mu |E1 - E0|^3), below 1e-16 mu per unit volume. */
#define MM_GONZALEZ_DROP 1e-10

/* The algorithmic second Piola-Kirchhoff stress of a step: S(E_m) with E_m = (E0 + E1)/2, plus for a
 * non-quadratic W Gonzalez's correction so that S_alg : (E1 - E0) = W(E1) - W(E0) exactly; then
 * P = F_m S_alg, F_m = I + (G0 + G1)/2, for which P : (F1 - F0) = S_alg : (E1 - E0). */
static void HyperStressAlg(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, PetscReal visc, const Mat3 G0, const Mat3 G1, Mat3 P)
{
  Mat3 E0, E1, Em, S, dE;

  GreenStrain(dim, G0, E0);
  GreenStrain(dim, G1, E1);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      Em[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
      dE[i][j] = E1[i][j] - E0[i][j];
    }
  law->stress(dim, lam, mu, Em, S);
  if (law->remainder) {
    const PetscReal n2 = Contract(dim, dE, dE);
    if (n2 > MM_GONZALEZ_DROP) {
      const PetscReal k = law->remainder(dim, lam, mu, E0, E1, Em, dE) / n2;
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt j = 0; j < dim; ++j) S[i][j] += k * dE[i][j];
    }
  }
  if (visc != 0) { /* the viscous stress visc D : dE, with D the moduli at E = 0 (docs/method.md section 13) */
    Mat3 Sv;
    SVKStressE(dim, lam, mu, dE, Sv);
    for (PetscInt i = 0; i < dim; ++i)
      for (PetscInt j = 0; j < dim; ++j) S[i][j] += visc * Sv[i][j];
  }
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J) {
      P[i][J] = S[i][J];
      for (PetscInt K = 0; K < dim; ++K) P[i][J] += 0.5 * (G0[i][K] + G1[i][K]) * S[K][J];
    }
}

/* Whether the symmetric S is positive semi-definite: all its principal minors non-negative */
static PetscBool SemiDefinite(PetscInt dim, const Mat3 S)
{
  for (PetscInt i = 0; i < dim; ++i)
    if (S[i][i] < 0) return PETSC_FALSE;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = i + 1; j < dim; ++j)
      if (S[i][i] * S[j][j] - S[i][j] * S[j][i] < 0) return PETSC_FALSE;
  return (PetscBool)(dim == 2 || MMDetInverse(3, S, NULL) >= 0);
}

/* The iteration matrix's A_iJkL = delta_ik S_JL + F_iI D_IJKL F_kK (dP_iJ / dF_kL), the symmetric part of
 * the step's tangent. *definite: whether it is positive semi-definite by construction (S is, and the moduli
 * D are); under compression S, and with it the cell's matrix, is indefinite, and K_t + 4/dt^2 M* could lose
 * the definiteness the factorizations of K~ need: elasticity.c then clamps the cell matrix's negative
 * eigenvalues (docs/method.md section 13, "The iteration matrix"), unless it wants dP/dF itself (the
 * static start's Newton, el->consistent). The iteration converges to the same step either way. */
static void HyperTangent(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, MMTangent A, PetscBool *definite)
{
  Mat3      E, S, F;
  MMTangent D, FD;

  GreenStrain(dim, G, E);
  law->stress(dim, lam, mu, E, S);
  law->moduli(dim, lam, mu, E, D);
  *definite = SemiDefinite(dim, S);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) F[i][j] = (i == j ? 1 : 0) + G[i][j];
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt K = 0; K < dim; ++K)
        for (PetscInt L = 0; L < dim; ++L) {
          FD[i][J][K][L] = 0;
          for (PetscInt M = 0; M < dim; ++M) FD[i][J][K][L] += F[i][M] * D[M][J][K][L];
        }
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt L = 0; L < dim; ++L) {
          PetscReal a = i == k ? S[J][L] : 0;
          for (PetscInt K = 0; K < dim; ++K) a += FD[i][J][K][L] * F[k][K];
          A[i][J][k][L] = a;
        }
}

/* sigma = F S F^T / J */
static void HyperCauchy(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, Mat3 sigma)
{
  Mat3      E, S, F, FS;
  PetscReal J;

  GreenStrain(dim, G, E);
  law->stress(dim, lam, mu, E, S);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) F[i][j] = (i == j ? 1 : 0) + G[i][j];
  J = MMDetInverse(dim, (const PetscReal(*)[MM_MAX_DIM])F, NULL);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      FS[i][j] = 0;
      for (PetscInt K = 0; K < dim; ++K) FS[i][j] += F[i][K] * S[K][j];
    }
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      sigma[i][j] = 0;
      for (PetscInt K = 0; K < dim; ++K) sigma[i][j] += FS[i][K] * F[j][K];
      sigma[i][j] /= J;
    }
}

/* dE : D : dE, dE = E(G1) - E(G0): twice the St. Venant-Kirchhoff energy of dE */
static PetscReal HyperDissipation(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G0, const Mat3 G1)
{
  Mat3 E0, E1;
  GreenStrain(dim, G0, E0);
  GreenStrain(dim, G1, E1);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) E1[i][j] -= E0[i][j];
  return 2 * SVKEnergyE(dim, lam, mu, E1);
}

static PetscReal HyperEnergy(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G)
{
  Mat3 E;
  GreenStrain(dim, G, E);
  return law->energy(dim, lam, mu, E);
}

/* ---------------------------------------------------------------- the linear law */

static void LinearSigma(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, Mat3 s)
{
  const PetscReal tr = Trace(dim, G);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) s[i][j] = mu * (G[i][j] + G[j][i]) + (i == j ? lam * tr : 0);
}

static PetscReal LinearEnergy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G)
{
  Mat3 s;
  LinearSigma(dim, lam, mu, G, s);
  return 0.5 * Contract(dim, s, G); /* s symmetric: s : G = s : eps */
}

/* sigma(eps_m) + visc sigma(d eps): the trapezoidal stress and beta K du/dt, the linear Rayleigh damping */
static void LinearStressAlg(PetscInt dim, PetscReal lam, PetscReal mu, PetscReal visc, const Mat3 G0, const Mat3 G1, Mat3 P)
{
  Mat3 Gm;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) Gm[i][j] = 0.5 * (G0[i][j] + G1[i][j]) + visc * (G1[i][j] - G0[i][j]);
  LinearSigma(dim, lam, mu, Gm, P);
}

/* d eps : D : d eps */
static PetscReal LinearDissipation(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G0, const Mat3 G1)
{
  Mat3 dG;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) dG[i][j] = G1[i][j] - G0[i][j];
  return 2 * LinearEnergy(dim, lam, mu, dG);
}

static void LinearTangent(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, MMTangent A, PetscBool *definite)
{
  SVKModuli(dim, lam, mu, G, A); /* the same isotropic moduli, on grad u */
  *definite = PETSC_TRUE;
}

/* ---------------------------------------------------------------- the tables */

#define MM_HYPER_OPS(Name, law) \
  static PetscReal Name##Energy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G) \
  { \
    return HyperEnergy(&law, dim, lam, mu, G); \
  } \
  static void Name##StressAlg(PetscInt dim, PetscReal lam, PetscReal mu, PetscReal visc, const Mat3 G0, const Mat3 G1, Mat3 P) \
  { \
    HyperStressAlg(&law, dim, lam, mu, visc, G0, G1, P); \
  } \
  static void Name##Tangent(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, MMTangent A, PetscBool *definite) \
  { \
    HyperTangent(&law, dim, lam, mu, G, A, definite); \
  } \
  static void Name##Cauchy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 G, Mat3 s) \
  { \
    HyperCauchy(&law, dim, lam, mu, G, s); \
  }
MM_HYPER_OPS(SVK, SVKLaw)
MM_HYPER_OPS(NH, NHLaw)

static const MMElasticityOps LinearOps     = {.energy = LinearEnergy, .stress_alg = LinearStressAlg, .dissipation = LinearDissipation, .tangent = LinearTangent, .cauchy = LinearSigma, .finite = PETSC_FALSE};
static const MMElasticityOps SVKOps        = {.energy = SVKEnergy, .stress_alg = SVKStressAlg, .dissipation = HyperDissipation, .tangent = SVKTangent, .cauchy = SVKCauchy, .finite = PETSC_TRUE};
static const MMElasticityOps NeoHookeanOps = {.energy = NHEnergy, .stress_alg = NHStressAlg, .dissipation = HyperDissipation, .tangent = NHTangent, .cauchy = NHCauchy, .finite = PETSC_TRUE};

const char *const MMElasticityTypes[] = {"linear", "svk", "neohookean", "MMElasticityType", "MM_ELASTICITY_", NULL};

/* The law's table, indexed by -elasticity's value */
const MMElasticityOps *MMElasticityGetOps(MMElasticityType type)
{
  static const MMElasticityOps *const table[] = {[MM_ELASTICITY_LINEAR] = &LinearOps, [MM_ELASTICITY_SVK] = &SVKOps, [MM_ELASTICITY_NEOHOOKEAN] = &NeoHookeanOps};
  return table[type];
}
