"""Cost of each phase in the number of dofs N, contact nodes N_c and ranks P (docs/scaling.md).

Runs the D2 ball (options/d2_ball.opts) at three mesh sizes on 1 and 2 ranks, each case for
STEPS steps of dt 1e-3 (contact from step 10), with -log_view, and reads the time of each phase's
event (the largest over the ranks). For every phase and rank count it fits t = C N^p over the three
sizes (least squares on the logarithms) and prints the exponent p, the time at the largest size
and the 2-rank speed-up there. Writes every measurement to bench/scaling.csv and the fits to
bench/scaling_fit.csv.

Usage: /usr/bin/python3 -s scripts/scaling.py [--meshes a.msh,b.msh,c.msh] [--steps 20] [--ranks 1,2]
The meshes default to the D2 ball at H 0.1, 0.07 and 0.045 (meshes/ball10.msh, ball07.msh,
ball_bench.msh: `make meshes/ball10.msh meshes/ball07.msh meshes/ball_bench.msh`).
"""
import argparse
import csv
import math
import os
import re
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])

# The cases: the linear step and the condensed formulation without and with friction, all three with
# K~ factored at every size (-iterative_dofs 0: the default switches to CG at 50k 3D dofs, which would
# change the method inside a fit), and the active-set formulation with friction (its K~ by CG with
# Jacobi, no factor).
CASES = {
    "linear": "-contact 0 -iterative_dofs 0",
    "condensed_mu0": "-contact_formulation condensed -mu 0 -iterative_dofs 0",
    "condensed_mu0.2": "-contact_formulation condensed -mu 0.2 -iterative_dofs 0",
    "active_set_mu0.2": "-contact_formulation active_set -mu 0.2",
}
# The phases: -log_view events (src/sys/log.c), and what each stands for in docs/scaling.md.
PHASES = {
    "MMMeshLoad": "mesh read and distribution",
    "MMFESetUp": "sections, matrix pattern",
    "MMAssemble": "assembly of K and M",
    "MMInitialState": "initial state (mass solve)",
    "MMStepMatrix": "K~ and its factor or PC (set-up)",
    "MMCandidateCols": "Delassus columns (condensed)",
    "MMFrictionLoop": "friction solve",
    "MMContactSolve": "contact solve",
    "MMActiveSetCG": "active-set CG solves",
    "MMEnergy": "energy audit",
    "MMCheckpoint": "checkpoint",
}
SUMMARY = re.compile(r"mmcontact summary: setup ([\d.]+) s; (\d+) steps .* \(([\d.]+) s/step\); peak memory ([\d.]+) MiB/rank")
DOFS = re.compile(r"(\d+) dofs[ ;(]")
CONTACT_NODES = re.compile(r"(\d+) contact nodes")


def event_times(log):
    """{event: seconds} summed over the log stages (the max-over-ranks time column of -log_view)."""
    times = {}
    for line in log.splitlines():
        words = line.split()
        if len(words) > 4 and words[0] in PHASES and re.fullmatch(r"\d+", words[1]):
            times[words[0]] = times.get(words[0], 0.0) + float(words[3])
    return times


def measure(mesh, case, ranks, steps):
    log_path = os.path.join(ROOT, "bench", f"scaling-{os.path.basename(mesh)}-{case}-{ranks}.log")
    cmd = MPIEXEC + ["-n", str(ranks), "./mmcontact", "-options_file", "options/d2_ball.opts", "-mesh", mesh, "-ts_dt", "1e-3",
                     "-ts_max_steps", str(steps), "-ts_max_time", "1", "-ts_monitor_cancel", "-output_every", "0",
                     "-output_dir", f"bench/out/scaling-{case}-{ranks}", "-log_view", f":{log_path}"] + shlex.split(CASES[case])
    print(f"  {os.path.basename(mesh)} {case} on {ranks} rank(s)", flush=True)
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    summary = SUMMARY.search(proc.stdout)
    if proc.returncode or not summary:
        sys.exit(f"scaling.py: {' '.join(cmd)} failed (exit {proc.returncode}):\n{proc.stderr[-2000:]}")
    with open(log_path) as f:
        times = event_times(f.read())
    row = dict(mesh=os.path.basename(mesh), case=case, ranks=ranks, dofs=int(DOFS.search(proc.stdout).group(1)),
               contact_nodes=int(CONTACT_NODES.search(proc.stdout).group(1)) if case != "linear" else 0,
               setup_s=float(summary.group(1)), s_per_step=float(summary.group(3)), peak_mib_max_rank=float(summary.group(4)))
    row.update({p: round(times.get(p, 0.0), 4) for p in PHASES})
    return row


def fit(rows, key):
    """Least-squares exponent p of t = C N^p over the rows with t > 0 (None with fewer than 2)."""
    pts = [(math.log(r["dofs"]), math.log(r[key])) for r in rows if r[key] > 0]
    if len(pts) < 2:
        return None
    mx, my = sum(x for x, _ in pts) / len(pts), sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return round(sum((x - mx) * (y - my) for x, y in pts) / sxx, 2) if sxx > 0 else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", default="meshes/ball10.msh,meshes/ball07.msh,meshes/ball_bench.msh")
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--cases", default=",".join(CASES))
    a = ap.parse_args()
    meshes, ranks, cases = a.meshes.split(","), [int(r) for r in a.ranks.split(",")], a.cases.split(",")
    os.makedirs(os.path.join(ROOT, "bench"), exist_ok=True)
    rows = [measure(m, c, p, a.steps) for c in cases for p in ranks for m in meshes]
    keys = ["setup_s", "s_per_step"] + list(PHASES)
    with open(os.path.join(ROOT, "bench/scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fits = []
    for c in cases:
        for k in keys:
            by_p = {p: [r for r in rows if r["case"] == c and r["ranks"] == p] for p in ranks}
            largest = {p: max(rs, key=lambda r: r["dofs"]) for p, rs in by_p.items() if rs}
            t1, t2 = largest.get(1, {}).get(k, 0), largest.get(2, {}).get(k, 0)
            if not any(r[k] > 0 for rs in by_p.values() for r in rs):
                continue
            fits.append(dict(case=c, phase=k, meaning=PHASES.get(k, k.replace("_", " ")),
                             **{f"exponent_{p}_rank": fit(rs, k) for p, rs in by_p.items()},
                             s_at_largest_1_rank=t1, s_at_largest_2_ranks=t2,
                             speedup_2_ranks=round(t1 / t2, 2) if t1 > 0 and t2 > 0 else "-"))
    with open(os.path.join(ROOT, "bench/scaling_fit.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(fits[0]))
        w.writeheader()
        w.writerows(fits)
    print("sizes:", ", ".join(f"{r['mesh']} {r['dofs']} dofs, {r['contact_nodes']} contact nodes" for r in rows if r["case"] == cases[-1] and r["ranks"] == ranks[0]))
    print(f"{'case':18} {'phase':16} {'p (1 rank)':>10} {'p (2 ranks)':>11} {'s, largest, 1':>13} {'s, largest, 2':>13} {'speed-up':>8}")
    for r in fits:
        print(f"{r['case']:18} {r['phase']:16} {str(r.get('exponent_1_rank')):>10} {str(r.get('exponent_2_rank')):>11} "
              f"{r['s_at_largest_1_rank']:>13} {r['s_at_largest_2_ranks']:>13} {r['speedup_2_ranks']:>8}")
    print("written to bench/scaling.csv and bench/scaling_fit.csv")


if __name__ == "__main__":
    main()
