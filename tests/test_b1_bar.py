"""B1 (benchmarks.md): fixed-end bar released from compression, exact periodic solution."""
import numpy as np
import pytest

N = 80          # cells along the bar (meshes/bar80.msh)
W = 1.0 / N     # strip width (meshes/bar.geo default)
H = 1.0 / N


def exact_contact_end(t):
    """u_x(0, t) of the exact solution: 1/2 - tau/2, then 0 in contact, then tau/2."""
    tp = np.mod(t, 3.0)
    k = np.floor(tp)
    tau = tp - k
    return np.where(k == 0, 0.5 - tau / 2, np.where(k == 1, 0.0, np.minimum(tau, 1.0) / 2))


@pytest.fixture(scope="module")
def b1(tmp_path_factory):
    from conftest import run
    return run("b1_bar", tmp_path_factory.mktemp("b1"), "-output_every", 1)


def contact_end_displacement(r):
    with r.fields() as f:
        x = f["geometry/vertices"][:]
        u = f["vertex_fields/displacement_displacement"][:]
        t = f["time"][:, 0]
    end = np.abs(x[:, 0]) < 1e-12
    return t, u[:, end, 0].mean(axis=1)


def test_contact_end_matches_exact_solution(b1):
    t, u0 = contact_end_displacement(b1)
    assert t[-1] >= 3.0 - 1e-9  # through the first contact [1, 2] and the release
    err = np.abs(u0 - exact_contact_end(t)).max()
    assert err <= 0.04, err


def test_first_stress_plateau(b1):
    h = b1.history
    t, stress = h["time"], h["force_normal"] / W
    window = (t >= 1.2) & (t <= 1.85)
    assert window.sum() > 40
    assert np.all(np.abs(stress[window] - 0.5) <= 0.01 * 0.5), (stress[window].min(), stress[window].max())
    # contact exactly on [1, 2]
    active = t[h["active"] > 0]
    assert abs(active[0] - 1.0) <= 1.5 * H and abs(active[-1] - 2.0) <= 1.5 * H


def test_energy_drift_and_balance(b1):
    h = b1.history
    drift = abs(h["total"][-1] - h["total"][0]) / h["total"][0]
    assert drift <= 2e-3, drift
    assert h["balance_residual"].max() <= 1e-10
    # energy is lost only through the contact work at switching steps
    assert abs(h["total"][-1] - h["total"][0] - h["work_contact"][-1]) <= 1e-10 * h["total"][0]


def test_consistent_initial_state(b1):
    """The massless contact node starts at the quasi-static value 1/2 - h/2, not 1/2, and step one
    loses no energy (an inconsistent start loses about 1.4%)."""
    t, u0 = contact_end_displacement(b1)
    assert abs(u0[0] - (0.5 - H / 2)) <= 1e-12, u0[0]
    h = b1.history
    assert abs(h["total"][1] - h["total"][0]) <= 1e-12 * h["total"][0]
    # E0 is the elastic energy of the consistent state: 1/8 W (1 - h) on the strip
    assert abs(h["total"][0] - W / 8 * (1 - H)) <= 1e-12


def test_redistributed_mass_rings_within_its_measured_bound(tmp_path):
    """B1 is exact with the paper's modified mass (options/b1_bar.opts sets it, the tests above). The
    redistributed mass, the default elsewhere, moves the end node's mass one cell into the bar: the
    contact stress plateau then rings, measured at 2.2% (docs/validation.md, "The mass"), and the energy balance
    still closes. Bound 3%, and the ringing is there (above 1%): what docs/validation.md says it gives."""
    from conftest import run
    h = run("b1_bar", tmp_path, "-mass", "redistributed", "-output_every", 0).history
    t, stress = h["time"], h["force_normal"] / W
    window = (t >= 1.2) & (t <= 1.85)
    err = np.abs(stress[window] - 0.5).max() / 0.5
    assert 0.01 < err <= 0.03, err
    assert h["balance_residual"].max() <= 1e-10
