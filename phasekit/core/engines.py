"""Engines: integrators that propagate one smooth flow until a time or its first located event.

Every engine follows one protocol (:class:`Engine`): a ``name`` (what a segment records), whether
it is ``pointwise`` (it sees the guards only at output points, so the stick guard is watched in
its smooth squared form with a rate) and ``propagate(flow, x0, t0, t_end, p, levels, *, budget,
dense, resume) -> Propagation``. :data:`ENGINES` maps the names that ``SolverOptions.backend``
accepts to them; :func:`register_engine` adds one (nothing else needs editing). The compiled
integrators of every engine come from one build path and one cache (:func:`compiled`: in memory,
and on disk for heyoka's, whose LLVM compilation costs seconds to minutes).

``taylor`` (default)
    heyoka's adaptive Taylor method on the CasADi model translated to heyoka
    expressions (:mod:`phasekit._runtime.translate`), LLVM-compiled once per (flow, guards,
    tolerance) and cached in memory and on disk. Events are located by polynomial root
    finding on each step's Taylor expansion, i.e. to about machine precision in time.
    Dense output is heyoka's continuous output (the steps' Taylor polynomials).
``cvodes`` / ``cvodes-adams`` / ``idas``
    SUNDIALS through CasADi. CasADi's event support is experimental, so events are
    bracketed on an output grid fine enough to resolve the fast oscillation (20 points per
    period of the fastest rotation) and refined by Brent's method on re-integrations from
    the last grid point. This is the backend for stiff fields (a regularised Coulomb law
    once the slip is below ~eps). Dense output is cubic Hermite on that grid.

``taylor-batch`` (:class:`TaylorBatchEngine`, used by :func:`phasekit.simulate_batch`)
    the same Taylor integrator on heyoka's SIMD batch mode: ``lanes`` starts at once, each
    propagated to a time or its own first event. Built from the same expressions, with the same
    compact mode and event cooldown, so a lane takes the steps a scalar run takes.

Each takes a :class:`phasekit.core.hybrid.CompiledFlow` and returns a :class:`Propagation` (a batch:
one per lane). Work is bounded by a step budget and a wall-clock deadline; running out of
either, or a non-finite state, ends with :attr:`End.FAILED` and the reason, never an exception.
"""

from __future__ import annotations

import contextlib
import enum
import hashlib
import io
import os
import pickle
import re
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Protocol

import numpy as np

from .._runtime.errors import ParameterError
from .hybrid import CompiledFlow

__all__ = ["Engine", "End", "Propagation", "Budget", "TaylorEngine", "TaylorBatchEngine", "CvodesEngine", "ENGINES",
           "engine_for", "register_engine", "engine_names"]

#: bump when the layout of the pickled cache entries changes
CACHE_FORMAT = 4
#: cooldown of every guard after it fires (a run resumed after a non-terminal event or a
#: graze must not find the same root again). heyoka deduces one from the guard's rate at the
#: root, which blows up at a tangential crossing: measured 8.6e8 for a section Lambda = 0 at a
#: start with dLambda/dt = 1e-16, which silenced the event for the rest of the run.
EVENT_COOLDOWN = 1e-9
#: steps per call of heyoka's propagate: between calls the wall clock is checked
STEP_CHUNK = 20_000
#: flows whose field and guards exceed this many CasADi instructions are compiled in heyoka's
#: compact mode (loops instead of unrolled code). Measured on an egg (Chebyshev support function
#: of degree 64, ~8000 instructions with its events): unrolled, the sliding and rolling
#: integrators took 16 min and 1.7 GB to compile; compact, the sliding one 7 s. Every spheroid
#: and tippe-top flow is below 2300 instructions and stays unrolled (fastest steps, numbers unchanged).
COMPACT_ABOVE = 3000


class End(str, enum.Enum):
    """How one propagation ended: at the requested time, at an event, or failed (see the reason).

    Examples
    --------
    >>> import phasekit as pk
    >>> [str(e) for e in pk.core.engines.End]
    ['time', 'event', 'failed']
    """

    TIME = "time"
    EVENT = "event"
    FAILED = "failed"

    def __str__(self) -> str:
        return self.value


@dataclass
class Budget:
    """What is left of a run's work allowance: steps and a wall-clock deadline.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.Budget(steps=10, deadline=float('inf')).wall_exceeded()
    False
    """

    steps: int
    deadline: float  # time.perf_counter() value
    tick: object = None  # called with the time reached between chunks of a long call (a progress bar)

    def wall_exceeded(self) -> bool:
        return time.perf_counter() > self.deadline


@dataclass
class Propagation:
    """What one call of an engine produced (filled in by the engine as it runs).

    Examples
    --------
    >>> import phasekit as pk
    >>> prop = pk.core.engines.Propagation(t=1.0, x=[0.0], outcome=pk.core.engines.End.TIME)
    >>> prop.outcome.value, prop.n_steps
    ('time', 0)
    """

    t: float
    x: np.ndarray
    outcome: End
    event: int | None = None  # index into the flow's guards
    reason: str | None = None
    n_steps: int = 0
    n_rhs: int = 0
    monitored: list = field(default_factory=list)  # [(t, x)] where the monitor crossed zero
    dense: list = field(default_factory=list)  # callables t -> states, in time order, with their spans


class Engine(Protocol):
    """An integrator of one smooth flow, to a time or the flow's first event.

    ``name`` is what the segments it integrates record; ``pointwise`` says it sees the guards
    only at output points (the stick guard is then watched in its smooth form with a rate, see
    :func:`phasekit.core.system.watched`). The batch engine (:class:`TaylorBatchEngine`) has the same
    name and pointwise flag, and its ``propagate`` takes every lane of an integrator at once.

    Examples
    --------
    >>> import phasekit as pk
    >>> engine = pk.core.engines.engine_for('cvodes', 1e-9)
    >>> engine.name, engine.pointwise
    ('cvodes', True)
    """

    name: str
    pointwise: bool

    def propagate(self, flow: CompiledFlow, x0, t0: float, t_end: float, p, levels, *, budget: Budget,
                  dense: bool = False, resume: bool = False) -> Propagation: ...


# -- one cache for every engine's compiled integrators ----------------------------------------------


def _cache_dir() -> Path | None:
    root = os.environ.get("PHASEKIT_CACHE")
    if root == "":
        return None  # caching disabled
    path = Path(root) if root else Path.home() / ".cache" / "phasekit"
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return path


_LOCK = threading.Lock()
_MEMORY: dict = {}  # key -> compiled entry (what ``build`` returned)
_PERSISTENT: set = set()  # the keys whose entries are picklable (heyoka's), for snapshot()
_RECORDERS: dict = {}  # id(integrator) -> the monitor recorder inside it (looked up once)


def compiled(key: tuple, build: Callable[[], object], *, disk: str | None = None):
    """The compiled entry ``key`` of an engine: from memory, else (``disk`` names the file kind)
    from the on-disk cache, else ``build()`` (then stored in both). Disk files are written under
    a temporary name and renamed, so processes sharing the cache never read a torn one."""
    with _LOCK:
        entry = _MEMORY.get(key)
    if entry is not None:
        return entry
    path = None
    if disk is not None:
        hy = _heyoka()
        digest = hashlib.sha256(repr((CACHE_FORMAT, key, hy.__version__)).encode()).hexdigest()[:24]
        cache = _cache_dir()
        path = cache / f"{disk}-{digest}.pkl" if cache else None
    if path is not None and path.exists():
        try:
            with open(path, "rb") as fh:
                entry = pickle.load(fh)
        except Exception:  # a stale or partial file: rebuild it
            entry = None
    if entry is None:
        entry = build()
        if path is not None:
            try:
                tmp = path.with_suffix(f".{os.getpid()}.tmp")
                with open(tmp, "wb") as fh:
                    pickle.dump(entry, fh)
                os.replace(tmp, path)
            except Exception:
                pass
    with _LOCK:
        entry = _MEMORY.setdefault(key, entry)
        if disk is not None:
            _PERSISTENT.add(key)
    return entry


def snapshot() -> dict:
    """The picklable compiled integrators of this process (for :class:`phasekit.sweep.ModelPack`)."""
    with _LOCK:
        return {k: _MEMORY[k] for k in _PERSISTENT}


def install(entries: dict) -> None:
    """Add a :func:`snapshot` of another process to this one's cache (entries already here are kept)."""
    with _LOCK:
        for k, v in entries.items():
            _MEMORY.setdefault(k, v)
            _PERSISTENT.add(k)


def forget() -> None:
    """Empty the in-memory cache (the next use reloads from disk; tests of the disk cache)."""
    with _LOCK:
        _MEMORY.clear()
        _PERSISTENT.clear()
        _RECORDERS.clear()


class _MonitorRecorder:
    """Non-terminal event callback storing (t, x) at each crossing of the monitor.

    heyoka deep-copies callbacks; returning self from __deepcopy__ keeps one shared list.
    """

    def __init__(self):
        self.points: list = []

    def __deepcopy__(self, memo):
        return self

    def __call__(self, ta, t, d_sgn):
        ta.update_d_output(t)
        self.points.append((float(t), np.array(ta.d_output, copy=True)))


class _TaylorSteps:
    """Dense output of the Taylor method: the Taylor coefficients of every step (heyoka's
    ``tc``, the expansion at the step's start), recorded by a step callback and evaluated
    here by Horner's rule. heyoka's own continuous output costs ~1.5-2.5 ms per propagate
    call whatever its length (measured), which dominates runs of many short segments; this
    costs ~2 us per step."""

    def __init__(self, t0: float):
        self.starts, self.coefs, self.t_last = [], [], float(t0)

    def __call__(self, ta) -> bool:  # heyoka's step callback: after every step
        self.starts.append(self.t_last)
        self.coefs.append(np.array(ta.tc, copy=True))
        self.t_last = float(ta.time)
        return True

    def __deepcopy__(self, memo):  # heyoka may copy callbacks; keep recording into this one
        return self

    def finish(self, ta) -> None:
        """Record the last, event-truncated step when the callback did not see it."""
        if float(ta.time) != self.t_last:
            self(ta)

    def span(self):
        if not self.coefs:
            return None
        starts, coefs = np.array(self.starts), np.array(self.coefs)
        ends = np.append(starts[1:], self.t_last)
        return _Span(_TaylorDense(starts, ends, coefs), starts[0], self.t_last)


class _TaylorDense:
    """x(t) = sum_j tc[:, j] (t - t_start)^j on the step containing t."""

    def __init__(self, starts, ends, coefs):
        self.starts, self.ends, self.coefs = starts, ends, coefs

    def __call__(self, ts) -> np.ndarray:
        ts = np.atleast_1d(np.asarray(ts, dtype=float))
        k = np.clip(np.searchsorted(self.ends, ts, side="left"), 0, len(self.starts) - 1)
        h = (ts - self.starts[k])[:, None]
        c = self.coefs[k]  # (n, states, order + 1)
        out = c[:, :, -1].copy()
        for j in range(c.shape[2] - 2, -1, -1):
            out = out * h + c[:, :, j]
        return out

    def pieces(self):
        """(starts, ends, coefficients (steps, states, order + 1)): the steps' polynomials in
        powers of t - start, for quadratures along the run (:mod:`phasekit.core.pose`)."""
        return self.starts, self.ends, self.coefs


class _Span:
    """A dense-output callable restricted to [t0, t1]."""

    def __init__(self, f, t0: float, t1: float):
        self.f, self.t0, self.t1 = f, float(t0), float(t1)

    def __call__(self, ts) -> np.ndarray:
        ts = np.asarray(ts, dtype=float)
        return np.asarray(self.f(ts)).reshape(ts.size, -1)

    def pieces(self):
        """The piecewise polynomials behind this span (see :meth:`_TaylorDense.pieces`)."""
        return self.f.pieces()


def _heyoka():
    import heyoka as hy

    # heyoka logs through spdlog to stdout; results go to stdout, so keep it quiet
    hy.set_logger_level_critical()
    return hy


def _build_taylor(flow: CompiledFlow, n_params: int, rtol: float, lanes: int | None):
    """heyoka's integrator of ``flow`` (``lanes`` None: scalar; else a batch of that many lanes):
    the field and guards translated from CasADi, every guard a terminal event with the cooldown
    EVENT_COOLDOWN, the monitor a non-terminal one (scalar only), compact mode for big flows.
    Returns (integrator, number of parameters it reads)."""
    from .._runtime.translate import to_heyoka

    hy = _heyoka()
    batch = lanes is not None
    xs = hy.make_vars(*[f"x{i}" for i in range(flow.n_states)])
    ps = [hy.par[i] for i in range(n_params)]
    rhs = to_heyoka(flow.field, [list(xs), ps])[0]
    direction = {-1: hy.event_direction.negative, 1: hy.event_direction.positive, 0: hy.event_direction.any}
    t_event = hy.t_event_batch if batch else hy.t_event
    t_events = [t_event(to_heyoka(g.function, [list(xs), ps, [hy.par[n_params + i]]])[0][0], direction=direction[g.direction],
                        cooldown=EVENT_COOLDOWN) for i, g in enumerate(flow.guards)]
    nt_events = []
    if flow.monitor is not None:
        if batch:
            raise ValueError("a batch integrator records no monitor: compile its flow without one")
        m = flow.monitor
        nt_events = [hy.nt_event(to_heyoka(m.function, [list(xs), ps, [hy.expression(0.0)]])[0][0],
                                 callback=_MonitorRecorder(), direction=direction[m.direction])]
    used = hy.get_params(list(rhs) + [e.expression for e in t_events] + [e.expression for e in nt_events])
    npar = 1 + max((int(str(q)[1:]) for q in used), default=-1)
    size = flow.field.n_instructions() + sum(g.function.n_instructions() for g in flow.guards)
    size += flow.monitor.function.n_instructions() if flow.monitor else 0
    if batch:
        ta = hy.taylor_adaptive_batch(list(zip(xs, rhs)), np.zeros((flow.n_states, lanes)), pars=np.zeros((npar, lanes)),
                                      tol=rtol, t_events=t_events, compact_mode=size > COMPACT_ABOVE)
    else:
        ta = hy.taylor_adaptive(list(zip(xs, rhs)), [0.0] * flow.n_states, pars=[0.0] * npar, tol=rtol,
                                t_events=t_events, nt_events=nt_events, compact_mode=size > COMPACT_ABOVE)
    return ta, npar


def taylor_end(hy, outcome) -> tuple[End | None, int | None]:
    """heyoka's outcome of a propagate call as (End, event index); (None, None) while it is under
    way (a step limit, or a batch lane stopped by another lane's event); (End.FAILED, None) for
    anything else (the caller words the reason)."""
    code = int(outcome.value)
    if outcome in (hy.taylor_outcome.step_limit, hy.taylor_outcome.success):
        return None, None
    if outcome == hy.taylor_outcome.time_limit:
        return End.TIME, None
    if -(2**31) < code < 0:  # terminal event i triggered: outcome -(i+1)
        return End.EVENT, -code - 1
    return End.FAILED, None


class TaylorEngine:
    """heyoka Taylor integrator; ``rtol`` is heyoka's (mixed absolute/relative) tolerance.

    Examples
    --------
    >>> import phasekit as pk
    >>> e = pk.core.engines.TaylorEngine(1e-9)
    >>> e.name, e.pointwise, e.rtol
    ('taylor', False, 1e-09)
    """

    name = "taylor"
    pointwise = False

    def __init__(self, rtol: float, atol: float | None = None):
        self.rtol = float(rtol)

    def integrator(self, flow: CompiledFlow, n_params: int):
        """(heyoka integrator, monitor recorder or None, number of parameters), compiled once."""
        ta, npar = compiled((flow.signature, self.rtol), partial(_build_taylor, flow, n_params, self.rtol, None),
                            disk="taylor")
        if flow.monitor is None:
            return ta, None, npar
        # the recorder inside the integrator is the one that records (heyoka copied ours, and
        # one loaded from disk or a snapshot is a new object): look it up in the integrator
        recorder = _RECORDERS.get(id(ta))
        if recorder is None:
            recorder = _RECORDERS.setdefault(id(ta), ta.nt_events[0].callback)
        return ta, recorder, npar

    def propagate(self, flow: CompiledFlow, x0, t0, t_end, p, levels, *, budget: Budget, dense: bool = False,
                  resume: bool = False) -> Propagation:
        """Integrate ``flow`` from (t0, x0) to t_end or its first guard's zero.

        ``levels`` are the guards' levels (run-time parameters). ``resume=True`` continues
        from where the last call on this flow stopped, keeping heyoka's event cooldowns so
        that the event just located does not fire again.
        """
        hy = _heyoka()
        ta, recorder, npar = self.integrator(flow, len(p))
        if not resume:
            ta.time = float(t0)
            ta.state[:] = np.asarray(x0, dtype=float)
            ta.pars[:] = np.concatenate([np.asarray(p, dtype=float), np.asarray(levels, dtype=float)])[:npar]
            ta.reset_cooldowns()
        if recorder is not None:
            recorder.points = []
        prop = Propagation(t=float(ta.time), x=np.array(ta.state), outcome=End.TIME)
        while True:
            record = _TaylorSteps(float(ta.time)) if dense else None
            try:
                res = ta.propagate_until(float(t_end), max_steps=int(max(1, min(budget.steps - prop.n_steps, STEP_CHUNK))),
                                         write_tc=dense, callback=record)
            except Exception as exc:  # heyoka raises on e.g. a non-finite state in an event
                prop.outcome, prop.reason = End.FAILED, f"taylor: {exc}"
                break
            steps = int(res[3])
            prop.n_steps += steps
            if record is not None and steps > 0:
                record.finish(ta)
                prop.dense.append(record.span())
            end, event = taylor_end(hy, res[0])
            if end is None:  # the step chunk ran out
                if prop.n_steps >= budget.steps:
                    prop.outcome, prop.reason = End.FAILED, f"step limit ({prop.n_steps} steps) reached at t = {ta.time:.6g}"
                    break
                if budget.wall_exceeded():
                    prop.outcome, prop.reason = End.FAILED, f"wall-time limit reached at t = {ta.time:.6g}"
                    break
                if budget.tick is not None:
                    budget.tick(float(ta.time))
                continue
            prop.outcome, prop.event = end, event
            if end is End.FAILED:
                prop.reason = (f"non-finite state at t = {ta.time:.6g}" if res[0] == hy.taylor_outcome.err_nf_state
                               else f"taylor integrator stopped: {res[0]}")
            break
        prop.t, prop.x = float(ta.time), np.array(ta.state, copy=True)
        prop.n_rhs = prop.n_steps * (ta.order + 1)
        if recorder is not None:
            prop.monitored = list(recorder.points)
        return prop


class TaylorBatchEngine:
    """The Taylor integrator on heyoka's batch mode: ``lanes`` starts of one flow (different states,
    parameters and times) propagated at once, each to its time limit or its own first event.

    Built by the same code as :class:`TaylorEngine` (same expressions, tolerance, compact mode and
    event cooldown); segments it integrates record the name "taylor", as they are the same steps.

    Examples
    --------
    >>> import phasekit as pk
    >>> e = pk.core.engines.TaylorBatchEngine(1e-9, lanes=8)
    >>> e.name, e.pointwise, e.lanes
    ('taylor', False, 8)
    """

    name = "taylor"
    pointwise = False

    def __init__(self, rtol: float, lanes: int):
        self.rtol, self.lanes = float(rtol), int(lanes)

    def integrator(self, flow: CompiledFlow, n_params: int):
        """(heyoka batch integrator, number of parameters), compiled once."""
        return compiled(("batch", flow.signature, self.rtol, self.lanes),
                        partial(_build_taylor, flow, n_params, self.rtol, self.lanes), disk="taylor-batch")

    def propagate(self, ta, limits, max_steps: int) -> list[tuple[End | None, int | None, int, str]]:
        """One call of heyoka's propagate on every lane (to ``limits``, at most ``max_steps``
        steps): per lane (End or None while under way, event index, steps taken, heyoka's
        outcome in words). A terminal event in one lane stops the call for every lane; the
        others end their current step and are under way (heyoka's batch-mode documentation,
        and measured here)."""
        hy = _heyoka()
        ta.propagate_until(limits, max_steps=max_steps)
        out = []
        for k, res in enumerate(ta.propagate_res):
            end, event = taylor_end(hy, res[0])
            if end is None and float(ta.time[k]) >= limits[k]:
                end = End.TIME  # the call ended on the lane's last step
            out.append((end, event, int(res[3]), str(res[0])))
        return out


class HermiteDense:
    """Cubic Hermite interpolation on an integrator's output grid (for output only)."""

    def __init__(self, ts, xs, field, p):
        self.ts, self.xs = np.asarray(ts, float), np.asarray(xs, float)
        self.field, self.p = field, np.asarray(p, float)

    def __call__(self, tt) -> np.ndarray:
        tt = np.atleast_1d(np.asarray(tt, dtype=float))
        out = np.empty((tt.size, self.xs.shape[1]))
        for i, t in enumerate(tt):
            j = int(min(max(np.searchsorted(self.ts, t), 1), len(self.ts) - 1))
            t0, t1 = self.ts[j - 1], self.ts[j]
            if t == t1:
                out[i] = self.xs[j]
                continue
            h = t1 - t0
            s = (t - t0) / h
            f0 = np.asarray(self.field(self.xs[j - 1], self.p)).ravel()
            f1 = np.asarray(self.field(self.xs[j], self.p)).ravel()
            out[i] = ((2 * s**3 - 3 * s**2 + 1) * self.xs[j - 1] + (s**3 - 2 * s**2 + s) * h * f0
                      + (-2 * s**3 + 3 * s**2) * self.xs[j] + (s**3 - s**2) * h * f1)
        return out

    def pieces(self):
        """The same cubics in powers of t - t_j, one per grid interval: (starts, ends,
        coefficients (intervals, states, 4))."""
        F = np.array([np.asarray(self.field(x, self.p)).ravel() for x in self.xs])
        keep = np.diff(self.ts) > 0  # an event appended on a grid point makes an empty interval
        h = np.diff(self.ts)[keep][:, None]
        x0, x1, f0, f1 = self.xs[:-1][keep], self.xs[1:][keep], F[:-1][keep], F[1:][keep]
        slope = (x1 - x0) / h
        c2 = (3 * slope - 2 * f0 - f1) / h
        c3 = (f0 + f1 - 2 * slope) / h**2
        return self.ts[:-1][keep], self.ts[1:][keep], np.stack([x0, f0, c2, c3], axis=2)


class CvodesEngine:
    """CVODES (BDF or Adams) or IDAS through CasADi, with grid-bracketed, Brent-refined events.

    Examples
    --------
    >>> import phasekit as pk
    >>> [pk.core.engines.engine_for(n, 1e-9).name for n in ('cvodes', 'cvodes-adams', 'idas')]
    ['cvodes', 'cvodes-adams', 'idas']
    """

    name = "cvodes"
    pointwise = True
    #: output points per chunk (the chunk length adapts to the rotation rate). Measured: 100
    #: is 2x faster than 40 (fewer restarts of CVODES) and no slower than 200.
    n_grid = 100
    #: CVODES' own step limit per output interval. The run's budgets are checked between
    #: chunks, so a chunk may take up to n_grid * mxstep = 2e6 steps (~4 s for Adams on a stiff
    #: field) past them; 500 000 let one chunk run 14.5 million steps (32 s) past --max-wall 2.
    #: Non-stiff output intervals take tens to hundreds of steps.
    mxstep = 20_000

    def __init__(self, rtol: float, atol: float | None = None, method: str = "bdf", plugin: str = "cvodes"):
        self.rtol = float(rtol)
        self.atol = self.rtol * 1e-2 if atol is None else float(atol)
        self.method, self.plugin = method, plugin
        self.name = {("cvodes", "bdf"): "cvodes", ("cvodes", "adams"): "cvodes-adams"}.get((plugin, method), plugin)

    def _functions(self, flow: CompiledFlow, n_params: int):
        # CasADi builds these in milliseconds: kept in memory only
        key = ("cvodes", flow.signature, self.rtol, self.atol, self.method, self.plugin, self.n_grid)
        return compiled(key, partial(self._build, flow, n_params))

    def _build(self, flow: CompiledFlow, n_params: int):
        import casadi as ca

        x = ca.SX.sym("x", flow.n_states)
        p = ca.SX.sym("p", n_params)
        T = ca.SX.sym("T")
        dae = {"x": x, "p": ca.vertcat(p, T), "ode": T * flow.field(x, p)}
        # SUNDIALS would print its warnings (mxstep, ...) itself; the reason of a failed run carries them
        opts = {"reltol": self.rtol, "abstol": self.atol, "max_num_steps": self.mxstep, "disable_internal_warnings": True}
        if self.plugin == "cvodes":
            opts["linear_multistep_method"] = self.method
            if self.method == "adams":
                opts["nonlinear_solver_iteration"] = "functional"
        tag = flow.mode.value
        grid = [k / self.n_grid for k in range(1, self.n_grid + 1)]
        chunk = ca.integrator(f"{self.plugin}_chunk_{tag}", self.plugin, dae, 0.0, grid, opts)
        single = ca.integrator(f"{self.plugin}_single_{tag}", self.plugin, dae, 0.0, 1.0, opts)
        # every guard, every guard rate (zeros where none) and the monitor on a whole grid at once
        lv = ca.SX.sym("lv", len(flow.guards))
        outs = [g.function(x, p, lv[i]) for i, g in enumerate(flow.guards)]
        outs += [g.rate(x, p) if g.rate is not None else ca.SX(0) for g in flow.guards]
        outs += [flow.monitor.function(x, p, 0.0) if flow.monitor else ca.SX(0)]
        monitor = ca.Function("monitor", [x, p, lv], [ca.vertcat(*outs)]).map(self.n_grid + 1)
        return chunk, single, monitor

    def propagate(self, flow: CompiledFlow, x0, t0, t_end, p, levels, *, budget: Budget, dense: bool = False,
                  resume: bool = False) -> Propagation:
        """As :meth:`TaylorEngine.propagate`. A guard at zero at t0 does not fire, nor (after
        ``resume``) does the same guard within 1e-9 of t0. The monitor is recorded to grid
        accuracy."""
        p = np.asarray(p, dtype=float)
        levels = np.asarray(levels, dtype=float)
        chunk, single, monitor = self._functions(flow, len(p))
        ng, ne = self.n_grid, len(flow.guards)
        P = np.tile(p[:, None], (1, ng + 1))
        L = np.tile(levels[:, None], (1, ng + 1)) if ne else np.zeros((0, ng + 1))
        t, x = float(t0), np.asarray(x0, dtype=float).copy()
        prop = Propagation(t=t, x=x, outcome=End.TIME)
        grid_t, grid_x = [t], [x.copy()]
        cool = 1e-9 * max(1.0, abs(t0)) if resume else 0.0

        def run(xa, T):
            return np.asarray(single(x0=xa, p=np.concatenate([p, [T]]))["xf"]).ravel() if T > 0 else xa

        with _library_output_dropped():  # SUNDIALS' own error lines: the reason carries them
            while t < t_end and prop.outcome is End.TIME:
                # 20 grid points per period of the fastest rotation resolve the oscillation of R.
                dt = min(2 * np.pi / 20 / flow.rate_hint(x) * ng, t_end - t)
                try:
                    r = chunk(x0=x, p=np.concatenate([p, [dt]]))
                except RuntimeError as exc:
                    prop.outcome, prop.reason = End.FAILED, f"{self.plugin}: {sundials_message(exc)} (chunk from t = {t:.6g})"
                    break
                st = chunk.stats()
                prop.n_steps += int(st.get("nsteps", 0))
                prop.n_rhs += int(st.get("nfevals", 0))
                X = np.vstack([x[None, :], np.asarray(r["xf"]).T])  # (ng + 1, nx), row 0 = start
                tk = t + dt * np.arange(ng + 1) / ng
                if not np.all(np.isfinite(X)):
                    prop.outcome, prop.reason = End.FAILED, f"non-finite state near t = {t:.6g}"
                    break
                M = np.asarray(monitor(X.T, P, L)) if ne or flow.monitor else np.zeros((1, ng + 1))
                hit, last = self._first_event(flow, run, p, levels, X, tk, M, dt / ng, ne, cool, t0)
                if hit is not None:
                    t, x = hit[0], hit[1]
                    prop.outcome, prop.event = End.EVENT, hit[2]
                if flow.monitor is not None:
                    Ms = M[2 * ne]
                    for j in np.flatnonzero(np.sign(Ms[:-1]) * flow.monitor.direction < 0):
                        if j < last and np.sign(Ms[j + 1]) * flow.monitor.direction >= 0:
                            prop.monitored.append((float(tk[j + 1]), X[j + 1].copy()))
                keep = tk <= (t if hit is not None else tk[-1])
                grid_t.extend(tk[1:][keep[1:]])
                grid_x.extend(X[1:][keep[1:]])
                if hit is not None:
                    grid_t.append(t)
                    grid_x.append(x.copy())
                else:
                    t, x = float(tk[-1]), X[-1].copy()
                if prop.n_steps >= budget.steps:
                    prop.outcome, prop.reason = End.FAILED, f"step limit ({prop.n_steps} steps) reached at t = {t:.6g}"
                elif budget.wall_exceeded() and prop.outcome is End.TIME and t < t_end:
                    prop.outcome, prop.reason = End.FAILED, f"wall-time limit reached at t = {t:.6g}"
                elif budget.tick is not None:
                    budget.tick(t)
        prop.t, prop.x = t, x
        if dense and len(grid_t) > 1:
            prop.dense.append(_Span(HermiteDense(grid_t, grid_x, flow.field, p), grid_t[0], grid_t[-1]))
        return prop

    def _first_event(self, flow, run, p, levels, X, tk, M, h, ne, cool, t0):
        """The earliest confirmed guard zero on this grid chunk: ((t, x, index), last grid index)."""
        ng = self.n_grid
        cand = np.zeros((ne, ng), dtype=bool)
        dips = np.zeros((ne, ng), dtype=bool)
        G, Gd = M[:ne], M[ne:2 * ne]
        for i, g in enumerate(flow.guards):
            a, b = G[i, :-1], G[i, 1:]
            down, up = (a > 0) & (b <= 0), (a < 0) & (b >= 0)
            cross = down if g.direction < 0 else up if g.direction > 0 else down | up
            if g.rate is not None and g.direction <= 0:
                dips[i] = ~cross & (a > 0) & (b > 0) & _hermite_dips(h, a, b, Gd[i, :-1], Gd[i, 1:])
            cand[i] = cross | dips[i]
        for j in np.flatnonzero(cand.any(axis=0)):
            found = None
            for i in np.flatnonzero(cand[:, j]):
                g = flow.guards[i]
                hit = _refine(run, lambda xx, g=g, lv=levels[i]: float(g.function(xx, p, lv)),
                              (lambda xx, g=g: float(g.rate(xx, p))) if g.rate is not None else None,
                              X[j], tk[j + 1] - tk[j], bool(dips[i, j]))
                if hit is not None and tk[j] + hit[0] - t0 <= cool:
                    hit = None  # the event just handled, found again at the restart
                if hit is not None and (found is None or hit[0] < found[0]):
                    found = (hit[0], hit[1], int(i))
            if found is not None:
                return (tk[j] + found[0], found[1], found[2]), j
        return None, ng


@contextlib.contextmanager
def _library_output_dropped():
    """SUNDIALS reports some errors itself ("At t = 0, too much accuracy requested.") through
    CasADi's output streams, which go to Python's sys.stderr/stdout: drop them while CVODES or
    IDAS runs (the reason of a failed run carries the message, see :func:`sundials_message`)."""
    sink = io.StringIO()
    with contextlib.redirect_stderr(sink), contextlib.redirect_stdout(sink):
        yield


def sundials_message(exc) -> str:
    """The informative part of a SUNDIALS error raised through CasADi (without C++ file paths),
    e.g. 'CVode returned "CV_TOO_MUCH_WORK"' (the step limit was reached)."""
    lines = [re.sub(r"^.*\.cpp:\d+:\s*", "", ln).strip() for ln in str(exc).splitlines()]
    lines = [ln for ln in lines if ln and not ln.startswith("Error in Function::call")]
    for key in ("TOO_MUCH_WORK", "CV_", "IDA_", "mxstep", "convergence", "error test"):
        for ln in lines:
            if key in ln:
                msg = ln.replace(" Consult CVODES documentation.", "").replace(" Consult IDAS documentation.", "")
                if "TOO_MUCH_WORK" in msg:
                    msg += " (step limit reached: the field is too stiff or the tolerance too tight for the step budget)"
                return msg[:240]
    return (lines[-1] if lines else "unknown failure")[:240]


def _refine(run, g, rate, xa, T, dip):
    """Locate a guard zero in (0, T] from state xa; None if a suspected dip does not cross."""
    from scipy.optimize import brentq

    def gt(tau):
        return g(run(xa, tau))

    hi = T
    if dip:
        # First find the bottom of the dip (dg/dt = 0); the guard must be <= 0 there.
        def rd(tau):
            return rate(run(xa, tau))

        if not rd(0.0) < 0.0 < rd(T):
            return None
        hi = brentq(rd, 0.0, T, xtol=1e-13)
        if gt(hi) > 0:
            return None
    g0, g1 = gt(0.0), gt(hi)
    if g0 == 0.0 or np.sign(g0) == np.sign(g1):  # re-integration did not confirm the crossing
        return None
    tau = brentq(gt, 0.0, hi, xtol=1e-13, maxiter=200)
    return tau, run(xa, tau)


_S = np.linspace(0.0, 1.0, 33)[:, None]
_H00, _H10, _H01, _H11 = 2 * _S**3 - 3 * _S**2 + 1, _S**3 - 2 * _S**2 + _S, -2 * _S**3 + 3 * _S**2, _S**3 - _S**2


def _hermite_dips(h, g0, g1, d0, d1) -> np.ndarray:
    """For each interval, does the cubic Hermite interpolant (values g0, g1, slopes d0, d1,
    interval length h) dip below zero inside? Vectorised over intervals."""
    v = _H00 * g0 + _H10 * (h * d0) + _H01 * g1 + _H11 * (h * d1)
    return v.min(axis=0) < 0


#: the engines ``SolverOptions.backend`` may name ("auto" besides): name -> factory(rtol, atol)
ENGINES: dict[str, Callable[..., Engine]] = {
    "taylor": TaylorEngine,
    "cvodes": CvodesEngine,
    "cvodes-adams": partial(CvodesEngine, method="adams"),
    "idas": partial(CvodesEngine, plugin="idas"),
}


def engine_names() -> tuple[str, ...]:
    """What ``SolverOptions.backend`` accepts: "auto" and every registered engine.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.engine_names()
    ('auto', 'taylor', 'cvodes', 'cvodes-adams', 'idas')
    """
    return ("auto", *ENGINES)


def register_engine(name: str, factory: Callable[..., Engine]) -> None:
    """Make an integrator available as ``SolverOptions(backend=name)``: ``factory(rtol, atol)``
    returns an :class:`Engine`. Nothing else needs editing: simulate asks the engine whether it
    is pointwise, and the options accept every registered name.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.register_engine('cvodes-loose', lambda rtol, atol=None: pk.core.engines.CvodesEngine(rtol, 1e-6))
    >>> pk.SolverOptions(backend='cvodes-loose').backend
    'cvodes-loose'
    >>> del pk.core.engines.ENGINES['cvodes-loose']
    """
    if not isinstance(name, str) or not name or name == "auto" or name in ENGINES:
        raise ParameterError("name", "must be a new engine name (not 'auto' or one of "
                                     f"{', '.join(ENGINES)})", name)
    ENGINES[name] = factory


def engine_for(name: str, rtol: float, atol: float | None = None) -> Engine:
    """The engine called ``name`` (see :data:`ENGINES`) at these tolerances; an unknown name is an
    error naming the choices.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.engine_for('taylor', 1e-9).name
    'taylor'
    >>> pk.core.engines.engine_for('rk4', 1e-9)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    phasekit._runtime.errors.ParameterError: `backend` must be one of taylor, cvodes, cvodes-adams, idas, got 'rk4'.
    """
    if name not in ENGINES:
        raise ParameterError("backend", f"must be one of {', '.join(ENGINES)}", name)
    return ENGINES[name](rtol, atol)
