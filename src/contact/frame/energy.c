/* The elastic energy of a w-frame state from the w-frame K and lift (docs/method.md section 4), and
 * its start-up audit against fem's quadrature of the Cartesian field (MMFEElasticEnergyIntegral). */
#include "../contactimpl.h"

/*@
  MMContactElasticEnergy - Computes the elastic energy of a w-frame state, the Dirichlet data's own
  included

  Collective

  Input Parameters:
+ ct - the contact object
- w  - the w-frame state

  Output Parameter:
. energy - 1/2 w.K w + w.lift + 1/2 u_D.A_DD u_D

  Note:
  Elastic energy of the whole field, Dirichlet data included: with u = (w, u_D),
  1/2 u.A u = 1/2 w.K w + w.lift + 1/2 u_D.A_DD u_D. One MatMult per call, where the FE
  integral of 1/2 sigma:eps would cost an assembly.

  Level: intermediate

.seealso: `MMContactCheckElasticEnergy()`, `MMFEElasticEnergyIntegral()`
@*/
PetscErrorCode MMContactElasticEnergy(MMContact ct, Vec w, PetscReal *energy)
{
  PetscScalar wKw, wl;
  PetscReal   energy_dirichlet;
  Vec         work;

  PetscFunctionBeginUser;
  PetscCall(MMFEGetDirichletEnergy(ct->op, &energy_dirichlet));
  PetscCall(DMGetGlobalVector(ct->dm, &work));
  PetscCall(MatMult(ct->K, w, work));
  PetscCall(VecDot(w, work, &wKw));
  PetscCall(DMRestoreGlobalVector(ct->dm, &work));
  PetscCall(VecDot(w, ct->lift, &wl));
  *energy = 0.5 * PetscRealPart(wKw) + PetscRealPart(wl) + energy_dirichlet;
  PetscFunctionReturn(0);
}

/* The round-off scale of the elastic energy's matrix form 1/2 w.K w + w.lift + E_D: the same sums
 * of absolute values, 1/2 |w|.|K| |w| + |w|.|lift| + |E_D|. On a slender part in bending, or a body
 * moved rigidly, the terms of w.K w cancel to a small fraction of their sum (2e-9 on the clamped
 * cantilever of t/L = 0.02 under its weight), so the energy's error is eps times this sum, not eps
 * times the energy. Once, at start-up and on a restart: |K| is a copy of K. */
static PetscErrorCode ElasticEnergyRoundoffScale(PetscReal energy_dirichlet, Mat K, Vec lift, Vec w, PetscReal *scale)
{
  Mat         A, blocks[2];
  Vec         aw, work;
  PetscScalar wAw, wl;
  PetscMPIInt size;
  PetscInt    nb = 1;

  PetscFunctionBeginUser;
  PetscCall(MatConvert(K, MATAIJ, MAT_INITIAL_MATRIX, &A));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)A), &size));
  if (size > 1) {
    PetscCall(MatMPIAIJGetSeqAIJ(A, &blocks[0], &blocks[1], NULL));
    nb = 2;
  } else blocks[0] = A;
  for (PetscInt k = 0; k < nb; ++k) {
    PetscScalar *a;
    MatInfo      info;

    PetscCall(MatSeqAIJGetArray(blocks[k], &a));
    PetscCall(MatGetInfo(blocks[k], MAT_LOCAL, &info));
    for (PetscInt i = 0; i < (PetscInt)info.nz_used; ++i) a[i] = PetscAbsScalar(a[i]);
    PetscCall(MatSeqAIJRestoreArray(blocks[k], &a));
  }
  PetscCall(VecDuplicate(w, &aw));
  PetscCall(VecCopy(w, aw));
  PetscCall(VecAbs(aw));
  PetscCall(VecDuplicate(w, &work));
  PetscCall(MatMult(A, aw, work));
  PetscCall(VecDot(aw, work, &wAw));
  PetscCall(VecCopy(lift, work));
  PetscCall(VecAbs(work));
  PetscCall(VecDot(aw, work, &wl));
  *scale = 0.5 * PetscRealPart(wAw) + PetscRealPart(wl) + PetscAbsReal(energy_dirichlet);
  PetscCall(VecDestroy(&work));
  PetscCall(VecDestroy(&aw));
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

/* The matrix form and the quadrature each sum their terms in their own order: they differ by the
 * rounding of sums of N terms, which grows as sqrt(N) eps of the terms' magnitudes (N eps at worst).
 * Measured on every case of options/ at its start (and -initial_state static) and on the slender
 * cantilevers: 0.002 to 2.7 eps of the absolute sum, N = 10^3 to 10^4 dofs; 4 sqrt(N) eps is 40
 * times the largest. A wrong assembly (a wrong entry, a missed cell, a material mixed up) differs
 * by a fraction of the energy (tests/test_limits_and_advice.py). */
#define MM_ENERGY_ROUNDOFF 4

/*@
  MMContactCheckElasticEnergy - Audits at start-up the matrix form of the elastic energy against
  fem's quadrature, and stops the run when they differ beyond round-off

  Collective

  Input Parameters:
+ ct  - the contact object
. mat - the bodies' material
- w   - the w-frame state

  Note:
  Start-up audit: the matrix form of the elastic energy against its quadrature on the state w. The
  quadrature inserts the Dirichlet data of t = 0: the caller skips it when the data have moved since.

  Level: developer

.seealso: `MMContactElasticEnergy()`, `MMFEElasticEnergyIntegral()`
@*/
PetscErrorCode MMContactCheckElasticEnergy(MMContact ct, const MMMaterial *mat, Vec w)
{
  MMOperators        op = ct->op;
  PetscReal          e, integral[1], scale, tol, energy_dirichlet;
  PetscInt           n;
  Vec                ucart;

  PetscFunctionBeginUser;
  PetscCall(MMContactElasticEnergy(ct, w, &e));
  PetscCall(DMGetGlobalVector(ct->dm, &ucart));
  PetscCall(MMFEToCartesian(op, w, ucart));
  PetscCall(MMFEElasticEnergyIntegral(op, mat, ucart, &integral[0]));
  PetscCall(DMRestoreGlobalVector(ct->dm, &ucart));
  PetscCall(MMFEGetDirichletEnergy(op, &energy_dirichlet));
  PetscCall(ElasticEnergyRoundoffScale(energy_dirichlet, ct->K, ct->lift, w, &scale));
  PetscCall(VecGetSize(w, &n));
  tol = MM_ENERGY_ROUNDOFF * PetscSqrtReal((PetscReal)n) * PETSC_MACHINE_EPSILON * scale;
  PetscCall(PetscInfo(NULL, "elastic energy: matrix form %.16e, integral %.16e: they differ by %g eps of the terms' absolute sum %g\n", (double)e, (double)integral[0], (double)(PetscAbsReal(e - integral[0]) / (PETSC_MACHINE_EPSILON * scale)), (double)scale));
  PetscCheck(PetscAbsReal(e - integral[0]) <= tol, PetscObjectComm((PetscObject)ct->dm), PETSC_ERR_PLIB, "Elastic energy audit failed: matrix form %.16e, %s %.16e, differ by %.3e, above %d sqrt(N) eps of the terms' absolute sum %.3e (N = %" PetscInt_FMT ")", (double)e, mat->uniform ? "quadrature" : "cell by cell", (double)integral[0], (double)PetscAbsReal(e - integral[0]), MM_ENERGY_ROUNDOFF, (double)scale, n);
  PetscFunctionReturn(0);
}
