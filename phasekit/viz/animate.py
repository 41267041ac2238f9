"""The moving body: movies (GIF, MP4), film strips (PNG) and single views, off-screen: the
options checked, the frames (drawn by :mod:`phasekit.viz.frames`) written to a file.

GIFs are written with Pillow (no ffmpeg); MP4 needs the optional extra ``phasekit[movie]``
(imageio-ffmpeg, which ships an ffmpeg binary). PyVista is imported only when drawing.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._runtime.validate import check_array, check_finite, check_int, check_positive
from ..errors import ParameterError, PhasekitError
from .frames import Style, check_choice, render_frames

#: what MP4 output needs: ``pip install "phasekit[movie]"``
MOVIE_EXTRA = ("imageio_ffmpeg",)
SUFFIXES = (".gif", ".mp4", ".png")
TIMINGS = ("body", "real")


@dataclass(frozen=True)
class AnimationInfo:
    """What was written: the file, the frame count and times (body units), the frame size in
    pixels, the frames per second and, with a scale, the playback speed relative to real time.

    Attributes
    ----------
    path : str
        The file written.
    n_frames : int
        The number of frames.
    times : numpy.ndarray
        The frames' times, units sqrt(b/g).
    frame_size : tuple of int
        (width, height) of a frame (of the whole image for a film strip), pixels.
    fps : float
        Frames per second of a movie (0 for a PNG).
    speed : float or None
        The playback speed relative to real time (movies given a ``scale``), else None.
    bytes : int
        The size of the file written, bytes.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> import tempfile, pathlib
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> info = pk.viz.render_body(traj, 40.0, pathlib.Path(tempfile.mkdtemp()) / 'body.png', window_size=(160, 120))
    >>> from phasekit.viz.animate import AnimationInfo
    >>> isinstance(info, AnimationInfo), info.times
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
        raise ParameterError("traj", "must keep its dense output (simulate with dense=True, the default)"
                             + _dropped(traj), show_value=False)


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
    from ..io import atomic_path

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
    if check_choice("timing", timing, TIMINGS) == "real" and scale is None:
        raise ParameterError("timing", "real needs `scale` (a pk.Scale giving the body's size)", timing)
    Style.make(gap_scale=gap_scale, camera=camera, panel=panel, window_size=window_size, scale=scale, title=None)
    _check_movie_extra(path)


def _check_movie_extra(path: Path) -> None:
    """Every optional dependency of the output, checked before anything is simulated."""
    import importlib.util

    if importlib.util.find_spec("pyvista") is None:
        raise PhasekitError(f'cannot draw {path}: 3-D drawing needs pyvista (pip install "phasekit[viz]")')
    if path.suffix.lower() == ".mp4":
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
        Frames per second of the movie, in (0, 240].
    t_span : (float, float), optional
        The stretch of the run to show (default the whole run).
    timing : {"body", "real"}
        "real" (needs ``scale``): the playback speed relative to real time (frames / fps
        against the span in seconds) is printed on every frame (and returned with a scale).
    scale : Scale, optional
        The body's size: every label in real units (clock in ms, s over 10 s; gaps in mm;
        the panel's R in N with the Scale's mass, else M g; rates in rev/s).
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
        The file, its frames and their times, and the playback speed (with ``scale``).

    Raises
    ------
    ParameterError
        A bad argument, named (before anything is drawn): ``traj`` not a Trajectory with
        dense output, ``path`` not ending in .gif, .mp4 or .png or not in a writable
        directory, ``frames`` or ``fps`` out of range, ``t_span`` not inside the run,
        ``timing`` not "body" or "real" (or "real" without ``scale``), ``scale`` not a Scale,
        ``gap_scale`` < 1, ``camera`` or ``panel`` not one of its choices, ``window_size`` not
        two integers in [64, 4096], or ``title`` not a string.
    PhasekitError
        If an MP4 is asked for without ``phasekit[movie]``, or pyvista (the extra
        ``phasekit[viz]``) is not installed.

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
    timing = check_choice("timing", timing, TIMINGS)
    style = Style.make(gap_scale=gap_scale, camera=camera, panel=panel, window_size=window_size, scale=scale,
                        title=title)
    _check_movie_extra(path)
    times = _times(traj, frames, span, timing, scale)
    style, speed = _playback(style, scale, span, frames, fps, timing)
    imgs = render_frames(traj, times, style, span, progress)
    _write(imgs, path, fps)
    return AnimationInfo(str(path), len(imgs), times, tuple(imgs[0].shape[:2][::-1]), fps, speed, path.stat().st_size)


def _playback(style: Style, scale, span, frames: int, fps: float, timing: str) -> tuple[Style, float | None]:
    """The playback speed of :func:`animate`'s movie relative to real time (None without a
    scale), and the style with it added to the title when ``timing`` is "real"."""
    speed = None
    if scale is not None:
        real_s = float(scale.to_real(span[1] - span[0], "time").to("s").magnitude)
        speed = real_s / (frames / fps)
    if timing == "real" and speed is not None:
        style = Style(style.gap_scale, style.camera, style.panel, style.window_size, style.scale,
                       ((style.title + "\n") if style.title else "") + f"playback {speed:.3g}x real time")
    return style, speed


def film_strip(traj, path, frames: int = 6, *, t_span=None, times=None, columns: int | None = None, scale=None,
               gap_scale: float = 1.0, camera: str = "follow", window_size=(360, 300), title: str | None = None):
    """A PNG of the body at several instants side by side (the same drawing as :func:`animate`).

    Parameters
    ----------
    traj : Trajectory
        A run with its dense output (the default of :func:`phasekit.simulate`).
    path : str or Path
        Ending in .png.
    frames : int
        Number of instants uniform over ``t_span``, in [1, 100] (default 6), when ``times``
        is not given.
    t_span : (float, float), optional
        The stretch of the run to show (default the whole run).
    times : array, optional
        The instants instead: 1 to 100 times inside the run.
    columns : int, optional
        Images per row, in [1, 100] (default all in one row).
    scale : Scale, optional
        The body's size: the clock in ms (s for a span over 10 s) and gaps in mm.
    gap_scale : float >= 1
        Draw the gap in flight this many times larger.
    camera : {"follow", "fixed"}
        Keep G in view, or one view of the whole path.
    window_size : (int, int)
        Pixels of each view, each in [64, 4096].
    title : str, optional
        A line above the strip.

    Returns
    -------
    AnimationInfo
        The PNG, with ``n_frames`` the number of instants.

    Raises
    ------
    ParameterError
        A bad argument, named: ``traj`` not a Trajectory with dense output, ``path`` not a
        .png in a writable directory, ``frames``, ``times`` or ``columns`` out of range,
        ``t_span`` not inside the run, ``scale`` not a Scale, ``gap_scale`` < 1, ``camera``
        not one of its choices, or ``window_size`` not two integers in [64, 4096].
    PhasekitError
        If pyvista (the extra ``phasekit[viz]``) is not installed.

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
    style = Style.make(gap_scale=gap_scale, camera=camera, panel=None, window_size=window_size, scale=scale,
                        title=None)
    imgs = render_frames(traj, times, style, (span[0], max(span[1], float(times[-1]))), progress=False)
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
    up to then.

    Parameters
    ----------
    traj : Trajectory
        A run with its dense output (the default of :func:`phasekit.simulate`).
    t : float
        The time, inside the run.
    path : str or Path
        Ending in .png.
    scale : Scale, optional
        The body's size: the clock in ms (s for a span over 10 s) and gaps in mm.
    gap_scale : float >= 1
        Draw the gap in flight this many times larger.
    window_size : (int, int)
        Pixels of the image, each in [64, 4096].
    title : str, optional
        A line at the top of the image.

    Returns
    -------
    AnimationInfo
        With one frame.

    Raises
    ------
    ParameterError
        A bad argument, named: ``traj`` not a Trajectory with dense output, ``t`` not a
        finite time inside the run, ``path`` not a .png in a writable directory, ``scale``
        not a Scale, ``gap_scale`` < 1, ``window_size`` not two integers in [64, 4096], or
        ``title`` not a string.
    PhasekitError
        If pyvista (the extra ``phasekit[viz]``) is not installed.

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
    style = Style.make(gap_scale=gap_scale, camera="follow", panel=None, window_size=window_size, scale=scale,
                        title=title)
    imgs = render_frames(traj, np.array([t]), style, (traj.t0, traj.t), progress=False)
    _write(imgs, path, 1.0)
    return AnimationInfo(str(path), 1, np.array([t]), tuple(imgs[0].shape[:2][::-1]), 0.0, None, path.stat().st_size)


def _dropped(traj) -> str:
    """The clause of a run that dropped its dense output under ``max_dense_mb`` (else empty)."""
    from ..core.energy import dropped_note

    note = dropped_note(traj)
    return f": {note}" if note else ""
