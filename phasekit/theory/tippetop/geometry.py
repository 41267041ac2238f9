"""Checks of the tippe top's parameters and the functions of z = cos(theta) that the others share.

The model, the units and the status of every result: :mod:`phasekit.theory.tippetop`.
"""

from __future__ import annotations

import math

from ..._runtime.validate import check_positive, check_range


def _alpha(alpha) -> float:
    return check_range("alpha", alpha, 0.0, 1.0, label="(0, 1) (G strictly between O and the surface)")

def params(alpha, A, C) -> tuple[float, float, float]:
    return _alpha(alpha), check_positive("A", A), check_positive("C", C)

def theta0_of(theta0) -> float:
    return check_range("theta0", theta0, 0.0, math.pi, closed="lr", label="[0, pi]")

def f_of(z, alpha, A, C):
    """d.I d = A sin^2 + C (cos - alpha)^2 at z = cos(theta)."""
    return A * (1.0 - z * z) + C * (z - alpha) ** 2

def D_of(z, alpha, A, C):
    return (A - C) * z + C * alpha

def margins(a, A, C) -> tuple[float, float]:
    """(A - C (1 - alpha), C (1 + alpha) - A) = (D(1), D(-1)): both > 0 iff gamma is in the
    classical interval. Every function tests the boundaries through these two numbers, so
    they agree with each other exactly, also under rounding."""
    return A - C * (1.0 - a), C * (1.0 + a) - A


# -------------------------------------------------------------- 1. inversion condition
