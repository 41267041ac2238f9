"""k-section rounds, independent searches run in lock-step, the sensitivity of a threshold to its
definition, the stick boundary, and the batch engine giving the published threshold."""

import math

import phasekit as pk
from phasekit.thresholds import (
    Definition,
    ThresholdSearch,
    find_stick_boundary,
    find_threshold,
    run_searches,
)

import numpy as np
import pytest

from .synthetic_definitions import power_law, synthetic


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


def test_threshold_on_the_batch_engine_is_the_published_one():
    """README table (default definition, a = 1.5): the same bracket, bit for bit, whether the
    simulations run one by one or 7 at a time on the batch integrator."""
    defn = Definition("sliding", "sliding")
    kw = dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5, guess=8.155872539891623)  # continued from a = 1.75
    ref = find_threshold(defn, 1.5, **kw)
    fast = find_threshold(defn, 1.5, engine="batch", levels=3, **kw)
    assert fast.bracket == ref.bracket and fast.n_rounds < ref.n_rounds
    assert ref.value == pytest.approx(9.7433, abs=5e-5)  # README, "Thresholds", prolate a = 1.5
