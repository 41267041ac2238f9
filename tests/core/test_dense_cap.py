"""The memory cap of the dense output (SolverOptions.max_dense_mb, phasekit.core.dense_cap): past it a
run keeps its samples at t_eval, its events and its energy budget (the same numbers as from the dense
output), its memory per step falls from ~0.75 KB to the tally's ~16 bytes, and what needs the dense
output says so; the work after a run stops when the wall budget in force runs out."""

from __future__ import annotations

import time
import tracemalloc

import phasekit as pk
from phasekit._runtime.watch import wall_deadline
from phasekit.core.dense_cap import DenseCap, span_bytes

import numpy as np
import pytest


def _model(drag: float = 1e-4):
    body = pk.Spheroid(1.5)
    return pk.Model(body, pk.Coulomb(0.1).with_dissipation(pk.AirDrag(rotation=drag))), \
        pk.gyroscopic_start(body, 1.5607963, omega0=11.0)


@pytest.fixture(scope="module")
def pair():
    model, x0 = _model()
    te = np.linspace(0.0, 300.0, 701)
    kept = pk.simulate(model, x0, 300.0, stop_at="none", t_eval=te)
    capped = pk.simulate(model, x0, 300.0, stop_at="none", t_eval=te, max_dense_mb=0.5)
    return kept, capped


def test_past_the_cap_the_energy_budget_samples_and_events_are_those_of_the_dense_run(pair):
    kept, capped = pair
    assert all(s.dense for s in kept.segments) and not any(s.tally for s in kept.segments)
    assert not any(s.dense for s in capped.segments) and all(s.tally for s in capped.segments)
    a, b = kept.energy_budget(), capped.energy_budget()
    assert a.dissipated[1] > 1.0 and a.residual_max < 1e-8  # the air drag took energy; the balance holds
    assert b == a  # the same quadratures, summed in the same order: bit for bit
    assert np.array_equal(capped.ts, kept.ts) and np.array_equal(capped.ys, kept.ys)
    assert [(e.name, e.t) for e in capped.events] == [(e.name, e.t) for e in kept.events]
    assert np.array_equal(capped.minima, kept.minima)
    assert capped.to_dict()["energy_budget"] == kept.to_dict()["energy_budget"]


def test_what_needs_the_dense_output_names_the_cap(pair):
    capped = pair[1]
    with pytest.raises(pk.ParameterError, match="^`traj` has no energy series: the run dropped"):
        capped.energy_series()
    for call in (lambda: capped.sample([10.0]), lambda: capped.pose([10.0]), capped.energy_series):
        with pytest.raises(pk.ParameterError, match=r"dropped its dense output when it passed max_dense_mb = 0\.5 MB"):
            call()
    kept, _ = pair
    assert "pose_end" in kept.to_dict() and "pose_end" not in capped.to_dict()  # poses need the dense output
    from phasekit.viz.mpl import _check_traj

    with pytest.raises(pk.ParameterError, match="must keep its dense output .*passed max_dense_mb = 0.5 MB"):
        _check_traj(capped)


def test_without_dense_output_t_eval_alone_is_kept_under_the_cap():
    model, x0 = _model()
    te = np.linspace(0.0, 200.0, 301)
    a = pk.simulate(model, x0, 200.0, stop_at="none", t_eval=te, dense=False)
    b = pk.simulate(model, x0, 200.0, stop_at="none", t_eval=te, dense=False, max_dense_mb=0.2)
    assert np.array_equal(a.ys, b.ys) and not any(s.tally for s in b.segments)
    with pytest.raises(pk.ParameterError, match="kept no dense output"):
        b.energy_budget()


def _held(t_end: float, cap):
    model, x0 = _model()
    # the same run once untraced first: what it compiles and caches (kept by the process, whichever test ran
    # before) is not the run's memory
    pk.simulate(model, x0, t_end, stop_at="none", max_dense_mb=cap)
    tracemalloc.start()
    traj = pk.simulate(model, x0, t_end, stop_at="none", max_dense_mb=cap)
    held, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return traj.n_steps, held, peak


def test_memory_per_step_is_bounded_past_the_cap():
    n1, held1, peak1 = _held(500.0, 0.5)
    n2, held2, peak2 = _held(1000.0, 0.5)
    m1, dense1, _ = _held(500.0, None)
    m2, dense2, _ = _held(1000.0, None)
    assert n2 > 1.8 * n1 and m1 == n1
    assert dense2 / dense1 > 1.6 and dense1 / m1 > 300  # uncapped: ~0.75 KB a step, and it grows with the run
    assert (held2 - held1) / (n2 - n1) < 40  # capped: the tally's 16 bytes a step, a little more
    assert peak2 < 1.25 * peak1  # the peak is a record of steps (RECORD_STEPS) and the cap, not the run


def test_the_cap_counts_the_bytes_behind_its_spans():
    model, x0 = _model()
    traj = pk.simulate(model, x0, 100.0, stop_at="none")
    spans = [sp for s in traj.segments for sp in s.dense]
    total = sum(span_bytes(sp) for sp in spans)
    steps = sum(len(sp.pieces()[0]) for sp in spans if hasattr(sp.f, "coefs"))
    assert 300 < total / steps < 3000  # ~0.75 KB a step (the coefficients of every state, z included)
    cap, kept = DenseCap(model, total / 2 / 1e6, None, energy=True), []
    for i, seg in enumerate(traj.segments):
        cap.where = (i, seg.mode)
        kept += [cap(sp) for sp in seg.dense]
    assert cap.dropped and kept.index(False) > 0 and not any(kept[kept.index(False):])
    drop = kept.index(False)  # the span that passed the cap: it and every span before it freed at once
    assert all(sp.f is None for sp in spans[:drop + 1]) and all(sp.f is not None for sp in spans[drop + 1:])
    assert sum(len(v) for v in cap.tallies.values()) == len(spans)  # each tallied once


def test_the_work_after_a_run_stops_when_the_wall_budget_runs_out(pair):
    kept, _ = pair
    fresh = pk.simulate(kept.model, kept.x0, 300.0, stop_at="none")
    with wall_deadline(1e-6):
        time.sleep(0.01)
        d = fresh.to_dict()
    assert d["energy_budget"] is None and d["post_run"]["skipped"] == ["energy budget", "poses"]
    assert "max_wall = 1e-06 s" in d["post_run"]["reason"] and "pose_end" not in d
    with wall_deadline(600.0):
        full = fresh.to_dict()
    assert "post_run" not in full and full["energy_budget"] == kept.to_dict()["energy_budget"]


class _Clock:
    """A Budget's wall clock that runs out after ``after`` looks."""

    def __init__(self, after: int):
        self.left = after

    def wall_exceeded(self) -> bool:
        self.left -= 1
        return self.left < 0


def test_a_wall_budget_that_runs_out_while_tallying_stops_the_tally(pair):
    from dataclasses import replace

    kept, _ = pair
    fresh = pk.simulate(kept.model, kept.x0, 300.0, stop_at="none")
    cap = DenseCap(fresh.model, 0.1, None, energy=True)
    cap.budget = _Clock(3)
    for i, seg in enumerate(fresh.segments):
        cap.where = (i, seg.mode)
        for sp in seg.dense:
            cap(sp)
    assert cap.dropped and cap.abandoned and cap.tallies == {}
    stopped = replace(fresh, segments=cap.segments(list(fresh.segments)))
    with pytest.raises(pk.ParameterError, match="wall budget ran out while it tallied the energy"):
        stopped.energy_budget()
    assert stopped.to_dict()["energy_budget"] is None
