/* io's private declarations: the output's own helpers, shared by its files, and io's log events. */
#pragma once
#include <stdio.h>
#include "io.h"
#include "sys.h"

#define MM_SNAPSHOT_COPY "checkpoint_snapshots.h5" /* solution.h5 as of the last checkpoint */

/* io's log stage and events (iopackage.c, MMIOInitializePackage) */
typedef struct {
  PetscLogStage output;               /* writing a snapshot */
  PetscLogEvent flush, index, copy;   /* HDF5 flush, XDMF rewrite, the checkpoint's copy of solution.h5 */
  PetscLogEvent space;                /* the free space checked before an HDF5 write */
  PetscLogEvent checkpoint;           /* a checkpoint written or read */
  PetscLogEvent restart_output;       /* -restart: the history cut and the earlier snapshots copied */
} MMIOLog;
PETSC_INTERN MMIOLog MMIOEvents;

/* A file system call that failed on rank 0: what was tried on which file, and errno. */
typedef struct {
  int  err;
  char what[2 * PETSC_MAX_PATH_LEN + 64];
} MMFileStatus;

/* A piece of text built whole: a history row, so that it goes to disk in one write; an index grid. */
typedef struct {
  char   s[8192];
  size_t n;
} MMLine;

PETSC_INTERN PetscErrorCode MMOutputFailed(MMFileStatus *st, const char fmt[], ...);
PETSC_INTERN PetscErrorCode MMOutputCheckRank0(MMFileStatus *st);
PETSC_INTERN int            MMOutputWriteAll(int fd, const char *buf, size_t len);
PETSC_INTERN PetscErrorCode MMOutputHDF5Begin(void);
PETSC_INTERN PetscErrorCode MMOutputHDF5End(PetscErrorCode ierr, const char action[], const char name[]);
PETSC_INTERN PetscErrorCode MMOutputHDF5Create(MPI_Comm comm, const char name[], PetscViewer *viewer);
PETSC_INTERN PetscErrorCode MMOutputHDF5Close(PetscViewer *viewer, const char name[]);
PETSC_INTERN PetscErrorCode MMOutputCheckSpace(const char dir[], const char name[], const char what[], PetscReal bytes);
PETSC_INTERN PetscErrorCode MMOutputLineAdd(MMLine *l, const char fmt[], ...);
PETSC_INTERN PetscErrorCode MMOutputCSVHeaderLine(const MMOutput *o, MMLine *line);
PETSC_INTERN PetscErrorCode MMOutputIndexAddGrid(MMOutput *o, PetscInt dim, PetscInt k, PetscReal t);
PETSC_INTERN size_t         MMOutputIndexFrameBytes(void);
PETSC_INTERN PetscReal      MMOutputIndexRoom(const MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputWriteIndexFile(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputFlushFields(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputWriteDataset(PetscViewer viewer, Vec v, PetscInt step, const char field_type[]);
PETSC_INTERN PetscErrorCode MMOutputWriteStaticFields(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputMakeDirectories(const char path[], MMFileStatus *st);
PETSC_INTERN PetscErrorCode MMOutputKeepPrevious(const char dir[], MMFileStatus *st);
/* The fields of each snapshot, in one table for the writer, the XDMF index and the restart's copy:
 * the XDMF name, the dataset under /vertex_fields (or /cell_fields), components, the vector and its
 * DM (NULL: a cell field, a plain vector in the topology's cell order). */
#define MM_SNAPSHOT_FIELDS 10
typedef struct {
  const char *name, *dataset;
  PetscInt    ncomp;
  Vec         vec;
  DM          dm;
} MMSnapshotField;
PETSC_INTERN PetscErrorCode MMOutputViewSnapshot(MMOutput *o, PetscViewer viewer, PetscInt step, PetscReal t);
PETSC_INTERN void MMOutputSnapshotFields(MMOutput *o, PetscInt dim, MMSnapshotField f[MM_SNAPSHOT_FIELDS]);
/* output_views.c: each snapshot's fields as datasets of their own, for the XDMF index */
PETSC_INTERN PetscErrorCode MMOutputCreateViews(PetscViewer viewer, const MMSnapshotField f[MM_SNAPSHOT_FIELDS], PetscInt k);
PETSC_INTERN PetscInt       MMOutputViewComponents(PetscInt ncomp);
PETSC_INTERN PetscErrorCode MMOutputViewPath(PetscInt k, const char name[], char path[], size_t len);
PETSC_INTERN PetscErrorCode MMOutputViewBytes(const MMSnapshotField f[MM_SNAPSHOT_FIELDS], PetscInt nv, PetscInt nc, PetscInt k0, PetscReal *bytes);
/* output_schedule.c: which steps write a row or a snapshot; the planned output's size */
PETSC_INTERN PetscBool      MMOutputHistoryDue(const MMOutput *o, PetscInt step);
PETSC_INTERN PetscBool      MMOutputSnapshotDue(const MMOutput *o, PetscInt step, PetscReal t, PetscReal dt);
PETSC_INTERN PetscErrorCode MMOutputPlanCheck(const MMOutput *o, TS ts);
PETSC_INTERN PetscErrorCode MMOutputPlanWrites(MMOutput *o);
/* probes.c: -probes, the groups' mean displacement and velocity */
PETSC_INTERN PetscErrorCode MMProbesSetUp(MMOutput *o, Vec vertex_masses);
PETSC_INTERN PetscErrorCode MMProbesEvaluate(MMOutput *o);
PETSC_INTERN PetscErrorCode MMProbesDestroy(MMProbes *probes);
/* output.c: the writer, from the fields the glue (output_monitor.c) filled */
PETSC_INTERN PetscErrorCode MMOutputOpenFiles(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputWriteRow(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputWriteSnapshot(MMOutput *o, PetscReal t);
/* output_restart.c: -restart continues the history and the snapshots up to the checkpoint */
PETSC_INTERN PetscErrorCode MMOutputRestartHistory(MMOutput *o, MMFileStatus *st);
PETSC_INTERN PetscErrorCode MMOutputRestartFields(MMOutput *o);
PETSC_INTERN PetscErrorCode MMOutputWriteMesh(MMOperators op, PetscViewer viewer);
