"""Figures of the outcome maps (studies/outcome_map.py): the outcome map of sliding-branch starts
and its traced boundaries (:func:`plot_outcome_map`), and the jump region in 3-D
(:func:`render_jump_region`).

Each takes the stored rows of :mod:`phasekit.studies.outcome_maps` (:class:`phasekit.studies.OutcomeRow`)
and :mod:`phasekit.studies.threshold_rows` (:class:`phasekit.studies.SearchRow`) and returns a
matplotlib figure for :meth:`phasekit.scaffold.Study.save` (the 3-D scene writes its PNG itself).
matplotlib and pyvista are imported by the functions that draw.
"""

from __future__ import annotations

import math

import numpy as np

from ..viz.mpl import plain_log_ticks
from ..viz.output import pyplot

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
