"""Backends: the on-disk cache round trip, event guards ~0 at events, bounded work."""

import numpy as np

import phasekit as pk
from phasekit.backends import TaylorBackend
from phasekit.modes import Mode, mode_events


def test_taylor_cache_reload_keeps_minima(tmp_path, monkeypatch, prolate, standard_start):
    """A cached integrator loaded from disk must still record the minima of R (regression:
    the recorder handle used to be the pickled copy, not the integrator's own)."""
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    model = pk.Model(prolate, pk.Coulomb(0.1))
    evs = mode_events(model, Mode.SLIDING)
    counts = []
    for _ in range(2):
        TaylorBackend._memory.clear()  # force a (re)load from the disk cache
        b = TaylorBackend(model, 3e-9)
        prop = b.propagate(Mode.SLIDING, standard_start, 0.0, 30.0, evs, model.p, max_steps=10**6, minima=("Rdot_sliding", 1))
        counts.append(len(prop.minima))
    assert list(tmp_path.glob("taylor-*.pkl"))
    assert counts[0] == counts[1] > 20


def test_guards_vanish_at_located_events(prolate, standard_start):
    m = pk.Model(prolate, pk.Coulomb(0.1))
    r = pk.simulate(m, standard_start, 200.0, rtol=1e-11)
    [lift] = r.events_named("lift-off")
    assert abs(m.normal_reaction(lift.x)) < 1e-10
    # located minima are minima: dR/dt ~ 0 there
    idx = np.argsort(r.minima[:, 1])[:3]
    assert np.all(r.minima[idx, 1] < 0.5)
