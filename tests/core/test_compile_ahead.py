"""A run compiles its other contact mode ahead, in the background: after a run that ends sliding
(it jumps before any stick), the rolling mode's integrator of the same model is already built,
and a second run that reaches rolling compiles nothing (counted by the builds the cache makes)."""

from __future__ import annotations

import phasekit as pk
from phasekit.core.engines import cache

import numpy as np


def test_a_run_that_ends_sliding_leaves_its_rolling_mode_compiled(tmp_path, monkeypatch):
    monkeypatch.setenv("PHASEKIT_COMPILE_AHEAD", "on")
    monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path))
    cache.forget()
    built = []
    monkeypatch.setattr(cache, "_announced", lambda build, disk, label=None: (built.append(label), build())[1])
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    r = pk.simulate(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0, rtol=1e-9)
    for thread in cache._THREADS:
        thread.join()
    assert r.jumped and {s.mode.value for s in r.segments} == {"sliding"}
    assert sorted(built) == sorted(["the Taylor integrator of the sliding mode",
                                    "the Taylor integrator of the rolling mode, in the background,"])
    stuck = pk.simulate(pk.Model(body, pk.Coulomb(0.5)), pk.gyroscopic_start(body, 1.0, omega0=3.0), 5.0, rtol=1e-9)
    assert "rolling" in {s.mode.value for s in stuck.segments} and len(built) == 2
