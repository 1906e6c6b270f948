"""Checking a case before it runs (mmcontact -check_input) on two-body contact (contact pairs,
bodies) and corner rows (issue 20): its counts and gaps are a run's, read from the run's header and
first snapshot. These were checks of the former Python check_case.py; they now hold against
mmcontact's own report."""
import re

import pytest

from conftest import ROOT, run
from test_check_case_geometry import check, obstacle_gaps, opts_with

PAIR_HEADER = r"pair p: slave \S+, (\d+) nodes \((\d+) facing a master node: node to node\), on (\d+) facets"
CFL = r"c_p dt / h_c' = (\S+)"


def shift_msh(src, dst, xmin, dx):
    """A copy of the gmsh 4.1 mesh src with its nodes at x > xmin moved by dx along x."""
    lines = open(src).read().split("\n")
    i = lines.index("$Nodes") + 2
    while lines[i] != "$EndNodes":
        n = int(lines[i].split()[3])
        for k in range(i + 1 + n, i + 1 + 2 * n):
            c = [float(v) for v in lines[k].split()]
            if c[0] > xmin:
                c[0] += dx
            lines[k] = " ".join(repr(v) for v in c)
        i += 1 + 2 * n
    open(dst, "w").write("\n".join(lines))


@pytest.mark.parametrize("case", ["two_bars", "two_balls", "ball_block"])
def test_pair_gap_and_counts_are_mmcontacts(tmp_path, case):
    """Each pair's slave nodes, those facing a master node and the master facets are the counts of
    the run's header line, the slave nodes those of its contact_obstacle field; the smallest gap is
    the smallest of the run's gap field at t = 0 over the slave nodes (node to node on two_balls,
    node to facet on ball_block, 1D on two_bars, where it is the geometric 1.005 - 1 = 0.005 and the
    bars, at +-0.01, meet at t = 0.25). No rigid obstacle: no 'contact' group is needed."""
    rc, out, err = check(case, tmp_path)
    assert rc == 0, out + err
    m = re.search(PAIR_HEADER, out)
    nslave, gap = obstacle_gaps(out)["p"]
    r = run(case, tmp_path, "-ts_max_steps", 1, np_=1)
    h = re.search(PAIR_HEADER, r.output)
    assert m and h and m.groups() == h.groups() and int(m[1]) == nslave, (out, r.output[-2000:])
    with r.fields() as f:
        assert f["time"][0, 0] == 0
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
        g0 = f["vertex_fields/gap_nodal"][0]
    assert int((owner == 0).sum()) == nslave
    assert abs(gap - g0[owner == 0].min()) <= 1e-5 * abs(gap), (gap, g0[owner == 0].min())
    if case == "two_bars":
        assert abs(gap - 0.005) <= 1e-6 * 0.005
        assert "first contact: t ~ 0.25 (step 25)" in out, out
    assert re.search(CFL, out)[1] == re.search(CFL, r.output)[1]


def test_overlapping_slave_is_refused(tmp_path):
    """two_bars with bar B moved 0.01 to the left overlaps bar A by 0.005: -check_input refuses it as
    the run does, naming the slave node and its depth."""
    shift_msh(f"{ROOT}/meshes/two_bars.msh", tmp_path / "overlap.msh", 1.0025, -0.01)
    opts = opts_with(tmp_path, "two_bars", [("-mesh", tmp_path / "overlap.msh")])
    r = run(str(opts), tmp_path, np_=0, check=False)
    h = re.search(r"penetrates the obstacle \"p\": the deepest contact node, at \((\S+), (\S+)\), is (\S+) inside it", r.output)
    assert r.returncode == 64 and h, r.output[-1500:]
    assert abs(float(h[3]) - 0.005) <= 1e-6 * 0.005
    rc, out, err = check(opts, tmp_path)
    assert rc == 64 and h[0] in err.splitlines()[0] and err.splitlines()[0] in r.output, err


def test_bodies_cells_and_largest_wave_speed(tmp_path):
    """Bar B four times stiffer: c_p dt / h_c' uses the largest c_p (2), as the run's header does; a
    body list that leaves bar B's 600 cells out is refused as the run refuses it."""
    opts = opts_with(tmp_path, "two_bars", [("-body_b_E", 4)])
    rc, out, err = check(opts, tmp_path)
    assert rc == 0 and "body b (group bar_b): 600 cells" in out and "group bar_b: 600 cells" in out, out + err
    assert "the largest wave speed, c_p = 2, sets c_p dt / h_c'" in out, out
    r = run(str(opts), tmp_path, "-ts_max_steps", 1, np_=0)
    assert re.search(CFL, out)[1] == re.search(CFL, r.output)[1]
    one = opts_with(tmp_path, "two_bars", [("-bodies", "a")])
    r = run(str(one), tmp_path, np_=0, check=False, name="one")
    rc, out, err = check(one, tmp_path)
    assert rc == r.returncode == 64 and err.splitlines()[0] in r.output, (err, r.output[-1500:])


@pytest.mark.parametrize("case,extra", [("cube_groove", []), ("block_push", [("-mu", 0)]), ("block_push", [])])
def test_corner_rows_are_mmcontacts(tmp_path, case, extra):
    """Frictionless, the contact nodes within h_c' of a second, non-parallel obstacle get a row for
    it: 14 on cube_groove (the lower edge and its neighbours: 83 nodes, 97 rows), 3 on block_push
    without friction (the corner and its two neighbours). With friction (block_push as it is) the same
    3 vertices are friction corners, one row each carrying both obstacles' laws (issue 38 item 2).
    -check_input's report has the run's counts."""
    opts = opts_with(tmp_path, case, extra) if extra else case
    rc, out, err = check(opts, tmp_path)
    assert rc == 0, out + err
    r = run(str(opts) if extra else case, tmp_path, "-ts_max_steps", 1, np_=1)
    line = lambda text: [l for l in text.splitlines() if l.startswith("  contact: ")]
    assert line(out) == line(r.output) and len(line(out)) == 1, (out, r.output[-2000:])
    h = re.search(r"contact: (\d+) contact nodes \((\d+) of them against two obstacles: (\d+) rows\)", out)
    hf = re.search(r"contact: 31 contact nodes \((\d+) of them against two obstacles, each with its own Coulomb law\)", out)
    if extra or case == "cube_groove":
        assert h and int(h[2]) == {"cube_groove": 14, "block_push": 3}[case], out
        assert int(h[1]) + int(h[2]) == int(h[3])
    else:
        assert not h and hf and int(hf[1]) == 3, out
    # the contact nodes of the obstacles: all of them, once
    assert sum(n for n, _ in obstacle_gaps(out).values()) == {"cube_groove": 83, "block_push": 31}[case]
