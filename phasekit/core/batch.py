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
at once (``stop_at="jump"``, no dense output): one batch integrator
(:class:`phasekit.core.engines.batch.TaylorBatchEngine`: the scalar Taylor engine's build, compact mode and
event cooldown) per contact flow of the declared system (:mod:`phasekit.core.system`; a new contact
mode is one more Flow there); a lane propagates its start to the mode's first event, and the
end of the segment is handled by the scalar loop's own routine
(:meth:`phasekit.core.simulate.RunState.end_segment`: the event's reset moves the start to the queue of
its next mode, or ends it: lift-off "jumped", a stop event "stopped", ``t_end`` "completed").
A start that the batch cannot follow - a stiff
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
(tests/core/test_batch_propagation.py). Runs that track the minima of R (``track_minima=True``) or keep
dense output are not batched: both are read from each step's Taylor coefficients, recorded by the
scalar engine's step callback, which the batch engine has not.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field, replace

import numpy as np

from .._runtime.validate import check_int
from .._runtime.watch import deadline as watch_deadline
from ..errors import ParameterError
from .audit import audited_options
from .charts import POLE_GUARD
from .engines import End
from .engines.batch import TaylorBatchEngine
from .engines.scaling import initial_scales, next_rescale, next_scales
from .engines.taylor_build import scales_at, taylor_pars
from .model import Model
from .options import SolverOptions
from .simulate import RunState, simulate, solver_options
from .system import declare, watched
from .trajectory import Trajectory

#: lanes per batch: the SIMD width for doubles on the reference machine (AVX-512)
LANES = 8
#: steps per call of propagate_until between checks of the budgets
STEP_CHUNK = 20_000
#: steps per call while another mode has starts waiting (the modes take turns)
STEP_SLICE = 500


@dataclass
class BatchStats:
    """What :func:`simulate_batch` did, filled in as it runs: starts finished in batch, starts
    handed to the scalar path (with the reasons), calls of heyoka's propagate, and the wall time.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.core import batch
    >>> stats = batch.BatchStats()
    >>> stats.handed_back("a reason"); (stats.scalar, stats.reasons)
    (1, {'a reason': 1})
    """

    batched: int = 0
    scalar: int = 0
    reasons: dict = field(default_factory=dict)
    calls: int = 0
    wall_s: float = 0.0

    def handed_back(self, why: str) -> None:
        self.scalar += 1
        self.reasons[why] = self.reasons.get(why, 0) + 1


# -- one start ---------------------------------------------------------------------------------


class _Job(RunState):
    """One start on its way through the modes: a run of the loop whose segments come from lanes."""

    def __init__(self, index, model, system, x0, t_end, user_events, opts):
        super().__init__(model, system, opts, 0.0, t_end)
        self.index, self.x0, self.user_events = index, np.asarray(x0, float), tuple(user_events)
        self.steps = 0  # in finished segments
        self.seg_steps = 0  # in the segment under way
        self.wall0 = time.perf_counter()

    def finish_segment(self, end: End, t, x, ev, order: int) -> None:
        """The lane's segment ends at (t, x): record it and let the shared loop handle the end."""
        extend, self.resume = self.resume, False
        steps, self.seg_steps = self.seg_steps, 0
        self.add_segment("taylor", t, x, ev.name if end is End.EVENT else str(end), steps, steps * (order + 1),
                         extend=extend)
        self.steps += steps
        self.end_segment(end, t, x, ev)

    def result(self) -> Trajectory:
        return self.trajectory(self.x0, time.perf_counter() - self.wall0, user_events=self.user_events)


def _prepare(i, model, x0, t_end, events, opts) -> "_Job | str":
    """The job of one start, or the reason it goes to the scalar path."""
    if not isinstance(model, Model):
        raise ParameterError("models", "must be phasekit Models", model)
    if not opts.creep and model.friction.creeps:  # the law's own field at zero slip, as simulate does
        model = Model(model.body, model.friction.without_creep(), model.chart)
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
    job = _Job(i, model, system, x0, t_end, events, opts)
    job.apply(system.initial(model, 0.0, x0, None))
    return job


def _batched(model, system, opts) -> list:
    """The flows the batch runs: the model's contact flows (the runs stop at the first lift-off)
    that the scalar loop would integrate with the Taylor method."""
    def taylor(flow):
        name = flow.engine or opts.backend
        return name == "taylor" or (name == "auto" and not flow.stiff)

    return [f for f in system.contact_flows if f.mode in model.modes and taylor(f)]


# -- the lanes of one mode -----------------------------------------------------------------------


class _Lanes:
    """One batch integrator (one mode's flow with its guards) and the jobs in its lanes."""

    def __init__(self, model, system, mode, opts, lanes):
        self.mode, self.opts, self.lanes, self.n_params = mode, opts, lanes, len(model.p)
        self.engine = TaylorBatchEngine(opts.rtol, lanes)
        flow = replace(system.flow(mode), monitor=None)  # what simulate integrates with track_minima=False
        self.guards = watched(system, mode, self.engine)
        self.cflow = model.compile_flow(flow, self.guards)
        self.ta = self.npar = None
        self.slot: list[_Job | None] = [None] * lanes
        self.queue: deque = deque()
        self.limit = np.zeros(lanes)

    def compile(self):
        if self.ta is None:
            self.ta, self.npar = self.engine.integrator(self.cflow, self.n_params)
        return self.ta

    def state(self, k: int) -> np.ndarray:
        """Lane ``k``'s state in the flow's variables (the integrator's are scaled, engines.scaling)."""
        first = scales_at(self.cflow, self.n_params)
        return self.ta.state[:, k] * self.ta.pars[first:first + self.cflow.n_states, k]

    def rescale(self, k: int, job) -> None:
        """Lane ``k`` reached a grid time of its scales (not its end): renew them, as the scalar engine does."""
        first, n = scales_at(self.cflow, self.n_params), self.cflow.n_states
        x = self.state(k)
        scale = next_scales(x, self.ta.pars[first:first + n, k])
        self.ta.pars[first:first + n, k] = scale
        self.ta.state[:, k] = x / scale
        self.limit[k] = min(job.t_end, next_rescale(float(self.ta.time[k])))

    def busy(self) -> bool:
        return bool(self.queue) or any(j is not None for j in self.slot)

    def load(self) -> int:
        """Starts in the lanes or waiting for one."""
        return len(self.queue) + sum(j is not None for j in self.slot)

    def fill(self) -> None:
        """Put queued jobs into free lanes; park the others (time limit = their time)."""
        ta = self.compile()
        hi, lo = (np.array(a, copy=True) for a in ta.dtime)
        fresh, idle = [], []
        if self.queue and any(j is None for j in self.slot):
            # longest first (steps ~ rotation rate x time left), so the last lanes to finish
            # are short ones and few lanes idle at the end
            self.queue = deque(sorted(self.queue, key=lambda j: -float(self.cflow.rate_hint(j.x)) * (j.t_end - j.t)))
        for k in range(self.lanes):
            if self.slot[k] is None and self.queue:
                job = self.slot[k] = self.queue.popleft()
                scale = initial_scales(job.x)
                ta.state[:, k] = job.x / scale
                ta.pars[:, k] = taylor_pars(job.model.p, [e.level for e in self.guards], scale)
                hi[k], lo[k], self.limit[k] = job.t, 0.0, min(job.t_end, next_rescale(job.t))
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

    Returns
    -------
    list of Trajectory
        One per start, in the order of ``starts``.

    Raises
    ------
    ParameterError
        If ``lanes`` is not an integer in [1, 64], ``models`` is neither one Model nor one
        per start, a start does not have the model's number of states, or an option is
        invalid; a start run by :func:`simulate` raises as it does.

    See Also
    --------
    phasekit.simulate
        one start, with every option

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (9.0, 10.5)]
    >>> runs = pk.core.simulate_batch(pk.Model(body, pk.Coulomb(0.1)), starts, 300.0, track_minima=False, dense=False)
    >>> [r.status.value for r in runs]
    ['completed', 'jumped']
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
    lane_opts = audited_options(opts)  # the scalar path (simulate) applies the audit itself
    for i, (model, x0) in enumerate(zip(models, starts)):
        job = _prepare(i, model, x0, float(t_ends[i]), events, lane_opts)
        if not isinstance(job, str):
            job.source = (model, x0)  # what a job handed back to simulate starts from (simulate audits it itself)
        if isinstance(job, str):
            stats.handed_back(job)
            out[i] = simulate(model, x0, float(t_ends[i]), events=events, options=opts, progress=False)
        elif job.status is not None:  # ended at the start (e.g. R <= 0)
            stats.batched += 1
            out[i] = job.result()
        else:
            groups.setdefault(model.compiled.signature, []).append(job)
    for jobs in groups.values():
        _run_group(jobs, events, lane_opts, lanes, out, stats, opts)
    stats.wall_s += time.perf_counter() - wall0
    return out


def _run_group(jobs, events, opts, lanes, out, stats, scalar_opts=None) -> None:
    """Run the jobs of one compiled model through one batch integrator per contact flow (a job
    handed back runs from its start through simulate with ``scalar_opts``, default ``opts``)."""
    scalar_opts = opts if scalar_opts is None else scalar_opts
    first = jobs[0]
    modes = {f.mode: _Lanes(first.model, first.system, f.mode, opts, lanes) for f in _batched(first.model, first.system, opts)}
    deadline = {}

    def finish(job, why=None):
        if why is not None:
            stats.handed_back(why)
            out[job.index] = simulate(*job.source, job.t_end, events=events, options=scalar_opts, progress=False)
        else:
            stats.batched += 1
            out[job.index] = job.result()

    def route(job):
        """Send a job to its mode's queue, or end it."""
        if job.status is not None:
            return finish(job)
        target = modes.get(job.mode)
        if target is None:
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
            ends = L.engine.propagate(L.ta, L.limit, STEP_SLICE if others else STEP_CHUNK)
        except Exception as exc:  # e.g. a non-finite state inside an event function
            for k, job in enumerate(L.slot):
                if job is not None:
                    L.slot[k] = None
                    finish(job, f"batch propagation raised {type(exc).__name__}")
            continue
        stats.calls += 1
        for k, lane_end in enumerate(ends):
            job = L.slot[k]
            if job is None:
                continue
            verdict = _lane_step(lane_end, k, L, job, opts, time.perf_counter() > deadline[job.index])
            if verdict == "running":
                continue
            L.slot[k] = None
            if verdict == "moved":
                route(job)
            else:
                finish(job, verdict)


def _lane_step(lane_end, k, L, job, opts, late) -> str:
    """Handle one lane after a propagate call: "running" (goes on in its lane), "moved"
    (to route: next mode or ended), or a reason to hand it to the scalar path."""
    end, event, steps, what = lane_end
    job.seg_steps += steps
    t, x = float(L.ta.time[k]), L.state(k)
    if end is End.TIME and t < job.t_end:  # a grid time of the scales
        L.rescale(k, job)
        end = None
    if end is None:
        if not np.all(np.isfinite(x)):
            return "non-finite state in a lane"
        if job.steps + job.seg_steps >= opts.max_steps or late:
            return "step or wall budget of the lane"
        return "running"
    if end is End.FAILED:
        return f"lane outcome {what}"
    job.finish_segment(end, t, x, L.guards[event] if end is End.EVENT else None, L.ta.order)
    if job.resume and job.status is None:
        return "running"  # grazed: the same lane goes on, its cooldown kept
    return "moved"


def compile_batch(model: Model, events=(), *, lanes: int = LANES, **option_fields) -> int:
    """Compile (or load from the disk cache) the batch integrators that
    :func:`simulate_batch` uses for ``model`` and ``events`` (one per contact flow it can
    batch), without running anything; returns how many. Sweeps call it before snapshotting
    their compiled code for the workers.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.core import batch
    >>> batch.compile_batch(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)), track_minima=False, dense=False)
    2
    """
    opts = solver_options(**option_fields)
    system = declare(model, stop_at="jump", events=events)
    flows = _batched(model, system, opts)
    for f in flows:
        _Lanes(model, system, f.mode, opts, lanes).compile()
    return len(flows)
