"""Free flight after lift-off (section 4): the exact solution, and flights on their own.

The numerical flight is the FLIGHT mode of the hybrid system (:mod:`phasekit.core.system`):
the rigid-body equations of the vector chart with no contact force, plus the gap
Delta (4.1) and its rate as states. At lift-off R = 0 and the friction (proportional to R)
vanishes, so no impulse acts: positions and velocities carry over, and so do accelerations.

Exact solution (4.6)-(4.14): Omega - Psi cot(theta) = C1, Psi^2 + thetadot^2 = C2^2,
Omega cos(theta) - Psi / sin(theta) = n0, and cos(theta(t)) of (4.12); the gap (4.1) follows.
Near lift-off, in the gyroscopic limit, Delta ~ Omega*^2 t^3 (4 W* - t) / 24 (4.22), with
maximum 9/8 Omega*^2 W*^4 at t = 3 W* (4.23).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_finite, check_vector, finite_result
from ..bodies.body import Body
from ..errors import ParameterError


@dataclass(frozen=True)
class FlightConstants:
    """Constants of the exact free motion (4.6)-(4.14), from the state at lift-off.

    Attributes
    ----------
    theta : float
        Inclination theta* at lift-off, radians.
    thetadot : float
        Its rate Lambda* = dtheta/dt at lift-off, units sqrt(g/b).
    Omega : float
        Precession rate Omega* at lift-off, units sqrt(g/b).
    Psi : float
        Psi* = (A Omega* cos(theta*) - C n*) sin(theta*) / A (3.1), units sqrt(g/b).
    n : float
        Spin n* at lift-off, units sqrt(g/b).
    W : float
        Vertical velocity W* of G at lift-off, units sqrt(g b).
    h : float
        Height h(theta*) of G at lift-off, units b.
    C1 : float
        C1 = Omega* - Psi* cot(theta*) (4.6).
    C2 : float
        C2 = sqrt(Psi*^2 + Lambda*^2) (4.7).
    C1p : float
        C1' = Psi* / sin(theta*) - Omega* cos(theta*).
    C3 : float
        C3 = sqrt(C1^2 + C2^2), the angular frequency of cos(theta(t)) in (4.12).
    C4 : float
        C4 = C1 C1' / C3^2, so that cos(theta(t)) oscillates about -C4 (4.12).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> k = pk.theory.flight_constants(body, pk.gyroscopic_start(body, 1.0, omega0=10.0), 0.01)
    >>> isinstance(k, pk.theory.flight.FlightConstants), round(k.h, 6)
    (True, 1.168293)
    """

    theta: float
    thetadot: float
    Omega: float
    Psi: float
    n: float
    W: float
    h: float
    C1: float
    C2: float
    C1p: float
    C3: float
    C4: float


@finite_result
def flight_constants(body: Body, euler_state, W: float) -> FlightConstants:
    """(4.5)-(4.14) from (U, V, Omega, Lambda, theta, n) at lift-off and the vertical velocity W*.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    euler_state : array_like
        The paper's state (U, V, Omega, Lambda, theta, n) at lift-off: 6 finite numbers, theta
        off the poles (abs(sin(theta)) >= 1e-12).
    W : float
        Vertical velocity W* of G at lift-off, units sqrt(g b), finite.

    Returns
    -------
    FlightConstants
        The state at lift-off with h(theta*) and the constants C1, C2, C1', C3, C4.

    Raises
    ------
    ParameterError
        If ``euler_state`` is not 6 finite numbers or has theta at a pole (where (4.5)-(4.14)
        divide by sin(theta)), ``W`` is not finite, or the result is not finite (an overflow of
        double precision or a singular configuration), naming the argument of largest magnitude.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0,
    ...                    stop_at='touchdown', rtol=1e-12)
    >>> fl = traj.flights[0]
    >>> k = pk.theory.flight_constants(body, traj.x_jump, fl.W_star)
    >>> isinstance(k, pk.theory.flight.FlightConstants), round(k.W, 6)
    (True, 0.006382)
    """
    _, _, Om, Lam, th, n = (float(v) for v in check_vector("euler_state", euler_state, 6))
    W = check_finite("W", W)
    if abs(np.sin(th)) < 1e-12:
        raise ParameterError("euler_state", "has theta at a pole, where (4.5)-(4.14) divide by sin(theta)", th)
    A, C = body.A, body.C
    s, c = np.sin(th), np.cos(th)
    Psi = (A * Om * c - C * n) * s / A  # (3.1)
    C1 = Om - Psi * c / s
    C2 = np.sqrt(Psi**2 + Lam**2)
    C1p = Psi / s - Om * c
    C3 = np.sqrt(C1**2 + C2**2)
    C4 = C1 * C1p / C3**2
    return FlightConstants(th, Lam, Om, Psi, n, W, body.h(th)[0], C1, C2, C1p, C3, C4)


@finite_result
def cos_theta_exact(k: FlightConstants, t):
    """(4.12): cos(theta(t)) of the free motion, t measured from lift-off."""
    t = np.asarray(t, dtype=float)
    return -k.C4 - k.thetadot * np.sin(k.theta) * np.sin(k.C3 * t) / k.C3 + (np.cos(k.theta) + k.C4) * np.cos(k.C3 * t)


@finite_result
def gap_exact(body: Body, k: FlightConstants, t):
    """(4.1) with (4.12): Delta(t) = h* + W* t - t^2/2 - h(theta(t)).

    Parameters
    ----------
    body : Body
        The body that lifted off (the one ``k`` was computed for).
    k : FlightConstants
        The constants of the flight, from :func:`flight_constants`.
    t : float or array_like
        Times since lift-off, units sqrt(b/g).

    Returns
    -------
    numpy.ndarray
        The gap Delta(t) between the body and the table, units b, of the shape of ``t``.

    Raises
    ------
    ParameterError
        If the result is not finite (an overflow of double precision or a singular configuration),
        naming the argument of largest magnitude.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> k = pk.theory.flight_constants(body, pk.gyroscopic_start(body, 1.0, omega0=10.0), 0.01)
    >>> pk.theory.gap_exact(body, k, [0.0, 1e-3]).round(12)
    array([0.000000e+00, 9.317979e-06])
    """
    th = np.arccos(np.clip(cos_theta_exact(k, t), -1.0, 1.0))
    return k.h + k.W * np.asarray(t) - 0.5 * np.asarray(t) ** 2 - body.h(th)[0]


@finite_result
def gap_series(Omega: float, W: float, t):
    """(4.22): Delta ~ Omega*^2 t^3 (4 W* - t) / 24.

    Parameters
    ----------
    Omega : float
        Precession rate Omega* at lift-off, units sqrt(g/b).
    W : float
        Vertical velocity W* of G at lift-off, units sqrt(g b).
    t : float or array_like
        Times since lift-off, units sqrt(b/g).

    Returns
    -------
    numpy.ndarray
        The gap Delta(t) of the gyroscopic limit near lift-off, units b, of the shape of ``t``.

    Raises
    ------
    ParameterError
        If the result is not finite (an overflow of double precision or a singular configuration),
        naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.gap_series(9.0, 0.006, [0.0, 0.01]).round(12)
    array([0.000e+00, 4.725e-08])
    """
    t = np.asarray(t, dtype=float)
    return Omega**2 * t**3 * (4 * W - t) / 24.0


@finite_result
def gap_max_series(Omega: float, W: float) -> tuple[float, float]:
    """(4.23): (Delta_max, t at the maximum) = (9/8 Omega*^2 W*^4, 3 W*).

    Parameters
    ----------
    Omega : float
        Precession rate Omega* at lift-off, units sqrt(g/b).
    W : float
        Vertical velocity W* of G at lift-off, units sqrt(g b).

    Returns
    -------
    tuple of float
        (Delta_max, t_max): the largest gap of (4.22), units b, and its time since lift-off,
        units sqrt(b/g).

    Raises
    ------
    ParameterError
        If the result is not finite (an overflow of double precision or a singular configuration),
        naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> [f'{v:.4e}' for v in pk.theory.gap_max_series(9.0, 0.006)]
    ['1.1810e-07', '1.8000e-02']
    """
    return 9.0 / 8.0 * Omega**2 * W**4, 3.0 * W


@finite_result
def flight_invariants(body: Body, euler_states) -> np.ndarray:
    """(4.6)-(4.8) along a flight: columns C1 = Omega - Psi cot, C2^2 = Psi^2 + thetadot^2,
    n0 = Omega cos - Psi / sin (all constant in free flight)."""
    Y = np.atleast_2d(np.asarray(euler_states, dtype=float))
    Om, Lam, th = Y[:, 2], Y[:, 3], Y[:, 4]
    n = Y[:, 5]
    s, c = np.sin(th), np.cos(th)
    Psi = (body.A * Om * c - body.C * n) * s / body.A
    return np.column_stack([Om - Psi * c / s, Psi**2 + Lam**2, Om * c - Psi / s])
