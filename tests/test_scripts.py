"""The study and plot scripts (README "Plots", docs/validation.md "Convergence in dt"): each runs the real
executable through mpiexec, or reads what it wrote, and the tests assert their numbers."""
import csv
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from conftest import EXE, ROOT

SCRIPTS = os.path.join(ROOT, "scripts")
sys.path.insert(0, SCRIPTS)
from mmrun import Solution, read_history  # noqa: E402
import plot_contact  # noqa: E402

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
# D1 without contact from a uniform strain: the free disk rings. dt = 2.5e-4 is c_p dt / h_c' = 0.11,
# where the highest mesh modes the strain excites are resolved and the trapezoidal rule shows its
# order; at dt = 2e-3 they are not, and the rates are 0.7 to 1.6.
LINEAR = "-contact 0 -u0_gradient 0.01,0.005,0,-0.01 -ts_max_time 0.04"


def script(name, *args, check=True):
    proc = subprocess.run([sys.executable, "-s", os.path.join(SCRIPTS, name), *map(str, args)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    if check:
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return proc


def table(outdir):
    with open(os.path.join(outdir, "dt_convergence.csv")) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def assert_png(path):
    assert os.path.getsize(path) > 10000, path
    with open(path, "rb") as f:
        assert f.read(8) == PNG_MAGIC, path


def test_dt_convergence_is_second_order_without_contact(tmp_path):
    """Linear elastodynamics: the trapezoidal rule's rate 2, in the energy norm and in L2, from the
    finest pairs; the errors fall by about 4 per halving. Also checks what the table says of itself."""
    out = tmp_path / "lin"
    r = script("dt_convergence.py", "options/d1_disk.opts", "--dt", 2.5e-4, "--levels", 4, "--np", 1,
               "--every", 40, "--extra", LINEAR, "--out", out, "--exe", EXE)
    rows = table(out)
    assert [row["steps"] for row in rows] == [160, 320, 640, 1280]
    assert [row["dt"] for row in rows] == pytest.approx([2.5e-4 / 2 ** k for k in range(4)], rel=1e-12)
    for k in ("energy", "L2"):
        for lev in (0, 1):  # the two rates four levels give
            assert 1.8 <= rows[lev][f"{k}_rate"] <= 2.2, (k, lev, rows[lev][f"{k}_rate"])
        err = [row[f"{k}_error"] for row in rows[:3]]
        assert err[0] > 3 * err[1] > 9 * err[2] > 0, (k, err)
        assert 1e-5 < err[0] < 0.1, (k, err)  # a real error, relative to the solution's norm
    # no contact: M* is M, and no contact force
    assert all(row["energy_M_error"] == pytest.approx(row["energy_error"], rel=1e-12) for row in rows[:3])
    assert all(row["force_error"] == 0 for row in rows[:3])
    assert "rate" in r.stdout and os.path.exists(out / "dt_convergence.png")
    assert_png(out / "dt_convergence.png")
    # the script's norms are the scheme's: read with another Young's modulus than the runs used,
    # its stiffness no longer gives history.csv's elastic energy and it stops
    bad = script("dt_convergence.py", "options/d1_disk.opts", "--dt", 2.5e-4, "--levels", 4, "--every", 40,
                 "--extra", LINEAR + " -E 1100", "--out", out, "--no-run", check=False)
    assert bad.returncode != 0 and "differ from history.csv" in bad.stderr, bad.stderr[-1000:]


@pytest.mark.parametrize("case", ["d1_disk", "d1_friction"])
def test_dt_convergence_d1_errors_decrease(tmp_path, case):
    """D1 with and without friction, at the case's dt 2e-3 and three halvings: the errors against
    the finest and the differences between successive levels decrease (Theorem 5.2: the fully
    discrete solution converges to the semi-discrete one as dt -> 0, with no rate). The rates are
    below the trapezoidal rule's 2: the contact is not smooth."""
    out = tmp_path / case
    script("dt_convergence.py", f"options/{case}.opts", "--levels", 4, "--np", 1, "--every", 10,
           "--out", out, "--exe", EXE)
    rows = table(out)
    assert [row["steps"] for row in rows] == [150, 300, 600, 1200]
    for k in ("energy", "energy_M", "L2", "force"):
        err = [row[f"{k}_error"] for row in rows[:3]]
        diff = [row[f"{k}_diff"] for row in rows[:3]]
        assert err[0] > err[1] > err[2] > 0, (k, err)
        assert diff[0] > diff[1] > diff[2] > 0, (k, diff)
    for lev in (0, 1):
        assert 0.4 < rows[lev]["energy_rate"] < 1.5, rows[lev]["energy_rate"]
    # the modified mass drops the contact nodes' normal velocity from the energy norm: M and M* differ
    assert rows[0]["energy_scale"] < rows[0]["energy_M_scale"]


def test_runs_are_compared_vertex_by_vertex_whatever_their_numbering(mm):
    """Runs on 1 and 2 ranks number the vertices differently (on several ranks the order follows
    the partition); the scripts match them by coordinates, and then the fields agree."""
    one = Solution(mm("d1_disk", "-ts_max_time", 0.04, np_=1, name="one").outdir)
    two = Solution(mm("d1_disk", "-ts_max_time", 0.04, np_=2, name="two").outdir)
    assert np.abs(one.vertices - two.vertices).max() > 0.1  # the orders differ
    two.reorder_like(one, "two")
    assert np.array_equal(one.vertices, two.vertices) and np.array_equal(one.obstacle, two.obstacle)
    scale = np.abs(one.displacement).max()
    assert np.abs(one.displacement - two.displacement).max() <= 1e-10 * scale
    assert np.abs(one.velocity - two.velocity).max() <= 1e-10 * np.abs(one.velocity).max()
    assert np.abs(one.pressure - two.pressure).max() <= 1e-8 * np.abs(one.pressure).max()


def test_plot_contact_2d_orders_the_boundary_and_writes_the_map(mm):
    """D1 with friction: the contact boundary (the lower half of the disk, 33 nodes) is chained in
    order, its arc length is the polygon's, the nodal pressures times the nodal lengths give
    history.csv's force, and the PNG is written."""
    r = mm("d1_friction", "-ts_max_time", 0.22, "-output_every", 2, np_=2)
    sol = Solution(r.outdir)
    chains = plot_contact.contact_chains(sol)
    assert len(chains) == 1 and len(chains[0]) == 33 == len(sol.contact_nodes)
    x = sol.vertices[chains[0]]
    angle = np.unwrap(np.arctan2(x[:, 1] - 1.01, x[:, 0]))
    steps = np.diff(angle)
    assert np.all(np.abs(steps - steps[0]) < 1e-6) and abs(abs(angle[-1] - angle[0]) - np.pi) < 1e-9
    s = plot_contact.arc_lengths(sol, chains)[0]
    assert s[-1] == pytest.approx(64 * np.sin(np.pi / 64), rel=1e-12)  # 32 chords of the unit circle
    snap, force = plot_contact.peak_snapshot(sol, plot_contact.contact_facets(sol))
    h = r.history
    rows = [int(np.argmin(np.abs(h["time"] - t))) for t in sol.time]
    assert np.abs(force - h["force_normal"][rows]).max() <= 1e-12 * force.max()
    assert force[snap] == pytest.approx(h["force_normal"].max(), rel=0.02)
    out = script("plot_contact.py", r.outdir, "--point", "0.3,0.05")
    png = os.path.join(r.outdir, "contact_pressure.png")
    assert f"plot: {png}" in out.stdout
    assert_png(png)


def test_plot_contact_3d_fits_the_plane_and_writes_the_map(mm):
    """D2: the plane fitted through the nodes in contact is the obstacle's, z = 0 with normal +z;
    the map is drawn at the snapshot of peak force, which matches history.csv's."""
    r = mm("d2_ball", "-ts_max_time", 0.2, "-output_every", 2, np_=1)
    sol = Solution(r.outdir)
    facets = plot_contact.contact_facets(sol)
    snap, force = plot_contact.peak_snapshot(sol, facets)
    n, t1, t2 = plot_contact.plane_axes(sol, snap)
    assert np.abs(n - [0, 0, 1]).max() < 1e-9
    assert abs(n @ t1) < 1e-12 and abs(n @ t2) < 1e-12 and abs(t1 @ t2) < 1e-12
    h = r.history
    rows = [int(np.argmin(np.abs(h["time"] - t))) for t in sol.time]
    assert np.abs(force - h["force_normal"][rows]).max() <= 1e-12 * force.max()
    script("plot_contact.py", r.outdir)
    assert_png(os.path.join(r.outdir, "contact_pressure.png"))


def test_compare_mass_standard_mass_chatters(tmp_path):
    """D1 with each mass: one smooth force pulse with the modified mass (total variation twice its
    peak), a chattering force with the standard mass; the figure is written."""
    out = tmp_path / "cmp"
    r = script("compare_mass.py", "options/d1_disk.opts", "--np", 1, "--every", 3, "--out", out, "--exe", EXE)
    assert_png(out / "compare_mass.png")
    osc = {}
    for m in ("modified", "standard"):
        f = read_history(str(out / m))["force_normal"]
        osc[m] = np.abs(np.diff(f)).sum() / (2 * f.max())
        assert f"{m} mass: force oscillation {osc[m]:.3f}" in r.stdout
    assert osc["modified"] < 1.05 and osc["standard"] > 5, osc


def test_bench_reads_the_finite_strain_summary(mm):
    """scripts/bench.py's finite suites (issue 40) read the run summary: its s/step, largest balance
    residual and the "finite strain:" line's iterations per step and tangent rebuilds. A D2 ball with
    svk and friction through first contact (ball10, dt 4e-3: contact from step 3); the iterations per
    step the bench reads are the line's total over its steps."""
    import bench
    r = mm("d2_ball", "-mesh", "meshes/ball10.msh", "-ts_dt", 4e-3, "-ts_max_steps", 4, "-ts_max_time", 1, "-output_every", 0,
           "-mu", 0.2, "-elasticity", "svk", np_=1)
    summary, balance = bench.SUMMARY.search(r.output), bench.BALANCE.search(r.output)
    nonlinear, rebuilds = bench.NONLINEAR.search(r.output), bench.REBUILDS.search(r.output)
    assert summary and balance and nonlinear and rebuilds, r.output[-2000:]
    assert float(summary.group(3)) > 0 and 0 <= float(balance.group(1)) <= 1e-10
    total = re.search(r"finite strain: [\d.]+ iterations per step \((\d+) over (\d+) steps\)", r.output)
    assert total and int(total.group(2)) == 4, r.output[-2000:]
    assert float(nonlinear.group(1)) == pytest.approx(int(total.group(1)) / 4, abs=0.005)
    assert float(nonlinear.group(1)) > 1  # the contact steps iterate
    assert int(rebuilds.group(1)) >= 0
    # a linear run has no finite-strain line: the bench leaves those columns "-"
    lin = mm("d2_ball", "-mesh", "meshes/ball10.msh", "-ts_dt", 4e-3, "-ts_max_steps", 2, "-ts_max_time", 1, "-output_every", 0,
             np_=1, name="lin")
    assert bench.BALANCE.search(lin.output) and not bench.NONLINEAR.search(lin.output)
