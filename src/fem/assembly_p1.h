/* Private to fem: the closed-form P1 stiffness and mass (src/fem/assembly_p1.c). */
#pragma once
#include "fem.h"
PETSC_INTERN PetscErrorCode MMCreateMatrixP1(DM dm, Mat *A);
PETSC_INTERN PetscErrorCode MMAssembleP1(DM dm, const MMMaterial *mat, Mat K, Mat M);
PETSC_INTERN PetscErrorCode MMApplyP1(DM dm, const MMMaterial *mat, Vec x, Vec f, PetscReal *energy);
