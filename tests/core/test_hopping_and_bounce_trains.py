"""Through hopping: a hopping run (self-induced jumps and bounce trains in turn) is physics, not
a failure: it runs to its end time within a switch budget that scales with the span, reports its
hop statistics, and a bounce train whose rebounds decay geometrically is resolved (its
accumulation point reached) with a bounded effect on the state after it. A whole rise with
repeated bouncing records every event.
"""

import json

import phasekit as pk
from phasekit.core.resets import BOUNCE_STOP, flight_state

import numpy as np
import pytest

A, MU, E = 1.5, 0.1, 0.5


@pytest.fixture(scope="module")
def body():
    return pk.Spheroid(A)


@pytest.fixture(scope="module")
def model(body):
    return pk.Model(body, pk.Coulomb(MU))


def _start(body, omega0):
    return pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=omega0)


@pytest.fixture(scope="module")
def hopping(model, body):
    """A hopping start: Omega0 = 30, to t = 400 through every flight."""
    return pk.simulate(model, _start(body, 30.0), 400.0, stop_at="none", restitution=E, dense=False)


def test_a_hopping_run_reaches_its_end_time_with_hop_statistics(hopping):
    assert hopping.status is pk.Status.COMPLETED and hopping.t == 400.0
    hops = hopping.hops
    # it used to fail at t = 180.4 after 10 000 switches; it makes more than that by t = 400
    assert len(hopping.events) > 10_000
    assert hops["n_liftoffs"] == len(hopping.events_named("lift-off")) > 100
    assert hops["n_flights"] == len(hopping.flights) == hops["n_impacts"] > hops["n_liftoffs"]
    durations = [f.t_touchdown - f.t_liftoff for f in hopping.flights]
    assert hops["t_flight"] == pytest.approx(sum(durations), rel=1e-12)
    assert hops["longest_flight"] == max(durations)
    assert hops["gap_max"] == max(f.gap_max for f in hopping.flights if f.gap_max is not None) > 0
    assert hops["flight_fraction"] == pytest.approx(hops["t_flight"] / 400.0) and 0 < hops["flight_fraction"] < 1


def test_hop_statistics_reach_the_json_and_the_ensemble_row(hopping, model, body):
    d = json.loads(json.dumps(hopping.to_dict(events=False)))
    assert d["hops"] == hopping.hops
    df = pk.ensemble(model, [_start(body, 30.0), _start(body, 8.0)], 400.0, stop_at="none", restitution=E,
                     processes=1, progress=False)
    row = df.iloc[0]
    for key in ("n_liftoffs", "n_flights", "t_flight", "longest_flight", "gap_max"):
        assert row[key] == hopping.hops[key]
    assert df.iloc[1]["n_flights"] == 0 and df.iloc[1]["t_flight"] == 0.0  # below the threshold: never leaves the table


def test_the_switch_budget_scales_with_the_span_and_an_explicit_one_is_a_budget(model, body):
    opts = pk.SolverOptions()
    # 100 switches per unit of the span, at least 10 000 (SolverOptions.max_switches, documented)
    assert opts.switch_limit(400.0) == 100 * 400 and opts.switch_limit(5.0) == 10_000
    r = pk.simulate(model, _start(body, 30.0), 400.0, stop_at="none", restitution=E, dense=False, max_switches=2000)
    assert r.status is pk.Status.FAILED and r.reason.startswith("more than 2000 mode switches by t = ")
    # stopped at the first transition that reached the budget (a touchdown records two events)
    last = [e for e in r.events if e.t == r.events[-1].t]
    assert len(r.events) - len(last) < 2000 <= len(r.events)


def test_a_hopping_ensemble_has_no_failed_run(model, body):
    """Four of 32 sliding-branch starts (Omega0 from 10 to 30), the fastest (all 32: slow test)."""
    starts = [_start(body, w) for w in np.geomspace(10, 30, 32)[-4:]]
    df = pk.ensemble(model, starts, 400.0, stop_at="none", restitution=E, processes=2, progress=False)
    assert list(df["status"]) == ["completed"] * 4 and list(df["t_end"]) == [400.0] * 4
    assert (df["n_liftoffs"] > 0).all()


@pytest.mark.slow
def test_a_hopping_ensemble_of_32_starts_has_no_failed_run(model, body):
    starts = [_start(body, w) for w in np.geomspace(10, 30, 32)]
    df = pk.ensemble(model, starts, 400.0, stop_at="none", restitution=E, progress=False)
    assert len(df) == 32 and "failed" not in set(df["status"])
    last = df.iloc[-1]
    assert last["Omega"] == 30.0 and last["t_end"] == 400.0 and last["n_flights"] > 1000


def _bounce_train(e, v0, **options):
    """A train of rebounds from a flight that leaves the table at v0 (vector chart, dense)."""
    body = pk.Spheroid(A)
    model = pk.Model(body, pk.Coulomb(MU), chart="vector")
    xf = flight_state(model, pk.core.to_chart("vector", pk.gyroscopic_start(body, np.pi / 2 - 0.3, omega0=11.0)))
    xf[9] = v0
    r = pk.simulate(model, xf, 3.0, stop_at="none", restitution=e, mode="flight", **options)
    back = [ev for ev in r.events if ev.name == "impact" and ev.mode_after != "flight"]
    return r, back[0]


@pytest.mark.parametrize("e, v0", [(0.98, 0.01), (0.99, 0.01)])
def test_a_resolved_bounce_train_changes_the_state_after_it_by_at_most_its_rebound_speed(e, v0):
    """Against the same train integrated rebound by rebound to a cut-off ten times smaller, the
    state after it differs by less than the stated tolerance: the largest rebound speed the
    rule drops, TAIL_SPEED x BOUNCE_STOP = 1e-3 (in units of sqrt(g b) and rates)."""
    fast, end_fast = _bounce_train(e, v0)
    full, end_full = _bounce_train(e, v0, bounce_stop=BOUNCE_STOP / 10, bounce_tail=None)
    assert "bounce train resolved" in end_fast.detail and fast.hops["n_trains_resolved"] == 1
    assert full.hops["n_trains_resolved"] == 0 and full.hops["n_impacts"] > 2 * fast.hops["n_impacts"]
    assert end_fast.t < end_full.t < end_fast.t + 0.2  # the tail it summed: a fraction of a fast period
    t = end_full.t + 0.5
    cols = list(pk.core.PAPER_NAMES)
    diff = np.abs(fast.sample([t])[cols].to_numpy() - full.sample([t])[cols].to_numpy()).max()
    assert diff < 1e-3  # the stated tolerance (TAIL_SPEED x BOUNCE_STOP as documented)


def test_a_train_that_does_not_decay_geometrically_is_integrated(hopping):
    """e = 0.5 trains reach the cut-off within a few tens of rebounds: none is resolved, so the
    published bouncing runs (e <= 0.9) keep the numbers of the cut-off alone."""
    assert hopping.hops["n_trains_resolved"] == 0


def test_whole_rise_with_repeated_bouncing_records_every_event():
    body = pk.Spheroid(1.5)
    m = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0)
    rise = pk.Event("theta", 0.05, direction=-1, name="rise-complete")
    r = pk.simulate(m, y0, 400.0, stop_at="none", restitution=0.5, events=[rise], max_switches=100_000)
    assert r.status is pk.Status.STOPPED and r.events[-1].name == "rise-complete"
    kinds = [e.kind for e in r.events]
    assert kinds.count("touchdown") == kinds.count("impact") > kinds.count("lift-off") > 1
    dE = [float(e.detail.split("dE=")[1].split(",")[0]) for e in r.events if e.kind == "impact"]
    assert max(dE) < 0
    assert all(b.t >= a.t for a, b in zip(r.events, r.events[1:]))
