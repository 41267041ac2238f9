"""Outcome map: where a start on the sliding branch sticks, rises, or jumps.

For an aspect ratio a, the start is the default definition's (exact Coulomb friction, mu =
0.1, on the sliding, gyroscopic-balance, branch at distance d from the fixed point: theta0 =
pi/2 - d with Omega0 given, prolate; theta0 = d with n0 given, oblate), with d log-spaced
from 1e-3 (starts that stick) to 0.2. Each start is classified:

    stuck  the body stuck (zero slip) and had not completed its rise by t = 3000: it rolls
    rise   the rise completed (theta within 0.1 rad of its final value) without losing contact
    jump   R reached 0 (dR/dt < 0) before that: t* and the share of the rise done then

The boundaries are traced, not read off the grid: the jump threshold Omega0*(d) / n0*(d) by a
bracketed bisection in the family parameter along each d-line (to 1e-3 relative), and the
sticking boundary d_min(Omega0) by a bisection in d along each Omega0-line (to 1e-2
relative). Maps for a = 1.5 and a = 2/3 (figures/outcome_map.png, .csv; the traced points in
outcome_map_boundaries.csv), and a 3-D scene of the jump region over (a, Omega0 or n0, d)
(figures/jump_region.png): its two boundary surfaces, computed on an (a, d) and an
(a, Omega0) grid only, with the jumping starts of the two maps.

Every start runs on heyoka's SIMD batch integrator (starts that stick are followed through
the rolling mode in batch too; see phasekit.batch). Dask LocalCluster (or --scheduler),
resumable: finished rows are appended to the CSV files at once and skipped on a rerun.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, replace
from functools import partial
from pathlib import Path

import phasekit as pk
from phasekit.viz import plain_log_ticks, pyplot, save_figure

import numpy as np

STEM = "outcome_map"
BASE = pk.Definition("sliding", "sliding")
THRESHOLD_SEARCH = dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5, levels=3)
STICK_SEARCH = dict(lo=1e-4, hi=0.2, tol=1e-2, n_coarse=8, levels=3)
D_RANGE = (1e-3, 0.2)
STEEP = 2.0  # d_min ratio between neighbouring value-lines above which a line is added between them
VALUE_SPAN = (2.0, 12.0)  # the family parameter from 2x to 12x the lower bound (1.05 x the stability threshold)
FULL = dict(maps=[1.5, 2 / 3], n_value=28, n_d=24, d_lines=10, stick_lines=8, refine=3,
            scene_a=[0.5, 0.6, 2 / 3, 0.75, 0.8, 1.2, 1.35, 1.5, 1.75, 2.0, 2.5], scene_d=6, scene_v=5, chunk=48, per_task=8)
QUICK = dict(maps=[1.5, 2 / 3], n_value=10, n_d=8, d_lines=5, stick_lines=4, refine=1,
             scene_a=[0.6, 2 / 3, 0.8, 1.3, 1.5, 2.0], scene_d=4, scene_v=3, chunk=40, per_task=6)
COLOURS = {"stuck": "0.6", "rise": "#4c72b0", "jump": "#dd8452", "slow": "#8172b3", "failed": "k"}


def value_range(a: float) -> tuple[float, float]:
    lo = BASE.lower_bound(a)
    return VALUE_SPAN[0] * lo, VALUE_SPAN[1] * lo


def grid_points(a: float, g: dict) -> list[tuple[float, float, float]]:
    """(a, d, value) of the sampled map."""
    vs = np.geomspace(*value_range(a), g["n_value"])
    ds = np.geomspace(*D_RANGE, g["n_d"])
    return [(a, float(d), float(v)) for d in ds for v in vs]


def search_specs(g: dict, engine: str):
    """The traced boundaries: d-lines (jump thresholds) and value-lines (sticking
    boundaries) of the 2-D maps, and the (a, d) / (a, value) grids of the 3-D scene; tasks
    of ``per_task`` searches traced in lock-step. Returns the tasks and their row keys."""
    points = set()
    for a in g["maps"]:
        points |= {("threshold", a, float(d)) for d in np.geomspace(2e-3, D_RANGE[1], g["d_lines"])}
        points |= {("stick", a, float(v)) for v in np.geomspace(*value_range(a), g["stick_lines"])}
    for a in g["scene_a"]:
        points |= {("threshold", a, float(d)) for d in np.geomspace(4e-3, D_RANGE[1], g["scene_d"])}
        points |= {("stick", a, float(v)) for v in np.geomspace(*value_range(a), g["scene_v"])}
    return _specs(points, g, engine)


def refine_stick_lines(searches, g: dict) -> set:
    """Where the traced sticking boundary of a 2-D map turns a corner (d_min changes by more
    than a factor STEEP between neighbouring value-lines, or one of them sticks at every d),
    a new value-line halfway (geometrically): the boundary is traced there too, not drawn
    as a straight line across the corner."""
    points = set()
    for a in g["maps"]:
        st = sorted((s.value, D_RANGE[1] if s.status == "no_jump_in_range" else s.threshold)
                    for s in searches if s.kind == "stick" and abs(s.a - a) < 1e-12)
        for (v1, d1), (v2, d2) in zip(st, st[1:]):
            if d1 and d2 and max(d1 / d2, d2 / d1) > STEEP and v2 / v1 > 1.01:
                points.add(("stick", a, float(math.sqrt(v1 * v2))))
    return points


def _specs(points, g: dict, engine: str):
    jobs, costs = [], []
    for kind, a, x in sorted(points):
        if kind == "threshold":
            jobs.append(pk.sweep.search_job(asdict(replace(BASE, amplitude=x)), a, THRESHOLD_SEARCH))
            costs.append(1.0 + 0.3 / abs(a - 1))
        else:
            jobs.append(pk.sweep.search_job(asdict(BASE), a, STICK_SEARCH, kind="stick", value=x))
            costs.append(3.0)
    return pk.sweep.group_search_tasks(jobs, costs, per_task=g["per_task"], study=STEM, engine=engine)


def grid_specs(g: dict, engine: str) -> tuple[list, dict]:
    """Tasks of ``chunk`` sampled starts each; returns them and each task's point keys."""
    task = partial(pk.sweep.outcome_task, study=STEM, engine=engine)
    specs, keys = [], {}
    for a in g["maps"]:
        s, k = pk.sweep.chunked(grid_points(a, g), lambda aa, d, v: pk.sweep.outcome_key(replace(BASE, amplitude=d), aa, v),
                                task, size=g["chunk"], args=(asdict(BASE),), prefix=f"grid|a={a:.10g}", cost=3.0)
        specs += s
        keys.update(k)
    return specs, keys


def warm_up() -> None:
    for a in (1.5, 2 / 3):
        BASE.prepare(a, engine="batch")


# -- the 2-D maps ---------------------------------------------------------------------------------


def plot_maps(points, searches, g, png: Path, quick: bool) -> None:
    plt = pyplot()
    from matplotlib import patheffects

    maps = g["maps"]
    fig, axes = plt.subplots(2, len(maps), figsize=(6.6 * len(maps), 10.5), squeeze=False)
    for col, a in enumerate(maps):
        pts = [p for p in points if abs(p.a - a) < 1e-12]
        name = r"\Omega_0" if a > 1 else "n_0"
        ax = axes[0, col]
        for kind, c in COLOURS.items():
            sel = [(p.value, p.d) for p in pts if p.outcome == kind]
            if sel:
                ax.scatter(*zip(*sel), s=22, marker="s", color=c, label=kind, edgecolors="none")
        _boundaries(ax, [s for s in searches if abs(s.a - a) < 1e-12], a)
        ax.set_title(f"a = {a:.4g} ({'prolate' if a > 1 else 'oblate'}): outcome of each start", fontsize=10)
        ax2 = axes[1, col]
        jp = [p for p in pts if p.outcome == "jump" and p.rise_fraction is not None]
        if jp:
            sc = ax2.scatter([p.value for p in jp], [p.d for p in jp], c=[p.rise_fraction for p in jp], s=22, marker="s",
                             cmap="magma", vmin=0.0, vmax=1.0, edgecolors="none")
            fig.colorbar(sc, ax=ax2, label="share of the rise done at the jump")
            for p in jp[:: max(1, len(jp) // 14)]:
                ax2.annotate(f"{p.t_jump:.0f}", (p.value, p.d), fontsize=7, color="black", xytext=(2, 2), textcoords="offset points",
                             path_effects=[patheffects.withStroke(linewidth=2.2, foreground="white")])
        _boundaries(ax2, [s for s in searches if abs(s.a - a) < 1e-12], a, legend=False)
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
    fig.suptitle(r"Outcome of sliding-branch starts, exact Coulomb $\mu$ = 0.1, rtol $10^{-9}$; "
                 r"thresholds bisected to $10^{-3}$, $d_{min}$ to $10^{-2}$" + (" (quick run)" if quick else ""), fontsize=11)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    save_figure(fig, png)


def _boundaries(ax, searches, a, legend=True) -> None:
    th = sorted((s.d, s) for s in searches if s.kind == "threshold" and s.threshold)
    if th:
        ax.errorbar([s.threshold for _, s in th], [d for d, _ in th],
                    xerr=[[s.threshold - s.bracket_lo for _, s in th], [s.bracket_hi - s.threshold for _, s in th]],
                    fmt="o-", color="k", ms=4, lw=1.2, label="jump threshold (bisection)" if legend else None)
    above = [s.value for s in searches if s.kind == "stick" and s.status == "no_jump_in_range"]
    if above:  # stuck at every d up to D_RANGE[1]: d_min lies above the map
        ax.plot(above, [D_RANGE[1]] * len(above), ls="none", marker=r"$\uparrow$", ms=12, color="crimson",
                label=f"stuck for every d \u2264 {D_RANGE[1]:g}" if legend else None)
    st = sorted((s.value, s) for s in searches if s.kind == "stick" and s.threshold)
    if st:
        ax.errorbar([v for v, _ in st], [s.threshold for _, s in st],
                    yerr=[[s.threshold - s.bracket_lo for _, s in st], [s.bracket_hi - s.threshold for _, s in st]],
                    fmt="D--", color="crimson", ms=4, lw=1.2, label="sticking boundary $d_{min}$ (bisection)" if legend else None)


# -- the 3-D scene --------------------------------------------------------------------------------


def render_region(points, searches, g, png: Path, quick: bool) -> dict:
    """Per branch (one view each): the threshold surface value*(a, d) and the sticking
    surface d_min(a, value), with the jumping starts of the 2-D maps, in a box of
    (a, log10 value, log10 d)."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    pl = pv.Plotter(off_screen=True, window_size=[1800, 900], shape=(1, 2), border=False)
    counts = {}
    for col, (branch, sel, name) in enumerate((("prolate", lambda a: a > 1, "Omega0"), ("oblate", lambda a: a < 1, "n0"))):
        pl.subplot(0, col)
        pl.set_background("white")
        sa = [a for a in g["scene_a"] if sel(a)]
        lv = [math.log10(x) for a in sa for x in value_range(a)]
        mine = [s for s in searches if any(abs(s.a - a) < 1e-12 for a in sa)]
        d_lo = min([D_RANGE[0]] + [s.threshold for s in mine if s.kind == "stick" and s.threshold])
        box = dict(a=(min(sa), max(sa)), v=(min(lv), max(lv)), d=(math.log10(d_lo), math.log10(D_RANGE[1])))
        to_box = _box_map(box)
        ds = np.geomspace(4e-3, D_RANGE[1], g["scene_d"])
        th = {(a, j): _find(mine, "threshold", a, d=d) for a in sa for j, d in enumerate(ds)}
        grid = [[None if th[a, j] is None else to_box(a, th[a, j], ds[j]) for j in range(len(ds))] for a in sa]
        surf = _grid_surface(grid)
        if surf is not None:
            pl.add_mesh(surf, color="#dd8452", opacity=0.8, show_edges=True, edge_color="#8c4a1f", label="jump threshold")
        st = {}
        for a in sa:
            for j, v in enumerate(np.geomspace(*value_range(a), g["scene_v"])):
                st[a, j] = (v, _find(mine, "stick", a, value=v))
        grid = [[None if st[a, j][1] is None else to_box(a, st[a, j][0], st[a, j][1]) for j in range(g["scene_v"])] for a in sa]
        surf = _grid_surface(grid)
        if surf is not None:
            pl.add_mesh(surf, color="#8c8c8c", opacity=0.8, show_edges=True, edge_color="#404040", label="sticking boundary d_min")
        n_th, n_st = sum(v is not None for v in th.values()), sum(v[1] is not None for v in st.values())
        jp = [p for p in points if p.outcome == "jump" and sel(p.a)]
        if jp:
            cloud = pv.PolyData(np.array([to_box(p.a, p.value, p.d) for p in jp]))
            cloud["t* (jump time)"] = np.array([p.t_jump for p in jp])
            pl.add_mesh(cloud, scalars="t* (jump time)", cmap="viridis", point_size=5, render_points_as_spheres=True, clim=(0, 60),
                        scalar_bar_args=dict(color="black", vertical=True, position_x=0.91, position_y=0.25, width=0.035, height=0.42,
                                             title="t*", n_labels=5, fmt="%.0f", title_font_size=16, label_font_size=13))
        pl.add_mesh(pv.Box(bounds=(0, 1.4, 0, 1, 0, 1)).extract_all_edges(), color="black", line_width=1)
        pl.show_grid(bounds=[0, 1.4, 0, 1, 0, 1], axes_ranges=[*box["a"], *box["v"], *box["d"]], color="black", fmt="%.2f",
                     xtitle="aspect ratio a", ytitle=f"log10({name} / sqrt(g/b))", ztitle="log10(d / rad)", font_size=15,
                     n_xlabels=4)
        pl.add_legend(bcolor="white", face="rectangle", size=(0.26, 0.08), loc="lower left")
        pl.add_text(f"{branch}, a = {min(sa):.3g} ... {max(sa):.3g}: a start jumps above both surfaces" + (" (quick run)" if quick else ""),
                    position=(0.03, 0.95), viewport=True, font_size=13, color="black")
        pl.add_text(f"surfaces: jump threshold {name}*(a, d) (bisected to 1e-3) and sticking\n"
                    f"boundary d_min(a, {name}) (to 1e-2); sliding-branch starts at distance d,\n"
                    f"exact Coulomb mu = {BASE.mu:g}, rtol {BASE.rtol:g}; dots: jumping starts, colour t* (sqrt(b/g))",
                    position=(0.03, 0.845), viewport=True, font_size=10, color="black")
        pl.camera_position = [(4.2, -1.5, 1.7), (0.7, 0.5, 0.42), (0, 0, 1)]  # value to the right, d up
        counts[branch] = {"threshold_points": n_th, "stick_points": n_st, "jump_starts": len(jp)}
    pl.screenshot(str(png))
    pl.close()
    return counts


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


# -- report ---------------------------------------------------------------------------------------


def summarise(points, searches, g) -> dict:
    out = {}
    for a in g["maps"]:
        pts = [p for p in points if abs(p.a - a) < 1e-12]
        counts = {k: sum(p.outcome == k for p in pts) for k in COLOURS}
        th = sorted((s.d, s.threshold, s.status) for s in searches if abs(s.a - a) < 1e-12 and s.kind == "threshold")
        st = sorted((s.value, s.threshold, s.status) for s in searches if abs(s.a - a) < 1e-12 and s.kind == "stick")
        jp = [p for p in pts if p.outcome == "jump"]
        # grid points on the wrong side of the traced threshold (a check of the tracing)
        out[f"a={a:.4g}"] = {"counts": counts, "threshold_vs_d": th, "d_min_vs_value": st,
                             "t_jump_range": [min((p.t_jump for p in jp), default=None), max((p.t_jump for p in jp), default=None)],
                             "rise_fraction_range": [min((p.rise_fraction for p in jp), default=None),
                                                     max((p.rise_fraction for p in jp), default=None)],
                             "grid_disagreements": _disagreements(pts, [s for s in searches if abs(s.a - a) < 1e-12])}
    return out


def _disagreements(pts, searches, margin: float = 0.03) -> dict:
    """A check of the tracing against the sampling: the traced threshold Omega0*(d) (or
    n0*(d)), interpolated log-log between its d-lines, against the sampled starts. Counts
    starts more than ``margin`` below it that jump, or more than ``margin`` above it that
    do not jump (inside the traced d range); and how many lie within the margin."""
    th = sorted((s.d, s.threshold) for s in searches if s.kind == "threshold" and s.status == "converged")
    if len(th) < 2:
        return {"checked": 0, "contradicting": 0, "within_margin": 0}
    ld, lt = np.log([d for d, _ in th]), np.log([t for _, t in th])
    checked = bad = close = 0
    for p in pts:
        if p.outcome == "failed" or not ld[0] <= math.log(p.d) <= ld[-1]:
            continue
        t = math.exp(np.interp(math.log(p.d), ld, lt))
        checked += 1
        if abs(p.value / t - 1) <= margin:
            close += 1
        elif (p.value < t and p.outcome == "jump") or (p.value > t and p.outcome != "jump"):
            bad += 1
    return {"checked": checked, "contradicting": bad, "within_margin": close}


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, dask=True)
    st.parser.add_argument("--no-scene", action="store_true", help="skip the 3-D scene")
    args = st.parse(argv)
    g = QUICK if args.quick else FULL
    meta = {"definition": asdict(BASE), "threshold_search": THRESHOLD_SEARCH, "stick_search": STICK_SEARCH, "d_range": D_RANGE,
            "value_span": VALUE_SPAN, "grid": g, "classes": {"stuck": "stuck and not risen by t_max",
                                                             "rise": "rise completed in contact",
                                                             "jump": "R = 0 before the rise completed"}}
    out_store = st.store(pk.sweep.OutcomeRow, meta)
    search_store = st.store(pk.sweep.SearchRow, meta, name=f"{STEM}_boundaries")
    gspecs, grid_keys = grid_specs(g, "batch")
    sspecs, members = search_specs(g, "batch")
    how = str(st.run(gspecs + sspecs, out_store, search_store, members={**grid_keys, **members}, warm_up=warm_up,
                     desc="outcome map"))
    point_keys = {k for ks in grid_keys.values() for k in ks}
    points = [r for r in out_store.rows() if r.key in point_keys]

    def traced():
        skeys = {k for ks in members.values() for k in ks}
        return [r for r in search_store.rows() if r.key in skeys]

    searches = traced()
    for level in range(g["refine"]):  # each level depends on the last: resumable, since its lines follow from stored rows
        extra = refine_stick_lines(searches, g)
        if not extra:
            break
        rspecs, rmembers = _specs(extra, g, "batch")
        members.update(rmembers)
        how += f"; corners of d_min, level {level + 1}: " + str(st.run(rspecs, out_store, search_store, members=members,
                                                                       warm_up=warm_up, desc="outcome map"))
        searches = traced()
    plot_maps(points, searches, g, st.path(f"{STEM}.png"), args.quick)
    counts = {} if args.no_scene else render_region(points, searches, g, st.path("jump_region.png"), args.quick)
    summary = summarise(points, searches, g)
    wall = st.wall
    n_sims = sum(s.n_sims for s in searches) + len(points)
    print(f"\n{STEM}: {len(points)} sampled starts, {len(searches)} traced boundary points; {how}; {wall:.1f} s wall")
    for k, v in summary.items():
        print(f"  {k}: classes {v['counts']}; t* {v['t_jump_range']}; rise share at the jump {v['rise_fraction_range']}; "
              f"sampled starts against the traced threshold (3% margin): {v['grid_disagreements']}")
        print("    jump threshold against d: " + ", ".join(f"d={d:.3g}: {t:.4g}" if t else f"d={d:.3g}: {s}" for d, t, s in v["threshold_vs_d"]))
        print("    d_min against the family parameter: " + ", ".join(f"{x:.3g}: {t:.3g}" if t else f"{x:.3g}: {s}" for x, t, s in v["d_min_vs_value"]))
    search_store.annotate(summary=summary, scene=counts)
    print(json.dumps({"wall_s": wall, "n_sims": n_sims, "n_points": len(points), "n_searches": len(searches)}))
    return {"points": points, "searches": searches, "summary": summary, "wall_s": wall}


if __name__ == "__main__":
    pk.sweep.run_study(main)
