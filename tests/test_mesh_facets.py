"""The facet physical groups of a mesh that is never interpolated (src/mesh/facets.c): the facet
elements read from the file mark their cells, and each rank lists its facets from the marks.
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


def test_mesh_holds_no_faces_or_edges(tmp_path):
    """The distributed mesh is cells and vertices only (no rank builds faces or edges); the binary
    file's, read by PETSc's reader, is interpolated."""
    ascii_run = run("d2_ball", tmp_path, "-ts_max_steps", 1, "-output_every", 0, "-dm_view", np_=2, name="ascii")
    strata = re.findall(r"Number of (\d)-cells per rank", ascii_run.output)
    assert strata == ["0", "3"], ascii_run.output[:3000]
    binary_run = run("d2_ball", tmp_path, "-ts_max_steps", 1, "-output_every", 0, "-dm_view", "-mesh", binary_copy("meshes/ball.msh", tmp_path), np_=2, name="binary")
    assert re.findall(r"Number of (\d)-cells per rank", binary_run.output) == ["0", "1", "2", "3"]


def interface_mesh(tmp_path, binary):
    """The bimaterial strip with its interface x = L1 (2 cells on each of its facets) as the facet
    group "interface"."""
    geo = tmp_path / "interface.geo"
    geo.write_text(open(f"{ROOT}/meshes/bimaterial.geo").read() + '\nPhysical Curve("interface") = {2};\n')
    out = tmp_path / ("interface_bin.msh" if binary else "interface.msh")
    subprocess.run(["gmsh", str(geo), "-2", *(["-bin"] if binary else []), "-format", "msh41", "-o", str(out), "-v", "2"], check=True)
    return str(out)


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("binary", [False, True], ids=["ascii", "binary"])
def test_interior_facet_group_counts_each_facet_once(binary, np_, tmp_path):
    """A traction on an interior curve (each facet bounds two cells, possibly on two ranks) loads
    the strip with its value times the curve's length, W = L1 / N1 = 0.0125, at every step: a facet
    listed from both of its cells would double it. As a pair's master surface it is refused."""
    mesh = interface_mesh(tmp_path, binary)
    r = run("bimaterial_pulse", tmp_path, "-mesh", mesh, "-traction", "left,interface", "-traction_interface_value", "2e-3,0",
            "-traction_interface_amplitude", "halfsine", "-traction_interface_amplitude_time", 0.2, "-ts_max_time", 0.1,
            "-output_every", 0, np_=np_)
    h = r.history
    expected = (1e-3 + 2e-3) * 0.0125 * np.sin(np.pi * h["time"] / 0.2)
    assert np.abs(h["load_x"] - expected).max() <= 1e-12 * 3e-3 * 0.0125
    assert np.abs(h["load_x"]).max() > 0.5 * 3e-3 * 0.0125
    bad = run("bimaterial_pulse", tmp_path, "-mesh", mesh, "-contact", 1, "-contact_pairs", "p", "-contact_pair_p_slave", "left",
              "-contact_pair_p_master", "interface", np_=np_, name="pair", check=False)
    assert bad.returncode != 0
    assert 'The master surface "interface" of contact pair p has a facet inside the mesh' in bad.output, bad.output[-1500:]
