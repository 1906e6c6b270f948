"""The friction solvers (-friction_type, docs/method.md section 6): the semismooth Newton solver, the
default, gives the paper's fixed point's solution wherever that converges, and converges where the
fixed point's contraction is poor (c_p dt / h_c' of 4 in 3D)."""
import h5py
import numpy as np
import pytest

from conftest import run

SOLVERS = ("newton", "fixedpoint")


def contact_fields(r):
    """Contact pressure and tangential traction of every snapshot, in the mesh file's vertex order."""
    with r.fields() as f:
        order = np.argsort(f["vertex_fields/serial_vertex_nodal"][:])
        return f["vertex_fields/contact_pressure_nodal"][:][:, order], f["vertex_fields/tangential_traction_displacement"][:][:, order]


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


def fc3d_error(W, q, mu, r):
    """The Friction Contact Library's (and Siconos') error of r for u = W r + q, r in the Coulomb cone:
    |r - P_K(r - (u + mu |u_t| e_n))| / max(|q|, |r|, |u|)."""
    u = W @ r + q
    R, U = r.reshape(-1, 3), u.reshape(-1, 3)
    z = R - U
    z[:, 0] -= mu * np.linalg.norm(U[:, 1:], axis=1)
    P = np.zeros_like(z)
    zn, nt = z[:, 0], np.linalg.norm(z[:, 1:], axis=1)
    inside = nt <= mu * zn
    P[inside] = z[inside]
    mid = ~inside & (mu * nt > -zn)
    a = (zn[mid] + mu[mid] * nt[mid]) / (1 + mu[mid] ** 2)
    P[mid, 0] = a
    P[mid, 1:] = (mu[mid] * a / nt[mid])[:, None] * z[mid, 1:]
    return np.linalg.norm(R - P) / max(np.linalg.norm(q), np.linalg.norm(r), np.linalg.norm(u))


def test_3d_friction_at_cfl_4_has_no_rejection(tmp_path):
    """The D2 ball on the H = 0.1 mesh at c_p dt / h_c' = 4 with mu = 0.5, through the impact: no step
    is rejected, a few Newton steps each, and the energy balance and Coulomb law hold at every step.
    -friction_dump writes each contact step's problem in fclib's form u = W r + q: W symmetric with a
    positive diagonal, our reactions solve it (fc3d error), and they are the step's contact force."""
    dump = tmp_path / "dump"
    r = run("d2_ball", tmp_path, "-mesh", "meshes/ball10.msh", "-mu", 0.5, "-ts_dt", 0.0109, "-ts_max_time", 11 * 0.0109,
            "-output_every", 0, "-friction_dump", str(dump))
    h = r.history
    files = sorted(dump.glob("step_*.h5"))
    steps = [int(f.name[5:11]) for f in files]
    assert steps == [k for k in range(1, len(h)) if h["candidates"][k] > 0]
    fscale = np.abs(h["force_normal"]).max()
    for f, k in zip(files, steps):
        with h5py.File(f, "r") as d:
            W, q, mu, rr = (np.array(d[x]) for x in ("W", "q", "mu", "r"))
            assert d.attrs["spacedim"] == 3 and d.attrs["n"] == h["candidates"][k] and d.attrs["dt"] == 0.0109
        assert np.abs(W - W.T).max() <= 1e-12 * np.abs(W).max() and np.diag(W).min() > 0
        assert np.all(mu == 0.5) and rr[0::3].min() >= 0
        assert fc3d_error(W, q, mu, rr) <= 1e-9
        assert abs(rr[0::3].sum() - h["force_normal"][k]) <= 1e-9 * fscale, k
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


def test_newton_without_the_delassus_operator_is_the_active_set_coulomb_iteration(tmp_path):
    """With the active-set formulation (no Delassus operator) -friction_type newton, the default, is
    that formulation's own Coulomb iteration: one active-set iteration per friction iteration, where
    the fixed point counts threshold updates, each a whole active-set solve."""
    opts = ("d1_friction", "-contact_formulation", "active_set", "-ts_max_time", 0.06, "-output_every", 0)
    h = run(opts[0], tmp_path, *opts[1:], name="newton").history
    hf = run(opts[0], tmp_path, *opts[1:], "-friction_type", "fixedpoint", name="fixedpoint").history
    contact = h["active"] > 0
    assert contact.sum() >= 5 and h["slipping"].max() > 0
    assert np.array_equal(h["friction_its"], h["vi_its"])
    assert not np.array_equal(hf["friction_its"], hf["vi_its"])


@pytest.mark.parametrize("extra", [("-mu", 0), ("-contact_formulation", "active_set")])
def test_friction_dump_needs_contact_space_problems(tmp_path, extra):
    """-friction_dump writes the contact-space Coulomb problems: a run that solves none (frictionless,
    or a formulation without the Delassus operator) is refused, naming what it needs."""
    r = run("d1_friction", tmp_path, "-friction_dump", str(tmp_path / "dump"), *extra, np_=0, check=False)
    assert r.returncode != 0 and "-friction_dump" in r.output and "-contact_formulation condensed" in r.output
    assert not (tmp_path / "dump").exists()


@pytest.mark.parametrize("case,extra", [
    ("d1_friction", ("-ts_max_time", 0.12)),                  # 2D: the interval
    ("d2_ball", ("-mu", 0.2, "-ts_max_time", 0.1)),          # 3D: the disk
])
def test_active_set_coulomb_equals_its_fixed_point(case, extra, tmp_path):
    """The active-set formulation's own Coulomb iteration (thresholds following the iterate,
    docs/method.md section 3) gives the reactions of the paper's fixed point around its Tresca solves,
    with the same stick/slip sets, and takes one linear solve per iteration: no more iterations on a
    contact step than the fixed point has threshold updates times active-set iterations."""
    opts = ("-contact_formulation", "active_set", "-contact_tol", "1e-14", "-output_every", 2, *extra)
    runs = {s: run(case, tmp_path, "-friction_type", s, *opts, name=s, np_=1) for s in SOLVERS}
    assert_same_solution(runs["newton"], runs["fixedpoint"])
    hn = runs["newton"].history
    assert hn["slipping"].max() > 0 and hn["friction_its"].max() >= 3
    # in the newton run a friction iteration is one active-set iteration: the two counts are one
    assert np.array_equal(hn["friction_its"], hn["vi_its"])
