"""Engines: integrators that propagate one smooth flow until a time or its first located event.

Every engine follows one protocol (:class:`Engine`): a ``name`` (what a segment records), whether
it is ``pointwise`` (it sees the guards only at output points, so the stick guard is watched in
its smooth squared form with a rate) and ``propagate(flow, x0, t0, t_end, p, levels, *, budget,
dense, resume) -> Propagation``. :data:`phasekit.core.engines.registry.ENGINES` maps the names that ``SolverOptions.backend``
accepts to them; :func:`register_engine` adds one (nothing else needs editing). The compiled
integrators of every engine come from one build path and one cache
(:func:`~phasekit.core.engines.cache.compiled`: in memory, and on disk for heyoka's, whose LLVM
compilation costs seconds to minutes).

``taylor`` (default)
    heyoka's adaptive Taylor method on the CasADi model translated to heyoka
    expressions (:mod:`phasekit.core.engines.translate`), LLVM-compiled once per (flow, guards,
    tolerance) and cached in memory and on disk. Events are located by polynomial root
    finding on each step's Taylor expansion, i.e. to about machine precision in time.
    Dense output is the steps' Taylor polynomials. The minima of R come from the expansion of
    one more state, the integral of R, whose steps are the run's own
    (:mod:`~phasekit.core.engines.roots`).
``cvodes`` / ``cvodes-adams`` / ``idas``
    SUNDIALS through CasADi. CasADi's event support is experimental, so events are
    bracketed on an output grid fine enough to resolve the fast oscillation (20 points per
    period of the fastest rotation) and refined by Brent's method on re-integrations from
    the last grid point. This is the backend for stiff fields (a regularised Coulomb law
    once the slip is below ~eps). Dense output is cubic Hermite on that grid.

``taylor-batch`` (:class:`TaylorBatchEngine`, used by :func:`phasekit.core.simulate_batch`)
    the same Taylor integrator on heyoka's SIMD batch mode: ``lanes`` starts at once, each
    propagated to a time or its own first event. Built from the same expressions, with the same
    compact mode and event cooldown, so a lane takes the steps a scalar run takes.

Each takes a :class:`phasekit.core.hybrid.CompiledFlow` and returns a :class:`Propagation` (a batch:
one per lane). Work is bounded by a step budget and a wall-clock deadline; running out of
either, or a non-finite state, ends with :attr:`End.FAILED` and the reason, never an exception.

The modules: :mod:`~phasekit.core.engines.protocol` (the protocol and what a call returns),
:mod:`~phasekit.core.engines.cache` (the compiled integrators, in memory and on disk),
:mod:`~phasekit.core.engines.taylor_build` (heyoka's integrators of a flow),
:mod:`~phasekit.core.engines.dense` (dense output), :mod:`~phasekit.core.engines.roots` (zeros of
the steps' polynomials), :mod:`~phasekit.core.engines.taylor`,
:mod:`~phasekit.core.engines.batch` and :mod:`~phasekit.core.engines.cvodes` (the engines) and
:mod:`~phasekit.core.engines.registry` (the engines by name).
"""

from .protocol import Budget, End, Engine, Propagation
from .registry import engine_for, register_engine

__all__ = ["Engine", "End", "Propagation", "Budget", "engine_for", "register_engine"]
