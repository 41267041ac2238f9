"""Steady rolling motions (parts III and IV of the series): :func:`rolling_motion`, the
two-parameter family under exact Coulomb friction with G moving on a circle (the branches of
steady precessions are its members with G at rest), and :func:`rolling_state`, rolling along a
straight line at a static equilibrium (the rolling family of phasekit.steady.families).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._runtime.validate import check_finite
from ..bodies.body import Body
from ..errors import ParameterError


@dataclass(frozen=True)
class RollingMotion:
    """A steady rolling motion under exact Coulomb friction: the axis at a fixed theta
    precessing at Omega, no slip, G moving on a circle (radius ``radius``) with speed V in the
    precessing frame, friction supplying the centripetal force (|F| = Omega |V| <= mu R is
    needed for static friction to hold it: ``needs_mu``). The branches (:func:`phasekit.steady_structure`)
    are its members with V = 0.

    Attributes
    ----------
    theta : float
        Tilt of the axis, radians, in (0, pi).
    Omega : float
        Precession rate, nonzero.
    n : float
        Spin.
    V : float
        Velocity of G in the precessing frame (U = 0).
    radius : float
        Radius |V / Omega| of the circle G moves on.
    needs_mu : float
        Omega |V|, the least mu at which static friction holds the motion (R = 1).
    x : numpy.ndarray
        The state (U, V, Omega, Lambda, theta, n).

    Examples
    --------
    >>> import phasekit as pk
    >>> r = pk.steady.rolling_motion(pk.Spheroid(1.5), 1.0, 5.0)
    >>> isinstance(r, pk.steady.rolling.RollingMotion), round(r.needs_mu, 6)
    (True, 1.439896)
    """

    theta: float
    Omega: float
    n: float
    V: float
    radius: float
    needs_mu: float
    x: np.ndarray = field(repr=False)


def rolling_motion(body, theta: float, Omega: float) -> RollingMotion:
    """The steady rolling motion with axis angle ``theta`` and precession rate ``Omega``.

    Derived from (2.7) with Lambda = 0 and zero slip (U = 0, V = -Omega h_theta - (n - Omega cos)
    x_P): (2.7c) and (2.7b) give F_y = 0, (2.7a) F_X = -Omega V, and (2.7d) with R = 1

        n = [A Omega^2 s c - h_theta (1 + h Omega^2) + h Omega^2 c x_P] / (Omega (C s + h x_P)).

    A two-parameter family (theta, Omega); with V = 0 it reduces to the branches. An egg that
    settles tilted under Coulomb friction ends on it (studies/steady_structure.py).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).
    theta : float
        Tilt of the axis from the vertical, radians, in (0, pi).
    Omega : float
        Precession rate, finite and nonzero.

    Returns
    -------
    RollingMotion
        The motion, with its spin n, speed V, radius and the mu it needs.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``theta`` is not in (0, pi) or ``Omega`` is zero or not finite.

    Examples
    --------
    >>> import phasekit as pk
    >>> r = pk.steady.rolling_motion(pk.Spheroid(1.5), 1.0, 5.0)
    >>> round(r.n, 6), round(r.radius, 6)
    (5.678572, 0.057596)
    """
    if not isinstance(body, Body):
        raise ParameterError("body", "must be a phasekit Body", body)
    theta = check_finite("theta", theta)
    if not 0.0 < theta < np.pi:
        raise ParameterError("theta", "must lie in (0, pi) (at the poles the axis does not precess)", theta)
    Omega = check_finite("Omega", Omega)
    if Omega == 0.0:
        raise ParameterError("Omega", "must be nonzero (a body at rest is a static equilibrium)", Omega)
    h, ht, _ = body.h(theta)
    s, c = np.sin(theta), np.cos(theta)
    xP = h * s + ht * c
    n = (body.A * Omega**2 * s * c - ht * (1 + h * Omega**2) + h * Omega**2 * c * xP) / (Omega * (body.C * s + h * xP))
    V = -Omega * ht - (n - Omega * c) * xP
    return RollingMotion(float(theta), float(Omega), float(n), float(V), float(abs(V / Omega)), float(abs(Omega * V)),
                         np.array([0.0, V, Omega, 0.0, theta, n]))


def rolling_state(body, theta: float, n: float) -> np.ndarray:
    """Rolling along a straight line at a static equilibrium theta (h_theta = 0): Omega = 0,
    Lambda = 0, zero slip, so V = -n x_P (paper's variables)."""
    h, ht, _ = body.h(theta)
    xP = h * np.sin(theta) + ht * np.cos(theta)
    return np.array([0.0, -n * xP, 0.0, 0.0, theta, n])
