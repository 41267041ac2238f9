"""Initial states in the paper's variables (U, V, Omega, Lambda, theta, n).

A gyroscopic start puts the body on the slow manifold: Lambda = U = V = 0 and the
leading-order gyroscopic balance (3.14c),

    (A Omega cos(theta) - C n) sin(theta) = h_theta / Omega,

holds. Given Omega0 (prolate) it fixes n; given n0 (oblate) it is a quadratic in Omega,
A cos(theta) Omega^2 - C n0 Omega - h_theta/sin(theta) = 0, whose fast root
(|Omega| ~ C n0 / (A cos theta)) is the gyroscopic branch. h_theta/sin(theta) = -H'(cos theta)
is regular at theta = 0, so the oblate start works down to the vertical.
"""

from __future__ import annotations

import numpy as np

from .body import Body
from .charts import euler_to_vector
from .errors import check_finite, check_open_interval, check_vector

__all__ = ["gyroscopic_start", "raw_start", "to_chart", "balance_residual"]


def _q(body: Body, theta: float) -> float:
    """h_theta / sin(theta) = -H'(cos theta), evaluated without dividing by sin(theta)."""
    return -body.height_slope(np.cos(theta))[1]


def gyroscopic_start(body: Body, theta0: float, *, omega0: float | None = None, n0: float | None = None) -> np.ndarray:
    """A start on the slow (gyroscopic-balance) manifold.

    Parameters
    ----------
    body : Body
    theta0 : float in (0, pi)
        Initial inclination of the symmetry axis.
    omega0 : float, optional
        Precession rate (prolate starts near the horizontal): n follows from the balance.
    n0 : float, optional
        Spin (oblate starts near the vertical): Omega is the fast root of the balance.

    Returns
    -------
    array (6,): (U, V, Omega, Lambda, theta, n) = (0, 0, Omega0, 0, theta0, n).
    """
    theta0 = check_open_interval("theta0", theta0, 0.0, np.pi, "(0, pi)")
    if (omega0 is None) == (n0 is None):
        raise ValueError("give exactly one of `omega0` (prolate) or `n0` (oblate).")
    A, C = body.A, body.C
    c = np.cos(theta0)
    q = _q(body, theta0)
    if omega0 is not None:
        omega0 = check_finite("omega0", omega0)
        if omega0 == 0.0:
            raise ValueError("`omega0` must be a finite nonzero number, got 0.0.")
        n = (A * omega0 * c - q / omega0) / C
        return np.array([0.0, 0.0, omega0, 0.0, theta0, n])
    n0 = check_finite("n0", n0)
    if n0 == 0.0:
        raise ValueError("`n0` must be a finite nonzero number, got 0.0.")
    if c <= 0.0:
        raise ValueError(f"`theta0` must lie in (0, pi/2) for a start given n0 (fast branch), got {theta0!r}.")
    disc = (C * n0) ** 2 + 4.0 * A * c * q
    if disc < 0.0:
        need = np.sqrt(max(-4.0 * A * c * q, 0.0)) / C
        raise ValueError(f"`n0` must satisfy |n0| > {need:.6g} for a gyroscopic balance at theta0 = {theta0:g}, got {n0!r}.")
    omega = (C * n0 + np.sign(n0) * np.sqrt(disc)) / (2.0 * A * c)
    return np.array([0.0, 0.0, omega, 0.0, theta0, n0])


def balance_residual(body: Body, y) -> float:
    """(A Omega cos - C n) sin - h_theta/Omega at a state: zero on a gyroscopic start."""
    U, V, Om, Lam, th, n = np.asarray(y, dtype=float)
    return (body.A * Om * np.cos(th) - body.C * n) * np.sin(th) - _q(body, th) * np.sin(th) / Om


def raw_start(state, *, chart: str = "euler") -> np.ndarray:
    """Validate a raw (U, V, Omega, Lambda, theta, n); theta in (0, pi), or [0, pi] for the
    vector chart, which is regular at the poles."""
    y = check_vector("state", state, 6)
    if chart == "euler":
        check_open_interval("theta", y[4], 0.0, np.pi, "(0, pi) in the euler formulation (use --formulation vector at 0 or pi)")
    elif not 0.0 <= y[4] <= np.pi:
        raise ValueError(f"`theta` must lie in [0, pi], got {y[4]!r}.")
    return y


def to_chart(chart: str, y) -> np.ndarray:
    """A state in the paper's variables expressed in ``chart`` coordinates."""
    y = np.asarray(y, dtype=float)
    return y.copy() if chart == "euler" else euler_to_vector(y)
