"""Runs a case with the modified mass and with the standard mass, and draws both side by side.

usage: /usr/bin/python3 -s scripts/compare_mass.py OPTIONS_FILE [--np 2] [--every 1]
           [--extra "..."] [--out DIR] [--exe ./mmcontact] [--full]

Run it from the repository root (the options files' paths are relative to it). The two runs
(`-mass modified`, the default, and `-mass standard`, each with -output_every EVERY) go to
DIR/modified and DIR/standard (default DIR: output/compare_mass/CASE). The figure
DIR/compare_mass.png has the two contact-force histories (history.csv force_normal) on one axes
and, below, the two contact-pressure maps with one colour scale, the modified run's peak pressure
(the standard run's higher values saturate): in 2D the space-time maps along
the contact boundary (scripts/plot_contact.py), in 3D the maps on the obstacle plane at each run's
peak force. This is what the method is for: with the standard mass the contact nodes keep their
inertia, and the force and the pressure chatter; with the modified mass they are one smooth pulse.
The script prints how much each force history oscillates: its total variation over twice its peak
(1 for a single pulse that rises and falls once)."""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mmrun import Solution, read_history, run_mmcontact, split_extra  # noqa: E402
from plot_contact import draw_plane_map, draw_space_time, pressure_limit  # noqa: E402

MASSES = ("modified", "standard")


def run_both(args, extra):
    """Runs the case with each mass; returns the output directories."""
    dirs = {}
    for mass in MASSES:
        dirs[mass] = os.path.join(args.out, mass)
        if not args.no_run:
            print(f"running with the {mass} mass", flush=True)
            run_mmcontact(args.exe, args.np, args.options_file,
                          extra + ["-mass", mass, "-output_every", str(args.every)], dirs[mass], args.mpiexec)
    return dirs


def oscillation(force):
    """Total variation of a force history over twice its peak: 1 for one pulse, more if it chatters."""
    peak = np.abs(force).max()
    return np.abs(np.diff(force)).sum() / (2 * peak) if peak > 0 else 0.0


def draw(dirs, title, out, zoom):
    """The figure. The force axis and the colour scale are set by the modified run (its peak force
    times 3, its peak pressure): the standard run's spikes, often ten times higher, would otherwise
    flatten the modified run's pulse into the axis. What is clipped is said on the figure."""
    sols = {m: Solution(d) for m, d in dirs.items()}
    hists = {m: read_history(d) for m, d in dirs.items()}
    fig = plt.figure(figsize=(12, 8.5), layout="constrained")
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 1.3])
    axf = fig.add_subplot(grid[0, :])
    for m in MASSES[::-1]:  # the modified run drawn last, on top
        h = hists[m]
        f = h["force_normal"]
        axf.plot(h["time"], f, lw=1.6 if m == "modified" else 0.8, color="C0" if m == "modified" else "C1",
                 label=f"{m} mass: peak {f.max():.4g}, oscillation {oscillation(f):.2f}")
    fmax = hists["modified"]["force_normal"].max()
    if fmax > 0 and hists["standard"]["force_normal"].max() > 3 * fmax:
        axf.set_ylim(-0.05 * 3 * fmax, 3 * fmax)
        axf.set_title("contact force (history.csv; axis clipped at 3 x the modified peak)")
    else:
        axf.set_title("contact force (history.csv)")
    axf.set_xlabel("time")
    axf.set_ylabel("total normal contact force")
    axf.grid(alpha=0.3)
    axf.legend(fontsize=8, loc="upper right")
    vmax = pressure_limit(sols["modified"])
    mesh = None
    for k, m in enumerate(MASSES):
        ax = fig.add_subplot(grid[1, k])
        peak = sols[m].pressure.max()
        clipped = f" (peak {peak:.3g}, clipped)" if peak > vmax * (1 + 1e-9) else ""
        if sols[m].dim == 2:
            mesh = draw_space_time(ax, sols[m], vmax=vmax, zoom=zoom)
            ax.set_title(f"{m} mass: contact pressure{clipped}", fontsize=9)
        else:
            mesh, snap = draw_plane_map(ax, sols[m], vmax=vmax)
            ax.set_title(f"{m} mass at peak force, t = {sols[m].time[snap]:.4g}{clipped}", fontsize=9)
    fig.colorbar(mesh, ax=fig.axes[1:], label="contact pressure (scale: the modified run's peak)",
                 extend="max")
    fig.suptitle(title, fontsize=10)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return {m: oscillation(h["force_normal"]) for m, h in hists.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("options_file")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks per run")
    ap.add_argument("--every", type=int, default=1, help="-output_every of both runs (the maps' time resolution)")
    ap.add_argument("--extra", default="", help="options added to both runs")
    ap.add_argument("--out", help="output directory (default output/compare_mass/CASE)")
    ap.add_argument("--exe", default="./mmcontact")
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("--full", action="store_true", help="2D: the whole contact boundary in the maps")
    ap.add_argument("--no-run", action="store_true", help="draw the runs already in --out")
    args = ap.parse_args()
    if args.every < 1:
        ap.error("--every must be at least 1")
    case = os.path.splitext(os.path.basename(args.options_file))[0]
    args.out = args.out or os.path.join("output", "compare_mass", case)
    dirs = run_both(args, split_extra(args.extra))
    out = os.path.join(args.out, "compare_mass.png")
    osc = draw(dirs, f"{case} {args.extra}".strip(), out, not args.full)
    for m in MASSES:
        print(f"{m} mass: force oscillation {osc[m]:.3f} (total variation / (2 x peak)), run in {dirs[m]}")
    print(f"plot: {out}")


if __name__ == "__main__":
    main()
