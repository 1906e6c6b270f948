/* The P1 discretization: the kernels' constants and the operators (src/fem/). */
#pragma once
#include "mmbase.h"

/* Physical parameters, also passed to the pointwise kernels as constants[]. */
typedef enum {
  MM_C_LAMBDA,
  MM_C_MU,
  MM_C_RHO,
  MM_C_WEIGHT_K, /* weights of the stiffness and mass kernels in an assembly */
  MM_C_WEIGHT_M,
  MM_C_GRAVITY,  /* MM_MAX_DIM entries */
  MM_C_NUM = MM_C_GRAVITY + MM_MAX_DIM
} MMConstantIndex;

/* Finite element operators in the contact frame (w-dofs). */
typedef struct {
  DM        dm;
  PetscInt  dim;
  Mat       K;      /* stiffness A */
  Mat       M;      /* standard mass (consistent or lumped) */
  Mat       Mstar;  /* mass used in time stepping: M with the contact-normal rows/columns removed, or M */
  Mat       Q;      /* frame rotation, u_cart = Q w */
  Vec       load;   /* L: body force + traction (w-frame), constant in time */
  Vec       lift;   /* K_fD u_D: the Dirichlet data's elastic force on the free dofs (w-frame) */
  Vec       mass_lumped_cart; /* lumped standard mass per Cartesian dof */
  PetscReal mass_M;           /* total mass of M */
  PetscReal mass_star[MM_MAX_DIM * MM_MAX_DIM]; /* M*'s mass for rigid translations, dim x dim (m I for M) */
  PetscReal x_cg[MM_MAX_DIM];                   /* M's centre of gravity in the reference configuration */
  PetscReal mass_correction;      /* -mass redistributed: the largest negative eigenvalue of a node's moment correction over its mass */
  PetscReal mass_moment_unreachable; /* 3D: |trace of G's translation-rotation block| left, / total mass (mass_redistribution.c) */
  PetscReal mass_moment_mismatch; /* -mass redistributed: max |rigid-mode Gram of M* - of M| / total mass */
  PetscReal c_p;    /* pressure wave speed */
  PetscReal energy_dirichlet; /* elastic energy of the Dirichlet data alone, 1/2 u_D.A_DD u_D */
  Vec       work;
} MMOperators;
