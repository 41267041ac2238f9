"""simulate: one short loop over the hybrid system of :mod:`phasekit.core.system`.

Propagate the current mode's flow to its first event, apply that event's reset (or end
the run with the event's status), record it, repeat. Nothing here knows any event by name.
"""

from __future__ import annotations

import functools
import os
import time
import warnings
from dataclasses import replace

import numpy as np

from .._runtime.validate import check_bool, check_finite, check_range, check_times, check_vector
from .._runtime.watch import WALL_REASON, claim_start, deadline, heartbeat, progress_bar, show_progress
from ..errors import ConvergenceError, ParameterError, Status
from .audit import audited_options
from .charts import FLIGHT, POLE_GUARD
from .dense_cap import DenseCap
from .engines import Budget, End, Propagation, engine_for
from .engines.dense import linear_span
from .face import run_face
from .hybrid import Event, Mode, Transition
from .model import Model
from .options import SolverOptions
from .pose import Pose
from .records import EventRecord, Segment
from .resets import contact_state
from .settle import settled
from .starts import RATE_MAX
from .system import declare, watched
from .trajectory import Trajectory

#: the largest |t0| a run may start at (see simulate)
T_MAX = 1e6
#: a single run shows its progress bar (where one is shown) once it has run this long, in s
PROGRESS_DELAY = 2.0
#: more simulated time per second of wall time than any run covers (measured: ~750 sliding, ~15 000
#: for a body that rolls steadily): a span beyond max_wall x this cannot be reached
REACH_PER_S = 1e5


def solver_options(options: SolverOptions | None = None, **overrides) -> SolverOptions:
    """``options`` (default SolverOptions()) with the given fields replaced; unknown names
    are an error naming them."""
    if options is None:
        try:  # the same keywords again (a sweep): the validated object from last time
            return _options_from(tuple(sorted(overrides.items())))
        except TypeError:  # an unhashable value: validate it below (and say what is wrong)
            pass
    return _solver_options(options, **overrides)


@functools.lru_cache(maxsize=256)
def _options_from(items: tuple) -> SolverOptions:
    return _solver_options(None, **dict(items))


def _solver_options(options: SolverOptions | None = None, **overrides) -> SolverOptions:
    if options is not None and not isinstance(options, SolverOptions):
        raise ParameterError("options", "must be a phasekit SolverOptions", options)
    unknown = sorted(set(overrides) - set(SolverOptions.names()))
    if unknown:
        raise ParameterError(unknown[0], f"is not an option of simulate (options: {', '.join(SolverOptions.names())})",
                             show_value=False)
    return replace(options or SolverOptions(), **overrides)


def simulate(model: Model, x0, t_end: float, *, t0: float = 0.0, stop_at: str = "jump", restitution: float = 0.0,
             events=(), t_eval=None, mode=None, options: SolverOptions | None = None, throw: bool = False,
             pose0=None, progress: bool | None = None, verify: bool = False, **option_fields) -> Trajectory:
    """Integrate the dynamics of ``model`` from ``x0`` until ``t_end``, a stop, or failure.

    Parameters
    ----------
    model : Model
        The body, friction law and chart to integrate.
    x0 : array
        A state of ``model.chart`` (6 numbers for "euler", 8 for "vector"); with
        ``mode="flight"``, a flight state (10) or a contact state lifted off with zero gap.
    t_end, t0 : float
        End time (> t0); start time, in [-1e6, 1e6] (default 0).
    stop_at : {"jump", "touchdown", "none", "rest"}
        Stop at the first lift-off or touchdown, or run to t_end through flights and impacts ("none";
        "rest" alike: a run with dissipation laws ends when the body rests, status "rest").
    restitution : float in [0, 1]
        Newton's coefficient e of the impact law (``stop_at="none"``).
    events : sequence of Event
        The user's events, e.g. ``[pk.Event("theta", 0.4)]`` (stop when theta reaches 0.4)
        or ``[pk.Event("Lambda", 0.0, direction=+1, terminal=False)]`` (a section).
    t_eval : array, optional
        Times at which to return states in ``traj.ts``, ``traj.ys`` (the model's chart).
    mode : "flight" or "face", optional
        Start in free flight instead of in contact; or lying flat on a face, sliding and spinning
        (e.g. :func:`phasekit.core.vertical_spin_start` at theta0 = 0 with ``v0``; a body with a flat
        face, :mod:`phasekit.core.face`).
    options : SolverOptions, optional
        Tolerances, integrator, step and wall budgets (its fields also as keywords: ``rtol=1e-12``).
    throw : bool
        True: raise ConvergenceError if the run fails; False (default): return it, status "failed" and reason.
    pose0 : Pose, dict or 4 numbers, optional
        Start psi, phi, X, Y (default 0) of :meth:`Trajectory.pose`, after-run quadratures the run does not use.
    progress : bool or None
        A progress bar on stderr after PROGRESS_DELAY (2 s); None (default): on a terminal or in a notebook.
    verify : bool
        Also repeat the run at rtol / 10 in the other chart and keep how far it is from converged as
        ``traj.verification`` (:meth:`Trajectory.verify`; costs that run).
    **option_fields
        Fields of :class:`SolverOptions`, replacing those of ``options``.

    Returns
    -------
    Trajectory
        The run: its ``status`` (and ``reason``), segments and event log.

    Raises
    ------
    ParameterError
        A bad argument, named: ``model`` not a Model; ``x0`` not a finite state of the
        chart's length, with an entry beyond 1e5 in size, or with theta at 0 or pi in the
        Euler chart; ``t0`` outside [-1e6, 1e6]; ``t_end`` not finite or not > t0; ``stop_at``
        not one of its choices; ``restitution`` outside [0, 1]; ``events`` not a list of
        Events; ``t_eval`` not finite times inside [t0, t_end]; ``mode`` neither None nor
        "flight"; ``options`` not a SolverOptions, or an unknown or invalid option field.
    ConvergenceError
        With ``throw=True``, if the run fails (the trajectory attached).

    Warns
    -----
    UserWarning
        If ``t_end`` cannot be reached within ``max_wall`` seconds.

    See Also
    --------
    phasekit.core.simulate_batch
        many starts at once on heyoka's SIMD batch integrator (the same statuses and events)
    phasekit.ensemble
        many starts on many cores, one table

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> traj.status.value, round(traj.t_jump, 4)
    ('jumped', 45.256)
    >>> round(float(traj.at(20.0)['theta']), 4)
    1.2621
    """
    opts = solver_options(options, **option_fields)
    pose0 = Pose.of(pose0)
    x0, t0, t_end, start_mode, te = _checked_arguments(model, x0, t0, t_end, mode, throw, events, t_eval, opts.max_wall)
    if not opts.creep and model.friction.creeps:  # the law's own field at zero slip (SolverOptions.creep)
        model = Model(model.body, model.friction.without_creep(), model.chart)
    opts = audited_options(opts)  # PHASEKIT_AUDIT (core/audit.py)
    system = _declared(model, stop_at, restitution, events, (opts.bounce_stop, opts.bounce_tail), opts.settle is not None)
    run = _Run(model, system, opts, t0, t_end, dense=opts.dense or te is not None, te=te)
    run.loop(system.initial(model, t0, x0, start_mode), progress)
    traj = run.result(x0, stop_at, restitution, events, te, pose0)
    if check_bool("verify", verify) and traj.status is not Status.FAILED:
        traj = replace(traj, verification=traj.verify())
    if throw and traj.status is Status.FAILED:
        raise ConvergenceError(f"simulation failed: {traj.reason}", traj)
    return traj


def extended(seg: Segment, t1: float, x1: np.ndarray, cap=None) -> Segment:
    """``seg`` carried on in a straight line to (t1, x1): the instants a reset extrapolates over (to
    the exact zero of the motion, or of the spin about the normal); its dense output gains that line
    (unless ``cap``, the run's memory cap, dropped the dense output: it takes the line: :mod:`.dense_cap`)."""
    if cap is not None and (seg.dense or cap.dropped):
        line = linear_span(seg.t1, t1, seg.x1, x1)
        return replace(seg, t1=t1, x1=x1, dense=seg.dense + (line,) if cap(line) else seg.dense)
    dense = seg.dense + (linear_span(seg.t1, t1, seg.x1, x1),) if seg.dense else ()
    return replace(seg, t1=t1, x1=x1, dense=dense)


def _checked_arguments(model, x0, t0, t_end, mode, throw, events, t_eval, max_wall):
    """simulate's arguments other than the options and the pose, checked (and a warning when
    ``t_end`` is out of reach of ``max_wall``): (x0, t0, t_end, start mode, t_eval)."""
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model such as Model(Spheroid(1.5), Coulomb(0.1))", model)
    if mode is not None and mode not in ("flight", Mode.FLIGHT, "face", Mode.FACE):
        raise ParameterError("mode", "must be None (start in contact), 'flight' or 'face'", mode)
    start_mode = None if mode is None else Mode(mode)
    if start_mode is Mode.FACE and not any(lim.face is not None for lim in model.body.limits):
        raise ParameterError("mode", "'face' needs a body with a flat face (a Disk, or a Cone on its rim)", mode)
    check_bool("throw", throw)
    if isinstance(events, Event) or not isinstance(events, (list, tuple)):
        raise ParameterError("events", "must be a list of phasekit Event objects, e.g. [pk.Event('theta', 0.4)]", events)
    x0, t0, t_end = _checked_span(model, x0, t0, t_end, start_mode)
    if t_end - t0 > REACH_PER_S * max_wall:  # said at once, not after max_wall seconds of silence
        warnings.warn(f"`t_end` = {t_end:g} cannot be reached within `max_wall` = {max_wall:g} s (no run covers "
                      f"more than {REACH_PER_S:g} time units per second): the run will end \"failed\" when its wall "
                      "budget runs out", stacklevel=3)  # the caller of simulate
    te = None if t_eval is None else check_times("t_eval", t_eval)
    if te is not None and te.size and (te[0] < t0 or te[-1] > t_end):
        raise ParameterError("t_eval", f"must lie in the requested span [t0, t_end] = [{t0:.10g}, {t_end:.10g}]",
                             float(te[0] if te[0] < t0 else te[-1]))
    return x0, t0, t_end, start_mode, te


def _checked_span(model, x0, t0, t_end, start_mode):
    """simulate's start state and span, checked: (x0, t0, t_end)."""
    n = FLIGHT.n_states if start_mode is Mode.FLIGHT and np.size(x0) == FLIGHT.n_states else model.n_states
    x0 = check_vector("x0", x0, n)
    if np.max(np.abs(x0)) > RATE_MAX:
        raise ParameterError("x0", f"must have entries of at most {RATE_MAX:g} in size (larger rates are beyond double "
                                   "precision)", x0)
    # beyond |t| = T_MAX the spacing of doubles (> 1e-10) is coarser than the located events
    t0 = check_range("t0", t0, -T_MAX, T_MAX, closed="lr", label=f"[-{T_MAX:g}, {T_MAX:g}]")
    t_end = check_finite("t_end", t_end)
    if not t_end > t0:
        raise ParameterError("t_end", f"must be > t0 = {t0:g}", t_end)
    if n == model.n_states and not model.chart.regular_at_poles and min(x0[4], np.pi - x0[4]) < POLE_GUARD \
            and start_mode is not Mode.FACE:  # lying flat, only v and w_Z are read
        raise ParameterError("x0", "has theta at 0 or pi, where the Euler chart is singular (2.7c): use "
                                   "Model(body, law, chart='vector')", x0)
    return x0, t0, t_end


def _declared(model, stop_at, restitution, events, bounce, periodic=False):
    """:func:`phasekit.core.system.declare`, kept for runs that declare the same system again (a
    sweep calls simulate thousands of times; declaring costs ~25 us a call, a few % of a run)."""
    events = tuple(events)
    try:  # events compare without their reset: key on the reset objects too
        return _declare_cached(model, stop_at, restitution, events, bounce, periodic,
                               tuple(id(getattr(e, "reset", None)) for e in events))
    except TypeError:  # unhashable arguments: declare (which validates them)
        return declare(model, stop_at=stop_at, restitution=restitution, events=events, bounce=bounce, periodic=periodic)


@functools.lru_cache(maxsize=64)
def _declare_cached(model, stop_at, restitution, events, bounce, periodic, _reset_ids):
    return declare(model, stop_at=stop_at, restitution=restitution, events=events, bounce=bounce, periodic=periodic)


@functools.lru_cache(maxsize=64)
def tracked(flow, track_minima: bool):
    """``flow``, without its monitor of the minima of R when they are not wanted: the
    integrator then carries no non-terminal event (fewer steps; the flight's gap maximum stays)."""
    return flow if track_minima or flow.mode is Mode.FLIGHT else replace(flow, monitor=None)


class RunState:
    """One run of the hybrid loop, as :func:`simulate` runs it or as a lane of
    :func:`phasekit.core.simulate_batch` does: the mode, time and state it has reached, its segments
    and event log, and its status once it ends. :meth:`end_segment` is the one place where the
    end of a propagation (a time, an event, a failure) becomes the next mode or the end of the run."""

    def __init__(self, model, system, opts, t0: float, t_end: float):
        self.model, self.system, self.opts, self.t_end = model, system, opts, t_end
        self.t_start, self.switch_limit = t0, opts.switch_limit(t_end - t0)
        self.mode, self.t, self.x = Mode.SLIDING, 0.0, None
        self.status = self.reason = None
        self.segments, self.records = [], []
        self.face = None  # the face phase (phasekit.core.face.FacePhase), once the body lies flat
        self.resume = False  # a non-terminal event or a graze: the segment goes on from where it stopped
        self.cap = None  # the memory cap of the dense output (simulate's: dense_cap.DenseCap)

    def record(self, name, t, before, after, x, detail="") -> None:
        x = None if x is None else np.asarray(x, dtype=float)
        if x is not None and x.size == FLIGHT.n_states:
            x = contact_state(self.model, x)
        y = None if x is None else self.model.chart.to_paper(x)
        self.records.append(EventRecord(name, float(t), before, after, x, detail, y))

    def apply(self, tr: Transition) -> None:
        """Log a transition's records, then continue in its mode or stop (the switch budget, or
        a settled body with the option ``settle``)."""
        for r in tr.records:
            self.record(r.name, tr.t, r.mode_before, r.mode_after, r.x, r.detail)
        if tr.resume:  # the segment goes on (a turn of theta, a graze): only the settle rule applies
            self.resume = True
        else:
            if tr.carried and self.segments and tr.t > self.segments[-1].t1:  # see Transition
                if self.cap is not None:
                    self.cap.where = (len(self.segments) - 1, self.segments[-1].mode)
                self.segments[-1] = extended(self.segments[-1], tr.t, np.asarray(tr.x, dtype=float), self.cap)
                self.t, self.x = tr.t, np.asarray(tr.x, dtype=float)
            if tr.stop is not None:
                self.status, self.reason = tr.stop, tr.reason
                if not self.segments:  # stopped before any integration: keep the start
                    self.t, self.x, self.mode = tr.t, np.asarray(tr.x, dtype=float), tr.mode or self.mode
                return
            self.mode, self.t, self.x = tr.mode, tr.t, np.asarray(tr.x, dtype=float)
            if len(self.records) >= self.switch_limit:
                self.status = Status.FAILED
                self.reason = f"more than {self.switch_limit} mode switches by t = {self.t:.6g} (chattering)"
                return
        if self.opts.settle is not None and tr.records:
            why = settled(self.model, self.records, self.t_start, self.opts.settle, self.opts.rtol)
            if why is not None:
                self.status, self.reason = Status.SETTLED, why

    def add_segment(self, engine: str, t1, x1, end: str, n_steps: int, n_rhs: int, monitored=(), dense=(),
                    extend: bool = False) -> None:
        """The stretch of the current mode from (t, x) to (t1, x1); ``extend``: it continues the
        last segment (after a non-terminal event or a graze)."""
        if extend and self.segments and self.segments[-1].mode is self.mode:
            last = self.segments[-1]
            self.segments[-1] = Segment(self.mode, last.t0, t1, last.x0, x1, engine, end, last.n_steps + n_steps,
                                        last.n_rhs + n_rhs, last.monitored + tuple(monitored), last.dense + tuple(dense))
        else:
            self.segments.append(Segment(self.mode, self.t, t1, self.x, x1, engine, end, n_steps, n_rhs, tuple(monitored),
                                         tuple(dense)))

    def end_segment(self, end: End, t: float, x, ev: Event | None, reason: str | None = None) -> None:
        """What the end of a propagation at (t, x) does to the run: a failure or the end time ends
        it; a non-terminal event is recorded and the run goes on; a terminal event without a
        reset ends it with the event's status; a reset's transition is applied."""
        self.t, self.x = t, x
        if end is End.FAILED:
            self.status, self.reason = Status.FAILED, reason or f"non-finite state at t = {t:.6g}"
        elif end is End.TIME:
            self.status = Status.COMPLETED
            self.reason = "in flight at t_end" if self.mode is Mode.FLIGHT else None
        elif not ev.terminal:
            self.record(ev.name, t, self.mode.value, self.mode.value, x)
            self.resume = True
        elif ev.reset is None:
            self.record(ev.name, t, self.mode.value, "end", x)
            self.status = ev.stop
            if ev.stop is Status.STOPPED:
                self.reason = f"{ev.name}: {ev.on} reached {ev.level:g}"
        else:
            log = {"log": self.records} if getattr(ev.reset, "uses_log", False) else {}  # a bounce train so far
            self.apply(ev.reset(self.model, ev, self.mode, t, x, **log))

    def trajectory(self, x0, wall_s: float, *, stop_at="jump", restitution=0.0, user_events=(), pose0=None,
                   ts=None, ys=None) -> Trajectory:
        # a run that ended before its first segment, or settled (it ends in the mode it settled
        # into), ends where its last transition put it
        here = not self.segments or self.status is Status.SETTLED
        return Trajectory(model=self.model, x0=x0, t0=self.t_start, t_end=self.t_end, options=self.opts,
                          status=self.status, reason=self.reason, segments=self.segments, events=self.records,
                          wall_s=wall_s, stop_at=stop_at, restitution=restitution, user_events=user_events, pose0=pose0,
                          ts=ts, ys=ys, x_stop=self.x if here else None, mode_stop=self.mode if here else None,
                          runner=simulate, face=self.face)


class _Run(RunState):
    """One run of simulate's loop: the state, the engines it uses and its budgets."""

    def __init__(self, model, system, opts, t0, t_end, dense, te=None):
        super().__init__(model, system, opts, t0, t_end)
        self.dense = dense
        self.cap = DenseCap(model, opts.max_dense_mb, te, energy=opts.dense) if dense else None
        self.wall0 = time.perf_counter()
        start = claim_start()  # the CLI's command counts in its --max-wall: from its start
        own, call = (self.wall0 if start is None else start) + opts.max_wall, deadline()
        # the caller's budget (a search, a map) when it ends first: the reason then names it
        self.call_budget = call[1] if call is not None and call[0] < own else None
        self.budget = Budget(opts.max_steps, own if self.call_budget is None else call[0], keep=self.cap)
        if self.cap is not None:
            self.cap.budget = self.budget
        self.engines, self.steps_done = {}, 0

    def loop(self, first: Transition, progress) -> None:
        """Run from the start transition ``first`` until a status is set (with a progress bar
        of the simulated time where one is shown, after PROGRESS_DELAY)."""
        t0 = self.t_start
        bar = progress_bar(self.t_end - t0, desc="simulate", unit="t", progress=progress, delay=PROGRESS_DELAY) \
            if show_progress(progress) else None
        self.budget.tick = (lambda t: bar.update(t - t0 - bar.n)) if bar is not None else \
            heartbeat(t0, self.t_end, "simulate") if progress is None else None
        self.apply(first)
        if self.status is None:
            self.prefetch()
        while self.status is None:
            self.step()
            if self.budget.tick is not None:
                self.budget.tick(self.t)
            if self.status is None and self.budget.wall_exceeded():  # many short segments (stick-slip chatter)
                self.status, self.reason = Status.FAILED, "wall-time limit reached"
        if bar is not None:
            bar.close()
        if self.status is Status.FAILED and (self.reason or "").startswith("wall-time limit reached") \
                and self.opts.max_wall is not None:  # here or an engine's check between chunks: one wording
            self.reason = f"wall-time limit ({self.opts.max_wall:g} s) reached at t = {self.t:.6g}"
        if self.call_budget is not None and self.status is Status.FAILED and "wall-time limit" in (self.reason or ""):
            self.reason = f"{WALL_REASON} (max_wall = {self.call_budget:g} s) ran out at t = {self.t:.6g}"

    def prefetch(self) -> None:
        """Compile in the background the Taylor integrator of the other of the two contact modes a
        run most often reaches (sliding, rolling): a body's first run then waits for one
        compilation on two cores, not for each in turn ($PHASEKIT_COMPILE_AHEAD=off: never)."""
        if self.mode is Mode.FACE or os.environ.get("PHASEKIT_COMPILE_AHEAD", "on").strip().lower() in ("off", "no", "0"):
            return
        for mode in (Mode.SLIDING, Mode.ROLLING):
            if mode is self.mode or mode not in self.model.modes:
                continue
            flow = tracked(self.system.flow(mode), self.opts.track_minima)
            engine = self.engine(flow)
            events = watched(self.system, mode, engine)
            if getattr(engine, "prefetch", None) is not None and not any(e.arm_after > 0 for e in events):
                engine.prefetch(self.model.compile_flow(flow, events), len(self.model.p))

    def engine(self, flow):
        name = flow.engine or self.opts.backend
        if name == "auto":
            name = "cvodes" if flow.stiff else "taylor"
        if name not in self.engines:
            self.engines[name] = engine_for(name, self.opts.rtol, self.opts.atol)
        return self.engines[name]

    def step(self) -> None:
        """Propagate the current mode to its first event and handle that event."""
        if self.mode is Mode.FACE:  # lying flat: its own flow (phasekit.core.face), to rest
            self.budget.steps = self.opts.max_steps - self.steps_done
            run_face(self)
            return
        flow = tracked(self.system.flow(self.mode), self.opts.track_minima)
        engine = self.engine(flow)
        events = watched(self.system, self.mode, engine)
        extend = self.resume  # a non-terminal event or a graze: the same segment goes on
        prop, ev = self.propagate(flow, engine, events)
        if not (np.isfinite(prop.t) and np.all(np.isfinite(prop.x))):
            # never a non-finite number in a result: the run ends at its last finite state
            self.status = Status.FAILED
            self.reason = f"the integration diverged after t = {self.t:.6g} (non-finite state)"
            return
        self.steps_done += prop.n_steps
        self.add_segment(engine.name, prop.t, prop.x, ev.name if prop.outcome is End.EVENT else str(prop.outcome),
                         prop.n_steps, prop.n_rhs, prop.monitored, prop.dense, extend)
        self.end_segment(prop.outcome, prop.t, prop.x, ev, prop.reason)

    def propagate(self, flow, engine, events) -> tuple[Propagation, Event | None]:
        """One call of the integrator; events armed after a delay are left out for that
        long, and fire at once if their guard is already past zero when armed."""
        cflow = lambda evs: self.model.compile_flow(flow, evs)  # noqa: E731
        delayed = [e for e in events if e.arm_after > 0]
        if not delayed or self.resume:
            return self._call(cflow(events), engine, events, self.x, self.t, self.t_end)
        early = [e for e in events if e.arm_after == 0]
        t_arm = min(self.t + max(e.arm_after for e in delayed), self.t_end)
        first, ev = self._call(cflow(early), engine, early, self.x, self.t, t_arm)
        if first.outcome is not End.TIME or t_arm >= self.t_end:
            return first, ev
        for e in delayed:
            g = float(self.model.guard_function(e.on, self.mode)(first.x, self.model.p, e.level))
            if (e.direction < 0 and g <= 0) or (e.direction > 0 and g >= 0):
                first.outcome = End.EVENT
                return first, e
        rest, ev = self._call(cflow(events), engine, events, first.x, first.t, self.t_end)
        rest.n_steps += first.n_steps
        rest.n_rhs += first.n_rhs
        rest.dense = first.dense + rest.dense
        rest.monitored = first.monitored + rest.monitored
        return rest, ev

    def _call(self, cflow, engine, events, x, t, t_stop) -> tuple[Propagation, Event | None]:
        self.budget.steps = self.opts.max_steps - self.steps_done
        if self.cap is not None:  # the segment the spans will belong to (add_segment's rule)
            on = self.resume and self.segments and self.segments[-1].mode is self.mode
            self.cap.where = (len(self.segments) - (1 if on else 0), self.mode)
        prop = engine.propagate(cflow, x, t, t_stop, self.model.p, [e.level for e in events],
                                budget=self.budget, dense=self.dense, resume=self.resume)
        self.resume = False
        return prop, (events[prop.event] if prop.event is not None else None)

    def result(self, x0, stop_at, restitution, events, te, pose0) -> Trajectory:
        wall = time.perf_counter() - self.wall0
        kw = dict(stop_at=stop_at, restitution=restitution, user_events=events, pose0=pose0)
        dropped = self.cap is not None and self.cap.dropped
        if dropped:
            self.segments = self.cap.segments(self.segments)
        if te is not None and (self.segments or self.face is not None):
            traj = self.trajectory(x0, wall, **kw)
            te = te[(te >= traj.t0) & (te <= traj.t)]
            if te.size:
                kw.update(ts=te, ys=self.cap.states(self.segments, te) if dropped else traj._chart_states(te))
        if not self.opts.dense and self.dense:  # dense output was kept only to answer t_eval
            self.segments = [replace(s, dense=()) for s in self.segments]
        return self.trajectory(x0, wall, **kw)
