"""The jump surface (6.3) in (Omega, theta, n) and the exact boundary R = 0, in closed form and
by root finding.

Section 6: in the gyroscopic region R = 0 is close to the 2-D surface (6.3),

    n = (A/C) (Omega cos(theta) + 1 / (Omega h_theta sin(theta))),

which is (6.1) with the Lambda^2 term dropped. The exact boundary is 5-dimensional; its section
at given Lambda (and the gyroscopic slip direction, which only enters the denominator of (6.1))
is n = (A/C) (Omega cos(theta) + (1 + h_tt Lambda^2) / (Omega h_theta sin(theta))).
:func:`exact_boundary` finds it independently, by root finding on the model's normal reaction;
at Lambda = 0 it coincides with (6.3), and trajectories cross R = 0 with Lambda != 0 (the fast
nutation), which is where (6.3) and the crossings differ.

The 3-D scenes that draw them are :mod:`phasekit.theory.surface`'s.
"""

from __future__ import annotations

import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_array, check_finite, check_instance, check_nonnegative
from ..bodies.body import Body
from ..core.model import Model
from ..friction.laws import Coulomb, FrictionLaw

__all__ = ["surface_n", "exact_boundary"]


def _body(body) -> Body:
    return check_instance("body", body, Body, "Spheroid(1.5)")


def _check_grid(body: Body, Omega, theta) -> tuple[np.ndarray, np.ndarray]:
    """Omega and theta as float arrays of shapes that broadcast together: finite, Omega != 0,
    theta in (0, pi) and away from the angles where (6.3) is infinite (h_theta sin(theta) = 0)."""
    Om = check_array("Omega", Omega)
    Th = check_array("theta", theta)
    if np.any(Om == 0.0):
        raise ParameterError("Omega", "must be finite and nonzero ((6.3) divides by Omega)", Om)
    if np.any((Th <= 0.0) | (Th >= np.pi)):
        raise ParameterError("theta", "must lie in (0, pi)", Th)
    try:
        np.broadcast_shapes(Om.shape, Th.shape)
    except ValueError:
        raise ParameterError("theta", f"must have a shape that broadcasts with that of `Omega`, {Om.shape} (got shape "
                                      f"{Th.shape})", show_value=False) from None
    h, ht, _ = body.h(Th)
    # (6.3) has 1 / (h_theta sin(theta)): infinite where it vanishes (at the roundoff level of h)
    flat = np.atleast_1d(np.abs(ht * np.sin(Th)) <= 1e-15 * np.abs(h))
    if np.any(flat):
        raise ParameterError("theta", "must avoid the angles where h_theta(theta) sin(theta) = 0, at which (6.3) is "
                                      "infinite (theta = pi/2 on a spheroid, every theta on a sphere)",
                             float(np.atleast_1d(Th).ravel()[np.flatnonzero(flat)[0]]))
    return Om, Th


def surface_n(body, Omega, theta):
    """(6.3): the spin n on the approximate jump surface at (Omega, theta).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    Omega : float or array_like
        Precession rate, units sqrt(g/b): finite, nonzero.
    theta : float or array_like
        Inclination of the symmetry axis from the vertical, radians: in (0, pi), where
        h_theta sin(theta) != 0 (not pi/2 on a spheroid). ``Omega`` and ``theta`` are numbers
        or arrays of shapes that broadcast together.

    Returns
    -------
    numpy.ndarray
        The spin n on (6.3), units sqrt(g/b), of the broadcast shape of ``Omega`` and
        ``theta`` (0-d for two numbers).

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``Omega`` is not finite or is 0, ``theta`` is outside
        (0, pi) or at an angle where h_theta sin(theta) = 0, the shapes do not broadcast
        together, or n is not finite (``abs(Omega)`` too small or too large).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.surface_n(pk.Spheroid(1.5), 12.0, 1.0)), 6)
    10.20507
    """
    body = _body(body)
    Om, Th = _check_grid(body, Omega, theta)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        out = _surface_n(body, Om, Th)
    if not np.all(np.isfinite(out)):
        raise ParameterError("Omega", "gives a non-finite n on (6.3) (|Omega| too small or too large)", Om)
    return out


def _surface_n(body, Omega, theta):
    """(6.3) without checks (the scene's grids, which may touch the singular angles)."""
    h, ht, _ = body.h(theta)
    return body.A / body.C * (Omega * np.cos(theta) + 1.0 / (Omega * ht * np.sin(theta)))


def exact_boundary(body, mu: float, Omega, theta, Lambda: float = 0.0, *, friction: FrictionLaw | None = None):
    """n at which the model's normal reaction (6.1) vanishes, for U = V = 0 and the given Lambda.

    Found by Brent's method on R(n) from the compiled model (Coulomb friction with ``mu``,
    or the law ``friction``; slip direction of that state), independently of the closed
    form (6.3).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    mu : float or None
        Coulomb friction coefficient, finite >= 0; may be None when ``friction`` is given.
    Omega : float or array_like
        Precession rate, units sqrt(g/b), as for :func:`surface_n`: finite, nonzero.
    theta : float or array_like
        Inclination, radians, as for :func:`surface_n`: in (0, pi) where
        h_theta sin(theta) != 0, of a shape that broadcasts with that of ``Omega``.
    Lambda : float, optional
        The rate Lambda = dtheta/dt of the section, units sqrt(g/b): finite (default 0).
    friction : FrictionLaw, optional
        The friction law of the model; default Coulomb(mu).

    Returns
    -------
    numpy.ndarray
        The spin n at which R = 0, units sqrt(g/b): an array of the broadcast shape of
        ``Omega`` and ``theta`` (at least 1-d), NaN where no sign change of R(n) was found.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``friction`` is not a FrictionLaw, ``mu`` is not a finite
        number >= 0 (when it is used), ``Omega`` or ``theta`` is invalid as for
        :func:`surface_n`, or ``Lambda`` is not finite.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.exact_boundary(pk.Spheroid(1.5), 0.1, [10.0, 12.0], [1.0, 1.0]).round(6)
    array([ 8.382922, 10.20507 ])
    """
    body = _body(body)
    if friction is not None:
        check_instance("friction", friction, FrictionLaw, "Coulomb(0.1)")
    if mu is not None or friction is None:
        check_nonnegative("mu", mu)
    Om, Th = _check_grid(body, Omega, theta)
    Lambda = check_finite("Lambda", Lambda)
    return _exact_boundary(body, mu, Om, Th, Lambda, friction=friction)


def _exact_boundary(body, mu, Omega, theta, Lambda=0.0, *, friction=None):
    from scipy.optimize import brentq

    model = Model(body, Coulomb(mu) if friction is None else friction)
    Rf = model.function("R_sliding")
    Om = np.atleast_1d(np.asarray(Omega, dtype=float))
    Th = np.atleast_1d(np.asarray(theta, dtype=float))
    Om, Th = np.broadcast_arrays(Om, Th)
    out = np.full(Om.shape, np.nan)
    for idx in np.ndindex(Om.shape):
        om, th = Om[idx], Th[idx]
        guess = _surface_n(body, om, th)
        f = lambda n: float(Rf(np.array([0.0, 0.0, om, Lambda, th, n]), model.p))  # noqa: E731
        span = 1e-3 + 0.2 * abs(guess) + abs(Lambda) * 10
        lo, hi = guess - span, guess + span
        for _ in range(40):
            if f(lo) * f(hi) < 0:
                break
            lo, hi = lo - span, hi + span
            span *= 2
        else:
            continue
        out[idx] = brentq(f, lo, hi, xtol=1e-14, rtol=1e-15)
    return out if out.ndim else float(out)
