/* Private to fem: the elasticity laws' pointwise tables (src/fem/elasticity_laws.c), per unit reference
 * volume, functions of the deformation gradient F (plane strain in 2D). */
#pragma once
#include "fem.h"

typedef PetscReal MMTangent[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM];

typedef struct {
  /* the stored energy W(F) */
  PetscReal (*energy)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal F[MM_MAX_DIM][MM_MAX_DIM]);
  /* the algorithmic first Piola-Kirchhoff stress of a step from F0 to F1: P : (F1 - F0) = W(F1) - W(F0) */
  void (*stress_alg)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal F0[MM_MAX_DIM][MM_MAX_DIM], const PetscReal F1[MM_MAX_DIM][MM_MAX_DIM], PetscReal P[MM_MAX_DIM][MM_MAX_DIM]);
  /* A = dP/dF at F (material and geometric parts): the Newton iteration matrix's */
  void (*tangent)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal F[MM_MAX_DIM][MM_MAX_DIM], MMTangent A);
  /* the Cauchy stress of the current configuration (the linear law: sigma(eps)) */
  void (*cauchy)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal F[MM_MAX_DIM][MM_MAX_DIM], PetscReal sigma[MM_MAX_DIM][MM_MAX_DIM]);
  PetscBool finite; /* a finite-strain law: rotations are free of strain */
} MMElasticityOps;

PETSC_INTERN const MMElasticityOps *MMElasticityGetOps(MMElasticityType type);
