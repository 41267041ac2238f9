"""Issue 7: threshold search (bracketing, bisection, non-monotone detection), resumable sweeps."""

import csv
import json
import math
from dataclasses import dataclass

import phasekit as pk
from phasekit.sweep import ModelPack, ResultStore, TaskSpec, run_tasks
from phasekit.thresholds import Definition, Outcome, find_threshold

import pytest


@dataclass(frozen=True)
class Synthetic(Definition):
    """A definition whose 'trajectory' jumps on a known set of intervals (no simulation)."""

    intervals: tuple = ((9.3, math.inf),)

    def outcome(self, a, value):
        jumped = any(lo <= value < hi for lo, hi in self.intervals)
        return Outcome(value, jumped, pk.Status.JUMPED if jumped else pk.Status.STOPPED, 0.0, False, None, 0.0)

    def lower_bound(self, a):
        return 2.0


def synthetic(intervals):
    return Synthetic("synthetic", "sliding", intervals=intervals)


def test_bisection_converges_to_known_threshold():
    th = find_threshold(synthetic(((9.3, math.inf),)), 1.5, hi=60.0, tol=1e-4)
    assert th.status is pk.SearchStatus.CONVERGED
    assert th.bracket[0] < 9.3 <= th.bracket[1] and th.bracket[1] / th.bracket[0] - 1 <= 1e-4
    assert abs(th.value / 9.3 - 1) < 1e-4
    assert th.n_sims == len(th.outcomes) < 30


def test_continuation_guess_saves_simulations_and_widens_when_needed():
    d = synthetic(((9.3, math.inf),))
    cold = find_threshold(d, 1.5, hi=60.0)
    warm = find_threshold(d, 1.5, hi=60.0, guess=9.0)
    far = find_threshold(d, 1.5, hi=60.0, guess=3.0)  # the window must widen upward to find it
    assert warm.n_sims <= cold.n_sims
    for th in (cold, warm, far):
        assert th.status is pk.SearchStatus.CONVERGED and abs(th.value / 9.3 - 1) < 1e-3


def test_non_monotone_answer_reports_every_transition():
    th = find_threshold(synthetic(((5.0, 7.0), (20.0, math.inf))), 1.5, hi=60.0)
    assert th.status is pk.SearchStatus.NON_MONOTONE
    assert len(th.transitions) == 3
    for x in (5.0, 7.0, 20.0):
        assert any(lo <= x <= hi for lo, hi in th.transitions)
    assert abs(th.value / 5.0 - 1) < 1e-3  # the smallest value that jumps


@pytest.mark.parametrize("intervals, status", [((), pk.SearchStatus.NO_JUMP_IN_RANGE), (((0.0, math.inf),), pk.SearchStatus.JUMPS_AT_LOWER_BOUND)])
def test_no_transition(intervals, status):
    th = find_threshold(synthetic(intervals), 1.5, hi=60.0, guess=10.0)
    assert th.status is status and th.value is None


def test_default_definition_threshold_at_a_1_5_and_its_self_consistency():
    d = Definition("sliding", "sliding")
    th = find_threshold(d, 1.5, hi=60.0, guess=9.5)
    assert th.status is pk.SearchStatus.CONVERGED and 9.6 < th.value < 9.9
    assert d.outcome(1.5, 1.02 * th.value).jumped is True
    assert d.outcome(1.5, 0.98 * th.value).jumped is False


def test_viscous_definition_does_not_jump():
    """(i): under viscous friction the R oscillations do not grow enough to lose contact."""
    d = Definition("viscous", "viscous")
    for om in (10.0, 30.0):
        o = d.outcome(1.5, om)
        assert o.jumped is False and o.how == "rise-complete"


def test_literal_recipe_sticks_under_exact_coulomb():
    d = Definition("literal-exact", "literal")
    o = d.outcome(1.5, 12.0)
    assert o.jumped is False and o.stuck
    o3 = Definition("literal-eps1e-3", "literal", eps=1e-3).outcome(1.5, 12.0)
    assert o3.jumped is True  # the regularised law slides and jumps: the answer depends on eps


@dataclass(frozen=True)
class Row:
    key: str
    value: float


def _task(prev, value):
    return Row(f"k{value}", value + (prev.value if prev else 0.0))


def test_store_resumes_without_recomputing(tmp_path):
    csv_path, man = tmp_path / "r.csv", tmp_path / "r.json"
    specs = [TaskSpec(f"k{v}", _task, (v,), after=f"k{v - 1}" if v > 0 else None) for v in range(5)]
    store = ResultStore(csv_path, man, Row, {"study": "test"})
    calls = []

    def on_result(s, r):
        calls.append(s.key)
        store.add(r)
        if len(calls) == 3:
            raise KeyboardInterrupt  # the sweep is killed after three points

    with pytest.raises(KeyboardInterrupt):
        run_tasks(specs, store_get=store.get, on_result=on_result, progress=False)
    assert len(list(csv.DictReader(open(csv_path)))) == 3  # nothing lost
    store2 = ResultStore(csv_path, man, Row, {"study": "test"})
    again = []
    res = run_tasks(specs, store_get=store2.get, on_result=lambda s, r: (again.append(s.key), store2.add(r)), progress=False)
    assert again == ["k3", "k4"]  # finished points are skipped
    assert res["k4"].value == 0 + 1 + 2 + 3 + 4  # continuation used the stored (typed) results
    meta = json.loads(man.read_text())
    assert meta["n_rows"] == 5 and meta["study"] == "test"


@pytest.mark.parametrize("tail", ["k9,", "k9,1.2.3\n", "k9,\"unterminated"])
def test_store_drops_a_torn_last_row_and_appends_on_a_new_line(tmp_path, tail):
    """A kill in mid-write leaves a partial last line: on resume it is dropped (to be
    recomputed) and the next row starts on a line of its own."""
    csv_path, man = tmp_path / "r.csv", tmp_path / "r.json"
    store = ResultStore(csv_path, man, Row, {})
    for v in range(3):
        store.add(Row(f"k{v}", float(v)))
    with open(csv_path, "a") as fh:
        fh.write(tail)
    store2 = ResultStore(csv_path, man, Row, {})
    assert "k9" not in store2 and store2.dropped == 1 and len(store2.rows()) == 3
    store2.add(Row("k3", 3.0))
    rows = list(csv.reader(open(csv_path)))
    assert rows[0] == ["key", "value"] and [r[0] for r in rows[1:]] == ["k0", "k1", "k2", "k3"]
    assert ResultStore(csv_path, man, Row, {}).get("k3").value == 3.0


def _pack_task(prev, a):
    from phasekit.core import fields as M

    return Row(f"a{a}", float(len(M._CACHE)))


@pytest.mark.slow
def test_dask_local_cluster_runs_chains_with_the_model_pack(tmp_path):
    from phasekit.sweep import make_client

    pack = ModelPack.build(lambda: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    client, cluster = make_client(workers=2)
    try:
        specs = [TaskSpec(f"a{a}", _pack_task, (a,), after=None) for a in range(4)]
        res = run_tasks(specs, store_get=lambda k: None, on_result=lambda s, r: None, client=client, pack=pack, progress=False)
    finally:
        client.close()
        cluster.close()
    assert all(r.value >= 1 for r in res.values())  # the pack's compiled model was installed
