#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMLogRegister(MMLog *);
/* The Cartesian stiffness and mass alone (fem.c), by the selected -assembly path: a global, as
 * PETSc's own events are, so the MMLog context type stays as it is. */
PETSC_EXTERN PetscLogEvent MM_AssembleKM;
