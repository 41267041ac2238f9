"""Every long search reports and ends: wall budgets (``max_wall``) of searches, continuations and
stick boundaries, and the default definition's settle rule, so that an egg that settles tilted
ends its search with a threshold."""

import phasekit as pk

import pytest


@pytest.fixture(scope="module")
def egg():
    return pk.core.egg_of_size("57 mm", "43 mm", w=0.05)[0]


@pytest.mark.timeout(1200)  # a hang guard: the search takes seconds (without the settle rule, > 300 s)
def test_an_egg_that_settles_tilted_ends_its_search_with_a_threshold(egg):
    """A hen's-egg-sized egg, whose runs below the threshold roll tilted in a steady state: they
    end as settled instead of stick-slipping to t_max, and the search converges."""
    th = pk.find_threshold(pk.Definition("sliding", "sliding", mu=0.1), egg, guess=11.0, window=1.2, n_coarse=4, tol=2e-3)
    assert th.status is pk.SearchStatus.CONVERGED and th.bracket[1] / th.bracket[0] - 1 < 2e-3
    lo, hi = th.bracket
    below = [o for o in th.outcomes if o.value <= lo]
    assert all(not o.jumped for o in below) and all(o.jumped for o in th.outcomes if o.value >= hi)
    settled = [o for o in below if o.how == "settled"]
    assert settled and all(o.kind == "stuck" and o.t < 200.0 for o in settled)


def test_the_default_settle_rule_keeps_the_keys_of_stored_results():
    """Results stored before the rule existed are found again: its default is not in the key."""
    d = pk.Definition("sliding", "sliding")
    assert "settle" not in d.key() and d.key().startswith("amplitude=0.01;eps=None;max_steps=20000000;mu=0.1;")
    assert "settle=None" in pk.Definition("sliding", "sliding", settle=None).key()


@pytest.mark.timeout(1200)  # a hang guard; the budget itself is checked by the reason the search gives
def test_a_search_with_a_wall_budget_returns_at_once_saying_so(prolate):
    # without the settle rule the runs below the threshold roll to t_max (~0.5 s each): the budget binds
    th = pk.find_threshold(pk.Definition("sliding", "sliding", settle=None), prolate, max_wall=0.05, progress=False)
    assert th.status in (pk.SearchStatus.FAILED, pk.SearchStatus.BRACKET_ONLY) and "max_wall = 0.05 s" in th.reason


def test_a_continuation_with_a_wall_budget_marks_the_bodies_it_did_not_reach():
    defn = pk.Definition("sliding", "sliding", settle=None)
    out = pk.thresholds.continue_threshold(defn, [1.5, 1.75, 2.0], max_wall=0.05, progress=False)
    assert len(out) == 3 and out[-1].status is pk.SearchStatus.FAILED and out[-1].reason.startswith("not searched")


def test_a_stick_boundary_search_takes_a_wall_budget(prolate):
    # below the threshold (9.74) the starts that stick roll to t_max without the settle rule: the budget binds
    th = pk.thresholds.find_stick_boundary(pk.Definition("sliding", "sliding", settle=None), prolate, 9.0, max_wall=0.01,
                                           progress=False)
    assert th.status in (pk.SearchStatus.FAILED, pk.SearchStatus.BRACKET_ONLY) and "max_wall" in th.reason


def test_a_run_cut_by_the_wall_budget_ends_its_search_where_it_is():
    """A run the caller's budget cut decides nothing: read as "no outcome", the cut runs below the
    threshold made a scan see jumps everywhere and report "jumps at the lower bound"."""
    from phasekit._runtime.watch import WALL_REASON

    s = pk.thresholds.ThresholdSearch(pk.Definition("sliding", "sliding"), pk.Spheroid(1.5), lo=5.0, hi=20.0, guess=None,
                                      n_coarse=4, window=1.5, tol=1e-2)
    values = s.ask()
    cut = f"{WALL_REASON} (max_wall = 0.05 s) ran out at t = 1.5"
    outs = [pk.thresholds.Outcome(v, None, pk.Status.FAILED, 1.5, False, cut, 0.0, None, None) if v < 10 else
            pk.thresholds.Outcome(v, True, pk.Status.JUMPED, 40.0, False, None, 0.0, 1.0, 0.5) for v in values]
    s.tell(outs)
    th = s.result()
    assert s.done and th.status is pk.SearchStatus.FAILED and "max_wall = 0.05 s" in th.reason and "at t =" not in th.reason
