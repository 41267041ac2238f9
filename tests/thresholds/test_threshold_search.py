"""Threshold search: bracketing, bisection, continuation guesses and non-monotone answers on known
answers, the default definition's threshold, and the searches' refusals of loops."""

import math

import phasekit as pk
from phasekit.thresholds import Definition, find_threshold

import pytest

from .synthetic_definitions import synthetic


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


@pytest.mark.parametrize("kw, name", [(dict(tol=0.0), "tol"), (dict(tol=-1e-3), "tol"), (dict(n_coarse=0), "n_coarse"),
                                      (dict(n_coarse=1), "n_coarse")])
def test_threshold_search_refuses_tolerances_and_counts_that_loop_or_mislead(kw, name):
    with pytest.raises(pk.ParameterError, match=f"^`{name}` "):
        pk.find_threshold(pk.thresholds.DEFAULT_DEFINITIONS[0], 1.5, **kw)
