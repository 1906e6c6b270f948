"""Benchmarks of mmcontact: a fixed number of steps through the impact, without and with contact.

Suites (the table SUITES below):
  2d     D1 disk, 115k dofs (meshes/disk_bench.msh): linear, contact, friction mu = 0.2, and
         contact on all dofs (full); contact_as and friction_as in the active-set formulation;
         1 and 2 ranks.                                                   -> bench/results.csv
  3d     D2 ball, 113k dofs (meshes/ball_bench.msh): linear, contact, friction mu = 0.2 (condensed); and
         two_body, two balls thrown at each other, frictionless (options/two_balls.opts on
         meshes/two_balls_bench.msh, H = 0.057: 117k dofs, its own dt); contact_as and friction_as,
         the contact rows in the active-set formulation (the default at this size); 1 and 2 ranks.
                                                                          -> bench/results.csv
  surface a slab pressed flat on a plane over its whole base (options/slab_press.opts on meshes/slab.msh:
         315k dofs, 21,025 contact nodes): linear (the slab squeezed, base clamped), contact, friction
         mu = 0.2; 2 ranks, 20 steps, the default formulation (active_set). -> bench/results.csv
  users  D2 ball at the time steps users choose (meshes/ball07.msh, H = 0.07, 33k dofs): dt = 4e-3
         and 8e-3 (c_p dt / h_c' = 2.1 and 4.2; suites users4, users8), linear; contact and friction
         with mu = 0.2 and 0.5 as users run them (contact, fric_0.2, fric_0.5: the formulation
         -contact_formulation auto chooses) and in each formulation (_condensed, _as), and the
         paper's fixed point (-friction_type fixedpoint, condensed); 1 rank, 20 steps through the
         impact.                                                          -> bench/results.csv
  finite issue 40's cost target of the finite-strain step: friction mu = 0.2 with -elasticity linear
         and svk, run as pairs back to back (the same options but -elasticity), in the formulation
         -contact_formulation auto picks. Suite finite07: the D2 ball at H = 0.07 (meshes/ball07.msh,
         33k dofs, condensed), dt = 4e-3, 20 steps, 1 rank; suite finite3d: the 3d suite's 113k-dof ball
         (meshes/ball_bench.msh, active_set), dt = 1e-3, 30 steps, 2 ranks. The svk row gives
         svk_over_linear (its s/step over the linear row's), nonlinear_its_per_step and
         tangent_rebuilds (the run summary's "finite strain:" line) and finite_target: "met" when
         svk_over_linear <= 2.5 and nonlinear_its_per_step <= 4 (issue 40), else "missed".
                                                                          -> bench/results.csv
  large  D2 ball, about 1M dofs (meshes/ball_large.msh): linear, contact, friction mu = 0.2 on 2
         ranks, contact solved with LARGE_OPTS.                           -> bench/results_large.csv

`make bench` runs 2d, 3d, surface and users (`BENCH_CASES=finite make bench` the finite suites),
`make bench-large` runs large. Each suite's rows are written to its
CSV (one common header) and printed as a table. Absolute times on a shared machine are noise: the
figures are the ratios within one run (contact/linear on the same ranks and mesh, 1-rank over
2-rank time for the 2-rank speed-up).

Environment (all optional):
  BENCH_CASES       suites or suite:case to run, comma-separated (e.g. 2d,3d or 3d:linear,3d:friction);
                    the command-line arguments, if any, take precedence. Default: 2d,3d,surface,users
                    (finite is not in the default: BENCH_CASES=finite make bench).
  BENCH_STEPS       steps per run for every suite (default: each suite's own, see SUITES)
  BENCH_RANKS       ranks to run, comma-separated (e.g. 2); ratios need both rows present
  BENCH_MESH_<SUITE> another mesh for that suite (e.g. BENCH_MESH_3D=meshes/ball.msh), to try rows quickly;
                    a variant with its own mesh (3d two_body) takes BENCH_MESH_<SUITE>_<CASE> instead
                    (e.g. BENCH_MESH_3D_TWO_BODY=meshes/two_balls.msh)
  BENCH_LARGE_OPTS  contact solver options for the large suite's contact rows (default LARGE_OPTS)

The ceiling of the 2-rank speed-up: before the rows, build/stream (scripts/stream.c, `make bench`
builds it) measures the STREAM triad bandwidth on 1 and 2 processes. Their ratio bounds what a
second rank can give a memory-bound phase (sparse products, CG, triangular solves); it is written
to bench/stream.csv and next to each 2-rank row as stream_ratio, with speedup_over_stream (the row's
speed-up over that ratio) and speedup_target, "met" when the speed-up is at least 1.7 or at least
95% of the STREAM ratio, whichever is lower (issue 21), else "missed". The ratio is the median of
STREAM_REPEATS alternating 1- and 2-process measurements: a shared machine moves single readings.

Pairs: a case's 1-rank and 2-rank rows run one after the other, not a suite apart, so that the
machine's drift does not enter their ratio. A case whose steps take less than SHORT_STEPPING_S of
wall time on 1 rank in its first run (the 2d rows but full, the 3d linear row, the active-set rows
on a quiet machine: 1 to 5 s, where one busy second moves the speed-up by 20 to 50%) runs
PAIR_REPEATS pairs in turn, and each row's s/step
and set-up are the medians over its runs (column repeats); the other columns come from the first.
The finite suites' pairs are their two rows (linear, then svk) back to back instead, repeated the same
way when the linear row's stepping is that short; svk_over_linear is the median of the pairs' ratios.
Every row gives max_balance, the largest energy-balance residual of the run (its summary).

The formulation chosen by cost (issue 41): formulation is the one the run used, chosen_by "auto" when
-contact_formulation auto chose it. For every case run in both the condensed and the active-set
formulation (same suite, ranks, mu, friction solver and elasticity), auto_choice is what auto
chooses for it (its own row's, or a -check_input run's) and auto_loss how much longer that
formulation's whole run (set-up + steps x s/step, its own row) took than the faster one's: issue 41
asks for at most 10%.

Peak memory: the program's summary prints the largest peak RSS over the ranks ("MiB/rank" is the
max over ranks, src/io/output.c); to get the total, every rank runs under this script's --rank-rss
mode, which reports the peak RSS of its mmcontact process, and the column peak_mib_total sums them.
"""
import csv
import os
import re
import resource
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC = ["mpiexec"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
PYTHON = [sys.executable, "-s"]

# The large suite's solvers: direct factors of K~ and M* do not fit at 1M dofs, so every row solves
# them by CG, and the contact rows use the active-set formulation (README "Large meshes").
LARGE_SOLVERS = "-contact_K_ksp_type cg -contact_K_pc_type jacobi -mass_ksp_type cg -mass_pc_type jacobi"
LARGE_OPTS = os.environ.get("BENCH_LARGE_OPTS", "-contact_formulation active_set")

LINEAR = dict(case="linear", options="-contact 0")
CONTACT = dict(case="contact", options="-contact_formulation condensed -mu 0")
FRICTION = dict(case="friction", options="-contact_formulation condensed -mu 0.2")
FULL = dict(case="full", options="-contact_formulation full -mu 0")
# The active-set formulation, which -contact_formulation auto picks for 3D meshes of -iterative_dofs
# (50,000) dofs and more: the 3d suite's contact rows in the formulation its users get by default.
CONTACT_AS = dict(case="contact_as", options="-contact_formulation active_set -mu 0")
FRICTION_AS = dict(case="friction_as", options="-contact_formulation active_set -mu 0.2")
# Two-body contact (issue 20): a variant may bring its own options file, mesh and dt (the suite's
# otherwise). Two balls of radius 1 at gap 0.01 and relative speed 1 (options/two_balls.opts): contact
# from t = 0.01, step 5 of dt 2e-3 (c_p dt / h_c' = 1.3 at H = 0.057), and it lasts about 0.3, so
# 25 of the 30 steps are in contact. Its contact_over_linear is against the D2 ball's linear row
# (112,605 dofs against 116,520): the cost of contact at about the same size, not on the same mesh.
TWO_BODY = dict(case="two_body", options="-contact_formulation condensed", options_file="options/two_balls.opts",
                problem="two balls", mesh="meshes/two_balls_bench.msh", dt=2e-3)
USERS = ((LINEAR, dict(case="contact", options="-mu 0"), dict(case="contact_condensed", options="-contact_formulation condensed -mu 0"),
          dict(case="contact_as", options="-contact_formulation active_set -mu 0"))
         + tuple(dict(case=f"fric_{mu}{suffix}", options=f"{form}-mu {mu}") for mu in (0.2, 0.5)
                 for suffix, form in (("", ""), ("_condensed", "-contact_formulation condensed "), ("_as", "-contact_formulation active_set ")))
         + (dict(case="fric_0.2_fixedpoint", options="-contact_formulation condensed -mu 0.2 -friction_type fixedpoint"),))
# Finite strain (issue 40): the friction row with -elasticity linear and with svk, the same options
# otherwise; in the formulation -contact_formulation auto picks at each size (written out, so that the
# CSV says it): condensed on the 33k-dof ball, active_set on the 113k-dof one. The svk row's case is the
# linear row's case and "_svk" (FINITE_TARGET: its s/step over the linear row's, its iterations).
FINITE_TARGET = dict(ratio=2.5, its=4.0)
FINITE07 = (dict(case="friction", options="-contact_formulation condensed -mu 0.2 -elasticity linear"),
            dict(case="friction_svk", options="-contact_formulation condensed -mu 0.2 -elasticity svk"))
FINITE3D = (dict(case="friction", options="-contact_formulation active_set -mu 0.2 -elasticity linear"),
            dict(case="friction_svk", options="-contact_formulation active_set -mu 0.2 -elasticity svk"))

# One row per (suite, variant, ranks). dt and steps go through the impact: the D1 disk touches the
# plane after 1 ms (gap 0.001, v = -1; step 5), the D2 ball after 10 ms (gap 0.01; step 10).
SUITES = [
    dict(suite="2d", problem="D1 disk", dim=2, options_file="options/d1_disk.opts", mesh="meshes/disk_bench.msh",
         dt=2e-4, steps=30, ranks=(1, 2), variants=(LINEAR, CONTACT, FRICTION, FULL, CONTACT_AS, FRICTION_AS), csv="bench/results.csv"),
    dict(suite="3d", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball_bench.msh",
         dt=1e-3, steps=30, ranks=(1, 2), variants=(LINEAR, CONTACT, FRICTION, TWO_BODY, CONTACT_AS, FRICTION_AS), csv="bench/results.csv"),
    # A large contact surface (issue 21): a slab of 315k dofs pressed flat on a plane over its whole
    # base, 21,025 contact nodes all touching from step 3, on 2 ranks. Its formulation is the default
    # (-contact_formulation auto: active_set at this size). The linear row is the same slab squeezed
    # between the press and a clamped base (-contact 0 -dirichlet top,base): the deformation of a
    # sticking contact with no contact solve, so that CG has work to do in both (a rigid motion is the
    # Newmark predictor itself).
    dict(suite="surface", problem="slab pressed flat", dim=3, options_file="options/slab_press.opts", mesh="meshes/slab.msh",
         dt=2e-4, steps=20, ranks=(2,),
         variants=(dict(case="linear", options="-contact 0 -dirichlet top,base -dirichlet_base_components 2 -mu 0"), dict(case="contact", options="-mu 0"),
                   dict(case="friction", options="-mu 0.2")),
         csv="bench/results.csv"),
    dict(suite="users4", group="users", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball07.msh",
         dt=4e-3, steps=20, ranks=(1,), variants=USERS, csv="bench/results.csv"),
    dict(suite="users8", group="users", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball07.msh",
         dt=8e-3, steps=20, ranks=(1,), variants=USERS, csv="bench/results.csv"),
    # Issue 40's cost target: the D2 ball at H = 0.07 as users4 (1 rank) and the 3d suite's ball (2 ranks).
    dict(suite="finite07", group="finite", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball07.msh",
         dt=4e-3, steps=20, ranks=(1,), variants=FINITE07, pairs=True, csv="bench/results.csv"),
    dict(suite="finite3d", group="finite", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball_bench.msh",
         dt=1e-3, steps=30, ranks=(2,), variants=FINITE3D, pairs=True, csv="bench/results.csv"),
    dict(suite="large", problem="D2 ball", dim=3, options_file="options/d2_ball.opts", mesh="meshes/ball_large.msh",
         dt=1e-3, steps=30, ranks=(2,),
         variants=(dict(case="linear", options=f"-contact 0 {LARGE_SOLVERS}"), dict(case="contact", options=f"-mu 0 {LARGE_SOLVERS} {LARGE_OPTS}"),
                   dict(case="friction", options=f"-mu 0.2 {LARGE_SOLVERS} {LARGE_OPTS}")),
         csv="bench/results_large.csv"),
]

FIELDS = ["suite", "problem", "dim", "ranks", "case", "formulation", "mu", "friction_type", "cfl", "dofs", "contact_nodes", "steps", "setup_s",
          "s_per_step", "contact_over_linear", "speedup_2_ranks", "peak_mib_max_rank", "peak_mib_total", "candidates",
          "max_active", "mean_vi_its", "mean_friction_its_in_contact", "max_friction_its", "rejections", "stream_ratio",
          "speedup_over_stream", "speedup_target", "max_balance", "elasticity", "svk_over_linear", "nonlinear_its_per_step",
          "tangent_rebuilds", "finite_target", "chosen_by", "auto_choice", "auto_loss", "repeats", "status"]
SUMMARY = re.compile(r"mmcontact summary: setup ([\d.]+) s; (\d+) steps .* \(([\d.]+) s/step\); peak memory ([\d.]+) MiB/rank")
DOFS = re.compile(r"(\d+) dofs[ ;(]")
CONTACT_NODES = re.compile(r"(\d+) contact nodes")
BALANCE = re.compile(r"largest balance residual ([-+\d.eE]+)")
NONLINEAR = re.compile(r"finite strain: ([\d.]+) iterations per step")
REBUILDS = re.compile(r"(\d+) tangent rebuilds")
FORMULATION = re.compile(r"contact formulation (\w+)( \(auto)?")
RANK_RSS = re.compile(r"bench rank peak rss (\d+) kB")
STREAM = re.compile(r"stream ranks (\d+) triad_mbs ([\d.]+)")
STREAM_EXE = "build/stream"
STREAM_REPEATS = 5
SHORT_STEPPING_S, PAIR_REPEATS = 5.0, 3
SPEEDUP_TARGET, STREAM_FRACTION = 1.7, 0.95


def option_value(options, name, default):
    """The value of option `name` in an options string, else `default`."""
    words = shlex.split(options)
    return words[words.index(name) + 1] if name in words[:-1] else default


def history_stats(path):
    """Per-run figures from history.csv: max candidates (or "-"), max active, mean VI its per step,
    mean friction its per step with contact."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    steps = rows[1:]  # row 0 is the initial state
    touching = [r for r in steps if int(r["active"]) > 0]
    mean = lambda rs, key: round(sum(int(r[key]) for r in rs) / len(rs), 2) if rs else 0
    return dict(candidates=max(int(r["candidates"]) for r in rows) if "candidates" in rows[0] else "-",
                max_active=max(int(r["active"]) for r in rows), mean_vi_its=mean(steps, "vi_its"),
                mean_friction_its_in_contact=mean(touching, "friction_its"),
                max_friction_its=max(int(r["friction_its"]) for r in rows), cfl=round(float(rows[-1]["cfl"]), 2))


def mmcontact_args(suite, variant, steps, out_dir):
    """The mmcontact command line of a row (without the launcher)."""
    mesh_env = f"BENCH_MESH_{suite['suite'].upper()}"  # BENCH_MESH_3D for the suite's mesh, BENCH_MESH_3D_TWO_BODY for a variant's own
    mesh = os.environ.get(f"{mesh_env}_{variant['case'].upper()}") or variant.get("mesh") or os.environ.get(mesh_env, suite["mesh"])
    options_file, dt = variant.get("options_file", suite["options_file"]), variant.get("dt", suite["dt"])
    return (["./mmcontact", "-options_file", options_file, "-mesh", mesh, "-ts_dt", str(dt), "-ts_max_steps", str(steps),
             "-ts_max_time", "1", "-ts_monitor_cancel", "-output_every", "0", "-output_dir", out_dir] + shlex.split(variant["options"]))


def run(suite, variant, ranks, steps):
    """Runs one row; returns its dict (status "ok", or "failed" with the blanks as "-")."""
    options = variant["options"]
    contact = option_value(options, "-contact", "1") != "0"
    out_dir = f"bench/out/{suite['suite']}-{variant['case']}-{ranks}"
    cmd = (MPIEXEC + ["-n", str(ranks)] + PYTHON + [os.path.abspath(__file__), "--rank-rss"] + mmcontact_args(suite, variant, steps, out_dir))
    row = dict(suite=suite["suite"], problem=variant.get("problem", suite["problem"]), dim=suite["dim"], ranks=ranks, case=variant["case"],
               formulation=option_value(options, "-contact_formulation", "default") if contact else "-",
               mu=float(option_value(options, "-mu", "0")), steps=steps, status="ok")
    row["friction_type"] = option_value(options, "-friction_type", "newton") if contact and row["mu"] > 0 else "-"
    row["elasticity"] = option_value(options, "-elasticity", "linear")
    print(f"  {suite['suite']} {variant['case']} on {ranks} rank(s): {' '.join(cmd[cmd.index('./mmcontact'):])}", flush=True)
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    summary, dofs, nodes = SUMMARY.search(proc.stdout), DOFS.search(proc.stdout), CONTACT_NODES.search(proc.stdout)
    if proc.returncode or not summary:
        lines = proc.stderr.splitlines()
        print(f"    failed (exit {proc.returncode}):", *(lines if len(lines) <= 16 else lines[:10] + ["..."] + lines[-5:]), sep="\n    ", flush=True)
        return dict(row, status="failed", **{k: "-" for k in FIELDS if k not in row})
    rss = [int(kb) / 1024 for kb in RANK_RSS.findall(proc.stderr)]
    form = FORMULATION.search(proc.stdout)
    if contact and form:
        row.update(formulation=form.group(1), chosen_by="auto" if form.group(2) else "option")
    balance, nonlinear, rebuilds = BALANCE.search(proc.stdout), NONLINEAR.search(proc.stdout), REBUILDS.search(proc.stdout)
    row.update(max_balance=float(balance.group(1)) if balance else "-", nonlinear_its_per_step=float(nonlinear.group(1)) if nonlinear else "-",
               tangent_rebuilds=int(rebuilds.group(1)) if nonlinear and rebuilds else "-")
    return dict(row, dofs=int(dofs.group(1)), contact_nodes=int(nodes.group(1)), setup_s=float(summary.group(1)),
                s_per_step=float(summary.group(3)), peak_mib_max_rank=float(summary.group(4)),
                peak_mib_total=round(sum(rss), 1) if len(rss) == ranks else "-", rejections=proc.stdout.count("step rejected"),
                **history_stats(os.path.join(ROOT, out_dir, "history.csv")))


def median(values):
    v = sorted(values)
    return v[len(v) // 2] if len(v) % 2 else (v[len(v) // 2 - 1] + v[len(v) // 2]) / 2


def run_case(suite, variant, ranks, steps):
    """One case on each of ranks, in turn; a short one (1-rank stepping under SHORT_STEPPING_S) on 1
    and 2 ranks PAIR_REPEATS times in turn, its s/step and set-up the medians (see the docstring)."""
    runs = [{n: run(suite, variant, n, steps) for n in ranks}]
    first = runs[0]
    short = (ranks == [1, 2] and all(r["status"] == "ok" for r in first.values())
             and first[1]["s_per_step"] * steps < SHORT_STEPPING_S)
    for _ in range(PAIR_REPEATS - 1 if short else 0):
        runs.append({n: run(suite, variant, n, steps) for n in ranks})
    rows = []
    for n in ranks:
        ok = [r[n] for r in runs if r[n]["status"] == "ok"]
        row = dict(first[n], repeats=len(runs))
        if len(ok) < len(runs):  # a repeat that fails fails the row
            row = dict(row, status="failed")
        elif len(ok) > 1:
            row.update(s_per_step=round(median(r["s_per_step"] for r in ok), 4), setup_s=round(median(r["setup_s"] for r in ok), 3))
        rows.append(row)
    return rows


def run_pairs(suite, ranks, steps):
    """A finite suite on one rank count: its variants (linear, then svk) back to back, PAIR_REPEATS
    times in turn when the first linear row's stepping is under SHORT_STEPPING_S; each row's s/step
    and set-up the medians, svk_over_linear on the svk row the median of the pairs' ratios."""
    linear, svk = suite["variants"]
    runs = [(run(suite, linear, ranks, steps), run(suite, svk, ranks, steps))]
    first = runs[0]
    short = all(r["status"] == "ok" for r in first) and first[0]["s_per_step"] * steps < SHORT_STEPPING_S
    for _ in range(PAIR_REPEATS - 1 if short else 0):
        runs.append((run(suite, linear, ranks, steps), run(suite, svk, ranks, steps)))
    rows = [dict(first[0], repeats=len(runs)), dict(first[1], repeats=len(runs))]
    if any(r["status"] != "ok" for pair in runs for r in pair):  # a repeat that fails fails both rows
        return [dict(r, status="failed", svk_over_linear="-", finite_target="-") for r in rows]
    for i, row in enumerate(rows):
        if len(runs) > 1:
            row.update(s_per_step=round(median(pair[i]["s_per_step"] for pair in runs), 4),
                       setup_s=round(median(pair[i]["setup_s"] for pair in runs), 3))
        row.update(svk_over_linear="-", finite_target="-")
    ratio = round(median(svk_row["s_per_step"] / lin["s_per_step"] for lin, svk_row in runs), 3)
    its = rows[1]["nonlinear_its_per_step"]
    met = its != "-" and ratio <= FINITE_TARGET["ratio"] and its <= FINITE_TARGET["its"]
    rows[1].update(svk_over_linear=ratio, finite_target="met" if met else "missed")
    return rows


def stream_bandwidth(ranks):
    """The STREAM triad bandwidth (MB/s, summed over the processes) of one run of build/stream."""
    proc = subprocess.run(MPIEXEC + ["-n", str(ranks), STREAM_EXE], cwd=ROOT, capture_output=True, text=True)
    found = STREAM.search(proc.stdout)
    if proc.returncode or not found:
        sys.exit(f"bench.py: {STREAM_EXE} on {ranks} process(es) failed (exit {proc.returncode}): {proc.stderr.strip()[-400:]}"
                 f"\n  build it with `make build/stream` (make bench does)")
    return float(found.group(2))


def measure_stream():
    """The 2-process over 1-process STREAM triad ratio, the median of STREAM_REPEATS alternating pairs;
    writes bench/stream.csv (every measurement) and returns the ratio."""
    if not os.path.exists(os.path.join(ROOT, STREAM_EXE)):
        sys.exit(f"bench.py: {STREAM_EXE} is missing: build it with `make build/stream` (make bench does)")
    pairs = [(stream_bandwidth(1), stream_bandwidth(2)) for _ in range(STREAM_REPEATS)]
    ratios = sorted(two / one for one, two in pairs)
    ratio = round(ratios[len(ratios) // 2], 3)
    with open(os.path.join(ROOT, "bench/stream.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["repeat", "triad_mbs_1", "triad_mbs_2", "ratio"])
        w.writerows([i, one, two, round(two / one, 3)] for i, (one, two) in enumerate(pairs))
    print(f"STREAM triad: 1 process {sorted(p[0] for p in pairs)[len(pairs) // 2]:.0f} MB/s, 2 processes "
          f"{sorted(p[1] for p in pairs)[len(pairs) // 2]:.0f} MB/s (medians of {STREAM_REPEATS}); ratio {ratio} "
          f"(the 2-rank ceiling of a memory-bound phase; written to bench/stream.csv)", flush=True)
    return ratio


def add_stream(rows, stream_ratio):
    """The STREAM ratio and the issue-21 target on each 2-rank row with a speed-up ("-" without a ratio)."""
    measured = stream_ratio != "-"
    target = min(SPEEDUP_TARGET, STREAM_FRACTION * stream_ratio) if measured else None
    for r in rows:
        has = measured and r["ranks"] == 2 and r["speedup_2_ranks"] != "-"
        r["stream_ratio"] = stream_ratio if r["ranks"] == 2 else "-"
        r["speedup_over_stream"] = round(r["speedup_2_ranks"] / stream_ratio, 3) if has else "-"
        r["speedup_target"] = ("met" if r["speedup_2_ranks"] >= target else "missed") if has else "-"


def add_ratios(rows):
    """contact/linear: s/step over the linear row's (same suite, ranks); 2-rank speed-up: the 1-rank
    row's s/step over the 2-rank row's (same suite, case), on the 2-rank row. "-" when a row is missing."""
    ok = {(r["suite"], r["case"], r["ranks"]): r["s_per_step"] for r in rows if r["status"] == "ok"}
    ratio = lambda a, b: round(ok[a] / ok[b], 3) if a in ok and b in ok and ok[b] > 0 else "-"
    for r in rows:
        key = (r["suite"], r["case"], r["ranks"])
        r["contact_over_linear"] = ratio(key, (r["suite"], "linear", r["ranks"]))
        r["speedup_2_ranks"] = ratio((r["suite"], r["case"], 1), key) if r["ranks"] == 2 else "-"


def auto_choice(suite, variant, ranks, steps):
    """What -contact_formulation auto chooses for a row's case (a -check_input run), or "-"."""
    v = dict(variant, options=" ".join(w for w in shlex.split(variant["options"]) if w not in ("-contact_formulation", "condensed", "active_set")))
    cmd = MPIEXEC + ["-n", str(ranks)] + mmcontact_args(suite, v, steps, "bench/out/auto-check") + ["-check_input"]
    m = FORMULATION.search(subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True).stdout)
    return m.group(1) if m else "-"


def add_auto_check(rows, variants):
    """auto_choice and auto_loss on the rows of each case run in both formulations (see the docstring)."""
    whole = lambda r: r["setup_s"] + r["steps"] * r["s_per_step"]
    groups = {}
    for r in rows:
        if r["status"] == "ok" and r.get("chosen_by") == "option" and r["formulation"] in ("condensed", "active_set"):
            key = (r["suite"], r["ranks"], r["mu"], r["friction_type"], r["elasticity"], r["problem"])
            groups.setdefault(key, {})[r["formulation"]] = r
    for key, byf in groups.items():
        if len(byf) < 2:
            continue
        auto_rows = [r for r in rows if r.get("chosen_by") == "auto" and (r["suite"], r["ranks"], r["mu"], r["friction_type"], r["elasticity"], r["problem"]) == key]
        if auto_rows:
            choice = auto_rows[0]["formulation"]
        else:
            suite, variant = variants[(byf["condensed"]["suite"], byf["condensed"]["case"])]
            choice = auto_choice(suite, variant, key[1], byf["condensed"]["steps"])
        best = min(whole(r) for r in byf.values())
        loss = round(whole(byf[choice]) / best - 1, 3) if choice in byf else "-"
        for r in list(byf.values()) + auto_rows:
            r.update(auto_choice=choice, auto_loss=loss)


def print_table(rows):
    cols = [("suite", 6), ("ranks", 5), ("case", 20), ("formulation", 11), ("mu", 4), ("friction_type", 13), ("cfl", 5), ("dofs", 8), ("contact_nodes", 13),
            ("steps", 5), ("setup_s", 8), ("s_per_step", 10), ("contact_over_linear", 19), ("speedup_2_ranks", 15),
            ("peak_mib_max_rank", 17), ("peak_mib_total", 14), ("candidates", 10), ("max_active", 10), ("mean_vi_its", 11),
            ("mean_friction_its_in_contact", 28), ("max_friction_its", 16), ("rejections", 10), ("stream_ratio", 12), ("speedup_over_stream", 19),
            ("speedup_target", 14), ("max_balance", 11), ("elasticity", 10), ("svk_over_linear", 15), ("nonlinear_its_per_step", 22),
            ("tangent_rebuilds", 16), ("finite_target", 13), ("chosen_by", 9), ("auto_choice", 11), ("auto_loss", 9), ("repeats", 7), ("status", 6)]
    print(" ".join(f"{name:>{width}}" for name, width in cols))
    for r in rows:
        print(" ".join(f"{r[name]:>{width}}" for name, width in cols))


def rank_rss(cmd):
    """--rank-rss mode, one per rank under mpiexec: runs cmd and reports its peak RSS on stderr."""
    code = subprocess.call(cmd)
    print(f"bench rank peak rss {resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss} kB", file=sys.stderr)
    return code


def main(args):
    selected = (args or os.environ.get("BENCH_CASES", "2d,3d,surface,users").split(","))
    ranks = [int(n) for n in os.environ["BENCH_RANKS"].split(",")] if os.environ.get("BENCH_RANKS") else None
    names = [suite["suite"] for suite in SUITES] + [suite.get("group") for suite in SUITES if suite.get("group")]
    unknown = [s for s in selected if s.split(":")[0] not in names]
    if unknown:
        sys.exit(f"bench.py: unknown suite(s) {unknown}; the suites are {names}")
    os.makedirs(os.path.join(ROOT, "bench"), exist_ok=True)
    stream_ratio = measure_stream() if ranks is None or 2 in ranks else "-"
    rows = []
    for suite in SUITES:
        steps = int(os.environ.get("BENCH_STEPS", suite["steps"]))
        suite_rows = []
        for variant in suite["variants"]:
            chosen = suite["suite"] in selected or suite.get("group") in selected or f"{suite['suite']}:{variant['case']}" in selected
            on = [n for n in suite["ranks"] if ranks is None or n in ranks]
            if chosen and on and not suite.get("pairs"):
                suite_rows += run_case(suite, variant, on, steps)
        chosen = (suite["suite"] in selected or suite.get("group") in selected
                  or any(f"{suite['suite']}:{v['case']}" in selected for v in suite["variants"]))
        if suite.get("pairs") and chosen:  # the finite suites: a pair of rows, not a case over ranks
            for n in [n for n in suite["ranks"] if ranks is None or n in ranks]:
                suite_rows += run_pairs(suite, n, steps)
        rows += sorted(suite_rows, key=lambda r: r["ranks"])  # by ranks, then the variants' order (stable)
    add_ratios(rows)
    add_stream(rows, stream_ratio)
    add_auto_check(rows, {(suite["suite"], v["case"]): (suite, v) for suite in SUITES for v in suite["variants"]})
    for r in rows:
        for k in ("svk_over_linear", "finite_target", "chosen_by", "auto_choice", "auto_loss"):
            r.setdefault(k, "-")
    for path in dict.fromkeys(suite["csv"] for suite in SUITES):
        written = [r for suite in SUITES if suite["csv"] == path for r in rows if r["suite"] == suite["suite"]]
        if written:
            with open(os.path.join(ROOT, path), "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=FIELDS)
                w.writeheader()
                w.writerows(written)
            print(f"written to {path}")
    print_table(rows)
    return 1 if any(r["status"] != "ok" for r in rows) else 0


if __name__ == "__main__":
    if sys.argv[1:2] == ["--rank-rss"]:
        sys.exit(rank_rss(sys.argv[2:]))
    sys.exit(main(sys.argv[1:]))
