"""Integrators: the on-disk cache round trip, guards ~0 at located events, located minima."""

import phasekit as pk
from phasekit.core.engines import Budget, TaylorEngine, cache
from phasekit.core.system import declare, watched

import numpy as np


def test_taylor_cache_reload_keeps_the_monitor(tmp_path, monkeypatch, prolate, standard_start):
    """A cached integrator loaded from disk must still record the minima of R (regression:
    the recorder handle used to be the pickled copy, not the integrator's own)."""
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    model = pk.Model(prolate, pk.Coulomb(0.1))
    system = declare(model)
    flow = system.flow(pk.core.Mode.SLIDING)
    events = watched(system, pk.core.Mode.SLIDING, TaylorEngine)
    cflow = model.compile_flow(flow, events)
    counts = []
    for _ in range(2):
        cache.forget()  # force a (re)load from the disk cache
        prop = TaylorEngine(3e-9).propagate(cflow, standard_start, 0.0, 30.0, model.p, [e.level for e in events],
                                            budget=Budget(10**6, float("inf")))
        counts.append(len(prop.monitored))
    assert list(tmp_path.glob("taylor-*.pkl"))
    assert counts[0] == counts[1] > 20


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


def test_step_and_wall_budgets_end_the_run_with_a_reason(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    r = pk.simulate(m, standard_start, 200.0, max_steps=50)
    assert r.status is pk.Status.FAILED and "step limit" in r.reason and r.t < 200.0
    assert np.all(np.isfinite(r.x))
    r = pk.simulate(m, standard_start, 1e4, max_wall=1e-3, stop_at="none")
    assert r.status is pk.Status.FAILED and "wall-time limit" in r.reason
