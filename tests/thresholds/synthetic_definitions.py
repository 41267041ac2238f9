"""Threshold definitions whose 'trajectories' are known answers, with no simulation: searches
checked against the truth."""

import math
from dataclasses import dataclass

import phasekit as pk
from phasekit.thresholds import Definition, Outcome


@dataclass(frozen=True)
class Synthetic(Definition):
    """A definition whose 'trajectory' jumps on a known set of intervals (no simulation)."""

    intervals: tuple = ((9.3, math.inf),)

    def outcome(self, a, value):
        jumped = any(lo <= value < hi for lo, hi in self.intervals)
        return Outcome(value, jumped, pk.Status.JUMPED if jumped else pk.Status.STOPPED, 0.0, False, None, 0.0)

    def lower_bound(self, a):
        return 2.0


def synthetic(intervals):
    return Synthetic("synthetic", "sliding", intervals=intervals)


@dataclass(frozen=True)
class PowerLaw(Definition):
    """A definition whose 'trajectory' jumps above value* = c d^-p and sticks below
    d_min = k / value^2 (no simulation): known thresholds, boundaries and sensitivity."""

    c: float = 9.3
    p: float = 0.1
    k: float = 0.5

    def outcome(self, body, value):
        if self.amplitude < self.k / value**2:
            return Outcome(value, False, pk.Status.COMPLETED, 3000.0, True, None, 0.0)
        jumped = value >= self.c * self.amplitude ** -self.p
        return Outcome(value, jumped, pk.Status.JUMPED if jumped else pk.Status.STOPPED, 1.0, False, None, 0.0)

    def lower_bound(self, body):
        return 2.0


def power_law(**kw):
    return PowerLaw("power-law", "sliding", amplitude=kw.pop("amplitude", 0.05), **kw)
