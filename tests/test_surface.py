"""A large contact surface (issue 21, the bench suite "surface"): a slab pressed flat on a plane over
its whole base (options/slab_press.opts), here on a small mesh of meshes/slab.geo (16 x 16 x 2
hexahedra split into tetrahedra: 289 base nodes, all touching from step 3). Every base node is in
contact at once, the case the condensed formulation's dense candidate set handles worst and the
active-set formulation is meant for: both must give the same answer."""
import os
import subprocess

import numpy as np
import pytest

from conftest import ROOT, run
from test_loads_time import impulse

NX = 16
TIGHT = ("-contact_tol", "1e-13")


@pytest.fixture(scope="module")
def slab_mesh(tmp_path_factory):
    path = str(tmp_path_factory.mktemp("slab") / "slab16.msh")
    subprocess.run(["gmsh", "-3", os.path.join(ROOT, "meshes/slab.geo"), "-setnumber", "NX", str(NX), "-setnumber", "NZ", "2",
                    "-setnumber", "H", "0.125", "-o", path, "-v", "2"], check=True, capture_output=True)
    return path


def assert_same_history(a, b, tol=1e-8):
    scale = np.abs(a["total"]).max()
    for c in ("kinetic", "elastic", "total", "work_friction"):
        assert np.abs(a[c] - b[c]).max() <= tol * scale, c
    assert np.array_equal(a["active"], b["active"]) and np.array_equal(a["slipping"], b["slipping"])


def test_slab_pressed_flat_frictionless(slab_mesh, tmp_path):
    """mu = 0: every base node is in contact from the first contact step and sits on the plane; the
    momentum of the free nodes changes by the trapezoidal impulses of the press's reaction and the
    plane's force, exactly; the energy balance closes with the press's work; the active-set
    formulation gives the condensed one's history."""
    runs = {f: run("slab_press", tmp_path, "-mesh", slab_mesh, "-mu", 0, "-contact_formulation", f, *TIGHT, name=f).history
            for f in ("active_set", "condensed")}
    h = runs["active_set"]
    touching = h["active"] > 0
    assert touching.sum() >= 15 and np.all(h["active"][touching] == (NX + 1) ** 2)
    assert h["max_penetration"].max() == 0
    fscale = h["force_normal"].max()
    assert fscale > 1
    net = impulse(h, "reaction_top_z") + impulse(h, "force_normal")
    assert np.abs(net - (h["P_z"] - h["P_z"][0])).max() <= 1e-10 * fscale * h["time"][-1]
    escale = np.abs(h["total"]).max()
    assert np.abs(h["total"] - h["total"][0] - h["work_dirichlet"] - h["work_contact"] - h["work_ext"]).max() <= 1e-9 * escale
    assert_same_history(runs["condensed"], h)


def test_slab_pressed_flat_with_friction(slab_mesh, tmp_path):
    """mu = 0.2: the base's Poisson expansion is resisted, part of the base slips and part sticks; the
    Coulomb law holds at every node; the active-set formulation's Coulomb iteration gives the
    condensed Newton's history, and 2 ranks give 1 rank's."""
    cond = run("slab_press", tmp_path, "-mesh", slab_mesh, "-contact_formulation", "condensed", *TIGHT, name="condensed").history
    one = run("slab_press", tmp_path, "-mesh", slab_mesh, "-contact_formulation", "active_set", *TIGHT, name="one").history
    two = run("slab_press", tmp_path, "-mesh", slab_mesh, "-contact_formulation", "active_set", *TIGHT, name="two", np_=2).history
    touching = one["active"] > 0
    assert np.all(one["active"][touching] == (NX + 1) ** 2)
    assert 0 < one["slipping"].max() < (NX + 1) ** 2 and one["work_friction"][-1] < 0
    for h in (cond, one, two):
        assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-9
        assert h["max_penetration"].max() <= 1e-10 / NX  # the condensed path's round-off on the gap: 3e-19
    assert_same_history(cond, one)
    assert_same_history(one, two)
