"""The final time (-ts_max_time, -ts_exact_final_time) and the static-sliding initial velocity."""
import numpy as np
import pytest

from conftest import run

LINEAR = ("-contact", 0, "-output_every", 0, "-quiet")


def test_final_time_is_never_passed_by_rounding(tmp_path):
    """-ts_dt 2e-5 -ts_max_time 0.2: the sum of the steps misses 0.2 by 1e-14, which used to cost a
    10001st step ending at 0.20002. Now exactly 10000 steps, the last at t = 0.2."""
    h = run("d1_disk", tmp_path, "-ts_dt", 2e-5, "-ts_max_time", 0.2, *LINEAR, np_=0).history
    assert h["step"][-1] == 10000 and len(h) == 10001
    assert h["time"][-1] == 0.2
    assert np.all(h["dt"] == 2e-5)  # no step changed by the final time: K~ factored once


@pytest.mark.parametrize("mode,steps,t_end,last_dt", [("matchstep", 15, 0.1, 0.002), ("stepover", 15, 0.105, 0.007)])
def test_exact_final_time(tmp_path, mode, steps, t_end, last_dt):
    """dt = 0.007 does not divide 0.1: matchstep (the default) shortens the 15th step to 0.002 and ends
    at 0.1 exactly, with the energy balance closing on that step too; stepover takes it whole and
    ends at 0.105, as PETSc's TS does."""
    h = run("d1_disk", tmp_path, "-ts_dt", 0.007, "-ts_max_time", 0.1, "-ts_exact_final_time", mode, "-output_every", 0, np_=0).history
    assert h["step"][-1] == steps
    assert abs(h["time"][-1] - t_end) <= 1e-12 * t_end
    assert abs(h["dt"][-1] - last_dt) <= 1e-12 and np.all(h["dt"][:-1] == 0.007)
    assert h["balance_residual"].max() <= 1e-10


def test_default_is_matchstep(tmp_path):
    h = run("d1_disk", tmp_path, "-ts_dt", 0.007, "-ts_max_time", 0.1, *LINEAR, np_=0).history
    assert h["time"][-1] == 0.1


def test_interpolate_is_refused_with_the_choices(tmp_path):
    r = run("d1_disk", tmp_path, "-ts_exact_final_time", "interpolate", np_=0, check=False)
    assert r.returncode == 64
    assert "-ts_exact_final_time interpolate is not supported" in r.output and "matchstep" in r.output and "stepover" in r.output


def test_static_sliding_uses_the_tangential_part_of_v0(tmp_path):
    """F1 (the block sliding on the plane y = 0): -v0 0.05,0.3 starts exactly as -v0 0.05,0 (README:
    the tangential part only): the same initial velocity, no normal velocity, the same history."""
    base = run("f1_block", tmp_path, "-ts_max_time", 0.5, "-output_every", 0, np_=0, name="tangential").history
    tilted = run("f1_block", tmp_path, "-ts_max_time", 0.5, "-output_every", 0, "-v0", "0.05,0.3", np_=0, name="tilted")
    h = tilted.history
    assert "the normal part 0.3 of -v0 is dropped" in tilted.output
    V = 0.05
    assert abs(h["vcm_y"][0]) <= 1e-12 * V and abs(h["vcm_x"][0] - V) <= 1e-12 * V
    E = np.abs(base["total"]).max()
    for c in ("kinetic", "elastic", "total", "work_friction"):
        assert np.abs(h[c] - base[c]).max() <= 1e-12 * E, c
