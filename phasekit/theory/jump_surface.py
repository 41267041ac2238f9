"""The jump surface (6.3) in (Omega, theta, n), in closed form.

Section 6: in the gyroscopic region R = 0 is close to the 2-D surface (6.3),

    n = (A/C) (Omega cos(theta) + 1 / (Omega h_theta sin(theta))),

which is (6.1) with the Lambda^2 term dropped. The exact boundary is 5-dimensional; its section
at given Lambda (and the gyroscopic slip direction, which only enters the denominator of (6.1))
is n = (A/C) (Omega cos(theta) + (1 + h_tt Lambda^2) / (Omega h_theta sin(theta))).
:func:`phasekit.scenes.exact_boundary` finds it independently, by root finding on the model's normal reaction;
at Lambda = 0 it coincides with (6.3), and trajectories cross R = 0 with Lambda != 0 (the fast
nutation), which is where (6.3) and the crossings differ.

The 3-D scenes that draw them are :mod:`phasekit.scenes`'.
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_array, check_instance
from ..bodies.body import Body
from ..errors import ParameterError


def check_body(body) -> Body:
    return check_instance("body", body, Body, "Spheroid(1.5)")


def check_grid(body: Body, Omega, theta) -> tuple[np.ndarray, np.ndarray]:
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

    See Also
    --------
    phasekit.scenes.exact_boundary
        R = 0 at a given Lambda by root finding on the model, which (6.3) approximates

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.surface_n(pk.Spheroid(1.5), 12.0, 1.0)), 6)
    10.20507
    """
    body = check_body(body)
    Om, Th = check_grid(body, Omega, theta)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        out = surface_n_unchecked(body, Om, Th)
    if not np.all(np.isfinite(out)):
        raise ParameterError("Omega", "gives a non-finite n on (6.3) (|Omega| too small or too large)", Om)
    return out


def surface_n_unchecked(body, Omega, theta):
    """(6.3) without checks (the scene's grids, which may touch the singular angles)."""
    h, ht, _ = body.h(theta)
    return body.A / body.C * (Omega * np.cos(theta) + 1.0 / (Omega * ht * np.sin(theta)))
