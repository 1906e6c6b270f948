"""make bench: D1 on a >= 100k-dof disk for a fixed number of steps through the impact, on 1 and 2
ranks: without contact, with contact (condensed), with contact and friction mu = 0.2, and with
contact on all dofs (full). Writes bench/results.csv and prints a table of ratios measured
in this one run (absolute times on a shared machine are noise; ratios are the figures)."""
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESH = "meshes/disk_bench.msh"
STEPS = int(os.environ.get("BENCH_STEPS", "30"))
SUMMARY = re.compile(r"mmcontact summary: setup ([\d.]+) s; (\d+) steps .* in ([\d.]+) s wall \(([\d.]+) s/step\); peak memory ([\d.]+) MiB/rank")
DOFS = re.compile(r"(\d+) dofs, (\d+) contact nodes")


def run(np_, contact, formulation="condensed", mu=0.0):
    cmd = ["mpiexec", "--allow-run-as-root", "-n", str(np_), "./mmcontact", "-options_file", "options/d1_disk.opts",
           "-mesh", MESH, "-ts_dt", "2e-4", "-ts_max_steps", str(STEPS), "-ts_max_time", "1", "-ts_monitor_cancel",
           "-output_every", "0", "-output_dir", "bench/out", "-contact", str(int(contact)), "-contact_formulation", formulation, "-mu", str(mu)]
    out = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True).stdout
    m, d = SUMMARY.search(out), DOFS.search(out)
    hist = os.path.join(ROOT, "bench/out/history.csv")
    with open(hist) as f:
        rows = list(csv.DictReader(f))
    active = max(int(r["active"]) for r in rows)
    vi = sum(int(r["vi_its"]) for r in rows[1:]) / max(len(rows) - 1, 1)
    touching = [r for r in rows[1:] if int(r["active"]) > 0]
    fits = sum(int(r["friction_its"]) for r in touching) / max(len(touching), 1)
    return dict(ranks=np_, contact=int(contact), formulation=formulation if contact else "-", mu=mu, dofs=int(d.group(1)), contact_nodes=int(d.group(2)), setup_s=float(m.group(1)),
                steps=int(m.group(2)), wall_s=float(m.group(3)), s_per_step=float(m.group(4)), peak_mib_per_rank=float(m.group(5)),
                max_active=active, mean_vi_its=round(vi, 2), mean_friction_its_in_contact=round(fits, 2))


def main():
    os.makedirs(os.path.join(ROOT, "bench"), exist_ok=True)
    runs = [(n, c, f, mu) for n in (1, 2) for c, f, mu in ((False, "condensed", 0.0), (True, "condensed", 0.0), (True, "condensed", 0.2), (True, "full", 0.0))]
    rows = [run(*r) for r in runs]
    by = {(r["ranks"], r["contact"], r["formulation"], r["mu"]): r for r in rows}
    for r in rows:
        r["contact_over_linear"] = round(r["s_per_step"] / by[(r["ranks"], 0, "-", 0.0)]["s_per_step"], 3)
        r["speedup_2_ranks"] = round(by[(1, r["contact"], r["formulation"], r["mu"])]["s_per_step"] / by[(2, r["contact"], r["formulation"], r["mu"])]["s_per_step"], 3)
    path = os.path.join(ROOT, "bench/results.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"D1 benchmark: {rows[0]['dofs']} dofs, {by[(1, 1, 'condensed', 0.0)]['contact_nodes']} contact nodes, {STEPS} steps through the impact")
    print(f"{'ranks':>5} {'contact':>7} {'formulation':>11} {'mu':>4} {'setup s':>8} {'s/step':>9} {'contact/linear':>14} {'2-rank speedup':>14} {'peak MiB/rank':>13} {'max active':>10} {'VI its/step':>11} {'friction its':>12}")
    for r in rows:
        print(f"{r['ranks']:>5} {r['contact']:>7} {r['formulation']:>11} {r['mu']:>4} {r['setup_s']:>8.2f} {r['s_per_step']:>9.4f} {r['contact_over_linear']:>14.2f} {r['speedup_2_ranks']:>14.2f} {r['peak_mib_per_rank']:>13.1f} {r['max_active']:>10} {r['mean_vi_its']:>11} {r['mean_friction_its_in_contact']:>12}")
    print(f"written to {path}")


if __name__ == "__main__":
    sys.exit(main())
