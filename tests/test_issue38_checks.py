"""Issue 38's checks: the contact audit stops a run whose contact law fails (exit 65, the output up
to the previous step intact), amplitude tables are read as written, values the arithmetic cannot
carry are refused, and the messages say what they mean."""
import os

import numpy as np
import pytest

from conftest import ROOT, run
from test_loads_time import options_without_amplitude

HC_D1 = 0.07987  # h_c' of the D1 disk


@pytest.mark.parametrize("np_", [0, 2])
def test_penetration_stops_the_run(tmp_path, np_):
    """-E 1e-30 on D1: the contact solve lets the disk cross the plane (by 10% of h_c' at step 9 on
    one rank, 34% later), with an exact energy balance. The contact audit stops the run there (65),
    naming the step and the depth, and the history ends at the step before."""
    r = run("d1_disk", tmp_path, "-E", 1e-30, "-ts_max_time", 0.04, "-output_every", 5, np_=np_, check=False)
    assert r.returncode == 65, r.output[-2000:]
    err = [l for l in r.output.splitlines() if l.startswith("mmcontact error")]
    assert len(err) == 1 and "Contact audit failed at step" in err[0] and "h_c', above -audit_penetration_tol 1e-06" in err[0], r.output[-2000:]
    step = int(err[0].split("at step ")[1].split()[0])
    h = r.history
    assert 5 <= step <= 12 and h["step"][-1] == step - 1
    assert h["max_penetration"].max() <= 1e-6 * HC_D1  # what was written is sound


def test_coulomb_residual_stops_the_run(tmp_path):
    """The same run with the penetration audit out of the way: the Coulomb residual (0.1 at step 9:
    the penetration over h_c' is one of its terms) is past -audit_coulomb_tol 1e-2, and stops it."""
    r = run("d1_disk", tmp_path, "-E", 1e-30, "-ts_max_time", 0.04, "-output_every", 0, "-audit_penetration_tol", 1, np_=0, check=False)
    assert r.returncode == 65, r.output[-2000:]
    assert "mmcontact error: Contact audit failed at step 9 (t = 0.018): the discrete Coulomb residual (history column coulomb_residual) is 0.102, above -audit_coulomb_tol 0.01" in r.output, r.output[-2000:]
    assert r.history["step"][-1] == 8 and r.history["coulomb_residual"].max() <= 1e-8


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
