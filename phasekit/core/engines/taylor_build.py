"""heyoka's Taylor integrators of a flow: the field, guards and monitor translated from CasADi
(:mod:`phasekit.core.engines.translate`), every guard a terminal event with a fixed cooldown, compact
mode for big flows, scalar or batch (:func:`build_taylor`); and heyoka's outcome of a propagate
call read as an :class:`~phasekit.core.engines.End` (:func:`taylor_end`).
"""

from __future__ import annotations

import numpy as np

from ..hybrid import CompiledFlow
from .protocol import End

#: cooldown of every guard after it fires (a run resumed after a non-terminal event or a
#: graze must not find the same root again). heyoka deduces one from the guard's rate at the
#: root, which blows up at a tangential crossing: measured 8.6e8 for a section Lambda = 0 at a
#: start with dLambda/dt = 1e-16, which silenced the event for the rest of the run.
EVENT_COOLDOWN = 1e-9
#: flows whose field and guards exceed this many CasADi instructions are compiled in heyoka's
#: compact mode (loops instead of unrolled code). Measured on an egg (Chebyshev support function
#: of degree 64, ~8000 instructions with its events): unrolled, the sliding and rolling
#: integrators took 16 min and 1.7 GB to compile; compact, the sliding one 7 s. Every spheroid
#: and tippe-top flow is below 2300 instructions and stays unrolled (fastest steps, numbers unchanged).
COMPACT_ABOVE = 3000
#: LLVM's optimisation level for compact-mode flows (heyoka's default is 3). Measured on the
#: egg (a = 1.33333, Coulomb, 2 cores, quiet): one integrator compiles in 4.5 s at level 1
#: against 9-10 s at 3, its steps run as fast (0.81 against 1.46 s for 6561 steps), and the
#: trajectories are bitwise identical; level 0 compiles in 0.4 s but its steps are 1.6x slower
#: and its results differ in the last digits. Unrolled flows keep level 3 (their compile time is
#: code generation, the same at levels 1-3).
COMPACT_OPT_LEVEL = 1
#: z' = PRIMITIVE_SCALE P(x) for a monitor with a primitive P (:mod:`phasekit.core.engines.roots`).
#: heyoka chooses a step from the Taylor coefficients of every state, so an unscaled z would
#: shorten the steps (measured: an event on dR/dt did, 515 steps against 413 on the benchmarks'
#: standard workload); scaled by 2^-40 (exact in binary) it leaves them, and the run, as they are
#: without it (the same t* to the last bit, tests/core/test_minima_of_R.py).
PRIMITIVE_SCALE = 2.0**-40


class _MonitorRecorder:
    """Non-terminal event callback storing (t, x) at each crossing of the monitor, x in the
    flow's own variables (the integrator's scaled state times its scales, :mod:`.scaling`).

    heyoka deep-copies callbacks; returning self from __deepcopy__ keeps one shared list.
    """

    def __init__(self, scales_at: int = 0, n: int = 0):
        self.points: list = []
        self.scales_at, self.n = scales_at, n

    def __deepcopy__(self, memo):
        return self

    def __call__(self, ta, t, d_sgn):
        ta.update_d_output(t)
        x = np.array(ta.d_output, copy=True)
        x[:self.n] *= ta.pars[self.scales_at:self.scales_at + self.n]
        self.points.append((float(t), x))


def load_heyoka():
    import heyoka as hy

    # heyoka logs through spdlog to stdout; results go to stdout, so keep it quiet
    hy.set_logger_level_critical()
    return hy


def scales_at(flow: CompiledFlow, n_params: int) -> int:
    """The index of the first state's scale in the parameters of ``flow``'s Taylor integrators:
    after the model's ``n_params`` parameters and the guards' levels."""
    return n_params + len(flow.guards)


def taylor_pars(p, levels, scales) -> np.ndarray:
    """The parameters of a Taylor integrator: the model's, the guards' levels, the states' scales."""
    return np.concatenate([np.asarray(p, dtype=float), np.asarray(levels, dtype=float), np.asarray(scales, dtype=float)])


def build_taylor(flow: CompiledFlow, n_params: int, rtol: float, lanes: int | None):
    """heyoka's integrator of ``flow`` (``lanes`` None: scalar; else a batch of that many lanes)
    in the scaled variables xs = x / S of :mod:`.scaling` (S: the last ``flow.n_states``
    parameters, see :func:`scales_at`): the field and guards translated from CasADi, every guard a
    terminal event with the cooldown EVENT_COOLDOWN, the monitor a non-terminal one (scalar only)
    or, when it has a primitive P, one more (unscaled) state z' = PRIMITIVE_SCALE P, compact mode
    for big flows. Returns (integrator, number of parameters it reads)."""
    from .translate import to_heyoka

    hy = load_heyoka()
    batch = lanes is not None
    n = flow.n_states
    xs = hy.make_vars(*[f"x{i}" for i in range(n)])
    ps = [hy.par[i] for i in range(n_params)]
    first = scales_at(flow, n_params)
    S = [hy.par[first + i] for i in range(n)]
    x = [s * v for s, v in zip(S, xs)]  # the flow's own variables
    rhs = [f / s for f, s in zip(to_heyoka(flow.field, [x, ps])[0], S)]
    direction = {-1: hy.event_direction.negative, 1: hy.event_direction.positive, 0: hy.event_direction.any}
    t_event = hy.t_event_batch if batch else hy.t_event
    t_events = [t_event(to_heyoka(g.function, [x, ps, [hy.par[n_params + i]]])[0][0], direction=direction[g.direction],
                        cooldown=EVENT_COOLDOWN) for i, g in enumerate(flow.guards)]
    nt_events = []
    if flow.monitor is not None and batch:
        raise ValueError("a batch integrator records no monitor: compile its flow without one")
    system = list(zip(xs, rhs))
    if flow.monitor is not None and flow.monitor_primitive is not None:  # one more state: z' = s P
        system.append((hy.make_vars("z"), PRIMITIVE_SCALE * to_heyoka(flow.monitor_primitive, [x, ps])[0][0]))
    elif flow.monitor is not None:
        m = flow.monitor
        nt_events = [hy.nt_event(to_heyoka(m.function, [x, ps, [hy.expression(0.0)]])[0][0],
                                 callback=_MonitorRecorder(first, n), direction=direction[m.direction])]
    npar = first + n  # every scale is read
    size = flow.field.n_instructions() + sum(g.function.n_instructions() for g in flow.guards)
    if flow.monitor is not None:
        size += (flow.monitor.function if flow.monitor_primitive is None else flow.monitor_primitive).n_instructions()
    compact = size > COMPACT_ABOVE
    level = {"compact_mode": compact, "opt_level": COMPACT_OPT_LEVEL if compact else 3}
    if batch:
        ta = hy.taylor_adaptive_batch(system, np.zeros((flow.n_states, lanes)), pars=np.zeros((npar, lanes)),
                                      tol=rtol, t_events=t_events, **level)
    else:
        ta = hy.taylor_adaptive(system, [0.0] * len(system), pars=[0.0] * npar, tol=rtol,
                                t_events=t_events, nt_events=nt_events, **level)
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
