"""Results of a simulation: segments (one mode each), the event log, and one status.

A :class:`Trajectory` is what :func:`phasekit.simulate` returns. It keeps the integrator's
dense output (heyoka's Taylor polynomials) per segment, up to ``max_dense_mb``
(:mod:`phasekit.core.dense_cap`), so :meth:`Trajectory.sample`
evaluates the state and any observable at any instant without re-integrating, and it
carries its inputs (model, start, options) so that it can be rerun from :meth:`to_dict`. Its
other forms (JSON, tables, xarray, NetCDF, Parquet) are built in :mod:`phasekit.core.trajectory_io`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from .._runtime.validate import check_times
from ..errors import ParameterError, Status
from .approximations import Approximation, approximations_of
from .charts import FLIGHT
from .energy import EnergyBudget, energy_budget
from .energy_series import energy_series
from .face_table import face_pose, face_split, face_table
from .fields import STICK_SLIP
from .hybrid import Mode
from .model import Model
from .observables import evaluate_function
from .pose import POSE_COLUMNS, Pose
from .records import EventRecord, Flight, Segment
from .trajectory_files import write_netcdf, write_parquet, write_run_table
from .trajectory_io import (
    STATE_COLUMNS,
    events_table,
    pose_table,
    trajectory_dict,
    trajectory_xarray,
)
from .verify import RunCheck, check_run

#: columns of :meth:`Trajectory.sample` after t and mode: the state's observables, then where
#: the body is and how it is turned (:mod:`phasekit.core.pose`)
SAMPLE_COLUMNS = (*STATE_COLUMNS, *POSE_COLUMNS)


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class Trajectory:
    """The outcome of :func:`phasekit.simulate` (and of :func:`phasekit.core.simulate_batch`): frozen.

    Attributes
    ----------
    status : Status
        ``jumped`` (R reached 0 with dR/dt < 0), ``touchdown`` (stopped at the first
        re-contact), ``stopped`` (a stop event), ``completed`` (reached ``t_end``), ``settled``
        or ``failed`` (see ``reason``).
    segments : tuple of Segment
        The stretches of one mode each, in time order.
    events : tuple of EventRecord
        Every located event in time order (stick, slip, lift-off, touchdown, impact, stops
        and the user's events).
    model, x0, t0, options
        The inputs, so that the run can be repeated.
    ts, ys
        The states at the requested ``t_eval`` inside the run (None without one).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> traj.status.value, round(traj.t_jump, 6)
    ('jumped', 45.256004)
    """

    model: Model
    x0: np.ndarray
    t0: float
    t_end: float
    options: object
    status: Status
    reason: str | None
    segments: tuple[Segment, ...]
    events: tuple[EventRecord, ...]
    wall_s: float
    stop_at: str = "jump"
    restitution: float = 0.0
    user_events: tuple = ()
    pose0: Pose | None = None
    ts: np.ndarray | None = None
    ys: np.ndarray | None = None
    #: where a run that ended without a segment of its own (or as it settled) stopped
    x_stop: np.ndarray | None = None
    mode_stop: Mode | None = None
    #: what made the run (:func:`phasekit.simulate`), to repeat it (:meth:`verify`)
    runner: object = field(default=None, repr=False, compare=False)
    #: the run against its repeat at rtol / 10 in the other chart (:meth:`verify`; simulate's ``verify=True``)
    verification: object = field(default=None, repr=False, compare=False)
    #: the face phase (:class:`phasekit.core.face.FacePhase`): the body lying flat, after the segments
    face: object = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        set_ = object.__setattr__  # frozen: the inputs are normalised once, here
        set_(self, "x0", np.asarray(self.x0, float))
        set_(self, "t0", float(self.t0))
        set_(self, "t_end", float(self.t_end))
        set_(self, "pose0", Pose.of(self.pose0))
        set_(self, "segments", tuple(self.segments))
        set_(self, "events", tuple(self.events))
        set_(self, "user_events", tuple(self.user_events))

    @functools.cached_property
    def _pose_track(self):
        from .pose import PoseTrack

        return PoseTrack(self, self.pose0)

    # -- summary ---------------------------------------------------------------------------
    @property
    def chart(self) -> str:
        return self.model.chart.name

    @property
    def rtol(self) -> float:
        return self.options.rtol

    @property
    def t(self) -> float:
        """The time the run ended."""
        if self.face is not None:
            return self.face.t1
        return self.segments[-1].t1 if self.segments else self.t0

    @property
    def x(self) -> np.ndarray:
        """The final state, in the model's chart."""
        if self.face is not None:
            return self.face.chart_states(self.model, self.face.y1)[0]
        if self.x_stop is not None:
            return self.x_stop
        seg = self.segments[-1]
        return self._to_chart(seg.mode, seg.x1)

    @property
    def mode(self) -> str:
        if self.face is not None:
            return Mode.FACE.value
        return (self.mode_stop or self.segments[-1].mode).value if (self.mode_stop or self.segments) else Mode.SLIDING.value

    @property
    def backend(self) -> str:
        used = []
        for s in self.segments:
            if s.mode is not Mode.FLIGHT and s.engine and s.engine not in used:
                used.append(s.engine)
        return "+".join(used) or self.options.backend

    @property
    def n_steps(self) -> int:
        return sum(s.n_steps for s in self.segments)

    @property
    def n_rhs(self) -> int:
        return sum(s.n_rhs for s in self.segments)

    @property
    def success(self) -> bool:
        return self.status is not Status.FAILED

    @property
    def jumped(self) -> bool:
        return self.status is Status.JUMPED

    def events_named(self, name: str) -> list[EventRecord]:
        return [e for e in self.events if e.name == name]

    @property
    def stuck(self) -> bool:
        """Whether the body ever held zero slip (rolling mode, a stick, a regularised start below 10 eps)."""
        if any(s.mode.free is Mode.ROLLING for s in self.segments) or self.events_named("stick"):
            return True
        law = self.model.friction
        if law.can_stick and not law.has_rolling_mode and self.segments and self.segments[0].mode is not Mode.FLIGHT:
            return float(self.model._evaluate("slip_speed", self.segments[0].x0)) < STICK_SLIP + 10 * law.eps
        return False

    @property
    def _liftoff(self) -> EventRecord | None:
        return next((e for e in self.events if e.name == "lift-off"), None)

    @property
    def t_jump(self) -> float | None:
        return None if self._liftoff is None else self._liftoff.t

    @property
    def x_jump(self) -> np.ndarray | None:
        return None if self._liftoff is None else self._liftoff.x

    @property
    def Rdot_jump(self) -> float | None:
        e = self._liftoff
        return None if e is None else float(self.model._evaluate(
            "Rdot", e.x, Mode(e.mode_before) if e.mode_before in ("sliding", "rolling", "edge", "off_edge") else Mode.SLIDING))

    def energy_budget(self) -> EnergyBudget:
        """Where the energy went, law by law, and at events (:mod:`phasekit.core.energy`)."""
        return energy_budget(self)

    def energy_series(self, times=None):
        """The energy budget along the run, as a table (units M g b; :mod:`phasekit.core.energy_series`).

        Parameters
        ----------
        times : array of float, optional
            Instants inside [t0, t] (sorted on return; a time at an event is taken before the
            reset). None: the start of each segment and the end of every Taylor step (at an
            event, the row before the reset, then the row after it).

        Returns
        -------
        pandas.DataFrame
            ``t``; ``energy``, the mechanical energy; one column per law of
            :meth:`energy_budget` ("sliding friction", then each dissipation law's name) with the
            energy it has taken out since the start (>= 0, non-decreasing); ``at_events``, the
            energy lost at events so far; ``residual``, energy at the start - ``energy`` - the
            laws' columns - ``at_events`` (the balance: the integrator's error). The last row of
            ``energy_series()`` is :meth:`energy_budget`.

        Raises
        ------
        ParameterError
            A time outside the run or not finite (``times``); a run without dense output.
        """
        return energy_series(self, times)

    @functools.cached_property
    def approximations(self) -> tuple[Approximation, ...]:
        """The approximations the run used, each with its bound (:mod:`phasekit.core.approximations`)."""
        return approximations_of(self)

    def verify(self) -> RunCheck:
        """The run repeated at rtol / 10 in the other chart, and how far it is from converged
        (:mod:`phasekit.core.verify`); ``simulate(..., verify=True)`` keeps it as ``verification``."""
        return self.verification if self.verification is not None else check_run(self)

    @property
    def minima(self) -> np.ndarray:
        """(t, R) at each located local minimum of R, shape (m, 2)."""
        rows = []
        for s in self.segments:
            if s.mode is not Mode.FLIGHT and s.monitored:
                X = np.array([x for _, x in s.monitored])
                R = np.atleast_1d(evaluate_function(self.model.observable("R", s.mode), self.model.p, X))
                rows.extend(zip([t for t, _ in s.monitored], R))
        return np.array(rows, dtype=float).reshape(-1, 2)

    @property
    def R_min(self) -> float | None:
        """The smallest normal reaction met: over the located minima, the segments' ends and starts
        (R jumps at a reset: an impact, a transfer between pieces), and 0 at a lift-off."""
        # R is 0 at a located lift-off (to the event tolerance): count it as 0
        vals = [float(self.model._evaluate("R", s.x1, s.mode)) for s in self.segments
                if s.mode is not Mode.FLIGHT and s.end != "lift-off"]
        vals += [float(self.model._evaluate("R", s.x0, s.mode)) for s in self.segments if s.mode is not Mode.FLIGHT]
        m = self.minima
        if m.size:
            vals.append(float(m[:, 1].min()))
        if self._liftoff is not None:
            vals.append(0.0)
        return min(vals) if vals else None

    @property
    def flights(self) -> tuple[Flight, ...]:
        return tuple(self._flight(s) for s in self.segments if s.mode is Mode.FLIGHT)

    @property
    def hops(self) -> dict:
        """Hop statistics: ``n_liftoffs`` (losses of contact), ``n_flights`` (every flight,
        rebounds included), ``n_impacts``, ``t_flight`` (time in flight), ``flight_fraction``
        (of the simulated span), ``longest_flight``, ``gap_max`` (the largest gap, units b)
        and ``n_trains_resolved`` (bounce trains whose geometric tail was summed)."""
        spans = [(s.t1 - s.t0, s) for s in self.segments if s.mode is Mode.FLIGHT]
        gaps = [max(x[8] for _, x in s.monitored) for _, s in spans if s.monitored]
        span = self.t - self.t0
        t_flight = float(sum(d for d, _ in spans))
        return {"n_liftoffs": sum(1 for e in self.events if e.name == "lift-off"), "n_flights": len(spans),
                "n_impacts": sum(1 for e in self.events if e.name == "impact"), "t_flight": t_flight,
                "flight_fraction": t_flight / span if span > 0 else 0.0,
                "longest_flight": float(max((d for d, _ in spans), default=0.0)),
                "gap_max": float(max(gaps)) if gaps else 0.0,
                "n_trains_resolved": sum(1 for e in self.events if e.name == "impact" and "train resolved" in e.detail)}

    def flight_summary(self) -> dict:
        """Every flight of the run in one dict (``flights[0]`` is only the first of them).

        Returns
        -------
        dict
            ``n_flights``; ``t_first_liftoff`` (the start of the first flight); ``gap_max``
            (the largest gap over all flights, units b) and ``t_gap_max``; ``longest_flight``
            (a duration) and ``t_longest_flight`` (its start); ``t_airborne`` (the time spent
            in flight) and ``airborne_fraction`` (of the simulated span). None where undefined:
            no flight, no located maximum of the gap, a run of zero span.

        Examples
        --------
        >>> import numpy as np, phasekit as pk
        >>> body = pk.Spheroid(1.5)
        >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0, stop_at='touchdown')
        >>> s = traj.flight_summary()
        >>> s['n_flights'], f"{s['gap_max']:.2e}", s['t_first_liftoff'] == traj.t_jump
        (1, '1.57e-07', True)
        """
        spans = [s for s in self.segments if s.mode is Mode.FLIGHT]
        peaks = [max(s.monitored, key=lambda q: q[1][8]) for s in spans if s.monitored]  # (t, x) of each flight's top
        top = max(peaks, key=lambda q: q[1][8], default=None)
        longest = max(spans, key=lambda s: s.t1 - s.t0, default=None)
        airborne, span = float(sum(s.t1 - s.t0 for s in spans)), self.t - self.t0
        return {"n_flights": len(spans), "t_first_liftoff": float(spans[0].t0) if spans else None,
                "gap_max": None if top is None else float(top[1][8]), "t_gap_max": None if top is None else float(top[0]),
                "longest_flight": None if longest is None else float(longest.t1 - longest.t0),
                "t_longest_flight": None if longest is None else float(longest.t0), "t_airborne": airborne,
                "airborne_fraction": airborne / span if span > 0 else None}

    def _flight(self, s: Segment) -> Flight:
        m = self.model
        gmax = tg = None
        if s.monitored:
            tg, xg = max(s.monitored, key=lambda q: q[1][8])
            gmax = float(xg[8])
        W = float(s.x0[9] + m._evaluate("Hdot", s.x0, Mode.FLIGHT))
        status = Status.TOUCHDOWN if s.end == "touchdown" else Status.FAILED if s.end == "failed" else Status.COMPLETED
        return Flight(status, s.t0, s.t1 if s.end == "touchdown" else None, s.x0, s.x1, gmax, tg, W,
                      float(FLIGHT.to_paper(s.x0)[2]), s.n_steps)

    # -- states ----------------------------------------------------------------------------
    def _to_chart(self, mode: Mode, X) -> np.ndarray:
        """States of ``mode``'s chart -> the model's chart (flight: drop the gap)."""
        if mode is not Mode.FLIGHT:
            return np.asarray(X, dtype=float)
        from .resets import contact_state

        if np.ndim(X) == 1:
            return contact_state(self.model, X)
        return np.array([contact_state(self.model, x) for x in X])

    def _locate(self, ts) -> np.ndarray:
        """Index of the segment each time belongs to (the first that contains it)."""
        ends = np.array([s.t1 for s in self.segments])
        return np.minimum(np.searchsorted(ends, ts, side="left"), len(self.segments) - 1)

    def _check_times(self, times) -> np.ndarray:
        ts = np.atleast_1d(np.asarray(check_times("times", times, allow_empty=True)))
        lo, hi = self.t0, self.t
        ulps = 16 * np.finfo(float).eps * max(1.0, abs(lo), abs(hi))  # t_end computed as t * (1 + 1e-15) is inside
        ts = np.where((ts < lo) & (ts >= lo - ulps), lo, np.where((ts > hi) & (ts <= hi + ulps), hi, ts))
        bad = ts[(ts < lo) | (ts > hi)]
        if bad.size:
            raise ParameterError("times", f"must lie in the simulated span [{lo:.10g}, {hi:.10g}] ({bad.size} outside)",
                                 float(bad[0]) if bad.size == 1 else [float(bad[0]), float(bad[-1])])
        if not self.segments and self.face is None:
            raise ParameterError("times", "cannot be sampled: the run has no segment", show_value=False)
        if not all(s.dense for s in self.segments):
            from .energy import dropped_note

            raise ParameterError("times", "cannot be sampled: " + (dropped_note(self) or "this run kept no dense output "
                                                                   "(simulate with dense=True)"), show_value=False)
        return ts

    def _chart_states(self, ts) -> np.ndarray:
        ts, on = face_split(self, ts)  # the face phase's states after the segments' (core/face_table.py)
        idx = self._locate(ts)
        out = np.empty((ts.size, self.model.n_states))
        for k in np.unique(idx):
            sel = idx == k
            seg = self.segments[k]
            out[sel] = self._to_chart(seg.mode, seg.states(ts[sel])).reshape(int(sel.sum()), -1)
        return out if not on.size else np.vstack([out, self.face.chart_states(self.model, self.face.states(on))])

    def states(self, times) -> np.ndarray:
        """States at ``times`` in the model's chart (flight states with the gap dropped)."""
        return self._chart_states(self._check_times(times))

    def sample(self, times):
        """The state and the observables at ``times``, from the dense output.

        Parameters
        ----------
        times : float or array of float
            Instants inside the simulated span [t0, t] (sorted on return). A time at an event
            belongs to the segment that ends there (the state before the reset).

        Returns
        -------
        pandas.DataFrame
            One row per time: ``t``, ``mode`` (the mode in force) and the columns of
            :data:`SAMPLE_COLUMNS`: the paper's state U, V, Omega, Lambda, theta, n; ``R``,
            the normal reaction of the mode in force (0 in flight); ``energy``; ``jellett``
            (Jellett's integral -L.GP); ``slip`` (slip speed of the contact point, of the lowest point in
            flight); ``L_Z``; ``h`` (height of G, the gap excluded); ``gap`` (0 in contact);
            ``psi``, ``phi`` (azimuth of the axis and spin angle about it), ``X``, ``Y`` (centre
            of mass on the table) and ``X_P``, ``Y_P`` (the contact point), see :meth:`pose`.

        Raises
        ------
        ParameterError
            A time outside the simulated span, or a run that kept no dense output.

        Notes
        -----
        No re-integration: the Taylor method's steps are polynomials, so the error is of
        the order of the tolerance (CVODES segments use cubic Hermite interpolation on their
        output grid, whose error can be larger).
        """
        return face_table(self, self._check_times(times))  # sample_table's rows, then the face phase's

    def _pose(self, idx, ts) -> dict:
        before, on = face_split(self, ts)  # sorted times: the face phase's after the segments'
        if not on.size:
            return self._pose_track(idx, ts)
        tail = face_pose(self, on)
        if not before.size:
            return tail
        head = self._pose_track(idx[:before.size], before)
        return {k: np.concatenate([head[k], tail[k]]) for k in tail}

    def pose(self, times):
        """Where the body is and how it is turned at ``times``: a DataFrame with ``t`` and
        the columns psi, phi, X, Y, X_P, Y_P (conventions in :mod:`phasekit.core.pose`).

        Computed after the integration by quadrature of the dense output (the run's numbers
        are those of a run without them); raises ParameterError when no dense output was kept.
        """
        return pose_table(self, self._check_times(times))

    def at(self, t: float):
        """The row of :meth:`sample` at one instant ``t``, as a pandas Series
        (``traj.at(12.0)["R"]``)."""
        if np.ndim(t) != 0:
            raise ParameterError("t", "must be one time (use sample for many)", t)
        return self.sample([t]).iloc[0]

    def events_table(self, name: str | None = None):
        """The recorded events (or those called ``name``) as a DataFrame: ``t``, ``event``,
        ``mode_before``, ``mode_after`` and the paper's state at the event."""
        return events_table(self, name)

    @property
    def euler_end(self) -> np.ndarray:
        return self.model.chart.to_paper(self.x)

    @property
    def euler_ys(self) -> np.ndarray | None:
        if self.ys is None:
            return None
        return np.array([self.model.chart.to_paper(z) for z in self.ys])

    # -- export ----------------------------------------------------------------------------
    def to_xarray(self, times=None, *, n: int = 2001, scale=None):
        """The run sampled at ``times`` (default ``n`` instants uniform over it) as an xarray
        Dataset: coordinate ``t``, one variable per column of :meth:`sample` with its ``units``
        and ``long_name``, the outcome as attributes, the inputs and the whole run as JSON in
        ``phasekit_json`` (needs ``phasekit[data]``). ``scale`` (a :class:`phasekit.Scale`):
        the columns in real units (t in ms, lengths in mm, rates in rev/s), each named in its
        ``units``."""
        return trajectory_xarray(self, times, n=n, scale=scale)

    def to_netcdf(self, path, times=None, *, n: int = 2001, scale=None):
        """Write :meth:`to_xarray` to a NetCDF file (``phasekit[data]``); returns the path.
        ``scale``: real units, as for :meth:`to_xarray`."""
        return write_netcdf(self, path, times, n=n, scale=scale)

    def to_parquet(self, path, times=None, *, n: int = 2001, scale=None):
        """Write the sampled table to a Parquet file, the run's inputs in its metadata and each
        column's unit where pyarrow (the field's metadata) and plain pandas
        (``pd.read_parquet(path).attrs["units"]``) see it (``phasekit[data]``); returns the
        path. ``scale``: real units, as for :meth:`to_xarray`."""
        return write_parquet(self, path, times, n=n, scale=scale)

    def to_csv(self, path, times=None, *, n: int = 2001, scale=None):
        """Write the sampled table to CSV with its sidecar ``path.json`` (units, long names, the
        run's inputs; :func:`phasekit.read_table` reads both); returns the path. ``scale``:
        real units, as for :meth:`to_xarray`."""
        return write_run_table(self, path, times, n=n, suffixes=(".csv",), scale=scale)

    def to_dict(self, *, events: bool = True) -> dict:
        """JSON form in the paper's variables, with the inputs (model, start, options)."""
        return trajectory_dict(self, events=events)

    def __repr__(self) -> str:
        tj = f", t_jump={self.t_jump:.9g}" if self.t_jump is not None else ""
        return (f"Trajectory(status={self.status.value}{tj}, t={self.t:.6g}, segments={len(self.segments)}, "
                f"events={len(self.events)}, wall_s={self.wall_s:.3g})")
