/* Private to the condensed formulation (src/contact/impls/condensed/): the candidate set, its cached
 * columns of K~^{-1} E, the condensed VI's vectors. */
#pragma once
#include "../../contactimpl.h"

/* The cached columns of K~^{-1} E of one factor of K~, which a kept factor keeps with it. */
typedef struct {
  PetscScalar *cols, *full;  /* on the owned condensed dofs; on all owned dofs (MMCandidates) */
  PetscInt    *slot_node;    /* per cached block: its contact node */
  PetscInt     n_cached, cap;
  PetscBool    full_ok;
} MMColumnCache;

/* The map from the solution rows of a MUMPS factor of K~ on several ranks to PETSc's rows, for the
 * candidate columns (src/contact/impls/condensed/mumps_columns.c): MUMPS keeps the same rows on each
 * rank for every solve with one factorization, so the map is built once per factorization. */
typedef struct {
  Mat          F;               /* the factor whose solution rows sf maps */
  PetscSF      sf;              /* MUMPS's solution rows here (leaves) -> PETSc's owned rows (roots) */
  int         *isol, *isol_map; /* MUMPS_INT, from 1: the rows of the last solve here; those sf maps */
  PetscScalar *sol;             /* the last solve's block on those rows, lsol x nb_cap */
  PetscInt     lsol, nb_cap;
} MMMumpsColumns;

/* The candidate set of the condensed formulation (docs/method.md section 3, "Candidate set"): the
 * contact nodes that can touch in the step, with the columns of K~^{-1} E computed when a node
 * first enters the set and kept, under a memory cap, until K~ is refactored. The step's VI on the
 * set is small and dense: it is replicated on every rank and solved with LAPACK. */
typedef struct {
  PetscInt     node_start;          /* global number of the first contact node owned here */
  PetscMPIInt *node_counts, *node_displs; /* contact nodes per rank, for the set's gathers */
  PetscInt    *normal_dof;          /* per contact node (all ranks): global index of its normal dof */
  PetscInt    *slot;                /* per contact node (all ranks): its column block in the cache, or -1 */
  PetscInt    *slot_node;           /* per cached block: its contact node */
  PetscInt     n_cached, cap;       /* cached nodes; blocks allocated */
  PetscScalar *cols;                /* cached columns of K~^{-1} E on the owned condensed rows (lda nc_local) */
  PetscInt     nc_local;            /* owned condensed dofs: ncomp n_local */
  PetscInt    *cond_row;            /* per owned condensed dof, its local row in the full vectors */
  PetscScalar *full;                /* the same columns on all owned dofs (lda n_local), while they fit */
  PetscInt     n_local, N;          /* owned and global dofs */
  PetscBool    full_ok;             /* full columns kept: the step is recovered from them, without a solve */
  PetscBool   *in_set;              /* per contact node (all ranks): in the step's set */
  PetscInt     n_set, *set;         /* the step's set: contact nodes in increasing order, on every rank */
  PetscInt     m;                   /* its condensed dofs: ncomp n_set */
  Mat          W;                   /* the set's Delassus block (seqdense, symmetrized) */
  Vec          x, lo, hi, q, f;     /* the set's reactions, bounds, right-hand side, residual */
  VecScatter   gather;              /* global condensed vectors -> the set */
  SNES         snes;                /* the VI on the set, prefix contact_ */
  MMBoundQP    qp;
  PetscReal    margin;              /* -contact_candidate_margin */
  PetscBool    all;                 /* -contact_candidate_all */
  PetscReal    memory_cap;          /* -contact_candidate_memory, bytes over all ranks */
  PetscReal    memory_mib;          /* the same in MiB, as given */
  PetscScalar *wc;                  /* the step's solution on the owned condensed dofs, from the set's reactions */
  PetscInt     resolves;            /* VI re-solves after the set grew, over the run */
  PetscInt     columns;             /* columns computed in the run */
  PetscInt     evicted;             /* cached nodes dropped under the memory cap, over the run */
  PetscInt     recover_solves;      /* steps recovered by a solve, the full columns being over the cap */
  PetscInt     max_set;             /* the largest set of the run */
  MMMumpsColumns mumps;             /* the columns' solves on a MUMPS factor on several ranks */
} MMCandidates;

/* The condensed formulation's state (MMContact's data). */
typedef struct {
  KSP              ksp_K;       /* K~ factored once per dt, prefix contact_K_ */
  MMCandidates     cand;
  MMColumnCache    kept_cache;  /* the kept K~'s cached columns (-contact_K_keep) */
  Vec              q;           /* the condensed right-hand side on all contact nodes: z_c - offset */
  Vec              offset, rhs_c; /* q = z_c - offset; E rho */
  Vec              z_b;         /* the right-hand side z was solved for (not owned), its state and dt */
  PetscObjectState z_b_state;
  PetscReal        z_dt;
  Vec              mu_c;        /* mu of each contact node in each of its condensed dofs (layout of rho) */
  Vec              Wdiag;       /* diag(W) on the cached nodes, the nodal compliances (1 elsewhere) */
} MMContact_Condensed;

static inline MMContact_Condensed *MMCondensedData(MMContact ct)
{
  return (MMContact_Condensed *)ct->data;
}

/* impls/condensed/condensed.c: the Delassus operator and the condensed VI */
PETSC_EXTERN PetscErrorCode MMCondensedFactor(MMContact ct);
PETSC_EXTERN PetscErrorCode MMCondensedCreateSolver(MMContact ct);
PETSC_EXTERN PetscErrorCode MMCondensedSolveReactions(MMContact ct, Vec b);
PETSC_EXTERN PetscErrorCode MMCondensedContactDofs(MMContact ct, Vec w, Vec react);
PETSC_EXTERN PetscErrorCode MMCondensedRecover(MMContact ct, Vec w);
PETSC_EXTERN PetscErrorCode MMCondensedSolveCoulomb(MMContact ct, Vec b, Vec w, Vec react, MMContactSetSolver fn, void *fctx, PetscBool *ok);

/* impls/condensed/candidates.c: the candidate set, its cached columns of K~^{-1} E and its dense block */
PETSC_EXTERN PetscErrorCode MMCandidatesSetUp(MMContact ct);
PETSC_EXTERN PetscErrorCode MMCandidatesInvalidate(MMContact ct);
PETSC_EXTERN PetscErrorCode MMCandidatesSwapCache(MMContact ct, MMColumnCache *other);
PETSC_EXTERN PetscErrorCode MMCandidatesSelect(MMContact ct);
PETSC_EXTERN PetscErrorCode MMCandidatesGrow(MMContact ct, const PetscScalar wc[], PetscBool *grown);
PETSC_EXTERN PetscErrorCode MMCandidatesMult(MMContact ct, Vec x, PetscScalar y[]);
PETSC_EXTERN PetscErrorCode MMCandidatesRecover(MMContact ct, Vec w);
PETSC_EXTERN PetscErrorCode MMCandidatesDestroy(MMCandidates *c);
/* impls/condensed/mumps_columns.c: columns of K~^{-1} for unit right-hand sides on a MUMPS factor on
 * several ranks (done false: not such a factor, use MatMatTransposeSolve) */
PETSC_INTERN PetscErrorCode MMMumpsColumnsSolve(MMMumpsColumns *mc, Mat F, PetscInt nb, const PetscInt rows[], PetscScalar X[], PetscInt ldx, PetscBool *done);
PETSC_INTERN PetscErrorCode MMMumpsColumnsDestroy(MMMumpsColumns *mc);
