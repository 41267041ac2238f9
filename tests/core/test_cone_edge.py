"""Exact Coulomb sliding on the edge of the friction cone (the EDGE mode, phasekit.core.cone_edge), on the
inverted tippe top with rolling resistance 0.05 mm alone (studies/spin_down.py), whose rolling needs a
force at the cone's edge once per nutation cycle from 12.1 s to 37 s."""

import importlib

import phasekit as pk
import phasekit.studies as ps
from phasekit.core import system, zero_slip
from phasekit.core.cone_edge import EDGE_OUT
from phasekit.core.hybrid import Mode

import numpy as np
import pytest

RTOL = 1e-10
SCALE = pk.Scale("15 mm")
SECOND = float(SCALE.unit("time").to("s").magnitude)  # the time unit sqrt(b/g), 39.1 ms


def _case(chart="vector"):
    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    law = ps.spin_down_law(SCALE, "coulomb", 0.3, delta="0.05 mm")
    y0 = pk.core.vertical_spin_start(0.1, SCALE.dimensionless("30 rev/s"))
    return pk.Model(top, law, chart), pk.core.to_chart(chart, np.asarray(y0, float))


def _run(model, x0, t_end_s, *, t0=0.0, max_steps=30_000, **kw):
    return pk.simulate(model, x0, t_end_s / SECOND, t0=t0, stop_at="rest", rtol=RTOL, max_steps=max_steps,
                       track_minima=False, progress=False, **kw)


@pytest.fixture(scope="module")
def edge_run():
    model, x0 = _case()
    return model, _run(model, x0, 60.0, t_eval=np.arange(0.0, 60.0 / SECOND, 0.05))


def _without_edge(monkeypatch):
    """phasekit's exact run before EDGE: slip onsets nudged into SLIDING (an independent formulation)."""
    monkeypatch.setattr(system, "_edge_events", lambda hold: [])
    monkeypatch.setattr(zero_slip.EdgeOnset, "__call__", lambda self, *a: self.fallback(*a))
    importlib.import_module("phasekit.core.simulate")._declare_cached.cache_clear()


def _switches(traj):
    return [e for e in traj.events if e.name in ("stick", "slip")]


@pytest.mark.timeout(900)
def test_the_inverted_tippe_top_runs_to_its_end_within_its_step_budget(edge_run):
    """It failed at its 30 000-step budget at 12.5 s; on the edge it runs its 60 s (measured: 23 376 steps)."""
    model, traj = edge_run
    assert traj.status is pk.Status.COMPLETED, traj.reason  # no rest: nothing stops the spin about the vertical
    assert traj.t == pytest.approx(60.0 / SECOND, rel=1e-12)
    assert traj.n_steps <= 30_000
    assert sum(s.mode is Mode.EDGE for s in traj.segments) > 100


@pytest.mark.timeout(900)
def test_at_most_two_stick_slip_switches_per_nutation_cycle(edge_run):
    """Stick and slip alternate, none or one of each per nutation cycle (from one maximum of the
    nutation rate Lambda to the next) while the force needed hovers at mu R (measured: 596 switches,
    2 in each of 298 cycles from 12.1 s to 37.3 s, none in the other 391)."""
    model, traj = edge_run
    sw = _switches(traj)[1:]  # the first: the stick that ends the inversion (0.94 s)
    names = [e.name for e in sw]
    assert names[0] == "slip" and all(a != b for a, b in zip(names, names[1:]))  # they alternate
    rate = model.evaluate("Lambda", traj.ys)
    peaks = traj.ts[1:-1][(rate[1:-1] > rate[:-2]) & (rate[1:-1] >= rate[2:])]
    per_cycle = np.histogram([e.t for e in sw], peaks)[0]
    assert per_cycle.sum() == len(sw) and len(sw) > 200
    assert per_cycle.max() <= 2


@pytest.mark.timeout(900)
def test_the_edge_agrees_with_the_exact_stick_slip_run(monkeypatch):
    """12 - 13 s (22 switches) against phasekit's exact run without EDGE (slip onsets nudged by 1e-6,
    ~50 000 steps): the same switches, their times within 1e-3 (measured 5.3e-4; the nudge alone moves
    that reference by ~1e-4 over 20 s), the state at 13 s within 3e-5 (measured 7.6e-6), in 1/40 the steps."""
    model, x0 = _case()
    start = _run(model, x0, 12.0)
    assert start.mode == "rolling" and not _switches(start)[1:]
    edge = _run(model, start.x, 13.0, t0=start.t)
    _without_edge(monkeypatch)
    ref = _run(model, start.x, 13.0, t0=start.t, max_steps=500_000)
    monkeypatch.undo()
    importlib.import_module("phasekit.core.simulate")._declare_cached.cache_clear()
    assert not any(s.mode is Mode.EDGE for s in ref.segments) and any(s.mode is Mode.EDGE for s in edge.segments)
    assert edge.n_steps * 10 < ref.n_steps
    a, b = _switches(edge), _switches(ref)
    assert [e.name for e in a] == [e.name for e in b] and len(a) >= 20
    assert np.max(np.abs([e.t - f.t for e, f in zip(a, b)])) < 1e-3
    assert np.max(np.abs(edge.x - ref.x)) < 3e-5


@pytest.mark.timeout(900)
def test_the_edge_keeps_the_energy_balance(edge_run):
    """The energy lost equals the work of sliding friction (on the edge: F.u with |F| ~ mu R) and of
    rolling resistance, plus the jumps at events (the slip set to 0 at a stick, ~1e-12)."""
    model, traj = edge_run
    b = traj.energy_budget()
    assert b.lost > 0.01 * b.energy_start
    assert abs(b.residual) <= b.residual_max <= 1e-8 * b.lost
    assert all(w > 0 for w in b.dissipated)
    assert abs(b.at_events) < 1e-9 * b.lost


@pytest.mark.timeout(900)
def test_a_slip_that_grows_leaves_the_edge_for_sliding(edge_run):
    """Where the sliding field points out of the cone (lambda = e*.a(e*) > 0) the slip grows along e*, and
    at |u| = EDGE_OUT the contact slides, on SLIDING's field (OFF_EDGE, measured: 121 times)."""
    model, traj = edge_run
    out = traj.events_named("edge out")
    assert len(out) > 10 and len(traj.events_named("edge in")) <= len(out)
    off = [s for s in traj.segments if s.mode is Mode.OFF_EDGE]
    assert off and np.array_equal(model.rhs(off[0].x0, Mode.OFF_EDGE), model.rhs(off[0].x0, Mode.SLIDING))
    for e in out:
        assert (e.mode_before, e.mode_after) == ("edge", "off_edge")
        assert model.evaluate("slip_speed", e.x) == pytest.approx(EDGE_OUT, rel=1e-6)
        R, lam, _ = np.asarray(model.function("edge_check")(e.x, model.p)).ravel()
        assert R > 0 and lam > 0
        assert float(model.function("margin_rolling")(e.x, model.p)) < 0  # rolling would need more than mu R


@pytest.mark.timeout(900)
def test_the_edge_is_not_entered_strictly_inside_the_cone(monkeypatch):
    """The inversion ends with a stick at 0.94 s where rolling needs |F| = 0.74 mu R: SLIDING to ROLLING
    directly, and the run to 5 s is bit for bit the run without EDGE."""
    model, x0 = _case()
    edge = _run(model, x0, 5.0)
    _without_edge(monkeypatch)
    ref = _run(model, x0, 5.0)
    monkeypatch.undo()
    importlib.import_module("phasekit.core.simulate")._declare_cached.cache_clear()
    [stick] = edge.events_named("stick")
    assert (stick.mode_before, stick.mode_after) == ("sliding", "rolling")
    F = np.asarray(model.function("Fc_rolling")(stick.x, model.p)).ravel()
    assert 0.5 < np.hypot(F[0], F[1]) / (0.3 * F[2]) < 0.9
    assert [s.mode for s in edge.segments] == [Mode.SLIDING, Mode.ROLLING] == [s.mode for s in ref.segments]
    assert edge.n_steps == ref.n_steps and np.array_equal(edge.x, ref.x)


@pytest.mark.timeout(900)
def test_on_the_edge_the_slaved_direction_is_the_rolling_force(edge_run):
    """At each slip onset (|F_roll| = mu R, u = 0) two formulations agree: EDGE's friction, from the secular
    equation and its 2x2 system, equals the rolling mode's, from its 3x3 no-slip system, and lies on the cone."""
    model, traj = edge_run
    onsets = [e for e in traj.events_named("slip") if e.mode_after == "edge"]
    assert len(onsets) > 100
    for e in onsets[::25]:
        F_edge = np.asarray(model.function("Fc_edge")(e.x, model.p)).ravel()
        F_roll = np.asarray(model.function("Fc_rolling")(e.x, model.p)).ravel()
        assert np.allclose(F_edge, F_roll, rtol=0, atol=1e-9)
        assert np.hypot(F_edge[0], F_edge[1]) == pytest.approx(0.3 * F_edge[2], rel=1e-9)


@pytest.mark.slow
@pytest.mark.timeout(1200)
def test_the_two_charts_agree_on_the_edge():
    """To 20 s (~200 switches) in the euler chart and the vector chart: the same switches within 1e-3
    (measured 4e-4), the same theta and energy at the end."""
    runs = [(m, _run(m, x0, 20.0)) for m, x0 in (_case("vector"), _case("euler"))]
    (mv, v), (me, e) = runs
    a, b = _switches(v), _switches(e)
    assert [x.name for x in a] == [x.name for x in b] and len(a) > 150
    assert np.max(np.abs([x.t - y.t for x, y in zip(a, b)])) < 1e-3
    for name in ("theta", "energy"):
        assert mv.evaluate(name, v.x) == pytest.approx(me.evaluate(name, e.x), abs=1e-5)
