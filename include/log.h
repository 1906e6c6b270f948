#pragma once
#include "systypes.h"
PETSC_EXTERN PetscErrorCode MMLogRegister(MMLog *log);
