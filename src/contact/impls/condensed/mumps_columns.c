/* Columns of K~^{-1} for unit right-hand sides, solved by PETSc's own MUMPS factor of K~ on several
 * ranks, with the map from MUMPS's distributed solution to PETSc's rows built once per factorization
 * (docs/scaling.md, "What the exponents say", the Delassus columns).
 *
 * Why not MatMatTransposeSolve: PETSc 3.18's MUMPS interface builds a new VecScatter from MUMPS's
 * solution rows to the dense X on every multi-column solve, (local rows) x (columns) indices long,
 * so that the columns gained nothing from a second rank though MUMPS's own solve did (the figures:
 * docs/scaling.md, "The figures behind the code's choices"). MUMPS
 * returns the same rows on each rank after every solve with one factorization (ISOL_loc), so one
 * PetscSF moves every column.
 *
 * The factor stays PETSc's: analysis, factorization, options (-contact_K_mat_mumps_*), the single
 * solves of each step and the error handling are untouched. This file calls MUMPS's solve phase on
 * the factor's own instance with a sparse right-hand side (ICNTL(20) = 1) and a distributed
 * solution (ICNTL(21) = 1) in buffers of its own, and puts every field of the instance back as it
 * found it. The instance is the first member of PETSc's private MUMPS context, as in PETSc 3.18; the
 * layout is checked (version, order, solution length) before any use, and any mismatch falls back
 * to MatMatTransposeSolve. */
#include "condensedimpl.h"
#include <petscsf.h>
#include <petsc/private/matimpl.h> /* Mat->data: PETSc's MUMPS context, whose first member is the MUMPS instance */

#if defined(PETSC_HAVE_MUMPS) && !defined(PETSC_USE_COMPLEX) && defined(PETSC_USE_REAL_DOUBLE) && !defined(PETSC_USE_64BIT_INDICES)
  #include <dmumps_c.h>
  #define MM_MUMPS_DIRECT 1
#endif

PetscErrorCode MMMumpsColumnsDestroy(MMMumpsColumns *mc)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSFDestroy(&mc->sf));
  PetscCall(PetscFree(mc->isol_map));
  PetscCall(PetscFree2(mc->isol, mc->sol));
  mc->lsol = mc->nb_cap = 0;
  mc->F    = NULL;
  PetscFunctionReturn(0);
}

#if defined(MM_MUMPS_DIRECT)
  #define ICNTL(I) icntl[(I)-1]
  #define INFOG(I) infog[(I)-1]
  #define INFO(I)  info[(I)-1]

/* The MUMPS instance inside F, if F is PETSc's MUMPS Cholesky or LU factor of the layout this file
 * was built for, on several ranks with a distributed solution; NULL otherwise. Collective: every
 * rank gets the same answer. */
static PetscErrorCode GetInstance(Mat F, DMUMPS_STRUC_C **idp)
{
  MatSolverType   type;
  PetscBool       mumps, ok;
  PetscMPIInt     size;
  PetscInt        M;
  DMUMPS_STRUC_C *id;

  PetscFunctionBeginUser;
  *idp = NULL;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)F), &size));
  PetscCall(MatFactorGetSolverType(F, &type));
  PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (size == 1 || !mumps) PetscFunctionReturn(0); /* one rank: MatMatTransposeSolve writes into X directly */
  PetscCall(MatGetSize(F, &M, NULL));
  id = (DMUMPS_STRUC_C *)F->data;
  ok = (PetscBool)(!strncmp(id->version_number, MUMPS_VERSION, sizeof(MUMPS_VERSION)) && id->n == M && id->par == 1 && id->ICNTL(21) == 1 && id->INFOG(1) >= 0 &&
                   id->lsol_loc == id->INFO(23) && id->lsol_loc >= 0 && id->lsol_loc <= M);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)F)));
  if (ok) *idp = id;
  else PetscCall(PetscInfo(F, "The MUMPS instance does not have the layout of MUMPS %s: the candidate columns go through MatMatTransposeSolve\n", MUMPS_VERSION));
  PetscFunctionReturn(0);
}

/* The SF from MUMPS's solution rows here (leaves, in ISOL_loc order) to PETSc's owned rows of F
 * (roots); rebuilt only when ISOL_loc changed (a new factorization). Every row must be solved on
 * exactly one rank, or a column would be left with stale values. */
static PetscErrorCode UpdateSolutionMap(MMMumpsColumns *mc, Mat F)
{
  MPI_Comm        comm = PetscObjectComm((PetscObject)F);
  PetscBool       same;
  PetscLayout     rmap;
  PetscInt       *gidx, n, rstart;
  const PetscInt *degree;

  PetscFunctionBeginUser;
  same = (PetscBool)(mc->sf && mc->F == F);
  for (PetscInt i = 0; same && i < mc->lsol; ++i) same = (PetscBool)(mc->isol[i] == mc->isol_map[i]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, comm));
  if (same) PetscFunctionReturn(0);
  PetscCall(PetscSFDestroy(&mc->sf));
  PetscCall(PetscFree(mc->isol_map));
  PetscCall(PetscMalloc1(mc->lsol, &mc->isol_map));
  PetscCall(PetscMalloc1(mc->lsol, &gidx));
  for (PetscInt i = 0; i < mc->lsol; ++i) {
    mc->isol_map[i] = mc->isol[i];
    gidx[i]         = (PetscInt)mc->isol[i] - 1; /* MUMPS numbers rows from 1 */
  }
  PetscCall(MatGetLayouts(F, &rmap, NULL));
  PetscCall(PetscSFCreate(comm, &mc->sf));
  PetscCall(PetscSFSetGraphLayout(mc->sf, rmap, mc->lsol, NULL, PETSC_OWN_POINTER, gidx));
  PetscCall(PetscFree(gidx));
  PetscCall(PetscSFSetUp(mc->sf));
  PetscCall(PetscSFComputeDegreeBegin(mc->sf, &degree));
  PetscCall(PetscSFComputeDegreeEnd(mc->sf, &degree));
  PetscCall(PetscLayoutGetLocalSize(rmap, &n));
  PetscCall(PetscLayoutGetRange(rmap, &rstart, NULL));
  for (PetscInt r = 0; r < n; ++r)
    PetscCheck(degree[r] == 1, PETSC_COMM_SELF, PETSC_ERR_LIB, "MUMPS's distributed solution holds row %" PetscInt_FMT " %" PetscInt_FMT " times, not once", rstart + r, degree[r]);
  mc->F = F;
  PetscFunctionReturn(0);
}

/* MUMPS's solve phase for the unit right-hand sides e_rows[j], j < nb (centralized on the host,
 * rank 0, as MUMPS requires of a sparse right-hand side), into mc->sol; the instance is restored. */
static PetscErrorCode SolveUnitColumns(MMMumpsColumns *mc, DMUMPS_STRUC_C *id, MPI_Comm comm, PetscInt nb, const PetscInt rows[])
{
  const DMUMPS_STRUC_C saved = *id;
  PetscMPIInt          rank;
  MUMPS_INT           *ptr = NULL, *irn = NULL, info1, info2;
  double              *val = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (nb > mc->nb_cap || saved.lsol_loc != mc->lsol) {
    PetscCall(PetscFree2(mc->isol, mc->sol));
    mc->lsol   = saved.lsol_loc;
    mc->nb_cap = nb;
    PetscCall(PetscMalloc2(PetscMax(mc->lsol, 1), &mc->isol, PetscMax(mc->lsol * nb, 1), &mc->sol));
  }
  if (!rank) {
    PetscCall(PetscMalloc3(nb + 1, &ptr, nb, &irn, nb, &val));
    for (PetscInt j = 0; j < nb; ++j) {
      ptr[j] = (MUMPS_INT)j + 1;
      irn[j] = (MUMPS_INT)rows[j] + 1;
      val[j] = 1.0;
    }
    ptr[nb] = (MUMPS_INT)nb + 1;
  }
  id->job         = 3;
  id->nrhs        = (MUMPS_INT)nb;
  id->lrhs        = id->n;
  id->rhs         = NULL;
  id->ICNTL(20)   = 1; /* sparse right-hand side: the forward elimination is pruned */
  id->ICNTL(21)   = 1; /* distributed solution, in our buffers */
  id->nz_rhs      = rank ? 0 : (MUMPS_INT)nb;
  id->irhs_ptr    = ptr;
  id->irhs_sparse = irn;
  id->rhs_sparse  = val;
  id->sol_loc     = mc->sol;
  id->isol_loc    = mc->isol;
  id->lsol_loc    = (MUMPS_INT)mc->lsol;
  PetscCall(PetscLogEventBegin(MMCONTACT_ColumnsSolve, 0, 0, 0, 0));
  dmumps_c(id);
  PetscCall(PetscLogEventEnd(MMCONTACT_ColumnsSolve, 0, 0, 0, 0));
  info1 = id->INFOG(1);
  info2 = id->INFO(2);
  *id   = saved;
  PetscCall(PetscFree3(ptr, irn, val));
  PetscCheck(info1 >= 0, comm, PETSC_ERR_LIB, "MUMPS failed in the solve of the contact candidates' columns of K~^{-1}: INFOG(1) = %d, INFO(2) = %d (see the MUMPS users' guide)", (int)info1, (int)info2);
  PetscFunctionReturn(0);
}
#endif

PetscErrorCode MMMumpsColumnsSolve(MMMumpsColumns *mc, Mat F, PetscInt nb, const PetscInt rows[], PetscScalar X[], PetscInt ldx, PetscBool *done)
{
  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
#if defined(MM_MUMPS_DIRECT)
  {
    DMUMPS_STRUC_C *id;
    PetscInt        n;

    PetscCall(GetInstance(F, &id));
    if (!id) PetscFunctionReturn(0);
    PetscCall(MatGetLocalSize(F, &n, NULL));
    PetscCheck(ldx >= n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Leading dimension %" PetscInt_FMT " below the %" PetscInt_FMT " owned rows", ldx, n);
    PetscCall(SolveUnitColumns(mc, id, PetscObjectComm((PetscObject)F), nb, rows));
    PetscCall(PetscLogEventBegin(MMCONTACT_ColumnsMove, 0, 0, 0, 0));
    PetscCall(UpdateSolutionMap(mc, F));
    for (PetscInt j = 0; j < nb; ++j) {
      PetscCall(PetscSFReduceBegin(mc->sf, MPIU_SCALAR, mc->sol + (size_t)j * mc->lsol, X + (size_t)j * ldx, MPI_REPLACE));
      PetscCall(PetscSFReduceEnd(mc->sf, MPIU_SCALAR, mc->sol + (size_t)j * mc->lsol, X + (size_t)j * ldx, MPI_REPLACE));
    }
    PetscCall(PetscLogEventEnd(MMCONTACT_ColumnsMove, 0, 0, 0, 0));
    *done = PETSC_TRUE;
  }
#endif
  PetscFunctionReturn(0);
}
