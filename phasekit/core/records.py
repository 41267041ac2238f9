"""What a :class:`~phasekit.core.trajectory.Trajectory` is made of: its :class:`Segment` (one mode each,
with dense output), its :class:`EventRecord` (the event log) and its :class:`Flight` (lift-off to touchdown).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import Status
from .hybrid import Mode
from .trajectory_io import event_dict, flight_dict


@dataclass(frozen=True)
class EventRecord:
    """A located event: its name, time, the modes before and after, the state and a detail.

    Attributes
    ----------
    name : str
        Stick, slip, lift-off, touchdown, impact, a stop or a user event.
    t : float
        Its time.
    mode_before, mode_after : str
        The modes before and after.
    x : numpy.ndarray or None
        The state, in the model's chart.
    detail : str
        A detail (e.g. an impact's bounce train resolved).
    y : numpy.ndarray or None
        The state in the paper's variables.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> ev = traj.events[0]
    >>> isinstance(ev, pk.core.EventRecord), ev.name, ev.mode_before, ev.mode_after
    (True, 'lift-off', 'sliding', 'end')
    """

    name: str
    t: float
    mode_before: str
    mode_after: str
    x: np.ndarray | None = field(default=None, repr=False, compare=False)
    detail: str = ""
    y: np.ndarray | None = field(default=None, repr=False, compare=False)  # the paper's variables

    @property
    def kind(self) -> str:  # the name, as older code called it
        return self.name

    def to_dict(self) -> dict:
        return event_dict(self)


@dataclass(frozen=True)
class Segment:
    """A stretch of one mode: from (t0, x0) to (t1, x1), states in the mode's chart (the
    model's chart in contact, the flight chart in flight).

    Attributes
    ----------
    mode : Mode
        The mode.
    t0, t1 : float
        Start and end times.
    x0, x1 : numpy.ndarray
        Start and end states.
    engine : str
        The engine that integrated it.
    end : str
        What ended it (an event, "time" or "failed").
    n_steps, n_rhs : int
        Steps taken and evaluations of the field.
    monitored : tuple
        The (t, x) where the flow's monitor crossed zero (minima of R; the maximum of the gap in flight).
    dense : tuple
        The dense output, callables t -> states in time order (empty without ``dense=True``, or
        once the run passed ``max_dense_mb``).
    tally : tuple
        With the dense output dropped under ``max_dense_mb``: the energy tally of each span of it
        (:class:`phasekit.core.dense_cap.SpanTally`), from which the energy budget is computed.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> seg = traj.segments[0]
    >>> isinstance(seg, pk.core.Segment), seg.mode.value, seg.end
    (True, 'sliding', 'lift-off')
    """

    mode: Mode
    t0: float
    t1: float
    x0: np.ndarray = field(repr=False)
    x1: np.ndarray = field(repr=False)
    engine: str = ""
    end: str = ""
    n_steps: int = 0
    n_rhs: int = 0
    monitored: tuple = field(default=(), repr=False)
    dense: tuple = field(default=(), repr=False)
    tally: tuple = field(default=(), repr=False)

    def states(self, ts) -> np.ndarray:
        """States at times inside [t0, t1] from the dense output.

        Parameters
        ----------
        ts : array_like
            The times; a time outside [t0, t1] is clipped into it.

        Returns
        -------
        numpy.ndarray
            One row per time, in the mode's chart.

        Raises
        ------
        ValueError
            If no dense output was kept.
        """
        ts = np.asarray(ts, dtype=float)
        out = np.empty((ts.size, self.x0.size))
        if not self.dense:
            raise ValueError("no dense output was kept: simulate with dense=True"
                             + (" and a larger max_dense_mb" if self.tally else ""))
        starts = np.array([s.t0 for s in self.dense])
        idx = np.clip(np.searchsorted(starts, ts, side="right") - 1, 0, len(self.dense) - 1)
        for k in np.unique(idx):
            sel = idx == k
            span = self.dense[k]
            out[sel] = span(np.clip(ts[sel], span.t0, span.t1))
        exact0, exact1 = ts == self.t0, ts == self.t1
        out[exact0], out[exact1] = self.x0, self.x1
        return out


@dataclass(frozen=True)
class Flight:
    """One flight: from lift-off to touchdown.

    Attributes
    ----------
    status : Status
        ``touchdown``, ``failed``, or ``completed`` (it ended otherwise).
    t_liftoff : float
        Time of lift-off.
    t_touchdown : float or None
        Time of touchdown, None if it did not end in one.
    x_liftoff, x_end : numpy.ndarray
        The states at its start and end, in the flight chart.
    gap_max, t_gap_max : float or None
        The located maximum of the gap and its time.
    W_star : float
        Vertical velocity of G at lift-off.
    Omega_star : float
        Precession rate at lift-off.
    n_steps : int
        Steps taken.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0, stop_at='touchdown')
    >>> fl = traj.flights[0]
    >>> isinstance(fl, pk.core.Flight), fl.status.value, f'{fl.gap_max:.2e}'
    (True, 'touchdown', '1.57e-07')
    """

    status: Status
    t_liftoff: float
    t_touchdown: float | None
    x_liftoff: np.ndarray = field(repr=False)
    x_end: np.ndarray = field(repr=False)
    gap_max: float | None
    t_gap_max: float | None
    W_star: float
    Omega_star: float
    n_steps: int = 0

    def to_dict(self) -> dict:
        return flight_dict(self)
