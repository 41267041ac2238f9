"""Off-screen 3-D rendering of jump-surface scenes with PyVista (Figure 6a).

Coordinates (Omega, theta, n) have very different spans, so each is mapped to a unit box for
drawing and the axes are labelled in the true units (``axes_ranges``). Works without a
display: PyVista renders off-screen (VTK's EGL or OSMesa window).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["render_scene", "RenderInfo"]


@dataclass(frozen=True)
class RenderInfo:
    """What was drawn: the image path, point counts per element, data bounds, image statistics."""

    path: str
    n_points: dict
    bounds: tuple
    image_shape: tuple
    image_std: float
    exported: tuple = ()


def _box(bounds, aspect=(1.4, 1.0, 1.0)):
    lo = np.array(bounds[0::2], dtype=float)
    hi = np.array(bounds[1::2], dtype=float)
    span = np.where(hi > lo, hi - lo, 1.0)

    def f(P):
        P = np.atleast_2d(np.asarray(P, dtype=float))
        return (P - lo) / span * np.asarray(aspect)

    return f


#: camera (position, focal point, up) in the unit-box coordinates, per branch: the prolate
#: trajectories run across Omega and n, the oblate ones mostly along theta
CAMERAS = {
    "prolate": [(3.3, -2.4, 1.9), (0.7, 0.5, 0.45), (0.0, 0.0, 1.0)],
    "oblate": [(3.9, 2.6, 1.7), (0.7, 0.45, 0.45), (0.0, 0.0, 1.0)],
}


def render_scene(data, path, *, window_size=(1400, 1000), html: str | None = None, gltf: str | None = None,
                 title: str | None = None, camera=None) -> RenderInfo:
    """Draw the elements of ``data.scene.show`` that ``data`` holds, save a PNG at ``path``."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    scene = data.scene
    show = scene.show
    f = _box(data.bounds)
    n_lo, n_hi = data.bounds[4], data.bounds[5]
    pl = pv.Plotter(off_screen=True, window_size=list(window_size))
    pl.set_background("white")
    counts = {}
    if data.surface is not None and "surface" in show:
        OM, TH, N = data.surface
        pts = f(np.column_stack([OM.ravel(), TH.ravel(), N.ravel()]))
        grid = pv.StructuredGrid()
        grid.points = pts
        grid.dimensions = (OM.shape[1], OM.shape[0], 1)
        grid["n"] = N.ravel()
        # a smooth cut at the n range (thresholding whole cells leaves a ragged edge)
        grid = grid.clip_scalar(scalars="n", value=n_hi).clip_scalar(scalars="n", value=n_lo, invert=False)
        counts["surface"] = grid.n_points
        if grid.n_points:
            pl.add_mesh(grid, scalars="n", cmap="coolwarm", opacity=0.55, show_scalar_bar="colorbar" in show,
                        scalar_bar_args=dict(title="n on (6.3)\n(units sqrt(g/b))", color="k", vertical=True, title_font_size=16,
                                             label_font_size=14), smooth_shading=True)
    if data.exact is not None and "exact_boundary" in show:
        OM, TH, N = data.exact
        pts = f(np.column_stack([OM.ravel(), TH.ravel(), N.ravel()]))
        grid = pv.StructuredGrid()
        grid.points = np.nan_to_num(pts, nan=0.0)
        grid.dimensions = (OM.shape[1], OM.shape[0], 1)
        grid["n"] = np.nan_to_num(N.ravel(), nan=-1e300)
        grid = grid.clip_scalar(scalars="n", value=n_hi).clip_scalar(scalars="n", value=n_lo, invert=False)
        counts["exact_boundary"] = grid.n_points
        if grid.n_points:
            pl.add_mesh(grid, style="wireframe", color="darkgreen", line_width=1, opacity=0.6)
    if "trajectories" in show:
        counts["trajectories"] = 0
        colors = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666"]
        for k, tr in enumerate(data.trajectories):
            line = pv.lines_from_points(f(tr))
            counts["trajectories"] += line.n_points
            pl.add_mesh(line, color=colors[k % len(colors)], line_width=2.5)
    if "crossings" in show and data.crossings:
        P = f([[c.Omega, c.theta, c.n] for c in data.crossings])
        counts["crossings"] = len(P)
        pl.add_points(P, color="black", point_size=16, render_points_as_spheres=True)
    if "fixed_points" in show and data.fixed_points is not None:
        P = f(data.fixed_points)
        counts["fixed_points"] = len(P)
        pl.add_points(P, color="red", point_size=12, render_points_as_spheres=True)
    if "axes" in show:
        b = data.bounds
        pl.show_bounds(bounds=[0, 1.4, 0, 1.0, 0, 1.0], axes_ranges=list(b), xtitle="Omega (units sqrt(g/b))", ytitle="theta (rad)",
                       ztitle="n (units sqrt(g/b))", color="k", font_size=16, location="outer", grid="back", ticks="outside")
    if title:
        pl.add_text(title, font_size=11, color="k", position="upper_left")
    pl.camera_position = camera or CAMERAS[scene.branch]
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    img = pl.screenshot(str(path), return_img=True)
    exported = []
    if gltf:
        pl.export_gltf(gltf)
        exported.append(gltf)
    if html:
        try:
            pl.export_html(html)
            exported.append(html)
        except Exception as exc:  # needs the optional trame packages
            print(f"HTML export skipped: {exc}")
    pl.close()
    return RenderInfo(str(path), counts, tuple(float(b) for b in data.bounds), tuple(img.shape), float(img.std()), tuple(exported))
