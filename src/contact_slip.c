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

/* Each owned node's (n, d, d_perp) basis as (1, cos, sin) of its slip direction in the frame's
 * tangent plane, gathered to the candidate set by the VI. */
PetscErrorCode MMSlipStoreRotations(MMContact *ct)
{
  PetscScalar *ra;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(ct->rot, &ra));
  for (PetscInt k = 0; k < ct->n_local; ++k) {
    const PetscReal *d  = &ct->slip_dir[2 * k];
    const PetscReal  dd = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]);
    ra[3 * k]     = 1.0;
    ra[3 * k + 1] = dd > 0 ? d[0] / dd : 1;
    ra[3 * k + 2] = dd > 0 ? d[1] / dd : 0;
  }
  PetscCall(VecRestoreArray(ct->rot, &ra));
  PetscFunctionReturn(0);
}

/* The 3x3 rotation R of a node, from the frame's (n, t1, t2) to its (n, d, d_perp): x_frame = R x_r. */
static void NodeRotation(const PetscScalar *rot, PetscReal R[3][3])
{
  const PetscReal c = PetscRealPart(rot[1]), s = PetscRealPart(rot[2]);
  R[0][0] = 1; R[0][1] = 0; R[0][2] = 0;
  R[1][0] = 0; R[1][1] = c; R[1][2] = -s;
  R[2][0] = 0; R[2][1] = s; R[2][2] = c;
}

/* The set's VI in the nodes' own bases, block by block: Wr_ij = R_i^T W_ij R_j, q_r = R^T q and
 * the warm start x_r = R^T x. Only the candidate block is rotated, never a whole matrix. */
PetscErrorCode MMSlipRotateSet(MMCandidates *c)
{
  const PetscInt     n = c->n_set, m = c->m;
  const PetscScalar *w, *ra;
  PetscScalar       *wr, *qa, *xa;

  PetscFunctionBeginUser;
  PetscCall(MatDenseGetArrayRead(c->W, &w));
  PetscCall(MatDenseGetArrayWrite(c->Wr, &wr));
  PetscCall(VecGetArrayRead(c->rot, &ra));
  for (PetscInt j = 0; j < n; ++j) {
    PetscReal Rj[3][3];
    NodeRotation(&ra[3 * j], Rj);
    for (PetscInt i = 0; i < n; ++i) {
      PetscReal Ri[3][3], WR[3][3];
      NodeRotation(&ra[3 * i], Ri);
      for (PetscInt p = 0; p < 3; ++p)
        for (PetscInt q = 0; q < 3; ++q) {
          WR[p][q] = 0;
          for (PetscInt r = 0; r < 3; ++r) WR[p][q] += PetscRealPart(w[(3 * i + p) + (size_t)(3 * j + r) * m]) * Rj[r][q];
        }
      for (PetscInt p = 0; p < 3; ++p)
        for (PetscInt q = 0; q < 3; ++q) {
          PetscReal v = 0;
          for (PetscInt r = 0; r < 3; ++r) v += Ri[r][p] * WR[r][q];
          wr[(3 * i + p) + (size_t)(3 * j + q) * m] = v;
        }
    }
  }
  PetscCall(MatDenseRestoreArrayWrite(c->Wr, &wr));
  PetscCall(MatDenseRestoreArrayRead(c->W, &w));
  PetscCall(MatAssemblyBegin(c->Wr, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(c->Wr, MAT_FINAL_ASSEMBLY));
  PetscCall(VecGetArray(c->q, &qa));
  PetscCall(VecGetArray(c->x, &xa));
  for (PetscInt i = 0; i < n; ++i) {
    PetscReal       R[3][3];
    const PetscReal q1 = PetscRealPart(qa[3 * i + 1]), q2 = PetscRealPart(qa[3 * i + 2]);
    const PetscReal x1 = PetscRealPart(xa[3 * i + 1]), x2 = PetscRealPart(xa[3 * i + 2]);
    NodeRotation(&ra[3 * i], R);
    qa[3 * i + 1] = R[1][1] * q1 + R[2][1] * q2;
    qa[3 * i + 2] = R[1][2] * q1 + R[2][2] * q2;
    xa[3 * i + 1] = R[1][1] * x1 + R[2][1] * x2;
    xa[3 * i + 2] = R[1][2] * x1 + R[2][2] * x2;
  }
  PetscCall(VecRestoreArray(c->x, &xa));
  PetscCall(VecRestoreArray(c->q, &qa));
  PetscCall(VecRestoreArrayRead(c->rot, &ra));
  PetscFunctionReturn(0);
}

/* x = R x_r: the set's reactions back in the frame's components. */
PetscErrorCode MMSlipRotateBack(MMCandidates *c, Vec x)
{
  const PetscScalar *ra;
  PetscScalar       *xa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(c->rot, &ra));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < c->n_set; ++i) {
    PetscReal       R[3][3];
    const PetscReal x1 = PetscRealPart(xa[3 * i + 1]), x2 = PetscRealPart(xa[3 * i + 2]);
    NodeRotation(&ra[3 * i], R);
    xa[3 * i + 1] = R[1][1] * x1 + R[1][2] * x2;
    xa[3 * i + 2] = R[2][1] * x1 + R[2][2] * x2;
  }
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecRestoreArrayRead(c->rot, &ra));
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
    PetscCall(MMSlipStoreRotations(ct));
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

