"""Settled runs: a body that rolls in a steady state ends its run with status "settled".

Under exact Coulomb friction a body can stop rising and settle: it rolls (zero slip) in a
steady precession, or alternates stick and slip in brief re-slips around one (an egg settles
tilted, with thousands of stick-slip cycles). Rolling does no work, so such a run can go on
to its end time without ever jumping, at the price of one integration per cycle. With the
option ``settle`` (:class:`Settle`) a run ends as soon as it has settled.

The rule, checked at each stick event (the slip has just returned to zero), over the last
``window`` time units:

1. contact throughout (no lift-off, no flight);
2. zero slip: the body rolled for at least half of the window, and no sliding stretch lasted
   longer than ``window / 10`` (the slip keeps returning to zero);
3. a steady state: at every event of the window, theta lies within ``tol`` (rad) of its mean
   over the window, and each of U, V, Omega, Lambda, n within ``tol`` times the rate scale
   1 + |Omega| + |n| of its mean; and the normal reaction R is at least ``R_floor`` (the weight
   is 1).

Only a law with an exact rolling mode (:class:`phasekit.Coulomb`) settles: a regularised law
keeps a small slip while "rolling", and its field stays dissipative.

A roll also settles one period after it starts, exactly (:func:`rolls_periodically`): rolling
without slip is integrable for a body of revolution on a plane (Chaplygin: with the energy, two
integrals linear in the rates reduce it to one degree of freedom in theta), so theta oscillates
between two turning points and every reduced variable (U, V, Omega, Lambda, theta, n, hence R and
the friction needed) is a function of the phase of that oscillation. Two successive maxima of theta
(Lambda falling through 0) with the same state close a period; neither R nor the friction margin
nor any other guard reached its zero over it, so none ever will. The state at the two maxima is
compared (to PERIOD_TOL times the run's tolerance): a check of the integrability, not an assumption.
Bodies whose contact passes between pieces (a tippe top with its stem) are left out, and so are
dissipation laws (the body comes to rest instead).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .._runtime.validate import check_range
from .hybrid import Mode, Record, Transition
from .observables import evaluate_function

CONTACT_MODES = ("sliding", "rolling", "edge", "off_edge")  # on the cone's edge the slip is not zero: a sliding stretch
#: the name of the turn of theta while rolling (a maximum: Lambda falls through 0)
TURN = "turn"
#: two maxima of theta close a period when their states agree to this times the run's tolerance, in
#: theta and in the rates relative to 1 + |Omega| + |n|. Measured drift per period at rtol 1e-9: 2.4e-11
#: (oblate a = 0.85, n0 = 20), so 1e3 leaves room for rounding, not for a motion that is not periodic
PERIOD_TOL = 1e3


@dataclass(frozen=True, kw_only=True)
class Settle:
    """When a run has settled (see :mod:`phasekit.core.settle` for the rule).

    Attributes
    ----------
    window : float, default 20
        Time (units sqrt(b/g)) over which the body must have rolled in a steady state.
    tol : float, default 0.01
        Steadiness: theta within ``tol`` rad of its mean over the window, the rates within
        ``tol`` times ``1 + abs(Omega) + abs(n)``.
    R_floor : float, default 0.5
        Smallest normal reaction (units M g) allowed at the window's events.

    Raises
    ------
    ParameterError
        If ``window`` is outside (0, 1e6], ``tol`` outside (0, 1] or ``R_floor`` outside
        [0, 1].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.Settle()
    Settle(window=20.0, tol=0.01, R_floor=0.5)
    """

    window: float = 20.0
    tol: float = 0.01
    R_floor: float = 0.5

    def __post_init__(self):
        object.__setattr__(self, "window", check_range("window", self.window, 0.0, 1e6, closed="r"))
        object.__setattr__(self, "tol", check_range("tol", self.tol, 0.0, 1.0, closed="r"))
        object.__setattr__(self, "R_floor", check_range("R_floor", self.R_floor, 0.0, 1.0, closed="lr"))

    def to_dict(self) -> dict:
        return asdict(self)


def check_settle(value) -> Settle | None:
    """None, False (no rule), True (the default :class:`Settle`), a Settle, or its dict."""
    from ..errors import ParameterError

    if value is None or value is False:
        return None
    if value is True:
        return Settle()
    if isinstance(value, Settle):
        return value
    if isinstance(value, dict):
        unknown = sorted(set(value) - {"window", "tol", "R_floor"})
        if unknown:
            raise ParameterError("settle", f"has no field {unknown[0]!r} (fields: window, tol, R_floor)", value)
        return Settle(**value)
    raise ParameterError("settle", "must be None, True, or a phasekit Settle(window=..., tol=...)", value)


def _window(records, t_from: float):
    """The records inside [t_from, now] in time order, and the mode in force at t_from
    (None if no record precedes the window)."""
    inside = []
    for r in reversed(records):
        if r.name == TURN:  # a turn of theta inside a roll (rolls_periodically) changes no mode
            continue
        if r.t < t_from:
            return inside[::-1], r.mode_after
        inside.append(r)
    return inside[::-1], None


def _rolled(inside, mode_from: str, t_from: float, t_now: float, window: float) -> bool:
    """Contact throughout, rolling at least half of the time, no long sliding stretch."""
    mode, t, rolling, longest = mode_from, t_from, 0.0, 0.0
    for r in inside:
        if mode not in CONTACT_MODES or r.mode_after not in CONTACT_MODES:
            return False
        span = r.t - t
        if mode == "rolling":
            rolling += span
        else:
            longest = max(longest, span)
        mode, t = r.mode_after, r.t
    return mode == "rolling" and rolling >= 0.5 * (t_now - t_from) and longest <= window / 10


def _steady(model, inside, settle: Settle) -> bool:
    Y = np.array([r.y for r in inside if r.y is not None])
    if len(Y) < 2:
        return False
    dev = np.abs(Y - Y.mean(axis=0)).max(axis=0)
    scale = 1.0 + abs(Y[-1, 2]) + abs(Y[-1, 5])  # 1 + |Omega| + |n|
    if dev[4] > settle.tol or np.any(dev[[0, 1, 2, 3, 5]] > settle.tol * scale):
        return False
    X = np.array([r.x for r in inside if r.x is not None and r.mode_after in CONTACT_MODES])
    modes = [Mode(r.mode_after) for r in inside if r.x is not None and r.mode_after in CONTACT_MODES]
    for mode in set(modes):
        sel = np.array([m is mode for m in modes])
        R = np.atleast_1d(evaluate_function(model.observable("R", mode), model.p, X[sel]))
        if np.any(R < settle.R_floor):
            return False
    return True


def settled(model, records, t_start: float, settle: Settle, rtol: float = 1e-9) -> str | None:
    """The reason the run has settled by its last record, or None (see the module's rule; ``rtol``
    is the run's tolerance, for :func:`rolls_periodically`)."""
    if not records or not model.friction.has_rolling_mode or model.friction.dissipation:
        return None  # with dissipation laws no roll is steady: the body comes to rest instead
    if records[-1].name == TURN:
        return rolls_periodically(records, rtol)
    last = records[-1]
    if last.name != "stick" or last.mode_after != "rolling" or last.t - settle.window < t_start:
        return None
    t_from = last.t - settle.window
    inside, mode_from = _window(records, t_from)
    if mode_from is None or not _rolled(inside, mode_from, t_from, last.t, settle.window):
        return None
    if not _steady(model, inside, settle):
        return None
    return (f"settled: rolled in a steady state for {settle.window:g} time units (theta within {settle.tol:g} of "
            f"{float(np.mean([r.y[4] for r in inside if r.y is not None])):.6g}, R >= {settle.R_floor:g})")


def rolls_periodically_here(model) -> bool:
    """Whether ``model``'s rolling is periodic in the reduced state (module notes): an exact rolling
    mode, no dissipation laws, one smooth piece of contact."""
    law = model.friction
    return law.has_rolling_mode and not law.dissipation and not model.body.transfers


def rolls_periodically(records, rtol: float) -> str | None:
    """The reason a roll has settled at its latest turn of theta, or None: the turn before it, with
    nothing between them, has the same state (see the module's notes).

    Parameters
    ----------
    records : sequence of EventRecord
        The run's log so far; its last record is a turn of theta while rolling.
    rtol : float
        The run's tolerance.

    Returns
    -------
    str or None
        The reason (the period and how closely the state repeated), or None.
    """
    if len(records) < 2:
        return None
    a, b = records[-2], records[-1]
    if a.name != TURN or b.name != TURN or a.y is None or b.y is None:
        return None
    scale = np.ones(6)
    scale[[0, 1, 2, 3, 5]] = 1.0 + abs(b.y[2]) + abs(b.y[5])  # 1 + |Omega| + |n|
    miss = float(np.max(np.abs(b.y - a.y) / scale))
    if miss > PERIOD_TOL * rtol:
        return None
    return (f"settled: rolls periodically (period {b.t - a.t:.6g}, the state at two maxima of theta agrees to "
            f"{miss:.1e}): no slip, lift-off or stop over a period, so none later")


class Turn:
    """The reset of a turn of theta while rolling: logged, and the segment goes on (the run's loop
    then applies the settle rule, :func:`rolls_periodically`)."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        return Transition(mode, t, x, (Record(TURN, mode.value, mode.value, x, ""),), resume=True)
