/* The elasticity laws of -elasticity (docs/method.md section 13): each a table of pointwise
 * functions of the deformation gradient F, per unit reference volume, in plane strain in 2D.
 * - linear: the paper's small-strain model, sigma(eps) with eps = sym(F - Ii);
 * - svk: St. Venant-Kirchhoff, W = lambda/2 (tr E)^2 + mu E:E with E = (C - Ii)/2;
 * - neohookean: W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2 (tr C - 3 = tr C_2D - 2 in plane strain).
 * The algorithmic stress of a step from F0 to F1 makes its work on the step equal the energy change
 * exactly: the stress at the mean strain (linear and svk, whose energies are quadratic in the strain),
 * and Gonzalez's discrete gradient for neo-Hookean (docs/method.md section 13, "The step's stress"). */
#include "elasticityimpl.h"

typedef PetscReal Mat3[MM_MAX_DIM][MM_MAX_DIM];

static void RightCauchyGreen(PetscInt dim, const Mat3 F, Mat3 C)
{
  for (PetscInt Ii = 0; Ii < dim; ++Ii)
    for (PetscInt J = 0; J < dim; ++J) {
      C[Ii][J] = 0;
      for (PetscInt k = 0; k < dim; ++k) C[Ii][J] += F[k][Ii] * F[k][J];
    }
}

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

/* ---------------------------------------------------------------- the laws on C: W, S = 2 dW/dC, D = dS/dE */

static PetscReal SVKEnergyC(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C)
{
  Mat3 E;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) E[i][j] = 0.5 * (C[i][j] - (i == j ? 1 : 0));
  return 0.5 * lam * PetscSqr(Trace(dim, E)) + mu * Contract(dim, E, E);
}

static void SVKStressC(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C, Mat3 S)
{
  PetscReal trE = 0;
  for (PetscInt i = 0; i < dim; ++i) trE += 0.5 * (C[i][i] - 1);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) S[i][j] = mu * (C[i][j] - (i == j ? 1 : 0)) + (i == j ? lam * trE : 0);
}

static void SVKModuli(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C, PetscReal D[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM])
{
  for (PetscInt Ii = 0; Ii < dim; ++Ii)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt K = 0; K < dim; ++K)
        for (PetscInt L = 0; L < dim; ++L) D[Ii][J][K][L] = (Ii == J && K == L ? lam : 0) + ((Ii == K && J == L) ? mu : 0) + ((Ii == L && J == K) ? mu : 0);
}

/* ln J = 1/2 ln det C and C^{-1} */
static PetscReal LogJInverse(PetscInt dim, const Mat3 C, Mat3 Ci)
{
  const PetscReal det = MMDetInverse(dim, C, Ci);
  return 0.5 * PetscLogReal(det);
}

static PetscReal NHEnergyC(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C)
{
  Mat3            Ci;
  const PetscReal lnJ = LogJInverse(dim, C, Ci);
  return 0.5 * mu * (Trace(dim, C) - dim) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
}

static void NHStressC(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C, Mat3 S)
{
  Mat3            Ci;
  const PetscReal lnJ = LogJInverse(dim, C, Ci);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) S[i][j] = mu * ((i == j ? 1 : 0) - Ci[i][j]) + lam * lnJ * Ci[i][j];
}

static void NHModuli(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C, PetscReal D[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM])
{
  Mat3            Ci;
  const PetscReal lnJ = LogJInverse(dim, C, Ci), m = mu - lam * lnJ;
  for (PetscInt Ii = 0; Ii < dim; ++Ii)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt K = 0; K < dim; ++K)
        for (PetscInt L = 0; L < dim; ++L) D[Ii][J][K][L] = lam * Ci[Ii][J] * Ci[K][L] + m * (Ci[Ii][K] * Ci[J][L] + Ci[Ii][L] * Ci[J][K]);
}

/* det(A + B) - det(A), without the cancellation of the two determinants: the expansion in B */
static PetscReal DetIncrement(PetscInt dim, const Mat3 A, const Mat3 B)
{
  if (dim == 2) return A[0][0] * B[1][1] + B[0][0] * A[1][1] - A[0][1] * B[1][0] - B[0][1] * A[1][0] + B[0][0] * B[1][1] - B[0][1] * B[1][0];
  {
    PetscReal d = 0;
    /* det is multilinear in the columns: the sum over the 7 mixes of columns of A and B with at least one of B */
    for (PetscInt mask = 1; mask < 8; ++mask) {
      Mat3 M;
      for (PetscInt j = 0; j < 3; ++j)
        for (PetscInt i = 0; i < 3; ++i) M[i][j] = (mask >> j) & 1 ? B[i][j] : A[i][j];
      d += M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    }
    return d;
  }
}

/* W(C1) - W(C0) - S(C_m) : dE for neo-Hookean, each term a difference of O(|dE|) quantities formed
 * without cancelling the energies themselves, whose round-off would swamp the O(|dE|^3) result */
static PetscReal NHRemainder(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 C0, const Mat3 C1, const Mat3 Cm, const Mat3 dE)
{
  Mat3            Ci, C2dE;
  const PetscReal lm = LogJInverse(dim, Cm, Ci), l0 = 0.5 * PetscLogReal(MMDetInverse(dim, C0, NULL)), l1 = 0.5 * PetscLogReal(MMDetInverse(dim, C1, NULL));
  PetscReal       X, dl;

  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) C2dE[i][j] = 2 * dE[i][j];
  dl = 0.5 * log1p(DetIncrement(dim, C0, C2dE) / MMDetInverse(dim, C0, NULL));
  X  = Contract(dim, Ci, dE);
  return mu * (X - dl) + lam * (0.5 * dl * (l1 + l0) - lm * X);
}

/* A hyperelastic law on C */
typedef struct {
  PetscBool quadratic; /* W quadratic in E: the stress at the mean strain is already exact */
  PetscReal (*remainder)(PetscInt, PetscReal, PetscReal, const Mat3, const Mat3, const Mat3, const Mat3); /* W1 - W0 - S(C_m) : dE */
  PetscReal (*energy)(PetscInt, PetscReal, PetscReal, const Mat3);
  void (*stress)(PetscInt, PetscReal, PetscReal, const Mat3, Mat3);
  void (*moduli)(PetscInt, PetscReal, PetscReal, const Mat3, PetscReal[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM]);
} HyperLaw;

static const HyperLaw SVKLaw = {PETSC_TRUE, NULL, SVKEnergyC, SVKStressC, SVKModuli};
static const HyperLaw NHLaw  = {PETSC_FALSE, NHRemainder, NHEnergyC, NHStressC, NHModuli};

/* Below |E1 - E0| = 1e-5 the discrete gradient's correction, O(|E1 - E0|) in stress, is dropped: its
 * quotient carries a round-off of about 1e-16 / |E1 - E0| of the stress, which would stall the step's
 * iteration, and the work it leaves out is O(mu |E1 - E0|^3), below 1e-16 mu per unit volume. */
#define MM_GONZALEZ_DROP 1e-10

/* The algorithmic second Piola-Kirchhoff stress of a step: S(C_m) with C_m = (C0 + C1)/2, plus for a
 * non-quadratic W Gonzalez's correction so that S_alg : (E1 - E0) = W(C1) - W(C0) exactly. */
static void HyperStressAlg(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F0, const Mat3 F1, Mat3 P)
{
  Mat3 C0, C1, Cm, S, dE, Fm;

  RightCauchyGreen(dim, F0, C0);
  RightCauchyGreen(dim, F1, C1);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      Cm[i][j] = 0.5 * (C0[i][j] + C1[i][j]);
      dE[i][j] = 0.5 * (C1[i][j] - C0[i][j]);
      Fm[i][j] = 0.5 * (F0[i][j] + F1[i][j]);
    }
  law->stress(dim, lam, mu, Cm, S);
  if (!law->quadratic) {
    const PetscReal n2 = Contract(dim, dE, dE);
    if (n2 > MM_GONZALEZ_DROP) {
      const PetscReal k = law->remainder(dim, lam, mu, C0, C1, Cm, dE) / n2;
      for (PetscInt i = 0; i < dim; ++i)
        for (PetscInt j = 0; j < dim; ++j) S[i][j] += k * dE[i][j];
    }
  }
  /* P = F_m S_alg: with E1 - E0 = sym(F_m^T (F1 - F0)), P : (F1 - F0) = S_alg : (E1 - E0) */
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J) {
      P[i][J] = 0;
      for (PetscInt K = 0; K < dim; ++K) P[i][J] += Fm[i][K] * S[K][J];
    }
}

/* A_iJkL = dP_iJ / dF_kL = delta_ik S_JL + F_iI D_IJKL F_kK */
static void HyperTangent(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, MMTangent A)
{
  Mat3      C, S;
  PetscReal D[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM], FD[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM];

  RightCauchyGreen(dim, F, C);
  law->stress(dim, lam, mu, C, S);
  law->moduli(dim, lam, mu, C, D);
  /* FD_iJKL = F_iI D_IJKL, then A_iJkL = FD_iJKL F_kK */
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt K = 0; K < dim; ++K)
        for (PetscInt L = 0; L < dim; ++L) {
          FD[i][J][K][L] = 0;
          for (PetscInt Ii = 0; Ii < dim; ++Ii) FD[i][J][K][L] += F[i][Ii] * D[Ii][J][K][L];
        }
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt L = 0; L < dim; ++L) {
          PetscReal a = (i == k) ? S[J][L] : 0;
          for (PetscInt K = 0; K < dim; ++K) a += FD[i][J][K][L] * F[k][K];
          A[i][J][k][L] = a;
        }
}

/* sigma = F S F^T / J */
static void HyperCauchy(const HyperLaw *law, PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, Mat3 sigma)
{
  Mat3            C, S, FS;
  const PetscReal J = MMDetInverse(dim, F, NULL);

  RightCauchyGreen(dim, F, C);
  law->stress(dim, lam, mu, C, S);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J2 = 0; J2 < dim; ++J2) {
      FS[i][J2] = 0;
      for (PetscInt K = 0; K < dim; ++K) FS[i][J2] += F[i][K] * S[K][J2];
    }
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) {
      sigma[i][j] = 0;
      for (PetscInt K = 0; K < dim; ++K) sigma[i][j] += FS[i][K] * F[j][K];
      sigma[i][j] /= J;
    }
}

/* ---------------------------------------------------------------- the linear law on F */

static void LinearStrain(PetscInt dim, const Mat3 F, Mat3 e)
{
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) e[i][j] = 0.5 * (F[i][j] + F[j][i]) - (i == j ? 1 : 0);
}

static void LinearSigma(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 e, Mat3 s)
{
  const PetscReal tr = Trace(dim, e);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) s[i][j] = 2 * mu * e[i][j] + (i == j ? lam * tr : 0);
}

static PetscReal LinearEnergy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F)
{
  Mat3 e;
  LinearStrain(dim, F, e);
  return 0.5 * lam * PetscSqr(Trace(dim, e)) + mu * Contract(dim, e, e);
}

static void LinearStressAlg(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F0, const Mat3 F1, Mat3 P)
{
  Mat3 e0, e1;
  LinearStrain(dim, F0, e0);
  LinearStrain(dim, F1, e1);
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt j = 0; j < dim; ++j) e0[i][j] = 0.5 * (e0[i][j] + e1[i][j]);
  LinearSigma(dim, lam, mu, e0, P);
}

static void LinearTangent(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, MMTangent A)
{
  (void)F;
  for (PetscInt i = 0; i < dim; ++i)
    for (PetscInt J = 0; J < dim; ++J)
      for (PetscInt k = 0; k < dim; ++k)
        for (PetscInt L = 0; L < dim; ++L) A[i][J][k][L] = (i == J && k == L ? lam : 0) + ((i == k && J == L) ? mu : 0) + ((i == L && J == k) ? mu : 0);
}

static void LinearCauchy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, Mat3 sigma)
{
  Mat3 e;
  LinearStrain(dim, F, e);
  LinearSigma(dim, lam, mu, e, sigma);
}

/* ---------------------------------------------------------------- the tables */

static PetscReal SVKEnergy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F)
{
  Mat3 C;
  RightCauchyGreen(dim, F, C);
  return SVKEnergyC(dim, lam, mu, C);
}
static void SVKStressAlg(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F0, const Mat3 F1, Mat3 P)
{
  HyperStressAlg(&SVKLaw, dim, lam, mu, F0, F1, P);
}
static void SVKTangent(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, MMTangent A)
{
  HyperTangent(&SVKLaw, dim, lam, mu, F, A);
}
static void SVKCauchy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, Mat3 s)
{
  HyperCauchy(&SVKLaw, dim, lam, mu, F, s);
}
static PetscReal NHEnergy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F)
{
  Mat3 C;
  RightCauchyGreen(dim, F, C);
  return NHEnergyC(dim, lam, mu, C);
}
static void NHStressAlg(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F0, const Mat3 F1, Mat3 P)
{
  HyperStressAlg(&NHLaw, dim, lam, mu, F0, F1, P);
}
static void NHTangent(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, MMTangent A)
{
  HyperTangent(&NHLaw, dim, lam, mu, F, A);
}
static void NHCauchy(PetscInt dim, PetscReal lam, PetscReal mu, const Mat3 F, Mat3 s)
{
  HyperCauchy(&NHLaw, dim, lam, mu, F, s);
}

static const MMElasticityOps LinearOps     = {.energy = LinearEnergy, .stress_alg = LinearStressAlg, .tangent = LinearTangent, .cauchy = LinearCauchy, .finite = PETSC_FALSE};
static const MMElasticityOps SVKOps        = {.energy = SVKEnergy, .stress_alg = SVKStressAlg, .tangent = SVKTangent, .cauchy = SVKCauchy, .finite = PETSC_TRUE};
static const MMElasticityOps NeoHookeanOps = {.energy = NHEnergy, .stress_alg = NHStressAlg, .tangent = NHTangent, .cauchy = NHCauchy, .finite = PETSC_TRUE};

const char *const MMElasticityTypes[] = {"linear", "svk", "neohookean", "MMElasticityType", "MM_ELASTICITY_", NULL};

/* The law's table, indexed by -elasticity's value */
const MMElasticityOps *MMElasticityGetOps(MMElasticityType type)
{
  static const MMElasticityOps *const table[] = {[MM_ELASTICITY_LINEAR] = &LinearOps, [MM_ELASTICITY_SVK] = &SVKOps, [MM_ELASTICITY_NEOHOOKEAN] = &NeoHookeanOps};
  return table[type];
}
