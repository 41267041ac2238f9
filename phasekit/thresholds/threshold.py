"""Jump thresholds: the smallest Omega0 (prolate) or n0 (oblate) whose trajectory loses contact.

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
import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from .._runtime.errors import ConvergenceError, ParameterError, SearchStatus, Status
from .._runtime.validate import check_choice, check_int, check_positive, check_range
from .._runtime.watch import WALL_REASON, check_max_wall, deadline, passed, progress_bar, wall_deadline
from ..bodies.body import Body, Spheroid
from ..core.hybrid import Event
from ..core.model import Model
from ..core.options import RTOL_RANGE
from ..core.settle import Settle, check_settle
from ..core.simulate import simulate
from ..core.starts import gyroscopic_start, to_chart
from ..friction.laws import Coulomb, RegularisedCoulomb, Viscous
from ..steady.manifolds import unstable_manifold_start
from ..theory.criteria import horizontal_stability_threshold, vertical_stability_threshold

__all__ = ["Definition", "Outcome", "Threshold", "Sensitivity", "ThresholdSearch", "find_threshold", "continue_threshold",
           "run_searches", "evaluate_outcomes", "find_stick_boundary",
           "threshold_searches", "threshold_result", "stick_search", "DEFAULT_DEFINITIONS", "EVALUATION", "as_body",
           "sensitivity_definitions", "sensitivity_parent", "prepare_definitions"]


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

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
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

    def __post_init__(self):
        object.__setattr__(self, "settle", check_settle(self.settle))
        check_choice("seed", self.seed, ("viscous", "sliding", "literal"))
        check_range("amplitude", self.amplitude, 0.0, 0.5, closed="r")
        check_range("mu", self.mu, 0.0, 10.0, closed="r")
        if self.eps is not None:
            check_range("eps", self.eps, 1e-14, 1.0, closed="lr")
        check_range("rtol", self.rtol, *RTOL_RANGE, closed="lr")
        check_range("rise_margin", self.rise_margin, 0.0, math.pi / 2)
        check_positive("t_max", self.t_max)
        check_int("max_steps", self.max_steps, minimum=1)

    @property
    def law_label(self) -> str:
        if self.seed == "viscous":
            return f"viscous mu={self.mu:g}"
        return f"coulomb mu={self.mu:g}" + (f" eps={self.eps:g}" if self.eps else " exact")

    @property
    def label(self) -> str:
        what = {"viscous": f"eigenvector delta={self.amplitude:g}", "sliding": f"sliding branch d={self.amplitude:g}",
                "literal": f"viscous eigenvector delta={self.amplitude:g}"}[self.seed]
        return f"{self.law_label}; seed: {what}"

    def key(self) -> str:
        """Identifies results that can be reused: every field that changes the answer. The
        default settle rule is left out: it ends only runs that would not jump (checked on the
        published studies), so results computed before it existed keep their keys."""
        d = asdict(self)
        d.pop("name")
        if self.settle == DEFAULT_SETTLE:
            d.pop("settle")
        return ";".join(f"{k}={v}" for k, v in sorted(d.items()))

    def friction(self):
        if self.seed == "viscous":
            return Viscous(self.mu)
        return Coulomb(self.mu) if self.eps is None else RegularisedCoulomb(self.mu, self.eps)

    def lower_bound(self, body) -> float:
        """Where the seed exists: the fixed point must be unstable (eigenvector seeds) and the
        gyroscopic balance solvable; thresholds are searched above this."""
        body = as_body(body)
        if isinstance(body, Spheroid) and body.flip_symmetric:
            fn = horizontal_stability_threshold if body.is_prolate else vertical_stability_threshold
            crit = fn(body.A, body.C, body.a) or 1.0
        else:  # no closed form: start the search at 1 (units sqrt(g/b))
            crit = 1.0
        return 1.05 * crit

    def start(self, body, value: float):
        """(model, x0) for ``body`` (or aspect ratio) and Omega0 (prolate) or n0 (oblate)."""
        body = as_body(body)
        law = self.friction()
        prolate = body.is_prolate
        if self.seed == "sliding":
            if prolate:
                y0 = gyroscopic_start(body, math.pi / 2 - self.amplitude, omega0=value)
            else:
                y0 = gyroscopic_start(body, self.amplitude, n0=value)
            return Model(body, law, "euler"), to_chart("euler", y0)
        kw = {"omega0": value} if prolate else {"n0": value}
        state = "horizontal" if prolate else "vertical"
        model, x0, _ = unstable_manifold_start(body, law, state=state, delta=self.amplitude, seed_law="viscous", **kw)
        return model, x0

    def rise_event(self, body) -> Event:
        """The stop that ends a rise: theta within rise_margin of 0 (prolate) or pi/2 (oblate)."""
        if as_body(body).is_prolate:
            return Event("theta", self.rise_margin, direction=-1, name="rise-complete")
        return Event("theta", math.pi / 2 - self.rise_margin, direction=+1, name="rise-complete")

    def outcome(self, body, value: float) -> "Outcome":
        """Simulate one trajectory and classify it."""
        body = as_body(body)
        model, x0 = self.start(body, value)
        r = simulate(model, x0, self.t_max, rtol=self.rtol, events=[self.rise_event(body)], track_minima=False,
                     dense=False, max_steps=self.max_steps, settle=self.settle, progress=False)
        return self.classify(body, value, model, x0, r)

    def classify(self, body, value: float, model, x0, r) -> "Outcome":
        """The Outcome of the trajectory ``r`` started from ``x0`` (scalar or batch run)."""
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
        ``engine="batch"`` the batch integrators of :mod:`phasekit.core.batch`."""
        body = as_body(body)
        value = 2.0 * self.lower_bound(body)
        model, x0 = self.start(body, value)
        simulate(model, x0, 1e-3, rtol=self.rtol, events=[self.rise_event(body)], track_minima=False, dense=False,
                 progress=False)
        if check_choice("engine", engine, EVALUATION) == "batch":
            from ..core.batch import compile_batch

            compile_batch(model, [self.rise_event(body)], rtol=self.rtol, track_minima=False, dense=False)

    def outcomes(self, body, values, engine: str = "scalar", stats=None) -> list["Outcome"]:
        """Outcomes of several values of the family parameter: one :meth:`outcome` each
        (``engine="scalar"``), or on heyoka's SIMD batch integrator (``"batch"``, see
        :mod:`phasekit.core.batch`: the same outcomes, event times to ~1e-12)."""
        return evaluate_outcomes([(self, body, v) for v in values], engine=engine, stats=stats)


#: how a search runs its simulations: one by one, or on the batch integrator
EVALUATION = ("scalar", "batch")


def evaluate_outcomes(jobs, engine: str = "scalar", stats=None) -> list["Outcome"]:
    """Outcomes of (definition, body, value) jobs, in order. ``engine="batch"`` runs the
    jobs of plain Definitions through :func:`phasekit.core.batch.simulate_batch` (one call per
    stop event and tolerance); a Definition subclass with its own ``outcome`` is called.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> d = pk.Definition('sliding', 'sliding')
    >>> [o.kind for o in pk.thresholds.evaluate_outcomes([(d, 1.5, 12.0), (d, 1.5, 4.0)], engine='batch')]
    ['jump', 'stuck']
    """
    check_choice("engine", engine, EVALUATION)
    out: list[Outcome | None] = [None] * len(jobs)
    groups: dict = {}
    for i, (defn, body, value) in enumerate(jobs):
        if engine == "scalar" or type(defn).outcome is not Definition.outcome:
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


@dataclass(frozen=True)
class Outcome:
    """One trajectory of a threshold search: did it jump, and how did it end
    (``status``: jumped; stopped = the rise completed; completed = reached t_max; settled =
    the body settled in contact (the definition's ``settle`` rule); failed).
    ``theta``: the inclination where it ended (at lift-off for a jump); ``rise_fraction``:
    how much of the rise from theta0 to the final state (0 prolate, pi/2 oblate) was done.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> o = pk.thresholds.evaluate_outcomes([(pk.Definition('sliding', 'sliding'), 1.5, 12.0)])[0]
    >>> isinstance(o, pk.thresholds.Outcome), o.kind, o.how
    (True, 'jump', 'jumped')
    """

    value: float
    jumped: bool | None  # None: the run failed
    status: Status
    t: float
    stuck: bool
    reason: str | None
    wall_s: float
    theta: float | None = None
    rise_fraction: float | None = None

    @property
    def how(self) -> str:
        return {Status.JUMPED: "jumped", Status.STOPPED: "rise-complete", Status.COMPLETED: "t_max",
                Status.SETTLED: "settled"}.get(self.status, "failed")

    @property
    def kind(self) -> str:
        """The outcome map's classes: "jump" (lost contact before the rise completed),
        "rise" (the rise completed in contact), "stuck" (neither by t_max: the body stuck and
        rolls), "slow" (neither, without sticking) or "failed"."""
        if self.jumped is None:
            return "failed"
        if self.jumped:
            return "jump"
        if self.status is Status.STOPPED:
            return "rise"
        return "stuck" if self.stuck else "slow"


@dataclass(frozen=True)
class Sensitivity:
    """How a threshold moves with the definition's seed distance (``amplitude``: d on the
    sliding branch, delta for eigenvector seeds), against the bisection bracket.

    ``amplitudes`` and ``values``: (d/2, d, 2d) and the thresholds there (None where there
    is none); ``slope``: d ln(threshold) / d ln(d), from the two outer points;
    ``shift``: the largest relative change of the threshold over the three; ``bracket``:
    the relative width of the bisection bracket at d; ``dominant``: which of the two is
    larger ("seed distance" or "bracket").

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2, sensitivity=True, engine='batch')
    >>> isinstance(th.sensitivity, ps.Sensitivity), th.sensitivity.amplitudes
    (True, (0.005, 0.01, 0.02))
    """

    amplitudes: tuple[float, float, float]
    values: tuple[float | None, float | None, float | None]
    brackets: tuple[tuple, tuple, tuple]
    statuses: tuple[str, str, str]
    slope: float | None
    shift: float | None
    bracket: float | None
    dominant: str | None
    n_sims: int = 0  # simulations of the two extra searches

    @classmethod
    def from_thresholds(cls, amps, ths) -> "Sensitivity":
        vals = tuple(t.value for t in ths)
        mid = ths[1]
        slope = shift = width = dominant = None
        if vals[0] is not None and vals[2] is not None:
            slope = math.log(vals[2] / vals[0]) / math.log(amps[2] / amps[0])
        if vals[1] is not None and all(v is not None for v in vals):
            shift = max(abs(v / vals[1] - 1) for v in vals)
        if mid.bracket[0] is not None and mid.bracket[1] is not None:
            width = mid.bracket[1] / mid.bracket[0] - 1
        if shift is not None and width is not None:
            dominant = "seed distance" if shift > width else "bracket"
        return cls(tuple(amps), vals, tuple(t.bracket for t in ths), tuple(t.status.value for t in ths), slope, shift,
                   width, dominant, ths[0].n_sims + ths[2].n_sims)

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class Threshold:
    """Result of one threshold search.

    ``status``: CONVERGED (bracket narrower than the tolerance), NON_MONOTONE (more than one
    jump/no-jump transition: ``transitions`` holds every bracket, ``value`` the lowest
    no-jump -> jump one), BRACKET_ONLY (a run failed inside the bracket, which is returned as
    far as it was narrowed; ``value`` is its geometric midpoint), NO_JUMP_IN_RANGE,
    JUMPS_AT_LOWER_BOUND, or FAILED (no run succeeded). ``n_rounds``: rounds of mutually
    independent simulations the search needed (its critical path). ``sensitivity`` is
    filled when asked (``find_threshold(..., sensitivity=True)``).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    >>> isinstance(th, pk.thresholds.Threshold), th.status.value, round(th.value, 2)
    (True, 'converged', 9.78)
    """

    a: float
    value: float | None
    bracket: tuple[float | None, float | None]
    status: SearchStatus
    n_sims: int
    transitions: tuple[tuple[float, float], ...] = ()
    outcomes: tuple[Outcome, ...] = field(default=(), repr=False)
    wall_s: float = 0.0
    reason: str | None = None
    sensitivity: Sensitivity | None = None
    n_rounds: int = 0

    @property
    def stuck_near(self) -> bool:
        """Did a trajectory within 5% of the threshold stick (stick event)?"""
        if self.value is None:
            return False
        return any(o.stuck for o in self.outcomes if abs(o.value / self.value - 1) < 0.05)


def _tree(lo: float, hi: float, tol: float, depth: int) -> list[float]:
    """Every midpoint sequential bisection of [lo, hi] could visit in ``depth`` steps (the
    same floating-point operations, so the walk in :meth:`_Bracket.walk` reproduces it)."""
    if depth == 0 or not hi / lo - 1 > tol:
        return []
    mid = math.sqrt(lo * hi)
    return _tree(lo, mid, tol, depth - 1) + [mid] + _tree(mid, hi, tol, depth - 1)


@dataclass
class _Bracket:
    """One transition being narrowed: [lo, hi] with the outcome at lo."""

    lo: float
    hi: float
    o_lo: Outcome
    active: bool = True
    good: bool = True

    def walk(self, results: dict, tol: float) -> None:
        """Follow sequential bisection through the outcomes of this round."""
        while self.active:
            if not self.hi / self.lo - 1 > tol:
                self.active = False
                return
            mid = math.sqrt(self.lo * self.hi)
            if mid not in results:
                return  # beyond this round's tree
            o = results[mid]
            if o.jumped is None:
                self.active, self.good = False, False
            elif o.jumped == self.o_lo.jumped:
                self.lo, self.o_lo = mid, o
            else:
                self.hi = mid


class ThresholdSearch:
    """:func:`find_threshold` as a state machine, so that many searches (and several values
    of one search) can be simulated at once: :meth:`ask` gives the values of the next round
    (mutually independent), :meth:`tell` takes their outcomes, :meth:`result` gives the
    Threshold once :attr:`done`.

    With ``levels = m`` a refinement round simulates every midpoint that sequential bisection
    could visit in its next m steps (a dyadic tree: k = 2^m - 1 values, k-section) and then
    walks the tree as bisection would: the bracket is the one sequential bisection gives, in
    ceil(steps / m) rounds instead of steps. The coarse scan is one round of ``n_coarse``
    values (more if it has to widen).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = pk.thresholds.ThresholdSearch(pk.Definition('sliding', 'sliding'), pk.Spheroid(1.5), lo=5.0, hi=20.0, guess=None, n_coarse=4, window=1.5, tol=1e-2)
    >>> [round(v, 4) for v in s.ask()]
    [5.0, 7.937, 12.5992, 20.0]
    """

    def __init__(self, defn, body, *, lo, hi, guess, n_coarse, window, tol, levels=1, job=None, flag=None):
        self.defn, self.body = defn, body
        # a search over another parameter p of the same simulations: job(p) -> (definition,
        # body, value) and flag(outcome) -> bool or None; its outcomes then carry p as
        # ``value`` and the flag as ``jumped``
        self.job = job or (lambda p: (defn, body, p))
        self.flag = flag
        self.lo, self.hi, self.tol, self.n_coarse, self.window = lo, hi, tol, n_coarse, window
        self.levels = levels
        self.w_lo, self.w_hi = (max(lo, guess / window), min(hi, guess * window)) if guess is not None else (lo, hi)
        self.outcomes: list[Outcome] = []
        self.phase, self.widenings, self.n_rounds = "scan", 0, 0
        self.trans: list[tuple[float, float]] = []
        self.brackets: list[_Bracket] = []
        self._asked: list[float] = []
        self.stopped: str | None = None  # why the search was ended before it finished

    @property
    def done(self) -> bool:
        return self.phase == "done"

    def ask(self) -> list[float]:
        """The values to simulate next (empty once done)."""
        while not self.done:
            if self.phase == "scan":
                known = {o.value for o in self.outcomes}
                vals = [float(v) for v in np.geomspace(self.w_lo, self.w_hi, self.n_coarse) if float(v) not in known]
                if vals:
                    self._asked = vals
                    return vals
                self._after_scan()
            else:
                vals = [v for b in self.brackets if b.active for v in _tree(b.lo, b.hi, self.tol, self.levels)]
                if vals:
                    self._asked = vals
                    return vals
                self.phase = "done"
        return []

    def stop(self, reason: str) -> None:
        """End the search where it is (a wall budget ran out): its result keeps the bracket it
        has, with status BRACKET_ONLY (FAILED before any transition was found) and ``reason``."""
        if self.phase == "scan":
            self._after_scan()
        if not self.done:
            self.phase, self.stopped = "done", reason

    def describe(self) -> str:
        """Where the search stands, in a few words (a progress bar's postfix)."""
        live = [b for b in self.brackets if b.active]
        if live:
            return f"bracket [{live[0].lo:.6g}, {live[0].hi:.6g}]"
        return f"scan [{self.w_lo:.4g}, {self.w_hi:.4g}]" if self.phase == "scan" else self.phase

    def tell(self, outcomes) -> None:
        outcomes = list(outcomes)
        if len(outcomes) != len(self._asked):
            raise ValueError("tell() needs the outcomes of the values ask() gave, in order")
        outcomes = [replace(o, value=v) if o.value != v else o for o, v in zip(outcomes, self._asked)]
        self.n_rounds += 1
        self._asked = []
        if self.flag is not None:
            outcomes = [replace(o, jumped=self.flag(o)) for o in outcomes]
        self.outcomes.extend(outcomes)
        if self.phase == "scan":
            self._after_scan()
        else:
            results = {o.value: o for o in outcomes}
            for b in self.brackets:
                b.walk(results, self.tol)
            if not any(b.active for b in self.brackets):
                self.phase = "done"

    def _after_scan(self) -> None:
        """Transitions on the scan so far; widen the window or go on to refine them."""
        self.widenings += 1
        scan = sorted((o for o in self.outcomes if o.jumped is not None), key=lambda o: o.value)
        self.trans = [(scan[k].value, scan[k + 1].value) for k in range(len(scan) - 1) if scan[k].jumped != scan[k + 1].jumped]
        stop = bool(self.trans) or not scan or self.widenings >= 30
        if not stop and not scan[0].jumped:  # no jump anywhere yet: look higher, up to hi
            stop = self.w_hi >= self.hi
            self.w_lo, self.w_hi = self.w_hi, min(self.hi, self.w_hi * self.window**2)
        elif not stop:  # jumps everywhere yet: look lower, down to lo
            stop = self.w_lo <= self.lo
            self.w_lo, self.w_hi = max(self.lo, self.w_lo / self.window**2), self.w_lo
        if stop:
            first = {}
            for o in self.outcomes:
                first.setdefault(o.value, o)
            self.brackets = [_Bracket(lo, hi, first[lo]) for lo, hi in self.trans]
            self.phase = "refine" if self.brackets else "done"

    def result(self, wall_s: float = 0.0) -> Threshold:
        a = getattr(self.body, "a", float("nan"))
        outs, n = tuple(self.outcomes), len(self.outcomes)
        if self.stopped is not None and not self.trans:
            return Threshold(a, None, (None, None), SearchStatus.FAILED, n, (), outs, wall_s,
                             f"{self.stopped} before a transition was found", n_rounds=self.n_rounds)
        if self.stopped is not None and any(b.active for b in self.brackets):
            first = next(b for b in self.brackets if b.active)
            return Threshold(a, math.sqrt(first.lo * first.hi) if not first.o_lo.jumped else None, (first.lo, first.hi),
                             SearchStatus.BRACKET_ONLY, n, tuple((b.lo, b.hi) for b in self.brackets), outs, wall_s,
                             f"{self.stopped}: the bracket is as far as it was narrowed", n_rounds=self.n_rounds)
        if not self.trans:
            valid = [o for o in self.outcomes if o.jumped is not None]
            if not valid:
                reason = next((o.reason for o in self.outcomes if o.reason), "no run succeeded")
                return Threshold(a, None, (None, None), SearchStatus.FAILED, n, (), outs, wall_s, reason, n_rounds=self.n_rounds)
            if all(o.jumped for o in valid):
                return Threshold(a, None, (None, self.lo), SearchStatus.JUMPS_AT_LOWER_BOUND, n, (), outs, wall_s, n_rounds=self.n_rounds)
            return Threshold(a, None, (self.hi, None), SearchStatus.NO_JUMP_IN_RANGE, n, (), outs, wall_s, n_rounds=self.n_rounds)
        brackets = [(b.lo, b.hi) for b in self.brackets]
        ok = all(b.good for b in self.brackets)
        # the threshold: the lowest transition from no jump (below) to jump (above)
        ups = [(b.lo, b.hi) for b in self.brackets if not b.o_lo.jumped]
        first = ups[0] if ups else brackets[0]
        status = SearchStatus.BRACKET_ONLY if not ok else (SearchStatus.NON_MONOTONE if len(brackets) > 1 else SearchStatus.CONVERGED)
        value = math.sqrt(first[0] * first[1]) if ups else None
        reason = None if ok else next((o.reason for o in self.outcomes if o.jumped is None), None)
        return Threshold(a, value, first, status, n, tuple(brackets), outs, wall_s, reason, n_rounds=self.n_rounds)


def run_searches(searches, *, engine: str = "scalar", evaluate=None, stats=None, bar=None) -> int:
    """Drive searches in lock-step: each round simulates the values every unfinished search
    asks for, all at once (on the batch integrator with ``engine="batch"``, or through
    ``evaluate(jobs) -> outcomes`` with jobs (definition, body, value), e.g. on a cluster).
    A wall budget in force (:func:`phasekit._runtime.watch.wall_deadline`) that has run out ends every
    search between rounds (:meth:`ThresholdSearch.stop`); ``bar`` (tqdm) counts the runs.
    Returns the number of rounds.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> searches = [pk.thresholds.ThresholdSearch(pk.Definition('sliding', 'sliding'), pk.Spheroid(a), lo=5.0, hi=20.0, guess=g, n_coarse=4, window=1.5, tol=1e-2) for a, g in ((1.5, 9.74), (1.75, 8.16))]
    >>> rounds = pk.thresholds.run_searches(searches, engine='batch')
    >>> [round(s.result().value, 2) for s in searches]
    [9.78, 8.13]
    """
    rounds = 0
    while True:
        asks = [(s, s.ask()) for s in searches if not s.done]
        asks = [(s, v) for s, v in asks if v]
        if not asks:
            return rounds
        if passed():
            budget = deadline()[1]
            for s, _ in asks:
                s.stop(f"{WALL_REASON} (max_wall = {budget:g} s) ran out")
            return rounds
        jobs = [s.job(x) for s, vals in asks for x in vals]
        outs = evaluate(jobs) if evaluate is not None else evaluate_outcomes(jobs, engine=engine, stats=stats)
        k = 0
        for s, vals in asks:
            s.tell(outs[k:k + len(vals)])
            k += len(vals)
        rounds += 1
        if bar is not None:
            bar.update(len(jobs))
            bar.set_postfix_str(searches[len(searches) // 2].describe(), refresh=False)


def threshold_searches(defn: Definition, body, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
                       n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3, levels: int = 1,
                       sensitivity: bool = False) -> list[ThresholdSearch]:
    """The searches :func:`find_threshold` runs (validated): the threshold search, and with
    ``sensitivity`` the same search at the seed distance halved and doubled (list order
    d/2, d, 2d). Run them, alone or with other searches, by :func:`run_searches`."""
    if not isinstance(defn, Definition):
        raise ParameterError("defn", "must be a phasekit threshold Definition", defn)
    body = as_body(body)
    if isinstance(body, Spheroid) and body.a == 1.0 and body.flip_symmetric:
        raise ParameterError("a", "must differ from 1 (a sphere has no jump threshold: h_theta = 0)", body.a)
    tol = check_range("tol", tol, 1e-12, 0.5, closed="lr")
    n_coarse = check_int("n_coarse", n_coarse, minimum=2, maximum=1000)
    levels = check_int("levels", levels, minimum=1, maximum=8)
    window = check_range("window", window, 1.0, 1e3, closed="r")
    hi = check_positive("hi", hi)
    lo = defn.lower_bound(body) if lo is None else check_positive("lo", lo)
    if not lo < hi:
        raise ParameterError("lo", f"must be < hi = {hi:g}", lo)
    if guess is not None:
        guess = check_positive("guess", guess)
    kw = dict(lo=lo, hi=hi, guess=guess, n_coarse=n_coarse, window=window, tol=tol, levels=levels)
    main = ThresholdSearch(defn, body, **kw)
    if not sensitivity:
        return [main]
    d = defn.amplitude
    return [ThresholdSearch(replace(defn, amplitude=d / 2), body, **kw), main,
            ThresholdSearch(replace(defn, amplitude=min(2 * d, 0.5)), body, **kw)]


def threshold_result(searches: list[ThresholdSearch], wall_s: float = 0.0) -> Threshold:
    """The Threshold of finished :func:`threshold_searches` (with the sensitivity if asked)."""
    if len(searches) == 1:
        return searches[0].result(wall_s)
    main = searches[1]
    th = main.result(wall_s)
    amps = tuple(s.defn.amplitude for s in searches)
    sens = Sensitivity.from_thresholds(amps, [s.result() for s in searches])
    return replace(th, sensitivity=sens, n_rounds=max(s.n_rounds for s in searches))


def find_threshold(defn: Definition, body, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
                   n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3, levels: int = 1, engine: str = "scalar",
                   sensitivity: bool = False, evaluate=None, throw: bool = False, max_wall: float | None = None,
                   progress: bool | None = None) -> Threshold:
    """Bracket and bisect the jump/no-jump transition in Omega0 (prolate) or n0 (oblate).

    A coarse geometric scan of ``n_coarse`` >= 2 points (over [lo, hi], or over
    [guess/window, guess*window] when a guess from a neighbouring body is given, widened until
    a transition shows) finds every transition on the grid; each is then bisected to relative
    width ``tol`` in [1e-12, 0.5]. ``body`` is a Body or an aspect ratio a (uniform spheroid).

    ``levels`` = m >= 1: bisect m steps per round by simulating the 2^m - 1 midpoints those
    steps could need at once (k-section; the same bracket as bisection in fewer rounds, at
    more simulations). ``engine``: "scalar" (one :func:`simulate` per value) or "batch"
    (heyoka's SIMD batch integrator, :mod:`phasekit.core.batch`); ``evaluate(jobs)`` replaces
    both (jobs: (definition, body, value); e.g. a cluster's map). ``sensitivity=True`` also
    searches at the seed distance (``defn.amplitude``) halved and doubled, in the same
    rounds, and fills :attr:`Threshold.sensitivity`. ``throw``: raise ConvergenceError
    instead of returning status FAILED.

    ``max_wall`` (seconds) bounds the whole search: a run under way when it runs out ends
    "failed", and the search returns the bracket it has (status BRACKET_ONLY, or FAILED
    before a transition was found) with a reason naming the budget. ``progress``: a bar of
    the runs with the current bracket (None: on a terminal or in a notebook only).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    >>> th.status.value, round(th.value, 2), th.bracket[0] < th.value < th.bracket[1]
    ('converged', 9.78, True)
    """
    t0 = time.perf_counter()
    check_choice("engine", engine, EVALUATION)
    max_wall = check_max_wall(max_wall)
    searches = threshold_searches(defn, body, lo=lo, hi=hi, guess=guess, n_coarse=n_coarse, window=window, tol=tol,
                                  levels=levels, sensitivity=sensitivity)
    with progress_bar(desc=_bar_label(searches[0]), progress=progress) as bar, wall_deadline(max_wall):
        run_searches(searches, engine=engine, evaluate=evaluate, bar=bar)
    th = threshold_result(searches, time.perf_counter() - t0)
    if throw and th.status is SearchStatus.FAILED:
        raise ConvergenceError(f"threshold search failed: {th.reason}", th)
    return th


def _bar_label(search: ThresholdSearch) -> str:
    a = getattr(search.body, "a", None)
    return "threshold" + (f" a={a:g}" if a is not None else "")


def stick_search(defn: Definition, body, value: float, *, lo: float = 1e-4, hi: float = 0.2, n_coarse: int = 8,
                 tol: float = 1e-2, levels: int = 1) -> ThresholdSearch:
    """The search :func:`find_stick_boundary` runs (validated)."""
    if not isinstance(defn, Definition):
        raise ParameterError("defn", "must be a phasekit threshold Definition", defn)
    body = as_body(body)
    value = check_positive("value", value)
    lo, hi = check_range("lo", lo, 0.0, 0.5, closed="r"), check_range("hi", hi, 0.0, 0.5, closed="r")
    if not lo < hi:
        raise ParameterError("lo", f"must be < hi = {hi:g}", lo)
    return ThresholdSearch(defn, body, lo=lo, hi=hi, guess=None, n_coarse=check_int("n_coarse", n_coarse, minimum=2),
                           window=1.5, tol=check_range("tol", tol, 1e-12, 0.5, closed="lr"),
                           levels=check_int("levels", levels, minimum=1, maximum=8),
                           job=lambda d: (replace(defn, amplitude=d), body, value),
                           flag=lambda o: None if o.jumped is None else o.kind != "stuck")


def find_stick_boundary(defn: Definition, body, value: float, *, lo: float = 1e-4, hi: float = 0.2, n_coarse: int = 8,
                        tol: float = 1e-2, levels: int = 1, engine: str = "scalar", evaluate=None,
                        max_wall: float | None = None, progress: bool | None = None) -> Threshold:
    """The sticking boundary d_min at one value of the family parameter: the smallest seed
    distance ``d`` (``defn.amplitude``) in [lo, hi] whose start does not stick and roll
    (outcome kind "stuck"), bracketed and bisected in d to relative width ``tol``.

    Returns a :class:`Threshold` over d: ``value`` is d_min (the lowest transition from
    stuck below to not stuck above), its outcomes carry d as ``value`` and "not stuck" as
    ``jumped``. ``max_wall`` and ``progress`` as for :func:`find_threshold`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> th = pk.thresholds.find_stick_boundary(pk.Definition('sliding', 'sliding', t_max=300.0), 1.5, 17.7, tol=0.1)
    >>> th.status.value, 1e-4 < th.value < 0.2
    ('converged', True)
    """
    t0 = time.perf_counter()
    check_choice("engine", engine, EVALUATION)
    max_wall = check_max_wall(max_wall)
    search = stick_search(defn, body, value, lo=lo, hi=hi, n_coarse=n_coarse, tol=tol, levels=levels)
    with progress_bar(desc="stick boundary", progress=progress) as bar, wall_deadline(max_wall):
        run_searches([search], engine=engine, evaluate=evaluate, bar=bar)
    return search.result(time.perf_counter() - t0)


def continue_threshold(defn: Definition, bodies, *, max_wall: float | None = None, progress: bool | None = None,
                       **kw) -> list[Threshold]:
    """Thresholds along a list of bodies (or aspect ratios), each search seeded by the previous
    result (keywords of :func:`find_threshold`). ``max_wall`` bounds the whole continuation: a
    search under way when it runs out returns its bracket, and the bodies after it a FAILED
    Threshold saying so; ``progress``: a bar over the bodies.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ths = pk.thresholds.continue_threshold(pk.Definition('sliding', 'sliding'), [1.75, 1.5], hi=120.0, tol=1e-2)
    >>> [th.status.value for th in ths]
    ['converged', 'converged']
    """
    max_wall = check_max_wall(max_wall)
    bodies = list(bodies)
    out, guess = [], None
    with progress_bar(len(bodies), desc="thresholds", unit="body", progress=progress) as bar, \
            wall_deadline(max_wall):
        for b in bodies:
            if passed():
                why = f"not searched: {WALL_REASON} (max_wall = {max_wall:g} s) ran out"
                out.append(Threshold(getattr(as_body(b), "a", float("nan")), None, (None, None), SearchStatus.FAILED, 0,
                                     reason=why))
                continue
            th = find_threshold(defn, b, guess=guess, progress=False, **kw)
            out.append(th)
            if th.value is not None:
                guess = th.value
            bar.update()
            bar.set_postfix_str(f"last {th.status.value} {th.value if th.value is None else format(th.value, '.6g')}",
                                refresh=False)
    return out


DEFAULT_DEFINITIONS = (
    Definition("sliding", "sliding"),
    Definition("viscous", "viscous"),
    Definition("literal-eps1e-3", "literal", eps=1e-3),
    Definition("literal-eps1e-4", "literal", eps=1e-4),
    Definition("literal-exact", "literal"),
)


def sensitivity_definitions(quick: bool = False) -> list[Definition]:
    """The variants of the default definition ("sliding", d = 0.01) and of the literal one with
    eps = 1e-4 at which a threshold's sensitivity is measured: the seed distance d (or delta)
    halved and doubled, rtol 1e-8 and 1e-10, and (unless ``quick``) eps 1e-4, 1e-6, 1e-8 for the
    sliding seed and the literal variants. Each is named after what it changes
    (:func:`sensitivity_parent` names the definition it varies).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [d.name for d in ps.sensitivity_definitions(quick=True)]
    ['sliding-d0.005', 'sliding-d0.02', 'sliding-rtol1e-8', 'sliding-rtol1e-10']
    >>> len(ps.sensitivity_definitions())
    13
    """
    base = next(d for d in DEFAULT_DEFINITIONS if d.name == "sliding")
    lit = Definition("literal-eps1e-4", "literal", eps=1e-4)
    out = [replace(base, name="sliding-d0.005", amplitude=0.005), replace(base, name="sliding-d0.02", amplitude=0.02),
           replace(base, name="sliding-rtol1e-8", rtol=1e-8), replace(base, name="sliding-rtol1e-10", rtol=1e-10)]
    if quick:
        return out
    out += [replace(base, name=f"sliding-eps{e:g}", eps=e) for e in (1e-4, 1e-6, 1e-8)]
    out += [replace(lit, name="literal-eps1e-4-delta0.005", amplitude=0.005), replace(lit, name="literal-eps1e-4-delta0.02", amplitude=0.02),
            replace(lit, name="literal-eps1e-4-rtol1e-8", rtol=1e-8), replace(lit, name="literal-eps1e-4-rtol1e-10", rtol=1e-10),
            replace(lit, name="literal-eps1e-6", eps=1e-6), replace(lit, name="literal-eps1e-8", eps=1e-8)]
    return out


def sensitivity_parent(defn) -> str:
    """The name of the definition of :data:`DEFAULT_DEFINITIONS` that a variant of
    :func:`sensitivity_definitions` (a definition, or a row with its ``seed``) varies.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [ps.sensitivity_parent(d) for d in ps.sensitivity_definitions()][::6]
    ['sliding', 'sliding', 'literal-eps1e-4']
    """
    return "literal-eps1e-4" if defn.seed == "literal" else "sliding"


def prepare_definitions(definitions, bodies, engine: str = "batch") -> None:
    """Compile (or load) the models and integrators of each definition for each body (or
    aspect ratio) in ``bodies`` (:meth:`Definition.prepare`), e.g. before a Dask run ships them
    to the workers; a definition that cannot be prepared is skipped (its runs compile when they
    first need it).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.prepare_definitions(pk.thresholds.DEFAULT_DEFINITIONS[:1], [1.5])
    """
    for d in definitions:
        for a in bodies:
            try:
                d.prepare(a, engine=engine)
            except Exception:
                pass
