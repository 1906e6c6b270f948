/* Private to fem: the elasticity laws' pointwise tables (src/fem/elasticity_laws.c), per unit reference
 * volume, functions of the displacement gradient G = grad u, F = I + G (plane strain in 2D). */
#pragma once
#include "fem.h"

typedef PetscReal MMTangent[MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM][MM_MAX_DIM];

typedef struct {
  /* the stored energy W */
  PetscReal (*energy)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal G[MM_MAX_DIM][MM_MAX_DIM]);
  /* the algorithmic first Piola-Kirchhoff stress of a step from G0 to G1: P : (G1 - G0) = W(G1) - W(G0),
   * plus the viscous stress of the step, visc D : dE (visc = beta/dt, D the moduli lambda, mu, dE the
   * step's strain increment): its work P_v : (G1 - G0) = visc dE : D : dE >= 0 */
  void (*stress_alg)(PetscInt dim, PetscReal lambda, PetscReal mu, PetscReal visc, const PetscReal G0[MM_MAX_DIM][MM_MAX_DIM], const PetscReal G1[MM_MAX_DIM][MM_MAX_DIM], PetscReal P[MM_MAX_DIM][MM_MAX_DIM]);
  /* dE : D : dE of the step from G0 to G1, the viscous stress's dissipation per unit volume and visc */
  PetscReal (*dissipation)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal G0[MM_MAX_DIM][MM_MAX_DIM], const PetscReal G1[MM_MAX_DIM][MM_MAX_DIM]);
  /* A = dP/dF at G (material and geometric parts): the Newton iteration matrix's; *definite false where
   * the geometric part is indefinite (a compressed cell): the cell's matrix is then made semi-definite */
  void (*tangent)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal G[MM_MAX_DIM][MM_MAX_DIM], MMTangent A, PetscBool *definite);
  /* the Cauchy stress of the current configuration (the linear law: sigma(eps)) */
  void (*cauchy)(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal G[MM_MAX_DIM][MM_MAX_DIM], PetscReal sigma[MM_MAX_DIM][MM_MAX_DIM]);
  PetscBool finite; /* a finite-strain law: rotations are free of strain */
} MMElasticityOps;

PETSC_INTERN const MMElasticityOps *MMElasticityGetOps(MMElasticityType type);

/* fem's events of the finite-strain laws (src/fem/fem.c registers them) */
PETSC_INTERN PetscLogEvent MM_FE_ElasticForce, MM_FE_ElasticEnergy, MM_FE_ElasticTangent;
