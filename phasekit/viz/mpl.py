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

from .._runtime.validate import check_bool, check_choice, check_int
from ..errors import ParameterError

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
    """The axis label of a column (the name itself when it has none).

    Parameters
    ----------
    name : str
        A column name, e.g. "theta" or "R" (a key of :data:`LABELS`, or any other).

    Returns
    -------
    str
        The symbol and unit, e.g. "theta [rad]".

    Raises
    ------
    ParameterError
        If ``name`` is not a string.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.viz.label('theta'), pk.viz.label('something')
    ('theta [rad]', 'something')
    """
    if not isinstance(name, str):
        raise ParameterError("name", "must be a column name (a string), e.g. one of " + ", ".join(LABELS), name)
    return LABELS.get(name, name)


def _columns() -> tuple:
    """The columns of :meth:`phasekit.core.Trajectory.sample`."""
    from ..core.trajectory import SAMPLE_COLUMNS

    return ("t", "mode", *SAMPLE_COLUMNS)


def _check_ax(ax):
    from matplotlib.axes import Axes

    if not isinstance(ax, Axes):
        raise ParameterError("ax", "must be matplotlib Axes (e.g. fig, ax = plt.subplots())", ax)
    return ax


def _check_traj(traj, *, dense: bool = True):
    from ..core.trajectory import Trajectory

    if not isinstance(traj, Trajectory):
        raise ParameterError("traj", "must be a phasekit Trajectory (from pk.simulate)", traj)
    if dense and (not traj.segments or not all(s.dense for s in traj.segments)):
        raise ParameterError("traj", "must keep its dense output (simulate with dense=True, the default)"
                             + _dropped(traj), show_value=False)
    return traj


def _check_column(name: str, value, valid) -> str:
    try:
        ok = value in valid
    except TypeError:  # unhashable
        ok = False
    if not ok or isinstance(value, bool):
        raise ParameterError(name, f"must be a column name, one of {', '.join(map(str, valid))}", value)
    return value


def _check_names(names, valid) -> list:
    if isinstance(names, str):
        names = [names]
    elif names is None or isinstance(names, (bytes, dict)) or not np.iterable(names):
        raise ParameterError("names", f"must be a column name or a list of them, from {', '.join(valid)}", names)
    names = list(names)
    if not names:
        raise ParameterError("names", f"must hold at least one column name, from {', '.join(valid)}", names)
    for name in names:
        _check_column("names", name, valid)
    return names


def _draw(what: str, draw, style: dict):
    """Call ``draw(**style)``; a style matplotlib refuses is a ParameterError naming ``style``
    (the other arguments were checked before)."""
    try:
        return draw(**style)
    except (AttributeError, TypeError, ValueError, KeyError) as exc:
        msg = " ".join(str(exc).split())
        raise ParameterError("style", f"must be keyword arguments of {what} ({type(exc).__name__}: {msg})",
                             style) from None


def _grid(traj, times, n: int) -> np.ndarray:
    if times is not None:
        return times  # checked by Trajectory.sample (named `times`)
    n = check_int("n", n, minimum=2, maximum=10**7)
    return np.linspace(traj.t0, traj.t, int(n))


def plot_timeseries(ax, traj, names, *, times=None, n: int = 4000, set_labels: bool = True, **style) -> list:
    """Plot observables of ``traj`` against time.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    traj : Trajectory
        With dense output (the default of :func:`phasekit.simulate`).
    names : str or sequence of str
        Columns of :meth:`Trajectory.sample` ("theta", "R", "energy", ...).
    times : array, optional
        Where to sample (default: ``n`` points spanning the run).
    n : int
        Number of points spanning the run when ``times`` is not given, in [2, 1e7]
        (default 4000).
    set_labels : bool
        Label the axes (y: the name's symbol and unit when one name is plotted).
    **style
        Passed to ``ax.plot``.

    Returns
    -------
    list of matplotlib.lines.Line2D
        One line per name, labelled with the name.

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``traj`` is not a Trajectory with dense output,
        ``names`` holds no column or something that is not one, ``times`` or ``n`` is
        invalid, ``set_labels`` is not a bool, or ``style`` is refused by ``ax.plot``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(pk.viz.plot_timeseries(ax, traj, ['theta', 'R'], n=200))
    2
    """
    _check_ax(ax)
    _check_traj(traj)
    names = _check_names(names, _columns())
    set_labels = check_bool("set_labels", set_labels)
    df = traj.sample(_grid(traj, times, n))
    lines = []
    for name in names:
        (line,) = _draw("Axes.plot", lambda **kw: ax.plot(df["t"], df[name], label=name, **kw), style)
        lines.append(line)
    if set_labels:
        ax.set_xlabel(label("t"))
        ax.set_ylabel(label(names[0]) if len(names) == 1 else ", ".join(names))
    return lines


def plot_events(ax, traj, names=None, *, text: bool = True, **style) -> list:
    """Mark the events of ``traj`` (all, or those in ``names``) as vertical lines.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    traj : Trajectory
        A run (dense output is not needed).
    names : str or sequence of str, optional
        Event names (e.g. lift-off, touchdown, impact, stick, slip); None (default): all.
    text : bool
        Label each event name at its first occurrence (default True).
    **style
        Passed to ``ax.axvline`` (default: a dashed line, coloured by the event's name).

    Returns
    -------
    list
        The artists: one line per event, and one text label per event name (at its first
        occurrence) when ``text`` is True.

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``traj`` is not a Trajectory, ``text`` is not a
        bool, ``names`` is not an event name, a list of them or None, or ``style`` is
        refused by ``ax.axvline``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(pk.viz.plot_events(ax, traj))
    2
    """
    _check_ax(ax)
    _check_traj(traj, dense=False)
    text = check_bool("text", text)
    if names is None or isinstance(names, str):
        wanted = None if names is None else {names}
    else:
        if isinstance(names, (bytes, dict)) or not np.iterable(names) or not all(isinstance(x, str) for x in names):
            raise ParameterError("names", "must be an event name (e.g. lift-off, touchdown, impact, stick, slip), a list "
                                          "of them, or None for all", names)
        wanted = set(names)
    artists, seen = [], set()
    for e in traj.events:
        if wanted is not None and e.name not in wanted:
            continue
        kw = {"color": EVENT_COLORS.get(e.name, "0.5"), "lw": 0.8, "ls": "--", **style}
        artists.append(_draw("Axes.axvline", lambda **k: ax.axvline(e.t, **k), kw))
        if text and e.name not in seen:
            seen.add(e.name)
            artists.append(ax.text(e.t, 0.98, f" {e.name}", transform=ax.get_xaxis_transform(), rotation=90, va="top",
                                   ha="left", fontsize=7, color=kw["color"]))
    return artists


def plot_section(ax, df, x: str, y: str, *, c: str | None = None, set_labels: bool = True, **style):
    """Scatter two columns of a table: a Poincare section (:func:`phasekit.core.poincare`), a
    sample, or an ensemble (:func:`phasekit.ensemble`); ``c`` colours by a third column.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    df : pandas.DataFrame
        The table.
    x, y : str
        The columns on the horizontal and vertical axes.
    c : str, optional
        A column that colours the points.
    set_labels : bool
        Label the axes with the columns' symbols and units (default True).
    **style
        Passed to ``ax.scatter`` (default marker size 12).

    Returns
    -------
    matplotlib.collections.PathCollection
        The points (no colour bar is added: pass the returned artist to ``fig.colorbar`` if
        you want one).

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``df`` is not a DataFrame, ``x``, ``y`` or ``c`` is
        not one of its columns, ``set_labels`` is not a bool, or ``style`` is refused by
        ``ax.scatter``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> m = pk.Model(body, pk.Coulomb(0.1))
    >>> sec = pk.core.poincare(m, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 30.0, on='Lambda', value=0.0, direction=+1)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> type(pk.viz.plot_section(ax, sec, 'theta', 'Omega')).__name__
    'PathCollection'
    """
    import pandas as pd

    _check_ax(ax)
    if not isinstance(df, pd.DataFrame):
        raise ParameterError("df", "must be a pandas DataFrame (a section, a sample or an ensemble table)", df)
    cols = list(df.columns)
    x, y = _check_column("x", x, cols), _check_column("y", y, cols)
    if c is not None:
        c = _check_column("c", c, cols)
    set_labels = check_bool("set_labels", set_labels)
    kw = {"s": 12, **style}
    if c is not None:
        kw["c"] = df[c]
    art = _draw("Axes.scatter", lambda **k: ax.scatter(df[x], df[y], **k), kw)
    if set_labels:
        ax.set_xlabel(label(x))
        ax.set_ylabel(label(y))
    return art


def plot_phase(ax, traj, x: str, y: str, *, times=None, n: int = 4000, set_labels: bool = True, **style) -> list:
    """The trajectory as a curve in the plane of two columns (e.g. theta and Lambda).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    traj : Trajectory
        With dense output (the default of :func:`phasekit.simulate`).
    x, y : str
        Columns of :meth:`Trajectory.sample` on the horizontal and vertical axes.
    times : array, optional
        Where to sample (default: ``n`` points spanning the run).
    n : int
        Number of points spanning the run when ``times`` is not given, in [2, 1e7]
        (default 4000).
    set_labels : bool
        Label the axes with the columns' symbols and units (default True).
    **style
        Passed to ``ax.plot``.

    Returns
    -------
    list of matplotlib.lines.Line2D
        The curve (one line).

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``traj`` is not a Trajectory with dense output,
        ``x`` or ``y`` is not a column, ``times`` or ``n`` is invalid, ``set_labels`` is not
        a bool, or ``style`` is refused by ``ax.plot``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(pk.viz.plot_phase(ax, traj, 'theta', 'Omega', n=200))
    1
    """
    _check_ax(ax)
    _check_traj(traj)
    x, y = _check_column("x", x, _columns()), _check_column("y", y, _columns())
    set_labels = check_bool("set_labels", set_labels)
    df = traj.sample(_grid(traj, times, n))
    lines = _draw("Axes.plot", lambda **k: ax.plot(df[x], df[y], **k), style)
    if set_labels:
        ax.set_xlabel(label(x))
        ax.set_ylabel(label(y))
    return lines


def plot_minima(ax, traj, **style):
    """The located local minima of R, (t, R_min), as points; returns the PathCollection.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    traj : Trajectory
        A run (its ``minima``: located when ``track_minima=True``, the default).
    **style
        Passed to ``ax.scatter`` (default: size 10, colour C3).

    Returns
    -------
    matplotlib.collections.PathCollection
        The points.

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``traj`` is not a Trajectory, or ``style`` is
        refused by ``ax.scatter``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> type(pk.viz.plot_minima(ax, traj)).__name__
    'PathCollection'
    """
    _check_ax(ax)
    _check_traj(traj, dense=False)
    m = traj.minima
    kw = {"s": 10, "color": "C3", "zorder": 3, **style}
    return _draw("Axes.scatter", lambda **k: ax.scatter(m[:, 0], m[:, 1], **k), kw)


def plain_log_ticks(ax, axis: str = "both", subs=(2, 3, 5)):
    """Label a log axis with plain numbers (6, 20, 0.002) instead of 6x10^0, at the
    decades and at the minor ticks with mantissa in ``subs``, so that values on a
    log scale that spans less than a decade can still be read off.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes whose log axis (or axes) to label.
    axis : {"x", "y", "both"}
        Which axis (default both).
    subs : sequence of float
        Mantissas in [1, 10) of the minor ticks to label (default (2, 3, 5)).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``axis`` is not "x", "y" or "both", or ``subs`` is
        not a sequence of numbers in [1, 10).

    Examples
    --------
    >>> import phasekit as pk
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> ax.set_xscale('log'); ax.set_xlim(1, 100)
    (1, 100)
    >>> pk.viz.plain_log_ticks(ax, 'x')
    <Axes: >
    """
    from matplotlib import ticker

    _check_ax(ax)
    axis = check_choice("axis", axis, ("x", "y", "both"))
    if isinstance(subs, (str, bytes, dict)) or not np.iterable(subs) or not all(
            isinstance(m, (int, float, np.integer, np.floating)) and not isinstance(m, bool) and 1 <= m < 10
            for m in subs):
        raise ParameterError("subs", "must be a sequence of mantissas in [1, 10), e.g. (2, 3, 5)", subs)

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


def _dropped(traj) -> str:
    """The clause of a run that dropped its dense output under ``max_dense_mb`` (else empty)."""
    from ..core.energy import dropped_note

    note = dropped_note(traj)
    return f": {note}" if note else ""
