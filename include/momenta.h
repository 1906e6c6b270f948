#pragma once
#include "mmcontact.h"
PETSC_EXTERN PetscErrorCode MMRigidBodyDiagnostics(MMCtx *, MMHistory *);
PETSC_EXTERN PetscErrorCode MMMomentaDestroy(MMMomenta *);
