"""Bad input exits non-zero with a message that names the problem."""
import pytest

from conftest import run

CASES = [
    (["-mesh", "meshes/no_such_mesh.msh"], ["no_such_mesh.msh", "does not exist"]),
    (["-contact_boundary", "bottom"], ['no physical group named "bottom"']),
    (["-dirichlet", "clamp"], ['no physical group named "clamp"']),
    (["-nu", "0.5"], ["Poisson ratio -nu 0.5", "must lie in (-1, 0.5)"]),
    (["-nu", "0.7"], ["Poisson ratio -nu 0.7", "must lie in (-1, 0.5)"]),
    (["-E", "0"], ["Young's modulus -E 0", "must be > 0"]),
    (["-E", "-5"], ["Young's modulus -E -5", "must be > 0"]),
    (["-ts_dt", "0"], ["time step -ts_dt 0", "must be > 0"]),
    (["-ts_dt", "-0.01"], ["time step -ts_dt -0.01", "must be > 0"]),
    (["-traction", "body", "-traction_body_value", "0,1"], ['-traction body: the physical group "body" holds cells, not boundary faces']),
    (["-dirichlet", "upper", "-dirichlet_upper_components", "1,1"], ["-dirichlet_upper_components lists component 1 twice"]),
    (["-E", "1e308"], ["The stiffness matrix overflows with -E 1e+308"]),
    # a switch given a value PETSc cannot read as a logical: PETSc's own message does not name it
    (["-active_set_block_matrix", "2"], ["-active_set_block_matrix 2: give 1 or 0"]),
    (["-mass_lumped", "yes2"], ["-mass_lumped yes2: give 1 or 0 (also true/false, yes/no, on/off)"]),
]


@pytest.mark.parametrize("extra,messages", CASES)
def test_bad_input_is_named(tmp_path, extra, messages):
    r = run("d1_disk", tmp_path, *extra, np_=0, check=False)
    assert r.returncode != 0
    for m in messages:
        assert m in r.output, r.output[-1500:]


def test_unknown_name_lists_the_known_ones(tmp_path):
    r = run("d1_disk", tmp_path, "-contact_boundary", "bottom", np_=0, check=False)
    assert '"contact"' in r.output and '"upper"' in r.output and '"body"' in r.output


def test_energy_audit_stops_the_run_and_keeps_the_output(tmp_path):
    """An audit tolerance below round-off trips at the first step with energy exchange: the run
    stops with a message that says why, and the history written so far stays readable."""
    import numpy as np
    r = run("d1_disk", tmp_path, "-audit_tol", 1e-30, "-output_every", 1, np_=0, check=False)
    assert r.returncode != 0
    assert "Energy audit failed at step" in r.output
    h = r.history
    assert len(h) >= 1 and h["step"][0] == 0
    with r.fields() as f:
        assert f["vertex_fields/displacement_displacement"].shape[0] == len(h)
