"""Matplotlib helpers: they draw on the axes they are given and return the artists.

None of them creates a figure, shows or saves one: compose them on your own axes, then
``fig.savefig(...)`` (or :func:`phasekit.viz.save_figure`, which writes atomically). Axis
labels carry the paper's symbols and units (mass M, length b, time sqrt(b/g)).

>>> import matplotlib; matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt, numpy as np, phasekit as pk
>>> from phasekit.viz import plot_timeseries, plot_events
>>> body = pk.Spheroid(1.5)
>>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=12.0), 100.0)
>>> fig, ax = plt.subplots()
>>> lines = plot_timeseries(ax, traj, ["R"])
>>> marks = plot_events(ax, traj)
>>> plt.close(fig)
"""

from __future__ import annotations

import numpy as np

__all__ = ["LABELS", "label", "plot_timeseries", "plot_events", "plot_section", "plot_phase", "plot_minima", "plain_log_ticks"]

#: axis labels: symbol and unit of every column of a sample or section table
LABELS = {
    "t": "t [sqrt(b/g)]",
    "U": "U [sqrt(g b)]",
    "V": "V [sqrt(g b)]",
    "Omega": "Omega [sqrt(g/b)]",
    "Lambda": "Lambda = dtheta/dt [sqrt(g/b)]",
    "theta": "theta [rad]",
    "n": "n [sqrt(g/b)]",
    "R": "R [M g]",
    "energy": "energy [M g b]",
    "jellett": "Jellett's L.GP [M b^2 sqrt(g/b)]",
    "slip": "slip speed |u_P| [sqrt(g b)]",
    "L_Z": "L_Z [M b^2 sqrt(g/b)]",
    "h": "h [b]",
    "gap": "gap [b]",
    "t_jump": "t_jump [sqrt(b/g)]",
    "R_min": "R_min [M g]",
}
#: event styles: colour per event name (others grey)
EVENT_COLORS = {"lift-off": "C3", "touchdown": "C2", "impact": "C2", "stick": "C1", "slip": "C4"}


def label(name: str) -> str:
    """The axis label of a column (the name itself when it has none)."""
    return LABELS.get(name, name)


def _grid(traj, times, n: int) -> np.ndarray:
    if times is not None:
        return np.asarray(times, dtype=float)
    return np.linspace(traj.t0, traj.t, int(n))


def plot_timeseries(ax, traj, names, *, times=None, n: int = 4000, set_labels: bool = True, **style) -> list:
    """Plot observables of ``traj`` against time.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    traj : Trajectory
        With dense output (the default of :func:`phasekit.simulate`).
    names : str or sequence of str
        Columns of :meth:`Trajectory.sample` ("theta", "R", "energy", ...).
    times : array, optional
        Where to sample (default: ``n`` points spanning the run).
    set_labels : bool
        Label the axes (y: the name's symbol and unit when one name is plotted).
    **style
        Passed to ``ax.plot``.

    Returns
    -------
    list of matplotlib.lines.Line2D
        One line per name, labelled with the name.
    """
    names = [names] if isinstance(names, str) else list(names)
    df = traj.sample(_grid(traj, times, n))
    lines = []
    for name in names:
        (line,) = ax.plot(df["t"], df[name], label=name, **style)
        lines.append(line)
    if set_labels:
        ax.set_xlabel(label("t"))
        ax.set_ylabel(label(names[0]) if len(names) == 1 else ", ".join(names))
    return lines


def plot_events(ax, traj, names=None, *, text: bool = True, **style) -> list:
    """Mark the events of ``traj`` (all, or those in ``names``) as vertical lines.

    Returns the artists: one line per event, and one text label per event name (at its
    first occurrence) when ``text`` is True.
    """
    wanted = None if names is None else ({names} if isinstance(names, str) else set(names))
    artists, seen = [], set()
    for e in traj.events:
        if wanted is not None and e.name not in wanted:
            continue
        kw = {"color": EVENT_COLORS.get(e.name, "0.5"), "lw": 0.8, "ls": "--", **style}
        artists.append(ax.axvline(e.t, **kw))
        if text and e.name not in seen:
            seen.add(e.name)
            artists.append(ax.text(e.t, 0.98, f" {e.name}", transform=ax.get_xaxis_transform(), rotation=90, va="top",
                                   ha="left", fontsize=7, color=kw["color"]))
    return artists


def plot_section(ax, df, x: str, y: str, *, c: str | None = None, set_labels: bool = True, **style):
    """Scatter two columns of a table: a Poincare section (:func:`phasekit.poincare`), a
    sample, or an ensemble (:func:`phasekit.ensemble`); ``c`` colours by a third column.

    Returns the PathCollection (and adds a colour bar label to nothing: pass the returned
    artist to ``fig.colorbar`` if you want one).
    """
    kw = {"s": 12, **style}
    if c is not None:
        kw["c"] = df[c]
    art = ax.scatter(df[x], df[y], **kw)
    if set_labels:
        ax.set_xlabel(label(x))
        ax.set_ylabel(label(y))
    return art


def plot_phase(ax, traj, x: str, y: str, *, times=None, n: int = 4000, set_labels: bool = True, **style) -> list:
    """The trajectory as a curve in the plane of two columns (e.g. theta and Lambda)."""
    df = traj.sample(_grid(traj, times, n))
    lines = ax.plot(df[x], df[y], **style)
    if set_labels:
        ax.set_xlabel(label(x))
        ax.set_ylabel(label(y))
    return lines


def plot_minima(ax, traj, **style):
    """The located local minima of R, (t, R_min), as points; returns the PathCollection."""
    m = traj.minima
    kw = {"s": 10, "color": "C3", "zorder": 3, **style}
    return ax.scatter(m[:, 0], m[:, 1], **kw)


def plain_log_ticks(ax, axis: str = "both", subs=(2, 3, 5)):
    """Label a log axis with plain numbers (6, 20, 0.002) instead of 6x10^0, at the
    decades and at the minor ticks with mantissa in ``subs``, so that values on a
    log scale that spans less than a decade can still be read off. Returns ``ax``."""
    from matplotlib import ticker

    def major(x, _=None):
        return f"{x:.10g}" if x > 0 else ""

    def minor(x, _=None):
        if x <= 0:
            return ""
        m = round(x / 10 ** np.floor(np.log10(x) + 1e-9))
        return major(x) if m in subs else ""

    for name in ("x", "y") if axis == "both" else (axis,):
        ax_ = getattr(ax, f"{name}axis")
        ax_.set_major_formatter(ticker.FuncFormatter(major))
        ax_.set_minor_formatter(ticker.FuncFormatter(minor))
    return ax
