/* io: the run's output (history.csv, solution.h5 and its XDMF index), checkpoints and restart, and the
 * progress lines (src/io/): their objects, and the functions the rest of the run calls. */
#pragma once
#include "mmbase.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"
#include "ts.h"

/* The problem as io reads it, filled by app (MMOptionsGetIOProblem): the names the history's columns and
 * the start-up report quote, and the fingerprint a checkpoint keeps (mesh, contact boundary, mu,
 * material). Borrowed: the strings and arrays are app's options. */
typedef struct {
  const char       *mesh_file, *contact_name;
  PetscReal         E, nu, rho, mu, mu_max;
  PetscInt          n_obstacles, n_rigid; /* the rigid obstacles, then the contact pairs */
  const MMObstacle *obstacles;
  PetscBool         obstacles_named; /* -obstacles was given (else the rigid obstacle is the plane of -obstacle_point, -obstacle_normal) */
  PetscInt          n_dirichlet;
  const MMDirichlet *dirichlet;
} MMIOProblem;

/* The progress line (src/io/progress.c): what it keeps between two lines. The references are taken at the
 * first monitor call, the start of TSSolve, so that the rates are those of this run's time loop. */
typedef struct {
  /* borrowed at MMProgressSetUp: what the start-up report and the progress lines describe */
  const MMIOProblem   *opt;
  MMOperators        op;
  const MMMaterial  *material;
  const MMHistory   *hist;
  const MMState     *state;
  MMContact          contact;
  const MMDamping   *damping;
  PetscBool      started;
  PetscLogDouble wall_start, wall_last; /* wall time at the start of the time loop and at the last line */
  PetscReal      t_start;               /* simulated time at the start of the time loop */
  PetscInt       step_start, step_last; /* the step then, and the last step counted */
  PetscInt       friction_its, steps;   /* friction iterations and steps since the last line */
  PetscReal      every;                 /* -progress_every: seconds of wall time between lines, 0: none */
} MMProgress;

/* -probes (src/io/probes.c): each group's owned vertices with their lumped masses, and the group's mass. */
typedef struct {
  PetscInt   n;                /* groups */
  char     (*name)[256];
  PetscInt  *start;            /* group g's vertices are vertex[start[g] .. start[g + 1]) */
  PetscInt  *vertex;           /* this rank's owned vertices of the groups (mesh points) */
  PetscReal *weight;           /* their lumped standard masses */
  PetscReal *mass;             /* per group, over all ranks */
  PetscReal *mean;             /* per group, 2 dim values: the mean u, then the mean v, of the current row */
} MMProbes;

typedef struct _MMOutput MMOutput;

/* Checkpoints (src/io/checkpoint.c, docs/method.md section 9): the state keyed by the serial mesh's vertex
 * numbers, so that a run can continue on any number of ranks. */
typedef struct {
  /* borrowed at MMCheckpointSetUp: what a checkpoint holds, and what a restart restores */
  const MMIOProblem   *opt;      /* the problem: its fingerprint (mesh, contact boundary, mu, material, mass) */
  MMOperators        op;       /* fem's operators: the mesh and its dimension, fetched at set-up into dm and dim */
  DM                 dm;       /* fem's (MMFEGetDM) */
  PetscInt           dim;      /* the mesh's (MMFEGetDimension) */
  const MMMaterial  *material; /* the bodies */
  MMHistory         *hist;     /* the running sums and maxima */
  MMState           *state;    /* u, v, a and the reactions, dt */
  MMDamping         *damping;  /* alpha, beta and vC */
  MMContact          contact;  /* the contact nodes' states: the solvers' warm starts */
  MMFriction         friction; /* its thresholds */
  MMOutput          *out;      /* the snapshots: their count and times, their copy */
  PetscReal          dt_next;  /* -restart: the dt the run continues with */
  PetscInt *vertex_orig; /* per local vertex (from vStart), its number in the serial mesh */
  PetscInt *vertex_file; /* per serial-mesh vertex, its position among the mesh file's nodes (mesh_file.c) */
  PetscInt  nv_global;   /* vertices of the whole mesh */
  PetscInt  every;       /* -checkpoint_every: steps between checkpoints, 0 only at the end */
  char      restart[PETSC_MAX_PATH_LEN]; /* -restart: the checkpoint, or its directory, to continue; empty: none */
  PetscInt  written;     /* checkpoints written by this run */
  PetscInt  last_step;   /* step of the last one written */
  /* -restart */
  PetscBool    restarted;
  PetscInt     restart_step;                   /* the step the run continues from */
  char         file[PETSC_MAX_PATH_LEN];       /* the checkpoint read */
  char         source_dir[PETSC_MAX_PATH_LEN]; /* its directory: the history and snapshots to continue */
  PetscReal    run[40];                        /* its run record */
  PetscScalar *node;                           /* its per-node records of the owned contact nodes */
  PetscScalar *frames;                         /* frames that follow: the owned contact nodes' frame records (NULL: none) */
  PetscReal    frames_run[4];                  /* and the run's W_frame and the frames' counters */
  PetscBool    mass_free_read;                 /* the mass in free flight's record was read */
  PetscReal    mass_free_work;                 /* and its W_frame so far */
  PetscScalar *pairs;                          /* large sliding: the owned contact nodes' pairing records (NULL: none) */
  PetscReal    pairs_run[3];                   /* and the run's counters of new pairings */
  Vec          tangent;                        /* finite strain: the point of the iteration matrix (NULL: K) */
  PetscReal    tangent_time;                   /* and its time */
  PetscReal   *snapshot_times;                 /* the times of its snapshots, until the output takes them */
} MMCheckpoint;

/* Output files. Rank 0 alone writes history.csv and solution.xmf; solution.h5 is written by all. */
struct _MMOutput {
  /* borrowed at MMOutputSetUp: what the output writes from */
  const MMIOProblem    *opt;     /* the problem: the obstacles' and Dirichlet boundaries' names, the history's columns */
  MMOperators         op;       /* fem's operators: the mesh's cells, the frames */
  DM                  dm;       /* fem's mesh (MMFEGetDM), borrowed at set-up */
  PetscInt            dim;      /* its dimension (MMFEGetDimension) */
  const MMMaterial   *material; /* each cell's material: the stress */
  const MMHistory    *hist;     /* the stepper's history row */
  const MMState      *state;    /* the stepper's u and v */
  MMContact           contact; /* each obstacle's force, in the history */
  MMLoads            *loads;   /* each Dirichlet boundary's reaction, in the history; the Dirichlet data of the whole fields */
  MMCheckpoint       *ckpt;    /* the restart the run continues (its snapshots taken over), the serial vertex numbers */
  char          dir[PETSC_MAX_PATH_LEN]; /* -output_dir */
  PetscInt      every;                 /* -output_every: snapshots every so many steps, 0: the first and last */
  PetscReal     interval;              /* -output_interval: snapshots at t = k T instead, 0: by steps */
  PetscInt      history_every;         /* -history_every: a history row every N steps and the last */
  char          probe_list[PETSC_MAX_PATH_LEN]; /* -probes: groups whose mean u and v go to the history, empty: none */
  int           csv_fd;                /* history.csv, on rank 0 (-1 elsewhere and once closed) */
  char          csv_name[PETSC_MAX_PATH_LEN], h5_name[PETSC_MAX_PATH_LEN], xmf_name[PETSC_MAX_PATH_LEN];
  PetscViewer   h5;                    /* solution.h5, open from MMOutputOpen to MMOutputClose */
  PetscInt      n_written;             /* snapshots on disk and flushed */
  PetscInt      n_indexed;             /* the ones the XDMF index on disk lists */
  PetscReal    *times;                 /* time of each snapshot */
  PetscInt      nv, nc;                /* global vertex and cell counts, for the XDMF index */
  char         *index;                 /* rank 0: the index's grids, written out at every snapshot */
  size_t        index_len, index_cap;
  DM            dm_out;                /* the displacement field without constraints: output of whole fields */
  MMInsertMap   to_out;                /* DMLocalToGlobal(INSERT) on dm_out, as a map */
  Vec           disp_cart, vel_cart;   /* Cartesian output fields on dm_out */
  DM            dm_scalar;             /* borrowed from fem (MMFEGetScalarDM) by MMOutputSetUp: one scalar per vertex */
  Vec           pressure, gap;
  Vec           obstacle;              /* each contact node's obstacle (index in -obstacles), -1 elsewhere: written once */
  Vec           serial;                /* each vertex's number in the serial mesh: written once */
  PetscBool     static_written;        /* obstacle and serial are in solution.h5 */
  Vec           traction_t, slip;      /* tangential traction and slip velocity on the contact boundary (dm_out) */
  MMStress      stress;                /* nodal and cell stress and von Mises (fem: src/fem/stress.c) */
  MMProbes      probes;                /* -probes: groups' mean displacement and velocity in the history */
  PetscBool     planned;               /* the planned output's size has been checked (output_schedule.c) */
  PetscReal     mesh_bytes, snapshot_bytes; /* the plan's bytes of solution.h5's mesh and of a snapshot: the room each write needs */
};

/* iopackage.c: io's log stage and events, registered once */
PETSC_EXTERN PetscErrorCode MMIOInitializePackage(void);

/* output.c: the files of a run, from set-up to close */
PETSC_EXTERN PetscErrorCode MMOutputSetFromOptions(MPI_Comm comm, MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputSetUp(MMOutput *o, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, const MMHistory *hist, const MMState *state, MMContact contact, MMLoads *loads, MMCheckpoint *ckpt);
/* output_monitor.c: the glue that gathers each snapshot's fields from the components below */
PETSC_EXTERN PetscErrorCode MMOutputOpen(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputSetUpProbes(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
PETSC_EXTERN PetscErrorCode MMOutputWriteFinal(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputClose(MMOutput *o, const MMCheckpoint *c, PetscInt step);
PETSC_EXTERN PetscErrorCode MMOutputView(const MMOutput *o, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMOutputDestroy(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputCheckHDF5Path(MPI_Comm comm, const char option[], const char path[], const char longest[]);
PETSC_EXTERN PetscErrorCode MMOutputSyncIndex(MMOutput *o);
PETSC_EXTERN PetscErrorCode MMOutputCopySnapshots(MMOutput *o);
/* output_lock.c: one run per output directory */
PETSC_EXTERN PetscErrorCode MMOutputLock(const char dir[]);
PETSC_EXTERN PetscErrorCode MMOutputUnlock(void);
/* What a run will write (src/io/output_plan.c, for -check_input and the large-output warning): its
 * steps from step0 at t0, each dt, to t_last (by_steps: -ts_max_steps ends it before -ts_max_time);
 * its snapshots, the bytes of each (with its views) and of the mesh, and solution.h5's and
 * solution.xmf's bytes; its history rows, the most bytes a row takes, the header's, and at most
 * history.csv's bytes. */
typedef struct {
  PetscReal step0, steps, t0, dt, t_last;
  PetscBool by_steps;
  PetscReal snapshots, snapshot_bytes, mesh_bytes, h5_bytes, xmf_bytes;
  PetscReal rows, row_bytes, header_bytes, csv_bytes;
} MMOutputPlan;
PETSC_EXTERN PetscErrorCode MMOutputPlanMake(const MMOutput *o, TS ts, MMOutputPlan *plan);

/* checkpoint.c: checkpoints and -restart (docs/method.md section 9) */
PETSC_EXTERN PetscErrorCode MMCheckpointSetFromOptions(MPI_Comm comm, MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointSetUp(MMCheckpoint *c, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, MMHistory *hist, MMState *state, MMDamping *damping, MMContact contact, MMFriction friction, MMOutput *out);
PETSC_EXTERN PetscErrorCode MMCheckpointWrite(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
PETSC_EXTERN PetscErrorCode MMCheckpointDestroy(MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointLoad(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointGetRestart(const MMCheckpoint *c, PetscBool *restarted, PetscInt *step, PetscReal *time);
PETSC_EXTERN PetscErrorCode MMCheckpointWriteFinal(MMCheckpoint *c, TS ts);
PETSC_EXTERN PetscErrorCode MMCheckpointView(const MMCheckpoint *c, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode MMCheckpointRestoreHistory(MMCheckpoint *c);
PETSC_EXTERN PetscErrorCode MMCheckpointGetFrames(const MMCheckpoint *c, const PetscScalar **rec, const PetscReal **counters);
PETSC_EXTERN PetscErrorCode MMCheckpointGetPairs(const MMCheckpoint *c, const PetscScalar **rec, const PetscReal **counters);
PETSC_EXTERN PetscErrorCode MMCheckpointGetTangent(const MMCheckpoint *c, Vec *at, PetscReal *t);
PETSC_EXTERN PetscErrorCode MMCheckpointSnapshots(MMCheckpoint *c, PetscInt *n, PetscReal **times);
PETSC_EXTERN PetscInt       MMCheckpointSnapshotCount(const MMCheckpoint *c);

/* progress.c: the start-up report and the progress lines */
PETSC_EXTERN PetscErrorCode MMProgressSetFromOptions(MPI_Comm comm, MMProgress *p);
PETSC_EXTERN PetscErrorCode MMProgressSetUp(MMProgress *p, const MMIOProblem *opt, MMOperators op, const MMMaterial *material, const MMHistory *hist, const MMState *state, MMContact contact, const MMDamping *damping);
PETSC_EXTERN PetscErrorCode MMProgressHeader(MMProgress *p, TS ts, KSP krylov, KSP pc_ksp);
PETSC_EXTERN PetscErrorCode MMProgressMonitorSet(MMProgress *p, TS ts);
PETSC_EXTERN PetscErrorCode MMProgressMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ctx);
