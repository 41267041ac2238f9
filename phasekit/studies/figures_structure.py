"""The steady-state structure in 3-D: the branches of :func:`phasekit.steady_structure` in
(Omega, theta, n), coloured by stability, with the families (spins about the vertical at the
poles, precession families), the ends and changes of stability, trajectories (e.g. seeded on
the unstable manifold of a branch state) and, for a body that jumps, the surface (6.3).

Omega diverges at an infinite-spin end: the box stops at ``omega_max`` and the branches are cut
at its faces, like the trajectories of :func:`phasekit.viz.render_scene`. PyVista is imported
when a scene is drawn, never at import.

In the planes (:func:`plot_branch_planes`, matplotlib): the branches in (theta, Omega) and
(theta, n) with trajectories over them and marked states, e.g. where a rise settles.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..viz.pv import ASPECT, RenderInfo, bounding_box, check_file, check_window_size, headless, inside_runs, quiet_vtk

#: none of them blue: blue is the colour of neutral states (phasekit.viz.stability)
TRAJECTORY_COLORS = ("#7b3294", "#8c510a", "#01665e", "#e08214")


def _box_bounds(structure, trajectories, omega_max):
    om = np.concatenate([b.Omega for b in structure.branches] + [np.zeros(1)])
    n = np.concatenate([b.n for b in structure.branches] + [np.zeros(1)])
    if omega_max is None:
        finite = om[np.isfinite(om)]
        omega_max = float(min(np.quantile(finite, 0.9) * 1.6, 4 * np.median(finite[finite > 0]) if np.any(finite > 0) else 10))
    keep = om <= omega_max
    n_lo, n_hi = float(np.min(n[keep])), float(np.max(n[keep]))
    for tr in trajectories:
        n_lo, n_hi = min(n_lo, float(np.min(tr[:, 2]))), max(n_hi, float(np.max(tr[:, 2])))
    pad = 0.05 * (n_hi - n_lo or 1.0)
    return (0.0, float(omega_max), 0.0, float(np.pi), n_lo - pad, n_hi + pad)


def _segments_by_stability(P: np.ndarray, words) -> list:
    """Split a polyline into runs of one stability word (each run shares its end point with the next)."""
    runs, start = [], 0
    for k in range(1, len(P)):
        if words[k] != words[start]:
            runs.append((P[start:k + 1], words[start]))
            start = k
    runs.append((P[start:], words[start]))
    return [(r, s) for r, s in runs if len(r) >= 2]


def render_structure(structure, path, *, trajectories=(), surface: bool = False, omega_max: float | None = None,
                     title: str | None = None, window_size=(1500, 1050), camera=None) -> RenderInfo:
    """Draw ``structure`` (a :class:`phasekit.steady.SteadyStructure` with stability) off-screen to a PNG,
    its branches and families coloured by the stability vocabulary of :mod:`phasekit.viz.stability`
    (under exact Coulomb friction the states that do not grow are neutral, never stable).

    Parameters
    ----------
    structure : SteadyStructure
    path : str or Path
        The PNG to write (its directory is made if missing).
    trajectories : sequence of arrays (N, 3)
        Curves in (Omega, theta, n), e.g. ``traj.sample(ts)[["Omega", "theta", "n"]].to_numpy()``.
    surface : bool
        Also draw the approximate jump surface (6.3) n(Omega, theta).
    omega_max : float, optional
        Top of the Omega axis (default: from the branches' spread).
    title : str, optional
    window_size : (int, int)
    camera : list, optional
        [position, focal point, view up] in the drawn box (Omega, theta, n spans 1.4, 1, 1).

    Returns
    -------
    RenderInfo

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> import tempfile, pathlib
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    >>> info = ps.render_structure(s, pathlib.Path(tempfile.mkdtemp()) / 's.png', window_size=(200, 150))
    >>> info.image_shape
    (150, 200, 3)
    """
    from ..steady.structure import SteadyStructure
    from ..viz.stability import COLOURS, state_word

    if not isinstance(structure, SteadyStructure):
        raise ParameterError("structure", "must be what phasekit.steady_structure returned", structure)
    if any(b.theta.size and not b.points for b in structure.branches):
        raise ParameterError("structure", "must carry stability (steady_structure(..., stability=True))", show_value=False)
    path = check_file("path", path, create=True)
    window_size = check_window_size(window_size)
    trs = [np.asarray(t, dtype=float).reshape(-1, 3) for t in trajectories]
    bounds = _box_bounds(structure, trs, omega_max)
    headless()
    import pyvista as pv

    f = bounding_box(bounds)
    counts = {"branches": 0, "trajectories": 0, "surface": 0, "points": 0}
    words = set()
    with quiet_vtk():
        pl = pv.Plotter(off_screen=True, window_size=list(window_size))
        pl.set_background("white")
        for b in structure.branches:
            P = np.column_stack([b.Omega, b.theta, b.n])
            for run, word in _segments_by_stability(P, [state_word(p) for p in b.points]):
                for piece in inside_runs(run, bounds):
                    line = pv.lines_from_points(f(piece))
                    counts["branches"] += line.n_points
                    words.add(word)
                    pl.add_mesh(line, color=COLOURS[word], line_width=5)
        counts["points"], family_words = _add_special_points(pl, pv, f, structure, bounds)
        for k, tr in enumerate(trs):
            for piece in inside_runs(tr, bounds):
                line = pv.lines_from_points(f(piece))
                counts["trajectories"] += line.n_points
                pl.add_mesh(line, color=TRAJECTORY_COLORS[k % len(TRAJECTORY_COLORS)], line_width=1.5, opacity=0.85)
        if surface:
            counts["surface"] = _add_surface(pl, pv, f, structure.body, bounds)
        pl.show_bounds(bounds=[0, ASPECT[0], 0, ASPECT[1], 0, ASPECT[2]], axes_ranges=list(bounds),
                       xtitle="Omega [sqrt(g/b)]", ytitle="theta [rad]", ztitle="n [sqrt(g/b)]", color="k", font_size=16,
                       location="outer", grid="back", ticks="outside")
        _legend_and_title(pl, structure, words, family_words, bool(trs), title, window_size)
        pl.camera_position = camera or [(3.4, -2.3, 1.8), (0.7, 0.5, 0.45), (0.0, 0.0, 1.0)]
        img = pl.screenshot(str(path), return_img=True)
        pl.close()
    return RenderInfo(str(path), counts, tuple(float(v) for v in bounds), tuple(img.shape), float(img.std()))


def _add_special_points(pl, pv, f, structure, bounds) -> tuple[int, set]:
    """Branch ends at poles and statics (black), stability changes (orange), the pole and
    precession families as thin lines coloured by their stability. Returns the number of points
    and the stability words of the families drawn."""
    from ..viz.stability import COLOURS, family_word

    lo, hi = np.array(bounds[0::2]), np.array(bounds[1::2])
    ends, changes = [], []
    for b in structure.branches:
        for e, om, n in ((b.ends[0], b.Omega[:1], b.n[:1]), (b.ends[1], b.Omega[-1:], b.n[-1:])):
            if e.kind == "pole":
                ends.append([e.Omega, e.theta, e.n])
            elif e.kind == "static":
                ends.append([0.0, e.theta, 0.0])
        changes += [[c.Omega, c.theta, c.n] for c in b.changes]
    count = 0
    for pts, color, size in ((ends, "black", 16), (changes, "#fdae61", 14)):
        P = np.asarray(pts, dtype=float).reshape(-1, 3)
        P = P[np.all((P >= lo) & (P <= hi), axis=1)]
        if len(P):
            pl.add_points(f(P), color=color, point_size=size, render_points_as_spheres=True)
            count += len(P)
    words = set()
    for fam in structure.families:
        if fam.parameter == "n":
            # spins about the vertical (Omega undefined: drawn in the plane where a branch meets
            # the pole, else Omega = 0) and straight rolling (Omega = 0)
            meet = [e.Omega for b in structure.branches for e in b.ends if e.kind == "pole" and e.theta == fam.theta]
            om = meet[0] if meet and fam.kind == "pole" else 0.0
            vals = np.linspace(lo[2], hi[2], 81)
            P = np.column_stack([np.full_like(vals, min(om, hi[0])), np.full_like(vals, fam.theta), vals])
        else:
            vals = np.linspace(lo[0], hi[0], 81)
            P = np.column_stack([vals, np.full_like(vals, fam.theta), np.zeros_like(vals)])
        side = [fam.stable_on[int(np.searchsorted(fam.criticals, abs(v)))] for v in vals]
        for run, word in _segments_by_stability(P, [family_word(s, structure.model.friction) for s in side]):
            words.add(word)
            pl.add_mesh(pv.lines_from_points(f(run)), color=COLOURS[word], line_width=2, opacity=0.7)
    return count, words


def _legend_and_title(pl, structure, words, family_words, trajectories: bool, title, window_size) -> None:
    """The legend names the stability words drawn (branches thick, families thin), under the law."""
    from ..viz.stability import COLOURS, WORDS, law_text, legend_label

    law = structure.model.friction
    legend = [[legend_label(w, law_text(law).replace("$\\mu$", "mu"), rolling=law.has_rolling_mode), COLOURS[w]]
              for w in WORDS if w in words | family_words]
    if "unknown" in family_words:
        legend.append(["family: stability not computed", COLOURS["unknown"]])
    legend.append(["end of a branch", "black"])
    if any(b.changes for b in structure.branches):
        legend.append(["change of stability", "#fdae61"])
    legend.append(["branches thick, families thin", (0.4, 0.4, 0.4)])
    if trajectories:
        legend.append(["trajectory", TRAJECTORY_COLORS[0]])
    # top right: the drawn box leaves it free from the cameras the studies use
    box = pl.add_legend(legend, bcolor="white", face="rectangle", loc=None)
    height = min(0.032, 22.0 / window_size[1]) * len(legend)  # VTK fits the font to the box: ~22 px a row
    box.SetPosition(0.64, 0.92 - height)  # top right, below a title of two lines
    box.SetPosition2(0.34, height)
    if title:
        actor = pl.add_text(title, position=(16, window_size[1] - 14), font_size=11, color="k")
        actor.GetTextProperty().SetVerticalJustificationToTop()


def _add_surface(pl, pv, f, body, bounds) -> int:
    """(6.3) over the box, cut at its n range; nothing where it does not exist."""
    from ..theory.jump_surface import surface_n

    om = np.linspace(max(bounds[0], 1e-3 * bounds[1]), bounds[1], 60)
    th = np.linspace(0.02, np.pi - 0.02, 90)
    h, ht, _ = body.h(th)
    th = th[np.abs(ht * np.sin(th)) > 1e-6 * np.abs(h)]
    if not th.size:
        return 0
    OM, TH = np.meshgrid(om, th)
    with np.errstate(all="ignore"):
        N = np.asarray(surface_n(body, OM, TH), dtype=float)
    grid = pv.StructuredGrid()
    grid.points = np.nan_to_num(f(np.column_stack([OM.ravel(), TH.ravel(), N.ravel()])), nan=0.0)
    grid.dimensions = (OM.shape[1], OM.shape[0], 1)
    grid["n"] = np.nan_to_num(N.ravel(), nan=-1e300, posinf=1e300, neginf=-1e300)
    grid = grid.clip_scalar(scalars="n", value=bounds[5]).clip_scalar(scalars="n", value=bounds[4], invert=False)
    if grid.n_points:
        pl.add_mesh(grid, color="#9ecae1", opacity=0.35, smooth_shading=True, label="jump surface (6.3)")
    return int(grid.n_points)


def plot_branch_planes(structure, runs, *, omega_max: float, title: str, caption: str = ""):
    """The branches of ``structure`` (a :class:`phasekit.steady.SteadyStructure`, G at rest) in the
    (theta, Omega) plane (left, cut at ``omega_max``) and the (theta, n) plane (right), with
    ``runs`` over them: each a dict with ``path`` (columns theta, Omega, n, e.g. a sampled
    trajectory), ``colour``, ``label`` and ``star`` (theta, Omega, n): a state marked in both
    planes. ``caption``: the right panel's title. Returns the figure.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    >>> path = {"theta": [1.0, 1.2], "Omega": [3.0, 3.5], "n": [2.0, 2.5]}
    >>> fig = ps.plot_branch_planes(s, [dict(path=path, colour="C0", label="a run", star=(1.2, 3.5, 2.5))],
    ...                                 omega_max=14.0, title="demo")
    >>> len(fig.axes)
    2
    """
    from ..viz.output import pyplot

    fig, (ax1, ax2) = pyplot().subplots(1, 2, figsize=(13, 5))
    for b in structure.branches:
        keep = b.Omega < omega_max
        for ax, y in ((ax1, b.Omega), (ax2, b.n)):
            ax.plot(b.theta[keep], y[keep], color="0.2", lw=2,
                    label="branch (G at rest)" if b is structure.branches[0] and ax is ax1 else None)
    for run in runs:
        path, colour, (th, om, n) = run["path"], run["colour"], run["star"]
        ax1.plot(path["theta"], path["Omega"], color=colour, lw=0.7, alpha=0.7, label=run["label"])
        ax2.plot(path["theta"], path["n"], color=colour, lw=0.7, alpha=0.7)
        ax1.plot(th, om, "*", color=colour, ms=13, mec="k")
        ax2.plot(th, n, "*", color=colour, ms=13, mec="k")
    for ax, yl in ((ax1, r"$\Omega$ ($\sqrt{g/b}$)"), (ax2, r"$n$ ($\sqrt{g/b}$)")):
        ax.set(xlabel=r"$\theta$ (rad)", ylabel=yl, xlim=(0, np.pi))
        ax.grid(alpha=0.3)
    ax1.set_ylim(0, omega_max)
    ax1.legend(fontsize=8)
    ax2.set_title(caption, fontsize=9)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig
