/* 3D Coulomb friction: the stick/slip states and slip directions that make the Tresca box the
 * isotropic disk, applied per node in its (n, d, d_perp) basis. */
#include "contact_impl.h"

/* 3D friction, the isotropic Coulomb disk |rho_t| <= s: each contact node sticks (rho_t free, so
 * the VI enforces zero slip) or slips (rho_t = s d fixed, d its slip direction); a node without
 * normal force carries no tangential force. The friction loop updates s, d and the states until
 * they stop changing (MMContactUpdateSlip), so the disk is exact, not a square. */
PetscErrorCode MMSlipSetDiskBounds(MMContact *ct, Vec s)
{
  const PetscScalar *sa;
  PetscScalar       *lo, *hi;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(s, &sa));
  PetscCall(VecGetArray(ct->rho_lo, &lo));
  PetscCall(VecGetArray(ct->rho_hi, &hi));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal sk = PetscRealPart(sa[k]);
    /* unknowns in the node's (d, d_perp) basis: a slipping node is a 1D Tresca box along d */
    if (sk <= 0) lo[3 * k + 1] = hi[3 * k + 1] = lo[3 * k + 2] = hi[3 * k + 2] = 0;
    else if (ct->slipping[k]) {
      lo[3 * k + 1] = -sk;
      hi[3 * k + 1] = sk;
      lo[3 * k + 2] = hi[3 * k + 2] = 0;
    } else {
      lo[3 * k + 1] = lo[3 * k + 2] = PETSC_NINFINITY;
      hi[3 * k + 1] = hi[3 * k + 2] = PETSC_INFINITY;
    }
  }
  PetscCall(VecRestoreArray(ct->rho_hi, &hi));
  PetscCall(VecRestoreArray(ct->rho_lo, &lo));
  PetscCall(VecRestoreArrayRead(s, &sa));
  PetscFunctionReturn(0);
}

/* P: the condensed dofs of each node from its (n, d, d_perp) basis to the frame's (n, t1, t2). */
PetscErrorCode MMSlipAssembleRotation(MMContact *ct)
{
  PetscInt cstart;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(ct->W, &cstart, NULL));
  if (!ct->P) PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)ct->W), 3 * ct->n_local, 3 * ct->n_local, PETSC_DETERMINE, PETSC_DETERMINE, 2, NULL, 0, NULL, &ct->P));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscInt  r   = cstart + 3 * k;
    const PetscReal *d  = &ct->slip_dir[2 * k];
    const PetscReal dd  = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]);
    const PetscReal c   = dd > 0 ? d[0] / dd : 1, sn = dd > 0 ? d[1] / dd : 0;
    PetscCall(MatSetValue(ct->P, r, r, 1.0, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 1, r + 1, c, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 1, r + 2, -sn, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 2, r + 1, sn, INSERT_VALUES));
    PetscCall(MatSetValue(ct->P, r + 2, r + 2, c, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(ct->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatPtAP(ct->W, ct->P, ct->Wr ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, 1.0, &ct->Wr));
  PetscFunctionReturn(0);
}

/* After a solve with thresholds s, the return mapping of each node: the trial force
 * rho_t + (dt/2) sigma_t / W_tt (its reaction plus its slip over its tangential compliance)
 * slips along itself when outside the disk, and sticks inside it. Returns the number of
 * stick/slip switches and the largest change of a slip direction. */
PetscErrorCode MMContactUpdateSlip(MMCtx *ctx, Vec s, Vec sigma, PetscInt *switches, PetscReal *dchange)
{
  MMContact         *ct = &ctx->contact;
  const PetscScalar *sa, *ra, *va, *wd;
  const PetscInt    *in;
  PetscInt           rstart, nsw = 0;
  PetscReal          dmax = 0;

  PetscFunctionBeginUser;
  *switches = 0;
  *dchange  = 0;
  if (ct->ncomp != 3) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(sigma, &rstart, NULL));
  PetscCall(ISGetIndices(ct->is_normal, &in));
  PetscCall(VecGetArrayRead(s, &sa));
  PetscCall(VecGetArrayRead(ct->rho, &ra));
  PetscCall(VecGetArrayRead(sigma, &va));
  PetscCall(VecGetArrayRead(ct->Wdiag, &wd));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal sk = PetscRealPart(sa[k]);
    const PetscReal kt = 0.5 * ct->Kt_dt * 2.0 / (PetscRealPart(wd[3 * k + 1]) + PetscRealPart(wd[3 * k + 2]));
    const PetscReal tr[2] = {PetscRealPart(ra[3 * k + 1]) + kt * PetscRealPart(va[in[k] + 1 - rstart]), PetscRealPart(ra[3 * k + 2]) + kt * PetscRealPart(va[in[k] + 2 - rstart])};
    const PetscReal tn = PetscSqrtReal(tr[0] * tr[0] + tr[1] * tr[1]);
    const PetscBool slip = (PetscBool)(sk > 0 && tn > sk * (1 + 1e-10));
    PetscReal      *d = &ct->slip_dir[2 * k];

    if (sk <= 0) continue;
    if (slip != ct->slipping[k]) ++nsw;
    ct->slipping[k] = slip;
    if (slip) {
      if (d[0] != 0 || d[1] != 0) dmax = PetscMax(dmax, PetscSqrtReal(PetscSqr(tr[0] / tn - d[0]) + PetscSqr(tr[1] / tn - d[1])));
      d[0] = tr[0] / tn;
      d[1] = tr[1] / tn;
    }
  }
  PetscCall(VecRestoreArrayRead(ct->Wdiag, &wd));
  PetscCall(VecRestoreArrayRead(sigma, &va));
  PetscCall(VecRestoreArrayRead(ct->rho, &ra));
  PetscCall(VecRestoreArrayRead(s, &sa));
  PetscCall(ISRestoreIndices(ct->is_normal, &in));
  PetscCall(MPIU_Allreduce(&nsw, switches, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)sigma)));
  PetscCall(MPIU_Allreduce(&dmax, dchange, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)sigma)));
  PetscFunctionReturn(0);
}

/* Friction thresholds s (one per contact node): |rho_t| <= s in the next solves (2D: a box, exact;
 * 3D: the disk through the stick/slip states). */
PetscErrorCode MMContactSetThresholds(MMCtx *ctx, Vec s)
{
  MMContact *ct = &ctx->contact;

  PetscFunctionBeginUser;
  if (ct->ncomp == 3) {
    PetscCall(MMSlipAssembleRotation(ct));
    PetscCall(MMSlipSetDiskBounds(ct, s));
    PetscFunctionReturn(0);
  }
  for (PetscInt c = 1; c < ct->ncomp; ++c) {
    PetscCall(VecStrideScatter(s, c, ct->rho_hi, INSERT_VALUES));
    PetscCall(VecStrideScatter(s, c, ct->rho_lo, INSERT_VALUES));
    PetscCall(VecStrideScale(ct->rho_lo, c, -1.0));
  }
  PetscFunctionReturn(0);
}

