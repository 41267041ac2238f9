"""Solver options: every integration default, written once.

Derive variants with :func:`dataclasses.replace`, e.g. ``replace(opts, rtol=1e-12)``, or
pass the fields as keywords to :func:`phasekit.simulate`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from .._runtime.validate import check_bool, check_choice, check_int, check_positive, check_range
from .engines.registry import engine_names
from .resets import BOUNCE_STOP, BOUNCE_TAIL
from .settle import Settle, check_settle

#: tolerances a double-precision integrator can honour: below 1e-16 the Taylor order grows
#: without bound (heyoka picks it from the tolerance) and CVODES cannot meet the error test.
RTOL_RANGE = (1e-16, 0.1)
#: the default mode-switch budget: this many per unit of the requested span, at least
#: MIN_SWITCHES. Measured: a hopping spheroid (a = 1.5, Omega0 = 30, e = 0.5) makes ~27 switches
#: per time unit while it hops; a fixed 10 000 ended it "failed" at t = 185 of 400.
SWITCHES_PER_TIME = 100
MIN_SWITCHES = 10_000


@dataclass(frozen=True, kw_only=True)
class SolverOptions:
    """Integration settings.

    Attributes
    ----------
    rtol : float, default 1e-9
        Relative tolerance, in [1e-16, 0.1]. For the Taylor method it is heyoka's single
        mixed absolute/relative tolerance; for CVODES/IDAS the relative one.
    atol : float or None, default None
        Absolute tolerance of CVODES/IDAS; None means ``rtol / 100``. The Taylor method has
        one mixed tolerance and does not use it.
    backend : {"auto", "taylor", "cvodes", "cvodes-adams", "idas"} or a registered engine, default "auto"
        The engine (:data:`phasekit.core.engines.registry.ENGINES`: heyoka's Taylor method; CVODES (BDF or
        Adams) and IDAS through CasADi; any added by :func:`phasekit.core.engines.register_engine`).
        "auto" is the Taylor method, handing over to CVODES BDF only while a regularised
        Coulomb law holds the slip below ~10 eps with mu/eps > 2000 (the stiff regime).
        Free flight always uses the Taylor method (its t^3 gap needs polynomial root finding).
    max_steps : int, default 5_000_000
        Step budget of the whole run; exceeding it ends the run with status "failed". What a
        step is depends on the integrator: a Taylor step (heyoka), or an internal step of
        CVODES/IDAS (the budget is checked between their chunks of 100 output points, so they
        may pass it by up to one chunk; the reason gives the count).
    max_wall : float, default 600
        Wall-clock budget of the whole run in seconds; exceeding it ends the run "failed".
    max_switches : int or None, default None
        Budget of recorded mode switches (stick, slip, lift-off, touchdown, impact); reaching
        it ends the run "failed" with the count and the time. None: 100 per unit of the
        requested span, at least 10 000.
    bounce_stop : float, default 1e-4
        A rebound slower than this (units sqrt(g b)) ends a bounce train: contact resumes.
    bounce_tail : int or None, default 100
        A bounce train whose flight times shrink geometrically with more than this many
        rebounds left before ``bounce_stop`` is resolved at once (its accumulation point is
        reached: contact resumes; :func:`phasekit.core.resets.bounce_tail`); None integrates every
        rebound down to ``bounce_stop``.
    settle : Settle, True or None, default None
        End a run that has settled (zero slip, steady state: :class:`phasekit.core.Settle`) with
        status "settled"; True is ``Settle()``.
    track_minima : bool, default True
        Locate every local minimum of R. (The maximum of each flight's gap is always located.)
    dense : bool, default True
        Keep the integrator's dense output (heyoka's Taylor polynomials) so that
        :meth:`Trajectory.sample` can evaluate any instant without re-integration. Costs
        ~2.5x the integration time of a bare run; sweeps turn it off.
    max_dense_mb : float or None, default 1000
        Memory cap of the dense output in MB (measured ~0.75 MB per thousand Taylor steps:
        ~1.3 million steps fit). A run that passes it goes on and keeps what was asked of it
        (the samples at ``t_eval``, events, minima, the energy budget, tallied as it goes, ~16
        bytes a step, and the summary) but drops its dense output: sample, pose, energy_series
        and animate then say so (:mod:`phasekit.core.dense_cap`). None: no cap.
    creep : bool, default True
        Let a stiff regularised law (mu/eps > 500) creep on its slow manifold while its slip is
        below 10 eps (an asymptotic reduction, listed in ``Trajectory.approximations``;
        docs/physics.md); False integrates the law's own field there (CVODES where mu/eps > 2000).

    Raises
    ------
    ParameterError
        If a field is outside its range: ``rtol`` outside [1e-16, 0.1], ``atol`` or
        ``max_wall`` not a finite number > 0, ``backend`` not a registered engine,
        ``max_steps``, ``max_switches`` or ``bounce_tail`` not an integer >= 1,
        ``bounce_stop`` outside (0, 1], ``max_dense_mb`` not None or a finite number > 0, ``settle`` not None, a bool, a Settle or its dict, or
        ``track_minima``, ``dense`` or ``creep`` not a bool.

    Examples
    --------
    >>> import phasekit as pk
    >>> from dataclasses import replace
    >>> opts = pk.SolverOptions(rtol=1e-10)
    >>> replace(opts, backend='cvodes').backend, opts.switch_limit(200.0)
    ('cvodes', 20000)
    """

    rtol: float = 1e-9
    atol: float | None = None
    backend: str = "auto"
    max_steps: int = 5_000_000
    max_wall: float = 600.0
    max_switches: int | None = None
    bounce_stop: float = BOUNCE_STOP
    bounce_tail: int | None = BOUNCE_TAIL
    settle: Settle | None = None
    track_minima: bool = True
    dense: bool = True
    max_dense_mb: float | None = 1000.0
    creep: bool = True

    def __post_init__(self):
        lo, hi = RTOL_RANGE
        object.__setattr__(self, "rtol", check_range("rtol", self.rtol, lo, hi, closed="lr", label=f"[{lo:g}, {hi:g}]"))
        if self.atol is not None:
            object.__setattr__(self, "atol", check_positive("atol", self.atol))
        check_choice("backend", self.backend, engine_names())
        object.__setattr__(self, "max_steps", check_int("max_steps", self.max_steps, minimum=1))
        object.__setattr__(self, "max_wall", check_positive("max_wall", self.max_wall))
        if self.max_switches is not None:
            object.__setattr__(self, "max_switches", check_int("max_switches", self.max_switches, minimum=1))
        object.__setattr__(self, "bounce_stop", check_range("bounce_stop", self.bounce_stop, 0.0, 1.0, closed="r"))
        if self.bounce_tail is not None:
            object.__setattr__(self, "bounce_tail", check_int("bounce_tail", self.bounce_tail, minimum=1))
        object.__setattr__(self, "settle", check_settle(self.settle))
        object.__setattr__(self, "track_minima", check_bool("track_minima", self.track_minima))
        object.__setattr__(self, "dense", check_bool("dense", self.dense))
        object.__setattr__(self, "creep", check_bool("creep", self.creep))
        if self.max_dense_mb is not None:
            object.__setattr__(self, "max_dense_mb", check_positive("max_dense_mb", self.max_dense_mb))

    @classmethod
    def names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))

    def switch_limit(self, span: float) -> int:
        """The mode-switch budget of a run over ``span`` time units.

        Parameters
        ----------
        span : float
            The requested span of the run, t_end - t0 (units sqrt(b/g)).

        Returns
        -------
        int
            ``max_switches`` if set, else 100 per time unit of ``span``, at least 10 000.
        """
        if self.max_switches is not None:
            return self.max_switches
        return int(max(MIN_SWITCHES, min(SWITCHES_PER_TIME * span, 1e15)))

    def to_dict(self) -> dict:
        d = {name: getattr(self, name) for name in self.names()}
        d["settle"] = None if self.settle is None else self.settle.to_dict()
        return d
