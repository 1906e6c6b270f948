"""Closed-form P1 assembly of K and M (src/assembly_p1.c) against the PetscFE quadrature path."""
import re

import numpy as np
import pytest

CHECK = re.compile(r"Assembly check, (\w+) against (\w+): K max\|diff\|/max\|entry\| = (\S+), M (\S+) \((\w+)")
SHORT = ["-output_every", 0, "-quiet"]


def check_line(r):
    m = CHECK.search(r.output)
    assert m, r.output[-2000:]
    return m.group(1), m.group(2), float(m.group(3)), float(m.group(4)), m.group(5)


@pytest.mark.parametrize("case,np_", [("d1_disk", 1), ("d1_disk", 2), ("d2_ball", 1), ("d2_ball", 2),
                                      ("b1_bar", 1), ("b1_bar", 2)])
def test_closed_form_matches_fe(case, np_, mm):
    # 2D and 3D, 1 and 2 ranks; b1_bar fixes component 0 on "right": constrained dofs dropped alike
    r = mm(case, "-assembly_check", "-ts_max_steps", 0, *SHORT, np_=np_)
    primary, other, dK, dM, mass = check_line(r)
    assert (primary, other, mass) == ("closed_form", "fe", "consistent")
    assert dK <= 1e-12 and dM <= 1e-12, (dK, dM)


def test_fe_path_checks_against_closed_form(mm):
    r = mm("d2_ball", "-assembly", "fe", "-assembly_check", "-ts_max_steps", 0, *SHORT, np_=0)
    primary, other, dK, dM, _ = check_line(r)
    assert (primary, other) == ("fe", "closed_form")
    assert dK <= 1e-12 and dM <= 1e-12, (dK, dM)


def test_lumped_mass_checks_stiffness_only(mm):
    r = mm("d1_disk", "-mass_lumped", "-assembly_check", "-ts_max_steps", 0, *SHORT, np_=0)
    _, _, dK, dM, mass = check_line(r)
    assert mass == "lumped" and dK <= 1e-12 and dM == 0


@pytest.mark.parametrize("case", ["d1_disk", "d2_ball"])
def test_same_history_both_ways(case, mm):
    # through the impact: contact and release happen in both runs
    t_end = {"d1_disk": 0.06, "d2_ball": 0.06}[case]
    runs = {a: mm(case, "-assembly", a, "-ts_max_time", t_end, *SHORT, np_=2, name=a).history
            for a in ("closed_form", "fe")}
    hc, hf = runs["closed_form"], runs["fe"]
    assert len(hc) == len(hf) and hc["active"].max() > 0
    scale = np.abs(hf["total"]).max()
    for col in ("kinetic", "elastic", "total", "work_ext", "work_contact"):
        assert np.abs(hc[col] - hf[col]).max() <= 1e-12 * scale, (col, np.abs(hc[col] - hf[col]).max() / scale)
    assert np.array_equal(hc["active"], hf["active"])
