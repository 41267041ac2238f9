"""A compact-mode integrator (an egg's) is compiled at LLVM level COMPACT_OPT_LEVEL, which
compiles in about half the time of heyoka's default level 3: its trajectories must be those of
level 3, bit for bit (the same steps, events and states)."""

import phasekit as pk
from phasekit.core.engines import cache, taylor_build

import numpy as np
import pytest


def _egg_run():
    """The 60 x 45 mm egg spun near flat, sliding until just before it sticks (at t = 0.0423):
    one compact integrator, compiled at each level (the rolling one is compiled alike)."""
    egg = pk.bodies.Egg(1.33333, w=0.0)
    x0 = pk.gyroscopic_start(egg, np.radians(89.4), omega0=7.52)
    return pk.simulate(pk.Model(egg, pk.Coulomb(0.2)), x0, 0.042, stop_at="none")


@pytest.mark.timeout(1200)
def test_the_egg_runs_the_same_at_the_compact_level_and_at_heyoka_s_default(tmp_path, monkeypatch):
    assert taylor_build.COMPACT_OPT_LEVEL != 3
    runs = {}
    for level in (taylor_build.COMPACT_OPT_LEVEL, 3):
        monkeypatch.setenv("PHASEKIT_CACHE", str(tmp_path / f"level{level}"))  # compiled afresh at that level
        monkeypatch.setattr(taylor_build, "COMPACT_OPT_LEVEL", level)
        cache.forget()
        runs[level] = _egg_run()
    cache.forget()
    fast, default = runs.values()
    assert [(e.name, e.t) for e in fast.events] == [(e.name, e.t) for e in default.events]
    assert fast.n_steps == default.n_steps > 5 and fast.mode == default.mode == "sliding"
    np.testing.assert_array_equal(fast.x, default.x)
    ts = np.linspace(0.0, fast.t, 101)
    np.testing.assert_array_equal(fast.sample(ts)[["theta", "Omega", "n"]].to_numpy(),
                                  default.sample(ts)[["theta", "Omega", "n"]].to_numpy())
