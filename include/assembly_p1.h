#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMAssembleP1(DM, PetscReal, PetscReal, PetscReal, Mat, Mat);
PETSC_EXTERN PetscErrorCode MMRotateP1(Mat, Mat, Mat);
