#pragma once
#include <petscdmplex.h>
#define MM_PARTITIONER_METIS "metis"
PETSC_EXTERN PetscErrorCode MMPartitionerRegisterMetis(void);
PETSC_EXTERN PetscErrorCode MMPartitionerMetisSetDM(PetscPartitioner, DM);
