"""Events and minima: guards vanish at located events, located minima of R are stationary and are
minima, SolverOptions.track_minima is honoured, non-terminal events keep firing, and the cached
declaration of the hybrid system never hands one run's events to another."""

from __future__ import annotations

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def standard():
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)


@pytest.fixture(scope="module")
def model(prolate):
    return pk.Model(prolate, pk.Coulomb(0.1))


def test_guards_vanish_at_located_events_and_minima_are_minima(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    r = pk.simulate(m, standard_start, 200.0, rtol=1e-11)
    [lift] = r.events_named("lift-off")
    assert abs(m.normal_reaction(lift.x)) < 1e-10
    assert m.evaluate("Rdot", lift.x) < 0  # R crosses zero downwards
    # located minima are stationary points of R: dR/dt ~ 0 there, relative to its typical size
    seg = r.segments[0]
    X = np.array([x for _, x in seg.monitored])
    rdot = m.evaluate("Rdot", X)
    scale = np.max(np.abs(m.evaluate("Rdot", r.states(np.linspace(0, r.t, 400)))))
    assert len(X) > 50 and np.max(np.abs(rdot)) < 1e-8 * scale
    # ... and minima: R just before and after is larger
    for t, x in seg.monitored[5:10]:
        Rm = m.normal_reaction(x)
        around = m.normal_reaction(r.states([t - 1e-3, t + 1e-3]))
        assert np.all(around > Rm)


def test_track_minima_false_locates_no_minima_and_true_locates_stationary_ones(standard):
    model, y0 = standard
    off = pk.simulate(model, y0, 200.0, track_minima=False, dense=False)
    on = pk.simulate(model, y0, 200.0, dense=False)
    assert off.minima.shape == (0, 2)
    assert len(on.minima) > 20
    # the minima of a growing nutation lie below the weight, and fall toward the jump
    assert np.all(on.minima[:, 1] < 1.0)
    assert on.minima[-1, 1] < on.minima[0, 1]
    # both runs end at the same lift-off to well within the tolerance (the monitor changes
    # the steps, not the solution)
    assert abs(on.t_jump - off.t_jump) < 1e-6


def test_rdot_vanishes_at_the_located_minima(standard):
    model, y0 = standard
    on = pk.simulate(model, y0, 200.0)
    X = on.states(on.minima[:, 0])
    rdot = model.evaluate("Rdot", X)
    assert np.max(np.abs(rdot)) < 1e-6


def test_runs_with_different_user_events_do_not_share_a_declaration(standard):
    model, y0 = standard
    a = pk.simulate(model, y0, 200.0, events=[pk.Event("theta", 1.0, direction=-1)], dense=False)
    b = pk.simulate(model, y0, 200.0, events=[pk.Event("theta", 0.9, direction=-1)], dense=False)
    c = pk.simulate(model, y0, 200.0, events=[pk.Event("theta", 1.0, direction=-1)], dense=False)
    assert a.status is b.status is pk.Status.STOPPED
    assert a.t < b.t and c.t == a.t
    assert a.x[4] == pytest.approx(1.0, abs=1e-9) and b.x[4] == pytest.approx(0.9, abs=1e-9)


def test_non_terminal_events_fire_after_a_tangential_start(model, standard_start):
    """Regression: heyoka's automatic cooldown after an event at a start with dLambda/dt ~ 1e-16
    was 8.6e8, which silenced the event for the rest of the run."""
    traj = pk.simulate(model, standard_start, 40.0, events=[pk.Event("Lambda", 0.0, direction=+1, terminal=False)])
    assert len(traj.events_named("Lambda=0")) >= 8
