#!/usr/bin/python3 -s
"""Solve the step problems of `-friction_dump DIR` with Siconos' fc3d solvers and compare them with
mmcontact's own solution and time (docs/method.md section 6: the problems are written in the
Friction Contact Library's form u = W r + q, r in the Coulomb cone, u + mu |u_t| e_n in its dual).

    ./mmcontact -options_file options/d2_ball.opts -mesh meshes/ball07.msh -mu 0.2 -ts_dt 4e-3 \\
        -ts_max_time 0.08 -friction_dump out/dump
    /usr/bin/python3 -s scripts/fclib_compare.py out/dump [--solvers NSN_AC,NSN_FB,NSGS,...]

For each solver: the problems it solved to --tol (Siconos' own relative error), its iterations and
time per problem (best of --repeat, from the same warm start as ours: the previous step's reactions),
and the largest distance of its reactions from ours, relative to |r|. mmcontact's row gives the
time its solver took inside the run (PetscTime around the solve) and the same error measure of its
answer. Needs Debian's python3-siconos (3D problems only: fc3d)."""
import argparse
import glob
import os
import site
import sys
import time

try:  # a user-site numpy 2.x would shadow the Debian numpy that h5py and siconos were built against
    _usp = site.getusersitepackages()
    sys.path = [p for p in sys.path if not p.startswith(_usp)]
except Exception:  # pragma: no cover
    pass

import h5py
import numpy as np

SOLVERS = {  # name: max iterations (Newton steps, sweeps or projections)
    "NSN_AC": 200, "NSN_FB": 200, "NSN_NM": 200, "NSGS": 20000, "PROX": 1000, "TFP": 1000,
    "VI_EG": 20000, "VI_FPP": 20000, "EG": 20000, "FPP": 20000, "ADMM": 20000,
}


def load(path):
    with h5py.File(path, "r") as f:
        d = {k: np.array(f[k]) for k in ("W", "q", "mu", "r", "r0")}
        d.update({k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()})
    d["W"] = np.ascontiguousarray(d["W"])
    return d


def proj_cone(z, mu):
    """Projection of each row (n, t1, t2) of z on the cone |t| <= mu n."""
    out = np.zeros_like(z)
    zn, zt = z[:, 0], z[:, 1:]
    nt = np.linalg.norm(zt, axis=1)
    inside = nt <= mu * zn
    out[inside] = z[inside]
    mid = ~inside & (mu * nt > -zn)
    a = (zn[mid] + mu[mid] * nt[mid]) / (1 + mu[mid] ** 2)
    out[mid, 0] = a
    out[mid, 1:] = (mu[mid] * a / np.maximum(nt[mid], 1e-300))[:, None] * zt[mid]
    return out


def fc3d_error(W, q, mu, r):
    """Siconos' fc3d error: |r - P_K(r - (u + mu |u_t| e_n))| / max(|q|, |r|, |u|)."""
    u = W @ r + q
    R, U = r.reshape(-1, 3), u.reshape(-1, 3)
    z = R - U
    z[:, 0] -= mu * np.linalg.norm(U[:, 1:], axis=1)
    e = np.linalg.norm(R - proj_cone(z, mu))
    return e / max(np.linalg.norm(q), np.linalg.norm(r), np.linalg.norm(u), 1e-300)


def siconos_solve(sn, name, p, tol, repeat):
    P = sn.FrictionContactProblem(3, p["W"], p["q"], p["mu"])
    best = None
    for _ in range(repeat):
        so = sn.SolverOptions(getattr(sn, "SICONOS_FRICTION_3D_" + name))
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = SOLVERS.get(name, 1000)
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        r = p["r0"].copy()
        u = np.zeros_like(p["q"])
        t0 = time.perf_counter()
        try:
            info = sn.fc3d_driver(P, r, u, so)
        except Exception:  # a numerics error: not converged
            return dict(ok=False, its=0, time=float("nan"), dist=float("nan"))
        t = time.perf_counter() - t0
        if best is None or t < best["time"]:
            err = fc3d_error(p["W"], p["q"], p["mu"], r)
            best = dict(ok=(info == 0 and err <= 10 * tol), its=int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE]), time=t,
                        dist=np.abs(r - p["r"]).max() / max(np.abs(p["r"]).max(), 1e-300))
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+", help="-friction_dump directories")
    ap.add_argument("--solvers", default="NSN_AC,NSN_FB,NSN_NM,NSGS,PROX,VI_EG,VI_FPP,ADMM")
    ap.add_argument("--tol", type=float, default=1e-10, help="Siconos' tolerance (its relative error)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per problem and solver; the fastest counts")
    ap.add_argument("--markdown", help="also write the table to this file")
    a = ap.parse_args()
    import siconos.numerics as sn

    lines = []
    for d in a.dirs:
        files = sorted(glob.glob(os.path.join(d, "step_*.h5")))
        if not files:
            sys.exit(f"{d}: no step_*.h5: run mmcontact with -friction_dump {d}")
        probs = [load(f) for f in files]
        probs = [p for p in probs if int(p["spacedim"]) == 3 and p["r"][0::3].max() > 0]  # 3D, in contact
        if not probs:
            sys.exit(f"{d}: no 3D problem with contact")
        sizes = [int(p["n"]) for p in probs]
        lines.append(f"\n{d}: {len(probs)} problems, {min(sizes)} to {max(sizes)} candidate nodes, "
                     f"mu {float(probs[0]['mu'][0]):g}, dt {float(probs[0]['dt']):g}")
        lines.append(f"| solver | solved | iterations, mean (max) | ms per problem, mean (max) | largest difference from our r, of max r |")
        lines.append("|---|---|---|---|---|")
        ours_t = np.array([float(p["solve_time"]) for p in probs]) * 1e3
        ours_i = np.array([int(p["its"]) for p in probs])
        ours_e = max(fc3d_error(p["W"], p["q"], p["mu"], p["r"]) for p in probs)
        lines.append(f"| mmcontact ({probs[0]['solver']}), in the run | {len(probs)} (fc3d error <= {ours_e:.0e}) | "
                     f"{ours_i.mean():.1f} ({ours_i.max()}) | {ours_t.mean():.2f} ({ours_t.max():.2f}) | 0 |")
        for name in [s for s in a.solvers.split(",") if s]:
            res = [siconos_solve(sn, name, p, a.tol, a.repeat) for p in probs]
            ok = [r for r in res if r["ok"]]
            if not ok:
                lines.append(f"| Siconos {name} | 0 | | | |")
                continue
            its = np.array([r["its"] for r in ok])
            t = np.array([r["time"] for r in ok]) * 1e3
            lines.append(f"| Siconos {name} | {len(ok)} | {its.mean():.1f} ({its.max()}) | {t.mean():.2f} ({t.max():.2f}) | "
                         f"{max(r['dist'] for r in ok):.1e} |")
    text = "\n".join(lines)
    print(text)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
