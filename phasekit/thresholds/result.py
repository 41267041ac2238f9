"""The result of a threshold search: :class:`Threshold` (value, bracket, status, the outcomes
it simulated) and, when asked for, its :class:`Sensitivity` to the seed distance."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from ..errors import SearchStatus
from .outcome import Outcome


@dataclass(frozen=True)
class Sensitivity:
    """How a threshold moves with the definition's seed distance (``amplitude``: d on the
    sliding branch, delta for eigenvector seeds), against the bisection bracket.

    Attributes
    ----------
    amplitudes : tuple of float
        (d/2, d, 2d).
    values : tuple of (float or None)
        The thresholds there (None where there is none).
    brackets : tuple of tuple
        The bisection bracket of each of the three searches.
    statuses : tuple of str
        The status of each of the three searches.
    slope : float or None
        d ln(threshold) / d ln(d), from the two outer points.
    shift : float or None
        The largest relative change of the threshold over the three.
    bracket : float or None
        The relative width of the bisection bracket at d.
    dominant : str or None
        Which of the two is larger ("seed distance" or "bracket").
    n_sims : int
        Simulations of the two extra searches.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.thresholds import result
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2, sensitivity=True, engine='batch')
    >>> isinstance(th.sensitivity, result.Sensitivity), th.sensitivity.amplitudes
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

    Attributes
    ----------
    a : float
        The body's aspect ratio (NaN for a body without one).
    value : float or None
        The threshold, the geometric midpoint of ``bracket``; None where there is none.
    bracket : tuple of (float or None)
        (lo, hi) of the transition; (None, lo) if every run jumped, (hi, None) if none did, (None, None)
        if the search failed.
    status : SearchStatus
        CONVERGED (bracket narrower than the tolerance), NON_MONOTONE (more than one
        jump/no-jump transition: ``transitions`` holds every bracket, ``value`` the lowest
        no-jump -> jump one), BRACKET_ONLY (a run failed inside the bracket, which is returned as
        far as it was narrowed; ``value`` is its geometric midpoint), NO_JUMP_IN_RANGE,
        JUMPS_AT_LOWER_BOUND, or FAILED (no run succeeded).
    n_sims : int
        The number of simulations.
    transitions : tuple of (float, float)
        The bracket of every transition found.
    outcomes : tuple of Outcome
        Every simulation, in the order run.
    wall_s : float
        Wall time of the search, seconds.
    reason : str or None
        Why the search failed or stopped early, else None.
    sensitivity : Sensitivity or None
        Filled when asked (``find_threshold(..., sensitivity=True)``).
    n_rounds : int
        Rounds of mutually independent simulations the search needed (its critical path).
    verification : Verification or None
        What its check found (:mod:`phasekit.thresholds.verify`: the bracket's ends at a ten times
        tighter tolerance); None when not checked (``verify=False``, or no bracket).

    Examples
    --------
    >>> import phasekit as pk
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
    verification: "Verification | None" = None  # noqa: F821 (thresholds.verify, which imports this module)

    @property
    def verified(self) -> bool | None:
        """Did the bracket's ends keep their outcomes at a tighter tolerance (None: not checked)?"""
        return None if self.verification is None else self.verification.verified

    @property
    def stuck_near(self) -> bool:
        """Did a trajectory within 5% of the threshold stick (stick event)?"""
        if self.value is None:
            return False
        return any(o.stuck for o in self.outcomes if abs(o.value / self.value - 1) < 0.05)
