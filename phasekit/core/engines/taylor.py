"""The default engine (:class:`TaylorEngine`): heyoka's adaptive Taylor method, LLVM-compiled once per
(flow, guards, tolerance) and cached (:mod:`phasekit.core.engines.cache`). Events are located by
polynomial root finding on each step's Taylor expansion, i.e. to about machine precision in time;
dense output is the steps' Taylor polynomials (:mod:`phasekit.core.engines.dense`).
"""

from __future__ import annotations

from functools import partial

import numpy as np

from ..hybrid import CompiledFlow
from .cache import RECORDERS, compiled, prefetch
from .dense import TaylorSteps
from .protocol import Budget, End, Propagation
from .scaling import initial_scales, next_rescale, next_scales
from .taylor_build import build_taylor, load_heyoka, scales_at, taylor_end, taylor_pars

#: steps per call of heyoka's propagate: between calls the wall clock is checked
STEP_CHUNK = 20_000
#: a propagation's recorded steps are turned into dense output and the monitor's zeros once they
#: are this many (or at its end): short runs pay that once (it costs ~0.2 ms a time), long ones as
#: they go, inside their wall budget
RECORD_STEPS = 20_000


class TaylorEngine:
    """heyoka Taylor integrator.

    Parameters
    ----------
    rtol : float
        heyoka's (mixed absolute/relative) tolerance.
    atol : float, optional
        Not used (accepted as every engine factory takes it).

    Examples
    --------
    >>> import phasekit as pk
    >>> e = pk.core.engines.taylor.TaylorEngine(1e-9)
    >>> e.name, e.pointwise, e.rtol
    ('taylor', False, 1e-09)
    """

    name = "taylor"
    pointwise = False

    def __init__(self, rtol: float, atol: float | None = None):
        self.rtol = float(rtol)

    def integrator(self, flow: CompiledFlow, n_params: int):
        """(heyoka integrator, monitor recorder or None, number of parameters), compiled once.

        Parameters
        ----------
        flow : CompiledFlow
            The flow integrated.
        n_params : int
            The number of model parameters.

        Returns
        -------
        tuple
            (integrator, recorder or None, number of parameters).
        """
        ta, npar = compiled((flow.signature, self.rtol), partial(build_taylor, flow, n_params, self.rtol, None),
                            disk="taylor", label=f"the Taylor integrator of the {flow.mode.value} mode")
        if flow.monitor is None or flow.monitor_primitive is not None:
            return ta, None, npar
        # the recorder inside the integrator is the one that records (heyoka copied ours, and
        # one loaded from disk or a snapshot is a new object): look it up in the integrator
        recorder = RECORDERS.get(id(ta))
        if recorder is None:
            recorder = RECORDERS.setdefault(id(ta), ta.nt_events[0].callback)
        return ta, recorder, npar

    def prefetch(self, flow: CompiledFlow, n_params: int) -> None:
        """Start compiling :meth:`integrator` of ``flow`` in the background (see
        :func:`phasekit.core.engines.cache.prefetch`)."""
        prefetch((flow.signature, self.rtol), partial(build_taylor, flow, n_params, self.rtol, None), disk="taylor",
                 label=f"the Taylor integrator of the {flow.mode.value} mode, in the background,")

    def propagate(self, flow: CompiledFlow, x0, t0, t_end, p, levels, *, budget: Budget, dense: bool = False,
                  resume: bool = False) -> Propagation:
        """Integrate ``flow`` from (t0, x0) to t_end or its first guard's zero.

        Parameters
        ----------
        flow : CompiledFlow
            The field, guards and monitor of one mode.
        x0 : array_like
            The start state (ignored with ``resume=True``).
        t0, t_end : float
            The start and end times.
        p : array_like
            The model's parameters.
        levels : array_like
            The guards' levels (run-time parameters).
        budget : Budget
            Steps and wall time left: running out ends the call with ``End.FAILED`` and a reason.
        dense : bool, optional
            Keep the steps' Taylor polynomials as dense output.
        resume : bool, optional
            True continues from where the last call on this flow stopped, keeping heyoka's event cooldowns so
            that the event just located does not fire again.

        Returns
        -------
        Propagation
            The time and state reached, how the call ended, steps, monitor crossings and dense output.
        """
        hy = load_heyoka()
        ta, recorder, npar = self.integrator(flow, len(p))
        n, first = flow.n_states, scales_at(flow, len(p))
        if not resume:
            _start(ta, n, t0, x0, taylor_pars(p, levels, initial_scales(x0)))
        scale = np.array(ta.pars[first:first + n])
        views = ta.state[:n], ta.pars[first:first + n]  # heyoka's buffers, for the renewals
        if recorder is not None:
            recorder.points = []
        prop = Propagation(t=float(ta.time), x=ta.state[:n] * scale, outcome=End.TIME)
        zeros = flow.monitor is not None and flow.monitor_primitive is not None  # the monitor's zeros from z's expansion
        tc = ta.tc if dense or zeros else None
        t_end = float(t_end)
        extra = np.ones(len(ta.state) - n)  # z (the monitor's integral) is not scaled
        record = TaylorSteps(float(ta.time), tc, np.concatenate([scale, extra])) if tc is not None else None
        while True:
            stop = min(t_end, next_rescale(float(ta.time)))  # the scales are renewed on a grid of times
            try:
                res = ta.propagate_until(stop, max_steps=int(max(1, min(budget.steps - prop.n_steps, STEP_CHUNK))),
                                         write_tc=tc is not None, callback=record.callback if record else None)
            except Exception as exc:  # heyoka raises on e.g. a non-finite state in an event
                prop.outcome, prop.reason = End.FAILED, f"taylor: {exc}"
                break
            prop.n_steps += int(res[3])
            if record is not None and int(res[3]) > 0:
                record.finish(ta)  # the last, truncated step, in the scales it was taken in
                if len(record.coefs) >= RECORD_STEPS:  # kept as it goes: the wall budget sees the cost
                    _keep(record, prop, flow, dense, zeros, budget.keep)
                    record = TaylorSteps(float(ta.time), tc, np.concatenate([scale, extra]))
            end, event = (End.TIME, None) if res[0] == hy.taylor_outcome.time_limit else taylor_end(hy, res[0])
            if end is End.TIME and stop < t_end:  # a grid time: renew the scales
                scale = _rescale(*views, scale)
                if record is not None:
                    record.rescale(np.concatenate([scale, extra]))
                end = None
            if end is None:  # under way: the step chunk ran out, or a grid time
                if _out_of_budget(prop, budget, float(ta.time)):
                    break
                continue
            prop.outcome, prop.event = end, event
            if end is End.FAILED:
                prop.reason = (f"non-finite state at t = {ta.time:.6g}" if res[0] == hy.taylor_outcome.err_nf_state
                               else f"taylor integrator stopped: {res[0]}")
            break
        if record is not None:
            _keep(record, prop, flow, dense, zeros, budget.keep)
        prop.t, prop.x = float(ta.time), ta.state[:n] * scale
        prop.n_rhs = prop.n_steps * (ta.order + 1)
        if recorder is not None:
            prop.monitored = list(recorder.points)
        return prop


def _start(ta, n: int, t0: float, x0, pars) -> None:
    """Set the integrator at (t0, x0), its parameters (the scales last) and its cooldowns."""
    ta.time = float(t0)
    ta.pars[:] = pars
    ta.state[:n] = np.asarray(x0, dtype=float) / pars[len(pars) - n:]
    ta.state[n:] = 0.0  # z, the integral of the monitor's primitive (its expansion is what counts)
    ta.reset_cooldowns()


def _rescale(state, scales, scale) -> np.ndarray:
    """New scales at a grid time (:func:`.scaling.next_scales`), the state rescaled to them;
    ``state`` and ``scales`` are views on the integrator's state and on its scale parameters."""
    x = state * scale
    new = next_scales(x, scale)
    scales[:] = new
    np.divide(x, new, out=state)
    return new


def _keep(record, prop: Propagation, flow: CompiledFlow, dense: bool, zeros: bool, keep=None) -> None:
    """What a propagation's recorded steps give: the monitor's zeros and the dense output (unless
    ``keep``, the run's memory cap, :class:`.protocol.Budget`, declines it)."""
    if not record.coefs:
        return
    if zeros:
        prop.monitored += record.zeros(flow.n_states, flow.monitor.direction)
    if dense:
        span = record.span(flow.n_states)
        if keep is None or keep(span):
            prop.dense.append(span)


def _out_of_budget(prop: Propagation, budget: Budget, t: float) -> bool:
    """Between calls: end ``prop`` as failed when its steps or wall time ran out, else tick the bar."""
    if prop.n_steps >= budget.steps:
        prop.outcome, prop.reason = End.FAILED, f"step limit ({prop.n_steps} steps) reached at t = {t:.6g}"
        return True
    if budget.wall_exceeded():
        prop.outcome, prop.reason = End.FAILED, f"wall-time limit reached at t = {t:.6g}"
        return True
    if budget.tick is not None:
        budget.tick(t)
    return False
