"""Shared by the study and plot scripts: run mmcontact through mpiexec, read the options a run
used, and read what a run wrote (solution.h5, history.csv).

Not a command: imported by dt_convergence.py, plot_contact.py and compare_mass.py."""
import os
import shlex
import subprocess
import sys

import h5py
import numpy as np


# The options of a run, read as mmcontact reads them (the checks of a case are mmcontact's own:
# `mmcontact -check_input`, README "Checking a case before a batch job").
def is_option_name(token):
    """-E, -ts_dt: an option; -1, -0.5: a value."""
    return token.startswith("-") and len(token) > 1 and (token[1].isalpha() or token[1] == "_")


def parse_option_tokens(tokens, where, opts=None):
    """Tokens '-name [value]' -> dict name -> value string ('' for a flag), added to opts.
    Later occurrences win, as in PETSc."""
    opts = {} if opts is None else opts
    i = 0
    while i < len(tokens):
        t = tokens[i]
        if not is_option_name(t):
            raise SystemExit(f"{where}: value {t!r} without an option")
        val = ""
        if i + 1 < len(tokens) and not is_option_name(tokens[i + 1]):
            val = tokens[i + 1]
            i += 1
        opts[t[1:]] = val
        i += 1
    return opts


def read_options(path):
    """Options file -> dict name -> value string ('' for a flag). Later occurrences win."""
    tokens = []
    for line in open(path):
        line = line.split("#", 1)[0]
        tokens += line.split()
    return parse_option_tokens(tokens, path)


def vec(opts, key, dim, default=None):
    if key not in opts:
        if default is None:
            raise SystemExit(f"-{key} is missing")
        return np.array(default, float)
    v = np.array([float(x) for x in opts[key].split(",")])
    if len(v) != dim:
        raise SystemExit(f"-{key} {opts[key]}: needs {dim} entries")
    return v


def obstacles(opts, dim):
    """The rigid obstacles: [(name, signed distance f(x), mu, velocity, start)], f taking an array of
    points (k x dim) and carrying the outward normal as f.normal(x) (the tuple keeps its 5 entries for
    scripts/dt_convergence.py). [] for a run with contact pairs and no rigid obstacle:
    without -obstacles, -obstacle_point and -obstacle_normal, -contact_pairs leaves out the default
    plane (as mmcontact does)."""
    mu0 = float(opts.get("mu", 0))
    zero = [0.0] * dim
    if "obstacles" not in opts:
        if "contact_pairs" in opts and "obstacle_point" not in opts and "obstacle_normal" not in opts:
            return []
        p, n = vec(opts, "obstacle_point", dim, zero), vec(opts, "obstacle_normal", dim, [0] * (dim - 1) + [1])
        n = n / np.linalg.norm(n)
        f = (lambda x, p=p, n=n: (x - p) @ n)
        f.normal = (lambda x, n=n: np.tile(n, (len(x), 1)))
        return [("plane", f, mu0, np.zeros(dim), 0.0)]
    out = []
    for name in opts["obstacles"].split(","):
        pre = f"obstacle_{name}_"
        typ = opts.get(pre + "type", "plane")  # the default type, as in mmcontact
        side = opts.get(pre + "side", "outside")
        if side not in ("outside", "inside"):
            raise SystemExit(f"-{pre}side {side}: outside or inside")
        sgn = 1.0 if side == "outside" else -1.0
        if typ == "plane":
            p, n = vec(opts, pre + "point", dim), vec(opts, pre + "normal", dim)
            if abs(np.linalg.norm(n) - 1) > 1e-12:
                print(f"  note: -{pre}normal has norm {np.linalg.norm(n):.15g}; normalized here")
            n = n / np.linalg.norm(n)
            f = (lambda x, p=p, n=n: (x - p) @ n)
            g = (lambda x, n=n: np.tile(n, (len(x), 1)))
        elif typ in ("sphere", "circle"):
            if (typ == "circle") != (dim == 2):
                raise SystemExit(f"-{pre}type {typ} in {dim}D: circle is 2D, sphere 3D")
            c, r = vec(opts, pre + "center", dim), float(opts[pre + "radius"])

            def f(x, c=c, r=r, s=sgn):
                return s * (np.linalg.norm(x - c, axis=1) - r)

            def g(x, c=c, s=sgn):
                d = x - c
                return s * d / np.linalg.norm(d, axis=1)[:, None]
        elif typ == "cylinder":
            if dim != 3:
                raise SystemExit(f"-{pre}type cylinder needs a 3D mesh")
            p, a, r = vec(opts, pre + "point", 3), vec(opts, pre + "axis", 3), float(opts[pre + "radius"])
            a = a / np.linalg.norm(a)

            def radial(x, p=p, a=a):
                d = x - p
                return d - np.outer(d @ a, a)

            def f(x, r=r, s=sgn):
                return s * (np.linalg.norm(radial(x), axis=1) - r)

            def g(x, s=sgn):
                d = radial(x)
                return s * d / np.linalg.norm(d, axis=1)[:, None]
        else:
            raise SystemExit(f"-{pre}type {typ}: plane, sphere, circle or cylinder")
        f.normal = g
        out.append((name, f, float(opts.get(pre + "mu", mu0)), vec(opts, pre + "velocity", dim, zero),
                    float(opts.get(pre + "start", 0))))
    return out


def case_options(options_file, extra_tokens):
    """The options of a run: the file's, overridden by the extra command-line tokens (as
    mmcontact does: the command line wins over the file)."""
    return parse_option_tokens(list(extra_tokens), "--extra", read_options(options_file))


def split_extra(extra):
    """--extra "-contact 0 -ts_max_time 0.1" -> tokens (quotes are honoured)."""
    return shlex.split(extra) if extra else []


def mpiexec_command(np_, mpiexec="mpiexec"):
    """mpiexec with the flags this machine needs: root needs --allow-run-as-root, and more ranks
    than cores need --oversubscribe."""
    cmd = shlex.split(mpiexec)
    if hasattr(os, "getuid") and os.getuid() == 0:
        cmd.append("--allow-run-as-root")
    if np_ > (os.cpu_count() or 1):
        cmd.append("--oversubscribe")
    return cmd + ["-n", str(np_)]


def run_mmcontact(exe, np_, options_file, args, outdir, mpiexec="mpiexec"):
    """Runs exe on np_ ranks with -options_file options_file, then args, then -output_dir outdir.
    The program's output goes to outdir/run.log; a failed run stops the script with its tail."""
    os.makedirs(outdir, exist_ok=True)
    cmd = mpiexec_command(np_, mpiexec) + [exe, "-options_file", options_file, *args, "-output_dir", outdir]
    log = os.path.join(outdir, "run.log")
    with open(log, "w") as f:
        f.write(" ".join(shlex.quote(c) for c in cmd) + "\n")
        f.flush()
        proc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if proc.returncode != 0:
        tail = open(log).read()[-3000:]
        sys.exit(f"mmcontact failed (exit {proc.returncode}): {' '.join(cmd)}\n{tail}")
    return cmd


def read_history(outdir):
    """history.csv as a structured array, columns by name."""
    return np.genfromtxt(os.path.join(outdir, "history.csv"), delimiter=",", names=True, ndmin=1)


class Solution:
    """The mesh and the snapshots of OUTPUT_DIR/solution.h5, read whole (the cases are small).

    solution.h5 of a run that was stopped may hold one partial snapshot beyond the others: the
    snapshots kept are those every dataset (and /time) has."""

    def __init__(self, outdir):
        path = os.path.join(outdir, "solution.h5")
        if not os.path.exists(path):
            sys.exit(f"{path}: no such file (OUTPUT_DIR is a run's -output_dir)")
        with h5py.File(path, "r") as h:
            self.vertices = h["/geometry/vertices"][:]
            self.cells = h["/viz/topology/cells"][:].astype(np.int64)
            vf = h["/vertex_fields"]
            time = h["/time"][:].ravel()
            names = ["displacement_displacement", "velocity_displacement", "contact_pressure_nodal",
                     "gap_nodal", "tangential_traction_displacement", "slip_velocity_displacement"]
            n = min([len(time)] + [vf[k].shape[0] for k in names if k in vf])
            self.time = time[:n]
            self.fields = {k: vf[k][:n] for k in names if k in vf}
            self.obstacle = (vf["contact_obstacle_nodal"][:].astype(int) if "contact_obstacle_nodal" in vf
                             else np.full(len(self.vertices), -1))
        self.path = path
        self.dim = self.vertices.shape[1]

    def reorder_like(self, ref, label):
        """Puts the vertices in ref's order (and takes ref's cells). Two runs of the same case need
        not number the vertices alike: on several ranks the order follows the partition, which
        can differ from run to run. Vertices are matched by their coordinates, which must agree."""
        if self.vertices.shape != ref.vertices.shape:
            sys.exit(f"{label}: {len(self.vertices)} vertices against {len(ref.vertices)}: not the same mesh")
        perm = np.empty(len(ref.vertices), dtype=np.int64)
        perm[np.lexsort(ref.vertices.T)] = np.lexsort(self.vertices.T)
        tol = 1e-12 * max(1.0, np.abs(ref.vertices).max())
        if np.abs(self.vertices[perm] - ref.vertices).max() > tol:
            sys.exit(f"{label}: the vertices differ from the reference run's: not the same mesh")
        self.vertices = self.vertices[perm]
        self.cells = ref.cells
        self.fields = {k: v[:, perm] for k, v in self.fields.items()}
        self.obstacle = self.obstacle[perm]
        return self

    @property
    def displacement(self):
        return self.fields["displacement_displacement"]

    @property
    def velocity(self):
        return self.fields["velocity_displacement"]

    @property
    def pressure(self):
        return self.fields["contact_pressure_nodal"]

    @property
    def contact_nodes(self):
        """Indices of the contact boundary's vertices (each has an obstacle, the others -1)."""
        return np.flatnonzero(self.obstacle >= 0)
