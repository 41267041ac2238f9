"""The contact passing between the pieces of a compound body: the tippe top started as a user does
(offset 0.3, A 0.38, C 0.4, Coulomb mu 0.3, theta0 0.1, spun at 15 about the vertical) inverts and
ends spinning on its stem, with the transfer in its events; the energy balance holds through it;
the transfer impact conserves the angular momentum about the new contact point, and where friction
stops the slip it leaves the body turning about that point (closed form); the Euler and vector
charts agree; a segment never crosses the switch; a body left on both pieces at once is reported."""

import math
from types import SimpleNamespace

import phasekit as pk
from phasekit import Status
from phasekit.core import Event, Mode
from phasekit.core.resets import SWITCH_EARLY, Transfer, flight_state, rigid_velocities

import numpy as np
import pytest

TOP = pk.bodies.TippeTop(0.3, A=0.38, C=0.4)  # the default stem: 0.375 out of the ball, end radius 0.2


def _run(chart, body=TOP, t_end=70.0):
    model = pk.Model(body, pk.Coulomb(0.3), chart)
    x0 = pk.core.starts.to_chart(chart, pk.core.vertical_spin_start(0.1, 15.0))
    return pk.simulate(model, x0, t_end, stop_at="none")


@pytest.fixture(scope="module")
def runs():
    return {chart: _run(chart) for chart in ("euler", "vector")}


@pytest.mark.timeout(600)
def test_it_inverts_and_ends_spinning_on_its_stem(runs):
    for traj in runs.values():
        assert traj.status == "completed" and traj.t == 70.0 and traj.mode in ("rolling", "sliding")
        tail = traj.sample(np.linspace(60.0, 70.0, 101))
        theta = tail["theta"].to_numpy()
        # near pi, nutating a little: standing on the stem's end, the contact on the stem (H = h_stem)
        assert np.all(theta > 2.9) and all(TOP.piece(th) == "stem" for th in theta)
        ball, stem = TOP.piece_heights(theta)
        assert np.max(np.abs(tail["h"].to_numpy() - stem)) < 1e-12 and np.all(stem > ball)
        names = [e.name for e in traj.events]
        last = max(i for i, n in enumerate(names) if n in ("stem touches", "ball touches"))
        assert names[last] == "stem touches" and traj.events[last].t < 60.0
        # still spinning, the other way about the body's axis (the stem now points down), L_Z > 0 as at the start
        assert np.all(tail["n"].to_numpy() < -5.0) and np.all(tail["L_Z"].to_numpy() > 2.0)


@pytest.mark.timeout(600)
def test_energy_balances_through_the_transfer(runs):
    for traj in runs.values():
        budget = traj.energy_budget()
        assert abs(budget.residual) <= 1e-8 * budget.energy_start
        assert budget.at_events > 0.0  # the impacts (touchdowns and the transfer) lost energy
        transfer = next(i for i, e in enumerate(traj.events) if e.name == "stem touches")
        detail = traj.events[transfer + 1].detail  # the transfer's impact, with its loss
        assert traj.events[transfer + 1].name == "impact" and float(detail.split("dE=")[1].split(",")[0]) < 0.0
        # the segment ending at the transfer ended on the ball's side: no step crossed the switch
        seg = next(s for s in traj.segments if s.end == "stem touches")
        theta = traj.model.chart.theta(seg.x1)
        assert TOP.theta_switch - 2 * SWITCH_EARLY < theta < TOP.theta_switch


@pytest.mark.timeout(600)
def test_the_euler_and_vector_charts_agree(runs):
    e, v = runs["euler"], runs["vector"]
    t_transfer = next(ev.t for ev in e.events if ev.name == "stem touches")
    assert t_transfer == pytest.approx(next(ev.t for ev in v.events if ev.name == "stem touches"), abs=1e-7)
    ts = np.linspace(0.0, t_transfer - 1e-3, 200)
    cols = ["theta", "Omega", "n", "energy", "h"]
    a, b = e.sample(ts)[cols].to_numpy(), v.sample(ts)[cols].to_numpy()
    assert np.max(np.abs(a - b)) < 1e-6
    assert [ev.name for ev in e.events] == [ev.name for ev in v.events]


def _closed_form_stick(body, k, w, v, k_new):
    """The post-impact w when the impact at the new contact point P stops P (e = 0, friction enough):
    L_P = I_G w + r_GP... conserved, with v = -w x r_P, so w = I_P^-1 L_P (I_P the inertia about P)."""
    from phasekit.core.impact import contact_point_of

    kk = k_new / np.linalg.norm(k_new)
    IG = body.A * np.eye(3) + (body.C - body.A) * np.outer(kk, kk)
    r = contact_point_of(body, k_new)
    L = IG @ w - np.cross(r, v)  # about P: the momentum's moment r_PG x v = -r x v
    IP = IG + (r @ r) * np.eye(3) - np.outer(r, r)
    return np.linalg.solve(IP, L), L, IG, r


@pytest.mark.timeout(600)
def test_the_transfer_impact_conserves_angular_momentum_about_the_new_contact_point(runs):
    traj = runs["vector"]
    seg = next(s for s in traj.segments if s.end == "stem touches")
    from phasekit.core.impact import contact_point_of

    stem_side = seg.x1[0:3] / np.linalg.norm(seg.x1[0:3])
    s = math.hypot(*stem_side[:2])
    stem_side = np.array([stem_side[0] / s * math.sin(TOP.theta_switch), stem_side[1] / s * math.sin(TOP.theta_switch),
                          math.cos(TOP.theta_switch)])
    rolling_in = seg.x1.copy()  # the same state with the stem's end not slipping as it comes down
    rolling_in[6:8] = -np.cross(seg.x1[3:6], contact_point_of(TOP, stem_side))[:2]
    for mu, x in ((0.3, seg.x1), (1e3, rolling_in)):  # the run's impact (sliding), and one friction stops
        model = pk.Model(TOP, pk.Coulomb(mu), "vector")
        tr = TOP.transfers[0]
        event = Event("theta", tr.theta, direction=1, name=tr.name)
        out = Transfer(tr)(model, event, Mode.SLIDING, seg.t1, x)
        assert out.stop is None and out.records[0].name == "stem touches"
        assert out.records[1].detail.startswith("1 impact(s)")  # the ball leaves: one impact, at the stem
        k, w, v = rigid_velocities(model, flight_state(model, x))
        k1, w1, v1 = rigid_velocities(model, flight_state(model, out.x) if out.mode is not Mode.FLIGHT else out.x)
        w_stick, L, IG, r = _closed_form_stick(TOP, k, w, v, k1)
        L_after = IG @ w1 - np.cross(r, v1)
        assert np.max(np.abs(L_after - L)) < 1e-9 * np.linalg.norm(L)
        assert k1[2] < math.cos(TOP.theta_switch)  # past the switch: on the stem
        if x is rolling_in:
            assert np.max(np.abs(w1 - w_stick)) < 1e-9 * np.linalg.norm(w_stick)
            assert np.max(np.abs(v1 + np.cross(w1, r))) < 1e-9 * np.linalg.norm(w_stick)  # P at rest


def test_a_body_on_both_pieces_at_once_is_reported_not_integrated(runs):
    model = pk.Model(TOP, pk.Coulomb(0.3), "vector")
    tr = TOP.transfers[0]
    event = Event("theta", tr.theta, direction=1, name=tr.name)
    th = tr.theta - SWITCH_EARLY
    at_rest = np.array([math.sin(th), 0.0, math.cos(th), 0.0, 0.0, 0.0, 0.0, 0.0])  # set down on both
    out = Transfer(tr)(model, event, Mode.ROLLING, 1.0, at_rest)
    assert out.stop is Status.STOPPED and out.mode is None  # the model's limit, as face down
    assert out.reason == "the body rests on two pieces at once (the ball and the stem): not integrated (t = 1)"
    # the contact passing to and fro ever faster (an accumulation, as of a bounce train): the same
    seg = next(s for s in runs["vector"].segments if s.end == "stem touches")
    t = seg.t1
    passes = [SimpleNamespace(name=("ball touches", "stem touches")[i % 2], t=t - 1e-4 * (6 - i)) for i in range(6)]
    out = Transfer(tr)(model, event, Mode.SLIDING, t, seg.x1, log=passes)
    assert out.stop is Status.STOPPED and "rests on two pieces at once" in out.reason
    slow = [SimpleNamespace(name=p.name, t=p.t - 1.0) for p in passes]  # passes long ago: a transfer as any
    assert Transfer(tr)(model, event, Mode.SLIDING, t, seg.x1, log=slow).stop is None
