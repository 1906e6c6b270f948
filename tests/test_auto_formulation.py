"""-contact_formulation auto (issue 41): the formulation whose whole run a cost model fitted on
measured runs predicts cheaper (src/contact/interface/cost.c, docs/scaling.md "The formulation
chosen by cost"), and the active-set path it now chooses for most runs, which is exact to its CG
tolerance rather than to round-off. The rest of the suite runs the condensed formulation
(conftest.py); these tests give -contact_formulation auto explicitly."""
import re

import numpy as np
import pytest

from conftest import run

CHOICE = re.compile(r"contact formulation (\w+) \(auto: (?:(\d+) steps predicted ([\d.e+-]+) s, (\w+) ([\d.e+-]+) s|the only formulation for this problem)\)")


def choice(r):
    m = CHOICE.search(r.output)
    assert m, r.output[-1500:]
    return m


@pytest.mark.parametrize("case,extra,expected", [
    # the users' D2 ball at H 0.1 over 75 steps: no factorization, CG steps cheaper than the triangular
    # solves (measured 1.1 s in all against 1.2 s, scripts/cost_model_runs.csv)
    ("d2_ball", ("-mesh", "meshes/ball10.msh"), "active_set"),
    # with friction at dt 8e-3 (c_p dt / h_c' = 5.9) the certified active set's CG needs many iterations:
    # 3.4 s against 2.2 s condensed over 38 steps
    ("d2_ball", ("-mesh", "meshes/ball10.msh", "-mu", 0.2, "-ts_dt", 8e-3), "condensed"),
    # 2D at c_p dt / h_c' = 7.4 over 150 steps: CG needs many iterations, the 2D factor is cheap
    ("d1_disk", ("-ts_dt", 1.6e-2, "-ts_max_time", 2.4), "condensed"),
])
def test_auto_chooses_the_cheaper_prediction(tmp_path, case, extra, expected):
    r = run(case, tmp_path, "-contact_formulation", "auto", *extra, "-check_input", np_=0)
    m = choice(r)
    assert m.group(1) == expected, r.output[-1500:]
    assert float(m.group(3)) < float(m.group(5)), m.group(0)
    assert m.group(4) in ("condensed", "active_set") and m.group(4) != expected


def test_auto_choice_is_the_same_on_any_number_of_ranks(tmp_path):
    """The model reads global quantities only (dofs, h_c', the plan): 2 ranks choose as 1 does."""
    lines = [choice(run("d2_ball", tmp_path, "-contact_formulation", "auto", "-mesh", "meshes/ball10.msh", "-mu", 0.2,
                        "-check_input", np_=n, name=f"r{n}")).group(0) for n in (1, 2)]
    assert lines[0] == lines[1]


@pytest.mark.parametrize("case,extra", [
    ("cube_groove", ("-mu", 0.3)),  # friction corners: two Coulomb laws on one node, contact space only
    ("two_balls", ("-elasticity", "svk", "-contact_pairs_sliding", "large")),  # K~'s pattern changes
])
def test_auto_chooses_condensed_where_only_it_can_carry_the_problem(tmp_path, case, extra):
    r = run(case, tmp_path, "-contact_formulation", "auto", *extra, "-check_input", np_=0)
    m = choice(r)
    assert m.group(1) == "condensed" and m.group(2) is None, m.group(0)


@pytest.fixture(scope="module", params=["d1_disk", "d2_ball"])
def auto_and_condensed(request, tmp_path_factory):
    d = tmp_path_factory.mktemp(request.param)
    active_set = run(request.param, d, "-contact_formulation", "active_set", "-output_every", 0, name="active_set")
    return active_set.history, run(request.param, d, "-contact_formulation", "condensed", "-output_every", 0, name="condensed").history


def test_auto_active_set_is_the_condensed_motion_to_its_tolerance(auto_and_condensed):
    """The showcases D1 and D2 on the active set, the path auto takes on larger meshes, against the
    condensed formulation: the same contact sets at every step, no penetration, the energy identity
    at round-off by the step certificate (it was 3.4e-10 and 2.5e-10 of the energy at -contact_tol
    alone), and the energies and the contact force equal to 1e-7 of their scales. (On these small
    meshes auto itself takes condensed, measured faster.)"""
    a, c = auto_and_condensed
    e0, f = c["total"][0], np.abs(c["force_normal"]).max()
    assert f > 0 and (c["active"] > 0).sum() >= 10
    assert np.array_equal(a["active"], c["active"])
    assert a["max_penetration"].max() <= 1e-12
    assert a["balance_residual"].max() <= 1e-11
    for col in ("kinetic", "elastic", "total"):
        assert np.abs(a[col] - c[col]).max() <= 1e-7 * e0, col
    assert np.abs(a["force_normal"] - c["force_normal"]).max() <= 1e-7 * f


def test_fit_script_reproduces_the_models_in_the_sources():
    """scripts/cost_model_fit.py on the committed runs (measured again with the step certificate,
    issue 50) prints the constants that the formulations' cost functions hold, and no measured case
    loses more than 10% to the choice but the eight the model's form does not capture
    (docs/scaling.md, "The formulation chosen by cost"): they are listed, so that a refit that
    loses elsewhere fails."""
    import os
    import subprocess
    import sys
    from conftest import ROOT
    out = subprocess.run([sys.executable, "-s", os.path.join(ROOT, "scripts", "cost_model_fit.py")], capture_output=True, text=True, check=True).stdout
    sources = {f: open(os.path.join(ROOT, "src", "contact", "impls", f, f + ".c")).read().replace(" ", "") for f in ("condensed", "active_set")}
    for line in out.splitlines():
        m = re.match(r"([23])D (\w+)\s+(\{\{.*\}\})$", line)
        if m:
            numbers = [float(x) for x in re.findall(r"-?[\d.]+(?:e-?\d+)?", m.group(3))]
            table = re.search(r"\{\{([^}]*)\},\{([^}]*)\}\},/\*" + m.group(1) + r"D\*/", sources[m.group(2)])
            assert table, (m.group(2), m.group(1))
            held = [float(x) for x in (table.group(1) + "," + table.group(2)).split(",")]
            assert np.allclose(held, numbers, rtol=2e-3, atol=2e-4), (line, held)
    losses = re.findall(r"^\s*(\d+)\s+(\d)D (\S+)\s+cfl\s+(\S+) mu (\S+).*?(\d+\.\d)%", out, re.M)
    assert losses
    known = {("20", "2", "disk05.msh", "1.81"), ("20", "3", "ball10.msh", "2.94"), ("75", "3", "ball10.msh", "1.47"),
             ("150", "3", "ball07.msh", "2.10"), ("1000", "2", "disk0125.msh", "1.75"), ("1000", "3", "ball07.msh", "2.10")}
    for steps, dim, mesh, cfl, mu, loss in losses:
        assert float(loss) <= 10 or ((steps, dim, mesh, cfl) in known and float(loss) <= 80), (steps, dim, mesh, cfl, mu, loss)
