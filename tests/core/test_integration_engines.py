"""Integration engines: one registry (an unknown name is an error naming the choices, a new engine is
one registration), and the Taylor integrators' on-disk cache."""

from __future__ import annotations

import phasekit as pk
from phasekit.core import engines
from phasekit.core.engines import Budget, cache
from phasekit.core.engines.taylor import TaylorEngine
from phasekit.core.system import declare, watched

import numpy as np
import pytest


def test_an_unknown_engine_is_an_error_and_a_registered_one_needs_nothing_else():
    with pytest.raises(pk.ParameterError) as info:
        engines.engine_for("rk4", 1e-9)
    assert info.value.param == "backend" and "taylor" in str(info.value)
    with pytest.raises(pk.ParameterError):
        pk.SolverOptions(backend="rk4")
    calls = []

    class Counting(engines.cvodes.CvodesEngine):
        """CVODES, counting its calls: a new engine is one registration."""

        def propagate(self, *args, **kwargs):
            calls.append(1)
            return super().propagate(*args, **kwargs)

    engines.register_engine("cvodes-counting", lambda rtol, atol=None: Counting(rtol, atol))
    try:
        body = pk.Spheroid(1.5)
        x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
        ref = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), x0, 200.0, backend="cvodes")
        got = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), x0, 200.0, backend="cvodes-counting")
        assert calls and got.t_jump == ref.t_jump  # pointwise (its stick guard) because CVODES is
    finally:
        del engines.registry.ENGINES["cvodes-counting"]
    with pytest.raises(pk.ParameterError):
        engines.register_engine("taylor", engines.taylor.TaylorEngine)


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
