"""The nutation about the gyroscopic mean (section 3c): its amplitude and phase from a start
(:func:`nutation_amplitude_phase`, (3.46)), the start from them (:func:`nutation_perturbation`,
(3.46) with (3.27)), and the mean of a quantity over the periods of the fast oscillation
(:func:`mean_over_periods`), to set simulations beside the multiple-scale envelope
(:mod:`phasekit.theory.multiscale`)."""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_array, finite_result
from ..bodies.body import Body
from ..errors import ParameterError
from .multiscale import checked_angle, checked_spin, nutation_frequency_squared, support_geometry, zeta


@finite_result
def nutation_amplitude_phase(body: Body, theta_bar0: float, Omega_bar0: float, mu: float, dtheta0: float, dthetadot0: float):
    """(3.46) inverted: amplitude c and phase xi of the initial nutation (theta', d theta'/dt).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta_bar0 : float
        Initial mean inclination theta-bar, radians: finite, off the poles (abs(sin) >= 1e-12).
    Omega_bar0 : float
        Initial mean precession rate Omega-bar, units sqrt(g/b): finite and nonzero.
    mu : float
        Friction coefficient (the slow time is T = mu t): finite.
    dtheta0 : float
        Initial fluctuation theta' of the inclination about its mean, radians: finite.
    dthetadot0 : float
        Its initial rate d theta'/dt, units sqrt(g/b): finite.

    Returns
    -------
    tuple of float
        (c, xi): the amplitude c, of the sign of ``dtheta0``, and the phase xi in
        [-pi/2, pi/2], radians.

    Raises
    ------
    ParameterError
        If ``theta_bar0`` is not finite or is at a pole, ``Omega_bar0`` is not finite or is 0,
        ``mu``, ``dtheta0`` or ``dthetadot0`` is not finite, or the result is not finite (an
        overflow of double precision or a singular configuration), naming the argument of largest
        magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(float(v), 6) for v in pk.theory.nutation.nutation_amplitude_phase(pk.Spheroid(1.5), 1.5607963, 10.5, 0.1, 1e-3, 0.0)]
    [0.003456, -0.343063]
    """
    theta_bar0, Omega_bar0 = float(checked_angle("theta_bar0", theta_bar0)), float(checked_spin("Omega_bar0", Omega_bar0))
    mu, dtheta0, dthetadot0 = (float(check_array(n, v)) for n, v in (("mu", mu), ("dtheta0", dtheta0), ("dthetadot0", dthetadot0)))
    w = np.sqrt(nutation_frequency_squared(body, theta_bar0, Omega_bar0))
    Idot = -0.5 * mu * zeta(body, theta_bar0, Omega_bar0)  # dI/dt = -mu zeta / 2
    # theta' = c cos(xi) w^-1/2;  theta'dot = c (-w^1/2 sin xi + Idot cos xi)
    cc = dtheta0 * np.sqrt(w)  # c cos xi
    cs = -(dthetadot0 - Idot * cc) / np.sqrt(w)  # c sin xi
    return float(np.hypot(cc, cs)) * (1 if cc >= 0 else -1), float(np.arctan2(cs, cc) if cc >= 0 else np.arctan2(-cs, -cc))


@finite_result
def nutation_perturbation(body: Body, theta_bar0: float, Omega_bar0: float, mu: float, c: float, xi: float):
    """Initial fluctuation (theta', Lambda', Omega') for amplitude c and phase xi: (3.46) for
    theta' and its rate, (3.27) for Omega' (with Psi' = -Omega theta' (3.28), n' = 0 (3.31)).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta_bar0 : float
        Initial mean inclination theta-bar, radians: finite, off the poles (abs(sin) >= 1e-12).
    Omega_bar0 : float
        Initial mean precession rate Omega-bar, units sqrt(g/b): finite and nonzero.
    mu : float
        Friction coefficient (the slow time is T = mu t).
    c : float
        Amplitude of the nutation (3.46).
    xi : float
        Phase of the nutation (3.46), radians.

    Returns
    -------
    tuple of float
        (theta', Lambda', Omega'): the fluctuations of the inclination (radians), of its rate
        Lambda and of the precession rate Omega (units sqrt(g/b)), to add to the mean state.

    Raises
    ------
    ParameterError
        If ``theta_bar0`` is at a pole or not finite (the error names ``theta``), ``Omega_bar0`` is
        0 or not finite (named ``Omega``), or the result is not finite (an overflow of double
        precision or a singular configuration), naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(float(v), 8) for v in pk.theory.nutation_perturbation(pk.Spheroid(1.5), 1.5607963, 10.5, 0.1, -0.00054, 0.0)]
    [-0.00016594, 0.00062767, 1.773e-05]
    """
    w = np.sqrt(nutation_frequency_squared(body, theta_bar0, Omega_bar0))
    Idot = -0.5 * mu * zeta(body, theta_bar0, Omega_bar0)
    th_p = c * np.cos(xi) / np.sqrt(w)
    lam_p = c * (-np.sqrt(w) * np.sin(xi) + Idot * np.cos(xi))
    _, ht, _, s, c_ = support_geometry(body, theta_bar0)
    om_p = (-Omega_bar0 * c_ / s + ht / (body.A * Omega_bar0 * s * s)) * th_p
    return float(th_p), float(lam_p), float(om_p)


def mean_over_periods(ts, values, marks):
    """(3.6) with the averaging window set to the fast period itself: the mean of ``values``
    over each interval [marks[k], marks[k+1]] (e.g. between successive located minima of R),
    returned at the interval midpoints as (t_mid, mean).

    Parameters
    ----------
    ts : array_like
        Times of the samples, increasing: a 1-d array of two or more.
    values : array_like
        The signal at those times, one value per time (trapezoidal rule between them).
    marks : array_like
        Boundaries of the intervals, increasing; those outside [ts[0], ts[-1]] are dropped.

    Returns
    -------
    tuple of numpy.ndarray
        (t_mid, mean): the midpoint and the mean of ``values`` of each interval between
        successive marks; both empty when fewer than two marks lie inside the sampled span.

    Raises
    ------
    ParameterError
        If there are fewer than two times or ``values`` is not one value per time.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> ts = np.linspace(0.0, 4 * np.pi, 401)
    >>> t_mid, means = pk.theory.mean_over_periods(ts, 1.0 + np.sin(ts), [0.0, 2 * np.pi, 4 * np.pi])
    >>> t_mid.round(4), means.round(4)
    (array([3.1416, 9.4248]), array([1., 1.]))
    """
    ts = np.asarray(ts, dtype=float)
    v = np.asarray(values, dtype=float)
    marks = np.asarray(marks, dtype=float)
    if ts.size < 2 or v.shape != ts.shape:
        raise ParameterError("values", "must be one value per time, at two or more times", show_value=False)
    marks = marks[(marks >= ts[0]) & (marks <= ts[-1])]
    if marks.size < 2:
        return np.empty(0), np.empty(0)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(ts))])
    area = np.diff(np.interp(marks, ts, cum))
    return 0.5 * (marks[1:] + marks[:-1]), area / np.diff(marks)
