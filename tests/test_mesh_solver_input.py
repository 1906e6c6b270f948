"""Unsupported meshes and solver options stop the run at set-up with a message that names the file
or option, the problem and the fix; the solver options the README offers really work."""
import os
import re
import subprocess

import numpy as np
import pytest

from conftest import EXE, ROOT, run, stage_event_count


def refused(tmp_path, *extra, case="d1_disk"):
    """Runs one rank without mpiexec (its abort path costs a second per run); returns the output
    of a run that must fail."""
    args = [EXE, "-options_file", os.path.join("options", case + ".opts"), "-output_dir", str(tmp_path / "out"), *map(str, extra)]
    proc = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=300)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out[-2000:]
    return out


def gmsh(tmp_path, geo, name, *args):
    path = str(tmp_path / name)
    subprocess.run(["gmsh", "-v", "2", *args, os.path.join(ROOT, "meshes", geo) if "/" not in geo else geo, "-o", path],
                   cwd=ROOT, check=True, capture_output=True, timeout=300)
    return path


def element_types(path):
    """gmsh element type numbers of a msh 4.1 file, with their counts."""
    lines = open(path).read().split("\n")
    i = lines.index("$Elements") + 2
    types = {}
    while lines[i] != "$EndElements":
        _, _, typ, n = map(int, lines[i].split())
        types[typ] = types.get(typ, 0) + n
        i += n + 1
    return types


# ---------------------------------------------------------------- unsupported meshes

SUPPORTED = "first-order triangles (2D) and tetrahedra (3D)"


def test_truncated_mesh_is_named(tmp_path):
    data = open(os.path.join(ROOT, "meshes", "disk.msh"), "rb").read()
    path = tmp_path / "cut.msh"
    path.write_bytes(data[: int(0.6 * len(data))])
    out = refused(tmp_path, "-mesh", path)
    assert 'Mesh file "%s" (-mesh) could not be read' % path in out, out[-2000:]
    assert "truncated or not a valid gmsh file" in out
    assert "first-order triangles (2D) or tetrahedra (3D)" in out


def test_quadrilateral_mesh_is_refused(tmp_path):
    path = gmsh(tmp_path, "disk.geo", "quad.msh", "-2", "-setnumber", "Mesh.RecombineAll", "1")
    assert set(element_types(path)) == {1, 3}  # lines and quadrangles only: the test does test quads
    out = refused(tmp_path, "-mesh", path)
    assert 'Mesh file "%s" (-mesh) has 388 quadrilateral cells' % path in out, out[-2000:]
    assert SUPPORTED in out and "without Recombine" in out


@pytest.mark.parametrize("geo,flag,case,cell", [("disk.geo", "-2", "d1_disk", "triangle"), ("ball.geo", "-3", "d2_ball", "tetrahedron")])
def test_second_order_mesh_is_refused(tmp_path, geo, flag, case, cell):
    """The 2D one failed in the contact set-up with "Edge has 0 coordinates != 4"; the 3D one ran."""
    path = gmsh(tmp_path, geo, "o2.msh", flag, "-order", "2")
    assert {8, 9} <= set(element_types(path)) or {9, 11} <= set(element_types(path))
    out = refused(tmp_path, "-mesh", path, case=case)
    assert 'Mesh file "%s" (-mesh) has high-order (order 2, curved) %s cells' % (path, cell) in out, out[-2000:]
    assert SUPPORTED in out and "default order 1" in out


def msh_with_swapped_nodes(src, dst, k, elem_type):
    """Copies a msh 4.1 file with the first two nodes of its k-th element of elem_type swapped;
    returns the centroid of that element."""
    lines = open(src).read().split("\n")
    nodes = {}
    i = lines.index("$Nodes") + 2
    while lines[i] != "$EndNodes":
        n = int(lines[i].split()[3])
        tags = [int(t) for t in lines[i + 1: i + 1 + n]]
        for t, xyz in zip(tags, lines[i + 1 + n: i + 1 + 2 * n]):
            nodes[t] = np.array([float(x) for x in xyz.split()])
        i += 1 + 2 * n
    i = lines.index("$Elements") + 2
    seen = 0
    while lines[i] != "$EndElements":
        _, _, typ, n = map(int, lines[i].split())
        for r in range(i + 1, i + 1 + n):
            if typ == elem_type and seen == k:
                tags = lines[r].split()
                tags[1], tags[2] = tags[2], tags[1]
                lines[r] = " ".join(tags)
                centroid = np.mean([nodes[int(t)] for t in tags[1:]], axis=0)
            seen += typ == elem_type
        i += n + 1
    open(dst, "w").write("\n".join(lines))
    return centroid


@pytest.mark.parametrize("case,mesh,elem_type,k", [("d1_disk", "disk.msh", 2, 100), ("d2_ball", "ball.msh", 4, 7)])
def test_inverted_cell_is_named(tmp_path, case, mesh, elem_type, k):
    """One element with two nodes swapped: DMPlex keeps the file's vertex order (its Jacobian is
    negative), and the run used to go on with that cell's mass negative (D1's kinetic energy
    1.87058 instead of 1.87580)."""
    path = str(tmp_path / "inverted.msh")
    centroid = msh_with_swapped_nodes(os.path.join(ROOT, "meshes", mesh), path, k, elem_type)
    out = refused(tmp_path, "-mesh", path, case=case)
    assert 'Mesh file "%s" (-mesh) has an inverted (negatively oriented) element: cell %d ' % (path, k) in out, out[-2000:]
    where = re.search(r"with centroid \(([^)]*)\)", out).group(1)
    dim = 2 if elem_type == 2 else 3
    assert np.allclose([float(x) for x in where.split(",")], centroid[:dim], rtol=1e-5, atol=1e-6)
    assert "(inverted cells: 1 of " in out


def test_backwards_surface_is_inverted_throughout(tmp_path):
    """A clockwise Curve Loop: gmsh meshes every triangle clockwise (the run used to start with a
    negative kinetic energy)."""
    geo = open(os.path.join(ROOT, "meshes", "disk.geo")).read().replace("Curve Loop(1) = {1, 2, 3, 4};", "Curve Loop(1) = {-4, -3, -2, -1};")
    assert "{-4, -3, -2, -1}" in geo
    (tmp_path / "cw.geo").write_text(geo)
    path = gmsh(tmp_path, str(tmp_path / "cw.geo"), "cw.msh", "-2")
    out = refused(tmp_path, "-mesh", path)
    assert "inverted (negatively oriented) element: cell 0 " in out, out[-2000:]
    assert "oriented backwards" in out and "Curve Loop" in out


# ---------------------------------------------------------------- solver options

@pytest.mark.parametrize("extra,messages", [
    (["-contact_K_pc_type", "jacobi"], ["-contact_K_pc_type jacobi is not supported", "Delassus operator", "-contact_K_pc_type lu", "cholesky", "-contact_formulation active_set"]),
    (["-contact_K_pc_type", "ilu"], ["-contact_K_pc_type ilu is not supported", "incomplete factorizations"]),
    (["-mass_ksp_type", "preonly", "-mass_pc_type", "jacobi"], ["-mass_pc_type jacobi is not supported", "initial acceleration", "-mass_pc_type lu"]),
    (["-contact_snes_type", "newtonls"], ["-contact_snes_type newtonls is not supported", "vinewtonrsls", "vinewtonssls"]),
    (["-mu", 0.2, "-contact_snes_type", "vinewtonssls"], ["-contact_snes_type vinewtonssls is not supported with friction (-mu 0.2)", "vinewtonrsls"]),
    (["-ts_adapt_type", "basic"], ["-ts_adapt_type basic is not supported", "no error estimate", "growback", "none"]),
    (["-contact_formulation", "condenced"], ["-contact_formulation condenced is not a contact formulation", "condensed", "full", "active_set"]),
    (["-mu", 0.2, "-contact_formulation", "full"], ["needs a contact formulation that solves the contact dofs alone", "-contact_formulation full cannot", "condensed or active_set"]),
    (["-contact_formulation", "full", "-contact_pc_type", "vifactor", "-contact_snes_type", "vinewtonssls"],
     ["-contact_pc_type vifactor solves the Newton steps of -contact_snes_type vinewtonrsls only", "drop one of the two options"]),
])
def test_unsupported_solver_option_is_named(tmp_path, extra, messages):
    out = refused(tmp_path, *extra)
    for m in messages:
        assert m in out, out[-2000:]


def compare(h1, h2, tol):
    assert len(h1) == len(h2)
    scale = np.abs(h1["total"]).max()
    for c in ["kinetic", "elastic", "total", "work_ext", "work_contact", "force_normal", "max_penetration", "vcm_x", "vcm_y", "L_z"]:
        assert np.abs(h1[c] - h2[c]).max() <= tol * max(scale, np.abs(h1[c]).max()), c
    assert np.array_equal(h1["active"], h2["active"])


def test_cholesky_factorizations_equal_lu(mm):
    """K~ and the mass matrix are symmetric: Cholesky (MUMPS, 2 ranks) gives the LU history. Gravity
    makes the initial acceleration nonzero, so the mass solve matters."""
    lu = mm("d1_disk", "-gravity", "0,-9.81", "-output_every", 0, np_=2, name="lu").history
    ch = mm("d1_disk", "-gravity", "0,-9.81", "-output_every", 0, "-contact_K_pc_type", "cholesky", "-mass_ksp_type", "preonly", "-mass_pc_type", "cholesky", np_=2, name="cholesky").history
    assert lu["active"].max() >= 3
    compare(lu, ch, 1e-10)


def test_semismooth_vi_equals_active_set_vi(mm):
    """vinewtonssls converges (it used to stall from its first contact step: it overwrote the
    operator with its semismooth Jacobian) and, being stopped by -contact_tol rather than exact
    like the active set, agrees with vinewtonrsls to that tolerance."""
    rs = mm("d1_disk", "-output_every", 0, name="rsls").history
    ss = mm("d1_disk", "-output_every", 0, "-contact_snes_type", "vinewtonssls", name="ssls").history
    compare(rs, ss, 1e-8)
    tight = mm("d1_disk", "-output_every", 0, "-contact_snes_type", "vinewtonssls", "-contact_tol", 1e-14, name="ssls_tight").history
    compare(rs, tight, 1e-10)
    assert ss["vi_its"].sum() > rs["vi_its"].sum()  # it really ran the other solver


def test_default_native_cholesky_equals_mumps_lu(mm):
    """On one rank K~ is factored by PETSc's own Cholesky (nested dissection) by default: the
    frictional D1 history is MUMPS LU's, to solver tolerance."""
    short = ("-ts_max_time", 0.06, "-output_every", 0)
    native = mm("d1_friction", *short, name="native").history
    mumps = mm("d1_friction", *short, "-contact_K_pc_type", "lu", "-contact_K_pc_factor_mat_solver_type", "mumps", name="mumps").history
    scale = np.abs(mumps["total"]).max()
    assert native["active"].max() > 0 and native["friction_its"].max() > 1
    for c in ("total", "work_contact", "work_friction", "force_normal", "force_tangential"):
        assert np.abs(native[c] - mumps[c]).max() <= 1e-10 * scale, c
    assert np.array_equal(native["active"], mumps["active"])


@pytest.mark.parametrize("np_", [2, 3])
def test_split_cholesky_on_several_ranks_equals_mumps_lu(mm, np_):
    """2D on several ranks: K~ is solved split at the ranks' interface (schursplit: each rank's
    interior by PETSc's Cholesky, the interface by its dense Schur complement), the Delassus columns
    by that solve. The frictional D1 history is the one of MUMPS's distributed LU on the same ranks,
    of the whole factor held on every rank (-contact_K_pc_type redundant), and of one rank, to solver
    tolerance. 3 ranks: interface rows on two ranks, which couple to each other."""
    short = ("-ts_max_time", 0.06, "-output_every", 0)
    split = mm("d1_friction", *short, "-contact_K_ksp_view", np_=np_, name="split")
    assert "schursplit (each rank's interior" in split.output
    assert "then mmcontact's backward sweep (checked against MatBackwardSolve at set-up)" in split.output
    mumps = mm("d1_friction", *short, "-contact_K_pc_type", "lu", "-contact_K_pc_factor_mat_solver_type", "mumps", np_=np_, name="mumps").history
    redundant = mm("d1_friction", *short, "-contact_K_pc_type", "redundant", "-contact_K_redundant_pc_type", "cholesky", np_=np_, name="redundant")
    assert "(redundant)" in redundant.output
    one = mm("d1_friction", *short, name="one").history
    h = split.history
    scale = np.abs(mumps["total"]).max()
    assert h["active"].max() > 0 and h["friction_its"].max() > 1
    for other in (mumps, redundant.history, one):
        for c in ("total", "work_contact", "work_friction", "force_normal", "force_tangential"):
            assert np.abs(h[c] - other[c]).max() <= 1e-10 * scale, c
        assert np.array_equal(h["active"], other["active"])


def test_failed_factorization_stops_the_run(mm):
    """A factorization that runs out of memory (MUMPS limited to 1 MB of working space here) used to
    go on to the next solve: now it stops at once, naming the solve and the reason."""
    r = mm("d1_disk", "-ts_max_steps", 2, "-contact_K_pc_type", "lu", "-contact_K_pc_factor_mat_solver_type", "mumps",
           "-contact_K_mat_mumps_icntl_14", -99, "-contact_K_mat_mumps_icntl_23", 1, np_=0, check=False)
    assert r.returncode != 0
    assert "The factorization for the solve -contact_K_ failed: FACTOR_OUTMEMORY" in r.output
    assert "does not fit in memory" in r.output


def test_failed_redundant_factorization_names_the_factor_reason(mm):
    """2D on 2 ranks with K~'s factor held whole on every rank (-contact_K_pc_type redundant), which
    reports only that its inner PC failed (SUBPC_ERROR): the check reads the inner factor's own reason."""
    r = mm("d1_disk", "-ts_max_steps", 2, "-contact_K_pc_type", "redundant", "-contact_K_redundant_pc_type", "lu", "-contact_K_redundant_pc_factor_mat_solver_type", "mumps",
           "-contact_K_redundant_mat_mumps_icntl_14", -99, "-contact_K_redundant_mat_mumps_icntl_23", 1, np_=2, check=False)
    assert r.returncode != 0
    assert "The factorization for the solve -contact_K_ failed: FACTOR_OUTMEMORY" in r.output
    assert "SUBPC_ERROR" not in r.output


@pytest.mark.parametrize("np_", [1, 2])
def test_full_formulation_whole_factor_equals_free_block_factor(mm, np_):
    """The full formulation's VI solves its Newton steps on the free dofs by one factor of the whole
    K~ with the active rows and columns the identity's (-contact_pc_type vifactor, the default): the
    history of factoring the free block itself (-contact_pc_type cholesky, a new matrix at each
    iteration), to 1e-10 of the energy, with the same active sets and VI iterations. -log_view:
    MUMPS's analysis at set-up and never in the time steps, against once per factorization there,
    and an active set met again (the VI's last iteration, the next step's first) is not factored
    again."""
    common = ("-contact_formulation", "full", "-ts_max_steps", 40, "-output_every", 0, "-log_view")
    whole = mm("d1_disk", *common, np_=np_, name="whole")
    block = mm("d1_disk", *common, "-contact_pc_type", "cholesky", "-contact_pc_factor_mat_solver_type", "mumps", np_=np_, name="block")
    assert "of the whole K~, the VI's active rows the identity's (vifactor)" in whole.output
    assert whole.history["active"].max() >= 3
    compare(whole.history, block.history, 1e-10)
    assert np.array_equal(whole.history["vi_its"], block.history["vi_its"])  # the same Newton steps: exact solves
    sym, num = ([stage_event_count(r.output, "MM time steps", e) for r in (whole, block)] for e in ("MatCholFctrSym", "MatCholFctrNum"))
    assert sym[0] == 0 and stage_event_count(whole.output, "MM setup", "MatCholFctrSym") >= 1, sym
    assert sym[1] == num[1] >= 10, (sym, num)
    assert 1 <= num[0] < num[1], num


def test_failed_whole_factor_names_the_factor_reason(tmp_path):
    """The full formulation's factor (8.6k dofs) runs out of memory (MUMPS limited to 1 MB here): the run stops
    naming the VI's solve and the factor's reason, where the VI alone said DIVERGED_LINEAR_SOLVE."""
    mesh = gmsh(tmp_path, "disk.geo", "disk_h03.msh", "-2", "-setnumber", "H", "0.03")
    r = run("d1_disk", tmp_path, "-mesh", mesh, "-ts_max_steps", 12, "-contact_formulation", "full",
            "-contact_mat_mumps_icntl_14", -99, "-contact_mat_mumps_icntl_23", 1, np_=0, check=False)
    assert r.returncode != 0
    assert "The factorization for the solve -contact_ failed: FACTOR_" in r.output, r.output[-2000:]
    assert "DIVERGED_LINEAR_SOLVE" not in r.output
