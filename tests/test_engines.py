"""Issue 25, item 4: one integrator build path and one event handler, frozen results, one status
vocabulary per level, one word per concept (the chart; "formulation" its old name)."""

from __future__ import annotations

import dataclasses
import json

import phasekit as pk
import phasekit.studies as ps
from phasekit.core import engines
from phasekit.core.system import declare, watched
from tests.helpers import run_cli

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
    cflow = model.compile_flow(flow, watched(system, pk.core.Mode.SLIDING, engines.TaylorEngine))
    scalar, _, _ = engines.TaylorEngine(1e-9).integrator(cflow, len(model.p))
    batch, _ = engines.TaylorBatchEngine(1e-9, 8).integrator(cflow, len(model.p))  # simulate_batch's lanes
    assert scalar.compact_mode and batch.compact_mode
    starts = [pk.gyroscopic_start(egg, np.pi / 2 - 0.01, omega0=w) for w in (6.0, 12.0, 20.0)]
    kw = dict(events=[rise], track_minima=False, dense=False)
    stats = ps.BatchStats()
    runs = pk.core.simulate_batch(model, starts, 60.0, stats=stats, **kw)
    assert stats.batched == 3 and stats.scalar == 0
    for b, x0 in zip(runs, starts):
        s = pk.simulate(model, x0, 60.0, **kw)
        assert b.status is s.status and [e.name for e in b.events] == [e.name for e in s.events]
        assert b.n_steps == s.n_steps and b.t == pytest.approx(s.t, rel=1e-12)
    assert {r.status for r in runs} == {pk.Status.COMPLETED, pk.Status.JUMPED}


def test_an_unknown_engine_is_an_error_and_a_registered_one_needs_nothing_else():
    with pytest.raises(pk.ParameterError) as info:
        engines.engine_for("rk4", 1e-9)
    assert info.value.param == "backend" and "taylor" in str(info.value)
    with pytest.raises(pk.ParameterError):
        pk.SolverOptions(backend="rk4")
    calls = []

    class Counting(engines.CvodesEngine):
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
        engines.register_engine("taylor", engines.TaylorEngine)


def test_results_are_frozen():
    body = pk.Spheroid(1.5)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0),
                       200.0, stop_at="touchdown", pose0=pk.core.Pose(psi=0.3))
    assert isinstance(traj.segments[0], pk.core.Segment) and isinstance(traj.events[0], pk.core.EventRecord)
    assert isinstance(traj.flights[0], pk.core.Flight) and traj.pose0 == pk.core.Pose(psi=0.3)
    for obj, field in ((traj, "status"), (traj, "segments"), (traj, "pose0"), (traj.segments[0], "t1"),
                       (traj.events[0], "t"), (traj.flights[0], "gap_max")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, field, None)
    r = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.0, omega0=10.0), 5.0, dense=False,
                    t_eval=[1.0, 2.0])
    assert r.ys.shape == (2, 6) and all(s.dense == () for s in r.segments)  # kept only to answer t_eval


def test_one_status_vocabulary_per_level():
    assert {s.value for s in pk.Status} == {"jumped", "touchdown", "stopped", "completed", "settled", "failed"}
    assert {s.value for s in pk.SearchStatus} == {"converged", "non_monotone", "bracket_only", "no_jump_in_range",
                                                  "jumps_at_lower_bound", "failed"}
    th = pk.find_threshold(pk.Definition("sliding", "sliding"), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    assert th.status is pk.SearchStatus.CONVERGED and all(isinstance(o.status, pk.Status) for o in th.outcomes)
    s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    assert isinstance(s, pk.steady.SteadyStructure) and s.status is pk.Status.COMPLETED
    assert all(c.status in pk.SearchStatus for b in s.branches for c in b.changes)
    prop = engines.engine_for("taylor", 1e-9)
    assert prop.name == "taylor" and {e.value for e in engines.End} == {"time", "event", "failed"}


def test_the_chart_and_its_old_name_formulation():
    args = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "1",
            "--json"]
    for flag in ("--chart", "--formulation"):
        code, out, err = run_cli(*args, flag, "vector")
        d = json.loads(out)
        assert code == 0 and d["chart"] == d["formulation"] == d["model"]["chart"] == "vector"
    code, out, err = run_cli(*args, "--formulation", "polar")
    assert code == 2 and "--formulation" in err
    code, out, err = run_cli(*args, "--chart", "polar")
    assert code == 2 and "--chart" in err
    d = json.loads(run_cli(*args)[1])
    d["model"].pop("chart")
    d["model"]["formulation"] = "euler"  # an old result's key
    assert pk.rerun(d).model.chart.name == "euler"
    assert np.allclose(pk.core.to_paper("vector", pk.core.to_chart("vector", [0, 0, 2.0, 0, 1.0, 5.0])), [0, 0, 2.0, 0, 1.0, 5.0])
