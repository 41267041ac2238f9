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
(typically a body that stuck and rolls) also counts as no jump and is flagged. Jumps happen
at theta* ~ 0.5-1.4 (prolate); near the end of the rise some bodies alternate stick and slip
for thousands of cycles (measured: a = 2, Omega0 = 7.19), which the 0.1 margin cuts short.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from .body import Body, Spheroid
from .errors import ConvergenceError, ParameterError, Status
from .friction import Coulomb, RegularisedCoulomb, Viscous
from .hybrid import Event
from .manifolds import horizontal_stability_threshold, unstable_manifold_start, vertical_stability_threshold
from .model import Model
from .options import RTOL_RANGE
from .simulate import simulate
from .starts import gyroscopic_start, to_chart
from .validate import check_choice, check_int, check_positive, check_range

__all__ = ["Definition", "Outcome", "Threshold", "find_threshold", "continue_threshold", "DEFAULT_DEFINITIONS", "as_body"]


def as_body(body) -> Body:
    """A Body, or an aspect ratio standing for the uniform Spheroid(a)."""
    if isinstance(body, Body):
        return body
    if isinstance(body, (int, float, np.integer, np.floating)) and not isinstance(body, bool):
        return Spheroid(float(body))
    raise ParameterError("body", "must be a phasekit Body or an aspect ratio a", body)


@dataclass(frozen=True)
class Definition:
    """How a jump threshold is measured (everything except the body and the family parameter)."""

    name: str
    seed: str  # "viscous", "sliding" or "literal"
    mu: float = 0.1
    amplitude: float = 0.01  # delta (eigenvector seeds) or d (sliding-branch seeds)
    eps: float | None = None  # regularisation of Coulomb friction (None: exact stick-slip)
    rtol: float = 1e-9
    rise_margin: float = 0.1
    t_max: float = 3000.0
    max_steps: int = 20_000_000

    def __post_init__(self):
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
        """Identifies results that can be reused: every field that changes the answer."""
        d = asdict(self)
        d.pop("name")
        return ";".join(f"{k}={v}" for k, v in sorted(d.items()))

    def friction(self):
        if self.seed == "viscous":
            return Viscous(self.mu)
        return Coulomb(self.mu) if self.eps is None else RegularisedCoulomb(self.mu, self.eps)

    def lower_bound(self, body) -> float:
        """Where the seed exists: the fixed point must be unstable (eigenvector seeds) and the
        gyroscopic balance solvable; thresholds are searched above this."""
        body = as_body(body)
        if isinstance(body, Spheroid):
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
                     dense=False, max_steps=self.max_steps)
        jumped = None if r.status is Status.FAILED else r.status is Status.JUMPED
        return Outcome(value, jumped, r.status, r.t, r.stuck, r.reason, r.wall_s)


@dataclass(frozen=True)
class Outcome:
    """One trajectory of a threshold search: did it jump, and how did it end
    (``status``: jumped; stopped = the rise completed; completed = reached t_max; failed)."""

    value: float
    jumped: bool | None  # None: the run failed
    status: Status
    t: float
    stuck: bool
    reason: str | None
    wall_s: float

    @property
    def how(self) -> str:
        return {Status.JUMPED: "jumped", Status.STOPPED: "rise-complete", Status.COMPLETED: "t_max"}.get(self.status, "failed")


@dataclass(frozen=True)
class Threshold:
    """Result of one threshold search.

    ``status``: CONVERGED (bracket narrower than the tolerance), NON_MONOTONE (more than one
    jump/no-jump transition: ``transitions`` holds every bracket, ``value`` the lowest
    no-jump -> jump one), BRACKET_ONLY (a run failed inside the bracket, which is returned as
    far as it was narrowed; ``value`` is its geometric midpoint), NO_JUMP_IN_RANGE,
    JUMPS_AT_LOWER_BOUND, or FAILED (no run succeeded). ``sensitivity`` holds, when asked
    for, how the value moves with the definition's seed distance.
    """

    a: float
    value: float | None
    bracket: tuple[float | None, float | None]
    status: Status
    n_sims: int
    transitions: tuple[tuple[float, float], ...] = ()
    outcomes: tuple[Outcome, ...] = field(default=(), repr=False)
    wall_s: float = 0.0
    reason: str | None = None
    sensitivity: dict = field(default_factory=dict)

    @property
    def stuck_near(self) -> bool:
        """Did a trajectory within 5% of the threshold stick (stick event)?"""
        if self.value is None:
            return False
        return any(o.stuck for o in self.outcomes if abs(o.value / self.value - 1) < 0.05)


def _bisect(defn, body, lo, hi, tol, outcomes):
    """Shrink a [no jump, jump] (or reverse) bracket geometrically to relative width tol."""
    o_lo = next(o for o in outcomes if o.value == lo)
    while hi / lo - 1 > tol:
        mid = math.sqrt(lo * hi)
        o = defn.outcome(body, mid)
        outcomes.append(o)
        if o.jumped is None:
            return lo, hi, False
        if o.jumped == o_lo.jumped:
            lo, o_lo = mid, o
        else:
            hi = mid
    return lo, hi, True


def _scan(defn, body, lo, hi, guess, n_coarse, window, outcomes) -> list[tuple[float, float]]:
    """Coarse geometric scan, widened until a transition shows; returns every transition."""
    w_lo, w_hi = (max(lo, guess / window), min(hi, guess * window)) if guess is not None else (lo, hi)
    trans: list[tuple[float, float]] = []
    for _ in range(30):  # widening steps; each multiplies the window by window**2
        done = {o.value for o in outcomes}
        for v in np.geomspace(w_lo, w_hi, n_coarse):
            if float(v) not in done:
                outcomes.append(defn.outcome(body, float(v)))
        scan = sorted((o for o in outcomes if o.jumped is not None), key=lambda o: o.value)
        trans = [(scan[k].value, scan[k + 1].value) for k in range(len(scan) - 1) if scan[k].jumped != scan[k + 1].jumped]
        if trans or not scan:
            break
        if not scan[0].jumped:  # no jump anywhere yet: look higher, up to hi
            if w_hi >= hi:
                break
            w_lo, w_hi = w_hi, min(hi, w_hi * window**2)
        else:  # jumps everywhere yet: look lower, down to lo
            if w_lo <= lo:
                break
            w_lo, w_hi = max(lo, w_lo / window**2), w_lo
    return trans


def find_threshold(defn: Definition, body, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
                   n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3, throw: bool = False) -> Threshold:
    """Bracket and bisect the jump/no-jump transition in Omega0 (prolate) or n0 (oblate).

    A coarse geometric scan of ``n_coarse`` >= 2 points (over [lo, hi], or over
    [guess/window, guess*window] when a guess from a neighbouring body is given, widened until
    a transition shows) finds every transition on the grid; each is then bisected to relative
    width ``tol`` in [1e-12, 0.5]. ``body`` is a Body or an aspect ratio a (uniform spheroid).
    ``throw``: raise ConvergenceError instead of returning status FAILED.
    """
    t0 = time.perf_counter()
    if not isinstance(defn, Definition):
        raise ParameterError("defn", "must be a phasekit threshold Definition", defn)
    body = as_body(body)
    if isinstance(body, Spheroid) and body.a == 1.0:
        raise ParameterError("a", "must differ from 1 (a sphere has no jump threshold: h_theta = 0)", body.a)
    tol = check_range("tol", tol, 1e-12, 0.5, closed="lr")
    n_coarse = check_int("n_coarse", n_coarse, minimum=2, maximum=1000)
    window = check_range("window", window, 1.0, 1e3, closed="r")
    hi = check_positive("hi", hi)
    lo = defn.lower_bound(body) if lo is None else check_positive("lo", lo)
    if not lo < hi:
        raise ParameterError("lo", f"must be < hi = {hi:g}", lo)
    if guess is not None:
        guess = check_positive("guess", guess)
    outcomes: list[Outcome] = []
    trans = _scan(defn, body, lo, hi, guess, n_coarse, window, outcomes)
    a = getattr(body, "a", float("nan"))
    th = _conclude(defn, body, a, lo, hi, tol, trans, outcomes, time.perf_counter() - t0)
    if throw and th.status is Status.FAILED:
        raise ConvergenceError(f"threshold search failed: {th.reason}", th)
    return th


def _conclude(defn, body, a, lo, hi, tol, trans, outcomes, wall0) -> Threshold:
    t0 = time.perf_counter()
    if not trans:
        valid = [o for o in outcomes if o.jumped is not None]
        if not valid:
            reason = next((o.reason for o in outcomes if o.reason), "no run succeeded")
            return Threshold(a, None, (None, None), Status.FAILED, len(outcomes), (), tuple(outcomes), wall0, reason)
        if all(o.jumped for o in valid):
            return Threshold(a, None, (None, lo), Status.JUMPS_AT_LOWER_BOUND, len(outcomes), (), tuple(outcomes), wall0)
        return Threshold(a, None, (hi, None), Status.NO_JUMP_IN_RANGE, len(outcomes), (), tuple(outcomes), wall0)
    brackets, ok = [], True
    for t_lo, t_hi in trans:
        b_lo, b_hi, good = _bisect(defn, body, t_lo, t_hi, tol, outcomes)
        brackets.append((b_lo, b_hi))
        ok = ok and good
    # the threshold: the lowest transition from no jump (below) to jump (above)
    ups = [b for b in brackets if not next(o for o in outcomes if o.value == b[0]).jumped]
    first = ups[0] if ups else brackets[0]
    status = Status.BRACKET_ONLY if not ok else (Status.NON_MONOTONE if len(brackets) > 1 else Status.CONVERGED)
    value = math.sqrt(first[0] * first[1]) if ups else None
    reason = None if ok else next((o.reason for o in outcomes if o.jumped is None), None)
    return Threshold(a, value, first, status, len(outcomes), tuple(brackets), tuple(outcomes),
                     wall0 + time.perf_counter() - t0, reason)


def continue_threshold(defn: Definition, bodies, **kw) -> list[Threshold]:
    """Thresholds along a list of bodies (or aspect ratios), each search seeded by the previous result."""
    out, guess = [], None
    for b in bodies:
        th = find_threshold(defn, b, guess=guess, **kw)
        out.append(th)
        if th.value is not None:
            guess = th.value
    return out


DEFAULT_DEFINITIONS = (
    Definition("sliding", "sliding"),
    Definition("viscous", "viscous"),
    Definition("literal-eps1e-3", "literal", eps=1e-3),
    Definition("literal-eps1e-4", "literal", eps=1e-4),
    Definition("literal-exact", "literal"),
)
