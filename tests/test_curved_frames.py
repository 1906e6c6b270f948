"""Contact frames that follow the contact point on a curved obstacle (-contact_frames follow, the
default with -elasticity svk and neohookean; docs/method.md section 8, "Frames that follow the contact
point").

Case options/disk_track.opts: an svk disk of radius r = 0.25 slides without friction around the inside
of a rigid circular track of radius R = 1, no gravity: the track alone turns it (centripetal force
m v^2 / (R - r)). The disk does not spin, so the contact point runs around its boundary, and each node
touches the track far from its reference position. With frames that follow, the disk stays on the true
circle through 76 degrees of arc, with the energy balance at round-off and the kinetic energy the frame
updates move booked as work_frame; with -contact_frames fixed each node keeps the tangent line of its
reference position, and the disk leaves through the wall. Its contact creates no energy (the step's
contact force is its mean, not a reaction carried from the last step along the last normal); a checkpoint of it continues on another rank count as if uninterrupted. In 3D, options/ball_bowl.opts
with svk (a ball inside a spherical bowl), with and without friction."""
import numpy as np
import pytest

R_TRACK, R_DISK, CENTER = 1.0, 0.25, np.array([0.0, 1.0])


def true_gaps(run):
    """g(X + u) = R - |X + u - c| at every vertex of every snapshot (positive inside the track)."""
    with run.fields() as f:
        X = f["geometry/vertices"][:]
        u = f["vertex_fields/displacement_displacement"][:]
    return R_TRACK - np.linalg.norm(X[None, :, :] + u - CENTER, axis=2)


def arc_degrees(h):
    """The angle of the disk's centre about the track's centre, from the lowest point."""
    x, y = h["ucm_x"], h["ucm_y"] + R_DISK
    return np.degrees(np.arctan2(x, CENTER[1] - y))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from conftest import run
    tmp = tmp_path_factory.mktemp("curved_frames")
    out = {}
    out["follow"] = run("disk_track", tmp, "-output_every", "10", name="follow")
    out["fixed"] = run("disk_track", tmp, "-output_every", "10", "-contact_frames", "fixed", name="fixed")
    out["follow2"] = run("disk_track", tmp, "-output_every", "10", np_=2, name="follow2")
    out["fine"] = run("disk_track", tmp, "-output_every", "0", "-ts_dt", "7.5e-4", "-contact_frames_angle", "0", name="fine")
    return out


def test_follow_stays_on_the_true_track(runs):
    """Through 76 degrees of arc the disk presses on the track (a node active at two steps in three: the elastic disk bounces) and no node
    crosses the true circle by more than 1e-4 h_c' (h_c' = 0.035): the bound linearized at each step's
    predicted midpoint leaves O((v dt)^2 / R) at most; measured 1.1e-6 = 3e-5 h_c', in the history
    (true geometry with this option) and in every snapshot."""
    r = runs["follow"]
    h = r.history
    h_c = 0.03503
    assert arc_degrees(h)[-1] > 70
    assert np.mean(h["active"] > 0) > 0.6
    assert h["max_penetration"].max() < 1e-4 * h_c
    assert -true_gaps(r).min() < 1e-4 * h_c
    # the disk's centre keeps to its circle of radius R - r (an elastic disk: within 1% of r)
    rc = np.hypot(h["ucm_x"], h["ucm_y"] + R_DISK - CENTER[1])
    assert np.abs(rc - (R_TRACK - R_DISK)).max() < 0.01 * R_DISK
    assert "contact frames follow the contact point" in r.output


def test_follow_energy_balance_and_frame_term(runs):
    """The balance, with the frame term booked, closes at round-off at every step; the frame term itself
    (the kinetic energy the turned massless directions move, 1/2 v.(M*_new - M*_old) v) stays below
    1e-3 of the energy (measured 1.3e-4: with the redistributed mass a rigid velocity keeps its kinetic
    energy exactly, docs/method.md section 8), and the energy stays within 1% of its initial value
    (measured -0.021%: test_contact_creates_no_energy)."""
    h = runs["follow"].history
    E0 = h["total"][0]
    assert h["balance_residual"].max() < 1e-11
    assert 0 < np.abs(h["work_frame"]).max() < 1e-3 * E0
    assert np.abs(h["total"] / E0 - 1).max() < 1e-2
    assert h["work_friction"].max() == 0  # frictionless: the turned reaction's work is contact work
    # the identity, summed: E - E0 = W_ext + W_c + W_f + W_frame
    lhs = h["total"] - E0
    rhs = h["work_ext"] + h["work_contact"] + h["work_friction"] + h["work_frame"]
    assert np.abs(lhs - rhs).max() < 1e-10 * E0


def lag_work(h, radius, centre, x0):
    """The contact work the frame updates predict (docs/method.md section 8, "The energy the turned
    frames make"): at each step in contact at both ends, 1/2 F^n sin(delta) v dt, the old reaction's part
    along the new tangent on the step's slide, v the body's speed along the obstacle (its centre's
    velocity less the part along the obstacle's normal: the bounces), delta = v dt / radius the angle one
    step turns a sliding node's normal (frames turned at every step: delta > -contact_frames_angle).
    centre: the obstacle's; x0: the body's centre of mass at the start."""
    axes = [c for c in "xyz" if "vcm_" + c in h.dtype.names]
    V = np.stack([h["vcm_" + c] for c in axes], axis=1)
    n = np.stack([h["ucm_" + c] for c in axes], axis=1) + x0 - centre
    n /= np.linalg.norm(n, axis=1)[:, None]
    v = np.linalg.norm(V - np.sum(V * n, axis=1)[:, None] * n, axis=1)
    v = 0.5 * (v[1:] + v[:-1])
    F, dt = h["force_normal"], h["dt"][1:]
    both = (h["active"][1:] > 0) & (h["active"][:-1] > 0)
    return np.sum((0.5 * F[:-1] * np.sin(v * dt / radius) * v * dt)[both])


def test_contact_creates_no_energy(runs):
    """The steps in persistent contact do no contact work (their sum: 1e-6 of E0 at most, measured 2e-8),
    where a reaction carried from the last step along the last step's normal would do the lagging normal's
    1/2 F sin(v dt / R) v dt at each (+2.0e-4 of E0 summed, lag_work: the finite-strain step had it before
    its contact force became the step's mean, docs/method.md section 13). What remains is dissipated: the
    steps where nodes enter or leave (-7.8e-5) and the frame term (-1.4e-4), -2.1e-4 of E0 in all, and
    with dt halved and every frame turned (-contact_frames_angle 0) half as much (measured 0.43 of it)."""
    h, fine = runs["follow"].history, runs["fine"].history
    E0 = h["total"][0]
    dW = np.diff(h["work_contact"])
    switch = h["switched"][1:] > 0
    assert abs(dW[~switch].sum()) < 1e-6 * E0
    assert lag_work(h, R_TRACK, CENTER, np.array([0.0, R_DISK])) > 1e-4 * E0  # what a carried reaction would do
    assert -5e-4 * E0 < dW[switch].sum() <= 0
    loss, loss_fine = h["total"][-1] - E0, fine["total"][-1] - fine["total"][0]
    assert -1e-3 * E0 < loss < 0 and 0.3 < loss_fine / loss < 0.6


def test_fixed_frames_leave_the_track(runs):
    """The same run with each node's reference frame: the disk crosses the true circle by a tenth of its
    own radius and more (measured 0.43, the disk's centre 1.18 from the track's), which the linearized
    history column does not see. This is what the option fixes."""
    r = runs["fixed"]
    # no frame turns (work_frame is there for the mass in free flight, and the disk, always near its
    # track, keeps -mass's M*: docs/method.md section 2)
    assert np.all(r.history["work_frame"] == 0)
    assert -true_gaps(r).min() > 0.1 * R_DISK
    assert r.history["max_penetration"].max() < 1e-12


def test_two_ranks_same_run(runs):
    """1 and 2 ranks: the same frames, the same trajectory to round-off of the energy scale."""
    h1, h2 = runs["follow"].history, runs["follow2"].history
    E0 = h1["total"][0]
    assert len(h1) == len(h2)
    for c in ("total", "work_frame", "work_contact", "ucm_x", "ucm_y"):
        assert np.abs(h1[c] - h2[c]).max() < 1e-9 * max(E0, 1.0), c


# 3D, with and without friction: options/ball_bowl.opts (an elastic ball, radius 1, 1200 dofs, inside a
# spherical bowl of radius 4, gravity 1, v0 = 1 along x, mu = 0.3) with -elasticity svk: frames follow.
BOWL_R, BALL_R, BOWL_C = 4.0, 1.0, np.array([0.0, 0.0, 4.0])
BOWL_H_C = 0.2546  # h_c' of meshes/ball_bowl.msh (start-up report)


def bowl_gaps(run):
    """g(X + u) = R_bowl - |X + u - c| at every vertex of every snapshot (positive inside the bowl)."""
    with run.fields() as f:
        X = f["geometry/vertices"][:]
        u = f["vertex_fields/displacement_displacement"][:]
    return BOWL_R - np.linalg.norm(X[None, :, :] + u - BOWL_C, axis=2)


def bowl_arc(h):
    """The angle (radians) of the ball's centre about the bowl's centre, from the bowl's axis."""
    c = np.stack([h["ucm_x"], h["ucm_y"], h["ucm_z"] + 1.01], axis=1) - BOWL_C
    return np.arccos(-c[:, 2] / np.linalg.norm(c, axis=1))


@pytest.fixture(scope="module")
def bowl(tmp_path_factory):
    from conftest import run
    tmp = tmp_path_factory.mktemp("bowl")
    common = ("ball_bowl", tmp, "-elasticity", "svk", "-output_every", "20")
    return {
        "friction": run(*common, np_=2, name="friction"),
        "friction1": run(*common, np_=1, name="friction1"),
        "frictionless": run(*common, "-mu", "0", np_=2, name="frictionless"),
        "fixed": run(*common, "-mu", "0", "-contact_frames", "fixed", np_=2, name="fixed"),
    }


@pytest.mark.parametrize("case", ["friction", "frictionless"])
def test_bowl_3d_follow(bowl, case):
    """A ball sliding (mu = 0) or rolling (mu = 0.3) inside a spherical bowl, 3D, frames that follow:
    its centre travels 17 (friction) and 21 (frictionless) degrees about the bowl's centre, its contact
    point 1.2 and 1.5 along the bowl, 5 and 6 h_c' (h_c' = 0.255), from nodes first active near the
    bottom. No node crosses the true sphere by more than 1e-4 h_c' (measured 8e-6 and 4e-6 h_c', the
    history and every snapshot); the balance closes at round-off with W_frame booked, W_frame below
    1e-3 of the energy (measured 3e-4 and 8e-5 E0); the Coulomb residual of every step after the
    initial state is at solver round-off (measured 2e-11); with friction the ball is dragged into
    rolling (spin L_y within 15% of 2/5 m R v, measured 7%) and friction dissipates a quarter of E0;
    without it the ball does not spin (L_y below 2% of that)."""
    r = bowl[case]
    h = r.history
    E0 = h["total"][0]
    assert "contact frames follow the contact point" in r.output
    assert BOWL_R * bowl_arc(h)[-1] > 4 * BOWL_H_C and np.mean(h["active"] > 0) > 0.5
    assert h["max_penetration"].max() < 1e-4 * BOWL_H_C
    assert -bowl_gaps(r).min() < 1e-4 * BOWL_H_C
    assert h["balance_residual"].max() < 1e-11
    assert 0 < np.abs(h["work_frame"]).max() < 1e-3 * E0
    lhs = h["total"] - E0
    rhs = h["work_ext"] + h["work_contact"] + h["work_friction"] + h["work_frame"]
    assert np.abs(lhs - rhs).max() < 1e-10 * E0
    assert h["coulomb_residual"][1:].max() < 1e-9
    mass = 4.100576  # of M (start-up report)
    rolling = 0.4 * mass * BALL_R * h["vcm_x"][-1]
    if case == "friction":
        assert h["slipping"].max() > 0 and h["work_friction"][-1] < -0.2 * E0
        assert abs(h["L_y"][-1] - rolling) < 0.15 * rolling
    else:
        assert h["work_friction"].max() == 0 and abs(h["L_y"][-1]) < 0.02 * rolling
        # as in 2D the contact creates no energy (measured -2.4e-4 of E0: nodes entering and leaving), where a
        # reaction carried along the last step's normal would make the lagging normal's +4e-3 (lag_work)
        assert -1e-3 * E0 < h["work_contact"][-1] <= 1e-8 * E0
        assert lag_work(h, BOWL_R, BOWL_C, np.array([0.0, 0.0, 1.01])) > 1e-3 * E0


def test_bowl_fixed_frames_cross_the_bowl(bowl):
    """The frictionless bowl with fixed frames: each node keeps the tangent plane of its reference
    normal line (near the bottom, nearly z = 0), a half-space wider than the sphere's inside: the ball
    crosses the true bowl by 0.85 h_c' (measured 0.217), which the history's linearized column does not see."""
    r = bowl["fixed"]
    assert -bowl_gaps(r).min() > 0.5 * BOWL_H_C
    assert r.history["max_penetration"].max() < 1e-9 * BOWL_H_C


def test_bowl_two_ranks_same_run(bowl):
    """Friction in 3D with frames that follow, 1 and 2 ranks: the same frames, slips and trajectory, to
    1e-9 of the energy (measured 1e-12)."""
    h1, h2 = bowl["friction1"].history, bowl["friction"].history
    E0 = h1["total"][0]
    assert len(h1) == len(h2) and np.array_equal(h1["active"], h2["active"])
    for c in ("total", "work_frame", "work_contact", "work_friction", "ucm_x", "ucm_z", "L_y"):
        assert np.abs(h1[c] - h2[c]).max() < 1e-9 * E0, c


def test_follow_refused_where_not_supported(mm):
    """-contact_frames follow with the linear law is refused, naming the fix."""
    r = mm("disk_track", "-elasticity", "linear", "-contact_frames", "follow", "-ts_max_time", "0.003", np_=0, check=False)
    assert r.returncode != 0
    assert "-contact_frames follow needs a finite-strain law" in r.output


def test_restart_across_rank_counts(runs, tmp_path):
    """Checkpointed at step 333 of 667 (38 degrees of arc) on 1 rank and continued on 2: the checkpoint
    records each following node's frame normal and gap (datasets "frames", "frames_run", written only
    with frames that follow; the state stays packed in those frames), so the restart rebuilds the very
    frames, M* and bounds of the straight run. The continued history then differs from the straight
    runs' by round-off alone: measured 1e-12 of E0 in the energies and works (work_frame restored
    with them), 2e-9 of the force scale in the contact force (the 1 vs 2 rank solver tolerance), 2e-13
    in the centre's position; asserted 1e-9 E0 and 1e-7 of the force, as 1 vs 2 ranks are. A restart
    without the frames (datasets deleted: the state read in the reference frames) stops at its first
    step with the contact solver diverging, and one without work_frame breaks the energy identity by
    1.3e-4 E0."""
    from conftest import run
    first = run("disk_track", tmp_path, "-output_every", "10", "-ts_max_steps", "333", name="ckpt")
    cont = run("disk_track", tmp_path, "-output_every", "10", "-restart", first.outdir, "-output_dir", first.outdir,
               np_=2, name="ckpt")
    assert "Restart from" in cont.output and "written on 1 rank, continued on 2" in cont.output
    h = cont.history
    E0 = runs["follow"].history["total"][0]
    fscale = np.abs(runs["follow"].history["force_normal"]).max()
    for ref in (runs["follow"].history, runs["follow2"].history):
        assert len(h) == len(ref) and np.array_equal(h["step"], ref["step"]) and np.array_equal(h["active"], ref["active"])
        for c in ("kinetic", "elastic", "total", "work_contact", "work_frame"):
            assert np.abs(h[c] - ref[c]).max() < 1e-9 * E0, c
        for c in ("ucm_x", "ucm_y"):
            assert np.abs(h[c] - ref[c]).max() < 1e-9 * R_DISK, c
        assert np.abs(h["force_normal"] - ref["force_normal"]).max() < 1e-7 * fscale
    # the identity over the restart: E - E0 = W_c + W_frame
    assert np.abs(h["total"] - E0 - h["work_contact"] - h["work_frame"]).max() < 1e-10 * E0
    assert h["balance_residual"].max() < 1e-11


def test_restart_keeps_the_frames_type(runs, mm):
    """A checkpoint of frames that follow holds its state in those frames: continued with fixed frames,
    it is refused with the option named."""
    r = mm("disk_track", "-restart", runs["follow"].outdir, "-contact_frames", "fixed", np_=0, check=False)
    assert r.returncode != 0
    assert "this run keeps them fixed" in r.output and "-contact_frames" in r.output
