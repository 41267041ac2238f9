"""SUNDIALS through CasADi (:class:`CvodesEngine`: ``cvodes``, ``cvodes-adams``, ``idas``). CasADi's
event support is experimental, so events are bracketed on an output grid fine enough to resolve the
fast oscillation (20 points per period of the fastest rotation) and refined by Brent's method on
re-integrations from the last grid point. Dense output is cubic Hermite on that grid.
"""

from __future__ import annotations

import contextlib
import io
import re
from functools import partial

import numpy as np

from ..hybrid import CompiledFlow
from .cache import compiled
from .dense import HermiteDense, Span
from .protocol import Budget, End, Propagation


class CvodesEngine:
    """CVODES (BDF or Adams) or IDAS through CasADi, with grid-bracketed, Brent-refined events.

    Parameters
    ----------
    rtol : float
        Relative tolerance.
    atol : float, optional
        Absolute tolerance; by default ``rtol * 1e-2``.
    method : {"bdf", "adams"}, optional
        CVODES' linear multistep method.
    plugin : {"cvodes", "idas"}, optional
        The SUNDIALS solver.

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
    #: CVODES' own step limit per output interval. The wall budget is checked between chunks,
    #: so a chunk may take up to n_grid * mxstep = 2e6 steps (~4 s for Adams on a stiff field)
    #: past it; 500 000 let one chunk run 14.5 million steps (32 s) past --max-wall 2.
    #: Non-stiff output intervals take tens to hundreds of steps.
    mxstep = 20_000
    #: chunks tried, each shorter, once the next one would pass the run's step budget (a refused
    #: chunk is not counted: the run's steps are those of the chunks it kept, so it ends within
    #: its budget, having computed at most this many chunks more)
    budget_tries = 3

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
        """As :meth:`~phasekit.core.engines.taylor.TaylorEngine.propagate`. A guard at zero at t0 does not fire, nor (after
        ``resume``) does the same guard within 1e-9 of t0. The monitor is recorded to grid
        accuracy.

        Parameters
        ----------
        flow, x0, t0, t_end, p, levels, budget, dense, resume
            As for :meth:`~phasekit.core.engines.taylor.TaylorEngine.propagate` (dense output is cubic Hermite on the grid).

        Returns
        -------
        Propagation
            As for :meth:`~phasekit.core.engines.taylor.TaylorEngine.propagate`.
        """
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

        shrink, refused = 1.0, 0  # a chunk that would pass the step budget is not taken: shorter ones are tried
        with _library_output_dropped():  # SUNDIALS' own error lines: the reason carries them
            while t < t_end and prop.outcome is End.TIME:
                # 20 grid points per period of the fastest rotation resolve the oscillation of R.
                dt = min(2 * np.pi / 20 / flow.rate_hint(x) * ng * shrink, t_end - t)
                try:
                    r = chunk(x0=x, p=np.concatenate([p, [dt]]))
                except RuntimeError as exc:
                    prop.outcome, prop.reason = End.FAILED, f"{self.plugin}: {sundials_message(exc)} (chunk from t = {t:.6g})"
                    break
                st = chunk.stats()
                steps, left = int(st.get("nsteps", 0)), budget.steps - prop.n_steps
                if steps > left:  # the run ends within its budget, at the last chunk that fitted
                    refused += 1
                    if refused > self.budget_tries or left <= 0 or budget.wall_exceeded():
                        prop.outcome, prop.reason = End.FAILED, (
                            f"step limit ({prop.n_steps} steps) reached at t = {t:.6g} (the next stretch of "
                            f"{self.plugin} needed {steps} steps, more than the {left} left)")
                        break
                    shrink *= 0.5 * left / steps
                    continue
                prop.n_steps += steps
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
                    _record_monitor(flow.monitor.direction, M[2 * ne], tk, X, last, prop)
                t, x = self._keep_grid(grid_t, grid_x, tk, X, hit, t, x)
                _check_budgets(prop, budget, t, t_end)
        prop.t, prop.x = t, x
        if dense and len(grid_t) > 1:
            span = Span(HermiteDense(grid_t, grid_x, flow.field, p), grid_t[0], grid_t[-1])
            if budget.keep is None or budget.keep(span):
                prop.dense.append(span)
        return prop

    @staticmethod
    def _keep_grid(grid_t, grid_x, tk, X, hit, t, x):
        """Append the chunk's grid points up to its event (all of them without one) to the dense
        output's grid; returns (t, x) at the chunk's end: the event's, or the chunk's last point."""
        keep = tk <= (t if hit is not None else tk[-1])
        grid_t.extend(tk[1:][keep[1:]])
        grid_x.extend(X[1:][keep[1:]])
        if hit is not None:
            grid_t.append(t)
            grid_x.append(x.copy())
            return t, x
        return float(tk[-1]), X[-1].copy()

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


def _record_monitor(direction, Ms, tk, X, last, prop) -> None:
    """Where the flow's monitor (values ``Ms`` on the chunk's grid) crossed zero in its direction
    before grid index ``last``: recorded in ``prop.monitored`` to grid accuracy."""
    for j in np.flatnonzero(np.sign(Ms[:-1]) * direction < 0):
        if j < last and np.sign(Ms[j + 1]) * direction >= 0:
            prop.monitored.append((float(tk[j + 1]), X[j + 1].copy()))


def _check_budgets(prop, budget, t, t_end) -> None:
    """After a chunk kept: a propagation still under way at ``t`` whose steps or wall time are
    spent fails there (an end or event reached is kept); else the progress bar is told."""
    going = prop.outcome is End.TIME and t < t_end
    if going and prop.n_steps >= budget.steps:
        prop.outcome, prop.reason = End.FAILED, f"step limit ({prop.n_steps} steps) reached at t = {t:.6g}"
    elif going and budget.wall_exceeded():
        prop.outcome, prop.reason = End.FAILED, f"wall-time limit reached at t = {t:.6g}"
    elif budget.tick is not None:
        budget.tick(t)


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
