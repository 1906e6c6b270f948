"""Issue 48, items 5, 8, 10 and 13: every refused option in one line with status 64 (enum typos, an
options file that is a directory, integers beyond the step counter), the Physical Points of a binary
.msh, a later amplitude replacing an earlier one, and what a run without contact, or a finite-strain
run at rest under gravity, reports. Each test failed on main 606351d."""
import os
import re
import subprocess

import numpy as np
import pytest

from conftest import EXE, MPIEXEC, ROOT, run

USAGE = 64


def first_line(r):
    return r.output.strip().splitlines()[0] if r.output.strip() else ""


# item 5: every enumerated option refused by name with its valid values, never a PETSc trace (83)
ENUMS = [
    ("-elasticity", "neo-hookean", "linear, svk or neohookean"),
    ("-mass", "standrd", "modified, standard or redistributed"),
    ("-initial_state", "statc", "given, static_sliding or static"),
    ("-nonlinear_tangent", "ref", "auto, reference or step"),
    ("-contact_frames", "foo", "fixed or follow"),
    ("-contact_pairs_sliding", "foo", "auto, small or large"),
    ("-assembly", "x", "closed_form or fe"),
]


@pytest.mark.parametrize("check_input", [False, True])
@pytest.mark.parametrize("option,value,valid", ENUMS)
def test_enum_typo_is_one_line_and_64(tmp_path, option, value, valid, check_input):
    extra = [option, value] + (["-check_input"] if check_input else [])
    r = run("d1_disk", tmp_path, *extra, np_=0, check=False)
    assert r.returncode == USAGE, r.output[-1500:]
    assert first_line(r) == f"mmcontact error: {option} {value} is not a valid value: use {valid}", r.output[-1500:]
    assert "PETSC ERROR" not in r.output


def test_enum_typo_on_two_ranks_is_said_once(tmp_path):
    r = run("d1_disk", tmp_path, "-elasticity", "neo-hookean", np_=2, check=False)
    assert r.returncode == USAGE
    assert r.output.count("is not a valid value") == 1, r.output[-1500:]
    assert "PETSC ERROR" not in r.output


def test_enum_value_is_case_insensitive_as_petsc_reads_it(tmp_path):
    r = run("d1_disk", tmp_path, "-elasticity", "NeoHookean", "-check_input", np_=0)
    assert "neo-Hookean" in r.output


@pytest.mark.parametrize("np_", [0, 2])
def test_options_file_that_is_a_directory(tmp_path, np_):
    launcher = MPIEXEC + ["-n", str(np_)] if np_ else []
    p = subprocess.run(launcher + [EXE, "-options_file", str(tmp_path)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    out = p.stdout + p.stderr
    assert p.returncode == USAGE, out[-1500:]
    assert out.count(f"mmcontact error: the options file {tmp_path} is a directory") == 1, out[-1500:]
    assert "PETSC ERROR" not in out


# item 10: integers beyond the step counter are refused with the value as given
@pytest.mark.parametrize("extra,message", [
    (("-ts_max_steps", "3000000000"), "-ts_max_steps 3000000000 is beyond the integers a run can count"),
    (("-output_every", "3000000000"), "-output_every 3000000000 is beyond the integers a run can count"),
    (("-ts_max_time", "1e30"), "-ts_max_time 1e+30 at -ts_dt 0.002 is 5e+32 steps, beyond the 2147483647 steps a run can count"),
])
@pytest.mark.parametrize("check_input", [False, True])
def test_step_counts_beyond_the_integers_are_refused(tmp_path, extra, message, check_input):
    r = run("d1_disk", tmp_path, *extra, *(["-check_input"] if check_input else []), np_=0, check=False)
    assert r.returncode == USAGE, r.output[-1500:]
    assert first_line(r).startswith("mmcontact error: " + message), r.output[-1500:]


def test_long_final_time_with_a_step_limit_runs(tmp_path):
    """-ts_max_time far beyond the counter is fine when -ts_max_steps ends the run first."""
    r = run("d1_disk", tmp_path, "-ts_max_time", "1e30", "-ts_max_steps", 3, "-output_every", 0, np_=0)
    assert r.history["step"][-1] == 3


# item 8: the Physical Points of a binary .msh (gmsh -bin), 4.1 and 2.2
@pytest.fixture(scope="module")
def binary_plates(tmp_path_factory):
    d = tmp_path_factory.mktemp("binary_plates")
    geo = open(os.path.join(ROOT, "meshes", "plate.geo")).read()
    out = {}
    for version in ("4.1", "2.2"):
        g = d / f"plate{version}.geo"
        g.write_text(geo.replace("Mesh.MshFileVersion = 4.1;", f"Mesh.MshFileVersion = {version};"))
        m = d / f"plate{version}.msh"
        subprocess.run(["gmsh", "-2", "-bin", str(g), "-o", str(m)], check=True, capture_output=True, timeout=120)
        assert open(m, "rb").read(64).split(b"\n")[1] == f"{version} 1 8".encode()  # binary indeed
        out[version] = str(m)
    return out


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("version", ["4.1", "2.2"])
def test_point_groups_of_a_binary_mesh(tmp_path, binary_plates, version, np_):
    """options/plate_loads.opts puts its point force on Physical Point "tip": the binary mesh's run
    equals the ASCII mesh's, energies and momenta to 1e-10 of their scales."""
    ascii = run("plate_loads", tmp_path, "-output_every", 0, np_=np_, name="ascii").history
    binary = run("plate_loads", tmp_path, "-mesh", binary_plates[version], "-output_every", 0, np_=np_, name="binary").history
    assert len(ascii) == len(binary)
    escale = np.abs(ascii["total"]).max()
    assert escale > 1e-8  # the point force did work
    for c in ("kinetic", "elastic", "total", "work_ext"):
        assert np.abs(ascii[c] - binary[c]).max() <= 1e-10 * escale, c
    pscale = np.abs(ascii["P_x"]).max() + np.abs(ascii["P_y"]).max()
    for c in ("P_x", "P_y"):
        assert np.abs(ascii[c] - binary[c]).max() <= 1e-10 * pscale, c


# item 13: the smaller ones
def test_contact_dirichlet_clash_names_a_3d_node_by_three_coordinates(tmp_path):
    r = run("f1_box", tmp_path, "-dirichlet", "sides", "-dirichlet_sides_value", "0,0,0", np_=0, check=False)
    assert r.returncode == USAGE
    assert re.search(r'contact boundary "base" at \([^,()]+, [^,()]+, [^,()]+\) is also on a Dirichlet boundary', r.output), r.output[-1500:]


def options_without(case, tmp_path, drop):
    lines = [l for l in open(os.path.join(ROOT, "options", case + ".opts")).read().splitlines()
             if not l.split() or l.split()[0] not in drop]
    p = tmp_path / f"{case}_edited.opts"
    p.write_text("\n".join(lines) + "\n")
    return str(p)


AMP = "-traction_right_amplitude"


@pytest.mark.parametrize("later", [
    (AMP, "constant"),
    (AMP, "ramp", AMP + "_time", "0.05"),
    (AMP, "table", AMP + "_table", "options/plate_loads_amplitude.csv"),
    (AMP + "_table", "options/plate_loads_amplitude.csv"),
])
def test_a_later_amplitude_replaces_the_options_files(tmp_path, later):
    """options/bar_pulse.opts sets a halfsine with its _amplitude_time; an amplitude given after it on
    the command line replaces it, the file's time dropped with it: the history is the one of the file
    edited to the new amplitude, bit for bit."""
    edited = options_without("bar_pulse", tmp_path, {AMP, AMP + "_time"})
    over = run("bar_pulse", tmp_path, *later, "-ts_max_time", 0.1, np_=0, name="over").history
    ref = run(edited, tmp_path, *later, "-ts_max_time", 0.1, np_=0, name="ref").history
    assert np.abs(ref["work_ext"]).max() > 0
    for c in ref.dtype.names:
        assert np.array_equal(over[c], ref[c]), c


def test_amplitude_data_after_the_kind_is_still_checked(tmp_path):
    """Data given after a kind that cannot use it is a mistake, refused as before."""
    r = run("bar_pulse", tmp_path, AMP, "constant", AMP + "_time", 0.3, np_=0, check=False)
    assert r.returncode == USAGE and "-traction_right_amplitude_time is given but the amplitude is constant" in r.output


def test_a_run_without_contact_reports_no_contact(tmp_path):
    """-contact 0 (options/plate_loads.opts): no obstacle force columns, no contact set in the
    progress lines, no penetration in the summary."""
    r = run("plate_loads", tmp_path, "-progress_every", 1e-9, np_=1)
    header = open(os.path.join(r.outdir, "history.csv")).readline().strip().split(",")
    assert not [c for c in header if c.startswith("force_plane")], header
    progress = [l for l in r.output.splitlines() if l.startswith("  t = ")]
    assert progress and not [l for l in progress if "active" in l or "slipping" in l], progress[:3]
    summary = [l for l in r.output.splitlines() if l.startswith("mmcontact summary")][0]
    assert "penetration" not in summary and "largest balance residual" in summary


@pytest.mark.parametrize("np_", [1, 2])
@pytest.mark.parametrize("law", ["neohookean", "svk"])
def test_finite_strain_step_zero_at_rest_has_no_contact_force(tmp_path, law, np_):
    """The D2 ball under gravity, 0.01 above the plane, no node touching: the step-0 row's contact
    force and Coulomb residual are round-off of the weight, as with the linear law (main: force 5e-3
    and Coulomb residual 4.7e-3 with neo-Hookean, the massless rows projected with K alone)."""
    r = run("d2_ball", tmp_path, "-elasticity", law, "-mu", 0.3, "-gravity", "0,0,-9.81", "-ts_max_steps", 1, "-output_every", 0, np_=np_)
    h = r.history
    weight = 4.0 / 3.0 * np.pi * 9.81  # rho 1, radius 1
    assert h["active"][0] == 0
    assert abs(h["force_normal"][0]) <= 1e-12 * weight, h["force_normal"][0]
    assert h["coulomb_residual"][0] <= 1e-10, h["coulomb_residual"][0]
