/* The time stepper's state, its per-step history row and the deformation audit (src/ts/). */
#pragma once
#include "mmbase.h"

/* The Newmark state and the per-step energy audit. */
typedef struct {
  Vec       u, v, a;           /* current state, w-frame */
  Vec       u_old, v_old, a_old;
  Vec       react, react_old;  /* contact reactions on the body (K~ w - b on contact dofs) */
  Vec       work;              /* scratch */
  Vec       u_next;            /* the TS solution vector */
  PetscReal dt;
  PetscReal dt_user;           /* -ts_dt: after a rejected step, dt grows back to it */
  PetscReal work_contact;      /* W_c of the accepted step, computed once by the contact-work guard */
} MMState;

/* One row of the history, and its running sums. */
typedef struct {
  PetscInt  step;
  PetscReal time, dt;
  PetscReal kinetic, elastic, total;
  PetscReal work_ext, work_contact, work_friction; /* running sums */
  PetscReal work_obstacle;     /* running sum: the work of the moving obstacles' contact forces */
  PetscReal work_damping;      /* running sum: the Rayleigh damping work W_d <= 0 (src/ts/damping.c) */
  PetscReal work_dirichlet;    /* running sum: the work of the moving Dirichlet boundaries' reactions */
  PetscReal balance_residual;
  PetscInt  active, slipping, switched;
  PetscReal force_normal, force_tangential, max_penetration, coulomb_residual;
  PetscInt  vi_its, friction_its;
  PetscInt  candidates, resolves; /* the step's candidate-set size; VI re-solves after the set grew, over the run */
  PetscReal cfl, contraction;
  PetscReal ucm[MM_MAX_DIM], vcm[MM_MAX_DIM], L[MM_MAX_DIM];
  PetscReal P[MM_MAX_DIM], J[3], load[MM_MAX_DIM]; /* the scheme's momenta and the loads' resultant */
  PetscReal max_balance, max_penetration_run; /* over the run, for the summary */
  PetscReal energy_scale;                     /* the largest |E| of the run so far */
} MMHistory;

/* The deformation audit (src/ts/deformation.c): the largest strain of the run and where it was. */
typedef struct {
  PetscReal     max_strain;                /* over the run: the largest principal strain magnitude */
  PetscReal     where[MM_MAX_DIM];         /* the reference centroid of the cell that had it */
  PetscInt      step;                      /* the step at which it was reached */
  PetscBool     warned;                    /* the -strain_warn warning was printed */
  PetscLogEvent ev;                        /* MMDeformation, in -log_view */
  PetscInt      ncells;                    /* this rank's cells, and for each its dim+1 vertices' */
  PetscInt     *cell_u, *cell_x;           /* offsets in the local displacement and coordinate vectors */
} MMDeformation;

/* The momentum audit's fixed data (src/ts/momenta.c), built on the first diagnostics: each linear
 * momentum functional as one w-frame vector, and the vertices of the angular momentum. */
typedef struct {
  PetscInt  ng, nJ;             /* ng = 2 dim + nJ functionals; nJ: J's components, 3 in 3D, 1 (z) in 2D */
  Vec       g[3 * MM_MAX_DIM];  /* g.x: the sums behind ucm or vcm (dim), P (dim) and J (nJ) for x = u or v */
  Vec       sel[MM_MAX_DIM];    /* Cartesian: 1 at component d of the vertices with no Dirichlet dof */
  PetscInt  nv;                 /* this rank's owned vertices with no Dirichlet dof */
  PetscInt *vert_u, *vert_x;    /* their offsets in the owned part of a global vector and in the local coordinates */
} MMMomenta;

/* Rayleigh damping C = alpha M* + beta B, B = K or its condensed form (src/ts/damping.c, docs/method.md section 3). */
typedef struct {
  PetscReal alpha, beta; /* 1/s and s; both 0: no damping, and nothing below exists */
  Vec       vC;          /* the trapezoidal velocity 2/dt (u^{n+1} - u^n) - vC^n, on all dofs */
  Mat       B;           /* the damping stiffness: K, or with massless dofs K with them condensed out cell by cell */
  Vec       work, x;     /* scratch */
} MMDamping;
