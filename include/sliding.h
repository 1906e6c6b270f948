#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMInitialStaticSliding(MMCtx *, Vec, Vec);
