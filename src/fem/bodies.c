/* The bodies of -bodies (README "Bodies"), each a physical group of cells with its own
 * material and initial velocity, read from their options and checked, and the limits of a nearly
 * incompressible material. */
#include "fem.h"
#include "sys.h"

/*@
  MMBodiesSetFromOptions - Reads the bodies of -bodies, each in its own options block, each value
  defaulting to the whole mesh's

  Collective

  Input Parameters:
+ comm  - the run's communicator
- whole - the whole mesh's material and initial velocity, the bodies' defaults

  Output Parameters:
+ nbodies - the number of bodies, 0 without -bodies
- bodies  - the bodies (freed by MMBodiesDestroy())

  Note:
  -bodies NAME,...: each body a physical group of cells with its own material and initial velocity,
  each defaulting to the whole mesh's (whole: -E, -nu, -rho, -elasticity, -v0, -omega0), in its own
  options block. The cells and the groups are checked against the mesh in src/fem/material.c.

  Level: intermediate

.seealso: `MMBodiesCheck()`, `MMBodiesCheckDimension()`, `MMBodiesDestroy()`
@*/
PetscErrorCode MMBodiesSetFromOptions(MPI_Comm comm, const MMBodyOptions *whole, PetscInt *nbodies, MMBodyOptions **bodies)
{
  char     list[PETSC_MAX_PATH_LEN] = "", **names;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "mmcontact: bodies", "MMBodies");
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-bodies", "Comma-separated names of the bodies, each a physical group of cells (-body_NAME_group) with its own -body_NAME_E, _nu, _rho and _v0; every cell must be in exactly one body (default: one body, the whole mesh, of -E, -nu, -rho and -v0)", list, sizeof(list), NULL));
  PetscCall(MMOptionsSplitNames(comm, "-bodies", list, &n, &names));
  *nbodies = n;
  PetscCall(PetscCalloc1(n, bodies));
  for (PetscInt b = 0; b < n; ++b) {
    MMBodyOptions *body = &(*bodies)[b];
    char           key[512];

    PetscCall(PetscStrallocpy(names[b], &body->name));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_group", body->name));
    PetscCall(MMOptionsString(PetscOptionsObject, comm, key, "Physical group of this body's cells: a Physical Surface (2D) or Physical Volume (3D) of the mesh; required", body->group, sizeof(body->group), &body->group_set));
    body->E   = whole->E;
    body->nu  = whole->nu;
    body->rho = whole->rho;
    body->elasticity = whole->elasticity;
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_elasticity", body->name));
    PetscCall(MMOptionsEnum(PetscOptionsObject, comm, key, "This body's elasticity law: linear, svk or neohookean (default -elasticity)", MMElasticityTypes, (PetscEnum *)&body->elasticity));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_E", body->name));
    PetscCall(MMOptionsReal(PetscOptionsObject, comm, key, "This body's Young's modulus (Pa), > 0 (default -E)", &body->E));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_nu", body->name));
    PetscCall(MMOptionsReal(PetscOptionsObject, comm, key, "This body's Poisson ratio, in (-1, 0.5), at most 0.4995 with a finite-strain law and 0.49999995 with linear (default -nu)", &body->nu));
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_rho", body->name));
    PetscCall(MMOptionsReal(PetscOptionsObject, comm, key, "This body's mass density (kg/m^d), > 0 (default -rho)", &body->rho));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->v0[d] = whole->v0[d];
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_v0", body->name));
    PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, key, "This body's initial translation velocity, d entries (default -v0); -omega adds the same rigid rotation to every body", MM_MAX_DIM, body->v0, &body->nv0));
    for (PetscInt d = 0; d < MM_MAX_DIM; ++d) body->omega0[d] = whole->omega0[d];
    PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_omega0", body->name));
    PetscCall(MMOptionsRealArray(PetscOptionsObject, comm, key, "This body's initial rigid angular velocity (rad/s) about its own centre of mass, added to its _v0: a scalar in 2D, a vector in 3D (default -omega0)", MM_MAX_DIM, body->omega0, &body->nomega0));
    body->omega0_set = (PetscBool)(body->nomega0 >= 0 || whole->omega0_set);
  }
  PetscOptionsEnd();
  PetscCall(PetscStrToArrayDestroy((int)n, names));
  PetscFunctionReturn(0);
}

/* A nearly incompressible material (docs/reference.md, "Large rotations and finite strain", "Nearly
 * incompressible materials"): P1 elements lock volumetrically,
 * and K~ holds a volumetric stiffness lambda above the shear one mu, lambda/mu = 2 nu / (1 - 2 nu).
 * The linear law's energy balance then sums terms lambda/mu times larger than the energy it checks:
 * on the D1 disk its residual is 60 to 120 eps lambda/mu from lambda/mu = 5e4 to 5e7, and the audit
 * (-audit_tol 1e-6) stops the run at 5e8; nu <= 0.49999995 (lambda/mu <= 1e7) keeps the residual at
 * 2.6e-7 at most. The finite-strain laws fail earlier, not by round-off: under the pressures of an
 * impact (of order lambda times the locked volume change) the neo-Hookean tangent loses its
 * definiteness and K~'s Cholesky factor stops ("Diagonal must be real and nonnegative", D1 at
 * lambda/mu = 2.5e3), and the svk step's Newton iteration diverges (D1 at 1e4); both hold their
 * audits at lambda/mu = 999, nu = 0.4995 (tests/test_limits_and_advice.py). A harder impact can still
 * turn the tangent indefinite there: the run then stops naming -ts_dt (src/contact/interface/pc_schursplit.c). */
#define MM_NU_MAX_LINEAR 0.49999995
#define MM_NU_MAX_FINITE 0.4995

/*@
  MMMaterialCheckNearlyIncompressible - Refuses a Poisson ratio too close to 0.5 for the elasticity
  law, naming its option

  Collective

  Input Parameters:
+ comm   - the run's communicator
. option - the option that gave nu
. nu     - the Poisson ratio
- law    - the elasticity law

  Level: intermediate

.seealso: `MMBodiesCheck()`
@*/
PetscErrorCode MMMaterialCheckNearlyIncompressible(MPI_Comm comm, const char option[], PetscReal nu, MMElasticityType law)
{
  const PetscBool finite = (PetscBool)(law != MM_ELASTICITY_LINEAR);
  const PetscReal numax  = finite ? MM_NU_MAX_FINITE : MM_NU_MAX_LINEAR;

  PetscFunctionBeginUser;
  PetscCheck(nu <= numax, comm, PETSC_ERR_USER_INPUT, "Poisson ratio %s %.10g is too close to 0.5 for -elasticity %s: lambda/mu = 2 nu/(1 - 2 nu) = %.3g, P1 elements lock volumetrically and K~'s conditioning grows as lambda/mu, %s. The largest accepted value with -elasticity %s is %.10g (lambda/mu %.3g; docs/reference.md, \"Large rotations and finite strain\")", option, (double)nu, MMElasticityTypes[law], (double)(2 * nu / (1 - 2 * nu)),
             finite ? "and under contact pressures the finite-strain step's tangent turns indefinite or its Newton iteration diverges" : "and the energy audit's round-off (about 100 eps lambda/mu) reaches -audit_tol", MMElasticityTypes[law], (double)numax, (double)(2 * numax / (1 - 2 * numax)));
  PetscFunctionReturn(0);
}

/*@
  MMBodiesCheck - Checks each body's material and group, refusing a wrong one with the body's option
  named

  Collective

  Input Parameters:
+ comm   - the run's communicator
. n      - the number of bodies
- bodies - the bodies

  Note:
  Each body's material in its range, refused naming the body's option.

  Level: intermediate

.seealso: `MMBodiesSetFromOptions()`, `MMBodiesCheckDimension()`
@*/
PetscErrorCode MMBodiesCheck(MPI_Comm comm, PetscInt n, const MMBodyOptions bodies[])
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < n; ++b) {
    const MMBodyOptions *body = &bodies[b];
    PetscCheck(body->group_set && body->group[0], comm, PETSC_ERR_USER_INPUT, "-bodies: body %s has no cells: give -body_%s_group GROUP, the physical group (a Physical %s) of its cells", body->name, body->name, "Surface in 2D, Volume in 3D");
    PetscCheck(body->E > 0, comm, PETSC_ERR_USER_INPUT, "Young's modulus -body_%s_E %g must be > 0", body->name, (double)body->E);
    PetscCheck(body->nu > -1.0, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -body_%s_nu %.6g must lie in (-1, 0.5): nu <= -1 makes the shear modulus E / (2 (1 + nu)) infinite or negative, an unstable material", body->name, (double)body->nu);
    PetscCheck(body->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "Poisson ratio -body_%s_nu %.6g must lie in (-1, 0.5): nu >= 0.5 is incompressible, which P1 elements cannot represent", body->name, (double)body->nu);
    PetscCheck(body->rho > 0, comm, PETSC_ERR_USER_INPUT, "Density -body_%s_rho %g must be > 0", body->name, (double)body->rho);
    {
      char key[512];

      PetscCall(PetscSNPrintf(key, sizeof(key), "-body_%s_nu", body->name));
      PetscCall(MMMaterialCheckNearlyIncompressible(comm, key, body->nu, body->elasticity));
    }
  }
  PetscFunctionReturn(0);
}

/*@
  MMBodiesCheckDimension - Checks that each body's _v0 and _omega0 have the entries of the mesh's
  dimension

  Collective

  Input Parameters:
+ comm   - the run's communicator
. n      - the number of bodies
. bodies - the bodies
- dim    - the mesh's dimension

  Note:
  Each body's _v0 and _omega0 has the entries of the dimension.

  Level: intermediate

.seealso: `MMBodiesCheck()`
@*/
PetscErrorCode MMBodiesCheckDimension(MPI_Comm comm, PetscInt n, const MMBodyOptions bodies[], PetscInt dim)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < n; ++b) {
    const MMBodyOptions *body = &bodies[b];
    PetscCheck(body->nv0 < 0 || body->nv0 == dim, comm, PETSC_ERR_USER_INPUT, "-body_%s_v0 has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %" PetscInt_FMT, body->name, body->nv0, dim, dim);
    PetscCheck(body->nomega0 < 0 || body->nomega0 == (dim == 2 ? 1 : 3), comm, PETSC_ERR_USER_INPUT, "-body_%s_omega0 has %" PetscInt_FMT " entries; the mesh is %" PetscInt_FMT "D, so it needs exactly %d (an angular velocity is a scalar in 2D, a vector in 3D)", body->name, body->nomega0, dim, dim == 2 ? 1 : 3);
  }
  PetscFunctionReturn(0);
}

/*@
  MMBodiesDestroy - Frees the bodies read by MMBodiesSetFromOptions()

  Not collective

  Input Parameters:
+ n      - the number of bodies, 0 on return
- bodies - the bodies, freed

  Level: intermediate

.seealso: `MMBodiesSetFromOptions()`
@*/
PetscErrorCode MMBodiesDestroy(PetscInt *n, MMBodyOptions **bodies)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < *n; ++b) PetscCall(PetscFree((*bodies)[b].name));
  PetscCall(PetscFree(*bodies));
  *n = 0;
  PetscFunctionReturn(0);
}
