"""Plots the contact pressure of a run from its OUTPUT_DIR/solution.h5.

usage: /usr/bin/python3 -s scripts/plot_contact.py OUTPUT_DIR [--point x,y] [--full] [--normal nx,ny,nz]
           [-o FILE.png]

2D run: the pressure as a space-time map along the contact boundary (arc length against time),
and the pressure against time at one contact node: the node nearest to --point (reference
position), by default the node of peak pressure. The contact boundary is ordered by chaining its
edges (the boundary edges of the mesh whose two vertices are contact nodes), so a curved or closed
boundary, or several pieces, come out in order; pieces follow each other along the axis, separated
by a gap, and a closed piece is cut opposite its peak. The map shows the part of the boundary
that ever carries pressure, and as much again around it (--full: all of it).
3D run: the pressure at the snapshot of peak total contact force (pressure times nodal area),
drawn on the contact surface projected on the obstacle plane, beside the contact force history.
The plane's normal is --normal, by default fitted to the deformed positions of the nodes in
contact in all the snapshots.

The snapshots are those of -output_every: a map needs a run with a small -output_every.
Writes OUTPUT_DIR/contact_pressure.png (or -o) and prints its path."""
import argparse
import itertools
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mmrun import Solution  # noqa: E402


def boundary_facets(cells):
    """The facets (edges in 2D, triangles in 3D) that belong to one cell only, as vertex lists."""
    d1 = cells.shape[1]
    faces = np.concatenate([cells[:, list(c)] for c in itertools.combinations(range(d1), d1 - 1)])
    key = np.sort(faces, axis=1)
    uniq, inverse, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return uniq[count == 1]


def contact_facets(sol):
    """Boundary facets whose vertices are all contact nodes: the contact boundary."""
    facets = boundary_facets(sol.cells)
    is_contact = sol.obstacle >= 0
    return facets[is_contact[facets].all(axis=1)]


def chain_edges(edges, vertices):
    """Orders the contact boundary's edges into chains of vertices, each an open path (from the end
    with the smallest coordinates) or a closed loop (first vertex repeated at its end). A vertex
    where more than two edges meet ends the chain there; the rest becomes further chains."""
    adj = {}
    for a, b in edges:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, []).append(a)
    unused = {frozenset(e) for e in map(tuple, edges)}
    chains = []

    def walk(start):
        path = [start]
        while True:
            nxt = [w for w in adj[path[-1]] if frozenset((path[-1], w)) in unused]
            if not nxt:
                return path
            unused.discard(frozenset((path[-1], nxt[0])))
            path.append(nxt[0])
            if nxt[0] == start or len(adj[nxt[0]]) > 2:
                return path

    def lexkey(v):
        return tuple(vertices[v])

    while unused:
        touched = {v for e in unused for v in e}
        ends = [v for v in touched if sum(frozenset((v, w)) in unused for w in adj[v]) != 2]
        chains.append(walk(min(ends or touched, key=lexkey)))
    return chains


def cut_loop(chain, peak):
    """A closed chain rotated so that `peak` (per vertex) is largest in its middle: the cut falls
    opposite the contact zone. Open chains are returned as they are."""
    if len(chain) < 3 or chain[0] != chain[-1]:
        return chain
    loop = chain[:-1]
    k = int(np.argmax(peak[loop]))
    start = (k + len(loop) // 2) % len(loop)
    loop = loop[start:] + loop[:start]
    return loop + [loop[0]]


def contact_chains(sol):
    """Chains of contact nodes along the boundary (2D), closed loops cut opposite the peak."""
    edges = contact_facets(sol)
    if len(edges) == 0:
        sys.exit(f"{sol.path}: no contact boundary edges (was contact on? -contact 0 runs have none)")
    peak = sol.pressure.max(axis=0)
    return [cut_loop(c, peak) for c in chain_edges(edges, sol.vertices)]


def arc_lengths(sol, chains):
    """Arc length of each chain's vertices along the reference boundary, the chains laid end to end
    with a gap of 5% of the total length between them."""
    lengths = [np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(sol.vertices[c], axis=0), axis=1))]) for c in chains]
    gap = 0.05 * sum(s[-1] for s in lengths)
    out, offset = [], 0.0
    for s in lengths:
        out.append(s + offset)
        offset += s[-1] + gap
    return out


def pressure_limit(*sols):
    """A common colour scale for the maps of several runs."""
    return max(max(s.pressure.max() for s in sols), 1e-300)


def draw_space_time(ax, sol, vmax=None, mark=None, zoom=True):
    """Pressure (colour) against arc length along the contact boundary and time; zoom: the arc
    length axis shows the part that ever carries pressure and as much again around it."""
    chains = contact_chains(sol)
    svals = arc_lengths(sol, chains)
    vmax = vmax or pressure_limit(sol)
    mesh = None
    for c, s in zip(chains, svals):
        S, T = np.meshgrid(s, sol.time)
        mesh = ax.pcolormesh(S, T, sol.pressure[:, c], shading="gouraud", cmap="inferno", vmin=0, vmax=vmax)
    if mark is not None:
        for c, s in zip(chains, svals):
            for k in np.flatnonzero(np.array(c) == mark)[:1]:
                ax.axvline(s[k], color="c", ls="--", lw=0.8)
    s_all = np.concatenate(svals)
    ever = pressed_nodes(sol.pressure[:, np.concatenate(chains)].max(axis=0))
    if zoom and ever.any():
        lo, hi = s_all[ever].min(), s_all[ever].max()
        half = max(hi - lo, 4 * np.diff(s_all).clip(0).max()) / 2
        ax.set_xlim(max(lo - half, s_all.min()), min(hi + half, s_all.max()))
    ax.set_xlabel("arc length along the contact boundary (reference)")
    ax.set_ylabel("time")
    return mesh


def chosen_node(sol, point):
    """The contact node nearest to point (reference position), or the node of peak pressure."""
    nodes = sol.contact_nodes
    if point is None:
        return int(np.unravel_index(np.argmax(sol.pressure), sol.pressure.shape)[1])
    return int(nodes[np.argmin(np.linalg.norm(sol.vertices[nodes] - point, axis=1))])


def nodal_areas(sol, facets):
    """Area (3D) or length (2D) of the contact boundary around each vertex: a third (half) of each
    facet's measure to each of its vertices."""
    x = sol.vertices[facets]
    if sol.dim == 3:
        meas = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
    else:
        meas = np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
    area = np.zeros(len(sol.vertices))
    np.add.at(area, facets.ravel(), np.repeat(meas / facets.shape[1], facets.shape[1]))
    return area


def peak_snapshot(sol, facets):
    """Snapshot of largest total contact force sum_i p_i area_i."""
    force = sol.pressure @ nodal_areas(sol, facets)
    return int(np.argmax(force)), force


def pressed_nodes(p):
    """Nodes carrying pressure: above round-off (nodes off the obstacle show about 1e-13 of the peak)."""
    return p > 1e-8 * max(p.max(), 1e-300)


def plane_axes(sol, snap, normal=None):
    """Unit normal of the obstacle plane and two tangents: the normal given, or the one of the
    plane fitted (least squares) through the deformed positions of the nodes in contact, taken at
    every snapshot (at the peak alone a chattering run may touch at one or two nodes)."""
    if normal is None:
        pressed = pressed_nodes(sol.pressure)
        x = (sol.vertices[None] + sol.displacement)[pressed]
        if len(x) < 3:
            sys.exit(f"{sol.path}: {len(x)} contact points in all the snapshots: give the plane with --normal")
        _, sv, vt = np.linalg.svd(x - x.mean(axis=0))
        if sv[1] <= 1e-9 * max(sv[0], 1e-300):
            sys.exit(f"{sol.path}: the contact points are on a line: give the plane with --normal")
        normal = vt[2]
        # a fitted normal has no sign: point it from the plane into the body, as mmcontact's do
        centroid = (sol.vertices + sol.displacement[snap]).mean(axis=0)
        if normal @ (centroid - x.mean(axis=0)) < 0:
            normal = -normal
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    e = np.eye(3)[np.argmin(np.abs(n))]  # the axis least aligned with n gives a well-posed tangent
    t1 = e - (e @ n) * n
    t1 /= np.linalg.norm(t1)
    return n, t1, np.cross(n, t1)


def draw_plane_map(ax, sol, snap=None, normal=None, vmax=None):
    """3D: the pressure on the contact surface around the contact zone at snapshot snap (default:
    peak force), projected on the obstacle plane. Returns the mappable and the snapshot."""
    facets = contact_facets(sol)
    if len(facets) == 0:
        sys.exit(f"{sol.path}: no contact boundary faces (was contact on?)")
    if snap is None:
        snap, _ = peak_snapshot(sol, facets)
    n, t1, t2 = plane_axes(sol, snap, normal)
    p = sol.pressure[snap]
    # the contact zone and the ring of faces around it, where the pressure falls to zero
    zone = facets[pressed_nodes(p)[facets].any(axis=1)]
    near = np.zeros(len(p), bool)
    near[zone.ravel()] = True
    tris = facets[near[facets].any(axis=1)]
    if len(tris) == 0:
        sys.exit(f"{sol.path}: no contact at t = {sol.time[snap]:.6g}")
    x = sol.vertices + sol.displacement[snap]
    px, py = x @ t1, x @ t2
    mesh = ax.tripcolor(px, py, tris, p, shading="gouraud", cmap="inferno", vmin=0, vmax=vmax or max(p.max(), 1e-300))
    ax.triplot(px, py, tris, color="w", lw=0.2, alpha=0.4)
    shown = np.unique(tris)
    pad = 0.05 * max(np.ptp(px[shown]), np.ptp(py[shown]))
    ax.set_xlim(px[shown].min() - pad, px[shown].max() + pad)
    ax.set_ylim(py[shown].min() - pad, py[shown].max() + pad)
    ax.set_aspect("equal")
    fmt = lambda v: "(" + ", ".join(f"{0.0 if abs(c) < 5e-3 else c:.2f}" for c in v) + ")"  # noqa: E731
    ax.set_xlabel(f"along {fmt(t1)}")
    ax.set_ylabel(f"along {fmt(t2)}")
    ax.set_title(f"t = {sol.time[snap]:.4g}, plane normal {fmt(n)}", fontsize=9)
    return mesh, snap


def force_history(outdir):
    """(time, force_normal) from history.csv, or None if it is not there."""
    path = os.path.join(outdir, "history.csv")
    if not os.path.exists(path):
        return None
    h = np.genfromtxt(path, delimiter=",", names=True, ndmin=1)
    return h["time"], h["force_normal"]


def plot_2d(sol, outdir, point, out, zoom):
    node = chosen_node(sol, point)
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw={"width_ratios": [1.3, 1]})
    mesh = draw_space_time(ax[0], sol, mark=node, zoom=zoom)
    fig.colorbar(mesh, ax=ax[0], label="contact pressure")
    ax[0].set_title("contact pressure along the contact boundary")
    where = ", ".join(f"{c:.4g}" for c in sol.vertices[node])
    ax[1].plot(sol.time, sol.pressure[:, node], ".-", ms=3)
    ax[1].set_title(f"pressure at the contact node at ({where})" + ("" if point is not None else ": the peak"), fontsize=10)
    ax[1].set_xlabel("time")
    ax[1].set_ylabel("contact pressure")
    ax[1].grid(alpha=0.3)
    fig.suptitle(os.path.abspath(outdir), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_3d(sol, outdir, normal, out):
    fig, ax = plt.subplots(1, 2, figsize=(12, 5), gridspec_kw={"width_ratios": [1.2, 1]})
    mesh, snap = draw_plane_map(ax[0], sol, normal=normal)
    fig.colorbar(mesh, ax=ax[0], label="contact pressure")
    hist = force_history(outdir)
    if hist is not None:
        ax[1].plot(hist[0], hist[1], label="force_normal (history.csv)")
    _, force = peak_snapshot(sol, contact_facets(sol))
    ax[1].plot(sol.time, force, "o", ms=3, label="sum of pressure x nodal area (snapshots)")
    ax[1].axvline(sol.time[snap], color="c", ls="--", lw=0.8, label="the map's snapshot")
    ax[1].set_xlabel("time")
    ax[1].set_title("total normal contact force")
    ax[1].grid(alpha=0.3)
    ax[1].legend(fontsize=7)
    fig.suptitle(os.path.abspath(outdir), fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def parse_vector(text, what):
    try:
        return np.array([float(c) for c in text.split(",")])
    except ValueError:
        sys.exit(f"{what} {text!r}: comma-separated numbers")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("output_dir")
    ap.add_argument("--point", help="2D: x,y of the point whose pressure is plotted against time (default: the peak)")
    ap.add_argument("--normal", help="3D: the obstacle plane's normal nx,ny,nz (default: fitted)")
    ap.add_argument("--full", action="store_true", help="2D: the whole contact boundary (default: around the contact zone)")
    ap.add_argument("-o", "--output", help="PNG file (default OUTPUT_DIR/contact_pressure.png)")
    args = ap.parse_args()
    sol = Solution(args.output_dir)
    out = args.output or os.path.join(args.output_dir, "contact_pressure.png")
    if len(sol.time) < 3:
        print(f"note: {len(sol.time)} snapshots only: run with a small -output_every for a map", file=sys.stderr)
    if sol.dim == 2:
        point = parse_vector(args.point, "--point") if args.point else None
        if point is not None and len(point) != 2:
            sys.exit("--point needs x,y")
        plot_2d(sol, args.output_dir, point, out, not args.full)
    else:
        normal = parse_vector(args.normal, "--normal") if args.normal else None
        if normal is not None and (len(normal) != 3 or not np.linalg.norm(normal) > 0):
            sys.exit("--normal needs three numbers, not all zero")
        plot_3d(sol, args.output_dir, normal, out)
    print(f"plot: {out}")


if __name__ == "__main__":
    main()
