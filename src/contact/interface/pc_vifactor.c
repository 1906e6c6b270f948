/* PC "vifactor": the full formulation's Newton solves (SNESVINEWTONRSLS, prefix contact_), exact,
 * through one factor of the whole K~ whose active rows and columns are the identity's
 * (docs/scaling.md, "The full formulation's factor").
 *
 * The VI solves K~(I, I) y_I = f_I on its inactive set I at each iteration, with a new submatrix
 * each time, so a factor PC orders and analyses it anew every time: MUMPS's analysis, sequential
 * on its host, was 1.6 of the 115k-dof D1 disk's 13.3 s on one rank and 2.3 of 9.4 s on two
 * (30 steps, 26 factorizations), and slower on two ranks than on one. Here the factored matrix is
 *   K~_A = K~ with the rows and columns of the active set A zeroed and d on their diagonal,
 * whose nonzero pattern is K~'s for every A: ordered and analysed once, refactored numerically
 * when A or K~ changes. K~_A = [K~(I, I) 0; 0 d 1] up to a permutation, so with zero right-hand
 * side on A the solve gives y_I = K~(I, I)^{-1} f_I exactly (and 0 on A). d is K~'s largest
 * diagonal entry: the identity block then has K~'s scale. */
#include <petsc/private/pcimpl.h>
#include "../contactimpl.h"

typedef struct {
  SNES             snes;   /* the VI (borrowed): its inactive set, and its Jacobian, the whole K~ */
  Mat              Ka;     /* K~_A */
  PC               inner;  /* K~_A's factor, prefix the PC's own */
  Vec              bf, xf; /* whole-size work vectors */
  IS               inact;  /* the inactive set K~_A was factored for (a reference to the VI's) */
  PetscScalar      d;      /* the diagonal of the active rows */
  PetscObjectState kstate; /* K~'s state when K~_A was built */
} PC_VIFactor;

/* K~_A and its vectors, on first use. A dense K~ (a VI on a Delassus block) is factored by LAPACK,
 * unless the user named a package. */
static PetscErrorCode CreateWhole(PC_VIFactor *vf, Mat K)
{
  Vec         diag;
  PetscReal   dmax;
  PetscBool   dense, set;
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATSEQDENSE, &dense));
  PetscCall(PCGetOptionsPrefix(vf->inner, &prefix));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-pc_factor_mat_solver_type", &set));
  if (dense && !set) PetscCall(PCFactorSetMatSolverType(vf->inner, MATSOLVERPETSC));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &vf->Ka));
  PetscCall(MatCreateVecs(K, &vf->xf, &vf->bf));
  PetscCall(MatCreateVecs(K, &diag, NULL));
  PetscCall(MatGetDiagonal(K, diag));
  PetscCall(VecNorm(diag, NORM_INFINITY, &dmax));
  PetscCall(VecDestroy(&diag));
  vf->d = dmax > 0 ? dmax : 1.0;
  PetscFunctionReturn(0);
}

/* Refactors K~_A unless it already holds this inactive set and this K~. */
static PetscErrorCode PCSetUp_VIFactor(PC pc)
{
  PC_VIFactor     *vf = (PC_VIFactor *)pc->data;
  Mat              K;
  IS               inact, act;
  PetscInt         rstart, rend;
  PetscObjectState kstate;
  PetscBool        same = PETSC_FALSE;
  PCFailedReason   reason;

  PetscFunctionBegin;
  PetscCheck(vf->snes && vf->inner, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONGSTATE, "PC %s solves the Newton steps of a SNESVINEWTONRSLS: MMPCVIFactorSetSNES() first", MMPCVIFACTOR);
  PetscCall(SNESVIGetInactiveSet(vf->snes, &inact));
  PetscCall(SNESGetJacobian(vf->snes, &K, NULL, NULL, NULL));
  PetscCall(PetscObjectStateGet((PetscObject)K, &kstate));
  if (vf->inact && kstate == vf->kstate) PetscCall(ISEqual(vf->inact, inact, &same));
  if (same) PetscFunctionReturn(0);
  if (!vf->Ka) PetscCall(CreateWhole(vf, K));
  else PetscCall(MatCopy(K, vf->Ka, SAME_NONZERO_PATTERN));
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  PetscCall(ISComplement(inact, rstart, rend, &act));
  PetscCall(MatZeroRowsColumnsIS(vf->Ka, act, vf->d, NULL, NULL));
  PetscCall(ISDestroy(&act));
  PetscCall(PCSetOperators(vf->inner, vf->Ka, vf->Ka));
  PetscCall(PCSetUp(vf->inner));
  PetscCall(PCGetFailedReasonRank(vf->inner, &reason));
  pc->failedreason = reason;
  PetscCall(PetscObjectReference((PetscObject)inact));
  PetscCall(ISDestroy(&vf->inact));
  vf->inact  = inact;
  vf->kstate = kstate;
  PetscFunctionReturn(0);
}

/* y_I = K~(I, I)^{-1} f_I: f_I into the whole vector (zero on A), one solve with K~_A, y_I out. */
static PetscErrorCode PCApply_VIFactor(PC pc, Vec f, Vec y)
{
  PC_VIFactor       *vf = (PC_VIFactor *)pc->data;
  const PetscInt    *idx;
  const PetscScalar *fa, *xa;
  PetscScalar       *ba, *ya;
  PetscInt           n, rstart;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(vf->bf, &rstart, NULL));
  PetscCall(ISGetLocalSize(vf->inact, &n));
  PetscCall(ISGetIndices(vf->inact, &idx));
  PetscCall(VecSet(vf->bf, 0.0));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArray(vf->bf, &ba));
  for (PetscInt i = 0; i < n; ++i) ba[idx[i] - rstart] = fa[i];
  PetscCall(VecRestoreArray(vf->bf, &ba));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(PCApply(vf->inner, vf->bf, vf->xf));
  PetscCall(VecGetArrayRead(vf->xf, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt i = 0; i < n; ++i) ya[i] = xa[idx[i] - rstart];
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(vf->xf, &xa));
  PetscCall(ISRestoreIndices(vf->inact, &idx));
  PetscFunctionReturn(0);
}

/* The VI resets its KSP whenever the inactive set changes (SNESVIResetPCandKSP): K~_A and its
 * factor outlive that, since their pattern is K~'s, and go only with the PC. */
static PetscErrorCode PCReset_VIFactor(PC pc)
{
  PetscFunctionBegin;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCDestroy_VIFactor(PC pc)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&vf->Ka));
  PetscCall(PCDestroy(&vf->inner));
  PetscCall(VecDestroy(&vf->bf));
  PetscCall(VecDestroy(&vf->xf));
  PetscCall(ISDestroy(&vf->inact));
  PetscCall(PetscObjectComposeFunction((PetscObject)pc, "MMPCVIFactorGetFactorPC_C", NULL));
  PetscCall(PetscFree(pc->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCView_VIFactor(PC pc, PetscViewer viewer)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  PetscBool    ascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  the whole K~ with the VI's active rows and columns the identity's (times %g), one pattern for every active set\n", (double)PetscRealPart(vf->d)));
  if (vf->inner) {
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(PCView(vf->inner, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PCVIFactorGetFactorPC_VIFactor(PC pc, PC *inner)
{
  PetscFunctionBegin;
  *inner = ((PC_VIFactor *)pc->data)->inner;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCCreate_VIFactor(PC pc)
{
  PC_VIFactor *vf;

  PetscFunctionBegin;
  PetscCall(PetscNew(&vf));
  pc->data                = (void *)vf;
  pc->ops->setup          = PCSetUp_VIFactor;
  pc->ops->apply          = PCApply_VIFactor;
  pc->ops->applytranspose = PCApply_VIFactor; /* K~ is symmetric */
  pc->ops->reset          = PCReset_VIFactor;
  pc->ops->destroy        = PCDestroy_VIFactor;
  pc->ops->view           = PCView_VIFactor;
  PetscCall(PetscObjectComposeFunction((PetscObject)pc, "MMPCVIFactorGetFactorPC_C", PCVIFactorGetFactorPC_VIFactor));
  PetscFunctionReturn(0);
}

PetscErrorCode MMPCRegisterVIFactor(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBegin;
  if (done) PetscFunctionReturn(0);
  PetscCall(PCRegister(MMPCVIFACTOR, PCCreate_VIFactor));
  done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The VI whose Newton steps pc solves (borrowed: the SNES holds the PC), and the factor's PC with
 * pc's prefix, so that the factor reads -PREFIX_mat_mumps_* as the VI's own factor did: Cholesky by
 * MUMPS, or by -PREFIX_pc_factor_mat_solver_type. Not PCSetFromOptions: -PREFIX_pc_type is this
 * PC's own type. */
PetscErrorCode MMPCVIFactorSetSNES(PC pc, SNES snes)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  const char  *prefix;
  char         type[64] = MATSOLVERMUMPS;
  PetscBool    is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCVIFACTOR, &is));
  if (!is) PetscFunctionReturn(0);
  vf->snes = snes;
  if (vf->inner) PetscFunctionReturn(0);
  PetscCall(PCCreate(PetscObjectComm((PetscObject)pc), &vf->inner));
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PCSetOptionsPrefix(vf->inner, prefix));
  PetscCall(PCSetType(vf->inner, PCCHOLESKY));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-pc_factor_mat_solver_type", type, sizeof(type), NULL));
  PetscCall(PCFactorSetMatSolverType(vf->inner, type));
  PetscFunctionReturn(0);
}

/* The factor's PC inside a vifactor PC, or NULL (another type, or before MMPCVIFactorSetSNES). */
PetscErrorCode MMPCVIFactorGetFactorPC(PC pc, PC *inner)
{
  PetscFunctionBegin;
  *inner = NULL;
  PetscTryMethod(pc, "MMPCVIFactorGetFactorPC_C", (PC, PC *), (pc, inner));
  PetscFunctionReturn(0);
}
