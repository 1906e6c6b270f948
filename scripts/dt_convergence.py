"""dt-convergence study on a fixed mesh (Theorem 5.2 of Doyen & Ern 2011, docs/method.md section 7).

usage: /usr/bin/python3 -s scripts/dt_convergence.py OPTIONS_FILE [--dt DT] [--levels 4] [--np 2]
           [--extra "-contact 0 -ts_max_time 0.1"] [--every 1] [--out DIR] [--exe ./mmcontact]

Run it from the repository root (the options files' paths are relative to it). It runs the case
at dt, dt/2, ..., dt/2^(levels-1) on the same mesh (level l: -ts_dt dt/2^l, -ts_max_steps N 2^l,
-output_every every 2^l, so that every level writes snapshots at the same times), into
DIR/level_l, and compares each level with the finest at those common times:

- energy: max over the common snapshots of sqrt(a(e_u, e_u) + (M* e_v, e_v)), the scheme's own
  energy norm (docs/method.md section 4) of the displacement and velocity errors, with A the P1
  stiffness (plane strain in 2D) and M* the consistent mass without the normal dof of each contact
  node (M with -mass standard or -contact 0);
- energy_M: the same with the full consistent mass M, i.e. counting the contact-normal velocity,
  which the modified mass makes a backward difference (no inertia) and Theorem 5.2 does not cover;
- L2: max over the common snapshots of sqrt(e_u^T M e_u);
- force: max over every step of the coarsest run of |force_normal - force_normal of the finest|
  (history.csv).
Each error is relative to the finest run's largest value of the same norm over the same times.
The observed rate of level l is log2(d_l / d_{l+1}), d_l the same norm of u_l - u_{l+1}: the
exponent p of a power law e = C dt^p, estimated without the exact solution. (log2(e_l / e_{l+1})
with errors against the finest is biased at the last pair, whose reference is itself off by a
comparable amount: it gives log2 5 = 2.32 for p = 2.)

The runs use -mass modified, the theorem's, unless the case sets -mass standard.
Writes DIR/dt_convergence.csv (the table), DIR/dt_convergence.png (log-log) and prints the table.
Before comparing it checks that its A and M* give the run's own elastic and kinetic energies.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mmrun import Solution, case_options, obstacles, read_history, run_mmcontact, split_extra  # noqa: E402

METRICS = ["energy", "energy_M", "L2", "force"]


def p1_geometry(vertices, cells):
    """Gradients of the P1 shape functions (cells x d+1 x d) and the cell volumes."""
    d = vertices.shape[1]
    x = vertices[cells]  # cells x d+1 x d
    jac = np.transpose(x[:, 1:] - x[:, :1], (0, 2, 1))  # columns: edges from vertex 0
    inv = np.linalg.inv(jac)  # row a: gradient of the shape function of vertex a+1
    grads = np.concatenate([-inv.sum(axis=1, keepdims=True), inv], axis=1)
    vol = np.abs(np.linalg.det(jac)) / math.factorial(d)
    return grads, vol


def lame(E, nu):
    """Lame constants; in 2D these are plane strain's (the 2D strain energy is then the 3D one)."""
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def stiffness_form(u, cells, grads, vol, lam, mu):
    """a(u, u) = sum over cells of vol (lam tr(eps)^2 + 2 mu eps:eps), for each snapshot of u
    (snapshots x vertices x d): the quadratic form of the P1 stiffness A, never assembled."""
    g = np.einsum("tcai,caj->tcij", u[:, cells], grads)
    eps = 0.5 * (g + np.swapaxes(g, 2, 3))
    tr = np.trace(eps, axis1=2, axis2=3)
    return np.einsum("c,tc->t", vol, lam * tr ** 2 + 2 * mu * np.einsum("tcij,tcij->tc", eps, eps))


def mass_form(w, cells, vol, rho):
    """(M w, w) for the consistent P1 mass M_ab = rho vol (1 + delta_ab) / ((d+1)(d+2)) per
    component, for each snapshot of w: rho vol / ((d+1)(d+2)) ((sum_a w_a)^2 + sum_a w_a^2)."""
    d = w.shape[2]
    wc = w[:, cells]  # snapshots x cells x d+1 x d
    per_cell = (wc.sum(axis=2) ** 2).sum(axis=2) + (wc ** 2).sum(axis=(2, 3))
    return rho / ((d + 1) * (d + 2)) * per_cell @ vol


def contact_normals(opts, sol):
    """Unit normal of each contact node's obstacle at its reference position (vertices x d, zero
    off the contact boundary): the gradient of the obstacle's signed distance, by central
    differences (exact for these shapes up to round-off). It is the direction whose mass M* drops."""
    normals = np.zeros_like(sol.vertices)
    nodes = sol.contact_nodes
    if len(nodes) == 0:
        return normals
    obs = obstacles(opts, sol.dim)
    x = sol.vertices[nodes]
    h = 1e-6 * max(1.0, np.abs(sol.vertices).max())
    for k, (_, f, _, _, _) in enumerate(obs):
        mine = sol.obstacle[nodes] == k
        if not mine.any():
            continue
        xs = x[mine]
        g = np.stack([(f(xs + h * e) - f(xs - h * e)) / (2 * h) for e in np.eye(sol.dim)], axis=1)
        normals[nodes[mine]] = g / np.linalg.norm(g, axis=1, keepdims=True)
    return normals


def drop_normal_velocity(v, normals):
    """The velocity M* sees: the contact nodes' normal component removed (normals zero elsewhere)."""
    return v - np.einsum("tvi,vi->tv", v, normals)[:, :, None] * normals[None]


class Norms:
    """The norms of the study on one mesh, with the case's material and mass."""

    def __init__(self, sol, opts):
        self.cells = sol.cells
        self.grads, self.vol = p1_geometry(sol.vertices, sol.cells)
        self.lam, self.mu = lame(float(opts.get("E", 1)), float(opts.get("nu", 0.3)))
        self.rho = float(opts.get("rho", 1))
        modified = opts.get("mass", "modified") == "modified" and opts.get("contact", "1") not in ("0", "false")
        self.normals = contact_normals(opts, sol) if modified else np.zeros_like(sol.vertices)

    def a(self, u):
        return stiffness_form(u, self.cells, self.grads, self.vol, self.lam, self.mu)

    def m(self, w):
        return mass_form(w, self.cells, self.vol, self.rho)

    def m_star(self, v):
        return self.m(drop_normal_velocity(v, self.normals))

    def all(self, u, v):
        """Per snapshot: energy (M*), energy_M (M) and L2 norms of (u, v)."""
        au, mu_ = self.a(u), self.m(u)
        return {"energy": np.sqrt(au + self.m_star(v)), "energy_M": np.sqrt(au + self.m(v)), "L2": np.sqrt(mu_)}


def check_energies(norms, sol, hist, label):
    """The script's A and M* against the run's own elastic and kinetic energies at the snapshot
    times: a mismatch means the norm is not the scheme's (wrong material, mass or normals)."""
    rows = match_times(hist["time"], sol.time, label)
    elastic, kinetic = 0.5 * norms.a(sol.displacement), 0.5 * norms.m_star(sol.velocity)
    scale = max(np.abs(hist["total"]).max(), 1e-300)
    mismatch = max(np.abs(elastic - hist["elastic"][rows]).max(), np.abs(kinetic - hist["kinetic"][rows]).max()) / scale
    if mismatch > 1e-8:
        sys.exit(f"{label}: the script's energies differ from history.csv's by {mismatch:.2e} of the energy "
                 "(E, nu, rho, -mass or the obstacles not read as the run used them?)")
    return mismatch


def match_times(times, wanted, label, tol=None):
    """Row of `times` at each of the `wanted` times; stops if one is missing."""
    tol = tol if tol is not None else 1e-9 * max(1.0, np.abs(wanted).max())
    idx = np.clip(np.searchsorted(times, wanted), 1, len(times) - 1)
    idx = np.where(np.abs(times[idx - 1] - wanted) <= np.abs(times[idx] - wanted), idx - 1, idx)
    bad = np.abs(times[idx] - wanted) > tol
    if bad.any():
        sys.exit(f"{label}: no output at t = {wanted[bad][0]:.12g} (nearest {times[idx][bad][0]:.12g}): "
                 "the levels' times do not agree (a step rejected and retried with a smaller dt?)")
    return idx


def final_steps(opts, dt):
    """Steps of the coarsest run: -ts_max_time / dt, which must be a whole number (to 1e-9), so that
    every level stops at the same time (accumulated round-off otherwise adds a step to some)."""
    if "ts_max_time" not in opts:
        sys.exit("the case needs -ts_max_time (in the options file or --extra)")
    t_end = float(opts["ts_max_time"])
    n = round(t_end / dt)
    if n < 1 or abs(n * dt - t_end) > 1e-9 * t_end:
        sys.exit(f"-ts_max_time {t_end:g} is not a whole number of steps of dt = {dt:g}")
    return n


def run_levels(args, opts, extra):
    """Runs every level (unless --no-run) and returns their output directories."""
    dirs = []
    n0 = final_steps(opts, args.dt)
    for lev in range(args.levels):
        k = 2 ** lev
        outdir = os.path.join(args.out, f"level_{lev}")
        dirs.append(outdir)
        if args.no_run:
            continue
        print(f"level {lev}: dt = {args.dt / k:.6g}, {n0 * k} steps, output every {args.every * k}", flush=True)
        run_mmcontact(args.exe, args.np, args.options_file,
                      extra + ["-ts_dt", repr(args.dt / k), "-ts_max_steps", str(n0 * k),
                               "-output_every", str(args.every * k)], outdir, args.mpiexec)
    return dirs


def load_levels(dirs, opts):
    """Solutions and histories of the levels; checks that their snapshot times agree and that each
    ran at its constant dt."""
    sols = [Solution(d) for d in dirs]
    hists = [read_history(d) for d in dirs]
    t0 = sols[0].time
    for lev, (s, h) in enumerate(zip(sols, hists)):
        if len(s.time) != len(t0) or np.abs(s.time - t0).max() > 1e-9 * max(1.0, t0.max()):
            sys.exit(f"level {lev}: snapshot times differ from level 0's ({len(s.time)} against {len(t0)} "
                     "snapshots): a step rejected and retried with a smaller dt?")
        s.reorder_like(sols[-1], f"level {lev}")
        dts = h["dt"][1:]
        if np.abs(dts - dts[0]).max() > 1e-9 * dts[0]:
            sys.exit(f"level {lev}: dt varied from {dts.min():.6g} to {dts.max():.6g} (rejected steps): "
                     "the levels are not at dt / 2^l")
    return sols, hists


def errors(norms, a, b, ha, hb, force_times):
    """Largest norms of a - b over the common snapshots, and of the force difference over force_times."""
    e = norms.all(a.displacement - b.displacement, a.velocity - b.velocity)
    out = {k: v.max() for k, v in e.items()}
    fa = ha["force_normal"][match_times(ha["time"], force_times, "history")]
    fb = hb["force_normal"][match_times(hb["time"], force_times, "history")]
    out["force"] = np.abs(fa - fb).max()
    return out


def study(sols, hists, opts):
    """The table: one row per level, errors against the finest and differences to the next level,
    relative to the finest's largest norms; rates from the successive differences."""
    norms = Norms(sols[-1], opts)
    for lev, (s, h) in enumerate(zip(sols, hists)):
        check_energies(norms, s, h, f"level {lev}")
    ref, href = sols[-1], hists[-1]
    force_times = hists[0]["time"]  # every step of the coarsest run is a step of every level
    own = norms.all(ref.displacement, ref.velocity)
    scale = {k: max(v.max(), 1e-300) for k, v in own.items()}
    scale["force"] = max(np.abs(href["force_normal"][match_times(href["time"], force_times, "history")]).max(), 1e-300)
    rows = []
    for lev in range(len(sols)):
        row = {"level": lev, "dt": hists[lev]["dt"][1], "steps": len(hists[lev]) - 1}
        vs_ref = errors(norms, sols[lev], ref, hists[lev], href, force_times)
        nxt = errors(norms, sols[lev], sols[lev + 1], hists[lev], hists[lev + 1], force_times) if lev + 1 < len(sols) else None
        for k in METRICS:
            row[f"{k}_error"] = vs_ref[k] / scale[k] if lev + 1 < len(sols) else float("nan")
            row[f"{k}_diff"] = nxt[k] / scale[k] if nxt else float("nan")
        rows.append(row)
    for lev, row in enumerate(rows):
        for k in METRICS:
            nxt = rows[lev + 1][f"{k}_diff"] if lev + 1 < len(rows) else float("nan")
            row[f"{k}_rate"] = math.log2(row[f"{k}_diff"] / nxt) if nxt > 0 and row[f"{k}_diff"] > 0 else float("nan")
            after = rows[lev + 1][f"{k}_error"] if lev + 1 < len(rows) else float("nan")
            row[f"{k}_ratio_vs_finest"] = (math.log2(row[f"{k}_error"] / after)
                                           if after > 0 and row[f"{k}_error"] > 0 else float("nan"))
    return rows, scale, len(ref.time)


def fmt(x, spec):
    return "-" if x is None or not math.isfinite(x) else format(x, spec)


def print_table(rows, scale, nsnap):
    force = f"{scale['force']:.4g}" if scale["force"] > 1e-300 else "0: no contact force"
    print(f"\nerrors against the finest level (dt = {rows[-1]['dt']:.6g}), relative to its largest norm "
          f"(energy {scale['energy']:.4g}, energy_M {scale['energy_M']:.4g}, L2 {scale['L2']:.4g}, "
          f"force {force}); max over {nsnap} common snapshots (force: every step of level 0)")
    print("rate: log2 of the ratio of successive differences |u_l - u_l+1| / |u_l+1 - u_l+2|")
    head = f"{'level':>5} {'dt':>10} {'steps':>6}" + "".join(f" {k + ' err':>12} {'rate':>6}" for k in METRICS)
    print(head)
    for r in rows:
        print(f"{r['level']:>5} {r['dt']:>10.4g} {r['steps']:>6}"
              + "".join(f" {fmt(r[k + '_error'], '.3e'):>12} {fmt(r[k + '_rate'], '.2f'):>6}" for k in METRICS))


def write_csv(rows, scale, path):
    cols = ["level", "dt", "steps"] + [f"{k}_{s}" for k in METRICS for s in ("error", "diff", "rate", "ratio_vs_finest")]
    cols += [f"{k}_scale" for k in METRICS]
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            vals = [r.get(c, scale.get(c[:-6]) if c.endswith("_scale") else None) for c in cols]
            f.write(",".join(str(v) if isinstance(v, int) else repr(float(v)) for v in vals) + "\n")


def plot(rows, path, title):
    """Left: errors against the finest; right: differences to the next level, with dt and dt^2 guides."""
    dt = np.array([r["dt"] for r in rows])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    labels = {"energy": "energy norm (A, M*)", "energy_M": "energy norm (A, M)", "L2": "L2 of displacement",
              "force": "contact force history"}
    for ax, kind, what in ((axes[0], "error", "error against the finest level"), (axes[1], "diff", "difference to the next level (dt/2)")):
        ys = []
        for k in METRICS:
            y = np.array([r[f"{k}_{kind}"] for r in rows])
            ok = np.isfinite(y) & (y > 0)
            if ok.any():
                ax.loglog(dt[ok], y[ok], "o-", label=labels[k])
                ys.append(y[ok])
        if ys:
            top = max(y[0] for y in ys)
            x0 = dt[0]
            for p, style in ((1, ":"), (2, "--")):
                ax.loglog(dt[:-1], top * (dt[:-1] / x0) ** p, "k" + style, lw=0.8, label=f"dt^{p}")
        ax.set_xlabel("dt")
        ax.set_title(f"relative {what}")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("options_file")
    ap.add_argument("--dt", type=float, help="coarsest dt (default: the case's -ts_dt)")
    ap.add_argument("--levels", type=int, default=4, help="runs at dt, dt/2, ..., dt/2^(levels-1) (>= 3)")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks per run")
    ap.add_argument("--exe", default="./mmcontact")
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--extra", default="", help='options added to every run, e.g. "-contact 0 -ts_max_time 0.1"')
    ap.add_argument("--every", type=int, default=1, help="snapshot every this many steps of the coarsest run")
    ap.add_argument("--out", help="output directory (default output/dt_convergence/CASE)")
    ap.add_argument("--no-run", action="store_true", help="analyse the levels already in --out")
    args = ap.parse_args()
    if args.levels < 3:
        ap.error("--levels must be at least 3: a rate needs two differences")
    if args.every < 1:
        ap.error("--every must be at least 1")
    extra = split_extra(args.extra)
    opts = case_options(args.options_file, extra)
    # Theorem 5.2 is the modified mass's; the norms rebuild M* in numpy for it and the standard
    # mass, not for the redistributed default (its node blocks come from a global solve)
    if "mass" not in opts:
        extra += ["-mass", "modified"]
        opts = case_options(args.options_file, extra)
    if opts["mass"] not in ("modified", "standard"):
        sys.exit(f"-mass {opts['mass']}: this study rebuilds M* for -mass modified (the theorem's) and standard; "
                 "add --extra \"-mass modified\"")
    if args.dt is None:
        args.dt = float(opts["ts_dt"])
    case = os.path.splitext(os.path.basename(args.options_file))[0]
    args.out = args.out or os.path.join("output", "dt_convergence", case)
    dirs = run_levels(args, opts, extra)
    sols, hists = load_levels(dirs, opts)
    rows, scale, nsnap = study(sols, hists, opts)
    print_table(rows, scale, nsnap)
    csv = os.path.join(args.out, "dt_convergence.csv")
    png = os.path.join(args.out, "dt_convergence.png")
    write_csv(rows, scale, csv)
    plot(rows, png, f"{case} {args.extra}".strip())
    print(f"table: {csv}\nplot: {png}")


if __name__ == "__main__":
    main()
