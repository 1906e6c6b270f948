#!/usr/bin/env python3
"""Checks a case (options file + gmsh mesh) before running it, without the executable.

    /usr/bin/python3 -s scripts/check_case.py options/ball_bowl.opts [more.opts ...]

Run it from the repository root: the options' paths are relative to it.

For each options file it reads the mesh (`-mesh`, gmsh 4.1 ASCII), and reports:
- the physical groups, and that `-contact_boundary` (and every `-dirichlet`/`-traction` name) exists;
- vertices, dofs (d x vertices), contact vertices;
- c_p, h_c' (the smallest diameter, i.e. longest edge, of the cells touching a contact vertex, as
  mmcontact computes it), `-ts_dt`, c_p dt / h_c' and the number of steps to `-ts_max_time`; with
  `-bodies`, c_p is the largest of the bodies' (their `-body_NAME_E`, `_nu`, `_rho`), as mmcontact
  takes it (the rigid-body estimate below still moves every vertex by `-v0`, not by its body's);
- the obstacles: the registry (`-obstacles a,b` with `-obstacle_NAME_type plane|sphere|circle|
  cylinder`, ...) or the single plane `-obstacle_point`/`-obstacle_normal`. Each contact vertex is
  assigned to the obstacle with the smallest signed distance in the reference configuration, ties
  to the one listed first, as mmcontact does; the script prints, per obstacle, the vertices it
  gets, their smallest gap, and a rigid-body estimate of the first contact (the body translated
  by its `-v0` and `-gravity`, the obstacle by `-obstacle_NAME_velocity` from `-obstacle_NAME_start`;
  it ignores `-omega`, deformation and the modified mass).
The geometry is placed as mmcontact places it: the mesh turned by `-mesh_rotation` about
`-mesh_rotation_center` when it is read (the vertices are assigned to obstacles there, in the
reference configuration), and the initial displacement u0 = a + B x of `-u0_offset` and
`-u0_gradient` added for the gaps and the initial-penetration check.
It exits 1 if a group is missing, a contact vertex starts inside an obstacle (signed distance < 0),
or c_p dt / h_c' is above 1.5.
"""
import math
import sys

import numpy as np

CFL_MAX = 1.5


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


def read_msh41(path):
    """gmsh 4.1 ASCII -> (coords (n x 3), node index of tag, {name: (dim, [cells as tag lists])})."""
    try:
        lines = open(path).read().split("\n")
    except OSError as e:
        raise SystemExit(f"{path}: {e.strerror} (make meshes builds the meshes of meshes/*.geo)")
    pos = 0

    def section(name):
        nonlocal pos
        while pos < len(lines) and lines[pos].strip() != "$" + name:
            pos += 1
        if pos == len(lines):
            return False
        pos += 1
        return True

    if not section("MeshFormat") or not lines[pos].split()[0].startswith("4.1") or lines[pos].split()[1] != "0":
        raise SystemExit(f"{path}: not a gmsh 4.1 ASCII mesh")
    pos = 0
    names = {}
    if section("PhysicalNames"):
        for k in range(int(lines[pos])):
            d, tag, name = lines[pos + 1 + k].split(maxsplit=2)
            names[(int(d), int(tag))] = name.strip('"')
    pos = 0
    ent_phys = {}  # (dim, entity tag) -> physical tags
    section("Entities")
    counts = list(map(int, lines[pos].split()))
    pos += 1
    for d in range(4):
        for _ in range(counts[d]):
            f = lines[pos].split()
            pos += 1
            tag = int(f[0])
            k = 4 if d == 0 else 7
            nphys = int(f[k])
            ent_phys[(d, tag)] = [int(x) for x in f[k + 1:k + 1 + nphys]]
    pos = 0
    section("Nodes")
    nblocks = int(lines[pos].split()[0])
    pos += 1
    tags, xyz = [], []
    for _ in range(nblocks):
        _, _, param, n = map(int, lines[pos].split())
        pos += 1
        tags += [int(lines[pos + k]) for k in range(n)]
        xyz += [list(map(float, lines[pos + n + k].split()[:3])) for k in range(n)]
        pos += 2 * n
    coords = np.array(xyz)
    index = {t: i for i, t in enumerate(tags)}
    pos = 0
    section("Elements")
    nblocks = int(lines[pos].split()[0])
    pos += 1
    groups = {}
    for _ in range(nblocks):
        edim, etag, etype, n = map(int, lines[pos].split())
        pos += 1
        cells = [[index[int(x)] for x in lines[pos + k].split()[1:]] for k in range(n)]
        pos += n
        for ptag in ent_phys.get((edim, etag), []):
            name = names.get((edim, ptag), f"#{ptag}")
            groups.setdefault(name, (edim, []))[1].extend(cells)
    return coords, groups


def wave_speed(opts):
    """The largest pressure wave speed c_p of the bodies, as mmcontact's CFL number takes it: each
    body of -bodies with its -body_NAME_E, _nu, _rho (default -E, -nu, -rho), or the one material."""
    E, nu, rho = float(opts.get("E", 1)), float(opts.get("nu", 0.3)), float(opts.get("rho", 1))
    bodies = opts["bodies"].split(",") if opts.get("bodies") else []
    mats = [(float(opts.get(f"body_{b}_E", E)), float(opts.get(f"body_{b}_nu", nu)), float(opts.get(f"body_{b}_rho", rho))) for b in bodies] or [(E, nu, rho)]
    return max(math.sqrt(e * (1 - n) / (r * (1 + n) * (1 - 2 * n))) for e, n, r in mats)


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
    """[(name, signed-distance function, mu, velocity, start)]."""
    mu0 = float(opts.get("mu", 0))
    zero = [0.0] * dim
    if "obstacles" not in opts:
        p, n = vec(opts, "obstacle_point", dim, zero), vec(opts, "obstacle_normal", dim, [0] * (dim - 1) + [1])
        n = n / np.linalg.norm(n)
        return [("plane", lambda x, p=p, n=n: (x - p) @ n, mu0, np.zeros(dim), 0.0)]
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
        elif typ in ("sphere", "circle"):
            if (typ == "circle") != (dim == 2):
                raise SystemExit(f"-{pre}type {typ} in {dim}D: circle is 2D, sphere 3D")
            c, r = vec(opts, pre + "center", dim), float(opts[pre + "radius"])

            def f(x, c=c, r=r, s=sgn):
                return s * (np.linalg.norm(x - c, axis=1) - r)
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
        else:
            raise SystemExit(f"-{pre}type {typ}: plane, sphere, circle or cylinder")
        out.append((name, f, float(opts.get(pre + "mu", mu0)), vec(opts, pre + "velocity", dim, zero),
                    float(opts.get(pre + "start", 0))))
    return out


def mesh_rotation(opts, dim):
    """The rigid rotation mmcontact applies to the mesh when it reads it (src/mesh/mesh.c): an angle in 2D,
    a rotation vector in 3D (Rodrigues), about -mesh_rotation_center. (R, center)."""
    center = vec(opts, "mesh_rotation_center", dim, [0.0] * dim)
    if dim == 2:
        th = vec(opts, "mesh_rotation", 1, [0.0])[0]
        c, s = math.cos(th), math.sin(th)
        return np.array([[c, -s], [s, c]]), center
    r = vec(opts, "mesh_rotation", 3, [0.0, 0.0, 0.0])
    th = np.linalg.norm(r)
    if th == 0:
        return np.eye(3), center
    k = r / th
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return math.cos(th) * np.eye(3) + (1 - math.cos(th)) * np.outer(k, k) + math.sin(th) * K, center


def initial_displacement(opts, x, dim):
    """u0 = a + B x (-u0_offset a, -u0_gradient B row-major), at the placed vertices x."""
    a = vec(opts, "u0_offset", dim, [0.0] * dim)
    B = vec(opts, "u0_gradient", dim * dim, [0.0] * dim * dim).reshape(dim, dim)
    return a + x @ B.T


def first_contact(f, x, v0, grav, vel, start, tmax, dt):
    """First time on a grid of dt / 10 up to tmax at which a vertex of x, translated rigidly by
    v0 t + grav t^2 / 2, reaches the obstacle f translated by vel (t - start)+; inf if none."""
    for t in np.arange(0, tmax + dt / 20, dt / 10):
        if f(x + v0 * t + 0.5 * grav * t * t - vel * max(t - start, 0.0)).min() <= 0:
            return t
    return math.inf


def check(path):
    ok = True
    opts = read_options(path)
    print(f"== {path}")
    coords, groups = read_msh41(opts["mesh"])
    dim = max(d for d, _ in groups.values())
    body = [c for d, cells in groups.values() if d == dim for c in cells]
    used = np.unique(np.array(body).ravel())
    R, center = mesh_rotation(opts, dim)
    x = center + (coords[:, :dim] - center) @ R.T
    if not np.array_equal(R, np.eye(dim)):
        print(f"  mesh turned by -mesh_rotation {opts['mesh_rotation']} about ({', '.join(f'{c:g}' for c in center)})")
    print(f"  mesh {opts['mesh']}: {dim}D, groups " + ", ".join(f"{n} (dim {d}, {len(c)} cells)" for n, (d, c) in groups.items()))
    print(f"  vertices {len(used)}, dofs {dim * len(used)}")
    cname = opts.get("contact_boundary", "contact")
    wanted = [cname] + [n for k in ("dirichlet", "traction") if opts.get(k) for n in opts[k].split(",")]
    for n in wanted:
        if n not in groups:
            print(f"  ERROR: no physical group {n!r}")
            ok = False
        elif groups[n][0] != dim - 1:
            print(f"  ERROR: group {n!r} has dimension {groups[n][0]}, not {dim - 1} (boundary faces)")
            ok = False
    if cname not in groups:
        return False
    cverts = np.unique(np.array(groups[cname][1]).ravel())
    mark = np.zeros(len(coords), bool)
    mark[cverts] = True
    hmin = math.inf
    for cell in body:
        if mark[cell].any():
            p = x[cell]
            hmin = min(hmin, max(np.linalg.norm(p[i] - p[j]) for i in range(len(cell)) for j in range(i + 1, len(cell))))
    cp = wave_speed(opts)
    dt, tmax = float(opts["ts_dt"]), float(opts["ts_max_time"])
    cfl = cp * dt / hmin
    print(f"  contact vertices {len(cverts)}; c_p {cp:.4g}, h_c' {hmin:.4g}, dt {dt:g}, c_p dt / h_c' {cfl:.3f}, "
          f"steps {tmax / dt:.0f} (to t = {tmax:g})")
    if cfl > CFL_MAX:
        print(f"  ERROR: c_p dt / h_c' above {CFL_MAX}")
        ok = False
    obs = obstacles(opts, dim)
    xc = x[cverts]
    # assigned in the reference configuration; the gaps are those of the initial state x + u0
    ref = np.array([f(xc) for _, f, _, _, _ in obs])  # obstacles x contact vertices
    owner = np.argmin(ref, axis=0)  # argmin takes the first of equal values: ties to the first listed
    srt = np.sort(ref, axis=0)
    xc = xc + initial_displacement(opts, xc, dim)
    dist = np.array([f(xc) for _, f, _, _, _ in obs])
    near_ties = int(np.sum(srt[1] - srt[0] <= 1e-9 * hmin)) if len(obs) > 1 else 0
    v0 = vec(opts, "v0", dim, [0.0] * dim)
    grav = vec(opts, "gravity", dim, [0.0] * dim)
    for k, (name, f, mu, vel, start) in enumerate(obs):
        mine = owner == k
        dmin_all = dist[k].min()
        if dmin_all < 0:
            print(f"  ERROR: obstacle {name}: contact vertex at {xc[np.argmin(dist[k])]} inside it (signed distance {dmin_all:.3g})")
            ok = False
        line = f"  obstacle {name}: {int(mine.sum())} contact vertices, mu {mu:g}"
        if vel.any():
            line += f", velocity {','.join(f'{v:g}' for v in vel)} from t = {start:g} (|v| / c_p = {np.linalg.norm(vel) / cp:.2g})"
        if mine.any():
            j = np.flatnonzero(mine)[np.argmin(dist[k][mine])]
            t = first_contact(f, xc[mine], v0, grav, vel, start, tmax, dt)
            line += f"; smallest gap {dist[k][j]:.4g} at ({', '.join(f'{c:.4g}' for c in xc[j])})"
            line += f"; rigid-body first contact t ~ {t:.3g} (step {t / dt:.0f})" if math.isfinite(t) else "; no contact before the end (rigid-body estimate)"
        print(line)
    if near_ties:
        print(f"  {near_ties} contact vertices equally near two obstacles (given to the first listed)")
    return ok


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    results = [check(p) for p in sys.argv[1:]]
    sys.exit(0 if all(results) else 1)
