#!/usr/bin/env python3
"""Measures the runs that -contact_formulation auto's cost model is fitted on (scripts/cost_model_fit.py,
src/contact/interface/cost.c, docs/scaling.md "The formulation chosen by cost").

Each case (mesh, c_p dt / h_c', mu, law, ranks) runs mmcontact for 20 steps in the condensed and in the
active-set formulation, each twice (the smaller time is kept: the machine is shared), and writes one row
per formulation: dim, mesh, dofs, cfl, mu, law, ranks, formulation, setup_s, s_per_step (from the run's
summary line "setup X s; N steps to t = T in W s wall"), and noise (the larger of the two whole runs over
the smaller, less 1). The dt of a case is the options file's dt scaled to the target c_p dt / h_c' read
from a -check_input run of the mesh (the ratio is proportional to dt).

The fit set: the D1 disk (options/d1_disk.opts) and the D2 ball (options/d2_ball.opts) on 8 meshes at 2
or 3 c_p dt / h_c' each, mu 0 and 0.2, 1 rank, the linear law; at each mesh's lowest and highest c_p dt /
h_c', 2 ranks (linear, mu 0 and 0.2) and -elasticity svk (mu 0.2, 1 and 2 ranks; not on the two largest
meshes, which would take the script past 20 minutes on 2 cores, and at the highest c_p dt / h_c' not on
ball07 either): the active set's cost grows with c_p dt / h_c' faster on 2 ranks and with svk.
--linear measures the runs without contact (-contact 0) instead, K~ factored against CG (-iterative_dofs 0
and 1), for the linear path's model; its rows' cfl is the run's c_p dt / h, h the smallest cell's diameter.
--resume keeps the rows already in the output file and measures only the cases missing from it.
--check runs the held-out cases instead (other c_p dt / h_c', the disk in the bowl on 2 ranks) in both
formulations and asks the binary's auto (-check_input) which it takes; it prints, for each, the chosen
formulation's whole run against the faster one's.
    Usage: scripts/cost_model_collect.py [--out FILE] [--subset] [--check] [--linear] [--meshes a.msh,b.msh] [--repeat N] [--resume] [--mmcontact PATH]
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FORMULATIONS = ("condensed", "active_set")
# without contact (--linear): K~ factored or solved by CG (-iterative_dofs 1: every size)
LINEAR_PATHS = ("factor", "cg")
PATH_ARGS = {"condensed": ["-contact_formulation", "condensed"], "active_set": ["-contact_formulation", "active_set"],
             "factor": ["-contact", 0, "-iterative_dofs", 0], "cg": ["-contact", 0, "-iterative_dofs", 1]}
# without contact the disk and the ball fly rigidly, which the step's predictor gives exactly (CG would take no
# iteration): they start strained (1%, volume-preserving), and vibrate
STRAIN = {2: "0.01,0,0,-0.01", 3: "0.01,0,0,0,0.01,0,0,0,-0.02"}
OPTS = {2: "options/d1_disk.opts", 3: "options/d2_ball.opts"}
# mesh: (dim, the c_p dt / h_c' of the fit set); a missing one is made by its Makefile rule (EnsureMeshes)
MESHES = {
    "disk.msh": (2, (0.92, 1.84, 7.35)),   # D1's own mesh (the bowl's at 0.92, held out with its own case)
    "disk05.msh": (2, (1.81, 7.24)),       # meshes/disk.geo at H 0.05
    "disk0125.msh": (2, (1.75, 7.0)),      # meshes/disk.geo at H 0.0125
    "disk_bench.msh": (2, (1.08, 5.4)),
    "ball.msh": (3, (0.609, 1.22, 2.43)),
    "ball10.msh": (3, (1.47, 2.94, 5.89)),
    "ball07.msh": (3, (2.1, 4.2, 8.4)),
    "ball_bench.msh": (3, (0.82, 1.64, 3.28)),
}
SVK_SKIPPED = ("disk_bench.msh", "ball_bench.msh")  # the largest: their svk runs alone would take ~10 minutes
# at the highest c_p dt / h_c' svk's condensed step rebuilds K~ and its Delassus columns on the tangent: the
# 33k-dof ball takes 9.6 s a step there, 13 minutes for its rows
SVK_HIGH_SKIPPED = ("ball07.msh",)
STEPS = 20
SUMMARY = re.compile(r"summary: setup ([\d.e+-]+) s; (\d+) steps to t = \S+ in ([\d.e+-]+) s wall")
HEADER = re.compile(r"(\d+) dofs; (\d+) rank")
CFL = re.compile(r"dt = ([\d.e+-]+) .*c_p dt / h(?:_c')? = ([\d.e+-]+)")
AUTO_LINEAR = re.compile(r"contact formulation none \(auto: (\d+) steps predicted ([\d.e+-]+) s by (CG|the factor), ([\d.e+-]+) s by")
AUTO = re.compile(r"contact formulation (\w+) \(auto: (?:(\d+) steps predicted ([\d.e+-]+) s, (\w+) ([\d.e+-]+) s|the only)")


def ensure_meshes(cases):
    """Makes the cases' meshes that are missing, by their Makefile rules (a fresh clone has none of them)."""
    missing = sorted({"meshes/" + c[0] for c in cases if not os.path.exists(os.path.join(ROOT, "meshes", c[0]))})
    if missing:
        subprocess.run(["make", "-C", ROOT] + missing, check=True)


def fit_cases(meshes=None):
    """(mesh, cfl, mu, law, ranks) of the fit set (on the given meshes only)."""
    cases = []
    for mesh, (dim, cfls) in MESHES.items():
        if meshes and mesh not in meshes:
            continue
        cases += [(mesh, cfl, mu, "linear", 1) for cfl in cfls for mu in (0.0, 0.2)]
        cases += [(mesh, cfl, mu, "linear", 2) for cfl in (cfls[0], cfls[-1]) for mu in (0.0, 0.2)]
        if mesh not in SVK_SKIPPED:
            cases += [(mesh, cfls[0], 0.2, "svk", n) for n in (1, 2)]
        if mesh not in SVK_SKIPPED + SVK_HIGH_SKIPPED:
            cases += [(mesh, cfls[-1], 0.2, "svk", n) for n in (1, 2)]
    held_out = {case_key(*c) for c in check_cases()}
    return [c for c in cases if case_key(*c) not in held_out]


def linear_fit_cases():
    """Without contact (--linear): (mesh, cfl, 0, law, ranks) at every mesh's c_p dt / h_c' (the run's own
    c_p dt / h, with h its smallest cell, is what the row keeps), 1 rank; 2 ranks at the lowest and the
    highest; svk at the lowest, 1 and 2 ranks (not on the two largest meshes)."""
    cases = []
    for mesh, (dim, cfls) in MESHES.items():
        cases += [(mesh, cfl, 0.0, "linear", 1) for cfl in cfls]
        cases += [(mesh, cfl, 0.0, "linear", 2) for cfl in (cfls[0], cfls[-1])]
        if mesh not in SVK_SKIPPED:
            cases += [(mesh, cfls[0], 0.0, "svk", n) for n in (1, 2)]
    held_out = {case_key(*c) for c in linear_check_cases()}
    return [c for c in cases if case_key(*c) not in held_out]


def linear_check_cases():
    return [("ball07.msh", 4.2, 0.0, "linear", 2), ("ball_bench.msh", 1.64, 0.0, "linear", 2),
            ("ball10.msh", 2.94, 0.0, "svk", 1), ("ball.msh", 1.22, 0.0, "svk", 2),
            ("disk0125.msh", 7.0, 0.0, "linear", 2), ("disk_bench.msh", 5.4, 0.0, "svk", 1)]


def subset_cases():
    return [(m, MESHES[m][1][0], mu, law, n) for m in ("disk05.msh", "ball.msh") for mu, law, n in
            ((0.0, "linear", 1), (0.2, "linear", 2), (0.2, "svk", 1))]


def check_cases():
    """Held out: c_p dt / h_c' and (law, ranks) pairs the fit set does not hold, and issue 50's bowl
    (options/disk_bowl.opts, 2 ranks, its own dt and length: cfl None)."""
    return [("ball07.msh", 4.2, 0.2, "linear", 2), ("ball07.msh", 4.2, 0.0, "linear", 2),
            ("disk0125.msh", 7.0, 0.0, "linear", 2), ("disk0125.msh", 7.0, 0.2, "linear", 2),
            ("ball10.msh", 2.94, 0.2, "svk", 1), ("ball10.msh", 2.94, 0.2, "svk", 2),
            ("disk0125.msh", 3.5, 0.2, "svk", 1), ("ball07.msh", 4.2, 0.2, "svk", 2),
            ("ball10.msh", 5.89, 0.0, "linear", 2), ("disk.msh", None, 0.0, "linear", 2)]


def case_key(mesh, cfl, mu, law, ranks):
    """A case as a row names it: its c_p dt / h_c' as the run printed it (3 digits)"""
    return (mesh, None if cfl is None else float("%.2g" % cfl), float(mu), law, int(ranks))


def run(exe, ranks, args, outdir):
    cmd = [exe] + [str(a) for a in args] + ["-output_dir", outdir]
    if ranks > 1:
        cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + cmd
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    return p.stdout


def case_args(mesh, cfl, mu, law, exe, tmp, dt_cache):
    """The options of a case: its options file, mesh, dt for the target c_p dt / h_c', mu and law."""
    if cfl is None:  # the bowl: its own options, whole run
        args = ["-options_file", "options/disk_bowl.opts"]
    else:
        dim = MESHES[mesh][0]
        args = ["-options_file", OPTS[dim], "-mesh", "meshes/" + mesh]
        if mesh not in dt_cache:
            m = CFL.search(run(exe, 1, args + ["-check_input"], tmp))
            dt_cache[mesh] = (float(m.group(1)), float(m.group(2)))
        dt0, cfl0 = dt_cache[mesh]
        args += ["-ts_dt", "%.6g" % (dt0 * cfl / cfl0), "-ts_max_steps", STEPS, "-ts_max_time", 1]
    args += ["-mu", mu, "-output_every", 0, "-ts_monitor_cancel"]
    if law != "linear":
        args += ["-elasticity", law]
    return args


def measure(exe, case, repeat, tmp, dt_cache, check, forms=FORMULATIONS):
    mesh, cfl, mu, law, ranks = case
    args = case_args(mesh, cfl, mu, law, exe, tmp, dt_cache)
    rows, runs = {}, {f: [] for f in forms}
    for _ in range(repeat):
        for form in forms:
            strain = ["-u0_gradient", STRAIN[MESHES[mesh][0]]] if form in LINEAR_PATHS else []
            out = run(exe, ranks, args + PATH_ARGS[form] + strain, tmp)
            s, h, c = SUMMARY.search(out), HEADER.search(out), CFL.search(out)
            assert s and h and c, out[-1500:]
            runs[form].append((float(s.group(1)), float(s.group(3)) / int(s.group(2)), int(s.group(2))))
            dofs, steps, cfl_run = int(h.group(1)), int(s.group(2)), float(c.group(2))
    for form in forms:
        setup, step = min(r[0] for r in runs[form]), min(r[1] for r in runs[form])
        whole = [r[0] + r[1] * r[2] for r in runs[form]]
        rows[form] = dict(dim=MESHES.get(mesh, (2,))[0], mesh=mesh if cfl is not None else "disk_bowl", dofs=dofs,
                          cfl="%.3g" % cfl_run, mu=mu, law=law, ranks=ranks, formulation=form, setup_s="%.4g" % setup,
                          s_per_step="%.4g" % step, noise="%.3f" % (max(whole) / min(whole) - 1), steps=steps)
        if form in LINEAR_PATHS:  # its cfl is the run's c_p dt / h: the case's target names it for --resume
            rows[form]["case_cfl"] = cfl
    if check and forms == LINEAR_PATHS:
        a = AUTO_LINEAR.search(run(exe, ranks, args + ["-contact", 0, "-u0_gradient", STRAIN[MESHES[mesh][0]], "-check_input"], tmp))
        chosen = "cg" if a.group(3) == "CG" else "factor"
        for form in forms:
            rows[form]["auto"] = chosen
            rows[form]["predicted_s"] = a.group(2) if chosen == form else a.group(4)
    elif check:
        a = AUTO.search(run(exe, ranks, args + ["-contact_formulation", "auto", "-check_input"], tmp))
        for form in forms:
            rows[form]["auto"] = a.group(1)
            rows[form]["predicted_s"] = a.group(3) if a.group(1) == form else a.group(5)
    return list(rows.values())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=None, help="the CSV written (default scripts/cost_model_runs.csv, or "
                    "scripts/cost_model_check.csv with --check)")
    ap.add_argument("--subset", action="store_true", help="a quick subset (a smoke run, 1 repeat)")
    ap.add_argument("--check", action="store_true", help="the held-out cases, with auto's choice")
    ap.add_argument("--meshes", help="comma-separated: the fit set's cases on these meshes only")
    ap.add_argument("--repeat", type=int, default=2, help="runs of each row; the smaller time is kept")
    ap.add_argument("--linear", action="store_true", help="without contact (-contact 0): K~ factored against CG "
                    "(default output scripts/cost_model_linear_runs.csv, or cost_model_linear_check.csv with --check)")
    ap.add_argument("--resume", action="store_true", help="keep the output file's rows and measure only the cases it lacks")
    ap.add_argument("--mmcontact", default=os.path.join(ROOT, "mmcontact"))
    a = ap.parse_args()
    if a.linear:
        cases = linear_check_cases() if a.check else linear_fit_cases()
    else:
        cases = check_cases() if a.check else subset_cases() if a.subset else fit_cases(a.meshes and a.meshes.split(","))
    forms = LINEAR_PATHS if a.linear else FORMULATIONS
    ensure_meshes(cases)
    repeat = 1 if a.subset else a.repeat
    stem = "cost_model_linear" if a.linear else "cost_model"
    out = a.out or os.path.join(ROOT, "scripts", stem + ("_check.csv" if a.check else "_runs.csv"))
    fields = ["dim", "mesh", "dofs", "cfl", "mu", "law", "ranks", "formulation", "setup_s", "s_per_step", "noise", "steps"]
    if a.linear:
        fields += ["case_cfl"]
    if a.check:
        fields += ["auto", "predicted_s"]
    t0, dt_cache, rows = time.time(), {}, []
    if a.resume and os.path.exists(out):
        rows = [dict(r, steps=int(r["steps"])) for r in csv.DictReader(open(out))]
        have = {case_key(r["mesh"], float(r.get("case_cfl") or r["cfl"]), float(r["mu"]), r["law"], int(r["ranks"])) for r in rows}
        cases = [c for c in cases if case_key(*c) not in have]
        print(f"{len(rows)} rows kept from {out}; {len(cases)} cases to measure", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for i, case in enumerate(cases):
            rows += measure(a.mmcontact, case, repeat, tmp, dt_cache, a.check, forms)
            print(f"[{time.time() - t0:6.0f} s] {i + 1}/{len(cases)} {case}: " + ", ".join(
                f"{r['formulation']} {r['setup_s']} + {r['s_per_step']}/step (noise {r['noise']})" for r in rows[-2:]), flush=True)
            with open(out, "w", newline="") as f:  # written as it goes: a stopped collection keeps its rows
                w = csv.DictWriter(f, fieldnames=fields)
                w.writeheader()
                w.writerows(rows)
    print(f"{len(rows)} rows in {out}; {time.time() - t0:.0f} s")
    if a.check:
        print("case                                           steps  auto        faster      loss")
        for c, f in zip(rows[0::2], rows[1::2]):
            total = {r["formulation"]: float(r["setup_s"]) + r["steps"] * float(r["s_per_step"]) for r in (c, f)}
            best = min(total, key=total.get)
            loss = total[c["auto"]] / total[best] - 1
            print(f"{c['dim']}D {c['mesh']:14s} cfl {c['cfl']:>5s} mu {c['mu']:.1f} {c['law']:6s} {c['ranks']} rk  {c['steps']:5d}  "
                  f"{c['auto']:10s}  {best:10s}  {100 * loss:5.1f}%  ({total[c['auto']]:.3g} s against {total[best]:.3g} s)")


if __name__ == "__main__":
    main()
