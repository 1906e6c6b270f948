/* Anderson acceleration of the finite-strain step's fixed point (docs/method.md section 13, "The
 * step's iteration"): the iteration maps the force correction c to H(c), the correction at the solve
 * it gives; with a fixed iteration matrix it converges only linearly. Anderson's mixing takes the
 * next c as the combination of the last m values of H whose residuals f = H - c combine to the least
 * norm: on a fixed contact set the map is smooth and this is a Krylov method on the step's residual,
 * at the cost of m dot products and no extra solve or force evaluation. */
#include "newmarkimpl.h"

PetscErrorCode MMAndersonSetUp(MMAnderson *aa, PetscInt m, Vec tmpl)
{
  PetscFunctionBeginUser;
  aa->m = m;
  aa->n = 0;
  if (m <= 0) PetscFunctionReturn(0);
  PetscCall(VecDuplicateVecs(tmpl, m, &aa->dF));
  PetscCall(VecDuplicateVecs(tmpl, m, &aa->dH));
  PetscCall(VecDuplicate(tmpl, &aa->f_prev));
  PetscCall(VecDuplicate(tmpl, &aa->H_prev));
  PetscCall(VecDuplicate(tmpl, &aa->f));
  PetscFunctionReturn(0);
}

PetscErrorCode MMAndersonReset(MMAnderson *aa)
{
  PetscFunctionBeginUser;
  aa->n     = 0;
  aa->first = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Solves the m x m normal equations A g = r by Gaussian elimination with partial pivoting, A
 * regularized by 1e-13 of its diagonal's largest entry (nearly dependent differences) */
static void SmallSolve(PetscInt n, PetscScalar A[], PetscScalar r[], PetscScalar g[])
{
  PetscReal dmax = 0;
  for (PetscInt i = 0; i < n; ++i) dmax = PetscMax(dmax, PetscAbsScalar(A[i * n + i]));
  for (PetscInt i = 0; i < n; ++i) A[i * n + i] += 1e-13 * dmax;
  for (PetscInt k = 0; k < n; ++k) {
    PetscInt p = k;
    for (PetscInt i = k + 1; i < n; ++i)
      if (PetscAbsScalar(A[i * n + k]) > PetscAbsScalar(A[p * n + k])) p = i;
    for (PetscInt j = 0; j < n && p != k; ++j) {
      PetscScalar t = A[k * n + j];
      A[k * n + j]  = A[p * n + j];
      A[p * n + j]  = t;
    }
    if (p != k) {
      PetscScalar t = r[k];
      r[k]          = r[p];
      r[p]          = t;
    }
    for (PetscInt i = k + 1; i < n; ++i) {
      const PetscScalar l = A[k * n + k] != 0.0 ? A[i * n + k] / A[k * n + k] : 0.0;
      for (PetscInt j = k; j < n; ++j) A[i * n + j] -= l * A[k * n + j];
      r[i] -= l * r[k];
    }
  }
  for (PetscInt i = n - 1; i >= 0; --i) {
    PetscScalar s = r[i];
    for (PetscInt j = i + 1; j < n; ++j) s -= A[i * n + j] * g[j];
    g[i] = A[i * n + i] != 0.0 ? s / A[i * n + i] : 0.0;
  }
}

/* c holds c_k on entry and c_{k+1} on return; H = H(c_k). Without history (or m = 0), c_{k+1} = H. */
PetscErrorCode MMAndersonUpdate(MMAnderson *aa, Vec c, Vec H)
{
  PetscScalar A[MM_ANDERSON_MAX * MM_ANDERSON_MAX], r[MM_ANDERSON_MAX], g[MM_ANDERSON_MAX];

  PetscFunctionBeginUser;
  if (aa->m <= 0) {
    PetscCall(VecCopy(H, c));
    PetscFunctionReturn(0);
  }
  PetscCall(VecWAXPY(aa->f, -1.0, c, H));
  if (!aa->first) {
    PetscInt slot = aa->n;
    if (aa->n == aa->m) { /* full: the oldest differences make room, their vectors reused */
      Vec f0 = aa->dF[0], h0 = aa->dH[0];
      for (PetscInt i = 0; i < aa->m - 1; ++i) {
        aa->dF[i] = aa->dF[i + 1];
        aa->dH[i] = aa->dH[i + 1];
      }
      aa->dF[aa->m - 1] = f0;
      aa->dH[aa->m - 1] = h0;
      slot              = aa->m - 1;
    } else aa->n++;
    PetscCall(VecWAXPY(aa->dF[slot], -1.0, aa->f_prev, aa->f));
    PetscCall(VecWAXPY(aa->dH[slot], -1.0, aa->H_prev, H));
  }
  aa->first = PETSC_FALSE;
  PetscCall(VecCopy(aa->f, aa->f_prev));
  PetscCall(VecCopy(H, aa->H_prev));
  PetscCall(VecCopy(H, c));
  if (!aa->n) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < aa->n; ++i) PetscCall(VecMDot(aa->dF[i], aa->n, aa->dF, &A[i * aa->n]));
  PetscCall(VecMDot(aa->f, aa->n, aa->dF, r));
  SmallSolve(aa->n, A, r, g);
  for (PetscInt i = 0; i < aa->n; ++i) g[i] = -g[i];
  PetscCall(VecMAXPY(c, aa->n, g, aa->dH));
  PetscFunctionReturn(0);
}

PetscErrorCode MMAndersonDestroy(MMAnderson *aa)
{
  PetscFunctionBeginUser;
  if (aa->m <= 0) PetscFunctionReturn(0);
  PetscCall(VecDestroyVecs(aa->m, &aa->dF));
  PetscCall(VecDestroyVecs(aa->m, &aa->dH));
  PetscCall(VecDestroy(&aa->f_prev));
  PetscCall(VecDestroy(&aa->H_prev));
  PetscCall(VecDestroy(&aa->f));
  PetscFunctionReturn(0);
}
