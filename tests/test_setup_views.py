"""-obstacle_view, -contact_view, -friction_view and -ts_view: each object's configuration printed
once the run is set up, before the first step, through a PetscViewer as PETSc's -ksp_view
(docs/reference.md, "Viewing the set-up"): the key settings of each, once on any number of ranks,
to standard output or with ascii:FILE to a file."""
import re
import subprocess

import pytest

from conftest import EXE, ROOT, run

VIEWS = ["-obstacle_view", "-contact_view", "-friction_view", "-ts_view"]


def first(output, text):
    i = output.find(text)
    assert i >= 0, (text, output[-3000:])
    return i


@pytest.mark.parametrize("np_", [1, 2])
def test_each_view_prints_its_objects_settings_once_before_the_first_step(tmp_path, np_):
    r = run("d1_friction", tmp_path, "-ts_max_steps", 2, "-quiet", "-ts_monitor", *VIEWS, np_=np_)
    out = r.output
    # obstacles: the single plane of -obstacle_point, -obstacle_normal and its friction coefficient
    assert out.count("MMObstacle plane: plane, the body outside; friction coefficient 0.2\n") == 1, out[-3000:]
    assert "  point (0., 0.)\n  normal (0., 1.)\n  fixed\n" in out
    # contact: the formulation, the contact set, the frames, the mass, the tolerances, K~'s solver
    assert out.count("MMContact: formulation condensed") == 1
    for line in ("33 contact rows", "2 reaction components per row", "obstacles: 1 rigid, 0 contact pairs; largest friction coefficient 0.2",
                 "contact frames: fixed", "mass: -mass redistributed", "-contact_tol 1e-11", "K~ solver (prefix contact_K_): KSP preonly"):
        assert line in out, line
    # friction: the type, its tolerances and the Coulomb audit
    assert out.count("MMFriction: type newton") == 1
    for line in ("-friction_snes_rtol 1e-12 (Alart-Curnier residual over the force scale), at most 100 iterations", "-friction_coulomb_tol 1e-08"):
        assert line in out, line
    # the TS type's view op, under PETSc's own TS lines: once at set-up and once more when TSSolve
    # ends, as PETSc's -ts_view does; the law, the damping and the step matrix's coefficients
    assert out.count("  type: newmark\n    Trapezoidal Newmark (beta = 1/4, gamma = 1/2)") == 2
    for line in ("elasticity law: linear", "damping: none", "step matrix K~ = ck K + cb B + cm M* at dt 0.002: ck 1., cb 0., cm 1e+06",
                 "audits: -audit_tol 1e-06, -contact_work_tol 0.001; deformation audit on"):
        assert out.count(line) == 2, line
    # set-up views come before the first step's monitor line
    step0 = first(out, "0 TS dt 0.002 time 0.")
    for head in ("MMObstacle plane", "MMContact: formulation", "MMFriction: type", "TS Object:"):
        assert first(out, head) < step0, head


def test_finite_strain_damped_stepper_view(tmp_path):
    """The law, Rayleigh damping as given and as used, and the coefficients K~ is built from:
    ck = 1 + 2 beta/dt (beta's viscous stress scales the iteration stiffness), cm = 4/dt^2 + 2 alpha/dt."""
    r = run("d1_disk", tmp_path, "-elasticity", "svk", "-damping_ratio", 0.05, "-damping_frequencies", "1,10", "-ts_max_steps", 1, "-quiet", "-ts_view", np_=0)
    out = r.output
    assert "elasticity law: svk (finite strain: the step iterates, below)" in out
    m = re.search(r"damping: Rayleigh C = alpha M\* \+ beta B, alpha (\S+) 1/s, beta (\S+) s \(-damping_ratio 0.05 at 1. and 10. Hz\)", out)
    assert m, out[-3000:]
    alpha, beta, dt = float(m.group(1)), float(m.group(2)), 0.002
    ck, cb, cm = (float(g) for g in re.search(r"at dt 0.002: ck (\S+), cb (\S+), cm ([^\s(]+)", out).groups())
    assert ck == pytest.approx(1 + 2 * beta / dt, rel=1e-5) and cb == 0 and cm == pytest.approx(4 / dt**2 + 2 * alpha / dt, rel=1e-5)
    assert "finite-strain iteration: -nonlinear_tangent auto, -nonlinear_rtol" in out and "-nonlinear_max_it 30" in out


def test_curved_obstacles_and_contact_pairs(tmp_path):
    r = run("ball_bowl", tmp_path, "-ts_max_steps", 1, "-quiet", "-obstacle_view", np_=0)
    assert "MMObstacle bowl: sphere (curved), the body inside; friction coefficient 0.3\n  center (0., 0., 4.)\n  radius 4.\n  fixed\n" in r.output, r.output[-2000:]
    r = run("two_bars", tmp_path, "-ts_max_steps", 1, "-quiet", "-obstacle_view", "-contact_view", name="pairs", np_=0)
    assert "MMObstacle p: contact pair, slave surface a_right, master surface b_left; friction coefficient 0." in r.output
    assert "obstacles: 0 rigid, 1 contact pair;" in r.output


def test_without_contact_and_without_friction(tmp_path):
    r = run("d1_disk", tmp_path, "-contact", 0, "-ts_max_steps", 1, "-quiet", "-contact_view", "-friction_view", np_=0)
    assert "MMContact: formulation none\n  no contact (-contact 0): K~ factored" in r.output
    assert "MMFriction: type newton (the default for this formulation)\n  no friction solve in this run" in r.output


@pytest.mark.parametrize("np_", [1, 2])
def test_ascii_file_viewer_writes_each_view_to_its_file(tmp_path, np_):
    files = {v: tmp_path / (v[1:] + ".txt") for v in VIEWS}
    args = [a for v in VIEWS for a in (v, f"ascii:{files[v]}")]
    r = run("d1_friction", tmp_path, "-ts_max_steps", 2, "-quiet", *args, np_=np_)
    text = {v: files[v].read_text() for v in VIEWS}
    assert text["-obstacle_view"].startswith("MMObstacle plane: plane") and text["-obstacle_view"].count("MMObstacle") == 1
    assert text["-contact_view"].startswith("MMContact: formulation condensed") and "33 contact rows" in text["-contact_view"]
    assert text["-friction_view"].startswith("MMFriction: type newton") and "-friction_coulomb_tol 1e-08" in text["-friction_view"]
    assert text["-ts_view"].startswith(f"TS Object: {np_} MPI process") and text["-ts_view"].count("Trapezoidal Newmark") == 1
    for head in ("MMObstacle", "MMContact:", "MMFriction:", "TS Object:", "Trapezoidal"):
        assert head not in r.output, head


def test_help_lists_the_views():
    out = subprocess.run([EXE, "-help"], cwd=ROOT, capture_output=True, text=True, timeout=60).stdout
    for v in VIEWS:
        assert re.search(rf"^  {v}: Print .*ascii:FILE", out, re.M), v
