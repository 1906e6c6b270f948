/* Private to mesh: METIS as a PetscPartitioner (src/mesh/partition_metis.c). */
#pragma once
#include <petscdmplex.h>
#define MM_PARTITIONER_METIS "metis"
PETSC_INTERN PetscErrorCode MMPartitionerRegisterMetis(void);
PETSC_INTERN PetscErrorCode MMPartitionerMetisSetDM(PetscPartitioner part, DM dm);
