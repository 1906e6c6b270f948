#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMFESetFromOptions(MPI_Comm comm, MMOperators *op);
PETSC_EXTERN PetscErrorCode MMFESetUp(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFEAssembleOperators(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFECreateMatrix(MMCtx *, DM, Mat *);
PETSC_EXTERN PetscErrorCode MMFEInterpolate(MMCtx *, PetscErrorCode (*)(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar *, void *), void *, Vec);
PETSC_EXTERN PetscErrorCode MMFEElasticEnergy(MMCtx *, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode MMFECheckElasticEnergy(MMCtx *, Vec);
PETSC_EXTERN PetscErrorCode MMFEToCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEFromCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEForceToCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEForceFromCartesian(MMCtx *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMFEDestroy(MMOperators *);
PETSC_EXTERN PetscErrorCode MMFERedistributeMass(MMCtx *);
PETSC_EXTERN PetscErrorCode MMFEMassMoments(MMCtx *);
/* rigid_modes.c: the rigid-body modes, translations then rotations */
#define MM_MAX_RIGID 6
static inline PetscInt MMFENumRigidModes(PetscInt dim)
{
  return dim == 2 ? 3 : 6;
}
PETSC_EXTERN void           MMFERigidModeMatrix(PetscInt, const PetscReal[], PetscReal[MM_MAX_DIM][MM_MAX_RIGID]);
PETSC_EXTERN PetscErrorCode MMFERigidModesCartesian(MMCtx *, const PetscReal[], PetscReal, PetscInt, Vec[]);
/* The modified and the redistributed mass leave the contact-normal dofs without inertia. */
static inline PetscBool MMFEHasMasslessDofs(const MMCtx *ctx)
{
  return (PetscBool)(ctx->contact.enabled && ctx->op.mass_type != MM_MASS_STANDARD);
}
PETSC_EXTERN PetscErrorCode MMFEAddTraction(MMCtx *, PetscInt, Vec);
PETSC_EXTERN PetscErrorCode MMFEVertexMasses(MMCtx *, Vec);
/* stress.c: the stress of a displacement, for the output */
PETSC_EXTERN PetscErrorCode MMStressCreate(const MMOperators *op, MMStress *st);
PETSC_EXTERN PetscErrorCode MMStressCompute(MMStress *st, const MMOperators *op, const MMMaterial *mat, DM dm_u, Vec u, PetscBool nodal);
PETSC_EXTERN PetscErrorCode MMStressDestroy(MMStress *st);
