"""Plots a history.csv written by mmcontact: energy terms, contact force, contact set, iterations.

usage: /usr/bin/python3 -s scripts/plot_history.py output/d1/history.csv [more.csv ...] [-o out.png]
Several histories are overlaid (for example modified against standard mass)."""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("histories", nargs="+")
    ap.add_argument("-o", "--output", help="PNG file (default: history.png next to the first CSV)")
    args = ap.parse_args()
    out = args.output or os.path.join(os.path.dirname(args.histories[0]), "history.png")
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    for path in args.histories:
        h = np.genfromtxt(path, delimiter=",", names=True)
        label = os.path.basename(os.path.dirname(os.path.abspath(path)))
        t = h["time"]
        ax[0, 0].plot(t, h["total"], label=f"{label}: total E")
        ax[0, 0].plot(t, h["kinetic"], "--", label=f"{label}: kinetic")
        ax[0, 0].plot(t, h["elastic"], ":", label=f"{label}: elastic")
        ax[0, 0].plot(t, h["total"] - h["work_ext"] - h["work_contact"] - h["work_friction"], "-.",
                      label=f"{label}: E - W (balance)")
        ax[0, 1].plot(t, h["force_normal"], label=f"{label}: normal")
        if np.abs(h["force_tangential"]).max() > 0:
            ax[0, 1].plot(t, h["force_tangential"], label=f"{label}: tangential")
        ax[1, 0].step(t, h["active"], where="post", label=f"{label}: active nodes")
        ax[1, 1].semilogy(t[1:], np.maximum(h["balance_residual"][1:], 1e-18), label=f"{label}: balance residual")
        ax[1, 1].semilogy(t, np.maximum(h["coulomb_residual"], 1e-18), label=f"{label}: Coulomb residual")
    titles = ["energy", "total contact force", "contact set", "audit (per step)"]
    for a, title in zip(ax.flat, titles):
        a.set_title(title)
        a.set_xlabel("time")
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"plot: {out}")


if __name__ == "__main__":
    main()
