/* Private to fem: the closed-form P1 stiffness and mass (src/fem/assembly_p1.c). */
#pragma once
#include "fem.h"
PETSC_INTERN PetscErrorCode MMCreateMatrixP1(DM dm, Mat *A);
PETSC_INTERN PetscErrorCode MMAssembleP1(DM dm, const MMMaterial *mat, Mat K, Mat M);
PETSC_INTERN PetscErrorCode MMApplyP1(DM dm, const MMMaterial *mat, Vec x, Vec f, PetscReal *energy);
/* The finite-strain tangent's assembly (src/fem/elasticity.c): element() fills the cell's
 * (dim+1) dim square matrix, dofs vertex-major, from its vertices v (local points) and P1 gradients g */
typedef PetscErrorCode (*MMP1ElementFn)(void *ctx, PetscInt c, const PetscInt v[], const PetscReal g[][MM_MAX_DIM], PetscReal vol, PetscScalar Ke[]);
PETSC_INTERN PetscErrorCode MMAssembleP1Elements(DM dm, Mat K, MMP1ElementFn element, void *ctx);
PETSC_INTERN PetscErrorCode MMP1CellGradients(PetscInt dim, const PetscReal x[][MM_MAX_DIM], PetscReal g[][MM_MAX_DIM], PetscReal *vol);
