"""The stability vocabulary of the figures (phasekit.viz.stability): a state's word is its
classification, read as neutral on the rolling field; a family's stable side is neutral under
exact Coulomb friction and stable under a law with friction-driven decay."""

import phasekit as pk
from phasekit.steady import FixedPoint
from phasekit.viz.stability import WORDS, family_word, law_text, legend_label, state_word

import numpy as np


def _point(eigenvalues, law):
    lam = np.asarray(eigenvalues, dtype=complex)
    return FixedPoint("horizontal", "euler", np.zeros(8), np.zeros(8), lam, np.eye(lam.size), 0.0, law)


def test_state_words_follow_the_eigenvalues_and_the_law():
    decaying = [0.0, 0.0, -0.3 + 1j, -0.3 - 1j]
    oscillating = [0.0, 0.0, 1j, -1j]
    growing = [0.2, 0.0, -0.2, 0.0]
    assert state_word(_point(decaying, "viscous")) == "stable"
    assert state_word(_point(oscillating, "coulomb-rolling")) == "neutral"
    assert state_word(_point(growing, "coulomb-rolling")) == state_word(_point(growing, "viscous")) == "unstable"
    # a real part inside its error bound, the imaginary part not: a dissipative law cannot sign it
    blurred = _point([1e-17 + 1j, 1e-17 - 1j], "viscous")
    assert blurred.n_undecided == 2 and state_word(blurred) == "undecided"
    assert set(WORDS) == {"stable", "neutral", "undecided", "unstable"}


def test_family_sides_under_coulomb_are_neutral_and_the_legend_says_why():
    s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Coulomb(0.1), samples=False)
    pole = next(f for f in s.families if f.kind == "pole")
    assert pole.stable_on == (False, True)
    assert [family_word(x, s.model.friction) for x in pole.stable_on] == ["unstable", "neutral"]
    assert [family_word(x, pk.Viscous(0.1)) for x in (False, True, None)] == ["unstable", "stable", "unknown"]
    label = legend_label("neutral", law_text(pk.Coulomb(0.1)), rolling=True)
    assert label.startswith("neutral (exact Coulomb") and "no decay" in label
    assert legend_label("stable", law_text(pk.Viscous(0.2)), rolling=False) == "stable (viscous $\\mu$ = 0.2)"
