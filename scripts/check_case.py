#!/usr/bin/env python3
"""Checks a case (options file + gmsh mesh) before running it, without the executable.

    /usr/bin/python3 -s scripts/check_case.py options/ball_bowl.opts [more.opts ...]

Run it from the repository root: the options' paths are relative to it.

For each options file it reads the mesh (`-mesh`, gmsh 4.1 ASCII), and reports:
- the physical groups, and that `-contact_boundary` (when there are rigid obstacles) and every
  `-dirichlet`/`-traction` name exists; with `-contact 0`, only the latter (no contact boundary);
- vertices, dofs (d x vertices);
- the bodies (`-bodies a,b` with `-body_NAME_group`, `-body_NAME_E/_nu/_rho/_v0`, defaulting to
  -E/-nu/-rho/-v0): per body its cells and c_p; every cell must be in exactly one body;
- the contact vertices: those of `-contact_boundary` if there are rigid obstacles, plus every contact
  pair's slave vertices; c_p (the largest over the bodies), h_c' (the smallest diameter, i.e.
  longest edge, of the cells touching a contact vertex, as mmcontact computes it), `-ts_dt`,
  c_p dt / h_c' and the number of steps to `-ts_max_time`; with `-bodies` the check takes it body by
  body (each contact-layer cell with its own body's c_p);
- the rigid obstacles: the registry (`-obstacles a,b` with `-obstacle_NAME_type plane|sphere|circle|
  cylinder`, ...) or the single plane `-obstacle_point`/`-obstacle_normal`; with `-contact_pairs` and
  none of these, there is no rigid obstacle (and no `-contact_boundary` is needed). Each contact
  vertex is assigned to the obstacle with the smallest signed distance in the reference
  configuration, ties to the one listed first, as mmcontact does; the script prints, per obstacle,
  the vertices it gets, their smallest gap, and a rigid-body estimate of the first contact (the body
  translated by its `-v0` and `-gravity`, the obstacle by `-obstacle_NAME_velocity` from
  `-obstacle_NAME_start`; it ignores `-omega`, deformation and the modified mass);
- corners (docs/method.md section 8): without friction (every obstacle's and pair's mu 0), a
  rigid-contact vertex whose nearest other obstacle, not parallel to its own (|n1.n2| <= 1 - 1e-6),
  is within h_c' at the reference position gets a second row: the count and the rows in all (as
  mmcontact's header: "N contact nodes (K of them against two obstacles: N + K rows)"). With friction
  each such vertex keeps one row that carries both obstacles' Coulomb laws (a friction corner,
  docs/method.md section 12; mmcontact's header: "N contact nodes (K of them against two obstacles,
  each with its own Coulomb law)"), which only -contact_formulation condensed solves;
- the contact pairs (`-contact_pairs p` with `-contact_pair_NAME_slave/_master/_mu`, docs/method.md
  section 11): the slave and master groups (boundary faces), the slave vertices, those facing a master
  vertex (node to node) and the master facets (as mmcontact's header line "pair p: ..."), the smallest
  gap n.(X_s - p) over the slave vertices, each projected as mmcontact does on the closest master
  facet (segment or triangle; n the facet's outward normal, p the closest point, the weights snapped
  within 1e-10 of 0 or 1), and a rigid-body estimate of the first contact from the two bodies' v0
  (the gap closing at n.(v_master - v_slave); gravity, the same for both, cancels).
The geometry is placed as mmcontact places it: the mesh turned by `-mesh_rotation` about
`-mesh_rotation_center` when it is read (the vertices are assigned to obstacles, projected on the
master facets and checked for corners there, in the reference configuration), and the initial
displacement u0 = a + B x of `-u0_offset` and `-u0_gradient` added for the gaps and the
initial-penetration checks.
It exits 1 if a group is missing or of the wrong dimension, a pair's group has facets inside the
mesh, a master surface shares a vertex with a contact surface, a cell is in no body or in two, a
contact vertex starts inside a rigid obstacle (signed distance < 0) or a slave vertex inside its
master body (gap < -1e-9 h_c'), or c_p dt / h_c' is above 1.5.
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


def pairs(opts):
    """The contact pairs: [(name, slave group, master group, mu)] (-contact_pair_NAME_mu defaults to -mu)."""
    out = []
    for name in opts.get("contact_pairs", "").split(","):
        if not name:
            continue
        pre = f"contact_pair_{name}_"
        out.append((name, opts.get(pre + "slave"), opts.get(pre + "master"), float(opts.get(pre + "mu", opts.get("mu", 0)))))
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


def wave_speed(E, nu, rho):
    """c_p = sqrt((lambda + 2 mu) / rho)."""
    return math.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))


def key(cell):
    return tuple(sorted(cell))


def facet_cells(cells):
    """Facet (sorted vertex tuple) -> the cells (indices into cells) it bounds: one on the boundary."""
    out = {}
    for c, cell in enumerate(cells):
        for i in range(len(cell)):
            out.setdefault(key(cell[:i] + cell[i + 1:]), []).append(c)
    return out


def check_group(groups, name, want, what):
    """ERROR line and False if the physical group is missing or not of dimension want."""
    if name not in groups:
        print(f"  ERROR: no physical group {name!r}{what}")
        return False
    if groups[name][0] != want:
        print(f"  ERROR: group {name!r}{what} has dimension {groups[name][0]}, not {want}")
        return False
    return True


def check_bodies(opts, groups, cells, dim, nverts):
    """-bodies: per body its cells and c_p; every cell in exactly one body. (ok, the largest c_p, the
    initial velocity of each vertex, the body of each vertex or -1, the body names)."""
    E, nu, rho = float(opts.get("E", 1)), float(opts.get("nu", 0.3)), float(opts.get("rho", 1))
    v0 = vec(opts, "v0", dim, [0.0] * dim)
    vel = np.tile(v0, (nverts, 1))
    owner = np.full(nverts, -1)
    if "bodies" not in opts:
        return True, wave_speed(E, nu, rho), vel, owner, []
    ok, cp_max, names = True, 0.0, opts["bodies"].split(",")
    seen = {}
    for b, name in enumerate(names):
        pre = f"body_{name}_"
        Eb, nub, rhob = (float(opts.get(pre + k, v)) for k, v in (("E", E), ("nu", nu), ("rho", rho)))
        cp = wave_speed(Eb, nub, rhob)
        cp_max = max(cp_max, cp)
        group = opts.get(pre + "group")
        if group is None:
            print(f"  ERROR: body {name} has no -{pre}group")
            ok = False
            continue
        if not check_group(groups, group, dim, f" (-{pre}group: a body is a group of cells)"):
            ok = False
            continue
        mine = groups[group][1]
        for cell in mine:
            seen[key(cell)] = seen.get(key(cell), 0) + 1
        verts = np.unique(np.array(mine).ravel())
        vel[verts] = vec(opts, pre + "v0", dim, v0)
        owner[verts] = b
        print(f"  body {name} (group {group}): {len({key(c) for c in mine})} cells, E {Eb:g}, nu {nub:g}, rho {rhob:g}, "
              f"c_p {cp:.4g}, v0 ({', '.join(f'{v:g}' for v in vel[verts[0]])})")
    none = sum(1 for c in cells if key(c) not in seen)
    both = sum(1 for n in seen.values() if n > 1)
    if none:
        print(f"  ERROR: {none} of the mesh's {len(cells)} cells are in no body's group")
        ok = False
    if both:
        print(f"  ERROR: {both} cells are in two bodies' groups")
        ok = False
    return ok, cp_max, vel, owner, names


def body_cfl(opts, x, cells, mark, owner, dt):
    """-bodies: the largest c_p dt / diam over the cells touching a contact vertex, each cell with its
    own body's c_p (a stiff body's c_p against another body's small cells means nothing)."""
    E, nu, rho = float(opts.get("E", 1)), float(opts.get("nu", 0.3)), float(opts.get("rho", 1))
    cps = [wave_speed(*(float(opts.get(f"body_{n}_{k}", v)) for k, v in (("E", E), ("nu", nu), ("rho", rho))))
           for n in opts["bodies"].split(",")]
    worst = 0.0
    for cell in cells:
        if mark[cell].any():
            p, b = x[cell], owner[cell[0]]
            diam = max(np.linalg.norm(p[i] - p[j]) for i in range(len(cell)) for j in range(i + 1, len(cell)))
            worst = max(worst, (cps[b] if b >= 0 else max(cps)) * dt / diam)
    return worst


def layer_diameter(x, cells, mark):
    """h_c': the smallest diameter (longest edge) of the cells touching a marked vertex."""
    hmin = math.inf
    for cell in cells:
        if mark[cell].any():
            p = x[cell]
            hmin = min(hmin, max(np.linalg.norm(p[i] - p[j]) for i in range(len(cell)) for j in range(i + 1, len(cell))))
    return hmin


def closest_on_facets(F, x):
    """The closest point to x of each facet F[f] (its dim vertices, dim x dim), as mmcontact computes
    it (src/contact/interface/pairs.c): barycentric weights phi (f x dim), snapped within 1e-10 of 0
    or 1, and the squared distances."""
    nf, dim = F.shape[0], F.shape[1]
    if dim == 2:
        e, r = F[:, 1] - F[:, 0], x - F[:, 0]
        t = np.clip(np.sum(r * e, axis=1) / np.sum(e * e, axis=1), 0, 1)
        phi = np.stack([1 - t, t], axis=1)
    else:
        a, ab, ac = F[:, 0], F[:, 1] - F[:, 0], F[:, 2] - F[:, 0]
        ap = x - a
        d00, d01, d11 = np.sum(ab * ab, 1), np.sum(ab * ac, 1), np.sum(ac * ac, 1)
        d20, d21 = np.sum(ap * ab, 1), np.sum(ap * ac, 1)
        den = d00 * d11 - d01 * d01
        v, w = (d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den
        phi = np.stack([1 - v - w, v, w], axis=1)
        inside = (v >= 0) & (w >= 0) & (v + w <= 1)
        # outside: the closest point of the three edges (the first of equal ones)
        best, pe = np.full(nf, np.inf), np.zeros((nf, 3))
        for e in range(3):
            i, j = e, (e + 1) % 3
            p, pq = F[:, i], F[:, j] - F[:, i]
            t = np.clip(np.sum((x - p) * pq, 1) / np.sum(pq * pq, 1), 0, 1)
            d2 = np.sum((p + t[:, None] * pq - x) ** 2, 1)
            take = d2 < best
            best[take] = d2[take]
            ph = np.zeros((nf, 3))
            ph[:, i], ph[:, j] = 1 - t, t
            pe[take] = ph[take]
        phi[~inside] = pe[~inside]
    phi[phi < 1e-10] = 0
    phi[phi > 1 - 1e-10] = 1
    phi /= phi.sum(axis=1)[:, None]
    return phi, np.sum((np.einsum("fj,fjd->fd", phi, F) - x) ** 2, axis=1)


def master_facets(x, cells, facets, fcells):
    """The master facets' vertices (f x dim x dim), outward normals (away from their cell) and
    centroids."""
    dim = x.shape[1]
    F = x[np.array(facets)]
    if dim == 2:
        e = F[:, 1] - F[:, 0]
        n = np.stack([e[:, 1], -e[:, 0]], axis=1)
    else:
        n = np.cross(F[:, 1] - F[:, 0], F[:, 2] - F[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    cen = F.mean(axis=1)
    ccen = np.array([x[cells[fcells[key(f)][0]]].mean(axis=0) for f in facets])
    n[np.sum((ccen - cen) * n, axis=1) > 0] *= -1
    return F, n, cen


def project_slaves(xs, F, cen):
    """Each slave vertex's closest master facet (equidistant ones told apart by the smallest centroid,
    as mmcontact does) and its weights: (facet index, phi) per vertex."""
    scale = np.sum((F[:, 0] - F[:, 1]) ** 2, axis=1)
    fbest, phis = [], []
    for xv in xs:
        phi, d2 = closest_on_facets(F, xv)
        cand = np.flatnonzero(d2 <= d2.min() + 1e-13 * scale)
        f = cand[np.lexsort(cen[cand].T[::-1])[0]]
        fbest.append(f)
        phis.append(phi[f])
    return np.array(fbest), np.array(phis)


def check_pair(pair, opts, groups, x, cells, fcells, contact_mark, hmin, vel, dt, tmax):
    """One contact pair: its groups, slave vertices, smallest gap (ERROR below -1e-9 h_c': a slave
    vertex inside the master body) and the rigid-body first contact from the bodies' v0."""
    name, slave, master, mu = pair
    dim = x.shape[1]
    ok = True
    for what, grp in (("slave", slave), ("master", master)):
        if grp is None:
            print(f"  ERROR: pair {name}: no -contact_pair_{name}_{what}")
            return False
        if not check_group(groups, grp, dim - 1, f" (pair {name}'s {what}, boundary faces)"):
            return False
        inner = sum(1 for f in groups[grp][1] if len(fcells.get(key(f), [])) != 1)
        if inner:
            print(f"  ERROR: pair {name}: {inner} facets of its {what} {grp!r} are not on the boundary (not one cell each)")
            ok = False
    if not ok:
        return False
    sv = np.unique(np.array(groups[slave][1]).ravel())
    mfac = groups[master][1]
    mv = np.unique(np.array(mfac).ravel())
    if contact_mark[mv].any():
        print(f"  ERROR: pair {name}: the master {master!r} shares {int(contact_mark[mv].sum())} vertices with a contact surface "
              "(a slave or -contact_boundary): mmcontact refuses it")
        ok = False
    F, n, cen = master_facets(x, cells, mfac, fcells)
    fb, phi = project_slaves(x[sv], F, cen)
    facing = int(np.sum((phi == 1.0).any(axis=1)))
    # the gaps at the initial state x + u0 (affine: sum_j phi_j u0(X_mj) = u0(p)), on the reference pairing
    y = x + initial_displacement(opts, x, dim)
    mverts = np.array(mfac)[fb]  # slave vertex -> its facet's vertices
    p = np.einsum("sj,sjd->sd", phi, y[mverts])
    nn = n[fb]
    gap = np.sum(nn * (y[sv] - p), axis=1)
    j = int(np.argmin(gap))
    print(f"  pair {name}: slave {slave}, {len(sv)} vertices ({facing} facing a master vertex: node to node), on "
          f"{len({key(f) for f in mfac})} facets of master {master}; mu {mu:g}; smallest gap {gap[j]:.6g} at "
          f"({', '.join(f'{c:.4g}' for c in y[sv][j])})")
    if gap[j] < -1e-9 * hmin:
        print(f"  ERROR: pair {name}: slave vertex at ({', '.join(f'{c:.4g}' for c in y[sv][j])}) starts inside the master body "
              f"(gap {gap[j]:.3g})")
        ok = False
    # rigid bodies: the gap closes at n.(v_m - v_s), the master point's velocity from its vertices' bodies
    rate = np.sum(nn * (vel[sv] - np.einsum("sj,sjd->sd", phi, vel[mverts])), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(gap <= 0, 0.0, np.where(rate < 0, gap / -rate, np.inf))
    tc = t.min()
    if tc <= tmax:
        print(f"    rigid-body first contact t ~ {tc:.3g} (step {tc / dt:.0f}), from the bodies' v0 along the normals")
    else:
        print("    no contact before the end (rigid-body estimate from the bodies' v0)")
    return ok


def second_obstacles(obs, xref, owner, hmin):
    """Per rigid-contact vertex, the second obstacle that would get a row (docs/method.md section 8):
    the nearest other one (ties to the first listed) within h_c' at the reference position and not
    parallel to the first (|n1.n2| <= 1 - 1e-6); -1 if none."""
    if len(obs) < 2:
        return np.full(len(xref), -1)
    ref = np.array([o[1](xref) for o in obs])
    nrm = np.array([o[1].normal(xref) for o in obs])  # obstacles x vertices x dim
    n1 = nrm[owner, np.arange(len(xref))]
    cos = np.abs(np.einsum("bvd,vd->bv", nrm, n1))
    ok = (ref <= hmin) & (cos <= 1 - 1e-6) & (np.arange(len(obs))[:, None] != owner[None, :])
    d = np.where(ok, ref, np.inf)
    return np.where(ok.any(axis=0), np.argmin(d, axis=0), -1)


def check_rigid(obs, opts, x, cverts, hmin, vel, frictionless, dt, tmax, cp):
    """The rigid obstacles: per obstacle its contact vertices, smallest gap and first contact; corner rows."""
    ok = True
    dim = x.shape[1]
    xc = x[cverts]
    # assigned in the reference configuration; the gaps are those of the initial state x + u0
    ref = np.array([o[1](xc) for o in obs])  # obstacles x contact vertices
    owner = np.argmin(ref, axis=0)  # argmin takes the first of equal values: ties to the first listed
    srt = np.sort(ref, axis=0)
    second = second_obstacles(obs, xc, owner, hmin)
    xc = xc + initial_displacement(opts, xc, dim)
    dist = np.array([o[1](xc) for o in obs])
    near_ties = int(np.sum(srt[1] - srt[0] <= 1e-9 * hmin)) if len(obs) > 1 else 0
    grav = vec(opts, "gravity", dim, [0.0] * dim)
    v0 = vel[cverts]
    for k, (name, f, mu, ovel, start) in enumerate(obs):
        mine = owner == k
        dmin_all = dist[k].min()
        if dmin_all < 0:
            print(f"  ERROR: obstacle {name}: contact vertex at {xc[np.argmin(dist[k])]} inside it (signed distance {dmin_all:.3g})")
            ok = False
        line = f"  obstacle {name}: {int(mine.sum())} contact vertices, mu {mu:g}"
        if ovel.any():
            line += f", velocity {','.join(f'{v:g}' for v in ovel)} from t = {start:g} (|v| / c_p = {np.linalg.norm(ovel) / cp:.2g})"
        if mine.any():
            j = np.flatnonzero(mine)[np.argmin(dist[k][mine])]
            t = first_contact(f, xc[mine], v0[mine], grav, ovel, start, tmax, dt)
            line += f"; smallest gap {dist[k][j]:.4g} at ({', '.join(f'{c:.4g}' for c in xc[j])})"
            line += f"; rigid-body first contact t ~ {t:.3g} (step {t / dt:.0f})" if math.isfinite(t) else "; no contact before the end (rigid-body estimate)"
        print(line)
    if near_ties:
        print(f"  {near_ties} contact vertices equally near two obstacles (given to the first listed)")
    ncorner = int(np.sum(second >= 0))
    if ncorner and frictionless:
        per = ", ".join(f"{obs[b][0]} {int(np.sum(second == b))}" for b in range(len(obs)) if np.any(second == b))
        print(f"  corners: {ncorner} contact vertices within h_c' of a second obstacle get a row for it too "
              f"({len(cverts) + ncorner} rows; second rows against {per})")
    elif ncorner:
        print(f"  friction corners: {ncorner} contact vertices within h_c' of a second obstacle carry its "
              "Coulomb law too (-contact_formulation condensed only)")
    return ok, ncorner


def check(path):
    ok = True
    opts = read_options(path)
    print(f"== {path}")
    coords, groups = read_msh41(opts["mesh"])
    dim = max(d for d, _ in groups.values())
    cells = list({key(c): c for d, cs in groups.values() if d == dim for c in cs}.values())
    used = np.unique(np.array(cells).ravel())
    R, center = mesh_rotation(opts, dim)
    x = center + (coords[:, :dim] - center) @ R.T
    if not np.array_equal(R, np.eye(dim)):
        print(f"  mesh turned by -mesh_rotation {opts['mesh_rotation']} about ({', '.join(f'{c:g}' for c in center)})")
    print(f"  mesh {opts['mesh']}: {dim}D, groups " + ", ".join(f"{n} (dim {d}, {len(c)} cells)" for n, (d, c) in groups.items()))
    print(f"  vertices {len(used)}, dofs {dim * len(used)}")
    body_ok, cp, vel, vbody, _ = check_bodies(opts, groups, cells, dim, len(coords))
    ok = ok and body_ok
    dt, tmax = float(opts["ts_dt"]), float(opts["ts_max_time"])
    if opts.get("contact", "1").lower() in ("0", "false", "no", "off"):
        # linear elastodynamics: no contact boundary, no h_c'
        print(f"  contact off (-contact {opts['contact']}): no contact boundary; c_p {cp:.4g}, dt {dt:g}, "
              f"steps {tmax / dt:.0f} (to t = {tmax:g})")
        for n in [n for k in ("dirichlet", "traction") if opts.get(k) for n in opts[k].split(",")]:
            ok = check_group(groups, n, dim - 1, " (boundary faces)") and ok
        return ok
    obs = obstacles(opts, dim)
    prs = pairs(opts)
    cname = opts.get("contact_boundary", "contact")
    wanted = ([cname] if obs else []) + [n for k in ("dirichlet", "traction") if opts.get(k) for n in opts[k].split(",")]
    for n in wanted:
        ok = check_group(groups, n, dim - 1, " (boundary faces)") and ok
    if obs and cname not in groups:
        return False
    # the contact vertices: -contact_boundary's (with rigid obstacles) and every pair's slave vertices
    mark = np.zeros(len(coords), bool)
    cverts = np.unique(np.array(groups[cname][1]).ravel()) if obs else np.zeros(0, int)
    mark[cverts] = True
    nslave = 0
    for _, slave, _, _ in prs:
        if slave in groups and groups[slave][0] == dim - 1:
            sv = np.unique(np.array(groups[slave][1]).ravel())
            if mark[sv].any():
                print(f"  ERROR: slave {slave!r} shares {int(mark[sv].sum())} vertices with another contact surface: mmcontact refuses it")
                ok = False
            mark[sv] = True
            nslave += len(sv)
    if not mark.any():
        print("  ERROR: no contact vertices")
        return False
    hmin = layer_diameter(x, cells, mark)
    cfl = cp * dt / hmin
    print(f"  contact vertices {int(mark.sum())} ({len(cverts)} against rigid obstacles, {nslave} slave); c_p {cp:.4g}"
          f"{' (the largest over the bodies)' if 'bodies' in opts else ''}, h_c' {hmin:.4g}, dt {dt:g}, "
          f"c_p dt / h_c' {cfl:.3f}, steps {tmax / dt:.0f} (to t = {tmax:g})")
    if "bodies" in opts:
        # the time-step bound holds body by body: each body's c_p against its own contact layer
        cfl = body_cfl(opts, x, cells, mark, vbody, dt)
        print(f"  body by body, the largest c_p dt / h_c' {cfl:.3f}")
    if cfl > CFL_MAX:
        print(f"  ERROR: c_p dt / h_c' above {CFL_MAX}")
        ok = False
    # frictionless when every obstacle's and pair's mu is 0 (mmcontact: one row per node otherwise)
    frictionless = max([o[2] for o in obs] + [p[3] for p in prs] + [0.0]) == 0
    if obs:
        rigid_ok, _ = check_rigid(obs, opts, x, cverts, hmin, vel, frictionless, dt, tmax, cp)
        ok = ok and rigid_ok
    fcells = facet_cells(cells) if prs else {}
    for pair in prs:
        ok = check_pair(pair, opts, groups, x, cells, fcells, mark, hmin, vel, dt, tmax) and ok
    return ok


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    results = [check(p) for p in sys.argv[1:]]
    sys.exit(0 if all(results) else 1)
