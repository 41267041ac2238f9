"""The static equilibria and the non-isolated families of steady states of a body (parts III
and IV of the series): the spins about the vertical at the poles, the precessions at any rate
where q = D = 0 (phasekit.steady.branches, module notes) and the rolling along a straight line
at a tilted static equilibrium, each with the values of its parameter where its stability
changes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._runtime.watch import check_deadline
from ..core.charts import EULER
from ..theory.criteria import PoleCriterion, pole_stability_threshold
from .branch_stability import linearise_precession
from .branches import family_rate2, holds_state, precession_geometry
from .linearisation import linearise
from .rolling import rolling_state


@dataclass(frozen=True)
class StaticEquilibrium:
    """G straight above the contact point (h_theta = 0), at rest: ``stable`` where the height of
    G is a minimum (h_tt > 0), ``kind`` "pole" at theta = 0 or pi, else "tilted"."""

    theta: float
    height: float
    h_tt: float
    kind: str

    @property
    def stable(self) -> bool:
        return self.h_tt > 0

    def to_dict(self) -> dict:
        return {"theta": self.theta, "kind": self.kind, "height": self.height, "h_tt": self.h_tt,
                "static_stability": "minimum (stable)" if self.h_tt > 0 else "maximum (unstable)" if self.h_tt < 0
                else "degenerate"}


@dataclass(frozen=True)
class SpinFamily:
    """A non-isolated family of steady states at one theta, with any value of its parameter:

    * ``pole``: the spin about the vertical at theta = 0 or pi (parameter "n");
    * ``precession``: where q = D = 0, a precession at any rate Omega with n = 0 (part I's
      horizontal state of a flip-symmetric body);
    * ``rolling``: at a tilted static equilibrium, rolling along a straight line at any spin n
      (Omega = 0, G moving at n x_P: part I's rolling on the equator).

    ``criticals`` are the values of abs(parameter) where its stability changes (the closed-form
    pole criterion of the law's linearisation: under exact Coulomb friction the rolling one, the
    fast-top condition, with the sliding one in ``sliding_criticals``; for a precession family
    the rate at which a branch crosses it; located by bisection for a rolling family),
    ``stable_on`` the stability on each interval between them from 0 up (None: not computed),
    ``branch_meets`` whether a branch ends on or crosses the family."""

    kind: str
    theta: float
    parameter: str
    criticals: tuple[float, ...]
    stable_on: tuple[bool | None, ...]
    branch_meets: bool
    criterion: PoleCriterion | None = field(default=None, repr=False)
    sliding_criticals: tuple[float, ...] | None = None

    @property
    def critical(self) -> float | None:
        return self.criticals[0] if self.criticals else None

    @property
    def stable_above(self) -> bool | None:
        """Whether the family is stable beyond its last critical value (None without one)."""
        return self.stable_on[-1] if self.criticals else None

    def to_dict(self) -> dict:
        return {"kind": self.kind, "theta": self.theta, "parameter": self.parameter, "critical": self.critical,
                "criticals": list(self.criticals), "stable_on_intervals": list(self.stable_on),
                "stable_above_critical": self.stable_above, "branch_meets": self.branch_meets,
                "sliding_criticals": None if self.sliding_criticals is None else list(self.sliding_criticals)}


# -- statics and families -----------------------------------------------------------------------


def statics_of(body, pts) -> tuple[StaticEquilibrium, ...]:
    thetas = [0.0] + [p.theta for p in pts if p.q] + [np.pi]
    h, htt = precession_geometry(body, thetas)[4:6]
    return tuple(StaticEquilibrium(float(t), float(h[i]), float(htt[i]), "pole" if t in (0.0, np.pi) else "tilted")
                 for i, t in enumerate(thetas))


def families_of(model, body, pts, intervals, stability: bool) -> tuple[SpinFamily, ...]:
    """The families of ``body``: the spins about the vertical at its poles, and at its special
    points ``pts`` (Edge records) the precession and rolling families, said to meet a branch
    where one of the branches' ``intervals`` (Interval records, ends classified) ends or crosses
    there."""
    ends = {e.pole for p in intervals for e in p.ends if e.kind == "pole"}
    static_ends = {e.theta for p in intervals for e in p.ends if e.kind == "static"}
    out = []
    for pole, t in (("upright", 0.0), ("inverted", np.pi)):
        if not holds_state(body, t):  # an edged body's pole off its range (a disk lying flat)
            continue
        crit = pole_stability_threshold(body, pole)
        sliding = (crit.threshold,) if crit.threshold else ()
        if model.friction.has_rolling_mode:  # exact Coulomb: the rolling spectrum, as along the branches
            crits = (crit.rolling_threshold,) if crit.rolling_threshold else ()
            side = (False, True) if crits else (crit.stable_rolling(1.0),)
        else:
            crits = sliding
            side = (not crit.stable_above, crit.stable_above) if crit.threshold else (crit.stable(1.0),)
        out.append(SpinFamily("pole", t, "n", crits, side, ("0" if t == 0.0 else "pi") in ends, crit,
                              sliding if model.friction.has_rolling_mode else None))
    crossed = {c for p in intervals for c in p.crossings}
    for p in pts:
        if p.q and p.D:
            om2 = family_rate2(body, p.theta)
            crit = float(np.sqrt(om2)) if om2 > 0 else None
            side = _precession_family_side(model, p.theta, crit) if stability else None
            out.append(SpinFamily("precession", p.theta, "Omega", (crit,) if crit else (),
                                  (None if side is None else not side, side) if crit else (None,), p.theta in crossed))
        if p.q:
            crits, side = _rolling_family(model, p.theta) if stability else ((), (None,))
            out.append(SpinFamily("rolling", p.theta, "n", crits, side, p.theta in static_ends or p.theta in crossed))
    return tuple(out)


def _precession_family_side(model, theta: float, crit: float | None) -> bool | None:
    """Whether the precession family at ``theta`` (n = 0 there) is stable above its critical rate
    (None when the linearisation does not change there)."""
    if crit is None:
        return None
    below = linearise_precession(model, theta, 0.8 * crit, 0.0, chart="euler")
    above = linearise_precession(model, theta, 1.25 * crit, 0.0, chart="euler")
    if below.stable == above.stable:
        return None
    return bool(above.stable)


#: the spins scanned for changes of stability of a rolling family
ROLLING_SCAN = np.geomspace(1e-2, 1e3, 101)


def _rolling_family(model, theta: float) -> tuple[tuple[float, ...], tuple[bool, ...]]:
    """The spins where the straight rolling at ``theta`` changes stability (scan, then bisection
    in log n to 1e-10 relative) and the stability between them."""
    me = model if model.chart is EULER else model.with_chart("euler")

    def count(n):
        check_deadline()
        return linearise(me, rolling_state(model.body, theta, n), kind="rolling").n_unstable

    counts = [count(n) for n in ROLLING_SCAN]
    crits = []
    for k in np.flatnonzero(np.diff(counts) != 0):
        lo, hi = np.log(ROLLING_SCAN[k]), np.log(ROLLING_SCAN[k + 1])
        c_lo = counts[k]
        while hi - lo > 1e-10:
            mid = 0.5 * (lo + hi)
            if count(np.exp(mid)) == c_lo:
                lo = mid
            else:
                hi = mid
        crits.append(float(np.exp(0.5 * (lo + hi))))
    side = tuple(bool(counts[0] == 0) if i == 0 else bool(counts[k + 1] == 0)
                 for i, k in enumerate([-1, *np.flatnonzero(np.diff(counts) != 0)]))
    return tuple(crits), side
