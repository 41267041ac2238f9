"""3-D scenes with PyVista (Figure 6a): off-screen PNGs, an interactive plotter, glTF and HTML.

Coordinates (Omega, theta, n) have very different spans, so each is mapped to a unit box for
drawing and the axes are labelled in the true values and units. Nothing is drawn outside the
axes box: trajectories are cut at its faces. Off-screen rendering needs no display: without
one, VTK's EGL window is chosen up front (so VTK does not first try an X server and warn),
and VTK warnings are silenced while a scene is drawn (errors still show).
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ParameterError, PhasekitError

__all__ = ["render_scene", "RenderInfo", "HTML_EXTRA"]

#: the optional packages the HTML export needs: ``pip install "phasekit[html]"``
HTML_EXTRA = ("trame_pyvista",)
#: drawn box in VTK coordinates: Omega, theta, n spans
ASPECT = (1.4, 1.0, 1.0)
#: where the glTF axes' tick values and titles sit, per axis, relative to the axis (box units)
TICK_OFFSETS = ((0.0, -0.08, -0.06), (-0.12, 0.0, -0.06), (-0.12, -0.05, 0.0))
TITLE_OFFSETS = ((0.0, -0.2, -0.12), (-0.25, 0.0, -0.12), (-0.25, -0.1, 0.0))
COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666")


@dataclass(frozen=True)
class RenderInfo:
    """What was drawn: the image path, point counts per element, data bounds, image statistics
    and the files exported."""

    path: str
    n_points: dict
    bounds: tuple
    image_shape: tuple
    image_std: float
    exported: tuple = ()


def _box(bounds, aspect=ASPECT):
    lo = np.array(bounds[0::2], dtype=float)
    hi = np.array(bounds[1::2], dtype=float)
    span = np.where(hi > lo, hi - lo, 1.0)

    def f(P):
        P = np.atleast_2d(np.asarray(P, dtype=float))
        return (P - lo) / span * np.asarray(aspect)

    return f


def _inside_runs(P: np.ndarray, bounds) -> list[np.ndarray]:
    """The pieces of the polyline P (N, 3) inside the box, each cut exactly at the faces."""
    lo, hi = np.array(bounds[0::2]), np.array(bounds[1::2])
    tol = 1e-12 * (hi - lo)
    inside = np.all((P >= lo - tol) & (P <= hi + tol), axis=1)
    runs, cur = [], []
    for k in range(len(P)):
        if inside[k]:
            if not cur and k > 0:
                cur.append(_cut(P[k], P[k - 1], lo, hi))
            cur.append(P[k])
        elif cur:
            cur.append(_cut(P[k - 1], P[k], lo, hi))
            runs.append(np.array(cur))
            cur = []
    if cur:
        runs.append(np.array(cur))
    return [r for r in runs if len(r) >= 2]


def _cut(a: np.ndarray, b: np.ndarray, lo, hi) -> np.ndarray:
    """The point where the segment from ``a`` (inside) to ``b`` (outside) leaves the box."""
    s = 1.0
    d = b - a
    for j in range(3):
        if d[j] > 0 and b[j] > hi[j]:
            s = min(s, (hi[j] - a[j]) / d[j])
        elif d[j] < 0 and b[j] < lo[j]:
            s = min(s, (lo[j] - a[j]) / d[j])
    return a + max(0.0, s) * d


@contextlib.contextmanager
def _quiet_vtk():
    """VTK warnings off while drawing (they would go to stderr); errors still show."""
    from vtkmodules.vtkCommonCore import vtkLogger as logger

    old = logger.GetCurrentVerbosityCutoff()
    logger.SetStderrVerbosity(logger.VERBOSITY_ERROR)
    try:
        yield
    finally:
        logger.SetStderrVerbosity(old)


def _headless() -> None:
    """Without a display, pick VTK's EGL window before the first one is made (VTK otherwise
    tries X first and prints 'bad X server connection')."""
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def _check_exports(html, gltf) -> None:
    """Fail before drawing when an export cannot be written (one line, naming the fix)."""
    for name, target in (("html", html), ("gltf", gltf)):
        if target is None:
            continue
        parent = Path(target).resolve().parent
        if not parent.is_dir() or not os.access(parent, os.W_OK):
            raise PhasekitError(f"cannot write the {name} export {target}: directory {parent} is missing or not "
                                "writable")
    if html is not None:
        missing = [m for m in HTML_EXTRA if importlib.util.find_spec(m) is None]
        if missing:
            raise PhasekitError(f"cannot write the HTML export {html}: it needs {', '.join(missing)} "
                                "(pip install \"phasekit[html]\")")


def render_scene(data, path=None, *, window_size=(1400, 1000), html: str | None = None, gltf: str | None = None,
                 title: str | None = None, camera=None, off_screen: bool | None = None):
    """Draw a scene: a PNG off-screen, or a PyVista plotter to show interactively.

    Parameters
    ----------
    data : SceneData or Scene
        What :func:`phasekit.compute_scene` returned (a Scene is computed first).
    path : str or Path, optional
        Where to write the PNG. Without it, nothing is written: the plotter is returned
        (call ``.show()`` on it; it is off-screen only if ``off_screen=True``).
    window_size : (int, int)
        Image width and height in pixels.
    html, gltf : str, optional
        Also export the scene as interactive HTML (needs ``phasekit[html]``) or glTF (with
        the axes, their tick values and units as geometry, and the axis ranges and units in
        the file's ``asset.extras``).
    title : str, optional
        Text at the top left.
    camera : list, optional
        PyVista camera position (default: one per branch).
    off_screen : bool, optional
        Default: True when writing a PNG, False when returning the plotter.

    Returns
    -------
    RenderInfo or pyvista.Plotter
        RenderInfo when ``path`` is given, else the plotter.

    Raises
    ------
    PhasekitError
        When an export cannot be written (missing directory, missing optional packages):
        before anything is drawn.
    """
    from ..surface import Scene, compute_scene

    if isinstance(data, Scene):
        data = compute_scene(data)
    if not hasattr(data, "bounds") or data.bounds is None:
        raise ParameterError("data", "must be a Scene or what compute_scene returned", data)
    _check_exports(html, gltf)
    _headless()
    import pyvista as pv

    off = (path is not None) if off_screen is None else bool(off_screen)
    with _quiet_vtk():
        pl = pv.Plotter(off_screen=off, window_size=list(window_size))
        counts = _draw(pl, data, title, window_size)
        pl.camera_position = camera or CAMERAS[data.scene.branch]
        if path is None:
            return pl
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        img = pl.screenshot(str(path), return_img=True)
        exported = _export(pl, data, html, gltf)
        pl.close()
    return RenderInfo(str(path), counts, tuple(float(b) for b in data.bounds), tuple(img.shape), float(img.std()),
                      tuple(exported))


#: camera (position, focal point, up) in the unit-box coordinates, per branch: the prolate
#: trajectories run across Omega and n, the oblate ones mostly along theta
CAMERAS = {
    "prolate": [(3.3, -2.4, 1.9), (0.7, 0.5, 0.45), (0.0, 0.0, 1.0)],
    "oblate": [(3.9, 2.6, 1.7), (0.7, 0.45, 0.45), (0.0, 0.0, 1.0)],
}


def _clipped_grid(pv, f, OM, TH, N, n_lo, n_hi):
    grid = pv.StructuredGrid()
    grid.points = np.nan_to_num(f(np.column_stack([OM.ravel(), TH.ravel(), N.ravel()])), nan=0.0)
    grid.dimensions = (OM.shape[1], OM.shape[0], 1)
    grid["n"] = np.nan_to_num(N.ravel(), nan=-1e300, posinf=1e300, neginf=-1e300)
    # a smooth cut at the n range (thresholding whole cells leaves a ragged edge)
    return grid.clip_scalar(scalars="n", value=n_hi).clip_scalar(scalars="n", value=n_lo, invert=False)


def _draw(pl, data, title, window_size) -> dict:
    import pyvista as pv

    show = data.scene.show
    f = _box(data.bounds)
    n_lo, n_hi = data.bounds[4], data.bounds[5]
    pl.set_background("white")
    counts = {}
    if data.surface is not None and "surface" in show:
        grid = _clipped_grid(pv, f, *data.surface, n_lo, n_hi)
        counts["surface"] = grid.n_points
        if grid.n_points:
            bar = dict(title="n on (6.3)\n(units sqrt(g/b))", color="k", vertical=True, title_font_size=16, fmt="%.3g", label_font_size=14,
                       position_x=0.86, position_y=0.08, width=0.05, height=0.6)
            pl.add_mesh(grid, scalars="n", cmap="coolwarm", opacity=0.55, show_scalar_bar="colorbar" in show,
                        clim=(n_lo, n_hi), scalar_bar_args=bar, smooth_shading=True)
    if data.exact is not None and "exact_boundary" in show:
        grid = _clipped_grid(pv, f, *data.exact, n_lo, n_hi)
        counts["exact_boundary"] = grid.n_points
        if grid.n_points:
            pl.add_mesh(grid, style="wireframe", color="darkgreen", line_width=1, opacity=0.6)
    if "trajectories" in show:
        counts["trajectories"] = 0
        for k, tr in enumerate(data.trajectories):
            for run in _inside_runs(tr, data.bounds):
                line = pv.lines_from_points(f(run))
                counts["trajectories"] += line.n_points
                pl.add_mesh(line, color=COLORS[k % len(COLORS)], line_width=2.5)
    for name, pts, color, size in (("crossings", [[c.Omega, c.theta, c.n] for c in data.crossings], "black", 16),
                                   ("fixed_points", data.fixed_points, "red", 12)):
        if name in show and pts is not None and len(pts):
            P = np.asarray(pts, dtype=float)
            lo, hi = np.array(data.bounds[0::2]), np.array(data.bounds[1::2])
            P = P[np.all((P >= lo) & (P <= hi), axis=1)]
            counts[name] = len(P)
            if len(P):
                pl.add_points(f(P), color=color, point_size=size, render_points_as_spheres=True)
    if "axes" in show:
        from ..surface import AXES

        titles = [f"{name} [{unit}]" for name, unit in AXES]
        pl.show_bounds(bounds=[0, ASPECT[0], 0, ASPECT[1], 0, ASPECT[2]], axes_ranges=list(data.bounds),
                       xtitle=titles[0], ytitle=titles[1], ztitle=titles[2], color="k", font_size=16, location="outer",
                       grid="back", ticks="outside")
    if title:
        # anchored by its top-left corner a margin inside the image (a corner annotation
        # touches the edge)
        actor = pl.add_text(title, position=(16, window_size[1] - 14), font_size=11, color="k")
        actor.GetTextProperty().SetVerticalJustificationToTop()
    return counts


def _export(pl, data, html, gltf) -> list[str]:
    out = []
    if gltf:
        _add_axes_geometry(pl, data.bounds)
        tmp = Path(gltf).with_name(f".{Path(gltf).name}.{os.getpid()}.tmp.gltf")
        try:
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # pyvista notes that it converts the grids to surfaces
                pl.export_gltf(str(tmp), inline_data=True)
            _annotate_gltf(tmp, data.bounds)
            os.replace(tmp, gltf)
        finally:
            tmp.unlink(missing_ok=True)
        out.append(str(gltf))
    if html:
        try:
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # pyvista's deprecation notice of export_html
                pl.export_html(html)
        except Exception as exc:
            raise PhasekitError(f"cannot write the HTML export {html}: {type(exc).__name__}: "
                                f"{' '.join(str(exc).split())}") from None
        out.append(str(html))
    return out


def _add_axes_geometry(pl, bounds) -> None:
    """The axes as meshes (glTF keeps meshes, not VTK's annotation actors): the three axis
    lines, tick marks with their values, and the titles with units, as 3-D text."""
    import pyvista as pv

    from ..surface import AXES

    f = _box(bounds)
    lo = np.array(bounds[0::2], dtype=float)
    hi = np.array(bounds[1::2], dtype=float)
    for j, (name, unit) in enumerate(AXES):
        a, b = lo.copy(), lo.copy()
        b[j] = hi[j]
        pl.add_mesh(pv.Line(f(a)[0], f(b)[0]), color="black", line_width=2)
        for v in np.linspace(lo[j], hi[j], 4):
            p = lo.copy()
            p[j] = v
            q = f(p)[0]
            label = pv.Text3D(f"{v:.3g}", depth=0.002).scale(0.035, inplace=False)
            off = np.array(TICK_OFFSETS[j])
            pl.add_mesh(label.translate(q + off, inplace=False), color="black")
        mid = lo.copy()
        mid[j] = 0.5 * (lo[j] + hi[j])
        q = f(mid)[0] + np.array(TITLE_OFFSETS[j])
        pl.add_mesh(pv.Text3D(f"{name} [{unit}]", depth=0.002).scale(0.045, inplace=False).translate(q, inplace=False),
                    color="black")


def _annotate_gltf(path: Path, bounds) -> None:
    """Record the axes (name, unit, range, drawn span) in the glTF ``asset.extras``."""
    from ..surface import AXES

    doc = json.loads(Path(path).read_text())
    doc.setdefault("asset", {}).setdefault("extras", {})["phasekit_axes"] = [
        {"name": name, "unit": unit, "range": [float(bounds[2 * j]), float(bounds[2 * j + 1])],
         "drawn_span": [0.0, ASPECT[j]]} for j, (name, unit) in enumerate(AXES)]
    Path(path).write_text(json.dumps(doc))
