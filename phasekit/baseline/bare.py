"""The bare heyoka integrator phasekit drives for one mode (:func:`taylor_integrator`): what a user
who wants heyoka without phasekit's loop starts from, and the benchmarks' "heyoka without
phasekit" reference."""

from __future__ import annotations

import copy

import numpy as np

from .._runtime.validate import check_vector
from ..core.engines.scaling import initial_scales
from ..core.engines.taylor import TaylorEngine
from ..core.engines.taylor_build import taylor_pars
from ..core.hybrid import Mode
from ..core.model import Model
from ..core.simulate import solver_options, tracked
from ..core.system import declare, watched


def taylor_integrator(model: Model, *, mode=Mode.SLIDING, stop_at: str = "jump", rtol: float = 1e-9, events=(),
                      track_minima: bool = True, x0=None):
    """A copy of the compiled heyoka integrator phasekit uses for one mode, for users (and
    benchmarks) who want to drive heyoka directly: returns (integrator, parameters). It is the
    caller's own: simulate's runs do not touch it (they shared one object before, and a simulate
    between two propagations left its parameters set for another segment). Its terminal events
    are the mode's guards (lift-off first, ...) with the levels of ``events`` appended, and its
    last parameters are the scales of the states: the integrator's state is the model's divided by
    them, which makes heyoka's one tolerance an error test per component
    (:mod:`phasekit.core.engines.scaling`). With ``x0`` they are the scales simulate starts a
    segment at ``x0`` with, and the state is set to ``x0`` scaled; without it they are 1 (the state is
    the model's, the error test heyoka's own). Set ``integrator.pars[:] = parameters`` (done here)
    and ``integrator.state``/``.time``; read the model's state as ``state * parameters[-n:]``.

    Parameters
    ----------
    model : Model
        The model whose flow is compiled.
    mode : Mode or str
        The mode ("sliding", "rolling" or "flight") whose flow the integrator follows.
    stop_at : str
        The stop rule, as for :func:`phasekit.simulate` ("jump", "touchdown", "none", ...).
    rtol : float
        Relative tolerance of the Taylor method, in (0, 1).
    events : sequence of Event
        User events whose levels are appended to the mode's guards.
    track_minima : bool
        True gives the integrator of simulate's default, with one more state, last: z' = 2^-40 R,
        from whose expansion the minima of R are found (:mod:`phasekit.core.engines.roots`);
        False the integrator simulate uses with ``track_minima=False``.
    x0 : array_like, optional
        A start state in the model's chart: sets the scales and the (scaled) state.

    Returns
    -------
    tuple
        (heyoka.taylor_adaptive, numpy.ndarray): the integrator with its parameters set, and those
        parameters (the model's, the event levels, the states' scales).

    Examples
    --------
    >>> import phasekit as pk
    >>> ta, pars = pk.baseline.taylor_integrator(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    >>> type(ta).__name__, len(pars)
    ('taylor_adaptive_dbl', 13)
    """
    mode = Mode(mode)
    system = declare(model, stop_at=stop_at, events=events)
    evs = watched(system, mode, TaylorEngine)
    cflow = model.compile_flow(tracked(system.flow(mode), track_minima), evs)
    ta, _, npar = TaylorEngine(solver_options(rtol=rtol).rtol).integrator(cflow, len(model.p))
    ta = copy.deepcopy(ta)
    scale = np.ones(cflow.n_states) if x0 is None else initial_scales(check_vector("x0", x0, cflow.n_states))
    pars = taylor_pars(model.p, [e.level for e in evs], scale)
    ta.pars[:] = pars
    if x0 is not None:
        ta.time = 0.0
        ta.state[:] = 0.0
        ta.state[:cflow.n_states] = np.asarray(x0, dtype=float) / scale
    return ta, pars
