"""Issue 16: the sweep engine - k-section, independent searches run in lock-step, batch
propagation against the scalar path, sensitivity of a threshold to its definition, and
resumable stores of the new row types."""

import csv
import json
import math
from dataclasses import asdict, dataclass, replace

import phasekit as pk
import phasekit.studies as ps
from phasekit.core.batch import BatchStats, simulate_batch
from phasekit.studies import SearchRow
from phasekit.sweep import ResultStore, TaskSpec, run_tasks
from phasekit.thresholds import (
    Definition,
    Outcome,
    ThresholdSearch,
    find_stick_boundary,
    find_threshold,
    run_searches,
)

import numpy as np
import pytest


@dataclass(frozen=True)
class PowerLaw(Definition):
    """A definition whose 'trajectory' jumps above value* = c d^-p and sticks below
    d_min = k / value^2 (no simulation): known thresholds, boundaries and sensitivity."""

    c: float = 9.3
    p: float = 0.1
    k: float = 0.5

    def outcome(self, body, value):
        if self.amplitude < self.k / value**2:
            return Outcome(value, False, pk.Status.COMPLETED, 3000.0, True, None, 0.0)
        jumped = value >= self.c * self.amplitude ** -self.p
        return Outcome(value, jumped, pk.Status.JUMPED if jumped else pk.Status.STOPPED, 1.0, False, None, 0.0)

    def lower_bound(self, body):
        return 2.0


def power_law(**kw):
    return PowerLaw("power-law", "sliding", amplitude=kw.pop("amplitude", 0.05), **kw)


def bisection_steps(ratio: float, tol: float) -> int:
    """How many halvings (in log) take a bracket of ratio hi/lo to relative width <= tol."""
    n = 0
    while ratio - 1 > tol:
        ratio, n = math.sqrt(ratio), n + 1
    return n


@pytest.mark.parametrize("levels", [2, 3, 4])
def test_k_section_gives_the_bisection_bracket_in_fewer_rounds(levels):
    defn = power_law()
    truth = defn.c * defn.amplitude ** -defn.p
    bis = find_threshold(defn, 1.5, hi=60.0, tol=1e-6)
    ks = find_threshold(defn, 1.5, hi=60.0, tol=1e-6, levels=levels)
    assert bis.bracket[0] < truth <= bis.bracket[1]
    assert ks.bracket == bis.bracket and ks.value == bis.value and ks.status is pk.SearchStatus.CONVERGED
    # the scan is one round; its transition interval then needs `steps` halvings
    scan = np.geomspace(2.0, 60.0, 8)
    j = np.searchsorted(scan, truth)
    steps = bisection_steps(scan[j] / scan[j - 1], 1e-6)
    assert bis.n_rounds == 1 + steps
    assert ks.n_rounds == 1 + math.ceil(steps / levels)
    assert ks.n_sims > bis.n_sims  # the price: more simulations per round


def test_k_section_follows_every_transition_of_a_non_monotone_answer():
    from tests.test_threshold import synthetic

    defn = synthetic(((5.0, 7.0), (20.0, math.inf)))
    bis = find_threshold(defn, 1.5, hi=60.0)
    ks = find_threshold(defn, 1.5, hi=60.0, levels=3)
    assert ks.status is pk.SearchStatus.NON_MONOTONE and ks.transitions == bis.transitions and len(ks.transitions) == 3


def test_independent_searches_run_in_lock_step_with_the_critical_path_of_the_longest():
    searches = [ThresholdSearch(power_law(amplitude=d), 1.5, lo=2.0, hi=60.0, guess=None, n_coarse=8, window=1.5,
                                tol=tol, levels=3) for d, tol in ((0.01, 1e-3), (0.05, 1e-6), (0.2, 1e-2))]
    alone = []
    for s in searches:
        solo = ThresholdSearch(s.defn, 1.5, lo=2.0, hi=60.0, guess=None, n_coarse=8, window=1.5, tol=s.tol, levels=3)
        run_searches([solo])
        alone.append(solo.n_rounds)
    rounds = run_searches(searches)
    assert rounds == max(alone) and [s.n_rounds for s in searches] == alone
    assert len(set(alone)) > 1  # the searches do differ in depth


def test_sensitivity_reports_the_slope_and_which_uncertainty_dominates():
    defn = power_law(amplitude=0.05, p=0.1)
    th = find_threshold(defn, 1.5, hi=60.0, tol=1e-4, sensitivity=True)
    s = th.sensitivity
    assert s.amplitudes == (0.025, 0.05, 0.1)
    assert s.slope == pytest.approx(-0.1, abs=2e-4)  # d ln(value*) / d ln(d) = -p
    assert s.shift == pytest.approx(2**0.1 - 1, rel=2e-3) and s.dominant == "seed distance"
    flat = find_threshold(power_law(amplitude=0.05, p=1e-6), 1.5, hi=60.0, tol=1e-2, sensitivity=True)
    assert flat.sensitivity.dominant == "bracket" and abs(flat.sensitivity.slope) < 1e-2
    assert th.n_rounds == max(th.n_rounds, 1) and s.n_sims > 0


def test_stick_boundary_by_bisection_in_d():
    defn = power_law(amplitude=0.05)
    for value in (8.0, 20.0):
        th = find_stick_boundary(defn, 1.5, value, tol=1e-4)
        assert th.status is pk.SearchStatus.CONVERGED
        assert th.bracket[0] < defn.k / value**2 <= th.bracket[1] and th.bracket[1] / th.bracket[0] - 1 <= 1e-4


def test_search_rows_survive_a_kill_and_resume(tmp_path):
    """Independent tasks (longest first) into a store; killed after two rows; the rerun
    computes only the rest; a torn row is recomputed."""
    defn = power_law()
    specs = [TaskSpec(f"k{i}", _row_task, (i,), cost=float(i)) for i in range(5)]
    csv_path, man = tmp_path / "s.csv", tmp_path / "s.json"
    store = ResultStore(csv_path, man, SearchRow, {"study": "t"})
    done = []

    def on_result(s, r):
        store.add(r)
        done.append(s.key)
        if len(done) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_tasks(specs, store_get=store.get, on_result=on_result, progress=False)
    assert done == ["k4", "k3"]  # the costliest first
    with open(csv_path, "a") as fh:
        fh.write("k9,t,threshold,prol")  # a kill in mid-write
    again = ResultStore(csv_path, man, SearchRow, {"study": "t"})
    assert again.dropped == 1 and again.get("k4") == _row_task(None, 4)
    later = []
    run_tasks(specs, store_get=again.get, on_result=lambda s, r: (later.append(s.key), again.add(r)), progress=False)
    assert later == ["k2", "k1", "k0"]
    with open(csv_path) as fh:
        rows = list(csv.DictReader(fh))
    assert [r["key"] for r in rows] == ["k4", "k3", "k2", "k1", "k0"] and rows[0]["sens_half"] == ""
    assert defn.key() != replace(defn, amplitude=0.1).key()
    # the manifest keeps both runs: what each computed, and under which command
    ResultStore(csv_path, man, SearchRow, {"study": "t", "command": "replot"})
    runs = json.loads(man.read_text())["runs"]
    assert [(r["rows_at_start"], r["rows_added"]) for r in runs] == [(0, 2), (2, 3), (5, 0)]
    assert runs[-1]["command"] == "replot" and json.loads(man.read_text())["started"] == runs[0]["started"]


def _row_task(prev, i):
    return SearchRow(key=f"k{i}", study="t", kind="threshold", branch="prolate", a=1.5, mu=0.1, d=0.01, value=None,
                     threshold=9.0 + i / 3, bracket_lo=9.0, bracket_hi=9.0 + i, status="converged", n_sims=15 + i, n_rounds=4,
                     levels=3, engine="batch", eps=None, rtol=1e-9, t_max=3000.0, transitions="[[9.0, 10.0]]",
                     stuck_near=False, sens_half=None, sens_double=None, sens_slope=-0.09, sens_shift=None,
                     sens_dominant="", wall_s=0.25, reason="")


# -- batch propagation against the scalar path -------------------------------------------------


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


@pytest.mark.parametrize("eps, batched", [(1e-4, True), (1e-5, False)])
def test_regularised_sticking_in_batch_or_handed_back(eps, batched):
    """A regularised law that sticks: with mu/eps below the stiff rate the slow-slip mode is
    run in batch too; above it the mode is CVODES', and those starts are rerun by simulate."""
    defn = Definition("literal", "literal", eps=eps, t_max=60.0)
    values = [10.0, 12.0]
    stats = BatchStats()
    got = defn.outcomes(1.5, values, engine="batch", stats=stats)
    want = [defn.outcome(1.5, v) for v in values]
    assert (stats.batched, stats.scalar) == ((2, 0) if batched else (0, 2))
    assert batched or "stiff" in " ".join(stats.reasons)
    for g, w in zip(got, want):
        assert (g.kind, g.status, g.stuck) == (w.kind, w.status, w.stuck) and g.t == pytest.approx(w.t, rel=1e-9)
    assert {g.kind for g in got} == {"stuck"}


def test_threshold_on_the_batch_engine_is_the_published_one():
    """README table (default definition, a = 1.5): the same bracket, bit for bit, whether the
    simulations run one by one or 7 at a time on the batch integrator."""
    defn = Definition("sliding", "sliding")
    kw = dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5, guess=8.155872539891623)  # continued from a = 1.75
    ref = find_threshold(defn, 1.5, **kw)
    fast = find_threshold(defn, 1.5, engine="batch", levels=3, **kw)
    assert fast.bracket == ref.bracket and fast.n_rounds < ref.n_rounds
    assert ref.value == pytest.approx(9.7433, abs=5e-5)  # README, "Thresholds", prolate a = 1.5


@pytest.mark.slow
def test_dask_k_section_round_and_grouped_searches_equal_the_serial_ones(tmp_path):
    """One search's k-section rounds spread over 2 workers, and grouped search tasks on the
    cluster, give the serial brackets."""
    defn = Definition("sliding", "sliding")
    pack = pk.sweep.ModelPack.build(lambda: defn.prepare(1.5, engine="batch"))
    client, cluster = pk.sweep.make_client(workers=2)
    try:
        ev = cluster.client_evaluator(client, pack=pack)
        far = find_threshold(defn, 1.5, hi=120.0, levels=3, evaluate=ev)
        near = find_threshold(defn, 1.5, hi=120.0, levels=3, engine="batch")
        assert far.bracket == near.bracket and far.n_rounds == near.n_rounds
        jobs = [ps.search_job(asdict(replace(defn, amplitude=d)), 1.5, dict(hi=120.0, levels=3)) for d in (0.01, 0.02, 0.04)]
        specs, members = ps.group_search_tasks(jobs, [1.0, 2.0, 3.0], per_task=2)
        store = ResultStore(tmp_path / "g.csv", tmp_path / "g.json", SearchRow, {})
        get, add = pk.sweep.stored_rows([store], members)
        run_tasks(specs, store_get=get, on_result=add, client=client, pack=pack, progress=False)
    finally:
        client.close()
        cluster.close()
    rows = {r.d: r for r in store.rows()}
    assert len(specs) == 2 and rows[0.01].threshold == near.value
    assert rows[0.04].threshold < rows[0.02].threshold < rows[0.01].threshold  # README: the threshold falls as d grows


def _pack_size(prev, i):
    return i


def test_runs_one_after_another_on_one_client_share_the_pack_without_losing_it():
    """The same model pack scattered run after run (a study's searches then its grid; a
    benchmark's serial and Dask passes): each run gets its own copy, so the release of the last
    one cannot take the next run's with it (with content-hashed keys it did: "lost dependencies",
    dask/distributed#8576)."""
    pack = pk.sweep.ModelPack.build(lambda: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    client, cluster = pk.sweep.make_client(workers=1)
    try:
        for run in range(12):
            specs = [TaskSpec(f"r{run}-{i}", _pack_size, (i,)) for i in range(3)]
            got = {}
            run_tasks(specs, store_get=lambda k: None, on_result=lambda s, r: got.__setitem__(s.key, r), client=client,
                      pack=pack, progress=False)
            assert got == {f"r{run}-{i}": i for i in range(3)}
    finally:
        client.close()
        cluster.close()


def test_a_task_function_from_a_module_loaded_from_its_file_runs_on_dask(tmp_path):
    """A study loaded from its file and registered with cloudpickle by value (what the benchmarks
    do) hands its own functions to the workers, which cannot import it by name: they are shipped
    by value (before, every worker died on the message and the run waited until its wall budget)."""
    import importlib.util
    import sys

    import cloudpickle

    (tmp_path / "a_study_by_path.py").write_text("def square(prev, x):\n    return x * x\n")
    spec = importlib.util.spec_from_file_location("a_study_by_path", tmp_path / "a_study_by_path.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["a_study_by_path"] = mod
    spec.loader.exec_module(mod)
    cloudpickle.register_pickle_by_value(mod)
    client, cluster = pk.sweep.make_client(workers=1)
    try:
        got = {}
        run_tasks([TaskSpec(f"sq{i}", mod.square, (i,)) for i in range(4)], store_get=lambda k: None,
                  on_result=lambda s, r: got.__setitem__(s.key, r), client=client, progress=False, max_wall=60.0)
    finally:
        client.close()
        cluster.close()
        cloudpickle.unregister_pickle_by_value(mod)
        del sys.modules["a_study_by_path"]
    assert got == {f"sq{i}": i * i for i in range(4)}
