#!/usr/bin/env python3
"""The cost model of -contact_formulation auto (src/contact/interface/cost.c), fitted again.

Reads measured runs (default scripts/cost_model_runs.csv and, without contact, K~ factored against CG,
scripts/cost_model_linear_runs.csv (--linear); written by scripts/cost_model_collect.py: 20
steps of the D1 disk and the D2 ball at several mesh sizes, c_p dt / h_c', mu, laws and ranks, each in
the condensed and the active-set formulation; columns dim, mesh, dofs, cfl, mu, law, ranks, formulation,
setup_s, s_per_step) and fits, per dimension and formulation, by least squares in logarithms:

    ln step  = s0 + s1 ln dofs + s2 ln(1 + cfl) + f (s3 + s4 ln(1 + cfl)) + g (s6 + s7 ln dofs + s10 ln(1 + cfl))
               + ln ranks (s5 + s8 ln dofs + s9 ln(1 + cfl))    (f = 1 with friction, g = 1 with svk)
    ln setup = u0 + u1 ln dofs + ln ranks (u2 + u3 ln dofs)

(a second rank pays on large meshes and costs on small ones: its term depends on the dofs; the active
set's cost grows with c_p dt / h_c' faster on 2 ranks and with svk: their terms in ln(1 + cfl)).

It prints the constants as the C initializers of MMCostModel (src/contact/contactimpl.h), and with
--write puts them into src/contact/impls/cost_constants.h, which the formulations' cost functions
include (then `make mmcontact`). Then the check of issues 41 and 50: over the measured cases (dim, mesh,
cfl, mu, law, ranks), for runs of 20, 75, 150 and 1000 steps, how much longer the run that the model
chooses takes than the faster of the two (measured set-up + steps x step); with --check FILE, the same
on held-out runs (scripts/cost_model_collect.py --check) that the fit did not see.
docs/scaling.md, "Refitted with the ranks and the law (issue 50)", has the tables this printed.
    Usage: scripts/cost_model_fit.py [runs.csv] [--check check.csv] [--write]
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FORMULATIONS = ("condensed", "active_set")
LINEAR_PATHS = ("factor", "cg")  # without contact (scripts/cost_model_collect.py --linear)
DIRECT = ("condensed", "factor")  # exact by construction: taken within DIRECT_MARGIN of the cheapest prediction
DIRECT_MARGIN = 0.1


HEADER = os.path.join(ROOT, "src", "contact", "impls", "cost_constants.h")
KEY = ("dim", "mesh", "dofs", "cfl", "mu", "law", "ranks")


def features(dofs, cfl, mu, law="linear", ranks=1):
    f, g = (1.0 if mu > 0 else 0.0), (0.0 if law == "linear" else 1.0)
    return [1.0, math.log(dofs), math.log(1 + cfl), f, f * math.log(1 + cfl), math.log(ranks), g, g * math.log(dofs),
            math.log(ranks) * math.log(dofs), math.log(ranks) * math.log(1 + cfl), g * math.log(1 + cfl)]


def setup_features(dofs, ranks=1):
    return [1.0, math.log(dofs), math.log(ranks), math.log(ranks) * math.log(dofs)]


def fit(runs):
    models = {}
    for dim in sorted({r["dim"] for r in runs}):
        for form in sorted({r["formulation"] for r in runs}):
            rs = [r for r in runs if r["dim"] == dim and r["formulation"] == form]
            X = np.array([features(*(r[k] for k in KEY[2:])) for r in rs])
            # without contact there is no friction, and svk is measured at each mesh's lowest c_p dt / h only:
            # those terms have no data (their columns zero or near another's) and are left at 0
            used = np.array([not (form in LINEAR_PATHS and i in (3, 4, 10)) for i in range(X.shape[1])])
            s = np.zeros(X.shape[1])
            s[used], *_ = np.linalg.lstsq(X[:, used], np.log([r["s_per_step"] for r in rs]), rcond=None)
            U = np.array([setup_features(r["dofs"], r["ranks"]) for r in rs])
            u, *_ = np.linalg.lstsq(U, np.log([r["setup_s"] for r in rs]), rcond=None)
            models[(dim, form)] = (s, u)
    return models


def predict(models, dim, form, dofs, cfl, mu, law="linear", ranks=1):
    s, u = models[(dim, form)]
    return math.exp(float(np.dot(u, setup_features(dofs, ranks)))), math.exp(float(np.dot(s, features(dofs, cfl, mu, law, ranks))))


def choose(pred):
    """auto's choice (src/contact/interface/cost.c): the cheapest prediction, or the direct solve within DIRECT_MARGIN of it"""
    cheapest = min(pred, key=pred.get)
    direct = [f for f in pred if f in DIRECT and pred[f] <= (1 + DIRECT_MARGIN) * pred[cheapest]]
    return direct[0] if direct else cheapest


def read(paths):
    runs = []
    for r in (r for path in paths for r in csv.DictReader(open(path))):
        runs.append(dict(dim=int(r["dim"]), mesh=r["mesh"], dofs=float(r["dofs"]), cfl=float(r["cfl"]), mu=float(r["mu"]),
                         law=r.get("law", "linear"), ranks=int(r.get("ranks", 1)), formulation=r["formulation"],
                         setup_s=float(r["setup_s"]), s_per_step=float(r["s_per_step"]), noise=float(r.get("noise", 0)),
                         steps=int(r.get("steps", 20))))
    return runs


def initializer(s, u):
    return "{{%s}, {%s}}" % (", ".join("%.4g" % v for v in s), ", ".join("%.4g" % v for v in u))


def write_header(models, source):
    with open(HEADER, "w") as f:
        f.write("/* -contact_formulation auto's fitted constants (MMCostModel, src/contact/contactimpl.h; docs/scaling.md,\n"
                " * \"Refitted with the ranks and the law\"), written by scripts/cost_model_fit.py --write from\n"
                f" * {source}, measured by scripts/cost_model_collect.py: refit them, do not edit. */\n")
        for (dim, form), (s, u) in sorted(models.items()):
            f.write(f"#define MM_COST_{form.upper()}_{dim}D {initializer(s, u)}\n")
        f.write(f"#define MM_COST_DIRECT_MARGIN {DIRECT_MARGIN} /* a direct solve within it of the cheapest prediction is taken */\n")
    print(f"wrote {os.path.relpath(HEADER, ROOT)}")


def check(models, runs, lengths, title):
    """The loss of the model's choice against the faster formulation, per case and run length (a length
    None: the run's own, its steps column)."""
    cases = {}
    for r in runs:
        cases.setdefault(tuple(r[k] for k in KEY), {})[r["formulation"]] = r
    worst, n, over = 0.0, 0, 0
    print(f"{title}\nsteps  case                                              chosen      best        loss")
    for length in lengths:
        for key, byf in sorted(cases.items()):
            if set(byf) not in (set(FORMULATIONS), set(LINEAR_PATHS)):
                continue
            dim, mesh, dofs, cfl, mu, law, ranks = key
            steps = length or next(iter(byf.values()))["steps"]
            total = {f: byf[f]["setup_s"] + steps * byf[f]["s_per_step"] for f in byf}
            pred = {f: sum(x * y for x, y in zip(predict(models, dim, f, *key[2:]), (1, steps))) for f in byf}
            chosen, best = choose(pred), min(total, key=total.get)
            loss = total[chosen] / total[best] - 1
            worst, n, over = max(worst, loss), n + 1, over + (loss > 0.1)
            if loss > 0 or steps == 75 or length is None:
                print(f"{steps:5d}  {dim}D {mesh:15s} cfl {cfl:5.2f} mu {mu:3.1f} {law:6s} {ranks} rk  {chosen:10s}  {best:10s}  "
                      f"{100 * loss:5.1f}%  ({total[chosen]:.3g} s against {total[best]:.3g} s)")
    print(f"largest loss: {100 * worst:.1f}%; {over} of {n} case-lengths lose more than 10%")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="*", default=[os.path.join(ROOT, "scripts", f) for f in ("cost_model_runs.csv", "cost_model_linear_runs.csv")])
    ap.add_argument("--check", nargs="+", help="held-out runs (scripts/cost_model_collect.py --check [--linear]) to check the fit on")
    ap.add_argument("--write", action="store_true", help=f"write the constants into {os.path.relpath(HEADER, ROOT)}")
    a = ap.parse_args()
    runs = read(a.runs)
    models = fit(runs)
    for (dim, form), (s, u) in sorted(models.items()):
        print(f"{dim}D {form:10s} {initializer(s, u)}")
    noise = [r["noise"] for r in runs]
    print(f"noise of the {len(runs)} rows (larger over smaller whole run, less 1): median {100 * np.median(noise):.1f}%, largest {100 * max(noise):.1f}%")
    if a.write:
        write_header(models, " and ".join(os.path.relpath(r, ROOT) for r in a.runs))
    check(models, runs, (20, 75, 150, 1000), "the fit set:")
    if a.check:
        check(models, read(a.check), (None, 150, 1000), "held out (each its run as measured: 20 steps, the bowl's 500; then set-up + 150 and 1000 steps):")


if __name__ == "__main__":
    main()
