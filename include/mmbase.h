/* What every component's types need: PETSc, and the sizes the types share.
 *
 * Frames. Global vectors hold the free (non-Dirichlet) dofs. At every contact node the d dofs are
 * expressed in the obstacle frame (nu, tau_1[, tau_2]), nu the body's outward normal (pointing into
 * the obstacle): component 0 is the normal displacement u.nu, so u.nu <= g is a bound on one
 * unknown. All other nodes keep Cartesian dofs. Q maps frame dofs to Cartesian: u_cart = Q w.
 */
#pragma once
#include <petscdmplex.h>
#include <petscds.h>
#include <petscfe.h>
#include <petscsnes.h>
#include <petscts.h>

#define MM_MAX_DIM 3
#define MM_TYPE_LEN 64 /* the name of a registered type (a contact formulation, a friction solver) */
