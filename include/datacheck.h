#pragma once
#include "mmcontact.h"
/* -check_input: the data check's report and clean-up (src/app/datacheck.c) */
PETSC_EXTERN PetscErrorCode MMDataCheckReport(MMCtx *, TS);
PETSC_EXTERN PetscErrorCode MMDataCheckDestroy(MMCtx *);
