"""A body's steady-state structure in a plane (:func:`plot_steady_structure`, matplotlib): every
branch of :func:`phasekit.steady_structure` as a curve of its rate (Omega or n) against theta,
its line style saying its stability sample by sample (solid stable, dashed unstable, dotted
neutral, dash-dot undecided; colours those of :mod:`phasekit.viz.stability`), its ends marked
by kind, the infinite-spin asymptotes as vertical dotted lines, and the families (the spins
about the vertical at the poles, the precession and rolling families) at their theta with
their critical values marked and annotated ("unstable above |n| = 1.212").

Each stretch of one stability word of a branch is one line, whose ``gid`` is "branch <k>" (k:
the branch's index in ``structure.branches``); the ends' markers have gid "end", the critical
values' markers and annotations "critical", the families' lines "family": a caller (or a test)
can find them with ``ax.get_lines()`` and ``ax.texts``.
"""

from __future__ import annotations

import math

import numpy as np

from .._runtime.validate import check_choice
from ..errors import ParameterError
from .mpl import _check_ax, label
from .stability import COLOURS, WORDS, family_word, law_text, legend_label, state_word

#: the rates a branch can be drawn in
QUANTITIES = ("Omega", "n")
#: one line style per stability word ("unknown": stability not computed)
STYLES = {"stable": "-", "neutral": ":", "undecided": "-.", "unstable": "--", "unknown": "-"}
#: the marker of a branch end, by its kind
END_MARKERS = {"pole": "o", "static": "^", "switch": "s", "limit": "D"}
END_WORDS = {"pole": "end at a spin about the vertical", "static": "end at a static equilibrium",
             "switch": "end where the contact passes to another piece", "limit": "end at a limit of the range"}
#: the legend's word for the families drawn, by quantity
FAMILY_WORDS = {"line": "family along its own rate (thin; styled by its stability)",
                "pole": "spin about the vertical (a family: any n)",
                "point": "family at rest in this plane (straight rolling; a precession family at n = 0)"}
#: the colour of the critical values of the families and of the changes of stability
CRITICAL = "#fd8d3c"


def plot_steady_structure(structure, ax=None, quantity: str = "Omega"):
    """Draw a body's steady-state structure in the plane (theta, ``quantity``) (module notes).

    Parameters
    ----------
    structure : SteadyStructure
        What :func:`phasekit.steady_structure` returned, with its samples (``samples=True``, the
        default); without stability (``stability=False``) the branches are drawn grey.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: a new figure of 8 x 6.2 inches, constrained layout); the
        legend goes below them.
    quantity : str
        The rate on the vertical axis: "Omega" (the precession rate, default) or "n" (the
        spin), in sqrt(g/b); theta in radians on the horizontal axis.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``, with a legend, axis labels and (if it had none) a title naming the body, the
        law and the signature.

    Raises
    ------
    ParameterError
        If ``structure`` is not a SteadyStructure, failed, or has no samples along its branches;
        ``ax`` is not matplotlib Axes; or ``quantity`` is not "Omega" or "n".

    Examples
    --------
    >>> import phasekit as pk
    >>> s = pk.steady_structure(pk.TippeTop(0.3, A=0.38, C=0.4), pk.Viscous(0.3))
    >>> ax = pk.viz.plot_steady_structure(s)
    >>> [t.get_text() for t in ax.texts if t.get_gid() == "critical"]
    ['unstable above |n| = 1.212', 'stable above |n| = 5.902']
    >>> pk.viz.pyplot().close(ax.figure)
    """
    _check_structure(structure)
    quantity = check_choice("quantity", quantity, QUANTITIES)
    if ax is None:
        from .output import pyplot

        ax = pyplot().subplots(figsize=(8.0, 6.2), layout="constrained")[1]
    _check_ax(ax)
    if structure.degenerate is not None:
        ax.text(0.5, 0.5, f"degenerate: {structure.degenerate}", transform=ax.transAxes, ha="center", va="center",
                wrap=True, fontsize=9)
    words = set()
    for k, b in enumerate(structure.branches):
        words |= _draw_branch(ax, k, b, quantity)
    top = _top(structure, quantity)
    drawn = _draw_ends(ax, structure, quantity) | _draw_families(ax, structure, quantity, top)
    ax.set_xlim(-0.03 * math.pi, 1.03 * math.pi)
    ax.set_ylim((-0.04 * top, top) if quantity == "Omega" else (-top, top))
    ax.axhline(0.0, color="0.8", lw=0.6, zorder=0)
    ax.set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi], ["0", "pi/4", "pi/2", "3pi/4", "pi"])
    ax.set_xlabel(label("theta"))
    ax.set_ylabel(label(quantity))
    ax.grid(alpha=0.25)
    if not ax.get_title():
        ax.set_title(f"{structure.body!r}\n{law_text(structure.model.friction)}: {structure.signature}", fontsize=9)
    _legend(ax, structure, quantity, words, drawn)
    return ax


def _check_structure(structure) -> None:
    from ..steady.structure import SteadyStructure

    if not isinstance(structure, SteadyStructure):
        raise ParameterError("structure", "must be what phasekit.steady_structure returned", structure)
    if structure.status.value == "failed":
        raise ParameterError("structure", f"must have completed (it failed: {structure.reason})", show_value=False)
    if any(not b.theta.size for b in structure.branches):
        raise ParameterError("structure", "must carry its samples (steady_structure(..., samples=True))",
                             show_value=False)


def stability_runs(words) -> list[tuple[int, int, str]]:
    """The stretches of one word in ``words`` (one per sample): (first, last, word), each sharing
    its last sample with the next stretch's first.

    Examples
    --------
    >>> from phasekit.viz.structure import stability_runs
    >>> stability_runs(["stable", "stable", "unstable", "unstable"])
    [(0, 2, 'stable'), (2, 3, 'unstable')]
    """
    out, start = [], 0
    for k in range(1, len(words) + 1):
        if k == len(words) or words[k] != words[start]:
            out.append((start, min(k, len(words) - 1), words[start]))
            start = k
    return out


def _draw_branch(ax, k: int, b, quantity: str) -> set:
    words = [state_word(p) for p in b.points] if b.points else ["unknown"] * b.theta.size
    y = getattr(b, quantity)
    for i, j, word in stability_runs(words):
        lw = 1.2 if word == "unknown" else 2.0
        ax.plot(b.theta[i:j + 1], y[i:j + 1], STYLES[word], color=COLOURS[word], lw=lw, gid=f"branch {k}")
    for c in b.changes:
        ax.plot(c.theta, getattr(c, quantity), "o", color=CRITICAL, ms=4, mec="k", mew=0.5, zorder=5, gid="change")
    return set(words)


def _top(structure, quantity: str) -> float:
    """The top of the vertical axis: the branches' bulk (not their divergence at an asymptote),
    their ends, and (spin) the families' critical spins."""
    ys = [np.abs(getattr(b, quantity)) for b in structure.branches]
    ys = np.concatenate(ys) if ys else np.zeros(1)
    ys = ys[np.isfinite(ys)]
    top = 2.0 * float(np.median(ys)) if ys.size else 1.0
    for b in structure.branches:
        for e in b.ends:
            v = e.Omega if quantity == "Omega" else e.n
            if v is not None and math.isfinite(v):
                top = max(top, 1.3 * abs(v))
    for f in structure.families:
        if f.parameter == quantity and f.criticals:
            top = max(top, 1.3 * max(f.criticals))
    return max(top, 1.0)


def _end_value(b, end, first: bool, quantity: str):
    v = end.Omega if quantity == "Omega" else end.n
    if v is None or not math.isfinite(v):
        y = getattr(b, quantity)
        v = y[0] if first else y[-1]
    return float(v)


def _draw_ends(ax, structure, quantity: str) -> set:
    """The ends' markers, the asymptotes and the switches; returns the kinds drawn."""
    kinds = set()
    for b in structure.branches:
        for first, e in ((True, b.ends[0]), (False, b.ends[1])):
            kinds.add(e.kind)
            v = e.Omega if quantity == "Omega" else e.n
            if e.kind == "infinite-spin" or (e.kind == "limit" and v is not None and not math.isfinite(v)):
                ax.axvline(e.theta, color="0.45", ls=(0, (1, 3)), lw=1.0, gid="asymptote")
                ax.annotate("theta_inf" if e.kind == "infinite-spin" else e.limit, (e.theta, 0.97),
                            xycoords=("data", "axes fraction"), fontsize=7, ha="center", va="top", color="0.3",
                            backgroundcolor="white")
                kinds.add("diverges")
                continue
            ax.plot(e.theta, _end_value(b, e, first, quantity), END_MARKERS[e.kind], color="k", ms=4.5, zorder=9,
                    gid="end")
            if e.kind == "switch" and not first:
                ax.axvline(e.theta, color="0.7", lw=0.8, zorder=0, gid="switch")
                ax.annotate(f"{b.piece} | {e.to_piece}", (e.theta, 0.03), xycoords=("data", "axes fraction"),
                            fontsize=7, ha="center", color="0.35",
                            bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none"))
    return kinds


def _family_y(structure, f, quantity: str, c: float) -> list[float]:
    """Where the critical value ``c`` of the family ``f`` is marked: on its own axis at +-c (the
    spin's sign does not matter) or +c; off it at the end of a branch that meets the family
    there, else at 0."""
    if f.parameter == quantity:
        return [c, -c] if quantity == "n" else [c]
    meet = [_end_value(b, e, e is b.ends[0], quantity) for b in structure.branches for e in b.ends
            if e.kind == "pole" and e.theta == f.theta and e.n is not None and math.isclose(abs(e.n), c, rel_tol=1e-6)]
    return meet[:1] or [0.0]


def _draw_families(ax, structure, quantity: str, top: float) -> set:
    """The families at their theta; returns what was drawn ("family", "critical")."""
    law, drawn = structure.model.friction, set()
    for f in structure.families:
        if f.parameter == quantity:  # a line along its own parameter, styled by its stability
            edges = [0.0, *f.criticals, 2.0 * top]
            for sign in ((1.0, -1.0) if quantity == "n" else (1.0,)):
                for lo, hi, side in zip(edges[:-1], edges[1:], f.stable_on):
                    word = family_word(side, law)
                    ax.plot([f.theta] * 2, [sign * lo, sign * hi], STYLES[word], color=COLOURS[word], lw=1.0,
                            alpha=0.8, gid="family")
        elif f.kind == "pole":  # the spin about the vertical: any rate, only its spin decides
            ax.axvline(f.theta, color="0.55", lw=0.8, zorder=1, gid="family")
        else:  # at rest in this plane (straight rolling: Omega = 0; a precession family: n = 0)
            ax.plot(f.theta, 0.0, "x", color="0.3", ms=7, mew=1.2, zorder=8, gid="family")
        drawn.add("family " + ("line" if f.parameter == quantity else "pole" if f.kind == "pole" else "point"))
        for i, c in enumerate(f.criticals):
            drawn.add("critical")
            ys = _family_y(structure, f, quantity, c)
            ax.plot([f.theta] * len(ys), ys, "D", color=CRITICAL, ms=8, mec="k", mew=0.6, zorder=7, gid="critical")
            sym = "n" if f.parameter == "n" else "Omega"
            text = f"{_word_above(f.stable_on[i + 1], law)} above |{sym}| = {c:.4g}"
            right = f.theta > 0.5 * math.pi
            ax.annotate(text, (f.theta, ys[0]), xytext=(-8 if right else 8, 6), textcoords="offset points",
                        ha="right" if right else "left", fontsize=8, color="0.15", gid="critical", zorder=8,
                        bbox=dict(boxstyle="round,pad=0.2", fc="white", ec=CRITICAL, lw=0.6, alpha=0.9))
    return drawn


def _word_above(side, law) -> str:
    word = family_word(side, law)
    return "stability not computed" if word == "unknown" else word


def _legend(ax, structure, quantity: str, words: set, drawn: set) -> None:
    from matplotlib.lines import Line2D

    law = structure.model.friction
    handles = [Line2D([], [], ls=STYLES[w], color=COLOURS[w], lw=2.0,
                      label=legend_label(w, law_text(law), rolling=law.has_rolling_mode))
               for w in (*WORDS, "unknown") if w in words]
    handles += [Line2D([], [], ls="none", marker=END_MARKERS[k], color="k", ms=5, label=END_WORDS[k])
                for k in END_MARKERS if k in drawn]
    if "diverges" in drawn:
        handles.append(Line2D([], [], ls=(0, (1, 3)), color="0.45", label="where the rate diverges (theta_inf: "
                              "infinite-spin asymptote; a limit of the range)"))
    if any(b.changes for b in structure.branches):
        handles.append(Line2D([], [], ls="none", marker="o", color=CRITICAL, mec="k", ms=4,
                              label="change of stability along a branch"))
    handles += [Line2D([], [], color="0.55", lw=0.8, ls="none" if k == "point" else "-", marker="x" if k == "point" else "",
                       label=FAMILY_WORDS[k]) for k in FAMILY_WORDS if f"family {k}" in drawn]
    if "critical" in drawn:
        handles.append(Line2D([], [], ls="none", marker="D", color=CRITICAL, mec="k", ms=7,
                              label="critical value of a family (where its stability changes)"))
    if handles:
        ax.legend(handles=handles, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
