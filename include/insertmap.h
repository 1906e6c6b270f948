#pragma once
#include <petscdm.h>

/* DMLocalToGlobal(dm, l, INSERT_VALUES, g) as a list of (local, global) dof pairs built once per
 * DM (src/fem/insertmap.c). */
typedef struct {
  DM        dm;         /* the DM the map was built for (not referenced) */
  PetscBool transform;  /* the DM has a basis transform: PETSc's own DMLocalToGlobal */
  PetscInt  n;
  PetscInt *loc, *glob; /* local offset, global offset from this rank's first */
} MMInsertMap;

PETSC_EXTERN PetscErrorCode MMInsertMapLocalToGlobal(DM, MMInsertMap *, Vec, Vec);
PETSC_EXTERN PetscErrorCode MMInsertMapDestroy(MMInsertMap *);
