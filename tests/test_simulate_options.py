"""SolverOptions.track_minima is honoured, and the cached declaration of the hybrid system
never hands one run's events to another."""

from __future__ import annotations

import phasekit as pk

import numpy as np
import pytest


@pytest.fixture(scope="module")
def standard():
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)


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


def test_repeated_keywords_give_the_same_validated_options_and_bad_ones_still_fail(standard):
    model, y0 = standard
    assert pk.simulate(model, y0, 1.0, rtol=1e-8).options.rtol == 1e-8
    assert pk.simulate(model, y0, 1.0, rtol=1e-10).options.rtol == 1e-10
    with pytest.raises(pk.ParameterError, match="rtol"):
        pk.simulate(model, y0, 1.0, rtol=0.0)
    with pytest.raises(pk.ParameterError, match="rtol"):
        pk.simulate(model, y0, 1.0, rtol=[1e-9])
