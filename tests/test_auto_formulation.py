"""-contact_formulation auto (issue 41): the formulation whose whole run a cost model fitted on
measured runs predicts cheaper (src/contact/interface/cost.c, docs/scaling.md "The formulation
chosen by cost"), and the active-set path it now chooses for most runs, which is exact to its CG
tolerance rather than to round-off. The rest of the suite runs the condensed formulation
(conftest.py); these tests give -contact_formulation auto explicitly."""
import re

import numpy as np
import pytest

from conftest import run

CHOICE = re.compile(r"contact formulation (\w+) \(auto: (?:(\d+) steps predicted ([\d.e+-]+) s, (\w+) ([\d.e+-]+) s(; a direct solve within \d+%)?|the only formulation for this problem)\)")


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
    assert float(m.group(3)) < float(m.group(5)) or (m.group(1) == "condensed" and m.group(6)), m.group(0)
    assert m.group(4) in ("condensed", "active_set") and m.group(4) != expected


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
    """scripts/cost_model_fit.py on the committed runs (scripts/cost_model_collect.py: 1 and 2 ranks, the
    linear law and svk, issue 50) prints the constants that src/contact/impls/cost_constants.h holds, and
    no measured case loses more than 10% to the choice but the ones the model's form does not capture
    (docs/scaling.md, "Refitted with the ranks and the law"): they are listed, so that a refit that
    loses elsewhere fails."""
    import os
    import subprocess
    import sys
    from conftest import ROOT
    out = subprocess.run([sys.executable, "-s", os.path.join(ROOT, "scripts", "cost_model_fit.py")], capture_output=True, text=True, check=True).stdout
    models, seen = header_models(), 0
    for line in out.splitlines():
        m = re.match(r"([23])D (\w+)\s+\{\{([^}]*)\}, \{([^}]*)\}\}$", line)
        if m:
            held = models[(int(m.group(1)), m.group(2))]
            assert np.allclose(held[0] + held[1], [float(x) for x in (m.group(3) + "," + m.group(4)).split(",")], rtol=2e-3, atol=2e-4), (line, held)
            seen += 1
    assert seen == 8, out  # condensed and active_set, factor and cg (-contact 0), 2D and 3D
    losses = re.findall(r"^\s*(\d+)\s+(\d)D (\S+)\s+cfl\s+(\S+) mu (\S+) (\w+)\s+(\d) rk.*?(\d+\.\d)%", out.split("held out")[0], re.M)
    assert losses
    for steps, dim, mesh, cfl, mu, law, ranks, loss in losses:
        assert float(loss) <= 10 or ((steps, mesh, cfl, mu, law, ranks) in KNOWN_LOSSES and float(loss) <= KNOWN_LOSSES_MAX), (steps, dim, mesh, cfl, mu, law, ranks, loss)


# the case-lengths of the committed fit that lose more than 10% (scripts/cost_model_fit.py's printout), the
# contact formulations' and the linear path's (mu 0.0: -contact 0 among them): (steps, mesh, cfl, mu, law, ranks).
# The worst, the 47k-dof 2D disk at c_p dt / h_c' 1.75 (condensed taken, the active set 1.5 times faster), is
# a case the model's power law does not capture (docs/scaling.md, "The linear path chosen by cost")
KNOWN_LOSSES = {
    ("20", "disk0125.msh", "7.00", "0.0", "linear", "1"),
    ("20", "disk_bench.msh", "1.23", "0.0", "linear", "2"),
    ("20", "ball.msh", "0.64", "0.0", "svk", "2"),
    ("20", "ball07.msh", "2.10", "0.0", "svk", "2"),
    ("20", "ball07.msh", "2.10", "0.2", "svk", "1"),
    ("20", "ball07.msh", "2.10", "0.2", "svk", "2"),
    ("20", "ball10.msh", "2.94", "0.2", "linear", "1"),
    ("20", "ball_bench.msh", "3.30", "0.0", "linear", "2"),
    ("75", "disk0125.msh", "1.75", "0.2", "linear", "2"),
    ("75", "disk0125.msh", "1.75", "0.2", "svk", "1"),
    ("75", "disk0125.msh", "1.75", "0.2", "svk", "2"),
    ("75", "ball07.msh", "2.10", "0.2", "svk", "2"),
    ("75", "ball_bench.msh", "3.30", "0.0", "linear", "1"),
    ("150", "disk0125.msh", "1.75", "0.0", "linear", "2"),
    ("150", "disk0125.msh", "1.75", "0.2", "linear", "1"),
    ("150", "disk0125.msh", "1.75", "0.2", "linear", "2"),
    ("150", "disk0125.msh", "1.75", "0.2", "svk", "1"),
    ("150", "disk0125.msh", "1.75", "0.2", "svk", "2"),
    ("1000", "disk0125.msh", "1.75", "0.0", "linear", "1"),
    ("1000", "disk0125.msh", "1.75", "0.0", "linear", "2"),
    ("1000", "disk0125.msh", "1.75", "0.2", "linear", "1"),
    ("1000", "disk0125.msh", "1.75", "0.2", "linear", "2"),
    ("1000", "disk0125.msh", "1.75", "0.2", "svk", "1"),
    ("1000", "disk0125.msh", "1.75", "0.2", "svk", "2"),
    ("1000", "ball10.msh", "1.47", "0.0", "svk", "1"),
    ("1000", "ball_bench.msh", "0.82", "0.0", "linear", "2"),
    ("1000", "ball_bench.msh", "1.65", "0.0", "linear", "1"),
}
KNOWN_LOSSES_MAX = 70



def header_models():
    """The constants auto holds: src/contact/impls/cost_constants.h, written by scripts/cost_model_fit.py --write."""
    import os
    from conftest import ROOT
    models = {}
    for m in re.finditer(r"#define MM_COST_(\w+)_([23])D \{\{([^}]*)\}, \{([^}]*)\}\}", open(os.path.join(ROOT, "src", "contact", "impls", "cost_constants.h")).read()):
        models[(int(m.group(2)), m.group(1).lower())] = ([float(x) for x in m.group(3).split(",")], [float(x) for x in m.group(4).split(",")])
    assert len(models) == 8
    return models


def choose(total, direct):
    """auto's rule (src/contact/interface/cost.c): the cheaper prediction, or the direct solve within MM_COST_DIRECT_MARGIN of it"""
    cheapest = min(total, key=total.get)
    return direct if total[direct] <= (1 + direct_margin()) * total[cheapest] else cheapest


def direct_margin():
    import os
    from conftest import ROOT
    return float(re.search(r"#define MM_COST_DIRECT_MARGIN ([\d.]+)", open(os.path.join(ROOT, "src", "contact", "impls", "cost_constants.h")).read()).group(1))


def model_total(models, dim, form, dofs, cfl, mu, law, ranks, steps):
    """docs/scaling.md, "Refitted with the ranks and the law": set-up + steps x step."""
    s, u = models[(dim, form)]
    ln, lc, lr, f, g = np.log(dofs), np.log1p(cfl), np.log(ranks), float(mu > 0), float(law != "linear")
    step = np.exp(s[0] + s[1] * ln + s[2] * lc + f * (s[3] + s[4] * lc) + g * (s[6] + s[7] * ln + s[10] * lc) + lr * (s[5] + s[8] * ln + s[9] * lc))
    return np.exp(u[0] + u[1] * ln + lr * (u[2] + u[3] * ln)) + steps * step


# issue 50's first row, the disk in the bowl; and the D2 ball on the 12k-dof mesh with friction. flips: the
# committed fit's choice differs among 1 and 2 ranks, linear and svk (after a refit, set it from the
# model's printout if it fails here only)
FLIPS_BOWL, FLIPS_BALL = False, True
RANKS_AND_LAW_CASES = [("disk_bowl", 2, (), 0.0, FLIPS_BOWL), ("d2_ball", 3, ("-mesh", "meshes/ball10.msh", "-mu", 0.2, "-ts_max_steps", 20), 0.2, FLIPS_BALL)]


@pytest.mark.parametrize("case,dim,extra,mu,flips", RANKS_AND_LAW_CASES)
def test_auto_choice_follows_the_ranks_and_the_law(tmp_path, case, dim, extra, mu, flips):
    """auto's prediction reads the run's ranks and the law (MMCostInput.ranks, .finite): on 1 and 2 ranks,
    linear and svk, the start-up report's predicted totals are the model's of cost_constants.h for that
    rank count and law (to the 3 digits printed), and the choice is the model's; where the model says the
    ranks or the law change the choice, the binary's choice changes with them. Not a timing test."""
    models, choices = header_models(), {}
    for ranks in (1, 2):
        for law in ("linear", "svk"):
            r = run(case, tmp_path, "-contact_formulation", "auto", *extra, *(("-elasticity", law) if law != "linear" else ()),
                    "-check_input", np_=ranks, name=f"{ranks}{law}")
            m = choice(r)
            dofs = float(re.search(r"(\d+) dofs;", r.output).group(1))
            cfl = float(re.search(r"c_p dt / h_c' = ([\d.e+-]+)", r.output).group(1))
            total = {f: model_total(models, dim, f, dofs, cfl, mu, law, ranks, int(m.group(2))) for f in ("condensed", "active_set")}
            expected = choose(total, "condensed")
            assert m.group(1) == expected, (ranks, law, m.group(0), total)
            assert float(m.group(3)) == pytest.approx(total[expected], rel=6e-3), (ranks, law, m.group(0), total)
            assert float(m.group(5)) == pytest.approx(total[m.group(4)], rel=6e-3), (ranks, law, m.group(0), total)
            choices[(ranks, law)] = m.group(1)
    assert (len(set(choices.values())) > 1) == flips, choices


LINEAR_CHOICE = re.compile(r"contact formulation none \(auto: (\d+) steps predicted ([\d.e+-]+) s by (CG|the factor), ([\d.e+-]+) s by (CG|the factor)(?:; a direct solve within the margin)?\); K~ by (\w+) \+ (\w+)")


def test_linear_path_is_the_models_choice(tmp_path):
    """-contact 0 (issue 50: "the linear path, factor or CG, too"): K~ is factored or solved by CG as the linear
    path's model in cost_constants.h predicts for the whole run (scripts/cost_model_collect.py --linear), its
    c_p dt / h taken with the smallest cell. On 1 and 2 ranks, linear and svk, a long and a short run of the
    12k-dof ball and the 2D disk: the start-up report's two totals are the model's (to the 3 digits printed),
    the solver is the choice's (CG with ICC(0) on one rank, Jacobi on two), and the choice changes with the
    run's length (the factor's set-up against CG's steps). Not a timing test."""
    models, choices = header_models(), set()
    cases = [("d2_ball", 3, ("-mesh", "meshes/ball10.msh")), ("d2_ball", 3, ("-mesh", "meshes/ball10.msh", "-ts_max_steps", 3)),
             ("d1_disk", 2, ())]
    for case, dim, extra in cases:
        for ranks in (1, 2):
            for law in ("linear", "svk"):
                r = run(case, tmp_path, "-contact", 0, *extra, *(("-elasticity", law) if law != "linear" else ()),
                        "-check_input", np_=ranks, name=f"{case}{len(extra)}{ranks}{law}")
                m = LINEAR_CHOICE.search(r.output)
                assert m, r.output[-1500:]
                dofs = float(re.search(r"(\d+) dofs;", r.output).group(1))
                cfl = float(re.search(r"c_p dt / h = ([\d.e+-]+)", r.output).group(1))
                total = {f: model_total(models, dim, f, dofs, cfl, 0.0, law, ranks, int(m.group(1))) for f in ("factor", "cg")}
                expected = choose(total, "factor")
                chosen = "cg" if m.group(3) == "CG" else "factor"
                assert chosen == expected, (case, extra, ranks, law, m.group(0), total)
                assert float(m.group(2)) == pytest.approx(total[chosen], rel=6e-3), (m.group(0), total)
                assert float(m.group(4)) == pytest.approx(total[({"factor", "cg"} - {chosen}).pop()], rel=6e-3), (m.group(0), total)
                if chosen == "cg":
                    assert (m.group(6), m.group(7)) == ("cg", "icc" if ranks == 1 else "jacobi"), m.group(0)
                else:  # MUMPS's Cholesky, or on 2 ranks in 2D the interior split (schursplit)
                    assert m.group(6) == "preonly" and m.group(7) in ("cholesky", "schursplit"), m.group(0)
                choices.add(chosen)
    assert choices == {"factor", "cg"}, choices


@pytest.mark.parametrize("n,solver", [(0, "preonly + cholesky"), (1, "cg + icc")])
def test_iterative_dofs_overrides_the_linear_model(tmp_path, n, solver):
    """-iterative_dofs 0: always the factor; N >= 1: CG from N dofs; either way no prediction is printed."""
    r = run("d2_ball", tmp_path, "-contact", 0, "-mesh", "meshes/ball10.msh", "-iterative_dofs", n, "-check_input", np_=1)
    assert f"contact formulation none; K~ by {solver}" in r.output, r.output[-1500:]
