"""Integrator backends: integrate one smooth mode until a time or the first located event.

``taylor`` (default)
    heyoka's adaptive Taylor method on the CasADi model translated to heyoka
    expressions (:mod:`phasekit._translate`), LLVM-compiled once per (model, mode,
    tolerance) and cached in memory and on disk. Events are located by polynomial root
    finding on each step's Taylor expansion, i.e. to about machine precision in time.
``cvodes``
    SUNDIALS CVODES (BDF, or Adams) through CasADi. CasADi's event support is
    experimental, so events are bracketed on an output grid fine enough to resolve the
    fast oscillation (20 points per period of the fastest rotation) and refined by
    Brent's method on re-integrations from the last grid point. This is the backend for
    stiff fields, i.e. the regularised Coulomb law once the slip is below ~eps.

Both return a :class:`Propagation`. Work is bounded by ``max_steps``; running out of
steps or a non-finite state gives outcome "failed" with the reason, never an exception.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import threading
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .model import Model
from .modes import Mode

__all__ = ["EventSpec", "Propagation", "TaylorBackend", "CvodesBackend", "get_backend", "BACKENDS"]


@dataclass(frozen=True)
class EventSpec:
    """A guard function g(x) (a model output) whose zero in ``direction`` ends a segment."""

    name: str
    function: str
    direction: int = -1  # -1: g goes from + to -; +1: from - to +; 0: either
    rate: str | None = None  # dg/dt, lets pointwise backends find dips between grid points


@dataclass
class Propagation:
    """What one call of a backend produced."""

    t: float
    x: np.ndarray
    outcome: str  # "time", "event" or "failed"
    event: str | None = None
    reason: str | None = None
    n_steps: int = 0
    n_rhs: int = 0
    minima: list = field(default_factory=list)  # [(t, x)] at local minima of R
    ts: np.ndarray | None = None
    ys: np.ndarray | None = None


#: bump when the layout of the pickled cache entries changes
CACHE_FORMAT = 2


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


class _MinimaRecorder:
    """Non-terminal event callback storing (t, x) at each local minimum of R.

    heyoka deep-copies callbacks; returning self from __deepcopy__ keeps one shared list.
    """

    def __init__(self):
        self.points: list = []

    def __deepcopy__(self, memo):
        return self

    def __call__(self, ta, t, d_sgn):
        ta.update_d_output(t)
        self.points.append((float(t), np.array(ta.d_output, copy=True)))


class TaylorBackend:
    """heyoka Taylor integrator; ``rtol`` is heyoka's (mixed absolute/relative) tolerance."""

    name = "taylor"
    _lock = threading.Lock()
    _memory: dict = {}

    def __init__(self, model: Model, rtol: float):
        self.model = model
        self.rtol = float(rtol)

    def _integrator(self, mode: Mode, events: tuple[EventSpec, ...], minima):
        m = self.model
        key = (m.compiled.key, mode, self.rtol, events, minima)
        with self._lock:
            entry = self._memory.get(key)
        if entry is None:
            entry = self._load_or_build(mode, events, minima, key)
            with self._lock:
                self._memory[key] = entry
        return entry

    def _load_or_build(self, mode, events, minima, key):
        import heyoka as hy

        m = self.model
        digest = hashlib.sha256(
            repr((CACHE_FORMAT, m.compiled.signature, mode.value, self.rtol, events, minima, hy.__version__)).encode()
        ).hexdigest()[:24]
        cache = _cache_dir()
        path = cache / f"taylor-{digest}.pkl" if cache else None
        if path is not None and path.exists():
            try:
                with open(path, "rb") as fh:
                    ta, npar = pickle.load(fh)
                # the recorder is pickled inside the integrator: take that one
                return ta, (ta.nt_events[0].callback if minima else None), npar
            except Exception:  # a stale or partial file: rebuild it
                pass
        from ._translate import to_heyoka

        xs = hy.make_vars(*[f"x{i}" for i in range(m.n_states)])
        ps = [hy.par[i] for i in range(len(m.p))]
        ins = [list(xs), ps]
        rhs = to_heyoka(m.function(f"rhs_{mode.value}"), ins)[0]
        direction = {-1: hy.event_direction.negative, 1: hy.event_direction.positive, 0: hy.event_direction.any}
        t_events = [
            hy.t_event(to_heyoka(m.function(ev.function), ins)[0][0], direction=direction[ev.direction]) for ev in events
        ]
        nt_events, recorder = [], None
        if minima:  # (function, direction): record where it crosses zero, e.g. dR/dt = 0 upward
            fname, fdir = minima
            recorder = _MinimaRecorder()
            rate = to_heyoka(m.function(fname), ins)[0][0]
            nt_events = [hy.nt_event(rate, callback=recorder, direction=direction[fdir])]
        used = hy.get_params(list(rhs) + [e.expression for e in t_events] + [e.expression for e in nt_events])
        npar = 1 + max((int(str(q)[1:]) for q in used), default=-1)
        ta = hy.taylor_adaptive(
            list(zip(xs, rhs)),
            [0.0] * m.n_states,
            pars=[0.0] * npar,
            tol=self.rtol,
            t_events=t_events,
            nt_events=nt_events,
        )
        if nt_events:  # the recorder inside the integrator is the one we keep
            recorder = ta.nt_events[0].callback
        if path is not None:
            try:
                tmp = path.with_suffix(f".{os.getpid()}.tmp")
                with open(tmp, "wb") as fh:
                    pickle.dump((ta, npar), fh)
                os.replace(tmp, path)
            except Exception:
                pass
        return ta, recorder, npar

    def propagate(self, mode, x0, t0, t_end, events, p, *, max_steps, t_eval=None, minima=None, resume=False) -> Propagation:
        """Integrate ``mode`` from (t0, x0) to t_end or the first event of ``events``.

        ``minima`` = (function, direction): also record (t, x) wherever that function crosses
        zero in that direction (e.g. ("Rdot_sliding", +1): the minima of R).
        ``resume=True`` continues from where the last call stopped (same mode and events),
        keeping heyoka's event cooldowns so that the event just located does not fire again.
        """
        minima = tuple(minima) if minima else None
        ta, recorder, npar = self._integrator(mode, tuple(events), minima)
        if not resume:
            ta.time = float(t0)
            ta.state[:] = np.asarray(x0, dtype=float)
            ta.pars[:] = np.asarray(p, dtype=float)[:npar]
            if events or minima:
                ta.reset_cooldowns()
        if recorder is not None:
            recorder.points = []
        want_dense = t_eval is not None and len(t_eval) > 0
        try:
            res = ta.propagate_until(float(t_end), max_steps=int(max(max_steps, 1)), c_output=want_dense)
        except Exception as exc:  # heyoka raises on e.g. a non-finite state in an event
            return Propagation(t=float(ta.time), x=np.array(ta.state), outcome="failed", reason=f"taylor: {exc}")
        outcome, n_steps, c_out = res[0], int(res[3]), res[4]
        x = np.array(ta.state, copy=True)
        prop = Propagation(t=float(ta.time), x=x, outcome="time", n_steps=n_steps, n_rhs=n_steps * (ta.order + 1))
        if recorder is not None:
            prop.minima = list(recorder.points)
        code = int(outcome.value)
        if outcome == _outcome("time_limit"):
            prop.outcome = "time"
        elif code < 0 and code > -(2**31):  # terminal event i triggered: outcome -(i+1)
            prop.outcome, prop.event = "event", events[-code - 1].name
        elif outcome == _outcome("step_limit"):
            prop.outcome, prop.reason = "failed", f"step limit ({max_steps} steps) reached at t = {ta.time:.6g}"
        elif outcome == _outcome("err_nf_state"):
            prop.outcome, prop.reason = "failed", f"non-finite state at t = {ta.time:.6g}"
        else:
            prop.outcome, prop.reason = "failed", f"taylor integrator stopped: {outcome}"
        if want_dense and c_out is not None:
            te = np.asarray(t_eval, dtype=float)
            te = te[(te >= t0) & (te <= prop.t)]
            if te.size:
                ys = np.asarray(c_out(te))
                prop.ts, prop.ys = te, ys.reshape(te.size, -1)
        return prop


def _outcome(name):
    import heyoka as hy

    return getattr(hy.taylor_outcome, name)


class CvodesBackend:
    """CVODES through CasADi with grid-bracketed, Brent-refined events."""

    name = "cvodes"
    _lock = threading.Lock()
    _memory: dict = {}
    #: output points per chunk (the chunk length adapts to the rotation rate). Measured: 100
    #: is 2x faster than 40 (fewer restarts of CVODES) and no slower than 200.
    n_grid = 100

    def __init__(self, model: Model, rtol: float, method: str = "bdf", plugin: str = "cvodes"):
        self.model = model
        self.rtol = float(rtol)
        self.method = method
        self.plugin = plugin  # "cvodes", or "idas" (SUNDIALS' DAE solver on the same ODE)

    def _functions(self, mode, max_steps: int):
        import casadi as ca

        m = self.model
        key = (m.compiled.key, mode, self.rtol, self.method, self.plugin, int(max_steps), self.n_grid)
        with self._lock:
            if key in self._memory:
                return self._memory[key]
        x = ca.SX.sym("x", m.n_states)
        p = ca.SX.sym("p", len(m.p))
        T = ca.SX.sym("T")
        rhs = m.function(f"rhs_{mode.value}")(x, p)
        dae = {"x": x, "p": ca.vertcat(p, T), "ode": T * rhs}
        opts = {"reltol": self.rtol, "abstol": self.rtol * 1e-2, "max_num_steps": int(max_steps)}
        if self.plugin == "cvodes":
            opts["linear_multistep_method"] = self.method
            if self.method == "adams":
                opts["nonlinear_solver_iteration"] = "functional"
        grid = [k / self.n_grid for k in range(1, self.n_grid + 1)]
        chunk = ca.integrator(f"{self.plugin}_chunk_{mode.value}", self.plugin, dae, 0.0, grid, opts)
        single = ca.integrator(f"{self.plugin}_single_{mode.value}", self.plugin, dae, 0.0, 1.0, opts)
        out = (chunk, single)
        with self._lock:
            self._memory[key] = out
        return out

    def _rate(self, x) -> float:
        """Fastest rotation rate, which sets the period of the fast oscillation of R."""
        m = self.model
        if m.chart == "euler":
            return float(max(1.0, abs(x[2]), abs(x[5]), abs(x[3])))
        return float(max(1.0, np.linalg.norm(x[3:6])))

    def _monitor(self, mode, events):
        """One CasADi function giving, on a whole output grid at once, every guard, every
        guard rate (zeros where none), R and dR/dt: one call per chunk instead of many."""
        import casadi as ca

        key = (self.model.compiled.key, mode, events, self.n_grid)
        with self._lock:
            if key in self._memory:
                return self._memory[key]
        m = self.model
        x = ca.SX.sym("x", m.n_states)
        p = ca.SX.sym("p", len(m.p))
        outs = [m.function(ev.function)(x, p) for ev in events]
        outs += [m.function(ev.rate)(x, p) if ev.rate else ca.SX(0) for ev in events]
        outs += [m.function(f"R_{mode.value}")(x, p), m.function(f"Rdot_{mode.value}")(x, p)]
        f = ca.Function("monitor", [x, p], [ca.vertcat(*outs)]).map(self.n_grid + 1)
        with self._lock:
            self._memory[key] = f
        return f

    def propagate(self, mode, x0, t0, t_end, events, p, *, max_steps, t_eval=None, minima=None, resume=False) -> Propagation:
        """As :meth:`TaylorBackend.propagate`; a guard exactly at zero at t0 does not fire.
        Only the minima of R can be recorded (``minima`` = (f"Rdot_{mode}", +1)), to grid accuracy."""
        m = self.model
        events = tuple(events)
        chunk, single = self._functions(mode, max_steps)
        monitor = self._monitor(mode, events)
        p = np.asarray(p, dtype=float)
        ng, ne = self.n_grid, len(events)
        P = np.tile(p[:, None], (1, ng + 1))
        t, x = float(t0), np.asarray(x0, dtype=float).copy()
        prop = Propagation(t=t, x=x, outcome="time")
        te = None if t_eval is None else np.asarray(t_eval, dtype=float)
        ts_out, ys_out = [], []
        guard_fn = [m.function(ev.function) for ev in events]
        rate_fn = [m.function(ev.rate) if ev.rate else None for ev in events]

        def run(xa, T):
            return np.asarray(single(x0=xa, p=np.concatenate([p, [T]]))["xf"]).ravel() if T > 0 else xa

        while t < t_end and prop.outcome == "time":
            # 20 grid points per period of the fastest rotation resolve the oscillation of R.
            dt = min(2 * np.pi / 20 / self._rate(x) * ng, t_end - t)
            try:
                r = chunk(x0=x, p=np.concatenate([p, [dt]]))
            except RuntimeError as exc:
                prop.outcome, prop.reason = "failed", f"{self.plugin}: {_sundials_message(exc)} (chunk from t = {t:.6g})"
                break
            st = chunk.stats()
            prop.n_steps += int(st.get("nsteps", 0))
            prop.n_rhs += int(st.get("nfevals", 0))
            X = np.vstack([x[None, :], np.asarray(r["xf"]).T])  # (ng + 1, nx), row 0 = start
            tk = t + dt * np.arange(ng + 1) / ng
            if not np.all(np.isfinite(X)):
                prop.outcome, prop.reason = "failed", f"non-finite state near t = {t:.6g}"
                break
            M = np.asarray(monitor(X.T, P))  # (2 ne + 2, ng + 1)
            G, Gd, Rs, Rds = M[:ne], M[ne:2 * ne], M[2 * ne], M[2 * ne + 1]
            # candidate intervals, vectorised: sign changes, or a Hermite dip below zero
            cand = np.zeros((ne, ng), dtype=bool)
            dips = np.zeros((ne, ng), dtype=bool)
            for i, ev in enumerate(events):
                a, b = G[i, :-1], G[i, 1:]
                down = (a > 0) & (b <= 0)
                up = (a < 0) & (b >= 0)
                cross = down if ev.direction < 0 else up if ev.direction > 0 else down | up
                if ev.rate and ev.direction <= 0:
                    dips[i] = ~cross & (a > 0) & (b > 0) & _hermite_dips(dt / ng, a, b, Gd[i, :-1], Gd[i, 1:])
                cand[i] = cross | dips[i]
            last = ng
            for j in np.flatnonzero(cand.any(axis=0)):
                found = None
                for i in np.flatnonzero(cand[:, j]):
                    hit = _refine(run, guard_fn[i], rate_fn[i], p, X[j], tk[j + 1] - tk[j], bool(dips[i, j]))
                    if hit is not None and (found is None or hit[0] < found[0]):
                        found = (hit[0], hit[1], events[i].name)
                if found is not None:
                    last = j
                    t, x = tk[j] + found[0], found[1]
                    prop.outcome, prop.event = "event", found[2]
                    break
            if minima:
                for j in np.flatnonzero((Rds[:-1] < 0) & (Rds[1:] >= 0))[: max(last, 0)]:
                    k = j + 1 if Rs[j + 1] < Rs[j] else j  # bottom of a dip, to grid accuracy
                    prop.minima.append((float(tk[k]), X[k].copy()))
            if te is not None:
                hi = t if prop.outcome == "event" else tk[-1]
                for tt in te[(te > tk[0]) & (te <= hi)]:
                    j = int(min(max(np.searchsorted(tk, tt), 1), ng))
                    ts_out.append(tt)
                    ys_out.append(_hermite_state(tk, X, j, tt, m, mode))
            if prop.outcome == "time":
                t, x = float(tk[-1]), X[-1].copy()
            if prop.n_steps >= max_steps:
                prop.outcome, prop.reason = "failed", f"step limit ({max_steps} steps) reached at t = {t:.6g}"
        prop.t, prop.x = t, x
        if te is not None and t0 in te:
            ts_out.insert(0, t0)
            ys_out.insert(0, np.asarray(x0, float))
        if ts_out:
            prop.ts, prop.ys = np.array(ts_out), np.array(ys_out)
        return prop


def _sundials_message(exc) -> str:
    """The informative part of a SUNDIALS error raised through CasADi (without C++ file paths),
    e.g. 'CVode returned "CV_TOO_MUCH_WORK"' (the step limit was reached)."""
    import re

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


def _refine(run, gf, rate, p, xa, T, dip):
    """Locate a guard zero in (0, T] from state xa; None if a suspected dip does not cross."""
    from scipy.optimize import brentq

    def g(tau):
        return float(gf(run(xa, tau), p))

    hi = T
    if dip:
        # First find the bottom of the dip (dg/dt = 0); the guard must be <= 0 there.
        def rd(tau):
            return float(rate(run(xa, tau), p))

        if not rd(0.0) < 0.0 < rd(T):
            return None
        hi = brentq(rd, 0.0, T, xtol=1e-13)
        if g(hi) > 0:
            return None
    g0, g1 = g(0.0), g(hi)
    if g0 == 0.0 or np.sign(g0) == np.sign(g1):  # re-integration did not confirm the crossing
        return None
    tau = brentq(g, 0.0, hi, xtol=1e-13, maxiter=200)
    return tau, run(xa, tau)


_S = np.linspace(0.0, 1.0, 33)[:, None]
_H00, _H10, _H01, _H11 = 2 * _S**3 - 3 * _S**2 + 1, _S**3 - 2 * _S**2 + _S, -2 * _S**3 + 3 * _S**2, _S**3 - _S**2


def _hermite_dips(h, g0, g1, d0, d1) -> np.ndarray:
    """For each interval, does the cubic Hermite interpolant (values g0, g1, slopes d0, d1,
    interval length h) dip below zero inside? Vectorised over intervals."""
    v = _H00 * g0 + _H10 * (h * d0) + _H01 * g1 + _H11 * (h * d1)
    return v.min(axis=0) < 0


def _hermite_state(seg_t, seg_x, j, tt, m, mode):
    """Cubic Hermite interpolation of the state between grid points (for output only)."""
    j = max(1, j)
    t0, t1 = seg_t[j - 1], seg_t[j]
    if tt == t1:
        return seg_x[j]
    h = t1 - t0
    s = (tt - t0) / h
    f0, f1 = m.rhs(seg_x[j - 1], mode), m.rhs(seg_x[j], mode)
    return (
        (2 * s**3 - 3 * s**2 + 1) * seg_x[j - 1]
        + (s**3 - 2 * s**2 + s) * h * f0
        + (-2 * s**3 + 3 * s**2) * seg_x[j]
        + (s**3 - s**2) * h * f1
    )


BACKENDS = {"taylor": TaylorBackend, "cvodes": CvodesBackend}


def get_backend(name: str, model: Model, rtol: float):
    if name == "cvodes-adams":
        return CvodesBackend(model, rtol, method="adams")
    if name == "idas":
        return CvodesBackend(model, rtol, plugin="idas")
    return BACKENDS[name](model, rtol)
