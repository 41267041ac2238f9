"""A body on its face (phasekit.core.face): launched sliding and spinning on its face, or landing there
from a tilt, it slides and spins under Coulomb friction over the face until sliding and spin stop at
the same instant, at the terminal ratio v/(r w) of uniform pressure (Farkas, Bartels, Unger & Wolf,
PRL 90 248302 (2003): 0.653), the energy accounted for; checked against phasekit.theory.face_down."""

import json
import math
import pickle

import phasekit as pk
from phasekit.core.face import FaceContact, face_motion, landing
from phasekit.errors import ParameterError
from phasekit.steady.precessions import intermediate_omega, precession_state
from phasekit.theory.face_down import inertia_factor, slide_to_rest, stop_time, terminal_ratio

import numpy as np
import pytest

THIN = pk.Disk(0.0)
MU = 0.3
#: the full disk's terminal ratio, mpmath to 30 digits (phasekit.theory.face_down)
EPS_STAR = 0.6530017892


def _on_face(v0, w0, body=THIN, chart="euler", **kw):
    m = pk.Model(body, pk.Coulomb(MU), chart)
    return pk.simulate(m, m.chart.from_paper(pk.core.vertical_spin_start(0.0, w0, v0=v0)), 100.0, mode="face", **kw)


@pytest.mark.parametrize("v0, w0", [(1.0, 3.0), (3.0, 1.0)], ids=["ratio-0.33-below", "ratio-3-above"])
def test_a_disk_launched_on_its_face_stops_sliding_and_spinning_at_the_same_instant_at_the_terminal_ratio(v0, w0):
    """Starts on both sides of 0.653: v and w stop together (measured: the two extrapolated stop
    times 1e-12 apart), at v/(r w) = 0.6530 (measured 0.65297 and 0.65302), the energy balance closing,
    and the stop time that of theory.face_down's scipy run (v, omega) and of its stop_time (integrated
    in ln omega): three formulations."""
    traj = _on_face(v0, w0)
    face = traj.face
    assert traj.status is pk.Status.REST and face.status is pk.Status.REST
    assert traj.reason.startswith("lies flat; slid and spun on its face to rest at t = ")
    assert abs(face.t_stop_slide - face.t_stop_spin) < 1e-9
    assert abs(face.ratio_end - EPS_STAR) < 1e-3 and (v0 / w0 - EPS_STAR) * (face.ratio_end - v0 / w0) < 0
    assert face.t1 == pytest.approx(slide_to_rest(v0, w0, mu=MU).t_stop_slide, rel=1e-9)
    assert face.t1 == pytest.approx(stop_time(v0, w0, mu=MU), rel=1e-9)
    budget = traj.energy_budget()
    assert budget.laws[-1] == "face friction" and budget.residual_max < 1e-8
    assert budget.energy_start == pytest.approx(0.5 * v0**2 + 0.5 * THIN.C * w0**2, rel=1e-14)
    assert budget.energy_end == 0.0 and budget.dissipated[-1] == pytest.approx(budget.energy_start, rel=1e-10)
    assert [e.name for e in traj.events] == ["on its face", "at rest"]


def test_the_smooth_approximant_on_the_face_agrees_with_the_closed_forms():
    """The face flow with patch_friction's rational approximant (CasADi) against the closed forms:
    the stop time to its error (measured 2.6e-6), the terminal ratio to 1e-4."""
    exact = slide_to_rest(1.0, 3.0, mu=MU)
    smooth = face_motion(FaceContact(1.0, 0.0, MU, 0.5, 0.0, 1e-3, law="rational"), [1.0, 0.0, 3.0], 0.0, 100.0)
    assert smooth.t1 == pytest.approx(exact.t_stop_slide, rel=1e-5) and smooth.t1 != exact.t_stop_slide
    assert abs(smooth.ratio_end - EPS_STAR) < 1e-4 and smooth.residual_max < 1e-8


def test_the_face_motion_does_not_depend_on_the_direction_of_v_the_sense_of_w_or_the_chart():
    """Turning v in the plane, reversing w, or the vector chart: the same stop time; the path is straight."""
    ref = _on_face(1.0, 3.0).face
    m = pk.Model(THIN, pk.Coulomb(MU))
    turned = face_motion(ref.contact, [0.6, -0.8, -3.0], 0.0, 100.0)
    vec = _on_face(1.0, 3.0, chart="vector").face
    assert turned.t1 == pytest.approx(ref.t1, rel=1e-12) and vec.t1 == pytest.approx(ref.t1, rel=1e-12)
    Y = turned.states(np.linspace(0.0, turned.t1, 7)[:-1])
    assert np.allclose(Y[:, 0] * 0.8 + Y[:, 1] * 0.6, 0.0, atol=1e-14)  # v stays along (0.6, -0.8)
    assert m.n_states == 6


@pytest.mark.parametrize("beta", [0.3, 0.5, 0.7, 0.9])
def test_an_annular_face_ends_at_the_terminal_ratio_of_its_inner_ratio(beta):
    """A washer's face (uniform pressure over beta r < rho < r, kappa = (1 + beta^2)/2): the ratio at rest
    is theory.face_down.terminal_ratio(beta) (0.7044, 0.7745, 0.8580, 0.9508), above the full disk's, to
    1e-3 (measured: 4e-10 to 4e-6), the two motions stopping together."""
    cc = FaceContact(1.0, beta, MU, inertia_factor(beta), 0.0, 1e-3)
    run = face_motion(cc, [1.0, 0.0, 3.0], 0.0, 100.0)
    assert run.status is pk.Status.REST and abs(run.t_stop_slide - run.t_stop_spin) < 1e-9
    assert abs(run.ratio_end - terminal_ratio(beta).eps) < 1e-3 and run.ratio_end > EPS_STAR
    assert run.t1 == pytest.approx(slide_to_rest(1.0, 3.0, mu=MU, ratio=beta).t_stop_slide, rel=1e-8)


def test_pure_sliding_and_pure_spin_on_the_face_stop_as_their_closed_forms_say():
    """w = 0: F = -mu M g, so v stops at v0/mu after v0^2/(2 mu); v = 0: M_z = -mu M g a g0 with g0 = 2/3
    (uniform pressure), so w stops at C w0/(mu a g0) after turning C w0^2/(2 mu a g0)."""
    cc = FaceContact(1.0, 0.0, MU, 0.5, 0.0, 1e-3)
    slide = face_motion(cc, [0.6, -0.8, 0.0], 0.0, 100.0)
    assert slide.t1 == pytest.approx(1.0 / MU, rel=1e-12) and slide.t_stop_slide == pytest.approx(1.0 / MU, rel=1e-12)
    assert math.hypot(*slide.y1[3:5]) == pytest.approx(1.0 / (2 * MU), rel=1e-10) and slide.y1[5] == 0.0
    spin = face_motion(cc, [0.0, 0.0, -2.0], 0.0, 100.0)
    t_spin, turned = 0.5 * 2.0 / (MU * 2 / 3), -0.5 * 4.0 / (2 * MU * 2 / 3)
    assert spin.t1 == pytest.approx(t_spin, rel=1e-12) and spin.y1[5] == pytest.approx(turned, rel=1e-10)
    assert np.all(spin.y1[3:5] == 0.0) and slide.dissipated == pytest.approx(0.5, rel=1e-12)


def test_a_viscous_law_on_the_face_decays_exponentially_to_its_rest_cut_off():
    """Viscous(mu): traction -(mu/area) u over the face, so v = v0 e^(-mu t), w = w0 e^(-mu a^2 t/(2C));
    the speed sqrt(10) e^(-t/2) falls to REST_SPEED at 2 ln(sqrt(10)/1e-7), extrapolated at its rate one
    time constant (2) further; the run ends "rest" there, the balance closing."""
    m = pk.Model(THIN, pk.Viscous(0.5))
    traj = pk.simulate(m, pk.core.vertical_spin_start(0.0, 3.0, v0=1.0), 100.0, mode="face")
    f = traj.face
    assert f.contact.law == "viscous" and traj.status is pk.Status.REST
    Y = f.states([2.0, 10.0])
    assert np.allclose(Y[:, 0], np.exp(-0.5 * np.array([2.0, 10.0])), rtol=1e-8, atol=0)
    assert np.allclose(Y[:, 2], 3.0 * np.exp(-0.5 * np.array([2.0, 10.0]) / (2 * THIN.C)), rtol=1e-8, atol=0)
    # measured 4.5e-6: near the cut-off the state is 1e-7 and the run's absolute tolerance (3e-11) shows
    assert f.t1 == pytest.approx(2 * math.log(math.sqrt(10.0) / 1e-7) + 2.0, rel=1e-5)
    assert traj.energy_budget().residual_max < 1e-8


def test_the_terminal_ratio_grows_towards_one_as_the_inner_radius_grows():
    ratios = [face_motion(FaceContact(1.0, b, MU, inertia_factor(b), 0.0, 1e-3), [3.0, 0.0, 1.0], 0.0, 100.0).ratio_end
              for b in (0.0, 0.3, 0.6, 0.9, 0.99)]
    assert np.all(np.diff(ratios) > 0) and 0.99 < ratios[-1] < 1.0


def _eulers_disk(theta0=0.3, law=None, **kw):
    law = law or pk.Coulomb(0.5).with_dissipation(pk.RollingResistance(0.05))
    m = pk.Model(THIN, law)
    y0 = precession_state(THIN, theta0, omega0=intermediate_omega(THIN, theta0))
    return m, pk.simulate(m, m.chart.from_paper(y0), 100.0, stop_at="rest", **kw)


def test_eulers_disk_from_a_tilt_lands_on_its_face_and_slides_and_spins_to_rest():
    """Spinning in place at 0.3 rad, rolling resistance brings the face down (t = 15.447); the run goes
    on to rest on the face (t = 15.468), both motions stopping together, the energy budget closing with
    the face's friction its own line and the landing's loss at events."""
    m, traj = _eulers_disk()
    names = [e.name for e in traj.events]
    assert names[-3:] == ["face down", "on its face", "at rest"] and traj.status is pk.Status.REST
    land = traj.events_named("face down")[0]
    assert traj.face.t0 == land.t and traj.segments[-1].t1 == land.t and traj.t == traj.face.t1 > land.t
    assert abs(traj.face.t_stop_slide - traj.face.t_stop_spin) < 1e-9 and traj.mode == "face"
    budget = traj.energy_budget()
    assert budget.laws == ("sliding friction", "rolling-resistance", "face friction")
    assert budget.residual_max < 1e-8 and budget.energy_end == 0.0 and budget.dissipated[-1] > 0
    assert np.allclose(traj.x, m.chart.from_paper([0, 0, 0, 0, 1e-3, 0]), atol=0)
    check = traj.verify()  # the run again at rtol / 10 in the vector chart: measured 4.7e-11
    assert check.verdict == "converged" and check.outcome == ("rest", "rest") and check.worst < 1e-8


def test_the_landing_loses_the_normal_and_tilt_motion_and_keeps_v_and_the_vertical_angular_momentum():
    """The plastic landing against its energy written a second way: the loss is v_z^2/2 (the normal
    velocity of G) + w.L/2 - L_Z^2/(2C) (the tilt's rotation) + h(theta_f) - h(0) (G's drop), >= 0;
    v and L_Z = C w are kept, and the friction impulse neglected is bounded by mu |v_z|."""
    m, traj = _eulers_disk()
    x = traj.events_named("face down")[0].x
    U, V, Om, Lam, th, n = m.chart.to_paper(x)
    c, s = math.cos(th), math.sin(th)
    h, h1 = (float(q) for q in THIN.height_slope(c))
    w = np.array([(n - Om * c) * s, Lam, Om + (n - Om * c) * c])  # in the turning axes (e_X, e_Y, e_Z)
    k = np.array([s, 0.0, c])
    L = THIN.A * (w - n * k) + THIN.C * n * k
    v_z = -h1 * s * Lam  # d/dt H(cos theta)
    loss = 0.5 * v_z**2 + 0.5 * w @ L - L[2] ** 2 / (2 * THIN.C) + h - THIN.height_slope(1.0)[0]
    cc, y, num = landing(m, x)
    assert num["energy_before"] - num["energy_after"] == pytest.approx(loss, rel=1e-9) and loss > 0
    assert num["v_normal"] == pytest.approx(v_z, rel=1e-12) and num["friction_bound"] == pytest.approx(0.5 * abs(v_z))
    assert np.allclose(y[0:2], [U, V], rtol=1e-14, atol=0) and THIN.C * y[2] == pytest.approx(L[2], rel=1e-14)
    seg = traj.segments[-1]  # the run's budget counts the same jump among its events' (with the slip onsets')
    assert float(m.function("energy", seg.mode)(seg.x1, m.p)) - traj.face.energy_start == pytest.approx(loss, rel=1e-9)


def test_the_energy_series_goes_on_over_the_face_and_ends_at_the_budget():
    """The series' rows on the face: the face's friction growing from 0 to its budget line, the landing
    counted at events from the landing on, the balance closing on every row, the last row the budget."""
    m, traj = _eulers_disk()
    df = traj.energy_series()
    budget = traj.energy_budget()
    on = np.asarray(df["t"] > traj.face.t0)
    assert on.sum() == traj.face.n_steps + 1 and np.all(df["face friction"][~on] == 0.0)  # the step ends, the rest
    assert np.all(np.diff(df["face friction"][on]) >= 0) and abs(df["residual"]).max() < 1e-8
    last = df.iloc[-1]
    assert last["face friction"] == budget.dissipated[-1] and last["at_events"] == budget.at_events
    assert last["energy"] == budget.energy_end == 0.0
    mid = traj.energy_series([0.5 * (traj.face.t0 + traj.t)]).iloc[0]
    assert 0 < mid["face friction"] < budget.dissipated[-1] and abs(mid["residual"]) < 1e-8


def test_the_face_phase_is_sampled_with_its_mode_energy_and_pose():
    m, traj = _eulers_disk()
    f = traj.face
    ts = np.linspace(f.t0 - 1e-3, f.t1, 9)
    s = traj.sample(ts)
    on = np.asarray(s["mode"] == "face")
    assert list(on) == list(ts > f.t0)
    E = 0.5 * (s["U"] ** 2 + s["V"] ** 2) + 0.5 * THIN.C * s["Omega"] ** 2
    assert np.allclose(s["energy"][on], E[on], rtol=1e-14, atol=0) and np.all(s["R"][on] == 1.0)
    assert np.all(np.diff(s["energy"][on]) < 0)
    last = traj.sample([f.t0]).iloc[0]  # continuous through the landing: position and the horizontal velocity
    first = traj.sample([f.t0 + 1e-12]).iloc[0]
    assert abs(first["X"] - last["X"]) < 1e-11 and abs(first["Y"] - last["Y"]) < 1e-11
    assert math.hypot(first["U"] - last["U"], first["V"] - last["V"]) < 1e-10


@pytest.mark.parametrize("how", ["face-start", "landing"])
def test_a_run_on_its_face_round_trips_through_its_json_and_rerun(how):
    traj = _on_face(1.0, 3.0) if how == "face-start" else _eulers_disk()[1]
    d = traj.to_dict()
    text = json.dumps(d, allow_nan=False)
    back = json.loads(text)
    assert back["status"] == "rest" and back["mode_end"] == "face" and back["face"]["t_end"] == traj.t
    assert back["energy_budget"]["dissipated"]["face friction"] == traj.energy_budget().dissipated[-1]
    again = pk.rerun(back)
    assert again.t == traj.t and again.face.t_stop_slide == traj.face.t_stop_slide
    assert back["pose_end"] == again.to_dict()["pose_end"] and traj.verify().verdict == "converged"
    ts = [0.5 * (traj.face.t0 + traj.t), traj.t]  # pickled (ensembles' processes): the same face phase
    assert pickle.loads(pickle.dumps(traj)).sample(ts).equals(traj.sample(ts))


def test_a_cone_on_its_base_and_a_coin_slide_and_spin_to_rest_with_their_own_inertia_and_height():
    """A cone on its base (C = 3/10, G 1/4 of its height above the base) and a coin (thickness 0.1):
    the same closed problem with kappa = C / (M r^2) (theory.face_down's stop time with kappa through
    'disk' at C = 1/2 only: here against the ratio's zero for that kappa), the energy ending at M g h0."""
    for body in (pk.bodies.Cone(2.0), pk.Disk(0.1)):
        traj = _on_face(1.0, 3.0, body=body)
        f = traj.face
        assert f.status is pk.Status.REST and abs(f.t_stop_slide - f.t_stop_spin) < 1e-9
        assert abs(f.ratio_end - terminal_ratio(0.0, kappa=body.C).eps) < 1e-3
        budget = traj.energy_budget()
        assert budget.energy_end == pytest.approx(float(body.height_slope(1.0)[0]), rel=1e-15)
        assert budget.residual_max < 1e-8


def test_only_a_body_with_a_face_starts_on_it():
    m = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.3))
    with pytest.raises(ParameterError, match="`mode` 'face' needs a body with a flat face"):
        pk.simulate(m, pk.core.vertical_spin_start(0.3, 5.0), 10.0, mode="face")
    with pytest.raises(ParameterError, match="`v0` must lie in \\[-100000, 100000\\], got 200000.0"):
        pk.core.vertical_spin_start(0.0, 1.0, v0=2e5)


def test_the_other_face_of_a_thin_disk_and_a_start_at_its_face_down_angle_give_the_same_motion():
    """theta0 = pi: the thin disk's upper face (vector chart: the axis ends pointing down); theta0 at
    the face-down angle 1e-3 instead of 0: the same v and w_Z, the same motion."""
    ref = _on_face(1.0, 3.0).face
    m = pk.Model(THIN, pk.Coulomb(MU), "vector")
    flipped = pk.simulate(m, m.chart.from_paper(pk.core.vertical_spin_start(np.pi, 3.0, v0=1.0)), 100.0, mode="face")
    assert flipped.face.contact.theta == np.pi - 1e-3 and flipped.face.t1 == pytest.approx(ref.t1, rel=1e-12)
    assert flipped.x[2] < 0 and flipped.energy_budget().residual_max < 1e-8
    m = pk.Model(THIN, pk.Coulomb(MU))
    tilted = pk.simulate(m, pk.core.vertical_spin_start(1e-3, 3.0, v0=1.0), 100.0, mode="face")
    assert tilted.face.contact.theta == 1e-3 and tilted.face.t1 == ref.t1


def test_a_start_on_the_face_carries_its_pose0_along_the_straight_path():
    """G moves along the start's e_X, turned by psi0, by the distance slid; phi turns with w."""
    traj = _on_face(1.0, 3.0, pose0=[0.5, 0.2, 1.0, 2.0])
    end = traj.pose([traj.t]).iloc[0]
    dist = traj.face.y1[3]
    assert end["X"] == pytest.approx(1.0 + dist * math.cos(0.5), rel=1e-14)
    assert end["Y"] == pytest.approx(2.0 + dist * math.sin(0.5), rel=1e-14)
    assert end["phi"] == pytest.approx(0.2 + traj.face.y1[5], rel=1e-14) and end["psi"] == 0.5
    assert (end["X_P"], end["Y_P"]) == (end["X"], end["Y"]) and "flat" in [a.name for a in traj.approximations]


def test_a_run_on_its_face_stops_at_t_end_or_its_step_budget_with_a_status():
    full = _on_face(1.0, 3.0).face
    short = full.t1 / 2
    m = pk.Model(THIN, pk.Coulomb(MU))
    x0 = pk.core.vertical_spin_start(0.0, 3.0, v0=1.0)
    half = pk.simulate(m, x0, short, mode="face")
    assert half.status is pk.Status.COMPLETED and half.t == short and "still sliding or spinning" in half.reason
    starved = pk.simulate(m, x0, 100.0, mode="face", max_steps=5)
    assert starved.status is pk.Status.FAILED and starved.reason.startswith("step limit (5 steps on the face) reached")
    assert starved.face.n_steps == 5 < full.n_steps and starved.t < full.t1
    budget = half.energy_budget()
    assert budget.residual_max < 1e-8 and 0 < budget.energy_end < budget.energy_start


def test_without_stop_at_rest_a_face_down_still_ends_the_run():
    """stop_at 'none' keeps its meaning: the run stops at the face-down limit, status 'stopped'."""
    law = pk.Coulomb(0.5).with_dissipation(pk.RollingResistance(0.05))
    m = pk.Model(THIN, law)
    y0 = precession_state(THIN, 0.3, omega0=intermediate_omega(THIN, 0.3))
    traj = pk.simulate(m, m.chart.from_paper(y0), 100.0, stop_at="none")
    assert traj.status is pk.Status.STOPPED and traj.events[-1].name == "face down" and traj.face is None
