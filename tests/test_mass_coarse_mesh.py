"""Issue 38, item 5: the default mass on a coarse mesh whose whole skin is contact boundary
(meshes/cube_drop.geo, a unit cube of rho 1). The smallest moment correction would take up to half of
a node's mass away there (M* indefinite), and the run used to be refused; the bounded correction
(docs/method.md section 2, "When the smallest correction would make M* indefinite") keeps M*
positive definite and M's total mass and first moments, so the cube falls at g."""
import subprocess

import numpy as np
import pytest

from conftest import ROOT

G = 9.81
DROP = ("-mesh", "meshes/cube_drop.msh", "-contact_boundary", "skin", "-obstacle_point", "0,0,0", "-obstacle_normal", "0,0,1",
        "-E", 1000, "-nu", 0.3, "-rho", 1, "-v0", "0,0,0", "-gravity", "0,0,%g" % -G, "-output_every", 0)


def coarse(tmp_path, h):
    mesh = tmp_path / ("cube_drop_%g.msh" % h)
    subprocess.run(["gmsh", "-3", "meshes/cube_drop.geo", "-setnumber", "H", str(h), "-o", str(mesh), "-v", "0"], check=True, cwd=ROOT)
    return str(mesh)


def mass_line(r):
    return next(l for l in r.output.splitlines() if l.strip().startswith("mass:"))


def falls_at_g(h):
    """Until the first contact (the base starts 0.05 above the plane: t = 0.101), vcm_z = -g t to 1e-10
    of the velocity scale g t, and the sideways vcm stays at round-off."""
    t = h["time"]
    first = int(np.argmax(h["active"] > 0))
    assert first > 10 and h["active"][:first].max() == 0
    pre = slice(0, first)
    scale = G * t[first - 1]
    assert np.abs(h["vcm_z"][pre] + G * t[pre]).max() <= 1e-10 * scale
    assert max(np.abs(h["vcm_" + a][pre]).max() for a in "xy") <= 1e-10 * scale


@pytest.mark.parametrize("np_", [1, 2])
def test_coarse_cube_all_skin_contact_falls_at_g(mm, np_):
    """240 nodes, 37 inside: the default runs (main refused it: "takes 0.305 of a node's own mass
    away"), M*'s mass along every axis is M's, its moments check, and the cube falls at g; after the
    impact it bounces (the contact force is positive)."""
    r = mm("d2_ball", *DROP, "-ts_dt", 2e-3, "-ts_max_time", 0.13, np_=np_)
    line = mass_line(r)
    words = line.replace(",", " ").replace(";", " ").split()
    assert float(words[words.index("M") + 1]) == pytest.approx(1.0, rel=1e-12)
    for a in "xyz":
        assert float(words[words.index(a) + 1]) == pytest.approx(1.0, rel=1e-12), line
    assert "bounded correction" in line and "moments equal M's" in line, line
    assert "warning" not in r.output
    h = r.history
    falls_at_g(h)
    assert h["force_normal"].max() > 0


def test_coarser_cube_keeps_mass_and_first_moments(tmp_path, mm):
    """144 nodes, 12 inside: the inertia is out of the bound's reach, the total mass and first
    moments are not (the report says which), and the cube falls at g."""
    r = mm("d2_ball", *DROP, "-mesh", coarse(tmp_path, 0.25), "-ts_dt", 2e-3, "-ts_max_time", 0.11, np_=2)
    line = mass_line(r)
    assert "total mass and first moments equal M's" in line and "inertia off by" in line, line
    falls_at_g(r.history)


def test_modified_mass_warns(mm):
    """-mass modified on the same cube keeps a third of M along z: one warning line on stderr, and the
    cube falls at about 3 g, as the warning says."""
    r = mm("d2_ball", *DROP, "-mass", "modified", "-ts_dt", 2e-3, "-ts_max_time", 0.02, np_=1)
    warnings = [l for l in r.output.splitlines() if l.startswith("mmcontact warning:")]
    assert len(warnings) == 1 and "-mass modified keeps only 0.329 along z of M's mass" in warnings[0], warnings
    h = r.history
    a = -h["vcm_z"][-1] / (G * h["time"][-1])
    assert a == pytest.approx(1 / 0.3288403163, rel=1e-6)


def test_mesh_too_coarse_is_refused_with_fixes_that_work(tmp_path, mm):
    """45 nodes, 1 inside: no node-block mass can hold M's first moments along z there. The refusal
    (64) names its fixes, and both run and fall at g: the base alone as contact boundary, or a finer
    mesh (the 240-node cube of the test above)."""
    mesh = coarse(tmp_path, 0.5)
    r = mm("d2_ball", *DROP, "-mesh", mesh, "-ts_max_steps", 2, np_=0, check=False)
    assert r.returncode == 64
    err = [l for l in r.output.splitlines() if l.startswith("mmcontact error:")]
    assert len(err) == 1 and "1 node off the contact boundary" in err[0], r.output[-2000:]
    assert "Name as -contact_boundary only the surface that can touch an obstacle, or mesh the body finer" in err[0]
    ok = mm("d2_ball", *DROP, "-mesh", mesh, "-contact_boundary", "base", "-ts_dt", 2e-3, "-ts_max_time", 0.11, np_=2, name="base")
    assert "warning" not in ok.output
    falls_at_g(ok.history)
