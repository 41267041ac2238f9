"""The frames of the moving body: the drawing options, the off-screen 3-D stage and the side
panel, and the rendering of one image per time (:mod:`phasekit.viz.animate` writes them out).

The body is drawn from its own support function: the meridian of the surface relative to G
is, for theta in [0, pi], the contact point of inclination theta, at z = h_t sin(theta) -
h cos(theta) along the axis k and at distance x_P = h sin(theta) + h_t cos(theta) from it
(section 2; a spheroid, an egg, the tippe top's ball and any user body alike). It is placed
by the run's pose (:mod:`phasekit.core.pose`): G at (X, Y, h + gap) and the rotation
R = Rz(psi) Ry(theta) Rz(phi), so one frame is one row of :meth:`Trajectory.sample`. A body
with an outline (an edge, or pieces: the tippe top with its stem) is drawn from it; the stem of
the tippe top modelled as a ball alone is decoration. Coloured sectors make the
spin about the axis visible; the contact point's path is traced on the table.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_positive
from ..errors import ParameterError
from .mesh import BODY_COLORS, body_mesh, decorations

PATH_COLOR, G_PATH_COLOR, TABLE_COLOR = "#08519c", "#969696", "#f0f0f0"
CAMERAS = ("follow", "fixed")
PANELS = ("none", "phase", "R")


def check_choice(name, value, choices):
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
class Style:
    """The drawing options shared by animate, film_strip and render_body (validated)."""

    gap_scale: float = 1.0
    camera: str = "follow"
    panel: str = "none"
    window_size: tuple = (480, 360)
    scale: object = None
    title: str | None = None

    @classmethod
    def make(cls, *, gap_scale, camera, panel, window_size, scale, title) -> "Style":
        from ..core.units import Scale

        gap_scale = check_positive("gap_scale", gap_scale)
        if gap_scale < 1.0:
            raise ParameterError("gap_scale", "must be >= 1 (the factor the gap is drawn larger by)", gap_scale)
        if scale is not None and not isinstance(scale, Scale):
            raise ParameterError("scale", "must be a phasekit Scale such as pk.Scale('21.5 mm'), or None", scale)
        if title is not None and not isinstance(title, str):
            raise ParameterError("title", "must be a string or None", title)
        return cls(gap_scale, check_choice("camera", camera, CAMERAS),
                   check_choice("panel", "none" if panel is None else panel, PANELS), _check_window(window_size),
                   scale, title)


class _Units:
    """The units a frame is labelled in: the body's (sqrt(b/g), M g, b) without a Scale; with
    one, real units: time in ms (s for a span over 10 s), R in N (in M g when the Scale has no
    mass), gaps in mm, rates in rev/s."""

    def __init__(self, scale, span):
        self.scale, self.real = scale, scale is not None
        long = self.real and float(scale.to_real(span[1] - span[0], "time", "s").magnitude) > 10.0
        self.time_unit = "sqrt(b/g)" if not self.real else "s" if long else "ms"
        self.force_unit = "N" if self.real and scale.mass is not None else "M g"
        self.gap_unit, self.rate_unit = ("mm", "rev/s") if self.real else ("b", "sqrt(g/b)")

    def _to(self, value, kind: str, unit: str):
        if not self.real or unit in ("M g", "b", "sqrt(b/g)", "sqrt(g/b)"):
            return value
        value = float(value) if np.ndim(value) == 0 else np.asarray(value, dtype=float)
        return self.scale.to_real(value, kind, unit).magnitude

    def time(self, t):
        return self._to(t, "time", self.time_unit)

    def force(self, R):
        return self._to(R, "force", self.force_unit)

    def gap(self, gap):
        return self._to(gap, "length", self.gap_unit)

    def rate(self, w):
        return self._to(w, "rate", self.rate_unit)


class _Stage:
    """One off-screen plotter with the table, the body, the traced paths and the captions;
    :meth:`frame` moves them to a time and returns the image."""

    def __init__(self, traj, style: Style, span):
        from .pv import headless

        headless()
        import pyvista as pv

        self.pv, self.traj, self.style, self.units = pv, traj, style, _Units(style.scale, span)
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
        units = self.units
        clock = f"t = {row['t']:.3f} sqrt(b/g)"
        if units.real:
            clock += f" = {units.time(row['t']):.{1 if units.time_unit == 'ms' else 3}f} {units.time_unit}"
        lines = [clock, f"{row['mode']}, theta = {row['theta']:.3f} rad"]
        if row["mode"] == "flight":
            lines.append(f"gap {units.gap(row['gap']):.3g} {units.gap_unit}")
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
    marker at the frame's time; every axis in the units of :class:`_Units` (real units with a
    Scale)."""

    def __init__(self, traj, kind: str, span, height: int, scale=None):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        from matplotlib.ticker import MaxNLocator

        self.kind = kind
        units = _Units(scale, span)
        ts = np.linspace(*span, 3000)
        df = traj.sample(ts)
        dpi = 100
        self.fig = Figure(figsize=(height / dpi, height / dpi), dpi=dpi)
        self.canvas = FigureCanvasAgg(self.fig)
        if kind == "R":
            ax = self.fig.add_subplot(111)
            x, y = units.time(ts), units.force(df["R"].to_numpy())
            ax.plot(x, y, lw=1, color="k")
            ax.fill_between(x, 0, 1, where=(df["mode"] == "flight").to_numpy(), color="#9ecae1", alpha=0.6,
                            transform=ax.get_xaxis_transform(), label="flight")
            ax.set_xlabel(f"t ({units.time_unit})")
            ax.set_ylabel(f"R ({units.force_unit})")
            ax.xaxis.set_major_locator(MaxNLocator(max(2, min(4, height // 90))))  # ms: four digits or more
            (self.marker,) = ax.plot([], [], "o", color="#e6550d")
            self.xy = (ts, x, y)
        else:
            ax = self.fig.add_subplot(111, projection="3d")
            P = np.column_stack([units.rate(df["Omega"].to_numpy()), df["theta"].to_numpy(),
                                 units.rate(df["n"].to_numpy())])
            ax.plot(P[:, 0], P[:, 1], P[:, 2], lw=0.8, color="k")
            ax.set_xlabel(f"Omega ({units.rate_unit})")
            ax.set_ylabel("theta (rad)")
            ax.set_zlabel(f"n ({units.rate_unit})")
            ax.set_box_aspect(None, zoom=0.8)  # room for the labels inside the square
            (self.marker,) = ax.plot([], [], [], "o", color="#e6550d")
            self.xyz = (ts, P)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # a small panel's labels may not fit: drawn all the same
            self.fig.tight_layout()

    def frame(self, t: float) -> np.ndarray:
        if self.kind == "R":
            ts, x, y = self.xy
            self.marker.set_data([np.interp(t, ts, x)], [np.interp(t, ts, y)])
        else:
            ts, P = self.xyz
            p = [np.interp(t, ts, P[:, j]) for j in range(3)]
            self.marker.set_data_3d([p[0]], [p[1]], [p[2]])
        self.canvas.draw()
        return np.asarray(self.canvas.buffer_rgba())[..., :3].copy()


def render_frames(traj, times, style: Style, span, progress: bool):
    """Render one image per time (the 3-D view, with the side panel to its right)."""
    from .._runtime.watch import progress_bar

    rows = traj.sample(times)
    stage = _Stage(traj, style, span)
    panel = None if style.panel == "none" else _Panel(traj, style.panel, span, style.window_size[1], style.scale)
    out = []
    try:
        for i in progress_bar(iterable=range(len(rows)), desc="frames", unit="it", progress=progress and len(rows) > 10):
            row = rows.iloc[i]
            img = stage.frame(row)
            if panel is not None:
                img = np.hstack([img, panel.frame(float(row["t"]))[: img.shape[0]]])
            out.append(img)
    finally:
        stage.close()
    return out
