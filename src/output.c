/* Output: the per-step history (CSV), HDF5 fields for ParaView with their XDMF index, and the closing summary.
 *
 * The HDF5 file is opened and closed around every write and the XDMF index rewritten after it, so
 * whatever stops the run, everything written so far stays readable. */
#include <petscsf.h>
#include <petscviewerhdf5.h>
#include <sys/resource.h>
#include "output.h"
#include "contact.h"
#include "fem.h"

static PetscErrorCode CSVHeader(MMCtx *ctx)
{
  const char *axes = "xyz";
  PetscInt    dim  = ctx->op.dim;

  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, "step,time,dt,kinetic,elastic,total,work_ext,work_contact,work_friction,balance_residual,active,slipping,force_normal,force_tangential,max_penetration,coulomb_residual,vi_its,friction_its,cfl"));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, ",ucm_%c", axes[d]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, ",vcm_%c", axes[d]));
  if (dim == 2) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, ",L_z"));
  else PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, ",L_x,L_y,L_z"));
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ctx->out.csv, ",switched,contraction\n"));
  PetscFunctionReturn(0);
}

static PetscErrorCode CSVRow(MMCtx *ctx)
{
  const MMHistory *h   = &ctx->hist;
  PetscInt         dim = ctx->op.dim;
  FILE            *f   = ctx->out.csv;

  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "%" PetscInt_FMT ",%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.16e,%.6e,%" PetscInt_FMT ",%" PetscInt_FMT ",%.16e,%.16e,%.6e,%.6e,%" PetscInt_FMT ",%" PetscInt_FMT ",%.6e", h->step, (double)h->time, (double)h->dt, (double)h->kinetic, (double)h->elastic, (double)h->total, (double)h->work_ext, (double)h->work_contact, (double)h->work_friction, (double)h->balance_residual, h->active, h->slipping, (double)h->force_normal, (double)h->force_tangential, (double)h->max_penetration, (double)h->coulomb_residual, h->vi_its, h->friction_its, (double)h->cfl));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, ",%.16e", (double)h->ucm[d]));
  for (PetscInt d = 0; d < dim; ++d) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, ",%.16e", (double)h->vcm[d]));
  if (dim == 2) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, ",%.16e", (double)h->L[2]));
  else PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, ",%.16e,%.16e,%.16e", (double)h->L[0], (double)h->L[1], (double)h->L[2]));
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, ",%" PetscInt_FMT ",%.6e\n", h->switched, (double)h->contraction));
  /* a row on disk is a row the user keeps, whatever happens next */
  if (f) PetscCheck(fflush(f) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Could not write the history file");
  PetscFunctionReturn(0);
}

/* The XDMF index of the HDF5 file, rewritten after every write so ParaView always opens all of it. */
static PetscErrorCode WriteXDMF(MMCtx *ctx)
{
  MMOutput   *o   = &ctx->out;
  DM          dm  = ctx->op.dm;
  PetscInt    dim = ctx->op.dim, nv, nc, vStart, vEnd, cStart, cEnd;
  char        xmf[PETSC_MAX_PATH_LEN], h5base[PETSC_MAX_PATH_LEN];
  FILE       *f;
  const char *topo = dim == 2 ? "Triangle" : "Tetrahedron";
  const char *fields[]  = {"displacement", "velocity", "contact_pressure", "gap", "tangential_traction", "slip_velocity"};
  const char *datasets[] = {"displacement_displacement", "velocity_displacement", "contact_pressure_nodal", "gap_nodal", "tangential_traction_displacement", "slip_velocity_displacement"};
  const PetscInt ncomp[] = {dim, dim, 1, 1, dim, dim};

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  {
    PetscInt loc[2], glob[2];
    PetscSF  sf;
    PetscInt nleaves;
    const PetscInt *leaves;
    PetscCall(DMGetPointSF(dm, &sf));
    PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
    loc[0] = vEnd - vStart;
    for (PetscInt l = 0; l < nleaves; ++l) {
      const PetscInt p = leaves ? leaves[l] : l;
      if (p >= vStart && p < vEnd) --loc[0];
    }
    loc[1] = cEnd - cStart;
    PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
    nv = glob[0];
    nc = glob[1];
  }
  PetscCall(PetscSNPrintf(xmf, sizeof(xmf), "%s/solution.xmf", ctx->opt.output_dir));
  PetscCall(PetscStrcpy(h5base, "solution.h5"));
  PetscCall(PetscFOpen(PETSC_COMM_WORLD, xmf, "w", &f));
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"2.99\">\n<Domain>\n"));
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<Grid Name=\"mmcontact\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"));
  for (PetscInt k = 0; k < o->n_written; ++k) {
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<Grid Name=\"step %" PetscInt_FMT "\" GridType=\"Uniform\">\n<Time Value=\"%.16e\"/>\n", k, (double)o->times[k]));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<Topology TopologyType=\"%s\" NumberOfElements=\"%" PetscInt_FMT "\">\n<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n</Topology>\n", topo, nc, nc, dim + 1, h5base));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<Geometry GeometryType=\"%s\">\n<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n</Geometry>\n", dim == 2 ? "XY" : "XYZ", nv, dim, h5base));
    for (size_t i = 0; i < sizeof(fields) / sizeof(fields[0]); ++i) {
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", fields[i], ncomp[i] > 1 ? "Vector" : "Scalar"));
      if (ncomp[i] > 1) {
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %" PetscInt_FMT " %" PetscInt_FMT "\" Type=\"HyperSlab\">\n", nv, ncomp[i]));
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem Dimensions=\"3 3\" Format=\"XML\">%" PetscInt_FMT " 0 0 1 1 1 1 %" PetscInt_FMT " %" PetscInt_FMT "</DataItem>\n", k, nv, ncomp[i]));
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem>\n</DataItem>\n</Attribute>\n", o->n_written, nv, ncomp[i], h5base, datasets[i]));
      } else {
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %" PetscInt_FMT "\" Type=\"HyperSlab\">\n", nv));
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem Dimensions=\"3 2\" Format=\"XML\">%" PetscInt_FMT " 0 1 1 1 %" PetscInt_FMT "</DataItem>\n", k, nv));
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "<DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/%s</DataItem>\n</DataItem>\n</Attribute>\n", o->n_written, nv, h5base, datasets[i]));
      }
    }
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "</Grid>\n"));
  }
  PetscCall(PetscFPrintf(PETSC_COMM_WORLD, f, "</Grid>\n</Domain>\n</Xdmf>\n"));
  PetscCall(PetscFClose(PETSC_COMM_WORLD, f));
  PetscFunctionReturn(0);
}

/* The Cartesian field on every node, from the free dofs w: the Dirichlet data on constrained dofs for
 * the displacement, zero for the velocity (the data are constant in time). */
static PetscErrorCode WholeField(MMCtx *ctx, Vec w, PetscBool with_bc, Vec whole)
{
  DM  dm = ctx->op.dm;
  Vec g, l;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(dm, &g));
  PetscCall(DMGetLocalVector(dm, &l));
  PetscCall(MMFEToCartesian(ctx, w, g));
  PetscCall(VecZeroEntries(l));
  PetscCall(DMGlobalToLocal(dm, g, INSERT_VALUES, l));
  if (with_bc) PetscCall(DMPlexInsertBoundaryValues(dm, PETSC_TRUE, l, ctx->hist.time, NULL, NULL, NULL));
  PetscCall(DMLocalToGlobal(ctx->out.dm_out, l, INSERT_VALUES, whole));
  PetscCall(DMRestoreLocalVector(dm, &l));
  PetscCall(DMRestoreGlobalVector(dm, &g));
  PetscFunctionReturn(0);
}

/* Writes the current fields as output number n_written, then closes the file again. */
static PetscErrorCode WriteFields(MMCtx *ctx)
{
  MMOutput   *o = &ctx->out;
  PetscViewer v;
  PetscReal   t = ctx->hist.time;

  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(ctx->log.output));
  PetscCall(WholeField(ctx, ctx->state.u, PETSC_TRUE, o->disp_cart));
  PetscCall(WholeField(ctx, ctx->state.v, PETSC_FALSE, o->vel_cart));
  PetscCall(MMContactBoundaryFields(ctx, o));
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_WORLD, o->h5_name, FILE_MODE_APPEND, &v));
  PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_HDF5_XDMF));
  PetscCall(DMSetOutputSequenceNumber(o->dm_out, o->n_written, t));
  PetscCall(DMSetOutputSequenceNumber(o->dm_scalar, o->n_written, t));
  PetscCall(VecView(o->disp_cart, v));
  PetscCall(VecView(o->vel_cart, v));
  PetscCall(VecView(o->pressure, v));
  PetscCall(VecView(o->gap, v));
  PetscCall(VecView(o->traction_t, v));
  PetscCall(VecView(o->slip, v));
  PetscCall(PetscViewerPopFormat(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(PetscRealloc(sizeof(PetscReal) * (o->n_written + 1), &o->times));
  o->times[o->n_written++] = t;
  PetscCall(WriteXDMF(ctx));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

/* mkdir -p: each missing component of the path, on rank 0 */
static PetscErrorCode MakeDirectories(const char path[])
{
  char      dir[PETSC_MAX_PATH_LEN];
  PetscBool exists;
  size_t    len;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(dir, path, sizeof(dir)));
  PetscCall(PetscStrlen(dir, &len));
  for (size_t i = 1; i <= len; ++i) {
    if (dir[i] != '/' && dir[i] != 0) continue;
    dir[i] = 0;
    PetscCall(PetscTestDirectory(dir, 'w', &exists));
    if (!exists) PetscCall(PetscMkdir(dir));
    if (i < len) dir[i] = '/';
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MMOutputOpen(MMCtx *ctx)
{
  MMOutput   *o = &ctx->out;
  char        name[PETSC_MAX_PATH_LEN];
  PetscViewer v;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank == 0) PetscCall(MakeDirectories(ctx->opt.output_dir));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/history.csv", ctx->opt.output_dir));
  PetscCall(PetscFOpen(PETSC_COMM_WORLD, name, "w", &o->csv));
  PetscCall(CSVHeader(ctx));
  PetscCall(PetscSNPrintf(o->h5_name, sizeof(o->h5_name), "%s/solution.h5", ctx->opt.output_dir));
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_WORLD, o->h5_name, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_HDF5_XDMF));
  PetscCall(DMView(ctx->op.dm, v));
  PetscCall(PetscViewerPopFormat(v));
  PetscCall(PetscViewerDestroy(&v));
  {
    PetscFE      fe;
    PetscSection s;
    const char  *names[] = {"displacement_x", "displacement_y", "displacement_z"};
    PetscCall(DMClone(ctx->op.dm, &o->dm_out));
    PetscCall(PetscFECreateLagrange(PETSC_COMM_WORLD, ctx->op.dim, ctx->op.dim, PETSC_TRUE, 1, PETSC_DETERMINE, &fe));
    PetscCall(PetscObjectSetName((PetscObject)fe, "displacement"));
    PetscCall(DMSetField(o->dm_out, 0, NULL, (PetscObject)fe));
    PetscCall(PetscFEDestroy(&fe));
    PetscCall(DMCreateDS(o->dm_out));
    PetscCall(DMGetLocalSection(o->dm_out, &s));
    for (PetscInt c = 0; c < ctx->op.dim; ++c) PetscCall(PetscSectionSetComponentName(s, 0, c, names[c]));
  }
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->disp_cart));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->vel_cart));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->traction_t));
  PetscCall(DMCreateGlobalVector(o->dm_out, &o->slip));
  PetscCall(PetscObjectSetName((PetscObject)o->traction_t, "tangential_traction"));
  PetscCall(PetscObjectSetName((PetscObject)o->slip, "slip_velocity"));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->pressure));
  PetscCall(DMCreateGlobalVector(o->dm_scalar, &o->gap));
  PetscCall(PetscObjectSetName((PetscObject)o->disp_cart, "displacement"));
  PetscCall(PetscObjectSetName((PetscObject)o->vel_cart, "velocity"));
  PetscCall(PetscObjectSetName((PetscObject)o->pressure, "contact_pressure"));
  PetscCall(PetscObjectSetName((PetscObject)o->gap, "gap"));
  PetscFunctionReturn(0);
}

/* TS monitor: one history row per step, fields every -output_every steps. */
PetscErrorCode MMOutputMonitor(TS ts, PetscInt step, PetscReal time, Vec u, void *ptr)
{
  MMCtx   *ctx   = (MMCtx *)ptr;
  PetscInt every = ctx->opt.output_every;

  PetscFunctionBeginUser;
  PetscCall(CSVRow(ctx));
  if (step == 0 || (every > 0 && step % every == 0)) PetscCall(WriteFields(ctx));
  PetscFunctionReturn(0);
}

/* Writes the final state if the cadence missed it, closes the files and prints the summary. */
PetscErrorCode MMOutputClose(MMCtx *ctx, PetscLogDouble setup, PetscLogDouble wall)
{
  MMOutput *o = &ctx->out;
  MMHistory *h = &ctx->hist;

  PetscFunctionBeginUser;
  if (o->n_written && o->times[o->n_written - 1] != h->time) PetscCall(WriteFields(ctx));
  PetscCall(PetscFClose(PETSC_COMM_WORLD, o->csv));
  if (!ctx->opt.quiet) {
    struct rusage ru;
    PetscReal     peak;
    getrusage(RUSAGE_SELF, &ru);
    peak = ru.ru_maxrss / 1024.0; /* kB on Linux */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &peak, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mmcontact summary: setup %.3f s; %" PetscInt_FMT " steps to t = %g in %.3f s wall (%.4f s/step); peak memory %.1f MiB/rank; largest balance residual %.3e; largest penetration %.3e (h_c' %.3e)\n", (double)setup, h->step, (double)h->time, (double)wall, h->step ? (double)(wall / h->step) : 0.0, (double)peak, (double)h->max_balance, (double)h->max_penetration_run, (double)ctx->contact.h_c));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  output: %s/history.csv, %s (%" PetscInt_FMT " snapshots), %s/solution.xmf\n", ctx->opt.output_dir, o->h5_name, o->n_written, ctx->opt.output_dir));
  }
  PetscCall(VecDestroy(&o->disp_cart));
  PetscCall(VecDestroy(&o->vel_cart));
  PetscCall(VecDestroy(&o->pressure));
  PetscCall(VecDestroy(&o->gap));
  PetscCall(VecDestroy(&o->traction_t));
  PetscCall(VecDestroy(&o->slip));
  PetscCall(DMDestroy(&o->dm_scalar));
  PetscCall(DMDestroy(&o->dm_out));
  PetscCall(PetscFree(o->times));
  PetscFunctionReturn(0);
}
