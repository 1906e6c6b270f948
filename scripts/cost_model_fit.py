#!/usr/bin/env python3
"""The cost model of -contact_formulation auto (src/contact/interface/cost.c), fitted again.

Reads measured runs (default scripts/cost_model_runs.csv: 1 rank, 20 steps of the D1 disk and the D2
ball at several mesh sizes, c_p dt / h_c' and mu, each in the condensed and the active-set
formulation; columns dim, mesh, dofs, cfl, mu, formulation, setup_s, s_per_step) and fits, per
dimension and formulation, by least squares in logarithms:

    ln step  = s0 + s1 ln dofs + s2 ln(1 + cfl) + f (s3 + s4 ln(1 + cfl))   (f = 1 with friction)
    ln setup = u0 + u1 ln dofs

It prints the constants as the C tables of the formulations' cost functions want them, and then the
check of issue 41: over the measured cases, for runs of 20, 75, 150 and 1000 steps, how much longer
the run that the model chooses takes than the faster of the two (measured set-up + steps x step).
docs/scaling.md, "The formulation chosen by cost", has the table this printed.
    Usage: scripts/cost_model_fit.py [runs.csv]
"""
import csv
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FORMULATIONS = ("condensed", "active_set")


def features(dofs, cfl, mu):
    f = 1.0 if mu > 0 else 0.0
    return [1.0, math.log(dofs), math.log(1 + cfl), f, f * math.log(1 + cfl)]


def fit(runs):
    models = {}
    for dim in sorted({r["dim"] for r in runs}):
        for form in FORMULATIONS:
            rs = [r for r in runs if r["dim"] == dim and r["formulation"] == form]
            X = np.array([features(r["dofs"], r["cfl"], r["mu"]) for r in rs])
            s, *_ = np.linalg.lstsq(X, np.log([r["s_per_step"] for r in rs]), rcond=None)
            u, *_ = np.linalg.lstsq(X[:, :2], np.log([r["setup_s"] for r in rs]), rcond=None)
            models[(dim, form)] = (s, u)
    return models


def predict(models, dim, form, dofs, cfl, mu):
    s, u = models[(dim, form)]
    return math.exp(u[0] + u[1] * math.log(dofs)), math.exp(float(np.dot(s, features(dofs, cfl, mu))))


def main(path):
    runs = []
    for r in csv.DictReader(open(path)):
        runs.append(dict(dim=int(r["dim"]), mesh=r["mesh"], dofs=float(r["dofs"]), cfl=float(r["cfl"]), mu=float(r["mu"]),
                         formulation=r["formulation"], setup_s=float(r["setup_s"]), s_per_step=float(r["s_per_step"])))
    models = fit(runs)
    for (dim, form), (s, u) in sorted(models.items()):
        print(f"{dim}D {form:10s} {{{{{', '.join('%.4g' % v for v in s)}}}, {{{', '.join('%.4g' % v for v in u)}}}}}")
    cases = {}
    for r in runs:
        cases.setdefault((r["dim"], r["mesh"], r["dofs"], r["cfl"], r["mu"]), {})[r["formulation"]] = r
    worst = 0.0
    print("steps  case                                  chosen      best        loss")
    for steps in (20, 75, 150, 1000):
        for (dim, mesh, dofs, cfl, mu), byf in sorted(cases.items()):
            if set(byf) != set(FORMULATIONS):
                continue
            total = {f: byf[f]["setup_s"] + steps * byf[f]["s_per_step"] for f in FORMULATIONS}
            pred = {f: sum(x * y for x, y in zip(predict(models, dim, f, dofs, cfl, mu), (1, steps))) for f in FORMULATIONS}
            chosen, best = min(pred, key=pred.get), min(total, key=total.get)
            loss = total[chosen] / total[best] - 1
            worst = max(worst, loss)
            if loss > 0 or steps == 75:
                print(f"{steps:5d}  {dim}D {mesh:15s} cfl {cfl:5.2f} mu {mu:3.1f}  {chosen:10s}  {best:10s}  {100 * loss:5.1f}%  ({total[chosen]:.3g} s against {total[best]:.3g} s)")
    print(f"largest loss over the measured cases: {100 * worst:.1f}%")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scripts", "cost_model_runs.csv"))
