"""Issue 38's checks: the contact audit stops a run whose contact law fails (exit 65, the output up
to the previous step intact), amplitude tables are read as written, values the arithmetic cannot
carry are refused, and the messages say what they mean."""
import os

import numpy as np
import pytest

from conftest import ROOT, run
from test_loads_time import options_without_amplitude

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
