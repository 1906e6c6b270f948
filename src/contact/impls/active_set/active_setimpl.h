/* Private to the active-set formulation (src/contact/impls/active_set/). */
#pragma once
#include "../../contactimpl.h"

/* The active-set contact solver (src/contact/impls/active_set/): per owned contact node its normal state and,
 * with friction, its stick/slip state and slip direction; the projected CG on the free dofs. */
typedef struct {
  KSP        ksp;       /* prefix contact_as_: CG on the free dofs, PC the projected contact_K_ PC */
  Mat        A;         /* shell operator P_F K~ P_F + P_D */
  Vec        free;      /* 1 on the dofs free in this iteration, 0 on the fixed ones (D) */
  Vec        x0, r, dx, t; /* the iterate with its fixed values, residuals, correction, scratch */
  Mat        Kc;        /* K~'s contact rows (is_cond), for the reactions: built from Kc_of at state Kc_state */
  Mat        Kc_of;
  PetscObjectState Kc_state;
  Vec        rc;        /* b - K~ w on the contact dofs */
  Vec        s;         /* Tresca thresholds per contact node (0 without friction) */
  Vec        ct_diag;   /* diag(K~): the scale c of the complementarity functions, per dof */
  PetscBool  block;     /* the CG's products with K~ through Kb, its block (BAIJ) copy */
  Mat        Kb, Kb_of; /* that copy, made from Kb_of at state Kb_state (block_operator.c) */
  PetscObjectState Kb_state;
  PetscBool *active;    /* normal: w_n = g (else rho_n = 0) */
  PetscBool *stick;     /* tangential: w_t = off_t (else rho_t = s d) */
  PetscReal *dir;       /* slip direction d per node, dim-1 components in the tangent frame */
  PetscReal *kappa, *beta, *rperp; /* 3D slip: Newton tangent of the disk across d (a spring kappa on
                                    * w.d_perp), and the reaction across d it corrects (beta rperp) */
  PetscInt   max_it, its, lin_its;
  KSPConvergedReason cg_failed; /* the last solve's CG failure (< 0), else KSP_CONVERGED_ITERATING */
  PetscReal  inexact_rtol; /* CG's relative tolerance while nodes change set (0: always tight) */
  PetscReal  inexact_coulomb_rtol; /* and while only the slip directions and thresholds move */
  PetscBool  monitor;
  PetscBool  coulomb;   /* the thresholds follow the iterate, s = mu rho_n (a Coulomb solve) */
  PetscReal  coulomb_rtol; /* its test: the thresholds' change over the force scale */
  Vec        kept_diag; /* the kept K~'s diag(K~) (-contact_K_keep) */
} MMActiveSet;

static inline MMActiveSet *MMActiveSetData(MMContact ct)
{
  return (MMActiveSet *)ct->data;
}

/* impls/active_set/: the primal-dual active-set formulation */
PETSC_EXTERN PetscErrorCode MMActiveSetSetUp(MMContact ct);
PETSC_EXTERN PetscErrorCode MMActiveSetSetOperator(MMContact ct);
PETSC_EXTERN PetscErrorCode MMActiveSetBlockOperator(Mat A, PetscInt dim, Mat *B);
PETSC_EXTERN PetscErrorCode MMActiveSetSetThresholds(MMContact ct, Vec s);
PETSC_EXTERN PetscErrorCode MMActiveSetSolve(MMContact ct, Vec b, Vec w, PetscBool *converged);
PETSC_EXTERN PetscErrorCode MMActiveSetDestroy(MMActiveSet *as);

