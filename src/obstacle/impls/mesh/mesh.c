/* A rigid obstacle of any shape, from a mesh of its surface (-obstacle_NAME_type mesh
 * -obstacle_NAME_mesh FILE.msh): the 2-node lines (2D) or 3-node triangles (3D) of a gmsh file, the
 * body on the side the facets' normals point to (-obstacle_NAME_side inside: the other one). A table's
 * edge, a step, a funnel, a groove. Its distance and normal are the surface's (closest.c); it moves as
 * the other shapes do. docs/method.md section 8, "A meshed obstacle". */
#include "surfaceimpl.h"
#include "sys.h"

typedef struct {
  char      file[PETSC_MAX_PATH_LEN];
  MMSurface surface;
} Meshed;

static const char *const MeshOptions[] = {"mesh", NULL};

static PetscErrorCode MeshSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, MMObstacle *ob)
{
  Meshed   *m = (Meshed *)ob->data;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(MMOptionsString(PetscOptionsObject, comm, "-mesh", "mesh: the gmsh file (.msh, ASCII 2.2 or 4.1) of the obstacle's surface: its 2-node lines in 2D, its 3-node triangles in 3D; the body on the side their normals point to (2D: the right of each line's direction; 3D: (b - a) x (c - a))", m->file, sizeof(m->file), &set));
  PetscCheck(set, comm, PETSC_ERR_USER_INPUT, "Obstacle %s is of type mesh but has no surface: give -obstacle_%s_mesh FILE.msh, a gmsh mesh of its lines (2D) or triangles (3D)", ob->name, ob->name);
  PetscFunctionReturn(0);
}

/* Once the dimension is known: the surface read, checked and searchable. */
static PetscErrorCode MeshCheck(MMObstacle *ob, MPI_Comm comm, PetscInt dim)
{
  Meshed *m = (Meshed *)ob->data;
  char    option[128];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(option, sizeof(option), "-obstacle_%s_mesh", ob->name));
  PetscCall(MMSurfaceDestroy(&m->surface));
  PetscCall(MMSurfaceRead(comm, option, m->file, dim, &m->surface));
  PetscCall(MMSurfaceSetUp(comm, option, ob->inside, &m->surface));
  PetscFunctionReturn(0);
}

static PetscErrorCode MeshDistance(const MMObstacle *ob, PetscInt dim, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Meshed *m = (const Meshed *)ob->data;

  PetscFunctionBeginUser;
  MMSurfaceDistance(&m->surface, x, g, n);
  PetscFunctionReturn(0);
}

static PetscErrorCode MeshView(const MMObstacle *ob, PetscViewer viewer)
{
  const Meshed *m = (const Meshed *)ob->data;
  const char   *what = m->surface.dim == 3 ? "triangles" : "lines";

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "mesh %s: %" PetscInt_FMT " %s, %" PetscInt_FMT " vertices; a search tree of %" PetscInt_FMT " boxes\n", m->file, m->surface.nf, what, m->surface.nv, m->surface.nnodes));
  PetscFunctionReturn(0);
}

/* The surface itself, not its file's name: its counts and a hash of its coordinates and facets. */
static PetscErrorCode MeshDescribe(const MMObstacle *ob, char text[], size_t len)
{
  const MMSurface *s    = &((const Meshed *)ob->data)->surface;
  unsigned long    hash = 1469598103934665603UL;
  const unsigned char *b = (const unsigned char *)s->x;

  PetscFunctionBeginUser;
  for (size_t i = 0; i < 3 * sizeof(PetscReal) * (size_t)s->nv; ++i) hash = (hash ^ b[i]) * 1099511628211UL;
  b = (const unsigned char *)s->f;
  for (size_t i = 0; i < sizeof(PetscInt) * (size_t)(s->dim * s->nf); ++i) hash = (hash ^ b[i]) * 1099511628211UL;
  PetscCall(PetscSNPrintf(text, len, "%" PetscInt_FMT " facets, %" PetscInt_FMT " vertices, hash %016lx", s->nf, s->nv, hash));
  PetscFunctionReturn(0);
}

static PetscErrorCode MeshDestroy(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  PetscCall(MMSurfaceDestroy(&((Meshed *)ob->data)->surface));
  PetscFunctionReturn(0);
}

static const MMObstacleOps MeshOps = {
  .params         = NULL,
  .nparams        = 0,
  .datasize       = sizeof(Meshed),
  .curved         = PETSC_TRUE,
  .faceted        = PETSC_TRUE,
  .sided          = PETSC_TRUE,
  .check          = MeshCheck,
  .distance       = MeshDistance,
  .options        = MeshOptions,
  .setfromoptions = MeshSetFromOptions,
  .view           = MeshView,
  .describe       = MeshDescribe,
  .destroy        = MeshDestroy,
};

PetscErrorCode MMObstacleCreate_Mesh(MMObstacle *ob)
{
  PetscFunctionBeginUser;
  ob->ops = &MeshOps;
  PetscFunctionReturn(0);
}
