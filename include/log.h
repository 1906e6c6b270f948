#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMLogRegister(MMLog *);
