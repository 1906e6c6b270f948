"""scripts/check_case.py on two-body contact (contact pairs, bodies) and corner rows (issue 20): its
counts and gaps are mmcontact's, read from mmcontact's header and its first snapshot."""
import re

import numpy as np
import pytest

from conftest import ROOT, run
from test_check_case_geometry import check_case, opts_with

PAIR_CHECK = r"pair p: slave \S+, (\d+) vertices \((\d+) facing a master vertex: node to node\), on (\d+) facets of master \S+; mu \S+; smallest gap (\S+) at"
PAIR_HEADER = r"pair p: slave \S+, (\d+) nodes \((\d+) facing a master node: node to node\), on (\d+) facets"


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
    """Each pair's slave vertices, those facing a master vertex (weight 1 after the snap) and the
    master facets are the counts of mmcontact's header line; the smallest gap is the smallest of
    mmcontact's gap field at t = 0 over the slave nodes (node to node on two_balls, node to facet on
    ball_block, 1D on two_bars, where it is the geometric 1.005 - 1 = 0.005 and the bars, at +-0.01,
    meet at t = 0.25). No rigid obstacle: no 'contact' group is needed."""
    c = check_case(f"options/{case}.opts")
    assert c.returncode == 0, c.stdout + c.stderr
    m = re.search(PAIR_CHECK, c.stdout)
    assert m, c.stdout
    nslave, facing, nfacets, gap = int(m[1]), int(m[2]), int(m[3]), float(m[4])
    r = run(case, tmp_path, "-ts_max_steps", 1, np_=1)
    h = re.search(PAIR_HEADER, r.output)
    assert h, r.output[-2000:]
    assert (nslave, facing, nfacets) == tuple(map(int, h.groups()))
    with r.fields() as f:
        assert f["time"][0, 0] == 0
        owner = f["vertex_fields/contact_obstacle_nodal"][:]
        g0 = f["vertex_fields/gap_nodal"][0]
    assert int((owner == 0).sum()) == nslave
    assert abs(gap - g0[owner == 0].min()) <= 1e-5 * abs(gap), (gap, g0[owner == 0].min())
    if case == "two_bars":
        assert abs(gap - 0.005) <= 1e-6 * 0.005
        assert "rigid-body first contact t ~ 0.25 (step 25)" in c.stdout, c.stdout
    m = re.search(r"c_p dt / h_c' (\S+),", c.stdout)
    h = re.search(r"c_p dt / h_c' = (\S+)", r.output)
    assert m and h and abs(float(m[1]) - float(h[1])) <= 1e-3 * float(h[1]), (m, h)


def test_overlapping_slave_is_an_error(tmp_path):
    """two_bars with bar B moved 0.01 to the left overlaps bar A by 0.005: check_case.py exits 1 with
    an ERROR naming the slave vertex and its depth, the node and depth at which mmcontact refuses the
    run."""
    shift_msh(f"{ROOT}/meshes/two_bars.msh", tmp_path / "overlap.msh", 1.0025, -0.01)
    opts = opts_with(tmp_path, "two_bars", [("-mesh", tmp_path / "overlap.msh")])
    c = check_case(opts)
    assert c.returncode == 1, c.stdout
    m = re.search(r"ERROR: pair p: slave vertex at \((\S+), (\S+)\) starts inside the master body \(gap (\S+)\)", c.stdout)
    assert m, c.stdout
    r = run(str(opts), tmp_path, np_=0, check=False)
    h = re.search(r"penetrates the obstacle \"p\": the deepest contact node, at \((\S+), (\S+)\), is (\S+) inside it", r.output)
    assert r.returncode != 0 and h, r.output[-1500:]
    assert abs(float(m[1]) - float(h[1])) <= 1e-6 and abs(float(m[2]) - float(h[2])) <= 1e-6
    assert abs(-float(m[3]) - 0.005) <= 1e-6 * 0.005 and abs(float(h[3]) - 0.005) <= 1e-6 * 0.005


def test_bodies_cells_and_largest_wave_speed(tmp_path):
    """Bar B four times stiffer: c_p dt / h_c' uses the largest c_p (2), as mmcontact's header does; a
    body list that leaves bar B's 600 cells out is an ERROR."""
    opts = opts_with(tmp_path, "two_bars", [("-body_b_E", 4)])
    c = check_case(opts)
    assert c.returncode == 0 and "body b (group bar_b): 600 cells" in c.stdout, c.stdout
    m = re.search(r"c_p (\S+) \(the largest over the bodies\), h_c' \S+, dt \S+, c_p dt / h_c' (\S+),", c.stdout)
    r = run(str(opts), tmp_path, "-ts_max_steps", 1, np_=0)
    h = re.search(r"c_p dt / h_c' = (\S+)", r.output)
    assert m and h and float(m[1]) == 2.0 and abs(float(m[2]) - float(h[1])) <= 1e-3 * float(h[1]), (m, h)
    c = check_case(opts_with(tmp_path, "two_bars", [("-bodies", "a")]))
    assert c.returncode == 1 and "ERROR: 600 of the mesh's 920 cells are in no body's group" in c.stdout, c.stdout


@pytest.mark.parametrize("case,extra", [("cube_groove", []), ("block_push", [("-mu", 0)]), ("block_push", [])])
def test_corner_rows_are_mmcontacts(tmp_path, case, extra):
    """Frictionless, the contact vertices within h_c' of a second, non-parallel obstacle get a row for
    it: 14 on cube_groove (the lower edge and its neighbours: 83 nodes, 97 rows), 3 on block_push
    without friction (the corner and its two neighbours), the counts of mmcontact's header. With
    friction (block_push as it is) the same 3 vertices are friction corners, one row each carrying
    both obstacles' laws (issue 38), as mmcontact's header counts them."""
    opts = opts_with(tmp_path, case, extra) if extra else f"options/{case}.opts"
    c = check_case(opts)
    assert c.returncode == 0, c.stdout
    r = run(str(opts) if extra else case, tmp_path, "-ts_max_steps", 1, np_=1)
    h = re.search(r"contact: (\d+) contact nodes \((\d+) of them against two obstacles: (\d+) rows\)", r.output)
    m = re.search(r"contact vertices (\d+) \(.*\n(?:.*\n)*?  corners: (\d+) contact vertices within h_c' of a second obstacle get a row for it too \((\d+) rows", c.stdout)
    w = re.search(r"friction corners: (\d+) contact vertices within h_c' of a second obstacle carry its Coulomb law too", c.stdout)
    hf = re.search(r"contact: 31 contact nodes \((\d+) of them against two obstacles, each with its own Coulomb law\)", r.output)
    if extra or case == "cube_groove":
        assert h and m and not w, (r.output[-2000:], c.stdout)
        assert tuple(map(int, m.groups())) == tuple(map(int, h.groups()))
        assert int(m[2]) == {"cube_groove": 14, "block_push": 3}[case]
    else:
        assert not h and hf and int(hf[1]) == 3, r.output[-2000:]
        assert w and int(w[1]) == 3 and "  corners:" not in c.stdout, c.stdout
