"""Batch propagation: many starts at once on heyoka's SIMD batch integrator.

heyoka's ``taylor_adaptive_batch`` integrates ``lanes`` copies of one vector field with
different states and parameters in the vector registers of one core (8 doubles with
AVX-512 on the reference machine). A phasekit model of one body structure, law class and
chart is one vector field per mode whose numbers (aspect ratio, A, C, mu, eps) are
run-time parameters, so one batch holds starts of different bodies, frictions and family
parameters at once.

The loop
--------
:func:`simulate_batch` is the hybrid loop of :func:`phasekit.simulate` run for many starts
at once (``stop_at="jump"``, no dense output): one batch integrator per contact mode
(SLIDING, ROLLING; the same compiled flows, guards and tolerance as
:class:`phasekit.backends.TaylorEngine`); a lane propagates its start to the mode's first
event; the event's reset (:mod:`phasekit.resets`, called exactly as the scalar loop calls
it) moves the start to the queue of its next mode, or ends it (lift-off: "jumped"; a stop
event: "stopped"; ``t_end``: "completed"). A start that the batch cannot follow - a stiff
mode handed to CVODES (a regularised law that has stuck), a non-finite state, a budget
overrun, a user event that is not a terminal stop - is run again from t = 0 by the scalar
:func:`phasekit.simulate`, so its result is the scalar one by construction.

Events in batch mode (heyoka's batch-mode documentation, and measured here): events are
detected lane by lane, but a terminal event in one lane stops ``propagate_until`` for the
whole batch; the other lanes stop at the end of their current step with outcome
"success" and simply go on at the next call. A lane that finished is parked (its time
limit set to its time) until it is refilled; cooldowns are reset lane by lane, so a lane
that grazed a guard keeps its cooldown, as the scalar loop's ``resume`` does.

Agreement with the scalar path: same steps, so states and event times agree to ~1e-12
(tests/test_sweep.py). Runs that track the minima of R (``track_minima=True``) are not
batched: the non-terminal monitor changes heyoka's steps.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import threading
import time
from collections import deque
from dataclasses import dataclass, field, replace

import numpy as np

from .errors import ParameterError, Status
from .hybrid import Mode
from .model import Model
from .options import SolverOptions
from .charts import POLE_GUARD
from .simulate import apply_transition, simulate, solver_options
from .watch import deadline as watch_deadline
from .system import declare, watched
from .trajectory import EventRecord, Segment, Trajectory
from .validate import check_int

__all__ = ["LANES", "simulate_batch", "compile_batch", "BatchStats"]

#: lanes per batch: the SIMD width for doubles on the reference machine (AVX-512)
LANES = 8
#: steps per call of propagate_until between checks of the budgets
STEP_CHUNK = 20_000
#: steps per call while another mode has starts waiting (the modes take turns)
STEP_SLICE = 500
#: bump when the layout of the pickled cache entries changes
CACHE_FORMAT = 1


@dataclass
class BatchStats:
    """What :func:`simulate_batch` did: starts finished in batch, starts handed to the scalar
    path (with the reasons), calls of heyoka's propagate, and the wall time."""

    batched: int = 0
    scalar: int = 0
    reasons: dict = field(default_factory=dict)
    calls: int = 0
    wall_s: float = 0.0

    def handed_back(self, why: str) -> None:
        self.scalar += 1
        self.reasons[why] = self.reasons.get(why, 0) + 1


class _Integrators:
    """Compiled batch integrators, in memory and on disk (as the scalar ones)."""

    _lock = threading.Lock()
    memory: dict = {}

    @classmethod
    def get(cls, cflow, n_params: int, rtol: float, lanes: int):
        key = (cflow.signature, float(rtol), int(lanes))
        with cls._lock:
            entry = cls.memory.get(key)
        if entry is None:
            entry = cls._load_or_build(cflow, n_params, rtol, lanes, key)
            with cls._lock:
                cls.memory[key] = entry
        return entry

    @classmethod
    def _load_or_build(cls, cflow, n_params, rtol, lanes, key):
        from .backends import _cache_dir, _heyoka

        hy = _heyoka()
        digest = hashlib.sha256(repr((CACHE_FORMAT, "batch", key, hy.__version__)).encode()).hexdigest()[:24]
        cache = _cache_dir()
        path = cache / f"taylor-batch-{digest}.pkl" if cache else None
        if path is not None and path.exists():
            try:
                with open(path, "rb") as fh:
                    return pickle.load(fh)
            except Exception:  # a stale or partial file: rebuild it
                pass
        entry = _build(hy, cflow, n_params, rtol, lanes)
        if path is not None:
            try:
                tmp = path.with_suffix(f".{os.getpid()}.tmp")
                with open(tmp, "wb") as fh:
                    pickle.dump(entry, fh)
                os.replace(tmp, path)
            except Exception:
                pass
        return entry


def _build(hy, cflow, n_params, rtol, lanes):
    """The batch twin of TaylorEngine's integrator: same field, guards and tolerance."""
    from ._translate import to_heyoka

    xs = hy.make_vars(*[f"x{i}" for i in range(cflow.n_states)])
    ps = [hy.par[i] for i in range(n_params)]
    rhs = to_heyoka(cflow.field, [list(xs), ps])[0]
    direction = {-1: hy.event_direction.negative, 1: hy.event_direction.positive, 0: hy.event_direction.any}
    t_events = [hy.t_event_batch(to_heyoka(g.function, [list(xs), ps, [hy.par[n_params + i]]])[0][0],
                                 direction=direction[g.direction]) for i, g in enumerate(cflow.guards)]
    used = hy.get_params(list(rhs) + [e.expression for e in t_events])
    npar = 1 + max((int(str(q)[1:]) for q in used), default=-1)
    ta = hy.taylor_adaptive_batch(list(zip(xs, rhs)), np.zeros((cflow.n_states, lanes)), pars=np.zeros((npar, lanes)),
                                  tol=rtol, t_events=t_events)
    return ta, npar


# -- one start ---------------------------------------------------------------------------------


@dataclass
class _Job:
    """One start on its way through the modes (the batch twin of simulate's _Run)."""

    index: int
    model: Model
    system: object
    x0: np.ndarray
    t_end: float
    user_events: tuple
    mode: Mode = Mode.SLIDING
    t: float = 0.0
    x: np.ndarray | None = None
    resume: bool = False  # a grazed guard: the lane goes on with its cooldown
    status: Status | None = None
    reason: str | None = None
    segments: list = field(default_factory=list)
    records: list = field(default_factory=list)
    steps: int = 0  # in finished segments
    seg_steps: int = 0  # in the segment under way
    wall0: float = 0.0

    def record(self, name, t, before, after, x, detail="") -> None:
        x = None if x is None else np.asarray(x, dtype=float)
        self.records.append(EventRecord(name, float(t), before, after, x, detail,
                                        None if x is None else self.model.chart.to_paper(x)))

    def apply(self, tr, opts) -> None:
        apply_transition(self, tr, opts.switch_limit(self.t_end), opts.settle, 0.0)

    def add_segment(self, t1, x1, end, order, extend) -> None:
        steps, self.seg_steps = self.seg_steps, 0
        if extend and self.segments and self.segments[-1].mode is self.mode:
            last = self.segments[-1]
            self.segments[-1] = Segment(self.mode, last.t0, t1, last.x0, x1, "taylor", end, last.n_steps + steps,
                                        last.n_rhs + steps * (order + 1))
        else:
            self.segments.append(Segment(self.mode, self.t, t1, self.x, x1, "taylor", end, steps, steps * (order + 1)))
        self.steps += steps

    def trajectory(self, opts) -> Trajectory:
        return Trajectory(model=self.model, x0=self.x0, t0=0.0, t_end=self.t_end, options=opts, status=self.status,
                          reason=self.reason, segments=self.segments, events=self.records,
                          wall_s=time.perf_counter() - self.wall0, stop_at="jump", user_events=self.user_events,
                          x_end=None if self.segments else self.x, mode_end=None if self.segments else self.mode)


def _prepare(i, model, x0, t_end, events, opts) -> "_Job | str":
    """The job of one start, or the reason it goes to the scalar path."""
    if not isinstance(model, Model):
        raise ParameterError("models", "must be phasekit Models", model)
    if x0.size != model.n_states:
        raise ParameterError("starts", f"must have {model.n_states} columns in the {model.chart.name} chart", x0.size)
    if opts.track_minima or opts.dense:
        return "track_minima or dense output asked"
    if opts.backend not in ("auto", "taylor"):
        return f"backend {opts.backend}"
    if any(not e.terminal or e.reset is not None for e in events):
        return "non-terminal or resetting user event"
    if not model.chart.regular_at_poles and min(x0[4], np.pi - x0[4]) < POLE_GUARD:
        return "start at a pole of the Euler chart"
    system = declare(model, stop_at="jump", events=events)
    job = _Job(i, model, system, np.asarray(x0, float), t_end, tuple(events), wall0=time.perf_counter())
    job.apply(system.initial(model, 0.0, x0, None), opts)
    return job


# -- the lanes of one mode -----------------------------------------------------------------------


class _Lanes:
    """One batch integrator (one mode's flow with its guards) and the jobs in its lanes."""

    def __init__(self, model, system, mode, opts, lanes):
        self.mode, self.opts, self.lanes, self.n_params = mode, opts, lanes, len(model.p)
        flow = replace(system.flow(mode), monitor=None)  # what simulate integrates with track_minima=False
        self.guards = watched(system, mode, "taylor")
        self.cflow = model.compile_flow(flow, self.guards)
        self.ta = self.npar = None
        self.slot: list[_Job | None] = [None] * lanes
        self.queue: deque = deque()
        self.limit = np.zeros(lanes)

    def busy(self) -> bool:
        return bool(self.queue) or any(j is not None for j in self.slot)

    def load(self) -> int:
        """Starts in the lanes or waiting for one."""
        return len(self.queue) + sum(j is not None for j in self.slot)

    def fill(self) -> None:
        """Put queued jobs into free lanes; park the others (time limit = their time)."""
        if self.ta is None:
            self.ta, self.npar = _Integrators.get(self.cflow, self.n_params, self.opts.rtol, self.lanes)
        ta = self.ta
        hi, lo = (np.array(a, copy=True) for a in ta.dtime)
        fresh, idle = [], []
        if self.queue and any(j is None for j in self.slot):
            # longest first (steps ~ rotation rate x time left), so the last lanes to finish
            # are short ones and few lanes idle at the end
            self.queue = deque(sorted(self.queue, key=lambda j: -float(self.cflow.rate_hint(j.x)) * (j.t_end - j.t)))
        for k in range(self.lanes):
            if self.slot[k] is None and self.queue:
                job = self.slot[k] = self.queue.popleft()
                ta.state[:, k] = job.x
                pars = np.concatenate([job.model.p, [e.level for e in self.guards]])
                ta.pars[:, k] = pars[:self.npar]
                hi[k], lo[k], self.limit[k] = job.t, 0.0, job.t_end
                fresh.append(k)
            elif self.slot[k] is None:
                idle.append(k)
        # An idle lane is still evaluated (SIMD): it must hold a valid state, or its nan
        # step would poison its time. It takes no steps (time limit = its time).
        model_lane = next(k for k in range(self.lanes) if self.slot[k] is not None)
        for k in idle:
            if not (np.isfinite(hi[k]) and np.isfinite(lo[k]) and np.all(np.isfinite(ta.state[:, k]))):
                ta.state[:, k] = ta.state[:, model_lane]
                ta.pars[:, k] = ta.pars[:, model_lane]
                hi[k], lo[k] = 0.0, 0.0
                fresh.append(k)
            self.limit[k] = hi[k]
        if fresh:
            ta.set_dtime(hi, lo)
            for k in fresh:
                ta.reset_cooldowns(k)


def simulate_batch(models, starts, t_end, *, events=(), lanes: int = LANES, options: SolverOptions | None = None,
                   stats: BatchStats | None = None, **option_fields) -> list[Trajectory]:
    """Simulate many starts, ``lanes`` at a time per mode on heyoka's batch integrator.

    Returns what ``[simulate(m, x0, t_end, events=events, options=...) for m, x0 in ...]``
    returns (``stop_at="jump"``): the same statuses, events and segments, with states and
    event times equal to ~1e-12. Starts the batch cannot follow are run by :func:`simulate`.

    Parameters
    ----------
    models : Model or sequence of Model
        One model for all starts, or one per start (bodies and coefficients of one body
        class, law class and chart share the batch integrators).
    starts : array (m, d)
        Start states in the models' chart.
    t_end : float or sequence of float
        End time(s) (> 0).
    events : sequence of Event
        Terminal stop events (e.g. ``Event("theta", 0.1, direction=-1)``); with a
        non-terminal event or one with a reset every start goes to the scalar path.
    lanes : int
        Lanes per batch integrator (default :data:`LANES`, the SIMD width).
    options, **option_fields
        As for :func:`simulate`. Dense output and ``track_minima=True`` (both defaults of
        simulate) are scalar-only: pass ``track_minima=False, dense=False`` to batch.
    stats : BatchStats, optional
        Filled with what was batched and what was handed back.
    """
    opts = solver_options(options, **option_fields)
    lanes = check_int("lanes", lanes, minimum=1, maximum=64)
    starts = np.atleast_2d(np.asarray(starts, dtype=float))
    m = starts.shape[0]
    models = [models] * m if isinstance(models, Model) else list(models)
    if len(models) != m:
        raise ParameterError("models", f"must be one Model or one per start ({m})", len(models))
    t_ends = np.broadcast_to(np.asarray(t_end, dtype=float), (m,)).copy()
    stats = stats if stats is not None else BatchStats()
    wall0 = time.perf_counter()
    out: list[Trajectory | None] = [None] * m
    groups: dict = {}
    for i, (model, x0) in enumerate(zip(models, starts)):
        job = _prepare(i, model, x0, float(t_ends[i]), events, opts)
        if isinstance(job, str):
            stats.handed_back(job)
            out[i] = simulate(model, x0, float(t_ends[i]), events=events, options=opts, progress=False)
        elif job.status is not None:  # ended at the start (e.g. R <= 0)
            stats.batched += 1
            out[i] = job.trajectory(opts)
        else:
            groups.setdefault(model.compiled.signature, []).append(job)
    for jobs in groups.values():
        _run_group(jobs, events, opts, lanes, out, stats)
    stats.wall_s += time.perf_counter() - wall0
    return out


def _run_group(jobs, events, opts, lanes, out, stats) -> None:
    """Run the jobs of one compiled model through one batch integrator per contact mode."""
    from .backends import _heyoka

    hy = _heyoka()
    first = jobs[0]
    modes = {mode: _Lanes(first.model, first.system, mode, opts, lanes) for mode in (Mode.SLIDING, Mode.ROLLING)
             if mode in first.model.modes}
    deadline = {}

    def finish(job, why=None):
        if why is not None:
            stats.handed_back(why)
            out[job.index] = simulate(job.model, job.x0, job.t_end, events=events, options=opts, progress=False)
        else:
            stats.batched += 1
            out[job.index] = job.trajectory(opts)

    def route(job):
        """Send a job to its mode's queue, or end it."""
        if job.status is not None:
            return finish(job)
        target = modes.get(job.mode)
        if target is None or (opts.backend == "auto" and job.system.flow(job.mode).stiff):
            return finish(job, f"{job.mode.value} mode is stiff (CVODES) or not batched")
        target.queue.append(job)

    call = watch_deadline()  # a search's or a map's budget, when it ends first
    for job in jobs:
        deadline[job.index] = min(job.wall0 + opts.max_wall, call[0] if call else np.inf)
        route(job)
    while any(L.busy() for L in modes.values()):
        # Work on the mode with the most starts, a slice at a time while another mode has
        # starts waiting: starts reach the rolling mode one by one (as they stick), and a
        # rolling integrator run alone to t_end would hold one lane of eight.
        L = max(modes.values(), key=lambda M: M.load())
        others = any(M.busy() for M in modes.values() if M is not L)
        L.fill()
        try:
            L.ta.propagate_until(L.limit, max_steps=STEP_SLICE if others else STEP_CHUNK)
        except Exception as exc:  # e.g. a non-finite state inside an event function
            for k, job in enumerate(L.slot):
                if job is not None:
                    L.slot[k] = None
                    finish(job, f"batch propagation raised {type(exc).__name__}")
            continue
        stats.calls += 1
        for k, res in enumerate(L.ta.propagate_res):
            job = L.slot[k]
            if job is None:
                continue
            verdict = _lane_step(hy, res, k, L, job, opts, time.perf_counter() > deadline[job.index])
            if verdict == "running":
                continue
            L.slot[k] = None
            if verdict == "moved":
                route(job)
            else:
                finish(job, verdict)


def _lane_step(hy, res, k, L, job, opts, late) -> str:
    """Handle one lane after a propagate call: "running" (goes on in its lane), "moved"
    (to route: next mode or ended), or a reason to hand it to the scalar path."""
    outcome, code = res[0], int(res[0].value)
    job.seg_steps += int(res[3])
    t, x = float(L.ta.time[k]), np.array(L.ta.state[:, k], copy=True)
    if outcome in (hy.taylor_outcome.success, hy.taylor_outcome.step_limit) and t >= job.t_end:
        outcome = hy.taylor_outcome.time_limit  # the slice ended on the lane's last step
    if outcome in (hy.taylor_outcome.success, hy.taylor_outcome.step_limit):
        if not np.all(np.isfinite(x)):
            return "non-finite state in a lane"
        if job.steps + job.seg_steps >= opts.max_steps or late:
            return "step or wall budget of the lane"
        return "running"
    extend, job.resume = job.resume, False
    if outcome == hy.taylor_outcome.time_limit:
        job.add_segment(t, x, "time", L.ta.order, extend)
        job.t, job.x, job.status = t, x, Status.COMPLETED
        return "moved"
    if not -(2**31) < code < 0:
        return f"lane outcome {outcome}"
    ev = L.guards[-code - 1]
    job.add_segment(t, x, ev.name, L.ta.order, extend)
    job.t, job.x = t, x
    if ev.reset is None:
        job.record(ev.name, t, job.mode.value, "end", x)
        job.status = ev.stop
        if ev.stop is Status.STOPPED:
            job.reason = f"{ev.name}: {ev.on} reached {ev.level:g}"
        return "moved"
    job.apply(ev.reset(job.model, ev, job.mode, t, x), opts)
    if job.resume and job.status is None:
        return "running"  # grazed: the same lane goes on, its cooldown kept
    return "moved"


def compile_batch(model: Model, events=(), *, lanes: int = LANES, **option_fields) -> int:
    """Compile (or load from the disk cache) the batch integrators that
    :func:`simulate_batch` uses for ``model`` and ``events`` (one per contact mode it can
    batch), without running anything; returns how many. Sweeps call it before snapshotting
    their compiled code for the workers."""
    opts = solver_options(**option_fields)
    system = declare(model, stop_at="jump", events=events)
    n = 0
    for mode in (Mode.SLIDING, Mode.ROLLING):
        if mode in model.modes and not (opts.backend == "auto" and system.flow(mode).stiff):
            L = _Lanes(model, system, mode, opts, lanes)
            _Integrators.get(L.cflow, L.n_params, opts.rtol, lanes)
            n += 1
    return n
