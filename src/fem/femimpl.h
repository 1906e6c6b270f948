/* Private to fem: its operators' struct, the object MMOperators of include/fem.h (docs/developer.md,
 * "Components"). Only src/fem/ includes it: another component reads what it needs through fem's
 * functions (MMFEGetDM, MMFEGetDimension, ...). */
#pragma once
#include "fem.h"

typedef struct {
  MMFrameOps ops;
  void      *ctx;
} MMFrame;

/* The finite element operators: fem assembles K, M, the load and the lift on the Cartesian dofs
 * (MMFEAssembleOperators) and hands K and M to contact (MMFEHandMatrices), whose frame
 * (src/contact/frame/, MMContactSetUpFrame) turns them into its own w-frame ones; it keeps its own
 * w-frame load and lift too (fem's stay Cartesian). Q and N are contact's, reached through MMFrame
 * (docs/method.md section 2). M* and its masses are contact's alone, built from M (the other
 * components read them by MMContactGetOperators). fem holds nothing in the w-frame. */
struct _p_MMOperators {
  MPI_Comm  comm;
  DM        dm;     /* the mesh's, referenced (MMFESetDM) */
  DM        dm_scalar; /* one P1 scalar per vertex, no constraints: lumped masses, contact pressure and gap, von Mises */
  MMCells   cells;
  PetscInt  dim;
  Mat       K;      /* stiffness A, Cartesian: NULL once handed to contact (MMFEHandMatrices) */
  Mat       M;      /* standard mass (consistent or lumped), Cartesian: likewise */
  MMFrame   frame;  /* the frame's transforms: contact's, installed by MMFESetFrame (fem holds no Q or N) */
  Vec       load;   /* L: body force + traction, constant in time, Cartesian (contact keeps the w-frame one) */
  Vec       lift;   /* K_fD u_D: the Dirichlet data's elastic force on the free dofs (likewise) */
  Vec       mass_lumped_cart; /* lumped standard mass per Cartesian dof */
  PetscBool      lumped;         /* -mass_lumped */
  MMAssemblyType assembly;       /* -assembly */
  PetscBool      assembly_check; /* -assembly_check: assemble K and M both ways and stop if they differ */
  PetscReal c_p;    /* pressure wave speed */
  PetscReal constants[MM_C_NUM]; /* the PetscDS constants of the kernels (MMConstantIndex) */
  PetscReal energy_dirichlet; /* elastic energy of the Dirichlet data alone, 1/2 u_D.A_DD u_D */
};
