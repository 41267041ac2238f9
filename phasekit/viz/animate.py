"""The moving body: movies (GIF, MP4), film strips (PNG) and single views, off-screen.

The body is drawn from its own support function: the meridian of the surface relative to G
is, for theta in [0, pi], the contact point of inclination theta, at z = h_t sin(theta) -
h cos(theta) along the axis k and at distance x_P = h sin(theta) + h_t cos(theta) from it
(section 2; a spheroid, an egg, the tippe top's ball and any user body alike). It is placed
by the run's pose (:mod:`phasekit.core.pose`): G at (X, Y, h + gap) and the rotation
R = Rz(psi) Ry(theta) Rz(phi), so one frame is one row of :meth:`Trajectory.sample`. The
tippe top's stem is decoration (the model's body is the ball). Coloured sectors make the
spin about the axis visible; the contact point's path is traced on the table.

GIFs are written with Pillow (no ffmpeg); MP4 needs the optional extra ``phasekit[movie]``
(imageio-ffmpeg, which ships an ffmpeg binary). PyVista is imported only when drawing.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._runtime.errors import ParameterError, PhasekitError
from .._runtime.validate import check_array, check_finite, check_int, check_positive
from .mesh import BODY_COLORS, body_mesh, decorations

__all__ = ["AnimationInfo", "animate", "film_strip", "render_body", "body_mesh", "MOVIE_EXTRA"]

#: what MP4 output needs: ``pip install "phasekit[movie]"``
MOVIE_EXTRA = ("imageio_ffmpeg",)
SUFFIXES = (".gif", ".mp4", ".png")
PATH_COLOR, G_PATH_COLOR, TABLE_COLOR = "#08519c", "#969696", "#f0f0f0"
CAMERAS = ("follow", "fixed")
PANELS = ("none", "phase", "R")
TIMINGS = ("body", "real")


@dataclass(frozen=True)
class AnimationInfo:
    """What was written: the file, the frame count and times (body units), the frame size in
    pixels, the frames per second and, with a scale, the playback speed relative to real time.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> import tempfile, pathlib
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> info = pk.viz.render_body(traj, 40.0, pathlib.Path(tempfile.mkdtemp()) / 'body.png', window_size=(160, 120))
    >>> isinstance(info, pk.viz.AnimationInfo), info.times
    (True, array([40.]))
    """

    path: str
    n_frames: int
    times: np.ndarray
    frame_size: tuple
    fps: float
    speed: float | None = None
    bytes: int = 0


def _check_traj(traj):
    from ..core.trajectory import Trajectory

    if not isinstance(traj, Trajectory):
        raise ParameterError("traj", "must be a phasekit Trajectory (from pk.simulate)", traj)
    if not traj.segments or not all(s.dense for s in traj.segments):
        raise ParameterError("traj", "must keep its dense output (simulate with dense=True, the default)",
                             show_value=False)


def _check_path(path, suffixes=SUFFIXES) -> Path:
    if not isinstance(path, (str, os.PathLike)) or Path(path).suffix.lower() not in suffixes:
        raise ParameterError("path", f"must be a file path ending in {', '.join(suffixes)}", path)
    p = Path(path)
    if p.exists() and p.is_dir():
        raise ParameterError("path", "must be a file path, not a directory", str(path))
    anc = p.resolve().parent
    while not anc.exists() and anc != anc.parent:  # missing directories are made when writing
        anc = anc.parent
    if not anc.is_dir() or not os.access(anc, os.W_OK):
        raise ParameterError("path", f"must be in a writable directory ({anc} is not one)", str(path))
    return p


def _check_span(traj, t_span):
    if t_span is None:
        return traj.t0, traj.t
    try:
        lo, hi = (float(v) for v in t_span)
    except (TypeError, ValueError):
        raise ParameterError("t_span", "must be a pair (t_start, t_stop) of times", t_span) from None
    if not (traj.t0 <= lo < hi <= traj.t):
        raise ParameterError("t_span", f"must satisfy {traj.t0:.10g} <= t_start < t_stop <= {traj.t:.10g} (the run)",
                             [lo, hi])
    return lo, hi


def _check_choice(name, value, choices):
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, f"must be one of {', '.join(choices)}", value)
    return value


def _check_window(value) -> tuple[int, int]:
    what = "must be two integers (width, height) in [64, 4096] pixels"
    try:
        w, h = (int(v) for v in value)
        ok = all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in value) and 64 <= w <= 4096 \
            and 64 <= h <= 4096
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ParameterError("window_size", what, value)
    return w, h


@dataclass(frozen=True)
class _Style:
    """The drawing options shared by animate, film_strip and render_body (validated)."""

    gap_scale: float = 1.0
    camera: str = "follow"
    panel: str = "none"
    window_size: tuple = (480, 360)
    scale: object = None
    title: str | None = None

    @classmethod
    def make(cls, *, gap_scale, camera, panel, window_size, scale, title) -> "_Style":
        from ..core.units import Scale

        gap_scale = check_positive("gap_scale", gap_scale)
        if gap_scale < 1.0:
            raise ParameterError("gap_scale", "must be >= 1 (the factor the gap is drawn larger by)", gap_scale)
        if scale is not None and not isinstance(scale, Scale):
            raise ParameterError("scale", "must be a phasekit Scale such as pk.Scale('21.5 mm'), or None", scale)
        if title is not None and not isinstance(title, str):
            raise ParameterError("title", "must be a string or None", title)
        return cls(gap_scale, _check_choice("camera", camera, CAMERAS),
                   _check_choice("panel", "none" if panel is None else panel, PANELS), _check_window(window_size),
                   scale, title)


class _Stage:
    """One off-screen plotter with the table, the body, the traced paths and the captions;
    :meth:`frame` moves them to a time and returns the image."""

    def __init__(self, traj, style: _Style, span):
        from .pv import _headless

        _headless()
        import pyvista as pv

        self.pv, self.traj, self.style = pv, traj, style
        self.body0 = body_mesh(traj.model.body)
        self.deco0 = [d.triangulate() for d in decorations(traj.model.body)]
        self.pl = pv.Plotter(off_screen=True, window_size=list(style.window_size))
        self.pl.set_background("white")
        # the traced paths: dense enough to follow the precession (30 points per turn at least)
        rate = max(1.0, float(np.nanmax(np.abs(traj.sample(np.linspace(*span, 200))["Omega"]))))
        n_trace = int(min(60000, max(400, 30 * rate * (span[1] - span[0]) / (2 * np.pi))))
        self.trace = traj.sample(np.linspace(traj.t0, span[1], n_trace))
        self.trace_t = self.trace["t"].to_numpy()
        extent = np.ptp(self.trace[["X_P", "Y_P"]].to_numpy(), axis=0).max() + 4.0
        centre = self.trace[["X", "Y"]].to_numpy().mean(axis=0)
        self.pl.add_mesh(pv.Plane(center=(*centre, 0.0), direction=(0, 0, 1), i_size=2 * extent, j_size=2 * extent,
                                  i_resolution=int(2 * extent), j_resolution=int(2 * extent)),
                         color=TABLE_COLOR, show_edges=True, edge_color="#d9d9d9", lighting=False)
        self.body = self.body0.copy()
        self.deco = [d.copy() for d in self.deco0]
        self.pl.add_mesh(self.body, scalars="sector", cmap=list(BODY_COLORS), show_scalar_bar=False,
                         smooth_shading=True)
        for d in self.deco:
            self.pl.add_mesh(d, color="#7f2704", smooth_shading=True)
        self._make_paths()
        font = max(6, round(style.window_size[0] / 45))  # captions that fit the frame's width
        self.text = self.pl.add_text("", position=(8, 6), font_size=font, color="k")
        if style.title:
            top = self.pl.add_text(style.title, position=(8, style.window_size[1] - 6), font_size=font, color="k")
            top.GetTextProperty().SetVerticalJustificationToTop()
        # camera distance and aim: the body's size (and, for a fixed camera, the extent of the path)
        size = float(np.ptp(self.body0.points, axis=0).max())
        self.lift = 0.4 * size
        self.focal0 = np.array([*centre, self.lift])
        self.reach = 2.9 * size + (0.0 if style.camera == "follow" else 1.5 * (extent - 4.0))

    def _place(self, row) -> np.ndarray:
        from ..core.pose import rotation_matrix

        R = rotation_matrix(row["psi"], row["theta"], row["phi"])
        G = np.array([row["X"], row["Y"], row["h"] + self.style.gap_scale * row["gap"]])
        self.body.points = self.body0.points @ R.T + G
        for d, d0 in zip(self.deco, self.deco0):
            d.points = d0.points @ R.T + G
        return G

    def _make_paths(self) -> None:
        """The traced paths of P and G as polylines over every trace point; each frame shows
        the first k of them (by their connectivity, without re-adding actors)."""
        self.paths = []
        for cols, color, z, width in ((("X_P", "Y_P"), PATH_COLOR, 2e-3, 2.5), (("X", "Y"), G_PATH_COLOR, 3e-3, 1.5)):
            pts = np.column_stack([self.trace[cols[0]].to_numpy(), self.trace[cols[1]].to_numpy(),
                                   np.full(len(self.trace), z)])
            mesh = self.pv.PolyData(pts, lines=np.array([2, 0, 1]))  # lines only: no vertex cells
            self.pl.add_mesh(mesh, color=color, line_width=width, render=False)
            self.paths.append(mesh)

    def _paths(self, t: float) -> None:
        k = max(2, int(np.searchsorted(self.trace_t, t, side="right")))
        for mesh in self.paths:
            mesh.lines = np.concatenate([[k], np.arange(k)])

    def caption(self, row) -> str:
        sc = self.style.scale
        clock = f"t = {row['t']:.3f} sqrt(b/g)"
        if sc is not None:
            clock += f" = {sc.to_real(row['t'], 'time').magnitude:.1f} ms"
        lines = [clock, f"{row['mode']}, theta = {row['theta']:.3f} rad"]
        if row["mode"] == "flight":
            gap = (f"gap {row['gap']:.3g} b" if sc is None
                   else f"gap {sc.to_real(row['gap'], 'length').to('um').magnitude:.3g} um")
            lines.append(gap)
        if self.style.gap_scale != 1.0:
            lines.append(f"gap drawn x{self.style.gap_scale:g}")
        return "\n".join(lines)

    def frame(self, row) -> np.ndarray:
        G = self._place(row)
        self._paths(float(row["t"]))
        self.text.SetInput(self.caption(row))
        focal = np.array([G[0], G[1], self.lift]) if self.style.camera == "follow" else self.focal0
        eye = focal + self.reach * np.array([0.59, -0.76, 0.27])  # from the front right, a little above
        self.pl.camera_position = [tuple(eye), tuple(focal), (0.0, 0.0, 1.0)]
        self.pl.render()
        return np.asarray(self.pl.screenshot(return_img=True))[..., :3]

    def close(self) -> None:
        self.pl.close()


class _Panel:
    """The side panel (matplotlib, Agg): R(t) or the trajectory in (Omega, theta, n), with a
    marker at the frame's time."""

    def __init__(self, traj, kind: str, span, height: int):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        self.kind = kind
        ts = np.linspace(*span, 3000)
        df = traj.sample(ts)
        dpi = 100
        self.fig = Figure(figsize=(height / dpi, height / dpi), dpi=dpi)
        self.canvas = FigureCanvasAgg(self.fig)
        if kind == "R":
            ax = self.fig.add_subplot(111)
            ax.plot(ts, df["R"], lw=1, color="k")
            ax.fill_between(ts, 0, 1, where=(df["mode"] == "flight").to_numpy(), color="#9ecae1", alpha=0.6,
                            transform=ax.get_xaxis_transform(), label="flight")
            ax.set_xlabel("t (units sqrt(b/g))")
            ax.set_ylabel("R (units Mg)")
            (self.marker,) = ax.plot([], [], "o", color="#e6550d")
            self.xy = (ts, df["R"].to_numpy())
        else:
            ax = self.fig.add_subplot(111, projection="3d")
            ax.plot(df["Omega"], df["theta"], df["n"], lw=0.8, color="k")
            ax.set_xlabel("Omega")
            ax.set_ylabel("theta")
            ax.set_zlabel("n")
            (self.marker,) = ax.plot([], [], [], "o", color="#e6550d")
            self.xyz = (ts, df[["Omega", "theta", "n"]].to_numpy())
        self.fig.tight_layout()

    def frame(self, t: float) -> np.ndarray:
        if self.kind == "R":
            ts, R = self.xy
            self.marker.set_data([t], [np.interp(t, ts, R)])
        else:
            ts, P = self.xyz
            p = [np.interp(t, ts, P[:, j]) for j in range(3)]
            self.marker.set_data_3d([p[0]], [p[1]], [p[2]])
        self.canvas.draw()
        return np.asarray(self.canvas.buffer_rgba())[..., :3].copy()


def _frames(traj, times, style: _Style, span, progress: bool):
    """Render one image per time (the 3-D view, with the side panel to its right)."""
    from ..sweep.study import progress as bar

    rows = traj.sample(times)
    stage = _Stage(traj, style, span)
    panel = None if style.panel == "none" else _Panel(traj, style.panel, span, style.window_size[1])
    out = []
    try:
        for i in bar(range(len(rows)), desc="frames", enabled=progress and len(rows) > 10):
            row = rows.iloc[i]
            img = stage.frame(row)
            if panel is not None:
                img = np.hstack([img, panel.frame(float(row["t"]))[: img.shape[0]]])
            out.append(img)
    finally:
        stage.close()
    return out


def _times(traj, frames, span, timing, scale):
    if timing == "real" and scale is None:
        raise ParameterError("timing", "real needs `scale` (a pk.Scale giving the body's size)", timing)
    return np.linspace(span[0], span[1], frames)


def _even(img: np.ndarray, block: int = 16) -> np.ndarray:
    """Pad an image to a multiple of ``block`` pixels per side (H.264 encodes macroblocks)."""
    h, w = img.shape[:2]
    H, W = -(-h // block) * block, -(-w // block) * block
    return np.pad(img, ((0, H - h), (0, W - w), (0, 0)), constant_values=255)


def _write(frames, path: Path, fps: float) -> None:
    from ..sweep.study import atomic_path

    suffix = path.suffix.lower()
    with atomic_path(path) as tmp:
        if suffix == ".gif":
            from PIL import Image

            imgs = [Image.fromarray(f).quantize(colors=128, method=Image.Quantize.MEDIANCUT) for f in frames]
            imgs[0].save(tmp, save_all=True, append_images=imgs[1:], duration=int(round(1000 / fps)), loop=0,
                         disposal=1)
        elif suffix == ".mp4":
            import imageio_ffmpeg

            imgs = [_even(f) for f in frames]
            h, w = imgs[0].shape[:2]
            writer = imageio_ffmpeg.write_frames(str(tmp), (w, h), fps=fps, codec="libx264", pix_fmt_out="yuv420p",
                                                 quality=7, macro_block_size=16, ffmpeg_log_level="error")
            writer.send(None)
            for f in imgs:
                writer.send(np.ascontiguousarray(f))
            writer.close()
        else:
            from PIL import Image

            Image.fromarray(frames[0]).save(tmp)


def check_movie_options(path, *, frames=96, fps=24.0, timing="body", gap_scale=1.0, camera="follow", panel=None,
                        window_size=(480, 360), scale=None) -> None:
    """Validate the options of :func:`animate` before anything is simulated or drawn (the CLI
    calls this first, so a bad option costs no simulation)."""
    path = _check_path(path)
    check_int("frames", frames, minimum=1, maximum=10_000)
    check_positive("fps", fps, upper=240.0)
    if _check_choice("timing", timing, TIMINGS) == "real" and scale is None:
        raise ParameterError("timing", "real needs `scale` (a pk.Scale giving the body's size)", timing)
    _Style.make(gap_scale=gap_scale, camera=camera, panel=panel, window_size=window_size, scale=scale, title=None)
    _check_movie_extra(path)


def _check_movie_extra(path: Path) -> None:
    if path.suffix.lower() == ".mp4":
        import importlib.util

        missing = [m for m in MOVIE_EXTRA if importlib.util.find_spec(m) is None]
        if missing:
            raise PhasekitError(f"cannot write the MP4 {path}: it needs {', '.join(missing)} (pip install "
                                "\"phasekit[movie]\"); a .gif needs nothing more")


def animate(traj, path, frames: int = 96, *, fps: float = 24.0, t_span=None, timing: str = "body", scale=None,
            gap_scale: float = 1.0, camera: str = "follow", panel: str | None = None, window_size=(480, 360),
            title: str | None = None, progress: bool = True) -> AnimationInfo:
    """Write a movie of the moving body: GIF (Pillow) or MP4 (``phasekit[movie]``).

    Parameters
    ----------
    traj : Trajectory
        A run with its dense output (the default of :func:`phasekit.simulate`).
    path : str or Path
        Ending in .gif or .mp4 (.png writes the first frame only; see :func:`film_strip`).
    frames : int
        Number of frames, in [1, 10000], at times uniform over ``t_span``.
    fps : float
        Frames per second of the movie.
    t_span : (float, float), optional
        The stretch of the run to show (default the whole run).
    timing : {"body", "real"}
        "body": the clock shows the body's time; "real" (needs ``scale``): also seconds, and
        the playback speed relative to real time (frames / fps against the span in seconds)
        is printed and returned.
    scale : Scale, optional
        The body's size: the clock in ms and gaps in micrometres.
    gap_scale : float >= 1
        Draw the gap in flight this many times larger (micrometre flights); printed on every
        frame when not 1.
    camera : {"follow", "fixed"}
        Keep G in view, or one view of the whole path.
    panel : {None, "R", "phase"}
        A side panel with R(t), or the trajectory in (Omega, theta, n), advancing with the movie.
    window_size : (int, int)
        Pixels of the 3-D view (the panel adds a square of the same height).
    title : str, optional
        A line at the top of every frame.
    progress : bool
        A progress bar on stderr for more than 10 frames.

    Returns
    -------
    AnimationInfo

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> import tempfile, pathlib
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0, stop_at='touchdown')
    >>> info = pk.viz.animate(traj, pathlib.Path(tempfile.mkdtemp()) / 'spin.gif', frames=4, window_size=(160, 120), progress=False)
    >>> info.n_frames, info.frame_size
    (4, (160, 120))
    """
    _check_traj(traj)
    path = _check_path(path)
    frames = check_int("frames", frames, minimum=1, maximum=10_000)
    fps = check_positive("fps", fps, upper=240.0)
    span = _check_span(traj, t_span)
    timing = _check_choice("timing", timing, TIMINGS)
    style = _Style.make(gap_scale=gap_scale, camera=camera, panel=panel, window_size=window_size, scale=scale,
                        title=title)
    _check_movie_extra(path)
    times = _times(traj, frames, span, timing, scale)
    speed = None
    if scale is not None:
        real_s = float(scale.to_real(span[1] - span[0], "time").to("s").magnitude)
        speed = real_s / (frames / fps)
    if timing == "real" and speed is not None:
        style = _Style(style.gap_scale, style.camera, style.panel, style.window_size, style.scale,
                       ((style.title + "\n") if style.title else "") + f"playback {speed:.3g}x real time")
    imgs = _frames(traj, times, style, span, progress)
    _write(imgs, path, fps)
    return AnimationInfo(str(path), len(imgs), times, tuple(imgs[0].shape[:2][::-1]), fps, speed, path.stat().st_size)


def film_strip(traj, path, frames: int = 6, *, t_span=None, times=None, columns: int | None = None, scale=None,
               gap_scale: float = 1.0, camera: str = "follow", window_size=(360, 300), title: str | None = None):
    """A PNG of the body at several instants side by side (the same drawing as :func:`animate`).

    ``times`` (inside the run) or ``frames`` instants uniform over ``t_span``; ``columns``
    per row (default all in one row). Returns an :class:`AnimationInfo`.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> import tempfile, pathlib
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0, stop_at='touchdown')
    >>> info = pk.viz.film_strip(traj, pathlib.Path(tempfile.mkdtemp()) / 'strip.png', frames=3, window_size=(120, 100))
    >>> info.n_frames
    3
    """
    _check_traj(traj)
    path = _check_path(path, (".png",))
    span = _check_span(traj, t_span)
    if times is None:
        times = np.linspace(span[0], span[1], check_int("frames", frames, minimum=1, maximum=100))
    else:
        times = check_array("times", times).ravel()
        times.sort()
        if times.size > 100 or times[0] < traj.t0 or times[-1] > traj.t:
            raise ParameterError("times", f"must be 1 to 100 times inside the run [{traj.t0:.10g}, {traj.t:.10g}]",
                                 times.tolist())
    style = _Style.make(gap_scale=gap_scale, camera=camera, panel=None, window_size=window_size, scale=scale,
                        title=None)
    imgs = _frames(traj, times, style, (span[0], max(span[1], float(times[-1]))), progress=False)
    cols = len(imgs) if columns is None else check_int("columns", columns, minimum=1, maximum=100)
    rows = [np.hstack(imgs[i:i + cols] + [np.full_like(imgs[0], 255)] * (cols - len(imgs[i:i + cols])))
            for i in range(0, len(imgs), cols)]
    strip = np.vstack(rows)
    if title:
        strip = _with_title(strip, title)
    _write([strip], path, 1.0)
    return AnimationInfo(str(path), len(imgs), times, tuple(strip.shape[:2][::-1]), 0.0, None, path.stat().st_size)


def _with_title(img: np.ndarray, title: str) -> np.ndarray:
    """A white band with ``title`` above ``img`` (PIL's default font)."""
    from PIL import Image, ImageDraw, ImageFont

    try:
        font = ImageFont.load_default(size=18)
    except TypeError:  # Pillow < 10.1: one bitmap size
        font = ImageFont.load_default()
    band = Image.new("RGB", (img.shape[1], 30), "white")
    ImageDraw.Draw(band).text((8, 5), title, fill="black", font=font)
    return np.vstack([np.asarray(band), img])


def render_body(traj, t: float, path, *, scale=None, gap_scale: float = 1.0, window_size=(640, 480), title=None):
    """A PNG of the body at time ``t`` of ``traj`` (placed by its pose), with the path traced
    up to then. Returns an :class:`AnimationInfo` with one frame.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> import tempfile, pathlib
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> pk.viz.render_body(traj, 40.0, pathlib.Path(tempfile.mkdtemp()) / 'body.png', window_size=(160, 120)).n_frames
    1
    """
    _check_traj(traj)
    t = check_finite("t", t)
    if not traj.t0 <= t <= traj.t:
        raise ParameterError("t", f"must lie in the run [{traj.t0:.10g}, {traj.t:.10g}]", t)
    path = _check_path(path, (".png",))
    style = _Style.make(gap_scale=gap_scale, camera="follow", panel=None, window_size=window_size, scale=scale,
                        title=title)
    imgs = _frames(traj, np.array([t]), style, (traj.t0, traj.t), progress=False)
    _write(imgs, path, 1.0)
    return AnimationInfo(str(path), 1, np.array([t]), tuple(imgs[0].shape[:2][::-1]), 0.0, None, path.stat().st_size)
