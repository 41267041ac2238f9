"""Figures of atlases of steady-state structure (:mod:`phasekit.studies.atlas`): the classes over each
panel's plane with the traced boundaries between them (:func:`plot_atlas`), and the branches
Omega(theta), n(theta) of one body of each class (:func:`plot_classes`), in the colours of
:func:`signature_colours`. matplotlib is imported by the functions that draw.
"""

from __future__ import annotations

import math

import numpy as np

from ..viz.output import pyplot

BIFURCATION_MARKERS = ("o", "s", "^", "D", "v", "P", "X")
CHANGE = "#fdae61"


def signature_colours(signatures) -> dict:
    """One colour per signature (tab20, in sorted order), the same in every figure.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> list(ps.signature_colours({"b", "a"}))
    ['a', 'b']
    """
    cmap = pyplot().get_cmap("tab20")
    return {sig: cmap(k % 20) for k, sig in enumerate(sorted(signatures))}


def _edges(rng, n, log):
    return np.geomspace(rng[0], rng[1], n + 1) if log else np.linspace(rng[0], rng[1], n + 1)


def plot_atlas(rows, bounds, panels: dict, colours: dict, *, n: int, note: str, closed_forms: dict | None = None):
    """Each panel's n x n grid (``panels``: name -> :class:`phasekit.studies.AtlasPanel`, up to four;
    ``rows``: :class:`phasekit.studies.AtlasRow`) as cells coloured by signature (``colours``), the
    traced boundary points on top (``bounds``: :class:`phasekit.studies.BoundaryRow`; marker: the
    bifurcation). ``closed_forms`` maps a panel to ``(curves, text)``: curves (x, y) drawn as
    white dashes, and the text that says what they are.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> P = {"demo": ps.AtlasPanel("demo", "x", "y", (0.0, 1.0), (0.0, 1.0), False, False)}
    >>> rows = [ps.AtlasRow(str(x), "demo", float(x), 0.5, 0.0, "A", "completed") for x in ps.axis_values((0, 1), 1, False)]
    >>> fig = ps.plot_atlas(rows, [], P, ps.signature_colours({"A"}), n=1, note="demo")
    >>> len(fig.axes)
    4
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from .atlas import axis_values, is_class

    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(13.5, 12))
    names = sorted({b.bifurcation for b in bounds})
    order = sorted(colours)
    cmap = ListedColormap([colours[s] for s in order])
    for ax, (panel, (title, xl, yl, xr, yr, logx, logy)) in zip(axes.ravel(), panels.items()):
        pts = [r for r in rows if r.panel == panel]
        xs, ys = axis_values(xr, n, logx), axis_values(yr, n, logy)
        ix = {float(x): i for i, x in enumerate(xs)}
        iy = {float(y): j for j, y in enumerate(ys)}
        grid = np.full((n, n), np.nan)
        for r in pts:
            if r.x in ix and r.y in iy:
                grid[iy[r.y], ix[r.x]] = order.index(r.signature)
        ax.pcolormesh(_edges(xr, n, logx), _edges(yr, n, logy), grid, cmap=cmap, vmin=-0.5, vmax=len(order) - 0.5)
        for k, name in enumerate(names):
            sel = np.array([[b.x, b.y] for b in bounds if b.panel == panel and b.bifurcation == name]).reshape(-1, 2)
            if len(sel):
                ax.scatter(sel[:, 0], sel[:, 1], s=10, marker=BIFURCATION_MARKERS[k % len(BIFURCATION_MARKERS)],
                           color="black", edgecolors="none")
        if panel in (closed_forms or {}):
            curves, text = closed_forms[panel]
            for x, y in curves:
                ax.plot(x, y, "w--", lw=1.4)
            ax.annotate(text, (0.03, 0.03), xycoords="axes fraction", fontsize=8, color="white")
        present = sorted({r.signature for r in pts})
        ax.legend(handles=[Patch(color=colours[s], label=s) for s in present], fontsize=7, loc="upper right", framealpha=0.9)
        ax.set(xlabel=xl, ylabel=yl, xlim=xr, ylim=yr, title=f"{title}: {len([s for s in present if is_class(s)])} classes")
        _scales(ax, logx, logy)
    handles = [plt.Line2D([], [], ls="none", marker=BIFURCATION_MARKERS[k % len(BIFURCATION_MARKERS)], color="black",
                          label=name) for k, name in enumerate(names)]
    fig.legend(handles=handles, loc="lower center", fontsize=8, ncol=1, frameon=False,
               title="boundaries between classes, traced by bisection on the signature")
    fig.suptitle("Classes of steady-state structure (signature: the branches' ends in theta order)\n" + note, fontsize=11)
    fig.tight_layout(rect=(0, 0.05 + 0.018 * len(names), 1, 0.95))
    return fig


def _scales(ax, logx, logy) -> None:
    from matplotlib.ticker import ScalarFormatter

    ax.set_xscale("log" if logx else "linear")
    ax.set_yscale("log" if logy else "linear")
    for axis in ((ax.xaxis,) if logx else ()) + ((ax.yaxis,) if logy else ()):
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(ScalarFormatter())
        ax.tick_params(which="minor", labelsize=7)


def plot_classes(structures: dict, *, note: str, law: str | None = None):
    """Omega(theta) (solid) and n(theta) (dashed) of each structure (``structures``: signature ->
    :class:`phasekit.steady.SteadyStructure` with stability), coloured by the stability
    vocabulary of :mod:`phasekit.viz.stability` (stable, neutral, undecided, unstable; under exact
    Coulomb friction no state is stable: the rolling field's are neutral), up to three to a row
    with one panel per structure: changes of stability, pole ends (spin n) and static ends
    marked, the infinite-spin ends dotted. ``law``: how the legend names the friction law
    (default: from the structures).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    >>> fig = ps.plot_classes({s.signature: s}, note="demo")
    >>> len(fig.axes)
    1
    """
    from ..viz.stability import COLOURS, WORDS, law_text, legend_label, state_word

    plt = pyplot()
    n = len(structures)
    cols = max(1, min(3, n))
    rows_ = max(1, math.ceil(n / cols))
    height = 3.9 * rows_ + (0.0 if cols == 3 else 0.8)  # fewer panels: room for a legend in rows
    fig, axes = plt.subplots(rows_, cols, figsize=(max(5.2 * cols, 8.0), height), squeeze=False)
    present = set()  # (word, legend label)
    for ax, (sig, s) in zip(axes.ravel(), structures.items()):
        top = 1.0
        friction = s.model.friction
        for b in s.branches:
            words = [state_word(p) for p in b.points]
            present.update((w, legend_label(w, law_text(friction) if law is None else law,
                                            rolling=friction.has_rolling_mode)) for w in words)
            for y, ls in ((b.Omega, "-"), (b.n, "--")):
                for seg, word in _runs(b.theta, y, words):
                    ax.plot(seg[0], seg[1], ls, color=COLOURS[word], lw=1.6)
            top = max(top, float(np.quantile(np.abs(b.Omega), 0.7)) * 1.8)
            for c in b.changes:
                ax.plot([c.theta] * 2, [c.Omega, c.n], "o", color=CHANGE, ms=4, zorder=5)
            _ends(ax, b.ends)
        ax.axhline(0, color="0.7", lw=0.6)
        ax.set(xlim=(0, math.pi), ylim=(-top, top), xlabel=r"$\theta$ (rad)", ylabel=r"$\Omega$, $n$ ($\sqrt{g/b}$)")
        ax.set_title(f"{sig}\n{s.body!r}", fontsize=8)
    for ax in axes.ravel()[n:]:
        ax.remove()
    handles = [plt.Line2D([], [], color="k", ls="-", label=r"$\Omega(\theta)$"),
               plt.Line2D([], [], color="k", ls="--", label=r"$n(\theta)$"),
               *[plt.Line2D([], [], color=COLOURS[w], label=text) for w, text in
                 sorted(present, key=lambda p: (WORDS.index(p[0]), p[1]))],
               plt.Line2D([], [], ls="none", marker="o", color="k", label="pole end (spin n)"),
               plt.Line2D([], [], ls="none", marker="^", color="k", label="static end")]
    if any(b.changes for s in structures.values() for b in s.branches):
        handles.insert(-2, plt.Line2D([], [], ls="none", marker="o", color=CHANGE, label="change of stability"))
    ncol = len(handles) if cols == 3 else math.ceil(len(handles) / 3)
    fig.legend(handles=handles, loc="lower center", ncol=ncol, fontsize=8, frameon=False)
    bodies = [repr(s.body) for s in structures.values()]
    what = f"One body of each of {n} classes" if n > 1 else f"The steady-state structure of {bodies[0]}" if n else "None"
    fig.suptitle(f"{what}: steady precessions " + r"$\Omega(\theta)$, $n(\theta)$" + "\n" + note, fontsize=10)
    legend_rows = math.ceil(len(handles) / ncol)
    fig.tight_layout(rect=(0, max(0.03, (0.25 * legend_rows + 0.1) / height), 1, 0.95 if cols == 3 else 1.0))
    return fig


def _ends(ax, ends) -> None:
    for e in ends:
        if e.kind == "infinite-spin":
            ax.axvline(e.theta, color="0.4", ls=":", lw=1)
            ax.annotate(r"$\theta_\infty$", (e.theta, 0.93), xycoords=("data", "axes fraction"), fontsize=8)
        elif e.kind == "static":
            ax.plot(e.theta, 0.0, "k^", ms=6)
        else:
            ax.plot([e.theta] * 2, [e.Omega, e.n], "ko", ms=5)
            ax.annotate(f"n = {e.n:.3g}", (e.theta, e.n), fontsize=7, xytext=(4, 4), textcoords="offset points")


def _runs(x, y, flags):
    """Runs of equal ``flags`` (each sharing its last point with the next)."""
    out, start = [], 0
    for k in range(1, len(x) + 1):
        if k == len(x) or flags[k] != flags[start]:
            out.append(((x[start:k + 1], y[start:k + 1]), flags[start]))
            start = k
    return out
