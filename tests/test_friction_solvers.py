"""The friction solvers (-friction_type, docs/method.md section 6): the semismooth Newton solver, the
default, gives the paper's fixed point's solution wherever that converges, and converges where the
fixed point's contraction is poor (c_p dt / h_c' of 4 in 3D)."""
import numpy as np
import pytest

from conftest import run

SOLVERS = ("newton", "fixedpoint")


def contact_fields(r):
    """Contact pressure and tangential traction of every snapshot, in the mesh file's vertex order."""
    with r.fields() as f:
        order = np.argsort(f["fields/serial_vertex"][:])
        return f["fields/contact_pressure"][:][:, order], f["fields/tangential_traction"][:][:, order]


def assert_same_solution(a, b):
    """Reactions to 1e-10 of their scale, the same active and slipping sets at every step."""
    ha, hb = a.history, b.history
    assert np.array_equal(ha["active"], hb["active"]) and np.array_equal(ha["slipping"], hb["slipping"])
    scale = np.abs(ha["force_normal"]).max()
    assert scale > 0
    for c in ("force_normal", "force_tangential"):
        assert np.abs(ha[c] - hb[c]).max() <= 1e-10 * scale, c
    (pa, ta), (pb, tb) = contact_fields(a), contact_fields(b)
    pscale = np.abs(pa).max()
    assert pscale > 0 and np.abs(pa - pb).max() <= 1e-10 * pscale
    assert np.abs(ta - tb).max() <= 1e-10 * pscale
    for h in (ha, hb):
        assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8


@pytest.mark.parametrize("case,extra", [
    ("d1_friction", ("-ts_max_time", 0.12)),                  # 2D: the interval
    ("d2_ball", ("-mu", 0.2, "-ts_max_time", 0.12)),         # 3D: the disk
    ("f1_box", ("-ts_max_time", 1.0)),                        # 3D, exact: steady sliding at 30 degrees
])
def test_newton_equals_the_papers_fixed_point(case, extra, tmp_path):
    runs = {s: run(case, tmp_path, "-friction_type", s, "-output_every", 2, *extra, name=s, np_=1) for s in SOLVERS}
    assert_same_solution(runs["newton"], runs["fixedpoint"])
    hn, hf = runs["newton"].history, runs["fixedpoint"].history
    assert hn["slipping"].max() > 0
    # Newton's iterations are fewer than the fixed point's threshold updates on the contact steps
    contact = hn["active"] > 0
    assert hn["friction_its"][contact].mean() < hf["friction_its"][contact].mean()


def test_newton_two_ranks_equal_one(tmp_path):
    a = run("d2_ball", tmp_path, "-mu", 0.2, "-ts_max_time", 0.12, "-output_every", 2, name="np1", np_=1)
    b = run("d2_ball", tmp_path, "-mu", 0.2, "-ts_max_time", 0.12, "-output_every", 2, name="np2", np_=2)
    assert_same_solution(a, b)


def test_3d_friction_at_cfl_4_has_no_rejection(mm):
    """The D2 ball on the H = 0.1 mesh at c_p dt / h_c' = 4 with mu = 0.5, through the impact: no step
    is rejected, a few Newton steps each, and the energy balance and Coulomb law hold at every step."""
    r = mm("d2_ball", "-mesh", "meshes/ball10.msh", "-mu", 0.5, "-ts_dt", 0.0109, "-ts_max_time", 11 * 0.0109,
           "-output_every", 0)
    h = r.history
    assert "rejected" not in r.output
    assert 3.8 <= h["cfl"][1:].min() and h["cfl"].max() <= 4.2
    assert np.allclose(np.diff(h["time"]), 0.0109, rtol=1e-9, atol=0)
    contact = h["active"] > 0
    assert contact.sum() >= 5 and h["slipping"].max() > 0
    assert h["friction_its"][contact].mean() <= 6 and h["friction_its"].max() <= 10
    assert h["coulomb_residual"].max() <= 1e-8 and h["balance_residual"].max() <= 1e-8
    audit = h["total"] - h["work_ext"] - h["work_contact"] - h["work_friction"]
    assert np.abs(audit - audit[0]).max() <= 1e-10 * h["total"][0]


def test_unknown_friction_type_is_refused(tmp_path):
    r = run("d1_friction", tmp_path, "-friction_type", "gauss_seidel", np_=0, check=False)
    assert r.returncode != 0 and "-friction_type gauss_seidel is not a friction solver" in r.output


def test_newton_needs_the_delassus_operator(tmp_path):
    r = run("d1_friction", tmp_path, "-friction_type", "newton", "-contact_formulation", "active_set", np_=0, check=False)
    assert r.returncode != 0 and "use -friction_type fixedpoint" in r.output
