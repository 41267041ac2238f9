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
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ParameterError, PhasekitError
from .box import ASPECT, bounding_box, inside_runs  # noqa: F401 (the studies' scenes draw in the same box)
from .export import axes_caption, export_scene  # noqa: F401 (axes_caption: what an exported scene's caption says)

#: the optional packages the HTML export needs: ``pip install "phasekit[html]"`` (pyvista's
#: export starts trame's server in-process, which needs nest_asyncio2 outside Jupyter)
HTML_EXTRA = ("trame_pyvista", "nest_asyncio2")
#: what the interactive 3-D view in Jupyter needs: ``pip install "phasekit[notebook]"``. pyvista's
#: interactive backends ("trame", "server", "client", "html") come from trame-pyvista, which shows
#: each scene as an anywidget widget (trame_pyvista/jupyter.py raises for want of anywidget)
NOTEBOOK_EXTRA = ("trame_pyvista", "anywidget", "ipywidgets")
COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666")


@dataclass(frozen=True)
class RenderInfo:
    """What was drawn: the image path, point counts per element, data bounds, image statistics
    and the files exported.

    Attributes
    ----------
    path : str
        The PNG written.
    n_points : dict
        Counts per element drawn: points of the "surface", the "exact_boundary" and the
        "trajectories", and the number of "bodies", "crossings" and "fixed_points".
    bounds : tuple of float
        The data's bounds, (Omega_min, Omega_max, theta_min, theta_max, n_min, n_max).
    image_shape : tuple of int
        The image's shape, (height, width, 3).
    image_std : float
        Standard deviation of the image's pixel values (0 for a blank image).
    exported : tuple of str
        The glTF and HTML files written.

    Examples
    --------
    >>> import phasekit as pk
    >>> import tempfile, pathlib
    >>> data = pk.compute_scene(pk.Scene('prolate', 1.5, values=(12.0,), resolution=20))
    >>> info = pk.viz.render_scene(data, pathlib.Path(tempfile.mkdtemp()) / 'scene.png', window_size=(200, 150))
    >>> isinstance(info, pk.viz.pv.RenderInfo), pathlib.Path(info.path).name
    (True, 'scene.png')
    """

    path: str
    n_points: dict
    bounds: tuple
    image_shape: tuple
    image_std: float
    exported: tuple = ()


@contextlib.contextmanager
def quiet_vtk():
    """VTK warnings off while drawing (they would go to stderr); errors still show."""
    from vtkmodules.vtkCommonCore import vtkLogger as logger

    old = logger.GetCurrentVerbosityCutoff()
    logger.SetStderrVerbosity(logger.VERBOSITY_ERROR)
    try:
        yield
    finally:
        logger.SetStderrVerbosity(old)


def headless() -> None:
    """Before the first 3-D drawing: pyvista must be installed (it is the optional extra [viz]:
    VTK is ~580 MB), and without a display VTK's EGL window is picked before the first one is
    made (VTK otherwise tries X first and prints 'bad X server connection')."""
    if importlib.util.find_spec("pyvista") is None:
        raise PhasekitError('3-D drawing needs pyvista: pip install "phasekit[viz]"')
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


#: the image size's range, pixels per side
WINDOW_RANGE = (16, 8192)
#: PyVista's named views (``camera="xy"`` looks down z, "iso" is isometric)
CAMERA_NAMES = ("xy", "xz", "yz", "yx", "zx", "zy", "iso")
#: the file types written, per argument
SUFFIXES = {"path": (".png",), "gltf": (".gltf",), "html": (".html", ".htm")}


class _UnwritableError(ParameterError, PhasekitError):
    """A target file that cannot be written: a ParameterError naming the argument, and (as
    before these checks) a PhasekitError."""


def _what(name: str) -> str:
    return "the PNG" if name == "path" else f"the {name} export"


def check_file(name: str, target, *, create: bool = False) -> Path:
    """A file path of the argument's type (suffix) whose directory exists (``create``: or can
    be created) and is writable; nothing is written yet."""
    kinds = " or ".join(SUFFIXES[name])
    if not isinstance(target, (str, os.PathLike)) or not isinstance(os.fspath(target), str) or not str(target).strip():
        raise ParameterError(name, f"must be a file path ending in {kinds}", target)
    p = Path(target)
    if p.suffix not in SUFFIXES[name]:
        raise ParameterError(name, f"must be a file path ending in {kinds}", str(target))
    try:
        resolved = p.resolve()
        is_dir = resolved.is_dir()
    except (OSError, ValueError, RuntimeError):
        raise ParameterError(name, f"must be a usable file path ending in {kinds}", str(target)) from None
    if is_dir:
        raise ParameterError(name, "must be a file path, not a directory", str(target))
    parent = resolved.parent
    if create:  # the nearest existing ancestor must be a directory (the rest is made before drawing)
        anc = parent
        while not anc.exists() and anc != anc.parent:
            anc = anc.parent
        parent = anc
    if not parent.is_dir() or not os.access(parent, os.W_OK):
        raise _UnwritableError(name, f"must be a path in a writable directory (cannot write {_what(name)} there: "
                                     f"{parent} is missing, not a directory or not writable)", str(target))
    return p


def _probe(name: str, target: Path) -> None:
    """Make the directory of ``target`` if missing and write (and remove) a file in it: catches
    what os.access does not (read-only and special file systems, running as root)."""
    import tempfile

    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=".phasekit-probe-")
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise _UnwritableError(name, f"must be a path in a writable directory (cannot write {_what(name)} there: "
                                     f"{exc.strerror or exc})", str(target)) from None


def check_window_size(value) -> tuple[int, int]:
    lo, hi = WINDOW_RANGE
    what = f"must be two integers (width, height) in [{lo}, {hi}] pixels"
    if isinstance(value, (str, bytes, dict, set)) or not np.iterable(value):
        raise ParameterError("window_size", what, value)
    size = list(value)
    if len(size) != 2 or not all(isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_)) for v in size):
        raise ParameterError("window_size", what, size)
    if not all(lo <= int(v) <= hi for v in size):
        raise ParameterError("window_size", what, size)
    return int(size[0]), int(size[1])


def _check_camera(camera):
    """None, a PyVista view name, a view vector (3 numbers) or (position, focal point, view up)."""
    what = (f"must be None, one of {', '.join(CAMERA_NAMES)}, a view direction (3 finite numbers, not all 0) or "
            "[position, focal point, view up] (three triples of finite numbers, the position away from the focal "
            "point, view up not along the line of sight)")
    if camera is None:
        return None
    if isinstance(camera, str):
        if camera.lower() not in CAMERA_NAMES:
            raise ParameterError("camera", what, camera)
        return camera
    if hasattr(camera, "to_list"):  # a pyvista CameraPosition
        camera = camera.to_list()
    if isinstance(camera, (bytes, dict, set)) or not np.iterable(camera):
        raise ParameterError("camera", what, camera)
    try:
        arr = np.array(camera, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("camera", what, camera) from None
    if not np.all(np.isfinite(arr)) or arr.shape not in ((3,), (3, 3)):
        raise ParameterError("camera", what, arr if arr.ndim else camera)
    if arr.shape == (3,):
        if not np.any(arr != 0):
            raise ParameterError("camera", what, arr)
        return [float(v) for v in arr]
    pos, focal, up = arr
    sight = focal - pos
    if not np.linalg.norm(sight) > 0 or not np.linalg.norm(np.cross(sight, up)) > 1e-12 * np.linalg.norm(sight) * (
            np.linalg.norm(up) or 1.0):
        raise ParameterError("camera", what, arr)
    return [tuple(float(v) for v in row) for row in arr]


def notebook_backend() -> str:
    """The Jupyter backend for a plotter of :func:`render_scene` when the user chose none:
    ``"html"`` when everything of :data:`NOTEBOOK_EXTRA` is installed (the scene in the browser,
    vtk.js: rotate and zoom), else ``"static"`` (an image made in the kernel). Neither fetches
    anything; pyvista's own choice with trame-pyvista installed, ``"trame"``, starts a trame server
    in the kernel whose trame-vtklocal downloads VTK's WebAssembly build from gitlab.kitware.com
    the first time (trame_vtklocal/module/wasm.py), and without anywidget it raises."""
    return "html" if all(importlib.util.find_spec(m) is not None for m in NOTEBOOK_EXTRA) else "static"


def _check_exports(html, gltf) -> None:
    """Fail before drawing when an export cannot be written (one line, naming the fix)."""
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
        Where to write the PNG (a missing directory is made). Without it, nothing is written: the plotter is returned
        (call ``.show()`` on it; it is off-screen only if ``off_screen=True``).
    window_size : (int, int)
        Image width and height in pixels, each in [16, 8192].
    html, gltf : str, optional
        Also export as interactive HTML (vtk.js, ``phasekit[html]``) or glTF, with the axes'
        true tick values and the title as geometry; the HTML adds a caption (title, each
        axis's range), the glTF puts them in ``asset.extras`` (it has no 2-D text).
    title : str, optional
        Text at the top left.
    camera : str or list, optional
        A PyVista view name (xy, xz, yz, yx, zx, zy, iso), a view direction (3 numbers) or
        [position, focal point, view up] in the drawn box's coordinates (default: one per branch).
    off_screen : bool, optional
        Default: True when writing a PNG, False when returning the plotter.

    Returns
    -------
    RenderInfo or pyvista.Plotter
        RenderInfo when ``path`` is given, else the plotter.

    Notes
    -----
    In Jupyter, ``render_scene(data).show()`` draws in the cell with pyvista's Jupyter backend
    ``"html"`` when ``phasekit[notebook]`` is installed (trame-pyvista, anywidget, ipywidgets:
    the scene drawn in the browser by vtk.js, to rotate and zoom) and ``"static"`` without it (a
    PNG made in the kernel). Neither reaches the internet. pyvista's own default with
    trame-pyvista installed (as ``phasekit[html]`` installs it) would be ``"trame"``, which raises
    for want of anywidget without the extra and, with it, starts a trame server in the kernel
    that downloads VTK's WebAssembly build the first time. Choose a backend for one plot with
    ``.show(jupyter_backend="static")`` (or ``"html"``, ``"trame"``, ``"server"``, ``"client"``),
    for the session with ``pyvista.set_jupyter_backend(...)`` or the environment variable
    ``PYVISTA_JUPYTER_BACKEND``: a backend chosen so is kept.

    Raises
    ------
    ParameterError
        A bad argument, named (before anything is computed or drawn). A target file that cannot
        be written (``path``, ``html``, ``gltf``: wrong suffix, missing or read-only directory)
        is one too; that one is also a PhasekitError.
    PhasekitError
        When the HTML export's optional packages are missing: before anything is drawn.

    Examples
    --------
    >>> import phasekit as pk
    >>> import tempfile, pathlib
    >>> data = pk.compute_scene(pk.Scene('prolate', 1.5, values=(12.0,), resolution=20))
    >>> info = pk.viz.render_scene(data, pathlib.Path(tempfile.mkdtemp()) / 'scene.png', window_size=(200, 150))
    >>> info.image_shape
    (150, 200, 3)
    """
    from ..scenes.scene import Scene, compute_scene

    path, window_size, camera = _checked_render(data, path, window_size, html, gltf, title, camera, off_screen)
    if isinstance(data, Scene):
        data = compute_scene(data)
    if data.bounds is None:
        raise ParameterError("data", "must be a Scene or what compute_scene returned", data)
    headless()
    import pyvista as pv

    off = (path is not None) if off_screen is None else bool(off_screen)
    with quiet_vtk():
        pl = pv.Plotter(off_screen=off, window_size=list(window_size))
        counts = _draw(pl, data, title, window_size)
        pl.camera_position = camera or CAMERAS[data.scene.branch]
        if path is None:
            if pl.notebook and pl.theme.jupyter_backend is None:  # none chosen (pyvista.set_jupyter_backend)
                pl.theme.jupyter_backend = notebook_backend()
            return pl
        img = pl.screenshot(str(path), return_img=True)
        exported = export_scene(pl, data, html, gltf, title)
        pl.close()
    return RenderInfo(str(path), counts, tuple(float(b) for b in data.bounds), tuple(img.shape), float(img.std()),
                      tuple(exported))


def _checked_render(data, path, window_size, html, gltf, title, camera, off_screen):
    """render_scene's arguments checked before anything is computed or drawn: (path, window_size, camera)."""
    from ..scenes.scene import Scene, SceneData

    if not isinstance(data, (Scene, SceneData)):
        raise ParameterError("data", "must be a Scene or what compute_scene returned", data)
    if path is not None:
        path = check_file("path", path, create=True)
    window_size = check_window_size(window_size)
    for name, target in (("html", html), ("gltf", gltf)):
        if target is not None:
            if path is None:
                raise ParameterError(name, "needs `path`: the exports are written with the PNG", str(target))
            check_file(name, target)
    if title is not None and not isinstance(title, str):
        raise ParameterError("title", "must be a string or None", title)
    camera = _check_camera(camera)
    if off_screen is not None and not isinstance(off_screen, (bool, np.bool_)):
        raise ParameterError("off_screen", "must be True, False or None", off_screen)
    _check_exports(html, gltf)
    for name, target in (("path", path), ("html", html), ("gltf", gltf)):
        if target is not None:
            _probe(name, Path(target))
    return path, window_size, camera


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
    f = bounding_box(data.bounds)
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
            for run in inside_runs(tr, data.bounds):
                line = pv.lines_from_points(f(run))
                counts["trajectories"] += line.n_points
                pl.add_mesh(line, color=COLORS[k % len(COLORS)], line_width=2.5)
    if data.bodies:
        counts["bodies"] = _draw_bodies(pl, data, f)
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
        from ..scenes.scene import AXES

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


#: size of a body drawn in a scene, in drawn-box units (the box is 1.4 x 1 x 1)
BODY_GLYPH = 0.16


def _draw_bodies(pl, data, f) -> int:
    """The bodies of Scene.add_trajectory(..., bodies=times): each body's own surface, turned as
    it was then, at its trajectory's point (those outside the box are left out)."""
    from .mesh import BODY_COLORS, body_mesh

    lo, hi = np.array(data.bounds[0::2]), np.array(data.bounds[1::2])
    n = 0
    for body, point, R in data.bodies:
        P = np.asarray(point, dtype=float)
        if not np.all((P >= lo) & (P <= hi)):
            continue
        mesh = body_mesh(body, n_theta=32, n_azimuth=24)
        scale = BODY_GLYPH / float(np.ptp(mesh.points, axis=0).max())
        mesh.points = (mesh.points @ np.asarray(R).T) * scale + f(P)[0]
        pl.add_mesh(mesh, scalars="sector", cmap=list(BODY_COLORS), show_scalar_bar=False, smooth_shading=True)
        n += 1
    return n
