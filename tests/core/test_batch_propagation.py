"""Batch propagation (many starts in the lanes of one Taylor integrator) against the scalar path:
the same events, segments, step counts and end times; starts the batch cannot take are handed
back to ``simulate``."""

from __future__ import annotations

import dataclasses
from dataclasses import replace

import phasekit as pk
from phasekit.core import engines, simulate_batch
from phasekit.core.batch import BatchStats
from phasekit.core.system import declare, watched
from phasekit.thresholds import (
    Definition,
)

import numpy as np
import pytest


def test_an_egg_runs_on_the_batch_engine_compiled_as_the_scalar_one_with_the_same_events():
    """pk.Egg(1.3, 0.05): its flows are big enough for heyoka's compact mode, which the batch
    integrator now gets from the same build (it had its own build without it, and without the
    event cooldown); the batch's events, steps and end times are the scalar ones."""
    egg = pk.Egg(1.3, 0.05)
    model = pk.Model(egg, pk.Coulomb(0.1))
    rise = pk.Event("theta", 0.1, direction=-1, name="rise-complete")
    system = declare(model, stop_at="jump", events=[rise])
    flow = dataclasses.replace(system.flow(pk.core.Mode.SLIDING), monitor=None)
    cflow = model.compile_flow(flow, watched(system, pk.core.Mode.SLIDING, engines.taylor.TaylorEngine))
    scalar, _, _ = engines.taylor.TaylorEngine(1e-9).integrator(cflow, len(model.p))
    batch, _ = engines.batch.TaylorBatchEngine(1e-9, 8).integrator(cflow, len(model.p))  # simulate_batch's lanes
    assert scalar.compact_mode and batch.compact_mode
    starts = [pk.gyroscopic_start(egg, np.pi / 2 - 0.01, omega0=w) for w in (6.0, 12.0, 20.0)]
    kw = dict(events=[rise], track_minima=False, dense=False)
    stats = BatchStats()
    runs = pk.core.simulate_batch(model, starts, 60.0, stats=stats, **kw)
    assert stats.batched == 3 and stats.scalar == 0
    for b, x0 in zip(runs, starts):
        s = pk.simulate(model, x0, 60.0, **kw)
        assert b.status is s.status and [e.name for e in b.events] == [e.name for e in s.events]
        assert b.n_steps == s.n_steps and b.t == pytest.approx(s.t, rel=1e-12)
    assert {r.status for r in runs} == {pk.Status.COMPLETED, pk.Status.JUMPED}


def _starts(defn, items):
    models, xs = [], []
    for a, value, d in items:
        m, x = replace(defn, amplitude=d).start(a, value)
        models.append(m)
        xs.append(x)
    return models, xs


def test_batch_runs_equal_scalar_runs_through_jumps_rises_and_sticking():
    """The same classification, events, segments and step counts, and t* to 1e-9: starts
    that jump, that rise, and that stick and roll (the rolling mode run in batch too)."""
    defn = Definition("sliding", "sliding")
    items = [(1.5, v, 0.01) for v in (4.0, 9.0, 9.7, 9.8, 10.5, 14.0)] + [(1.5, 10.4, 0.003), (2.0, 7.1, 0.01),
                                                                          (3.0, 7.5, 0.01), (1.2, 18.0, 0.02)]
    models, xs = _starts(defn, items)
    kw = dict(events=[defn.rise_event(1.5)], track_minima=False, dense=False, max_steps=defn.max_steps)
    stats = BatchStats()
    batch = simulate_batch(models, xs, 3000.0, stats=stats, **kw)
    scalar = [pk.simulate(m, x, 3000.0, **kw) for m, x in zip(models, xs)]
    kinds = set()
    for b, s in zip(batch, scalar):
        assert b.status is s.status and [e.name for e in b.events] == [e.name for e in s.events]
        assert [sg.mode for sg in b.segments] == [sg.mode for sg in s.segments] and b.n_steps == s.n_steps
        assert b.t == pytest.approx(s.t, rel=1e-9) and b.stuck == s.stuck
        if s.t_jump is not None:
            assert b.t_jump == pytest.approx(s.t_jump, rel=1e-9)
        o = defn.classify(models[0].body, 1.0, b.model, b.x0, b)
        kinds.add(o.kind)
    assert kinds == {"jump", "rise", "stuck"} and stats.scalar == 0 and stats.batched == len(items)


@pytest.mark.parametrize("eps", [1e-4, 1e-5])
def test_regularised_sticking_in_batch(eps):
    """A regularised law that sticks: its slow-slip mode is run in batch too, whether it follows
    the law's own field (mu/eps below the creep rate) or its creep (above: no longer stiff)."""
    defn = Definition("literal", "literal", eps=eps, t_max=60.0)
    values = [10.0, 12.0]
    stats = BatchStats()
    got = defn.outcomes(1.5, values, engine="batch", stats=stats)
    want = [defn.outcome(1.5, v) for v in values]
    assert (stats.batched, stats.scalar) == (2, 0)
    for g, w in zip(got, want):
        assert (g.kind, g.status, g.stuck) == (w.kind, w.status, w.stuck) and g.t == pytest.approx(w.t, rel=1e-9)
    assert {g.kind for g in got} == {"stuck"}
