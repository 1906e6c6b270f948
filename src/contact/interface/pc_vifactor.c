/* PC "vifactor": the full formulation's Newton solves (SNESVINEWTONRSLS, prefix contact_), exact,
 * through one factor of the whole K~ whose active rows and columns are the identity's
 * (docs/scaling.md, "The full formulation's factor").
 *
 * The VI solves K~(I, I) y_I = f_I on its inactive set I at each iteration, with a new submatrix
 * each time, so a factor PC orders and analyses it anew every time: MUMPS's analysis, sequential
 * on its host, was a large share of the run, and slower on two ranks than on one (the figures:
 * docs/scaling.md, "The figures behind the code's choices"). Here the factored matrix is
 *   K~_A = K~ with the rows and columns of the active set A zeroed and d on their diagonal,
 * whose nonzero pattern is K~'s for every A: ordered and analysed once, refactored numerically
 * when A or K~ changes. K~_A = [K~(I, I) 0; 0 d 1] up to a permutation, so with zero right-hand
 * side on A the solve gives y_I = K~(I, I)^{-1} f_I exactly (and 0 on A). d is K~'s largest
 * diagonal entry: the identity block then has K~'s scale. The ordering and analysis run when K~ is
 * first set (MMPCVIFactorAnalyse, from the formulation's set-up): set-up work, not the first
 * contact step's. The factor is held here, not by an inner PC, whose set-up would also factor. */
#include <petsc/private/pcimpl.h>
#include "../contactimpl.h"

typedef struct {
  SNES             snes;      /* the VI (borrowed): its inactive set, and its Jacobian, the whole K~ */
  Mat              Ka;        /* K~_A */
  Mat              F;         /* its factor, analysed once */
  MatFactorInfo    info;
  char             type[64];  /* the factor's package: -PREFIX_pc_factor_mat_solver_type, or MUMPS */
  PetscBool        type_set;  /* whether the user named it */
  Vec              bf, xf;    /* whole-size work vectors */
  IS               inact;     /* the inactive set F holds (a reference to the VI's), NULL before the first */
  PetscScalar      d;         /* the diagonal of the active rows */
  PetscObjectId    kid;       /* the K~ F was computed from: its object id and state */
  PetscObjectState kstate;
} PC_VIFactor;

/* K~_A's matrix, vectors and factor, ordered and analysed. A dense K~ (a VI on a Delassus block) is
 * factored by LAPACK unless the user named a package. */
static PetscErrorCode Analyse(PC pc, Mat K)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  const char  *prefix;
  Vec          diag;
  PetscReal    dmax;
  PetscBool    dense, canorder;
  IS           row = NULL, col = NULL;

  PetscFunctionBegin;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATSEQDENSE, &dense));
  if (dense && !vf->type_set) PetscCall(PetscStrncpy(vf->type, MATSOLVERPETSC, sizeof(vf->type)));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &vf->Ka));
  PetscCall(MatCreateVecs(K, &vf->xf, &vf->bf));
  PetscCall(MatCreateVecs(K, &diag, NULL));
  PetscCall(MatGetDiagonal(K, diag));
  PetscCall(VecNorm(diag, NORM_INFINITY, &dmax));
  PetscCall(VecDestroy(&diag));
  vf->d = dmax > 0 ? dmax : 1.0;
  PetscCall(MatSetOptionsPrefixFactor(vf->Ka, prefix)); /* the factor reads -PREFIX_mat_mumps_* */
  PetscCall(MatGetFactor(vf->Ka, vf->type, MAT_FACTOR_CHOLESKY, &vf->F));
  PetscCall(MatFactorInfoInitialize(&vf->info));
  PetscCall(MatFactorGetCanUseOrdering(vf->F, &canorder));
  if (canorder) {
    MatOrderingType otype;
    PetscCall(MatFactorGetPreferredOrdering(vf->F, MAT_FACTOR_CHOLESKY, &otype));
    PetscCall(MatGetOrdering(vf->Ka, otype, &row, &col));
  }
  PetscCall(MatCholeskyFactorSymbolic(vf->F, vf->Ka, row, &vf->info));
  PetscCall(ISDestroy(&row));
  PetscCall(ISDestroy(&col));
  PetscFunctionReturn(0);
}

/* K~_A for the inactive set inact, factored unless F already is, for this K~. */
static PetscErrorCode FactorForInactiveSet(PC pc, Mat K, IS inact)
{
  PC_VIFactor     *vf = (PC_VIFactor *)pc->data;
  IS               act;
  PetscInt         rstart, rend;
  PetscObjectId    kid;
  PetscObjectState kstate;
  PetscBool        same = PETSC_FALSE;
  MatFactorError   err;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetId((PetscObject)K, &kid));
  PetscCall(PetscObjectStateGet((PetscObject)K, &kstate));
  if (vf->inact && kid == vf->kid && kstate == vf->kstate) PetscCall(ISEqual(vf->inact, inact, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(PetscInfo(pc, "Factoring K~_A: %s\n", !vf->inact ? "first" : kid != vf->kid || kstate != vf->kstate ? "K~ changed" : "the active set changed"));
  if (!vf->F) PetscCall(Analyse(pc, K));
  PetscCall(MatCopy(K, vf->Ka, SAME_NONZERO_PATTERN));
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  PetscCall(ISComplement(inact, rstart, rend, &act));
  PetscCall(MatZeroRowsColumnsIS(vf->Ka, act, vf->d, NULL, NULL));
  PetscCall(ISDestroy(&act));
  PetscCall(MatCholeskyFactorNumeric(vf->F, vf->Ka, &vf->info));
  PetscCall(MatFactorGetError(vf->F, &err));
  pc->failedreason = (PCFailedReason)err; /* the two enums agree, as PETSc's own factor PCs assume */
  PetscCall(PetscObjectReference((PetscObject)inact));
  PetscCall(ISDestroy(&vf->inact));
  vf->inact  = inact;
  vf->kid    = kid;
  vf->kstate = kstate;
  PetscFunctionReturn(0);
}

/* The VI's current inactive set. */
static PetscErrorCode PCSetUp_VIFactor(PC pc)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  Mat          K;
  IS           inact;

  PetscFunctionBegin;
  PetscCheck(vf->snes, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONGSTATE, "PC %s solves the Newton steps of a SNESVINEWTONRSLS: MMPCVIFactorSetSNES() first", MMPCVIFACTOR);
  PetscCall(SNESVIGetInactiveSet(vf->snes, &inact));
  PetscCall(SNESGetJacobian(vf->snes, &K, NULL, NULL, NULL));
  PetscCall(FactorForInactiveSet(pc, K, inact));
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
  PetscCall(MatSolve(vf->F, vf->bf, vf->xf));
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
  PetscCall(MatDestroy(&vf->F));
  PetscCall(VecDestroy(&vf->bf));
  PetscCall(VecDestroy(&vf->xf));
  PetscCall(ISDestroy(&vf->inact));
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Cholesky (%s) of the whole K~ with the VI's active rows and columns the identity's (times %g): one pattern for every active set\n", vf->type, (double)PetscRealPart(vf->d)));
  if (vf->F) {
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(MatView(vf->F, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PCCreate_VIFactor(PC pc)
{
  PC_VIFactor *vf;

  PetscFunctionBegin;
  PetscCall(PetscNew(&vf));
  PetscCall(PetscStrncpy(vf->type, MATSOLVERMUMPS, sizeof(vf->type)));
  pc->data                = (void *)vf;
  pc->ops->setup          = PCSetUp_VIFactor;
  pc->ops->apply          = PCApply_VIFactor;
  pc->ops->applytranspose = PCApply_VIFactor; /* K~ is symmetric */
  pc->ops->reset          = PCReset_VIFactor;
  pc->ops->destroy        = PCDestroy_VIFactor;
  pc->ops->view           = PCView_VIFactor;
  PetscFunctionReturn(0);
}

/*@
  MMPCRegisterVIFactor - Registers the PC type vifactor (MMPCVIFACTOR), once

  Not collective

  Level: developer

.seealso: `MMPCVIFactorSetSNES()`, `MMPCRegisterSchurSplit()`
@*/
PetscErrorCode MMPCRegisterVIFactor(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBegin;
  if (done) PetscFunctionReturn(0);
  PetscCall(PCRegister(MMPCVIFACTOR, PCCreate_VIFactor));
  done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode IsVIFactor(PC pc, PetscBool *is)
{
  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, MMPCVIFACTOR, is));
  PetscFunctionReturn(0);
}

/*@
  MMPCVIFactorSetSNES - Gives a vifactor PC the VI whose Newton steps it solves, and reads its
  factor package

  Logically collective

  Input Parameters:
+ pc   - the PC (nothing is done for another type)
- snes - the VI's SNES (borrowed)

  Note:
  The VI whose Newton steps pc solves (borrowed: the SNES holds the PC), and the factor's package:
  -PREFIX_pc_factor_mat_solver_type, or MUMPS.

  Level: developer

.seealso: `MMPCVIFactorAnalyse()`, `MMPCVIFactorGetFactor()`
@*/
PetscErrorCode MMPCVIFactorSetSNES(PC pc, SNES snes)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  const char  *prefix;
  PetscBool    is;

  PetscFunctionBegin;
  PetscCall(IsVIFactor(pc, &is));
  if (!is) PetscFunctionReturn(0);
  vf->snes = snes;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-pc_factor_mat_solver_type", vf->type, sizeof(vf->type), &vf->type_set));
  PetscFunctionReturn(0);
}

/*@
  MMPCVIFactorAnalyse - Orders and analyses a new K~ in a vifactor PC, once

  Collective

  Input Parameters:
+ pc - the PC (nothing is done for another type, or when a factor exists)
- K  - the new K~

  Note:
  A new K~ (set-up, a new dt): ordered and analysed now, on first use. The numeric factorization
  waits for the VI's first active set.

  Level: developer

.seealso: `MMPCVIFactorSetSNES()`, `MMPCVIFactorGetFactor()`
@*/
PetscErrorCode MMPCVIFactorAnalyse(PC pc, Mat K)
{
  PC_VIFactor *vf = (PC_VIFactor *)pc->data;
  PetscBool    is;

  PetscFunctionBegin;
  PetscCall(IsVIFactor(pc, &is));
  if (!is || vf->F) PetscFunctionReturn(0);
  PetscCall(Analyse(pc, K));
  PetscFunctionReturn(0);
}

/*@
  MMPCVIFactorGetFactor - Gives a vifactor PC's factor and its package, for the start-up report

  Not collective

  Input Parameter:
. pc - the PC

  Output Parameters:
+ F    - the factor, NULL before the analysis or for another PC type
- type - the factor's package (or NULL)

  Note:
  The factor and its package, for the start-up report; F is NULL before the analysis or for another
  PC type.

  Level: developer

.seealso: `MMPCVIFactorAnalyse()`
@*/
PetscErrorCode MMPCVIFactorGetFactor(PC pc, Mat *F, const char **type)
{
  PetscBool is;

  PetscFunctionBegin;
  *F = NULL;
  if (type) *type = NULL;
  PetscCall(IsVIFactor(pc, &is));
  if (!is) PetscFunctionReturn(0);
  *F = ((PC_VIFactor *)pc->data)->F;
  if (type) *type = ((PC_VIFactor *)pc->data)->type;
  PetscFunctionReturn(0);
}
