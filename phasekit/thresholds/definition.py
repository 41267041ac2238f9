"""What counts as a jump: a threshold :class:`Definition`, the :class:`Outcome` of one trajectory and
:func:`evaluate_outcomes` (many at once, scalar or on the batch integrator).

A jump threshold is the smallest Omega0 (prolate) or n0 (oblate) whose trajectory loses contact;
the search for it is in :mod:`phasekit.thresholds.search`.

A *definition* fixes everything but the body and the family parameter: the friction law,
how the trajectory is seeded near the fixed point, the tolerances and the completion
criterion. Figure 6b,c of the paper reads "seed on the unstable manifold of the horizontal
(prolate) or vertical (oblate) state with delta = 0.01, integrate with Coulomb friction,
record whether R reaches 0". Read literally that depends on numerics (the seed has almost
no slip and exact Coulomb friction sticks; see docs/physics.md), so three definitions are
provided:

``viscous``
    (i) viscous friction, seeded along the viscous unstable eigenvector (delta). Well posed.
``sliding``
    (ii) exact Coulomb friction, seeded on the sliding (gyroscopic-balance) branch at a
    distance d from the fixed point: theta0 = pi/2 - d (prolate, n from the balance) or
    theta0 = d (oblate, Omega on the fast branch). Converges as eps -> 0; the default.
``literal``
    (iii) the paper's recipe: the viscous unstable eigenvector (delta), integrated with
    Coulomb friction, regularised with ``eps`` or exact (eps = None).

Outcome of one trajectory
-------------------------
"jump" means R reaches 0 with dR/dt < 0 before the rise completes. The rise is complete
when theta comes within ``rise_margin`` (0.1 rad) of the final state (theta -> 0 for a
prolate body, pi/2 for an oblate one): a stop event; a run that reaches ``t_max`` first
(typically a body that stuck and rolls) also counts as no jump and is flagged, and so does one
that has settled (``settle``, :class:`phasekit.core.Settle`: rolling in a steady state; an egg that
settles tilted would otherwise stick and slip until ``t_max``). Jumps happen
at theta* ~ 0.5-1.4 (prolate); near the end of the rise some bodies alternate stick and slip
for thousands of cycles (measured: a = 2, Omega0 = 7.19), which the 0.1 margin cuts short.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np

from .._runtime.validate import check_choice, check_int, check_positive, check_range
from ..bodies.body import Body
from ..bodies.spheroid import Spheroid
from ..core.hybrid import Event
from ..core.model import Model
from ..core.options import RTOL_RANGE
from ..core.settle import Settle, check_settle
from ..core.simulate import simulate
from ..core.starts import gyroscopic_start, to_chart, to_paper
from ..errors import ParameterError, Status
from ..friction.dissipation import check_dissipation
from ..friction.laws import Coulomb, RegularisedCoulomb, Viscous
from ..steady.manifolds import unstable_manifold_start
from ..theory.criteria import horizontal_stability_threshold, vertical_stability_threshold
from .outcome import Outcome

#: the settle rule of every built-in definition (see :mod:`phasekit.core.settle`)
DEFAULT_SETTLE = Settle()


def as_body(body) -> Body:
    """A Body, or an aspect ratio standing for the uniform Spheroid(a)."""
    if isinstance(body, Body):
        return body
    if isinstance(body, (int, float, np.integer, np.floating)) and not isinstance(body, bool):
        return Spheroid(float(body))
    raise ParameterError("body", "must be a phasekit Body or an aspect ratio a", body)


@dataclass(frozen=True)
class Definition:
    """How a jump threshold is measured (everything except the body and the family parameter).

    Parameters
    ----------
    name : str
        A name for the definition (left out of :meth:`key`).
    seed : {"viscous", "sliding", "literal"}
        The seed and law (module notes): viscous eigenvector, sliding branch, or the paper's recipe.
    mu : float, optional
        Friction coefficient, in (0, 10].
    amplitude : float, optional
        delta (eigenvector seeds) or d (sliding-branch seeds), in (0, 0.5].
    eps : float or None, optional
        Regularisation of Coulomb friction, in [1e-14, 1]; None: exact stick-slip. Unused by "viscous".
    rtol : float, optional
        Relative tolerance of the integrator, in [1e-16, 0.1].
    rise_margin : float, optional
        The rise is complete when theta is within this of the final state, radians, in (0, pi/2).
    t_max : float, optional
        Length of a run, > 0; a run that reaches it counts as no jump.
    max_steps : int, optional
        Step budget of a run, >= 1.
    settle : Settle, dict, bool or None, optional
        The settle rule: a run that has settled ends as no jump. None or False: no rule; True: ``Settle()``.
    dissipation : tuple of Dissipation, optional
        Laws acting besides sliding friction (:class:`phasekit.RollingResistance`,
        :class:`phasekit.SpinFriction`, :class:`phasekit.AirDrag`), default none: the runs
        simulate ``friction().with_dissipation(*dissipation)`` (seeds as without them); a run
        in which the body comes to rest counts as no jump.
    chart : {None, "euler", "vector"}, optional
        The coordinates the runs are integrated in (:mod:`phasekit.core.charts`): None, the
        start's choice (:func:`phasekit.core.choose_chart`: the paper's variables, the vector chart
        within 1e-5 of a pole); "euler", the paper's variables always; "vector", regular at
        theta = 0, which a prolate body rising to the vertical needs near a = 1
        (docs/results/maps.md). The seeds are the same.

    Raises
    ------
    ParameterError
        If a field is out of its range.

    Examples
    --------
    >>> import phasekit as pk
    >>> d = pk.Definition('sliding', 'sliding')
    >>> d.label
    'coulomb mu=0.1 exact; seed: sliding branch d=0.01'
    >>> round(d.lower_bound(1.5), 6)
    2.347871
    """

    name: str
    seed: str  # "viscous", "sliding" or "literal"
    mu: float = 0.1
    amplitude: float = 0.01  # delta (eigenvector seeds) or d (sliding-branch seeds)
    eps: float | None = None  # regularisation of Coulomb friction (None: exact stick-slip)
    rtol: float = 1e-9
    rise_margin: float = 0.1
    t_max: float = 3000.0
    max_steps: int = 20_000_000
    #: a run that has settled (zero slip, steady state; exact Coulomb only) ends as no jump:
    #: a body that settles tilted (an egg) would otherwise stick and slip until t_max
    settle: Settle | None = DEFAULT_SETTLE
    dissipation: tuple = ()
    chart: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "settle", check_settle(self.settle))
        object.__setattr__(self, "dissipation", check_dissipation(self.dissipation))
        check_choice("seed", self.seed, ("viscous", "sliding", "literal"))
        check_range("amplitude", self.amplitude, 0.0, 0.5, closed="r")
        check_range("mu", self.mu, 0.0, 10.0, closed="r")
        if self.eps is not None:
            check_range("eps", self.eps, 1e-14, 1.0, closed="lr")
        check_range("rtol", self.rtol, *RTOL_RANGE, closed="lr")
        check_range("rise_margin", self.rise_margin, 0.0, math.pi / 2)
        check_positive("t_max", self.t_max)
        check_int("max_steps", self.max_steps, minimum=1)
        if self.chart is not None:
            check_choice("chart", self.chart, ("euler", "vector"))

    @property
    def law_label(self) -> str:
        extra = "".join(f" + {d.describe()}" for d in self.dissipation)
        if self.seed == "viscous":
            return f"viscous mu={self.mu:g}{extra}"
        return f"coulomb mu={self.mu:g}" + (f" eps={self.eps:g}" if self.eps else " exact") + extra

    @property
    def label(self) -> str:
        what = {"viscous": f"eigenvector delta={self.amplitude:g}", "sliding": f"sliding branch d={self.amplitude:g}",
                "literal": f"viscous eigenvector delta={self.amplitude:g}"}[self.seed]
        return f"{self.law_label}; seed: {what}" + (f"; {self.chart} chart" if self.chart else "")

    def key(self) -> str:
        """Identifies results that can be reused: every field that changes the answer. The
        default settle rule is left out: it ends only runs that would not jump (checked on the
        published studies), so results computed before it existed keep their keys; so are an
        empty ``dissipation`` and the default chart."""
        d = asdict(self)
        d.pop("name")
        if self.settle == DEFAULT_SETTLE:
            d.pop("settle")
        d["dissipation"] = [x.describe() for x in self.dissipation]
        if not self.dissipation:
            d.pop("dissipation")
        if self.chart is None:
            d.pop("chart")
        return ";".join(f"{k}={v}" for k, v in sorted(d.items()))

    def tighter(self, factor: float = 10.0) -> "Definition":
        """This definition at its tolerance divided by ``factor`` (not below the smallest accepted),
        written short (1e-10, not 1.0000000000000001e-10): what a threshold's check runs
        (:mod:`phasekit.thresholds.verify`).

        Parameters
        ----------
        factor : float, optional
            How much tighter, > 1 (default 10).

        Returns
        -------
        Definition
            The same definition at the tighter tolerance.

        Examples
        --------
        >>> import phasekit as pk
        >>> pk.Definition('sliding', 'sliding').tighter().rtol
        1e-10
        """
        factor = check_range("factor", factor, 1.0, 1e16, closed="r")
        return replace(self, rtol=max(float(f"{self.rtol / factor:.12g}"), RTOL_RANGE[0]))

    def friction(self):
        if self.seed == "viscous":
            law = Viscous(self.mu)
        else:
            law = Coulomb(self.mu) if self.eps is None else RegularisedCoulomb(self.mu, self.eps)
        return law.with_dissipation(*self.dissipation) if self.dissipation else law

    def lower_bound(self, body) -> float:
        """Where the seed exists: the fixed point must be unstable (eigenvector seeds) and the
        gyroscopic balance solvable; thresholds are searched above this.

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).

        Returns
        -------
        float
            1.05 times the closed-form stability threshold of a flip-symmetric spheroid, else 1.05.

        Raises
        ------
        ParameterError
            If ``body`` is neither a Body nor a number.
        """
        body = as_body(body)
        if isinstance(body, Spheroid) and body.flip_symmetric:
            fn = horizontal_stability_threshold if body.is_prolate else vertical_stability_threshold
            crit = fn(body.A, body.C, body.a) or 1.0
        else:  # no closed form: start the search at 1 (units sqrt(g/b))
            crit = 1.0
        return 1.05 * crit

    def start(self, body, value: float):
        """(model, x0) for ``body`` (or aspect ratio) and Omega0 (prolate) or n0 (oblate).

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).
        value : float
            Omega0 (prolate body) or n0 (oblate body).

        Returns
        -------
        tuple of (Model, numpy.ndarray)
            The model to simulate and the initial state in its chart.

        Raises
        ------
        ParameterError
            If ``body`` is invalid or the seed does not exist at ``value``.
        ConvergenceError
            If Newton does not converge at the fixed point (eigenvector seeds).
        """
        body = as_body(body)
        law = self.friction()
        prolate = body.is_prolate
        if self.seed == "sliding":
            if prolate:
                y0 = gyroscopic_start(body, math.pi / 2 - self.amplitude, omega0=value)
            else:
                y0 = gyroscopic_start(body, self.amplitude, n0=value)
            chart = self.chart or "euler"
            return Model(body, law, chart), to_chart(chart, y0)
        kw = {"omega0": value} if prolate else {"n0": value}
        state = "horizontal" if prolate else "vertical"
        model, x0, _ = unstable_manifold_start(body, law, state=state, delta=self.amplitude, seed_law="viscous", **kw)
        if self.chart is None or model.chart.name == self.chart:
            return model, x0
        return model.with_chart(self.chart), to_chart(self.chart, to_paper(model.chart, x0))

    def rise_event(self, body) -> Event:
        """The stop that ends a rise: theta within rise_margin of 0 (prolate) or pi/2 (oblate).

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).

        Returns
        -------
        Event
            A terminal event on theta named "rise-complete".
        """
        if as_body(body).is_prolate:
            return Event("theta", self.rise_margin, direction=-1, name="rise-complete")
        return Event("theta", math.pi / 2 - self.rise_margin, direction=+1, name="rise-complete")

    def outcome(self, body, value: float) -> "Outcome":
        """Simulate one trajectory and classify it.

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).
        value : float
            Omega0 (prolate body) or n0 (oblate body).

        Returns
        -------
        Outcome
            The outcome of the run (:meth:`classify`).
        """
        body = as_body(body)
        model, x0 = self.start(body, value)
        r = simulate(model, x0, self.t_max, rtol=self.rtol, events=[self.rise_event(body)], track_minima=False,
                     dense=False, max_steps=self.max_steps, settle=self.settle, progress=False)
        return self.classify(body, value, model, x0, r)

    def classify(self, body, value: float, model, x0, r) -> "Outcome":
        """The Outcome of the trajectory ``r`` started from ``x0`` (scalar or batch run).

        Parameters
        ----------
        body : Body
            The body simulated.
        value : float
            The family parameter of the run.
        model : Model
            The model simulated.
        x0 : numpy.ndarray
            The initial state, in the chart of ``model``.
        r : Trajectory
            The result of the run.

        Returns
        -------
        Outcome
            The outcome; ``jumped``, ``theta`` and ``rise_fraction`` are None for a failed run.
        """
        jumped = None if r.status is Status.FAILED else r.status is Status.JUMPED
        theta = frac = None
        if r.status is not Status.FAILED:
            theta0 = float(model.chart.to_paper(x0)[4])
            theta = float(r.euler_end[4])
            final = 0.0 if body.is_prolate else math.pi / 2
            frac = (theta0 - theta) / (theta0 - final) if theta0 != final else None
        return Outcome(value, jumped, r.status, r.t, r.stuck, r.reason, r.wall_s, theta, frac)

    def prepare(self, body, engine: str = "batch") -> None:
        """Compile (or load) the integrators this definition's runs use for ``body``'s
        branch, without simulating: the scalar flows by a short run, and with
        ``engine="batch"`` the batch integrators of :mod:`phasekit.core.batch`.

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).
        engine : {"batch", "scalar"}, optional
            "scalar" compiles the scalar flows only.

        Raises
        ------
        ParameterError
            For an invalid ``body`` or ``engine``.
        """
        body = as_body(body)
        value = 2.0 * self.lower_bound(body)
        model, x0 = self.start(body, value)
        simulate(model, x0, 1e-3, rtol=self.rtol, events=[self.rise_event(body)], track_minima=False, dense=False,
                 settle=self.settle, progress=False)
        if check_choice("engine", engine, EVALUATION) == "batch":
            from ..core.batch import compile_batch

            compile_batch(model, [self.rise_event(body)], rtol=self.rtol, track_minima=False, dense=False)

    def outcomes(self, body, values, engine: str = "scalar", stats=None) -> list["Outcome"]:
        """Outcomes of several values of the family parameter: one :meth:`outcome` each
        (``engine="scalar"``), or on heyoka's SIMD batch integrator (``"batch"``, see
        :mod:`phasekit.core.batch`: the same outcomes, event times to ~1e-12).

        Parameters
        ----------
        body : Body or float
            The body, or an aspect ratio a standing for the uniform Spheroid(a).
        values : sequence of float
            Values of the family parameter.
        engine : {"scalar", "batch"}, optional
            How the runs are made.
        stats : BatchStats, optional
            Filled with what the batch integrator did (``engine="batch"``).

        Returns
        -------
        list of Outcome
            One per value, in order.
        """
        return evaluate_outcomes([(self, body, v) for v in values], engine=engine, stats=stats)


#: how a search runs its simulations: one by one, or on the batch integrator
EVALUATION = ("scalar", "batch")


def evaluate_outcomes(jobs, engine: str = "scalar", stats=None) -> list["Outcome"]:
    """Outcomes of (definition, body, value) jobs, in order. ``engine="batch"`` runs the
    jobs of plain Definitions through :func:`phasekit.core.batch.simulate_batch` (one call per
    stop event and tolerance); a Definition subclass with its own ``outcome`` is called.

    Parameters
    ----------
    jobs : sequence of (Definition, Body or float, float)
        The definition, the body (or aspect ratio) and the value of the family parameter of each run.
    engine : {"scalar", "batch"}, optional
        How the runs are made.
    stats : BatchStats, optional
        Filled with what the batch integrator did (``engine="batch"``).

    Returns
    -------
    list of Outcome
        One per job, in order.

    Raises
    ------
    ParameterError
        For an unknown ``engine`` or an invalid body.

    Examples
    --------
    >>> import phasekit as pk
    >>> d = pk.Definition('sliding', 'sliding')
    >>> [o.kind for o in pk.thresholds.evaluate_outcomes([(d, 1.5, 12.0), (d, 1.5, 4.0)], engine='batch')]
    ['jump', 'stuck']
    """
    check_choice("engine", engine, EVALUATION)
    out: list[Outcome | None] = [None] * len(jobs)
    groups: dict = {}
    for i, (defn, body, value) in enumerate(jobs):
        # the batch integrator has no dissipation laws' rest and pivot resets: those run one by one
        if engine == "scalar" or type(defn).outcome is not Definition.outcome or defn.dissipation:
            out[i] = defn.outcome(body, value)
            continue
        body = as_body(body)
        ev = defn.rise_event(body)
        groups.setdefault((ev.level, ev.direction, defn.rtol, defn.max_steps, defn.settle), []).append((i, defn, body, value))
    if groups:
        from ..core.batch import simulate_batch

        for (_, _, rtol, max_steps, settle), items in groups.items():
            starts = [d.start(b, v) for _, d, b, v in items]
            ev = items[0][1].rise_event(items[0][2])
            runs = simulate_batch([m for m, _ in starts], [x for _, x in starts], [d.t_max for _, d, _, _ in items],
                                  events=[ev], rtol=rtol, max_steps=max_steps, track_minima=False, dense=False, stats=stats,
                                  settle=settle)
            for (i, d, b, v), (m, x0), r in zip(items, starts, runs):
                out[i] = d.classify(b, v, m, x0, r)
    return out


DEFAULT_DEFINITIONS = (
    Definition("sliding", "sliding"),
    Definition("viscous", "viscous"),
    Definition("literal-eps1e-3", "literal", eps=1e-3),
    Definition("literal-eps1e-4", "literal", eps=1e-4),
    Definition("literal-exact", "literal"),
)
