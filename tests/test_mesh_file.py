"""What the mesh file itself can get wrong (README "What is checked before the run"), and the
serial_vertex field against the file's nodes, with a node that no element uses."""
import os
import subprocess

import h5py
import numpy as np
import pytest

from conftest import EXE, MPIEXEC, ROOT

# a unit square meshed by gmsh, with a point (5, 5) that no element uses, first in the file
GEO = """Point(1) = {5, 5, 0, 0.3};
Point(2) = {0, 0, 0, 0.3}; Point(3) = {1, 0, 0, 0.3}; Point(4) = {1, 1, 0, 0.3}; Point(5) = {0, 1, 0, 0.3};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("contact") = {1}; Physical Surface("body") = {1};
"""
CASE = ["-contact_boundary", "contact", "-E", 1000, "-v0", "0,-1", "-obstacle_point", "0,-0.01", "-ts_dt", 1e-3, "-ts_max_steps", 3, "-quiet"]


@pytest.fixture(scope="module")
def square(tmp_path_factory):
    d = tmp_path_factory.mktemp("square")
    (d / "sq.geo").write_text(GEO)
    for fmt in ("msh22", "msh41"):
        subprocess.run(["gmsh", "-2", str(d / "sq.geo"), "-format", fmt, "-o", str(d / f"{fmt}.msh"), "-v", "2"], check=True)
    # -save_all: every node and element, the isolated point's too (node 1, in no cell)
    subprocess.run(["gmsh", "-2", str(d / "sq.geo"), "-format", "msh22", "-save_all", "-o", str(d / "all22.msh"), "-v", "2"], check=True)
    return d


def nodes41(path):
    """The nodes of an ASCII gmsh 4.1 file, in file order: tags and coordinates."""
    lines = open(path).read().split("$Nodes\n")[1].split("$EndNodes")[0].splitlines()[1:]
    tags, xyz, i = [], [], 0
    while i < len(lines):
        n = int(lines[i].split()[3])
        tags += [int(l) for l in lines[i + 1:i + 1 + n]]
        xyz += [[float(v) for v in l.split()[:3]] for l in lines[i + 1 + n:i + 1 + 2 * n]]
        i += 1 + 2 * n
    return tags, np.array(xyz)


def with_unused_first_node(src, dst):
    """The 4.1 file with one more node, (5, 5), first in $Nodes and used by no element."""
    s = open(src).read()
    head = s.split("$Nodes\n")[1].splitlines()[0].split()
    blocks, n, lo, hi = map(int, head)
    new = f"$Nodes\n{blocks + 1} {n + 1} {lo} {hi + 1}\n0 1 0 1\n{hi + 1}\n5 5 0\n"
    open(dst, "w").write(s.replace("$Nodes\n" + " ".join(head) + "\n", new, 1))


def mmcontact(mesh, outdir, np_=0):
    launcher = MPIEXEC + ["-n", str(np_)] if np_ else []
    return subprocess.run(launcher + [EXE, "-mesh", str(mesh), "-output_dir", str(outdir), *map(str, CASE)], cwd=ROOT, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("np_", [1, 2])
def test_serial_vertex_is_the_node_position_in_the_file(square, tmp_path, np_):
    """With an unused node first in the file (PETSc's 4.1 reader skips it), serial_vertex still gives
    each written vertex its position among the file's nodes: the coordinates agree exactly (they
    were off by one node)."""
    mesh = tmp_path / "unused.msh"
    with_unused_first_node(square / "msh41.msh", mesh)
    r = mmcontact(mesh, tmp_path / "out", np_)
    assert r.returncode == 0, r.stderr[-2000:]
    tags, Y = nodes41(mesh)
    with h5py.File(tmp_path / "out" / "solution.h5", "r") as f:
        X = f["geometry/vertices"][:]
        s = f["vertex_fields/serial_vertex_nodal"][:].astype(int)
    assert len(X) == len(Y) - 1 and s.min() == 1 and len(set(s)) == len(s)
    assert np.array_equal(X, Y[s, :2])


def test_unused_node_of_a_gmsh2_file_is_refused(square, tmp_path):
    """gmsh -save_all writes the isolated point's node, and PETSc's 2.2 reader keeps it as a vertex:
    it would have no mass (a zero pivot in the mass solve). It is refused by its tag and place."""
    r = mmcontact(square / "all22.msh", tmp_path / "out")
    assert r.returncode == 64
    assert r.stderr.startswith(f'mmcontact error: Mesh file "{square}/all22.msh" (-mesh): node 1 at (5., 5.) belongs to no element'), r.stderr[:500]


@pytest.mark.parametrize("fmt", ["msh22", "msh41"])
def test_nan_coordinate_is_named_by_node(square, tmp_path, fmt):
    """A NaN coordinate is named by its node's tag, not taken for an inverted element."""
    lines = open(square / f"{fmt}.msh").read().split("\n")
    start = lines.index("$Nodes")
    if fmt == "msh22":
        k = next(i for i in range(start + 2, len(lines)) if lines[i].split()[1:] == ["0.2499999999994109", "0", "0"])
        tag = int(lines[k].split()[0])
        lines[k] = f"{tag} nan 0 0"
    else:
        tags, Y = nodes41(square / "msh41.msh")
        j = next(i for i, (x, y, _) in enumerate(Y) if 0 < x < 1 and y == 0)
        tag = tags[j]
        k = next(i for i in range(start + 2, len(lines)) if len(lines[i].split()) == 3 and
                 all(abs(float(a) - b) <= 1e-12 for a, b in zip(lines[i].split(), Y[j])))
        lines[k] = "nan 0 0"
    mesh = tmp_path / "nan.msh"
    mesh.write_text("\n".join(lines))
    r = mmcontact(mesh, tmp_path / "out")
    assert r.returncode == 64
    assert f"node {tag} has a non-finite coordinate" in r.stderr.splitlines()[0], r.stderr[:500]
    assert "inverted" not in r.stderr


def test_byte_order_mark_and_directory_are_named(square, tmp_path):
    bom = tmp_path / "bom.msh"
    bom.write_bytes(b"\xef\xbb\xbf" + open(square / "msh41.msh", "rb").read())
    r = mmcontact(bom, tmp_path / "out")
    assert r.returncode == 64 and "starts with a UTF-8 byte order mark" in r.stderr.splitlines()[0]
    d = mmcontact(square, tmp_path / "out")
    assert d.returncode == 64 and d.stderr.splitlines()[0] == f"mmcontact error: -mesh {square} is a directory: give the .msh file in it (make meshes writes meshes/NAME.msh from meshes/NAME.geo)"
