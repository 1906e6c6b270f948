"""The facet physical groups of a mesh read without faces (src/mesh/facets.c): each rank interpolates
its own part after the distribution, and the facet elements read from the file label the faces.
PETSc's gmsh reader labels them itself only when it interpolates the whole mesh on rank 0, which it
still does for a binary file: the binary copy of a mesh is the reference. The same contact nodes,
Dirichlet dofs, tractions and master surfaces must follow, on 1 and 2 ranks, in 2D and 3D."""
import re
import subprocess

import numpy as np
import pytest

from conftest import ROOT, run


def binary_copy(mesh, tmp_path):
    """The mesh as gmsh writes it in binary 4.1: the same nodes, elements and groups."""
    out = tmp_path / ("bin_" + mesh.split("/")[-1])
    subprocess.run(["gmsh", f"{ROOT}/{mesh}", "-0", "-bin", "-format", "msh41", "-o", str(out), "-v", "2"], check=True)
    return str(out)


def contact_nodes(output):
    m = re.search(r"contact: (\d+) contact nodes", output)
    return int(m.group(1)) if m else None


CASES = {
    # 3D: the contact surface against a plane
    "d2_ball": ("d2_ball", "meshes/ball.msh", ("-ts_max_time", 0.06)),
    # 3D: a slave and a master surface of two bodies, a Dirichlet surface on the block
    "ball_block": ("ball_block", "meshes/ball_block.msh", ("-ts_max_time", 0.06)),
    # 2D: a Dirichlet curve and a traction curve
    "bar_ramp": ("bar_ramp", "meshes/bar80.msh", ("-ts_max_time", 20, "-traction_right_amplitude_time", 10)),
    # 2D: the contact curve
    "d1_disk": ("d1_disk", "meshes/disk.msh", ("-ts_max_time", 0.01)),
}


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("case", sorted(CASES))
def test_facet_groups_are_those_of_petsc_reader(case, np_, tmp_path):
    opts, mesh, extra = CASES[case]
    ascii_run = run(opts, tmp_path, *extra, "-output_every", 0, np_=np_, name="ascii")
    binary_run = run(opts, tmp_path, *extra, "-mesh", binary_copy(mesh, tmp_path), "-output_every", 0, np_=np_, name="binary")
    assert contact_nodes(ascii_run.output) == contact_nodes(binary_run.output)
    a, b = ascii_run.history, binary_run.history
    assert len(a) == len(b) and len(a) >= 5
    scale = max(np.abs(a["total"]).max(), np.abs(a["work_ext"]).max())
    for c in ("kinetic", "elastic", "total", "work_ext", "work_contact"):
        assert np.abs(a[c] - b[c]).max() <= 1e-10 * scale, c
    assert np.array_equal(a["active"], b["active"])
    # the runs do something with their groups: contact, or the load's work
    assert a["active"].max() > 0 or np.abs(a["work_ext"]).max() > 0


def elements(text):
    """The 2D 4.1 file's facet element lines (2-node lines), as (index, tag, nodes), and triangles."""
    lines = text.split("\n")
    start = lines.index("$Elements")
    nblocks = int(lines[start + 1].split()[0])
    i, facets, triangles = start + 2, [], []
    for _ in range(nblocks):
        edim, _, etype, n = map(int, lines[i].split())
        for k in range(i + 1, i + 1 + n):
            if edim == 1 and etype == 1:
                facets.append((k, *map(int, lines[k].split())))
            if etype == 2:
                triangles.append(set(map(int, lines[k].split()[1:])))
        i += 1 + n
    return lines, facets, triangles


def test_facet_off_the_cells_is_refused(tmp_path):
    """A facet element whose nodes are not a face of any cell (the first segment of a facet group
    made to join two nodes that share no triangle) is refused, naming its group and nodes."""
    text = open(f"{ROOT}/meshes/bar80.msh").read()
    lines, facets, triangles = elements(text)
    k, tag, n0, n1 = facets[0]
    far = next(n for f in facets for n in f[2:] if not any({n0, n} <= t for t in triangles))
    lines[k] = f"{tag} {n0} {far}"
    mesh = tmp_path / "bad.msh"
    mesh.write_text("\n".join(lines))
    r = run("bar_ramp", tmp_path, "-mesh", str(mesh), np_=0, check=False)
    assert r.returncode != 0
    assert re.search(r'a facet of the physical group "\w+" \(nodes %d %d\) is not a face of any triangle' % (n0, far), r.output), r.output[-1500:]
