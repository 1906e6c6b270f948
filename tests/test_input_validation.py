"""Input that used to be accepted silently: each is refused with a message that names the option and
what would be valid, or, for the physics guards, the run stays right. Refused input runs without
mpiexec (np_=0): MPI's abort path would cost a second per case."""
import os
import subprocess

import numpy as np
import pytest

from conftest import EXE, ROOT, UNUSED, run

# vector options must have exactly d (or d*d) entries: a missing component used to become 0
LENGTHS_2D = [
    (["-gravity", "-9.8"], "-gravity has 1 entries; the mesh is 2D, so it needs exactly 2"),
    (["-v0", "-1"], "-v0 has 1 entries; the mesh is 2D, so it needs exactly 2"),
    (["-obstacle_point", "0"], "-obstacle_point has 1 entries; the mesh is 2D, so it needs exactly 2"),
    (["-obstacle_point", "0,0,0"], "-obstacle_point has 3 entries; the mesh is 2D, so it needs exactly 2"),
    (["-obstacle_normal", "0"], "-obstacle_normal has 1 entries; the mesh is 2D, so it needs exactly 2"),
    (["-obstacle_normal", "0,1,5"], "-obstacle_normal has 3 entries; the mesh is 2D, so it needs exactly 2"),
    (["-traction", "upper", "-traction_upper_value", "0,-20,0"], "-traction_upper_value has 3 entries; the mesh is 2D, so it needs exactly 2"),
    (["-traction", "upper", "-traction_upper_value", "-20"], "-traction_upper_value has 1 entries; the mesh is 2D, so it needs exactly 2"),
    (["-u0_gradient", "1,0,0,0,1,0,0,0,1"], "-u0_gradient has 9 entries; the mesh is 2D, so it needs exactly 4"),
    (["-omega", "1,2"], "-omega has 2 entries; the mesh is 2D, so it needs exactly 1"),
    (["-v0", "1,2,3,4"], "-v0 has more than 3 entries"),
    (["-dirichlet", "upper", "-dirichlet_upper_value", "0.1"], "-dirichlet_upper_value has 1 entries but the boundary fixes 2 components"),
]

LENGTHS_3D = [
    (["-u0_gradient", "1,0,0,1"], "-u0_gradient has 4 entries; the mesh is 3D, so it needs exactly 9"),
    (["-v0", "0.5,-1"], "-v0 has 2 entries; the mesh is 3D, so it needs exactly 3"),
    (["-omega", "2"], "-omega has 1 entries; the mesh is 3D, so it needs exactly 3"),
]

# NaN and inf are refused by option name; values out of range with their range
VALUES = [
    (["-v0", "nan,-1"], "-v0: entry 0 is NaN; every value must be a finite number"),
    (["-u0_offset", "nan,0"], "-u0_offset: entry 0 is NaN"),
    (["-omega", "nan"], "-omega: entry 0 is NaN"),
    (["-E", "inf"], "-E: entry 0 is infinite"),
    (["-ts_dt", "inf"], ["The time step -ts_dt inf", "must be > 0 and finite"]),
    (["-contact_tol", "0"], ["-contact_tol 0", "must lie in (0, 1)"]),
    (["-contact_tol", "-1"], ["-contact_tol -1", "must lie in (0, 1)"]),
    (["-audit_tol", "-1"], ["-audit_tol -1", "must be > 0"]),
    (["-friction_coulomb_tol", "0"], ["-friction_coulomb_tol 0", "must lie in (0, 1)"]),
    (["-contact_work_tol", "0"], ["-contact_work_tol 0", "must be > 0"]),
    (["-ts_max_time", "-1"], ["The final time -ts_max_time -1", "must be > 0 and finite"]),
    (["-ts_max_steps", "-5"], "-ts_max_steps -5 must be >= 0"),
    (["-active_set_inexact_rtol", "1"], ["-active_set_inexact_rtol 1", "must be in [0, 1)"]),
    (["-ts_dt", "1e30"], "The time step -ts_dt 1e+30 is beyond the final time -ts_max_time 0.3"),
]


def refused(case, tmp_path, extra, message):
    r = run(case, tmp_path, *extra, np_=0, check=False)
    assert r.returncode != 0, r.output[-1500:]
    for m in [message] if isinstance(message, str) else message:
        assert m in r.output, r.output[-2500:]
    # refused before the time loop: nothing was written
    assert not os.path.exists(os.path.join(r.outdir, "history.csv"))
    return r


@pytest.mark.parametrize("extra,message", LENGTHS_2D + VALUES)
def test_refused_2d(tmp_path, extra, message):
    refused("d1_disk", tmp_path, extra, message)


@pytest.mark.parametrize("extra,message", LENGTHS_3D)
def test_refused_3d(tmp_path, extra, message):
    refused("d2_ball", tmp_path, extra, message)


def test_misspelled_option_names_the_closest_valid_one(tmp_path):
    r = refused("d1_disk", tmp_path, ["-mu_", "0.2"], "-mu_ 0.2: unknown; did you mean -mu?")
    assert "-allow_unused_options" in r.output
    refused("d1_disk", tmp_path, ["-ts_dtt", "0.001", "-contact_snes_rtoll", "1e-9"], "did you mean -ts_dt?")
    refused("d1_disk", tmp_path, ["-contact_snes_rtoll", "1e-9"], "did you mean -contact_snes_rtol?")


def test_option_valid_elsewhere_but_unread_here(tmp_path):
    """A friction-loop option without friction reads nothing: said so, not called a typo."""
    refused("d1_disk", tmp_path, ["-friction_snes_rtol", "1e-12"], "-friction_snes_rtol 1e-12: a valid option, but nothing in this run reads it")


def test_equals_sign_in_an_options_file(tmp_path):
    opts = tmp_path / "case.opts"
    opts.write_text(open(os.path.join(ROOT, "options", "d1_disk.opts")).read() + "-E=1000\n")
    proc = subprocess.run([EXE, "-options_file", str(opts), "-output_dir", str(tmp_path / "o")], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode != 0
    assert 'options take the form "-E 1000", with a blank, not "="' in proc.stderr + proc.stdout


def test_allow_unused_options_opts_out(tmp_path):
    r = run("d1_disk", tmp_path, "-mu_", 0.2, "-allow_unused_options", "-ts_max_steps", 2, np_=0, check=False)
    assert r.returncode == 0 and len(r.history) == 3
    assert UNUSED in r.output  # -options_left still reports it at the end


def test_help_without_a_mesh_prints_help_and_exits_0():
    proc = subprocess.run([EXE, "-help"], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-1500:]
    out = proc.stdout
    assert "PETSC ERROR" not in out + proc.stderr and "MPI_ABORT" not in out + proc.stderr
    for opt in ("-mesh", "-allow_unused_options", "-contact_work_tol", "-ts_dt", "-contact_snes_type", "-contact_K_pc_type",
                "-friction_snes_max_it", "-mass_pc_type"):
        assert "  " + opt + " " in out or "  " + opt + ":" in out, opt


def test_initial_penetration_is_refused_naming_the_deepest_node(tmp_path):
    # the plane moved up through the disk: the lowest node, (0, 0.01), is 0.49 deep
    refused("d1_disk", tmp_path, ["-obstacle_point", "0,0.5"], "the deepest contact node, at (0, 0.01), is 0.49 inside it")
    # the plane's normal reversed: the whole disk is inside the obstacle, the top node deepest
    r = refused("d1_disk", tmp_path, ["-obstacle_normal", "0,-1"], "The initial state penetrates the obstacle")
    assert "is 2.01 inside it" in r.output or "is 1.01 inside it" in r.output, r.output[-1500:]


def rotation(k):
    """Rodrigues: the rotation matrix of rotation vector k (as -mesh_rotation applies it)."""
    k = np.asarray(k, float)
    th = np.linalg.norm(k)
    n = k / th
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K


@pytest.fixture(scope="module")
def d2_reference(tmp_path_factory):
    return run("d2_ball", tmp_path_factory.mktemp("d2ref"), "-output_every", 0, "-ts_max_time", 0.12).history


@pytest.mark.parametrize("k", [(-np.pi / 2, 0, 0), (0.3, -0.5, 0.7)], ids=["y_normal", "arbitrary"])
def test_3d_plane_normal_is_honoured(k, d2_reference, tmp_path):
    """D2 with mesh, plane normal and velocity rotated together: a y normal (the ball rotated from
    above z = 0 to above y = 0) and an arbitrary one give the reference history. (0, 1, 0) used to be
    replaced by (0, 0, 1), which on the rotated ball is now an initial penetration."""
    R = rotation(k)
    fmt = lambda v: ",".join("%.17g" % x for x in v)
    n, v = R @ [0, 0, 1], R @ [0.5, 0, -1]
    if k[0] == -np.pi / 2:
        assert np.allclose(n, [0, 1, 0]) and np.allclose(v, [0.5, -1, 0])
        n = [0, 1, 0]
    h = run("d2_ball", tmp_path, "-mesh_rotation", fmt(k), "-obstacle_normal", fmt(n), "-v0", fmt(v), "-output_every", 0,
            "-ts_max_time", 0.12).history
    scale = np.abs(d2_reference["total"]).max()
    for c in ("kinetic", "elastic", "total", "work_contact", "force_normal"):
        assert np.abs(h[c] - d2_reference[c]).max() <= 1e-8 * scale, c
    assert np.array_equal(h["active"], d2_reference["active"]) and d2_reference["active"].max() > 0
    assert np.allclose([h["vcm_x"][0], h["vcm_y"][0], h["vcm_z"][0]], v, atol=1e-12)


def test_steel_disk_rebounds_no_faster_than_it_hit(tmp_path):
    """D1 in steel, SI units, dt = 2e-3: c_p dt / h_c' = 150. The release used to create 3.26 times
    the initial energy (the disk left at 2.26 times its impact speed) with exit code 0. Now the start
    warns, the release steps are retried with smaller dt, and the disk leaves no faster than it came."""
    r = run("d1_disk", tmp_path, "-E", 2.1e11, "-rho", 7850, "-output_every", 0, np_=2)
    h = r.history
    assert "c_p dt / h_c' = 150 is far above 1" in r.output
    assert "would create" in r.output and "retrying with dt" in r.output
    v_in, v_out = np.hypot(h["vcm_x"][0], h["vcm_y"][0]), np.hypot(h["vcm_x"][-1], h["vcm_y"][-1])
    assert h["vcm_y"][-1] > 0.5 and v_out <= v_in, (v_in, v_out)
    # no step created more than -contact_work_tol of the energy scale
    assert np.diff(h["work_contact"]).max() <= 1e-3 * np.abs(h["total"]).max()
    assert h["total"][-1] <= 1.001 * h["total"][0]
    assert h["balance_residual"].max() <= 1e-6
    # dt was cut at the release and grew back to -ts_dt afterwards: by 4 on each step after it, a
    # release being an event, not a regime (the growback adaptor); the last steps share what is left
    # before the final time (-ts_exact_final_time matchstep, TSAdapt's rule)
    dt = h["dt"][1:]
    assert dt.min() < 1e-4 and (dt[-100:-2] == 2e-3).all() and (0 < dt[-2:]).all() and (dt[-2:] <= 2e-3).all()
    assert h["time"][-1] == 0.3
    grown = np.flatnonzero(dt[1:] > dt[:-1]) + 1
    assert len(grown) >= 2 and all(dt[g] == 4 * dt[g - 1] for g in grown) and np.diff(grown).min() == 1


def test_contact_work_guard_stops_when_it_cannot_retry(tmp_path):
    r = run("d1_disk", tmp_path, "-E", 2.1e11, "-rho", 7850, "-ts_max_reject", 0, "-output_every", 0, np_=0, check=False)
    assert r.returncode != 0
    for m in ("A contact release at t = 0.012 creates energy that dt does not resolve", "-contact_work_tol 0.001",
              "Use a -ts_dt near h_c' / c_p = 1.33", "The output up to t = 0.012 is intact"):
        assert m in r.output, m
    assert len(r.history) == 7


def test_non_finite_state_stops_the_run_with_step_and_quantity(tmp_path):
    """Gravity of 1e155 overflows the kinetic energy after 37 steps: the run stops there, and no
    inf or NaN reaches history.csv. (The deformation audit, which would stop it at step 1, is off:
    the non-finite check is the one tested.)"""
    r = run("d1_disk", tmp_path, "-contact", 0, "-gravity", "0,1e155", "-output_every", 1, "-deformation_audit", 0, np_=0, check=False)
    assert r.returncode != 0
    assert "The kinetic energy is infinite at step 38" in r.output, r.output[-1500:]
    h = r.history
    assert len(h) == 38 and np.all(np.isfinite(h["total"])) and np.all(np.isfinite(h["kinetic"]))


def test_full_formulation_factor_options_are_read_at_set_up(tmp_path):
    """The full formulation's VI factors K~ (its active rows the identity's) inside its iterations, after the options
    audit: its MUMPS options are read at set-up on a stand-in factor, so a valid one is accepted and
    applied (another ordering, the same history) and a misspelled one refused."""
    common = ("-contact_formulation", "full", "-ts_max_steps", 40)
    ref = run("d1_disk", tmp_path, *common, np_=2, name="default")
    pord = run("d1_disk", tmp_path, *common, "-contact_mat_mumps_icntl_7", 4, "-contact_mat_mumps_icntl_14", 40, np_=2, name="pord")
    a, b = ref.history, pord.history
    assert a["active"].max() > 0 and np.array_equal(a["active"], b["active"])
    scale = np.abs(a["total"]).max()
    for k in ("kinetic", "elastic", "work_contact"):
        assert np.abs(a[k] - b[k]).max() <= 1e-10 * scale, k
    refused("d1_disk", tmp_path, ["-contact_formulation", "full", "-contact_mat_mumps_icntl_777", "1"], "-contact_mat_mumps_icntl_777 1: unknown; did you mean -contact_mat_mumps_icntl_7?")
    # the options are read on a stand-in factor whose analysis runs with them: PORD on one rank
    # ended the process there when the stand-in was a single unit row (a graph without edges)
    one = run("d1_disk", tmp_path, "-contact_formulation", "full", "-ts_max_steps", 3, "-contact_mat_mumps_icntl_7", 4, np_=1, name="pord_1rank")
    assert "mmcontact summary:" in one.output
    # in 2D K~ is factored by PETSc's Cholesky: MUMPS's options for it are valid but read by nothing
    refused("d1_disk", tmp_path, ["-contact_K_mat_mumps_icntl_14", "50"], "-contact_K_mat_mumps_icntl_14 50: a valid option, but nothing in this run reads it")


def test_solve_time_viewers_are_accepted(tmp_path):
    """-PREFIX_snes_converged_reason and -PREFIX_ksp_view are read when a solve ends, after the options
    audit: accepted (the VI's refusal message suggests the first), and a misspelling still refused."""
    r = run("d1_disk", tmp_path, "-contact_snes_converged_reason", "-contact_K_ksp_converged_reason", "-ts_max_steps", 8, np_=0, name="viewers")
    assert "Nonlinear contact_ solve converged" in r.output
    refused("d1_disk", tmp_path, ["-contact_snes_converged_reasonn"], "did you mean -contact_snes_converged_reason?")
