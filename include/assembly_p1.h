#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMCreateMatrixP1(DM, Mat *);
PETSC_EXTERN PetscErrorCode MMAssembleP1(DM, const MMMaterial *, Mat, Mat);
PETSC_EXTERN PetscErrorCode MMApplyP1(DM, const MMMaterial *, Vec, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode MMRotateP1(Mat, Mat, Mat);
PETSC_EXTERN PetscErrorCode MMAssembleP1DampingStiffness(DM, const MMMaterial *, Mat, Vec, Mat);
