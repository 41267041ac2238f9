"""Jump thresholds: the smallest Omega0 (prolate) or n0 (oblate) whose trajectory loses contact.

A *definition* fixes everything but the aspect ratio and the family parameter: the friction
law, how the trajectory is seeded near the fixed point, the tolerances and the completion
criterion. Figure 6b,c of the paper reads "seed on the unstable manifold of the horizontal
(prolate) or vertical (oblate) state with delta = 0.01, integrate with Coulomb friction,
record whether R reaches 0". Read literally that depends on numerics (the seed has almost
no slip and exact Coulomb friction sticks; see ../shared/NOTES.md), so three definitions
are provided:

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
prolate body, pi/2 for an oblate one); a run that reaches ``t_max`` first (typically a
body that stuck and rolls) also counts as no jump and is flagged. Jumps happen at
theta* ~ 0.5-1.4 (prolate); near the end of the rise some bodies alternate stick and slip
for thousands of cycles (measured: a = 2, Omega0 = 7.19), which the 0.1 margin cuts short.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from .body import Spheroid
from .errors import Status, check_choice, check_positive
from .friction import Coulomb, RegularisedCoulomb, Viscous
from .manifolds import horizontal_stability_threshold, unstable_manifold_start, vertical_stability_threshold
from .model import Model
from .simulate import simulate
from .starts import gyroscopic_start, to_chart

__all__ = [
    "Definition",
    "Outcome",
    "Threshold",
    "find_threshold",
    "continue_threshold",
    "threshold_key",
    "threshold_row",
    "DEFAULT_DEFINITIONS",
]


@dataclass(frozen=True)
class Definition:
    """How a jump threshold is measured (everything except a and the family parameter)."""

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
        check_positive("amplitude", self.amplitude)
        check_positive("mu", self.mu)
        if self.eps is not None:
            check_positive("eps", self.eps)

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

    def lower_bound(self, a: float) -> float:
        """Where the seed exists: the fixed point must be unstable (eigenvector seeds) and the
        gyroscopic balance solvable; thresholds are searched above this."""
        body = Spheroid(a)
        if a > 1:
            crit = horizontal_stability_threshold(body.A, body.C, a) or 1.0
        else:
            crit = vertical_stability_threshold(body.A, body.C, a) or 1.0
        return 1.05 * crit

    def start(self, a: float, value: float):
        """(model, x0) for aspect ratio a and Omega0 (a > 1) or n0 (a < 1)."""
        body = Spheroid(a)
        law = self.friction()
        state = "horizontal" if a > 1 else "vertical"
        kw = {"omega0": value} if a > 1 else {"n0": value}
        if self.seed == "sliding":
            if a > 1:
                y0 = gyroscopic_start(body, math.pi / 2 - self.amplitude, omega0=value)
            else:
                y0 = gyroscopic_start(body, self.amplitude, n0=value)
            return Model(body, law, "euler"), to_chart("euler", y0)
        model, x0, _ = unstable_manifold_start(body, law, state=state, delta=self.amplitude, seed_law="viscous", **kw)
        return model, x0

    def outcome(self, a: float, value: float) -> "Outcome":
        """Simulate one trajectory and classify it."""
        model, x0 = self.start(a, value)
        rise = self.rise_margin if a > 1 else math.pi / 2 - self.rise_margin
        r = simulate(model, x0, self.t_max, rtol=self.rtol, rise_theta=rise, track_minima=False, max_steps=self.max_steps)
        if r.status is Status.FAILED:
            return Outcome(value, None, "failed", r.t, r.stuck, r.reason, r.wall_s)
        if r.status is Status.JUMPED:
            return Outcome(value, True, "jumped", r.t, r.stuck, None, r.wall_s)
        how = "rise-complete" if (r.reason or "").startswith("rise complete") else "t_max"
        return Outcome(value, False, how, r.t, r.stuck, None, r.wall_s)


@dataclass(frozen=True)
class Outcome:
    value: float
    jumped: bool | None  # None: the run failed
    how: str  # jumped, rise-complete, t_max, failed
    t: float
    stuck: bool
    reason: str | None
    wall_s: float


@dataclass(frozen=True)
class Threshold:
    """Result of one threshold search.

    ``status``: "converged" (bracket narrower than the tolerance), "non_monotone" (more
    than one jump/no-jump transition: ``transitions`` holds every bracket, ``value`` the
    lowest no-jump -> jump one), "bracket_only" (a run failed inside the bracket, which is
    returned as far as it was narrowed; ``value`` is its geometric midpoint),
    "no_jump_in_range", "jumps_at_lower_bound", or "failed" (no run succeeded).
    """

    a: float
    value: float | None
    bracket: tuple[float | None, float | None]
    status: str
    n_sims: int
    transitions: tuple[tuple[float, float], ...] = ()
    outcomes: tuple[Outcome, ...] = field(default=(), repr=False)
    wall_s: float = 0.0

    @property
    def stuck_near(self) -> bool:
        """Did a trajectory within 5% of the threshold stick (stick event)?"""
        if self.value is None:
            return False
        return any(o.stuck for o in self.outcomes if abs(o.value / self.value - 1) < 0.05)


def _bisect(defn, a, lo, hi, tol, outcomes):
    """Shrink a [no jump, jump] (or reverse) bracket geometrically to relative width tol."""
    o_lo = next(o for o in outcomes if o.value == lo)
    while hi / lo - 1 > tol:
        mid = math.sqrt(lo * hi)
        o = defn.outcome(a, mid)
        outcomes.append(o)
        if o.jumped is None:
            return lo, hi, False
        if o.jumped == o_lo.jumped:
            lo, o_lo = mid, o
        else:
            hi = mid
    return lo, hi, True


def find_threshold(
    defn: Definition, a: float, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
    n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3,
) -> Threshold:
    """Bracket and bisect the jump/no-jump transition in Omega0 (a > 1) or n0 (a < 1).

    A coarse geometric scan (over [lo, hi], or over [guess/window, guess*window] when a
    guess from the neighbouring aspect ratio is given, widened until a transition shows)
    finds every transition on the grid; each is then bisected to relative width ``tol``.
    """
    t0 = time.perf_counter()
    check_positive("a", a)
    if a == 1.0:
        raise ValueError("`a` must differ from 1 (a sphere has no jump threshold: h_theta = 0).")
    lo = defn.lower_bound(a) if lo is None else lo
    outcomes: list[Outcome] = []
    if guess is not None:
        w_lo, w_hi = max(lo, guess / window), min(hi, guess * window)
    else:
        w_lo, w_hi = lo, hi
    trans: list[tuple[float, float]] = []
    for _ in range(30):  # widening steps; each multiplies the window by window**2
        done = {o.value for o in outcomes}
        for v in np.geomspace(w_lo, w_hi, n_coarse):
            if float(v) not in done:
                outcomes.append(defn.outcome(a, float(v)))
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
    wall = lambda: time.perf_counter() - t0  # noqa: E731
    if not trans:
        valid = [o for o in outcomes if o.jumped is not None]
        if any(o.jumped is None for o in outcomes) and not valid:
            return Threshold(a, None, (None, None), "failed", len(outcomes), (), tuple(outcomes), wall())
        if all(o.jumped for o in valid):
            return Threshold(a, None, (None, lo), "jumps_at_lower_bound", len(outcomes), (), tuple(outcomes), wall())
        return Threshold(a, None, (hi, None), "no_jump_in_range", len(outcomes), (), tuple(outcomes), wall())
    brackets, ok = [], True
    for t_lo, t_hi in trans:
        b_lo, b_hi, good = _bisect(defn, a, t_lo, t_hi, tol, outcomes)
        brackets.append((b_lo, b_hi))
        ok = ok and good
    # the threshold: the lowest transition from no jump (below) to jump (above)
    ups = [b for b in brackets if not next(o for o in outcomes if o.value == b[0]).jumped]
    first = ups[0] if ups else brackets[0]
    status = "bracket_only" if not ok else ("non_monotone" if len(brackets) > 1 else "converged")
    value = math.sqrt(first[0] * first[1]) if ups else None
    return Threshold(a, value, first, status, len(outcomes), tuple(brackets), tuple(outcomes), wall())


def continue_threshold(defn: Definition, a_values, **kw) -> list[Threshold]:
    """Thresholds along a list of aspect ratios, each search seeded by the previous result."""
    out, guess = [], None
    for a in a_values:
        th = find_threshold(defn, float(a), guess=guess, **kw)
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


def threshold_key(defn: Definition, a: float, search: dict) -> str:
    """Key of a stored threshold row: every input that changes the answer."""
    return f"{defn.key()}|a={a:.10g}|search={json.dumps(search, sort_keys=True)}"


def threshold_row(prev, defn_fields: dict, a: float, group: str, is_default: bool, search: dict) -> dict:
    """One sweep task: the threshold at aspect ratio ``a`` (the search seeded by the previous
    point's row ``prev``), then the self-consistency check (1.02 x jumps, 0.98 x does not).

    Returns a flat row for the results table; errors become a row with status "failed".
    Lives in the library (not in a study script) so that every Dask worker can import it.
    """
    defn = Definition(**defn_fields)
    t0 = time.perf_counter()
    key = threshold_key(defn, a, search)
    base = dict(key=key, branch="prolate" if a > 1 else "oblate", a=a, definition=defn.label, default=is_default,
                group=group, name=defn.name, seed=defn.seed, amplitude=defn.amplitude, mu=defn.mu, rtol=defn.rtol,
                eps=defn.eps if defn.eps else ("exact" if defn.seed != "viscous" else ""))
    guess = None
    if prev and prev.get("threshold") not in (None, ""):
        guess = float(prev["threshold"])
    try:
        th = find_threshold(defn, a, guess=guess, **search)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        return dict(base, status="failed", transitions=f"error: {exc}", wall_s=time.perf_counter() - t0)
    above = below = consistent = None
    n_check = 0
    if th.value is not None and th.status in ("converged", "non_monotone"):  # not for bracket_only
        o_above, o_below = defn.outcome(a, 1.02 * th.value), defn.outcome(a, 0.98 * th.value)
        n_check = 2
        above, below = o_above.jumped, o_below.jumped
        consistent = bool(above) and below is False
    return dict(
        base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], n_sims=th.n_sims, status=th.status,
        transitions=json.dumps([list(t) for t in th.transitions]), stuck_near=th.stuck_near,
        check_above_jumped=above, check_below_jumped=below, consistent=consistent, n_check_sims=n_check,
        wall_s=time.perf_counter() - t0,
    )
