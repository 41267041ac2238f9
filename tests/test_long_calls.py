"""Issue 24, item 2: every long call reports and ends.

Wall budgets (``max_wall``) of searches, continuations, maps and ensembles; progress bars where
a person waits (``progress``); runs that have settled end as "settled" (:class:`phasekit.core.Settle`),
and the default threshold definition uses that rule, so that an egg that settles tilted no
longer stick-slips to t_max.
"""

import importlib
import time

import phasekit as pk
from phasekit._runtime.watch import show_progress

import numpy as np
import pytest

HANG_GUARD = 120.0  # s


@pytest.fixture(scope="module")
def egg():
    return pk.core.egg_of_size("57 mm", "43 mm", w=0.05)[0]


def test_the_issues_egg_search_ends_with_a_threshold(egg):
    """The search of the issue (it ran > 300 s silently): the no-jump runs settle tilted."""
    t0 = time.monotonic()
    th = pk.find_threshold(pk.Definition("sliding", "sliding", mu=0.1), egg, guess=11.0, window=1.2, n_coarse=4, tol=2e-3)
    assert time.monotonic() - t0 < HANG_GUARD
    assert th.status is pk.SearchStatus.CONVERGED and th.bracket[1] / th.bracket[0] - 1 < 2e-3
    lo, hi = th.bracket
    below = [o for o in th.outcomes if o.value <= lo]
    assert all(not o.jumped for o in below) and all(o.jumped for o in th.outcomes if o.value >= hi)
    settled = [o for o in below if o.how == "settled"]
    assert settled and all(o.kind == "stuck" and o.t < 200.0 for o in settled)


def test_a_settled_egg_would_not_have_jumped(egg):
    """The settled run against the same run without the rule, to t = 180: it goes on rolling and
    re-slipping about the same tilted state, R far from 0 at every event, and never jumps."""
    model, x0 = pk.Definition("sliding", "sliding", mu=0.1).start(egg, 11.0)
    fast = pk.simulate(model, x0, 180.0, settle=True, track_minima=False)
    assert fast.status is pk.Status.SETTLED and fast.reason.startswith("settled: rolled in a steady state")
    assert fast.mode == "rolling" and fast.t < 150.0
    slow = pk.simulate(model, x0, 180.0, track_minima=False, dense=False)
    assert slow.status is pk.Status.COMPLETED and slow.t_jump is None
    later = [e for e in slow.events if e.t > fast.t and e.x is not None]
    theta = np.array([e.y[4] for e in later])
    assert len(later) > 50 and np.abs(theta - fast.euler_end[4]).max() < 2 * pk.core.Settle().tol
    R = [model.evaluate("R", e.x, e.mode_after) for e in later]
    assert min(R) > pk.core.Settle().R_floor


def test_the_settle_rule_leaves_sliding_and_regularised_runs_alone(prolate, standard_start):
    coulomb = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 200.0, settle=True)
    assert coulomb.status is pk.Status.JUMPED
    # a regularised law keeps a small slip while "rolling": it never settles
    model, x0 = pk.paper_start("5.2")
    reg = pk.Model(model.body, pk.RegularisedCoulomb(0.1, 1e-3))
    r = pk.simulate(reg, x0, 120.0, settle=pk.core.Settle(window=5.0))
    assert r.status is not pk.Status.SETTLED and r.stuck


def test_settle_options_are_validated_and_reach_the_json():
    with pytest.raises(pk.ParameterError, match="`window`"):
        pk.core.Settle(window=-1.0)
    with pytest.raises(pk.ParameterError, match="`settle`"):
        pk.SolverOptions(settle="yes")
    opts = pk.SolverOptions(settle={"window": 30.0})
    assert opts.settle == pk.core.Settle(window=30.0) and opts.to_dict()["settle"]["window"] == 30.0


def test_the_default_settle_rule_keeps_the_keys_of_stored_results():
    """Results stored before the rule existed are found again: its default is not in the key."""
    d = pk.Definition("sliding", "sliding")
    assert "settle" not in d.key() and d.key().startswith("amplitude=0.01;eps=None;max_steps=20000000;mu=0.1;")
    assert "settle=None" in pk.Definition("sliding", "sliding", settle=None).key()


def test_a_search_with_a_wall_budget_returns_at_once_saying_so(prolate):
    t0 = time.monotonic()
    th = pk.find_threshold(pk.Definition("sliding", "sliding"), prolate, max_wall=0.05, progress=False)
    assert time.monotonic() - t0 < HANG_GUARD
    assert th.status in (pk.SearchStatus.FAILED, pk.SearchStatus.BRACKET_ONLY) and "max_wall = 0.05 s" in th.reason


def test_a_continuation_with_a_wall_budget_marks_the_bodies_it_did_not_reach():
    defn = pk.Definition("sliding", "sliding")
    out = pk.thresholds.continue_threshold(defn, [1.5, 1.75, 2.0], max_wall=0.05, progress=False)
    assert len(out) == 3 and out[-1].status is pk.SearchStatus.FAILED and out[-1].reason.startswith("not searched")


def test_a_stick_boundary_search_takes_a_wall_budget(prolate):
    th = pk.thresholds.find_stick_boundary(pk.Definition("sliding", "sliding"), prolate, 10.0, max_wall=0.01, progress=False)
    assert th.status in (pk.SearchStatus.FAILED, pk.SearchStatus.BRACKET_ONLY) and "max_wall" in th.reason


def test_progress_is_shown_where_asked_and_only_there(capsys, prolate):
    assert show_progress(None) is False  # pytest captures stderr: not a terminal, not a notebook
    assert show_progress(True) is True and show_progress(False) is False
    with pytest.raises(pk.ParameterError, match="`progress`"):
        show_progress("yes")
    defn = pk.Definition("sliding", "sliding")
    pk.find_threshold(defn, prolate, guess=9.74, window=1.01, n_coarse=2, tol=5e-3, progress=True)
    err = capsys.readouterr().err
    assert "threshold a=1.5" in err and "run" in err
    pk.find_threshold(defn, prolate, guess=9.74, window=1.01, n_coarse=2, tol=5e-3)
    assert capsys.readouterr().err == ""


def test_a_single_long_run_shows_its_progress(capsys, monkeypatch, prolate, standard_start):
    monkeypatch.setattr(importlib.import_module("phasekit.core.simulate"), "PROGRESS_DELAY", 0.0)
    pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 40.0, progress=True)
    assert "simulate" in capsys.readouterr().err
    pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), standard_start, 40.0)
    assert capsys.readouterr().err == ""


def test_a_map_with_a_wall_budget_leaves_the_rest_for_a_rerun():
    done = []

    def slow(prev, k):
        time.sleep(0.05)
        return k

    specs = [pk.sweep.TaskSpec(f"k{k}", slow, (k,)) for k in range(40)]
    res = pk.sweep.run_tasks(specs, store_get=lambda key: None, on_result=lambda s, r: done.append(s.key), progress=False,
                       max_wall=0.3)
    assert 0 < len(res) == len(done) < 40
    stored = dict.fromkeys(done, 0)
    again = pk.sweep.run_tasks(specs, store_get=stored.get, on_result=lambda s, r: done.append(s.key), progress=False)
    assert len(again) == 40 and len(done) == 40
