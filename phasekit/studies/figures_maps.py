"""Figures of the sweep studies' results (maps over parameters): the outcome map of sliding-branch
starts and its traced boundaries (:func:`plot_outcome_map`), the jump region in 3-D
(:func:`render_jump_region`), jump-threshold curves against the aspect ratio
(:func:`plot_threshold_curves`, :func:`plot_threshold_map`), the linear-stability map of the
steady states (:func:`plot_stability_map`), the paper's printed pairs against the
regularisation of Coulomb friction (:func:`plot_pair_scan`), and eggs: which end rises over
(asymmetry, start) (:func:`plot_which_end`), thresholds against a body parameter
(:func:`plot_threshold_against`), and flights in real units against experiment
(:func:`plot_flights`).

Each takes the stored rows of :mod:`phasekit.studies.maps` (:class:`phasekit.studies.OutcomeRow`,
:class:`phasekit.studies.SearchRow`, :class:`phasekit.studies.ThresholdRow`) and returns a
matplotlib figure for :meth:`phasekit.sweep.Study.save` (the 3-D scene writes its PNG itself).
matplotlib and pyvista are imported by the functions that draw.
"""

from __future__ import annotations

import math

import numpy as np

from ..viz.mpl import plain_log_ticks
from ..viz.output import pyplot

__all__ = ["OUTCOME_COLOURS", "plot_outcome_map", "render_jump_region", "plot_threshold_curves", "plot_threshold_map",
           "plot_stability_map", "plot_pair_scan", "plot_which_end", "plot_threshold_against", "plot_flights"]

#: the colour of each outcome class of an :class:`phasekit.studies.OutcomeRow`
OUTCOME_COLOURS = {"stuck": "0.6", "rise": "#4c72b0", "jump": "#dd8452", "slow": "#8172b3", "failed": "k"}


def _at(rows, a):
    return [r for r in rows if abs(r.a - a) < 1e-12]


# -- the outcome map ------------------------------------------------------------------------------


def plot_outcome_map(points, searches, maps, *, d_top: float, title: str):
    """The outcome map of sliding-branch starts, one column per aspect ratio in ``maps``: the
    class of every sampled start (``points``, :class:`phasekit.studies.OutcomeRow`) over (family
    parameter, seed distance d), with the traced boundaries (``searches``,
    :class:`phasekit.studies.SearchRow`: jump thresholds along d-lines, sticking boundaries d_min
    along value-lines, an arrow at ``d_top`` where a value-line sticks at every d); below, the
    jumping starts coloured by the share of the rise done at the jump (numbers: t*).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> rows = ps.outcome_task(None, [(1.5, 0.01, 12.0), (1.5, 0.02, 4.0)], asdict(pk.Definition("sliding", "sliding")))
    >>> fig = ps.plot_outcome_map(rows, [], [1.5], d_top=0.2, title="demo")
    >>> len(fig.axes)
    3
    """
    plt = pyplot()
    fig, axes = plt.subplots(2, len(maps), figsize=(6.6 * len(maps), 10.5), squeeze=False)
    for col, a in enumerate(maps):
        pts, mine = _at(points, a), _at(searches, a)
        name = r"\Omega_0" if a > 1 else "n_0"
        ax = axes[0, col]
        for kind, c in OUTCOME_COLOURS.items():
            sel = [(p.value, p.d) for p in pts if p.outcome == kind]
            if sel:
                ax.scatter(*zip(*sel), s=22, marker="s", color=c, label=kind, edgecolors="none")
        _boundaries(ax, mine, d_top)
        ax.set_title(f"a = {a:.4g} ({'prolate' if a > 1 else 'oblate'}): outcome of each start", fontsize=10)
        ax2 = axes[1, col]
        _jump_shares(fig, ax2, [p for p in pts if p.outcome == "jump" and p.rise_fraction is not None])
        _boundaries(ax2, mine, d_top, legend=False)
        ax2.set_title("jumping starts: share of the rise done at the jump (numbers: t*)", fontsize=10)
        for axx in (ax, ax2):
            axx.set_xscale("log")
            axx.set_yscale("log")
            axx.set_xlabel(f"${name}$ (units $\\sqrt{{g/b}}$)")
            axx.set_ylabel(r"seed distance $d$ from the fixed point (rad)")
            axx.grid(alpha=0.3, which="both")
            plain_log_ticks(axx, "x")
            plain_log_ticks(axx, "y", subs=())
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=8, frameon=False)
    for ax in axes[1]:
        ax.set_xlim(axes[0, list(axes[1]).index(ax)].get_xlim())
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    return fig


def _jump_shares(fig, ax, jp) -> None:
    from matplotlib import patheffects

    if not jp:
        return
    sc = ax.scatter([p.value for p in jp], [p.d for p in jp], c=[p.rise_fraction for p in jp], s=22, marker="s",
                    cmap="magma", vmin=0.0, vmax=1.0, edgecolors="none")
    fig.colorbar(sc, ax=ax, label="share of the rise done at the jump")
    for p in jp[:: max(1, len(jp) // 14)]:
        ax.annotate(f"{p.t_jump:.0f}", (p.value, p.d), fontsize=7, color="black", xytext=(2, 2), textcoords="offset points",
                    path_effects=[patheffects.withStroke(linewidth=2.2, foreground="white")])


def _boundaries(ax, searches, d_top, legend=True) -> None:
    th = sorted((s.d, s) for s in searches if s.kind == "threshold" and s.threshold)
    if th:
        ax.errorbar([s.threshold for _, s in th], [d for d, _ in th],
                    xerr=[[s.threshold - s.bracket_lo for _, s in th], [s.bracket_hi - s.threshold for _, s in th]],
                    fmt="o-", color="k", ms=4, lw=1.2, label="jump threshold (bisection)" if legend else None)
    above = [s.value for s in searches if s.kind == "stick" and s.status == "no_jump_in_range"]
    if above:  # stuck at every d up to d_top: d_min lies above the map
        ax.plot(above, [d_top] * len(above), ls="none", marker=r"$\uparrow$", ms=12, color="crimson",
                label=f"stuck for every d \u2264 {d_top:g}" if legend else None)
    st = sorted((s.value, s) for s in searches if s.kind == "stick" and s.threshold)
    if st:
        ax.errorbar([v for v, _ in st], [s.threshold for _, s in st],
                    yerr=[[s.threshold - s.bracket_lo for _, s in st], [s.bracket_hi - s.threshold for _, s in st]],
                    fmt="D--", color="crimson", ms=4, lw=1.2, label="sticking boundary $d_{min}$ (bisection)" if legend else None)


# -- the jump region in 3-D -----------------------------------------------------------------------


def render_jump_region(points, searches, path, *, scene_a, value_range, d_range, threshold_d, stick_values,
                       caption: str, quick: bool = False) -> dict:
    """The jump region over (a, family parameter, d), one view per branch, in a box of
    (a, log10 value, log10 d): the threshold surface value*(a, d) through the traced jump
    thresholds at the seed distances ``threshold_d`` (the same for every a), and the sticking
    surface d_min(a, value) through the traced sticking boundaries at ``stick_values(a)``
    (``searches``: :class:`phasekit.studies.SearchRow`), with the jumping starts of ``points``
    coloured by t*. The box spans ``value_range(a)`` for a in ``scene_a`` and ``d_range``
    (down to the lowest d_min). ``caption`` (``{name}``: the family parameter) is printed
    under the title. Writes the PNG ``path``; returns per branch the nodes drawn.

    Examples
    --------
    >>> import phasekit as pk, tempfile, pathlib, phasekit.studies as ps
    >>> counts = ps.render_jump_region([], [], pathlib.Path(tempfile.mkdtemp()) / "r.png", scene_a=[0.6, 1.5],
    ...     value_range=lambda a: (5.0, 60.0), d_range=(1e-3, 0.2), threshold_d=[0.01, 0.1], stick_values=lambda a: [10.0],
    ...     caption="{name}: a demo")
    >>> counts["prolate"]
    {'threshold_points': 0, 'stick_points': 0, 'jump_starts': 0}
    """
    import pyvista as pv

    pv.OFF_SCREEN = True
    pl = pv.Plotter(off_screen=True, window_size=[1800, 900], shape=(1, 2), border=False)
    counts = {}
    for col, (branch, sel, name) in enumerate((("prolate", lambda a: a > 1, "Omega0"), ("oblate", lambda a: a < 1, "n0"))):
        pl.subplot(0, col)
        pl.set_background("white")
        sa = [a for a in scene_a if sel(a)]
        lv = [math.log10(x) for a in sa for x in value_range(a)]
        mine = [s for s in searches if any(abs(s.a - a) < 1e-12 for a in sa)]
        d_lo = min([d_range[0]] + [s.threshold for s in mine if s.kind == "stick" and s.threshold])
        box = dict(a=(min(sa), max(sa)), v=(min(lv), max(lv)), d=(math.log10(d_lo), math.log10(d_range[1])))
        to_box = _box_map(box)
        th = {(a, j): _find(mine, "threshold", a, d=d) for a in sa for j, d in enumerate(threshold_d)}
        st = {(a, j): (v, _find(mine, "stick", a, value=v)) for a in sa for j, v in enumerate(stick_values(a))}
        drawn = [_add_surface(pl, [[None if th[a, j] is None else to_box(a, th[a, j], d) for j, d in enumerate(threshold_d)]
                                   for a in sa], "#dd8452", "#8c4a1f", "jump threshold"),
                 _add_surface(pl, [[None if st[a, j][1] is None else to_box(a, st[a, j][0], st[a, j][1])
                                    for j in range(len(stick_values(a)))] for a in sa], "#8c8c8c", "#404040",
                              "sticking boundary d_min")]
        jp = [p for p in points if p.outcome == "jump" and sel(p.a)]
        _jump_cloud(pl, pv, [to_box(p.a, p.value, p.d) for p in jp], [p.t_jump for p in jp])
        pl.add_mesh(pv.Box(bounds=(0, 1.4, 0, 1, 0, 1)).extract_all_edges(), color="black", line_width=1)
        pl.show_grid(bounds=[0, 1.4, 0, 1, 0, 1], axes_ranges=[*box["a"], *box["v"], *box["d"]], color="black", fmt="%.2f",
                     xtitle="aspect ratio a", ytitle=f"log10({name} / sqrt(g/b))", ztitle="log10(d / rad)", font_size=15,
                     n_xlabels=4)
        if any(drawn):  # the legend names the surfaces
            pl.add_legend(bcolor="white", face="rectangle", size=(0.26, 0.08), loc="lower left")
        pl.add_text(f"{branch}, a = {min(sa):.3g} ... {max(sa):.3g}: a start jumps above both surfaces" + (" (quick run)" if quick else ""),
                    position=(0.03, 0.95), viewport=True, font_size=13, color="black")
        pl.add_text(caption.format(name=name), position=(0.03, 0.845), viewport=True, font_size=10, color="black")
        pl.camera_position = [(4.2, -1.5, 1.7), (0.7, 0.5, 0.42), (0, 0, 1)]  # value to the right, d up
        counts[branch] = {"threshold_points": sum(v is not None for v in th.values()),
                          "stick_points": sum(v[1] is not None for v in st.values()), "jump_starts": len(jp)}
    pl.screenshot(str(path))
    pl.close()
    return counts


def _add_surface(pl, grid, color, edge_color, label) -> bool:
    surf = _grid_surface(grid)
    if surf is not None:
        pl.add_mesh(surf, color=color, opacity=0.8, show_edges=True, edge_color=edge_color, label=label)
    return surf is not None


def _jump_cloud(pl, pv, xyz, t_jump) -> None:
    if not xyz:
        return
    cloud = pv.PolyData(np.array(xyz))
    cloud["t* (jump time)"] = np.array(t_jump)
    pl.add_mesh(cloud, scalars="t* (jump time)", cmap="viridis", point_size=5, render_points_as_spheres=True, clim=(0, 60),
                scalar_bar_args=dict(color="black", vertical=True, position_x=0.91, position_y=0.25, width=0.035, height=0.42,
                                     title="t*", n_labels=5, fmt="%.0f", title_font_size=16, label_font_size=13))


def _box_map(box):
    def to_box(a, v, d):
        return [(a - box["a"][0]) / (box["a"][1] - box["a"][0]) * 1.4, (math.log10(v) - box["v"][0]) / (box["v"][1] - box["v"][0]),
                (math.log10(d) - box["d"][0]) / (box["d"][1] - box["d"][0])]

    return to_box


def _find(searches, kind, a, d=None, value=None):
    """The traced boundary of one scene grid node (None where there is none)."""
    for s in searches:
        if s.kind == kind and abs(s.a - a) < 1e-12 and s.threshold is not None:
            if (d is not None and s.d is not None and abs(s.d / d - 1) < 1e-9) or (
                    value is not None and s.value is not None and abs(s.value / value - 1) < 1e-9):
                return s.threshold
    return None


def _grid_surface(grid):
    """A surface from a grid of 3-D points (rows: aspect ratios), None marking missing
    nodes: the quads whose four corners exist, as triangles."""
    import pyvista as pv

    index, pts, faces = {}, [], []
    for i, row in enumerate(grid):
        for j, p in enumerate(row):
            if p is not None:
                index[i, j] = len(pts)
                pts.append(p)
    for (i, j) in list(index):
        quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
        if all(q in index for q in quad):
            k = [index[q] for q in quad]
            faces += [3, k[0], k[1], k[2], 3, k[0], k[2], k[3]]
    if not faces:
        return None
    return pv.PolyData(np.asarray(pts, dtype=float), faces=np.asarray(faces))


# -- jump thresholds against the aspect ratio ------------------------------------------------------


def plot_threshold_curves(rows, definitions, *, default: str, styles: dict, hi: float, brackets: dict, title: str):
    """Jump thresholds against the aspect ratio (Figure 6b,c): Omega0*(a) prolate (left), n0*(a)
    oblate (right), one curve per definition (``rows``: :class:`phasekit.studies.ThresholdRow` of
    group "main"; ``styles``: the plot keywords per definition name; ``default``: the name of
    the default definition). A definition that does not jump up to ``hi`` is an arrow at ``hi``;
    ``brackets`` maps an aspect ratio to the paper's (no jump, jump) pair of single runs.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> d = pk.Definition('sliding', 'sliding')
    >>> row = ps.threshold_task(None, asdict(d), 1.5, 'main', True, dict(hi=120.0, tol=0.05))
    >>> fig = ps.plot_threshold_curves([row], [d], default='sliding', styles={'sliding': {}}, hi=120.0,
    ...                                    brackets={1.5: (10.2, 10.5)}, title='demo')
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6))
    main = [r for r in rows if r.group == "main"]
    for ax, branch in zip(axes, ("prolate", "oblate")):
        for defn in definitions:
            pts = sorted(((r.a, r) for r in main if r.name == defn.name and r.branch == branch), key=lambda q: q[0])
            if not pts:
                continue
            ok = [(a, r.threshold) for a, r in pts if r.threshold is not None]
            label = defn.label + (" [default]" if defn.name == default else "")
            none = [a for a, r in pts if r.status == "no_jump_in_range"]
            if ok:
                ax.plot(*zip(*ok), label=label, **styles.get(defn.name, {}))
            if none:
                ax.plot(none, [hi] * len(none), ls="none", marker=r"$\uparrow$", ms=10, color=styles[defn.name]["color"],
                        label=(label + f": no jump up to {hi:g}") if not ok else None)
        for a, (lo, up) in brackets.items():
            if (a > 1) == (branch == "prolate"):
                ax.errorbar([a], [0.5 * (lo + up)], yerr=[[0.5 * (up - lo)]], fmt="D", color="m", ms=5, capsize=3,
                            label="paper Fig. %s: bracket from two runs" % ("4" if a > 1 else "3"))
        ax.set_yscale("log")
        ax.axvline(1.0, color="0.7", ls=":")
        ax.set_xlabel(r"aspect ratio $a$")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel(r"threshold precession rate $\Omega_0$ (units $\sqrt{g/b}$)")
    axes[1].set_ylabel(r"threshold spin $n_0$ (units $\sqrt{g/b}$)")
    axes[0].set_title(r"prolate, from the horizontal precession (cf. Fig. 6b)", fontsize=10)
    axes[1].set_title(r"oblate, from the vertical spin (cf. Fig. 6c)", fontsize=10)
    for ax in axes:
        ax.set_ylim(4.0, 1.6 * hi)
    handles = {}
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=2, fontsize=8, frameon=False)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.17, 1, 1))
    return fig


def _log_thresholds(ax) -> None:
    ax.set_yscale("log")
    plain_log_ticks(ax, "y", subs=(2, 3, 4, 5, 6, 7, 8))


def plot_threshold_map(rows, mus, collapse: dict, *, d0: float, d_lines: dict, d_mu, title: str):
    """Jump thresholds over (a, mu) (``rows``: :class:`phasekit.studies.SearchRow`, one colour per
    mu in ``mus``): top, threshold(a) per branch at the seed distance ``d0``; bottom left, the
    collapse test (each curve divided by the fitted f(mu) of ``collapse``, as
    :func:`phasekit.studies.threshold_collapse` gives it); bottom right, threshold against d at the
    aspect ratios ``d_lines["a"]`` (solid, dashed) for the mu in ``d_mu``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fig = ps.plot_threshold_map([], [0.1], {}, d0=0.01, d_lines={"a": [1.5], "d": [0.005, 0.01]}, d_mu=[0.1],
    ...                                 title="demo")
    >>> len(fig.axes)
    4
    """
    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    cmap = plt.get_cmap("viridis")
    colour = {mu: cmap(i / max(1, len(mus) - 1)) for i, mu in enumerate(mus)}
    main = [r for r in rows if r.d == d0]
    for ax, branch in zip(axes[0], ("prolate", "oblate")):
        for mu in mus:
            pts = sorted((r.a, r.threshold) for r in main if r.branch == branch and r.mu == mu and r.threshold)
            if pts:
                ax.plot(*zip(*pts), "o-", color=colour[mu], ms=4, label=fr"$\mu$ = {mu:.3g}")
        _log_thresholds(ax)
        ax.set_xlabel(r"aspect ratio $a$")
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].set_ylabel(r"threshold $\Omega_0^*$ (units $\sqrt{g/b}$)")
    axes[0, 1].set_ylabel(r"threshold $n_0^*$ (units $\sqrt{g/b}$)")
    axes[0, 0].set_title(r"prolate, from the horizontal precession ($\mu \leq 0.1$: curves nearly coincide)", fontsize=10)
    axes[0, 1].set_title("oblate, from the vertical spin", fontsize=10)
    if axes[0, 0].get_legend_handles_labels()[0]:  # an empty map has no curves to name
        axes[0, 0].legend(fontsize=8, ncol=2)
    _collapse_panel(axes[1, 0], main, mus, collapse, colour)
    ax = axes[1, 1]
    for a, ls in zip(d_lines["a"], ("-", "--")):
        for mu in d_mu:
            pts = sorted((r.d, r.threshold) for r in rows if abs(r.a - a) < 1e-12 and r.mu == mu and r.threshold)
            if len(pts) > 1:
                ax.plot(*zip(*pts), marker="o", ls=ls, color=colour.get(mu, "k"), ms=4)
        ax.plot([], [], ls=ls, color="0.3", label=f"a = {a:.3g}")  # line style only: colours are mu, as above
    ds = np.array([2.5e-3, 1e-2])
    ax.plot(ds, 30.0 * (ds / ds[0]) ** -0.5, "k:", lw=1, label=r"slope $-1/2$ ($d\,\Omega_0^2$ = const: the sticking boundary)")
    ax.set_xscale("log")
    _log_thresholds(ax)
    plain_log_ticks(ax, "x", subs=())
    ax.set_xticks(d_lines["d"], [f"{d:g}" for d in d_lines["d"]])
    ax.set_xlabel(r"seed distance $d$ from the fixed point (rad)")
    ax.set_ylabel(r"threshold $\Omega_0^*$ or $n_0^*$ (units $\sqrt{g/b}$)")
    ax.set_title(r"threshold against $d$ (one colour per $\mu$; solid a = 1.5, dashed a = 2/3)", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    return fig


def _collapse_panel(ax, main, mus, coll, colour) -> None:
    for branch, marker in (("prolate", "o"), ("oblate", "s")):
        for mu in mus:
            f = coll.get(branch, {}).get(mu, {}).get("f")
            if f is None:
                continue
            pts = sorted((r.a, r.threshold / f) for r in main if r.branch == branch and r.mu == mu and r.threshold)
            ax.plot(*zip(*pts), marker=marker, ls="-", color=colour[mu], ms=3, lw=0.8)
    _log_thresholds(ax)
    ax.set_xlabel(r"aspect ratio $a$")
    ax.set_ylabel(r"threshold / $f(\mu)$ (units $\sqrt{g/b}$)")
    spread = coll.get("max_spread")
    ax.set_title(r"collapse test: threshold / $f(\mu)$, $f$ fitted per $\mu$ and branch" + "\n"
                 + (f"remaining spread max |ln| = {spread:.3f} (raw, f = 1: {coll['max_raw_spread']:.3f})" if spread else ""),
                 fontsize=9)
    ax.grid(alpha=0.3, which="both")


# -- linear stability of the steady states ---------------------------------------------------------


def plot_stability_map(a_values, omegas, spins, horizontal, vertical, *, mu: float):
    """The dimension of the unstable subspace of the horizontal steady precession over (a, Omega0)
    (``horizontal``, rows: ``omegas``) and of the vertical spin over (a, n0) (``vertical``, rows:
    ``spins``), as :func:`phasekit.studies.stability_grid` gives them for uniform spheroids under
    viscous friction ``mu``, with the closed-form criteria drawn over them.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> a, s = np.linspace(0.5, 2.0, 3), np.linspace(1.0, 10.0, 3)
    >>> fig = ps.plot_stability_map(a, s, s, np.zeros((3, 3), int), np.zeros((3, 3), int), mu=0.1)
    >>> len(fig.axes)
    3
    """
    from ..bodies.body import Spheroid
    from ..theory.criteria import horizontal_stability_threshold, vertical_stability_threshold

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    cmap = plt.get_cmap("viridis", 3)
    for ax, M, ys, title, ylabel in [
        (axes[0], horizontal, omegas, "horizontal steady precession", r"precession rate $\Omega_0$ (units $\sqrt{g/b}$)"),
        (axes[1], vertical, spins, "vertical spin", r"spin $n_0$ (units $\sqrt{g/b}$)"),
    ]:
        im = ax.pcolormesh(a_values, ys, M, cmap=cmap, vmin=-0.5, vmax=2.5, shading="nearest")
        ax.axvline(1.0, color="w", lw=0.8, ls=":")
        ax.set_xlabel(r"aspect ratio $a$")
        ax.set_title(title, fontsize=10)
        ax.set_ylabel(ylabel)
    aa = np.linspace(a_values[0], a_values[-1], 300)
    axes[1].plot(aa, [vertical_stability_threshold(Spheroid(x).A, Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$n_0=\sqrt{5a^3}$: $(a^2C-A)n_0^2=a^3(a^2-1)$")
    axes[1].set_ylim(spins[0], spins[-1])
    axes[0].plot(aa, [horizontal_stability_threshold(Spheroid(x).A, Spheroid(x).C, x) or np.nan for x in aa],
                 "r--", lw=1.2, label=r"$\Omega_0=\sqrt{5}$: $(a^2C-A)\Omega_0^2=a^2-1$")
    axes[0].legend(loc="upper left", fontsize=8)
    axes[1].legend(loc="upper left", fontsize=8)
    cb = fig.colorbar(im, ax=axes, ticks=[0, 1, 2])
    cb.set_label("dimension of the unstable subspace")
    fig.suptitle(f"Linear stability, viscous friction $\\mu={mu:g}$, uniform spheroids (exact CasADi Jacobians)", fontsize=10)
    return fig


# -- the paper's printed pairs under regularisation --------------------------------------------------


def plot_pair_scan(rows, table, cases: dict, *, charts, t_end: float, t_tolerance: float, title: str):
    """The paper's single-trajectory pairs (``cases``: label -> :class:`phasekit.theory.PaperCase`,
    one panel each) against the regularisation eps of Coulomb friction: the jump time t* of each
    start that jumps (per chart in ``charts``: solid, dashed), markers above the axis for a start
    whose rise completes or that sticks by ``t_end``, the printed t* band (+- ``t_tolerance``),
    and green lines at the eps where ``table`` says the pair comes out as printed. ``rows``: one
    per run, with ``label``, ``role`` ("no_jump" or "jump"), ``chart``, ``eps`` (None: exact
    Coulomb, not drawn), ``outcome`` and ``t_jump``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Run
    >>> rows = [Run(label="5.2", role="jump", chart="euler", eps=1e-3, outcome="jump", t_jump=110.0)]
    >>> fig = ps.plot_pair_scan(rows, [], pk.theory.PAPER_CASES, charts=("euler",), t_end=600.0, t_tolerance=0.15,
    ...                             title="demo")
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.4))
    top = {"rise": 1.12 * t_end, "stuck": 1.22 * t_end, "slow": 1.22 * t_end, "failed": 1.3 * t_end}
    for ax, (label, case) in zip(axes, cases.items()):
        for chart, ls, dy in zip(charts, ("-", "--"), (1.0, 1.03)):
            for role, colour in (("no_jump", "C0"), ("jump", "C3")):
                value = case.no_jump if role == "no_jump" else case.jump
                pts = sorted(((r.eps, r) for r in rows if r.label == label and r.role == role and r.chart == chart
                              and r.eps is not None), key=lambda q: q[0])
                jumped = [(e, r.t_jump) for e, r in pts if r.outcome == "jump"]
                if jumped:
                    ax.plot(*zip(*jumped), marker="o", ls=ls, color=colour, ms=4,
                            label=f"{case.parameter} = {value:g} jumps at t* ({chart})")
                for kind, marker in (("rise", "o"), ("stuck", "x")):
                    sel = [e for e, r in pts if r.outcome == kind]
                    if sel:
                        y = top[kind] * dy + (0.0 if role == "no_jump" else 0.07 * t_end)
                        ax.plot(sel, [y] * len(sel), ls="none", marker=marker, mfc="none", color=colour, ms=6,
                                label=f"{case.parameter} = {value:g}: {'rises, no jump' if kind == 'rise' else 'sticks, no rise'}"
                                      f" by t = {t_end:g} ({chart})")
        for t in table:
            if t["label"] == label and t["as_printed"] and t["chart"] == "euler":
                ax.axvline(float(t["eps"]), color="g", lw=1.5, alpha=0.6, label="as printed (both charts)")
        ax.axhspan(case.t_jump * (1 - t_tolerance), case.t_jump * (1 + t_tolerance), color="m", alpha=0.15,
                   label=f"printed t* ~ {case.t_jump:g} (+-{t_tolerance:.0%})")
        ax.set_xscale("log")
        ax.set_ylim(0, 1.45 * t_end)
        ax.set_xlabel(r"regularisation $\epsilon$ of $|u_P|$ (units $\sqrt{gb}$); exact Coulomb: sticks in both")
        ax.set_ylabel(r"jump time $t^*$ (units $\sqrt{b/g}$)")
        ax.set_title(f"{case.figure}: start ({label}), a = {case.a:.4g}: {case.parameter} = {case.no_jump:g} and {case.jump:g}",
                     fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6.5, loc="center left")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return fig


# -- eggs: which end rises, the threshold against the asymmetry, and flights -------------------------


def plot_which_end(rows, omegas, *, risen, theta_2, title: str):
    """Which end an egg rises onto, over (asymmetry w, theta0 - pi/2), one panel per Omega0 in
    ``omegas``: each start (``rows``, with ``w``, ``omega0``, ``theta0``, ``theta_h`` and
    ``predicted``) coloured by ``risen(row)`` ("fat" blue, "thin" red, "none" grey: stuck at
    once, "failed" black), a cross where it is not as predicted; the predicted separatrix
    theta_h(Omega0) and its Omega0 -> infinity limit ``theta_2(w)``.

    Examples
    --------
    >>> import math, phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(w=w, omega0=6.0, theta0=1.5, theta_h=math.pi / 2, predicted="fat", end="fat") for w in (0.0, 0.05)]
    >>> fig = ps.plot_which_end(rows, [6.0], risen=lambda r: r.end, theta_2=lambda w: math.pi / 2, title="demo")
    >>> len(fig.axes)
    1
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, len(omegas), figsize=(6.2 * len(omegas), 5.0), squeeze=False)
    for ax, om in zip(axes[0], omegas):
        sub = [r for r in rows if r.omega0 == om]
        for r in sub:
            end = risen(r)
            c = {"fat": "#2166ac", "thin": "#b2182b", "none": "0.6", "failed": "k"}[end]
            ax.scatter(r.w, r.theta0 - math.pi / 2, c=c, marker="o" if end in (r.predicted, "none") else "X", s=50, zorder=3)
        ws = sorted({r.w for r in sub})
        th_h = [next(r.theta_h for r in sub if r.w == w) for w in ws]
        ax.plot(ws, np.array(th_h) - math.pi / 2, "k-", lw=1.5, label=r"$\theta_h(\Omega_0)$: horizontal-like state (predicted separatrix)")
        wf = np.linspace(0.0, max(ws), 30)
        ax.plot(wf, [theta_2(w) - math.pi / 2 if w > 0 else 0.0 for w in wf], "k:", lw=1,
                label=r"$\theta_2$: its $\Omega_0\to\infty$ limit")
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.set_xlabel(r"asymmetry $w$ (shift of the widest section / length)")
        ax.set_ylabel(r"$\theta_0 - \pi/2$ (rad; > 0: thin end lower)")
        ax.set_title(rf"$\Omega_0$ = {om:g}: blue = rises onto the fat end, red = thin end, grey = stuck at once"
                     "\n(X: not as predicted)", fontsize=9)
        ax.legend(fontsize=8, loc="lower right")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def plot_threshold_against(rows, x: str, curves: dict, *, xlabel: str, title: str, rev_scale=None, rev_label: str = ""):
    """Jump thresholds against a body parameter ``x`` (``rows``: dicts with ``x``, "threshold"
    and "start"), one curve per start (``curves``: start -> (format, label)); with ``rev_scale``
    (a :class:`phasekit.Scale`), a right axis in revolutions per second of that body
    (``rev_label``).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [{"w": w, "threshold": 12.0 + w, "start": "s"} for w in (0.0, 0.05)]
    >>> fig = ps.plot_threshold_against(rows, "w", {"s": ("ko-", "start s")}, xlabel="w", title="demo",
    ...                                     rev_scale=pk.Scale("21.5 mm"), rev_label="rev/s")
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['start s']
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.2, 4.8))
    for start, (style, label) in curves.items():
        pts = [(r[x], r["threshold"]) for r in rows if r["threshold"] is not None and r["start"] == start]
        ax.plot(*zip(*pts), style, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"threshold precession rate $\Omega_0$ (units $\sqrt{g/b}$)")
    if rev_scale is not None:
        per_rev = rev_scale.dimensionless("1 rev/s")  # Omega0 of one revolution per second
        sec = ax.secondary_yaxis("right", functions=(lambda v: v / per_rev, lambda v: v * per_rev))
        sec.set_ylabel(rev_label)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig


def plot_flights(rows, *, experiment: dict, title: str):
    """Flights of runs in real units, one marker per lever (``rows``: dicts with "lever",
    "value", "e" (restitution) and, for runs that flew, "first_flight_ms", "first_gap_mm",
    "longest_flight_ms", "largest_gap_mm"): the longest flight and largest gap of each run
    (black without rebounds, e = 0; labelled with the lever's value), the first flight hollow,
    and the experiment's reported range (``experiment``: "flight_ms" and "gap_mm" ranges).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [dict(lever="spin", value=50.0, e=0.5, first_flight_ms=2.0, first_gap_mm=0.01, longest_flight_ms=5.0,
    ...              largest_gap_mm=0.1)]
    >>> fig = ps.plot_flights(rows, experiment=dict(gap_mm=(0.05, 0.5), flight_ms=(5.0, 30.0)), title="demo")
    >>> len(fig.axes)
    1
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8.6, 6.0))
    g, f = experiment["gap_mm"], experiment["flight_ms"]
    ax.fill_between(f, g[0], g[1], color="#fdd0a2", alpha=0.6, label="Mitsui et al. 2006 (reported range)")
    markers = dict(zip(sorted({r["lever"] for r in rows}), "osD^vP*X"))
    for r in rows:
        if r.get("largest_gap_mm") is None:
            continue
        m = markers[r["lever"]]
        ax.scatter(r["first_flight_ms"], r["first_gap_mm"], marker=m, s=30, facecolors="none", edgecolors="grey")
        ax.scatter(r["longest_flight_ms"], r["largest_gap_mm"], marker=m, s=40, color="k" if r["e"] == 0 else "C0",
                   zorder=3)
        ax.annotate(f"{r['value']:.3g}", (r["longest_flight_ms"], r["largest_gap_mm"]), fontsize=7,
                    xytext=(3, 3), textcoords="offset points")
    for lever, m in markers.items():
        ax.scatter([], [], marker=m, color="C0", label=f"{lever}: longest flight, largest gap of the run")
    ax.scatter([], [], marker="o", facecolors="none", edgecolors="grey", label="the first flight alone (hollow)")
    ax.scatter([], [], marker="s", color="k", label="restitution 0 (no rebound)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log_ticks(ax)
    ax.set_xlabel("flight duration (ms)")
    ax.set_ylabel("gap (mm)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig
