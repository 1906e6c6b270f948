#pragma once
#include "systypes.h"
PETSC_EXTERN PetscErrorCode MMLogRegister(MMLog *log);
/* MUMPS's solve of the candidate columns on several ranks, and their move to PETSc's rows (src/contact/impls/condensed/mumps_columns.c) */
PETSC_EXTERN PetscLogEvent MM_ColumnsSolve, MM_ColumnsMove;
/* schursplit's apply: the interface's sum and dense solve (with the wait for the other ranks), the own backward sweep */
PETSC_EXTERN PetscLogEvent MM_SplitInterface, MM_SplitBackward;
/* the active-set CG's block copy of K~, made or refilled (src/contact/impls/active_set/block_operator.c) */
PETSC_EXTERN PetscLogEvent MM_BlockOperator;
