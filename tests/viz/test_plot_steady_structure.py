"""pk.viz.plot_steady_structure: one line per stretch of one stability of each branch,
its style that of the structure's own label at every sample, the families' critical values marked
and annotated, theta over [0, pi]."""

from __future__ import annotations

import math
import re

import phasekit as pk

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.colors import to_hex

STYLE = {"stable": "-", "unstable": "--", "neutral": ":", "undecided": "-."}


@pytest.fixture(scope="module")
def structures():
    return {"tippe top": pk.steady_structure(pk.TippeTop(0.3, A=0.38, C=0.4), pk.Viscous(0.3)),
            "spheroid": pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))}


@pytest.fixture
def plt():
    p = pk.viz.pyplot()
    yield p
    p.close("all")


def _own_word(p) -> str:
    """The structure's own label of a sample (FixedPoint.classification and .stable), read here
    without the drawing module's vocabulary."""
    if p.n_unstable > 0:
        return "unstable"
    if not p.stable:
        return "undecided"
    return "stable" if p.classification.startswith("stable") else "neutral"


def _runs(words) -> list:
    runs, start = [], 0
    for k in range(1, len(words)):
        if words[k] != words[start]:
            runs.append((start, k, words[start]))
            start = k
    return runs + [(start, len(words) - 1, words[start])]


@pytest.mark.parametrize("name", ["tippe top", "spheroid"])
@pytest.mark.parametrize("quantity", ["Omega", "n"])
def test_one_line_per_stretch_of_one_stability_styled_sample_by_sample(structures, plt, name, quantity):
    s = structures[name]
    ax = pk.viz.plot_steady_structure(s, quantity=quantity)
    assert isinstance(ax, Axes)
    for k, b in enumerate(s.branches):
        lines = [ln for ln in ax.get_lines() if ln.get_gid() == f"branch {k}"]
        words = [_own_word(p) for p in b.points]
        expected = _runs(words)
        assert len(lines) == len(expected), (name, k)
        drawn = [None] * b.theta.size  # the style of every sample, read back from the lines
        for ln, (i, j, word) in zip(lines, expected):
            x, y = ln.get_data()
            np.testing.assert_array_equal(x, b.theta[i:j + 1])
            np.testing.assert_array_equal(y, getattr(b, quantity)[i:j + 1])
            for m in range(i, j if j < b.theta.size - 1 else j + 1):
                drawn[m] = ln.get_linestyle()
        assert drawn == [STYLE[w] for w in words], (name, k)
    n_lines = sum(1 for ln in ax.get_lines() if (ln.get_gid() or "").startswith("branch "))
    assert n_lines == sum(len(_runs([_own_word(p) for p in b.points])) for b in s.branches)


def test_the_spheroid_has_stable_and_unstable_stretches(structures, plt):
    ax = pk.viz.plot_steady_structure(structures["spheroid"])
    styles = {ln.get_linestyle() for ln in ax.get_lines() if (ln.get_gid() or "").startswith("branch ")}
    assert {"-", "--"} <= styles


@pytest.mark.parametrize("name", ["tippe top", "spheroid"])
@pytest.mark.parametrize("quantity", ["Omega", "n"])
def test_the_critical_values_annotated_are_the_families_criticals(structures, plt, name, quantity):
    s = structures[name]
    ax = pk.viz.plot_steady_structure(s, quantity=quantity)
    texts = [t.get_text() for t in ax.texts if t.get_gid() == "critical"]
    annotated = [float(re.search(r"= (\S+)$", t).group(1)) for t in texts]
    criticals = [c for f in s.families for c in f.criticals]
    assert len(annotated) == len(criticals) > 0
    np.testing.assert_allclose(annotated, criticals, rtol=5e-4)
    if quantity == "n":  # marked on the spin axis at +- the critical spin exactly
        marks = sorted(abs(float(y)) for ln in ax.get_lines() if ln.get_gid() == "critical" for y in ln.get_ydata())
        expected = sorted(c for f in s.families if f.parameter == "n" for c in f.criticals for _ in (0, 1))
        assert marks == expected


def test_the_tippe_tops_spins_about_the_vertical_in_words(structures, plt):
    s = structures["tippe top"]
    ax = pk.viz.plot_steady_structure(s)
    texts = [t.get_text() for t in ax.texts if t.get_gid() == "critical"]
    up, down = (f.critical for f in s.families)
    assert texts == [f"unstable above |n| = {up:.4g}", f"stable above |n| = {down:.4g}"]


@pytest.mark.parametrize("name", ["tippe top", "spheroid"])
def test_theta_covers_zero_to_pi_with_labelled_axes_and_a_legend(structures, plt, name):
    ax = pk.viz.plot_steady_structure(structures[name])
    lo, hi = ax.get_xlim()
    assert lo <= 0.0 and hi >= math.pi
    assert ax.get_xlabel() == "theta [rad]" and ax.get_ylabel() == "Omega [sqrt(g/b)]"
    assert ax.get_legend() is not None
    ends = [ln for ln in ax.get_lines() if ln.get_gid() == "end"]
    finite = [e for b in structures[name].branches for e in b.ends if e.kind != "infinite-spin"]
    assert len(ends) == len(finite)


def test_draws_on_the_axes_given_and_refuses_bad_input(structures, plt):
    fig, ax = plt.subplots()
    assert pk.viz.plot_steady_structure(structures["tippe top"], ax, quantity="n") is ax
    assert ax.get_ylabel() == "n [sqrt(g/b)]"
    with pytest.raises(pk.ParameterError, match="quantity"):
        pk.viz.plot_steady_structure(structures["tippe top"], quantity="spin")
    with pytest.raises(pk.ParameterError, match="structure"):
        pk.viz.plot_steady_structure(pk.TippeTop(0.3))
    with pytest.raises(pk.ParameterError, match="samples"):
        pk.viz.plot_steady_structure(pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), samples=False))
    with pytest.raises(pk.ParameterError, match="ax"):
        pk.viz.plot_steady_structure(structures["tippe top"], ax="axes")


def test_without_stability_the_branches_are_drawn_grey(plt):
    s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), stability=False)
    ax = pk.viz.plot_steady_structure(s)
    lines = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("branch ")]
    assert len(lines) == len(s.branches)
    assert {to_hex(ln.get_color()) for ln in lines} == {"#808080"}
