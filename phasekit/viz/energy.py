"""Where the energy of a run went, drawn: the mechanical energy and what each mechanism (sliding
friction, each dissipation law, the jumps at events) has taken out so far, against time, from
:meth:`phasekit.core.Trajectory.energy_series`.
"""

from __future__ import annotations

import numpy as np

from .mpl import _check_ax, _check_traj, label

#: points spread evenly over the run, drawn with the Taylor steps' ends when no times are given
EVEN_POINTS = 1000
#: the jumps at events are drawn when they reach this fraction of the energy at the start (not rounding)
AT_EVENTS_DRAWN = 1e-9


def plot_energy(traj, times=None, ax=None):
    """Draw the energy budget of a run along time, in one call.

    Parameters
    ----------
    traj : Trajectory
        With dense output (the default of :func:`phasekit.simulate`).
    times : array of float, optional
        Instants inside the run to draw at; default: the end of every Taylor step, both sides
        of every event, and 1000 instants spread evenly over the run.
    ax : matplotlib.axes.Axes, optional
        Where to draw; default: a new figure of its own (off-screen, see :func:`pyplot`).

    Returns
    -------
    matplotlib.axes.Axes
        The axes, with a thick black line ``energy`` (the mechanical energy, M g b), one line per
        mechanism with the energy it has taken out so far (sliding friction and each
        dissipation law of the model, labelled with its name; "at events" when the run lost or
        gained more than :data:`AT_EVENTS_DRAWN` of its energy at events), the axes labelled
        with their symbols and units, and a legend.

    Raises
    ------
    ParameterError
        If ``ax`` is not matplotlib Axes, ``traj`` is not a Trajectory or kept no dense output,
        or a time is outside the run or not finite (``times``).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 20.0)
    >>> ax = pk.viz.plot_energy(traj)
    >>> [line.get_label() for line in ax.get_lines()]
    ['energy', 'sliding friction']
    >>> pk.viz.pyplot().close(ax.figure)
    """
    _check_traj(traj, dense=False)  # the series names a run without dense output as the budget does
    if ax is not None:
        _check_ax(ax)
    df = _table(traj, times)  # before a figure is made: a bad time leaves none open
    if ax is None:
        from .output import pyplot

        _, ax = pyplot().subplots(figsize=(8, 4.5))
    t = df["t"].to_numpy()
    ax.plot(t, df["energy"].to_numpy(), color="k", lw=2.0, label="energy")
    laws = [c for c in df.columns if c not in ("t", "energy", "at_events", "residual")]
    for name in laws:
        ax.plot(t, df[name].to_numpy(), lw=1.3, label=name)
    at_events = df["at_events"].to_numpy()
    if at_events.size and np.max(np.abs(at_events)) > AT_EVENTS_DRAWN * abs(df["energy"].iloc[0]):
        ax.plot(t, at_events, lw=1.3, ls="--", label="at events")
    ax.set_xlabel(label("t"))
    ax.set_ylabel(label("energy"))
    ax.legend(loc="best", fontsize="small")
    return ax


def _table(traj, times):
    """The energy series at ``times``; without them, at the steps' ends and evenly spread instants
    (in time order; at an event, the row before the reset first)."""
    if times is not None:
        return traj.energy_series(times)
    import pandas as pd

    even = traj.energy_series(np.linspace(traj.t0, traj.t, EVEN_POINTS))
    df = pd.concat([even, traj.energy_series()], ignore_index=True)
    return df.sort_values("t", kind="stable", ignore_index=True)
