"""The exports of a 3-D scene: glTF and interactive HTML (vtk.js). Neither keeps VTK's annotation
actors (the cube axes would show the drawn box's 0..1.4 coordinates, 2-D text vanishes), so the
axes and their tick values in the data's units are added as 3-D text, upright and turned to face
the scene's camera, at round values away from the corner the three axes share (where their
first values would overlap). The HTML page carries the title once, as its header (with each
axis's true range); the glTF, which has no 2-D text, gets the title as 3-D text above the box
and in ``asset.extras``.
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path

import numpy as np

from ..errors import PhasekitError
from .box import ASPECT, bounding_box

#: heights of the 3-D text, box units: tick values, axis titles, the glTF's title
TEXT_SIZES = {"tick": 0.042, "title": 0.048, "scene_title": 0.05}
#: where an axis's tick values and title sit relative to the axis, box units, seen from a
#: camera at -y and +x (the prolate scene's): mirrored to the side the camera is on
TICK_OFFSETS = ((0.0, -0.07, -0.07), (0.09, 0.0, -0.07), (-0.1, -0.1, 0.0))
TITLE_OFFSETS = ((0.0, -0.2, -0.2), (0.32, 0.0, -0.14), (0.0, 0.0, 0.12))
#: no tick value nearer than this fraction of the span to the corner the axes share (the
#: floor's two axes; the vertical axis rises away from their labels and needs half of it)
CORNER_GAP = 0.2


def tick_values(lo: float, hi: float, n: int = 5, gap: float = CORNER_GAP) -> np.ndarray:
    """Round tick values inside [lo, hi] (matplotlib's MaxNLocator, about ``n``), none within
    ``gap`` of the span from ``lo``, the end where the three axes meet.

    Examples
    --------
    >>> from phasekit.viz.export import tick_values
    >>> tick_values(6.759, 31.5).tolist(), tick_values(-2.978, 12.9, gap=0.1).tolist()
    ([15.0, 20.0, 25.0, 30.0], [0.0, 5.0, 10.0])
    """
    from matplotlib.ticker import MaxNLocator

    if not hi > lo:
        return np.array([lo])
    v = MaxNLocator(nbins=n, steps=[1, 2, 2.5, 5, 10]).tick_values(lo, hi)
    tol = 1e-9 * (hi - lo)
    return v[(v >= lo + gap * (hi - lo) - tol) & (v <= hi + tol)]


def export_scene(pl, data, html, gltf, title=None) -> list[str]:
    """Write the glTF and HTML exports: the cube axes replaced by 3-D text axes, the title as
    3-D text in the glTF only (the HTML page shows it as its header)."""
    out = []
    if gltf or html:
        pl.remove_bounds_axes()
        yaw, side = _facing(pl)
        _add_axes_geometry(pl, data.bounds, yaw, side)
    if gltf:
        actor = _add_title_geometry(pl, title, yaw) if title else None
        tmp = Path(gltf).with_name(f".{Path(gltf).name}.{os.getpid()}.tmp.gltf")
        try:
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # pyvista notes that it converts the grids to surfaces
                pl.export_gltf(str(tmp), inline_data=True)
            _annotate_gltf(tmp, data.bounds, title)
            os.replace(tmp, gltf)
        finally:
            tmp.unlink(missing_ok=True)
        if actor is not None:
            pl.remove_actor(actor)
        out.append(str(gltf))
    if html:
        tmp = Path(html).with_name(f".{Path(html).stem}.{os.getpid()}.tmp{Path(html).suffix}")
        try:
            import warnings

            with warnings.catch_warnings(), _without_vtk_wasm():
                warnings.simplefilter("ignore")  # pyvista's deprecation notice of export_html
                pl.export_html(str(tmp))
            _caption_html(tmp, data, title)
            os.replace(tmp, html)
        except Exception as exc:
            raise PhasekitError(f"cannot write the HTML export {html}: {type(exc).__name__}: "
                                f"{' '.join(str(exc).split())}") from None
        finally:
            tmp.unlink(missing_ok=True)
        out.append(str(html))
    return out


@contextlib.contextmanager
def _without_vtk_wasm():
    """pyvista's HTML export starts trame's server, which initialises trame-vtklocal when it is
    installed; that module then downloads VTK's WebAssembly bundle from the internet (not needed:
    the page is vtk.js) and, offline, prints a traceback later. Hide it while the server starts."""
    import sys

    key, missing = "trame.widgets.vtklocal", object()
    saved = sys.modules.get(key, missing)
    sys.modules[key] = None  # an import of it raises ImportError, which trame-pyvista skips
    try:
        yield
    finally:
        if saved is missing:
            sys.modules.pop(key, None)
        else:
            sys.modules[key] = saved


def axes_caption(data, title=None) -> list[str]:
    """The lines of text that say what an exported scene shows: its title and each axis with
    its unit and true range (the drawn box is rescaled).

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.viz.export import axes_caption
    >>> data = pk.compute_scene(pk.Scene('prolate', 1.5, values=(12.0,), resolution=20))
    >>> axes_caption(data, "demo")[0], axes_caption(data)[0].split(":")[0]
    ('demo', 'Omega [sqrt(g/b)]')
    """
    from ..scenes.scene import AXES

    lines = [title] if title else []
    for j, (name, unit) in enumerate(AXES):
        lines.append(f"{name} [{unit}]: {data.bounds[2 * j]:.4g} to {data.bounds[2 * j + 1]:.4g}")
    if data.surface is not None and "surface" in data.scene.show:
        lines.append(f"colour: n on (6.3) [sqrt(g/b)], {data.bounds[4]:.4g} to {data.bounds[5]:.4g}")
    return lines


def _caption_html(path: Path, data, title) -> None:
    """Put the caption into the exported page: the page's title, and a header over the 3-D view
    (the title once, then each axis's true range), clear of the colour bar at the right."""
    import html as _html

    text = Path(path).read_text(encoding="utf-8")
    lines = axes_caption(data, title)
    items = "".join(f"<div>{_html.escape(line)}</div>" for line in lines)
    box = ('<div id="phasekit-caption" style="position:fixed;top:8px;left:8px;max-width:calc(100% - 160px);z-index:10;font:14px sans-serif;'
           f'background:rgba(255,255,255,0.85);color:#000;padding:6px 10px;border-radius:4px">{items}</div>')
    head_title = _html.escape(title or "phasekit scene")
    text = text.replace("<title>VTK.js | Example - OfflineLocalView</title>", f"<title>{head_title}</title>", 1)
    if "<body>" not in text:
        raise PhasekitError("the HTML export has no <body> to caption (an unexpected page layout)")
    # vtk.js replaces what is in its container (.content, else <body>): give it its own
    view = '<div class="content" style="position:absolute;top:0;left:0;width:100%;height:100%"></div>'
    Path(path).write_text(text.replace("<body>", "<body>\n" + view + box, 1), encoding="utf-8")


def _facing(pl) -> tuple[float, np.ndarray]:
    """The turn about the vertical (degrees) that makes upright text face the plotter's camera,
    and the signs that mirror the offsets (:data:`TICK_OFFSETS`) to the camera's side."""
    pos, focal, _ = pl.camera_position
    d = np.asarray(pos, dtype=float) - np.asarray(focal, dtype=float)
    yaw = float(np.degrees(np.arctan2(d[0], -d[1]))) if np.hypot(d[0], d[1]) > 0 else 0.0
    side = np.array([1.0 if d[0] >= 0 else -1.0, 1.0 if d[1] <= 0 else -1.0, 1.0])
    return yaw, side


def _text(text: str, size: float, at, yaw: float):
    """3-D text of height ``size`` standing upright, turned by ``yaw`` about the vertical, centred on ``at``."""
    import pyvista as pv

    mesh = pv.Text3D(text, depth=0.002)
    lo, hi = np.array(mesh.bounds[0::2]), np.array(mesh.bounds[1::2])
    mesh = mesh.translate(-(lo + hi) / 2, inplace=False).scale(size / max(hi[1] - lo[1], 1e-12), inplace=False)
    return mesh.rotate_x(90, inplace=False).rotate_z(yaw, inplace=False).translate(np.asarray(at, float), inplace=False)


def _add_title_geometry(pl, title: str, yaw: float):
    """The title as 3-D text above the box, for the glTF (which keeps meshes, not 2-D text)."""
    top = (0.5 * ASPECT[0], 0.5 * ASPECT[1], ASPECT[2] + 0.25)
    return pl.add_mesh(_text(title.replace("\n", " "), TEXT_SIZES["scene_title"], top, yaw), color="black")


def _add_axes_geometry(pl, bounds, yaw: float, side) -> None:
    """The axes as meshes (exports keep meshes, not VTK's annotation actors): the three axis
    lines, tick marks at round values with their values, and the titles with units."""
    import pyvista as pv

    from ..scenes.scene import AXES

    f = bounding_box(bounds)
    lo = np.array(bounds[0::2], dtype=float)
    hi = np.array(bounds[1::2], dtype=float)
    for j, (name, unit) in enumerate(AXES):
        a, b = lo.copy(), lo.copy()
        b[j] = hi[j]
        pl.add_mesh(pv.Line(f(a)[0], f(b)[0]), color="black", line_width=2)
        for v in tick_values(lo[j], hi[j], gap=CORNER_GAP if j < 2 else CORNER_GAP / 2):
            p = lo.copy()
            p[j] = v
            q = f(p)[0]
            off = side * np.array(TICK_OFFSETS[j])
            pl.add_mesh(pv.Line(q, q + 0.4 * off), color="black", line_width=2)
            pl.add_mesh(_text(f"{v:.4g}", TEXT_SIZES["tick"], q + off, yaw), color="black")
        end = lo.copy()
        end[j] = 0.5 * (lo[j] + hi[j]) if j < 2 else hi[j]  # the vertical axis's title above it
        q = f(end)[0] + side * np.array(TITLE_OFFSETS[j])
        pl.add_mesh(_text(f"{name} [{unit}]", TEXT_SIZES["title"], q, yaw), color="black")


def _annotate_gltf(path: Path, bounds, title=None) -> None:
    """Record the axes (name, unit, range, drawn span), the title and what glTF cannot hold in
    the file's ``asset.extras``."""
    from ..scenes.scene import AXES

    doc = json.loads(Path(path).read_text())
    extras = doc.setdefault("asset", {}).setdefault("extras", {})
    extras["phasekit_axes"] = [
        {"name": name, "unit": unit, "range": [float(bounds[2 * j]), float(bounds[2 * j + 1])],
         "drawn_span": [0.0, ASPECT[j]]} for j, (name, unit) in enumerate(AXES)]
    extras["phasekit_title"] = title
    extras["phasekit_note"] = ("glTF holds meshes only: the axes, their tick values (true values) and the title are "
                               "3-D text; the colour bar and 2-D annotations of the PNG are not in the file")
    Path(path).write_text(json.dumps(doc))
