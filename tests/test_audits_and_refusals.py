"""Issue 38's checks: the contact audit stops a run whose contact law fails (exit 65, the output up
to the previous step intact), amplitude tables are read as written, values the arithmetic cannot
carry are refused, and the messages say what they mean."""
import os
import re
import subprocess

import numpy as np
import pytest

from conftest import EXE, ROOT, run
from test_loads_time import options_without_amplitude

HC_D1 = 0.07987  # h_c' of the D1 disk


def audit_step(r, quantity):
    """The step a failed contact audit names in its one error line, which names the quantity."""
    err = [l for l in r.output.splitlines() if l.startswith("mmcontact error")]
    assert r.returncode == 65 and len(err) == 1, r.output[-2000:]
    m = re.match(r"mmcontact error: Contact audit failed at step (\d+) \(t = \S+\): (.*)", err[0])
    assert m and quantity in m[2] and "The output up to the previous step is intact" in m[2], err[0]
    return int(m[1]), m[2]


@pytest.mark.parametrize("np_", [0, 2])
def test_penetration_stops_the_run(tmp_path, np_):
    """-E 1e-8 on D1 (c_p dt / h_c' = 3e-6: the massless contact dofs' rows are 1e-10 of the others,
    and the contact solve's relative residual leaves them off by a tenth of h_c'): the disk crosses
    the plane by 10% of h_c' at step 9, with an exact energy balance, and used to end with exit 0.
    The contact audit stops the run there (65), naming the step and the depth over h_c', and the
    history ends at the step before, without a penetration."""
    r = run("d1_disk", tmp_path, "-E", 1e-8, "-ts_max_time", 0.04, "-output_every", 5, np_=np_, check=False)
    step, what = audit_step(r, "h_c', above -audit_penetration_tol 1e-06")
    depth = float(re.search(r"a contact node is (\S+) inside an obstacle", what)[1])
    assert depth > 1e-2 * HC_D1
    h = r.history
    assert 5 <= step <= 12 and h["step"][-1] == step - 1
    assert h["max_penetration"].max() <= 1e-6 * HC_D1  # what was written is sound
    with r.fields() as f:  # and readable, up to the last snapshot before the failure
        assert f["time"][-1, 0] <= h["time"][-1]


def test_coulomb_residual_stops_the_run(tmp_path):
    """The same run with the penetration audit out of the way: the Coulomb residual (0.1 at step 9:
    the penetration over h_c' is one of its terms) is past -audit_coulomb_tol 1e-2, and stops it."""
    r = run("d1_disk", tmp_path, "-E", 1e-8, "-ts_max_time", 0.04, "-output_every", 0, "-audit_penetration_tol", 1, np_=0, check=False)
    step, what = audit_step(r, "the discrete Coulomb residual (history column coulomb_residual) is")
    assert "above -audit_coulomb_tol 0.01" in what and float(what.split(" is ")[1].split(",")[0]) > 1e-2
    assert 5 <= step <= 12 and r.history["step"][-1] == step - 1 and r.history["coulomb_residual"].max() <= 1e-8


def test_audit_tolerances_are_checked(tmp_path):
    for opt in ("-audit_penetration_tol", "-audit_coulomb_tol"):
        r = run("d1_disk", tmp_path, opt, 0, np_=0, check=False)
        assert r.returncode == 64 and f"{opt} 0 must be > 0" in r.output, r.output[-1500:]


def table_run(tmp_path, content, name):
    path = tmp_path / (name + ".csv")
    path.write_bytes(content)
    return run(options_without_amplitude(tmp_path), tmp_path, "-ts_max_time", 1, "-output_every", 0,
               "-traction_right_amplitude_table", str(path), np_=0, name=name, check=False)


def test_amplitude_table_with_bom_is_refused(tmp_path):
    """A table saved with a UTF-8 byte order mark lost its first row (taken for a header) and the
    load started in full: refused, as the options and mesh readers refuse one."""
    r = table_run(tmp_path, b"\xef\xbb\xbf0,0\n0.5,0\n10,1\n", "bom")
    assert r.returncode == 64, r.output[-1500:]
    assert "-traction_right_amplitude_table" in r.output and "starts with a UTF-8 byte order mark (bytes EF BB BF)" in r.output


def test_first_row_of_numbers_is_data(tmp_path):
    """A first row that starts with a number is data: "0;0" is refused by its line, not skipped as a
    header (which started the load at the next row's factor); a header still is one."""
    r = table_run(tmp_path, b"0;0\n0.5,0\n10,1\n", "semicolon")
    assert r.returncode == 64 and "line 1 \"0;0\" is not two numbers time,factor" in r.output, r.output[-1500:]
    r = table_run(tmp_path, b"0,0,0\n0.5,0\n10,1\n", "three")
    assert r.returncode == 64 and "line 1 \"0,0,0\" is not two numbers" in r.output, r.output[-1500:]
    r = table_run(tmp_path, b"t (s), factor\n0,0\n0.5,0\n10,1\n", "header")
    assert r.returncode == 0, r.output[-1500:]
    assert r.history["load_x"][np.searchsorted(r.history["time"], 0.5)] == 0  # the first rows hold it at 0


ARITHMETIC = [
    # the mass term of K~ = K + 4/dt^2 M below the stiffness' round-off: K~ singular in floating point
    (("-rho", "1e-300"), "The step matrix K + 4/dt^2 M cannot be formed in double precision with dt = 0.002, -E 1000, -rho 1e-300 (c_p dt / h_c' = 9.19e+149): the mass term"),
    (("-rho", "1e-16"), "(c_p dt / h_c' = 9.19e+07): the mass term, which alone holds the rigid motions"),
    # 4/dt^2 overflows
    (("-ts_dt", "1e-300"), "-ts_dt 1e-300 is too small for double precision: the step matrix's mass term 4/dt^2 M overflows"),
    # the stiffness below the mass term's round-off
    (("-E", "1e-30"), "-E 1e-30, -rho 1 (c_p dt / h_c' = 2.91e-17): the stiffness is"),
    (("-ts_dt", "1e-100"), "the stiffness is"),
    # the mass itself underflows
    (("-rho", "1e-310"), "The mass matrix underflows with -E 1000, -rho 1e-310 on this mesh"),
]


@pytest.mark.parametrize("extra,message", ARITHMETIC)
def test_what_the_arithmetic_cannot_carry_is_refused(tmp_path, extra, message):
    """-rho 1e-300 and -ts_dt 1e-300 ended with status 56 and PETSc's trace from the factorization
    (pc_schursplit.c): refused at set-up with one line, exit 64."""
    r = run("d1_disk", tmp_path, *extra, "-ts_max_steps", 5, np_=0, check=False)  # main ran -ts_dt 1e-100 for ever
    err = [l for l in r.output.splitlines() if "error" in l.lower()]
    assert r.returncode == 64 and len(err) == 1 and err[0].startswith("mmcontact error: "), r.output[-2000:]
    assert message in err[0], err[0]


def test_what_the_arithmetic_cannot_carry_two_ranks(tmp_path):
    r = run("d1_disk", tmp_path, "-rho", "1e-300", np_=2, check=False)
    assert r.returncode == 64 and r.output.count("mmcontact error: The step matrix K + 4/dt^2 M cannot be formed") == 1, r.output[-2000:]
    assert "PETSC ERROR" not in r.output


def test_correct_runs_are_far_from_the_arithmetic_limits(tmp_path):
    """D1 in steel in SI units (c_p dt / h_c' = 150, README "Contact release") and at dt / 1000 still
    start: the refusals sit at c_p dt / h_c' of about 4e6 and 3e-7."""
    for extra in (("-E", 2.1e11, "-rho", 7850), ("-ts_dt", 2e-6)):
        r = run("d1_disk", tmp_path, *extra, "-ts_max_steps", 1, "-output_every", 0, np_=0)
        assert r.returncode == 0


@pytest.mark.parametrize("extra,said,unsaid", [
    (("-nu", -1.1), "Poisson ratio -nu -1.1 must lie in (-1, 0.5): nu <= -1 makes the shear modulus", "incompressible"),
    (("-nu", 0.5), "Poisson ratio -nu 0.5 must lie in (-1, 0.5): nu >= 0.5 is incompressible", "shear modulus"),
])
def test_poisson_ratio_refusal_names_its_side(tmp_path, extra, said, unsaid):
    """-nu -1.1 was refused as "nu >= 0.5 is incompressible": each side says its own reason."""
    r = run("d1_disk", tmp_path, *extra, np_=0, check=False)
    assert r.returncode == 64 and said in r.output and unsaid not in r.output, r.output[-1500:]


def test_body_poisson_ratio_refusal_names_its_side(tmp_path):
    r = run("two_balls", tmp_path, "-body_a_nu", -2, np_=0, check=False)
    assert r.returncode == 64 and "Poisson ratio -body_a_nu -2 must lie in (-1, 0.5): nu <= -1" in r.output, r.output[-1500:]


def test_mu_used_nowhere_is_refused(tmp_path):
    """-mu is the default of every obstacle's and pair's own mu: given while each sets its own it was
    read and silently unused. Refused, naming them; where an obstacle takes it, it is used."""
    r = run("two_balls", tmp_path, "-mu", 0.2, np_=0, check=False)
    assert r.returncode == 64 and "mmcontact error: -mu 0.2 is used nowhere" in r.output and "(-contact_pair_p_mu)" in r.output, r.output[-1500:]
    r = run("block_push", tmp_path, "-obstacle_floor_mu", 0.3, np_=0, check=False)
    assert r.returncode == 64 and "(-obstacle_floor_mu, -obstacle_plate_mu)" in r.output, r.output[-1500:]
    r = run("block_push", tmp_path, "-ts_max_steps", 1, "-output_every", 0, np_=0)  # the floor takes -mu 0.3
    assert "Coulomb friction, mu = 0 to 0.3 by obstacle" in r.output


def test_mass_line_says_held_dofs_are_left_out(tmp_path):
    """punch holds its top by -dirichlet: M's total, 0.475 of the block's 0.5, leaves those nodes out
    and says so; D1, with nothing held, does not say it."""
    r = run("punch", tmp_path, "-ts_max_steps", 1, "-output_every", 0, np_=0, name="punch")
    assert "  mass: total of M 0.475 (without the dofs held by -dirichlet); of M* along x" in r.output, r.output[-2000:]
    r = run("d1_disk", tmp_path, "-ts_max_steps", 1, "-output_every", 0, np_=0, name="d1")
    assert "  mass: total of M 3.136548491; of M*" in r.output


def test_friction_coulomb_tol_help_says_what_it_is(tmp_path):
    out = subprocess.run([EXE, "-options_file", "options/d1_friction.opts", "-help", "-ts_max_steps", "0", "-output_dir", str(tmp_path / "help")],
                         cwd=ROOT, capture_output=True).stdout.decode(errors="replace")  # PETSc 3.18's -help prints an uninitialized buffer
    line = [l for l in out.splitlines() if l.strip().startswith("-friction_coulomb_tol")][0]
    assert "Coulomb audit of every friction solve" in line and "rejected and retried with a smaller dt" in line, line


def test_missing_contact_boundary_names_the_default(tmp_path):
    """A mesh without a group "contact" and no -contact_boundary: the refusal says "contact" was the
    default tried; a misspelt -contact_boundary names the option."""
    opts = tmp_path / "block.opts"
    opts.write_text("-mesh meshes/block.msh\n-ts_dt 1e-3\n-ts_max_time 1e-2\n")
    r = run(str(opts), tmp_path, np_=0, check=False)
    assert r.returncode == 64 and "no physical group named \"contact\" (the default of -contact_boundary, which was not given: name the mesh's contact boundary with -contact_boundary NAME)" in r.output, r.output[-1500:]
    r = run(str(opts), tmp_path, "-contact_boundary", "bases", np_=0, check=False)
    assert r.returncode == 64 and "no physical group named \"bases\" (-contact_boundary). Its physical names are: \"body\" \"base\"" in r.output, r.output[-1500:]


def test_relative_mesh_path_names_the_file_tried(tmp_path):
    """A relative -mesh is the current directory's, not the options file's: the refusal says so and
    prints the absolute path it tried."""
    r = run("d1_disk", tmp_path, "-mesh", "meshes/nothere.msh", np_=0, check=False)
    assert r.returncode == 64, r.output[-1500:]
    assert f"a relative path is taken from the current directory, not from the options file's, so the file tried was {ROOT}/meshes/nothere.msh" in r.output


@pytest.mark.parametrize("np_", [0, 2])
def test_unknown_option_is_refused_before_the_header(tmp_path, np_):
    """The refusal of an unknown option came after the start-up report, which announced a run that
    then did not happen: it comes first now, and alone."""
    r = run("d1_disk", tmp_path, "-mu_", 0.2, np_=np_, check=False)
    assert r.returncode == 64 and "-mu_ 0.2: unknown; did you mean -mu?" in r.output, r.output[-1500:]
    assert "mmcontact: case" not in r.output and "  material:" not in r.output
