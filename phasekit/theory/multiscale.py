"""Multiple-scale quantities of section 3c-d: the fast oscillation and the envelope of R.
Each function's docstring names the paper's symbol and equation (omega^2 (3.30), Sigma (3.64), ...).

All functions take the mean state (theta-bar, Omega-bar) of the gyroscopic solution
(:mod:`phasekit.theory.gyroscopic`) and a uniform spheroid or any Body. Time derivatives of the mean
state are with respect to the slow time T = mu t and come from (3.16) (Coulomb friction).

nutation_frequency_squared (omega2, 3.30): fast frequency squared;
              gyroscopic_nutation_frequency (omega_gyro, 3.47): its gyroscopic limit
lam           (3.35)
zeta          (3.38)  damping coefficient; the last term is printed h^2/|Vhat_P| but, from
                      (3.11) (F'_X = mu h/|Vbar_P| d theta'/d tau), it is h^2/|Vbar_P|: used so
zeta_gyro     (3.48)
growth_integral (I_quadrature, 3.45): I = -1/2 int zeta dT, by quadrature along the rise (dT = dtheta/(dtheta/dT))
I1_closed     (3.53)  exact for the spheroid;  I3_closed (3.52) exact
I2_dominant   (3.57)  ONLY the dominant part of I2 near theta-bar = 0 or pi/2; away from them
                      it differs from the quadrature of (3.51) (tested and reported)
Gamma         (3.44)  omega^(-1/2) exp(I);  amplitude_growth_closed (Gamma_closed, 3.58) = omega^(-1/2) sigma gamma^(...)
reaction_envelope (Sigma, 3.64): envelope of the minima of R: 1 - |h_theta omega^2 c Gamma|
nutation_amplitude_phase / nutation_perturbation (c_xi / perturbation_from_c_xi, 3.46), and the accompanying Omega' (3.27), Psi' (3.28), n' = 0
mean_over_periods (3.6) fast-time average over each period of a simulated signal
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_array, finite_result
from ..bodies.body import Body
from ..errors import ParameterError
from .gyroscopic import mean_slip


def support_geometry(body, theta):
    h, ht, htt = body.h(theta)
    return h, ht, htt, np.sin(theta), np.cos(theta)


def checked_angle(name: str, theta):
    """Finite inclinations off the poles (where the theory's cot and 1/sin diverge)."""
    th = check_array(name, theta)
    if np.any(np.abs(np.sin(th)) < 1e-12):
        raise ParameterError(name, "must be off the poles (0 < theta < pi): the theory divides by sin(theta)", theta)
    return th


def checked_spin(name: str, value):
    """A finite, non-zero spin rate (the theory divides by it)."""
    v = check_array(name, value)
    if np.any(v == 0):
        raise ParameterError(name, "must be non-zero (the theory divides by it)", value)
    return v


@finite_result
def nutation_frequency_squared(body: Body, theta, Omega):
    """(3.30): A/(A + h_t^2) [Omega^2 + (h_tt + h_t cot)/A + (h_t/(A Omega sin))^2].

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta : float or array_like
        Mean inclination theta-bar, radians: finite, off the poles (abs(sin(theta)) >= 1e-12).
    Omega : float or array_like
        Mean precession rate Omega-bar, units sqrt(g/b): finite and nonzero, of a shape that
        broadcasts with that of ``theta``.

    Returns
    -------
    float or numpy.ndarray
        The squared frequency omega^2 of the fast nutation, units g/b.

    Raises
    ------
    ParameterError
        If ``theta`` is not finite or is at a pole, ``Omega`` is not finite or is 0, or the result
        is not finite (an overflow of double precision or a singular configuration), naming the
        argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.multiscale.nutation_frequency_squared(pk.Spheroid(1.5), 1.0, 10.0)), 6)
    73.238621
    """
    theta, Omega = checked_angle("theta", theta), checked_spin("Omega", Omega)
    h, ht, htt, s, c = support_geometry(body, theta)
    A = body.A
    return A / (A + ht**2) * (Omega**2 + (htt + ht * c / s) / A + (ht / (A * Omega * s)) ** 2)


@finite_result
def gyroscopic_nutation_frequency(body: Body, theta, Omega):
    """(3.47): |Omega| (A/(A + h_t^2))^(1/2).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta : float or array_like
        Mean inclination theta-bar, radians.
    Omega : float or array_like
        Mean precession rate Omega-bar, units sqrt(g/b), of a shape that broadcasts with that
        of ``theta``.

    Returns
    -------
    float or numpy.ndarray
        The frequency omega of the fast nutation in the gyroscopic limit, units sqrt(g/b).

    Raises
    ------
    ParameterError
        If the result is not finite (an overflow of double precision or a singular configuration),
        naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.gyroscopic_nutation_frequency(pk.Spheroid(1.5), 1.0, 10.0)), 6)
    8.562205
    """
    _, ht, _, _, _ = support_geometry(body, theta)
    return np.abs(Omega) * np.sqrt(body.A / (body.A + ht**2))


@finite_result
def slow_rates(body: Body, theta, Omega):
    """(dOmega/dT, dtheta/dT, Vhat_P, Vbar_P) of (3.16) at the mean state.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta : float or array_like
        Mean inclination theta-bar, radians: finite numbers.
    Omega : float or array_like
        Mean precession rate Omega-bar, units sqrt(g/b): finite and nonzero, of a shape that
        broadcasts with that of ``theta``.

    Returns
    -------
    tuple
        (dOmega/dT, dtheta/dT, Vhat_P, Vbar_P): the rates of (3.16) with respect to the slow
        time T = mu t, dOmega/dT = -h_theta Vhat_P / A and dtheta/dT = h Vhat_P / (A Omega);
        the sign Vhat_P (+1, -1, or 0 without slip) of the mean slip; and the leading-order
        mean slip velocity Vbar_P (generalised (3.10)), units sqrt(g b).

    Raises
    ------
    ParameterError
        If ``theta`` or ``Omega`` is not finite real numbers (the error names ``omega``), or the
        result is not finite (an overflow of double precision or a singular configuration), naming
        the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(float(v), 6) for v in pk.theory.slow_rates(pk.Spheroid(1.5), 1.0, 10.0)]
    [-0.748378, -0.179737, -1.0, -2.432228]
    """
    h, ht, _, _, _ = support_geometry(body, theta)
    VP = mean_slip(body, theta, Omega)
    v = np.sign(VP)
    return -ht * v / body.A, h * v / (body.A * Omega), v, VP


@finite_result
def lam(body: Body, theta, Omega):
    """(3.35)."""
    h, ht, _, s, c = support_geometry(body, theta)
    A = body.A
    dOm, dth, v, _ = slow_rates(body, theta, Omega)
    w2 = nutation_frequency_squared(body, theta, Omega)
    return (ht * v / A + dOm + (Omega * c / s + ht / (A * Omega * s**2)) * dth) / w2 - h * ht * v / A


@finite_result
def zeta(body: Body, theta, Omega):
    """(3.38), with h^2/|Vbar_P| as the last term (see the module notes)."""
    h, ht, htt, s, c = support_geometry(body, theta)
    A = body.A
    dOm, dth, v, VP = slow_rates(body, theta, Omega)
    w2 = nutation_frequency_squared(body, theta, Omega)
    L = lam(body, theta, Omega)
    return ((A * Omega + ht * c / (s * Omega)) * L + (2 * ht * htt - ht / h * (htt / w2 - ht**2)) * dth + h**2 / np.abs(VP)) / (A + ht**2)


def _zeta_gyro_terms(body: Body, theta, Omega):
    """The three terms of (3.48) before the factor dtheta/dT (the integrands of I1, I2, I3)."""
    h, ht, _, s, c = support_geometry(body, theta)
    A, C, a = body.A, body.C, body.shape_params[0]
    return (-A * ht / (A + ht**2) * Omega**2, -(a * a - 1) / (A - a * a * C) * A * C / (A + ht**2) * h / ht, c / s)


@finite_result
def zeta_gyro(body: Body, theta, Omega):
    """(3.48) (spheroid: the second term uses a)."""
    _, dth, _, _ = slow_rates(body, theta, Omega)
    return sum(_zeta_gyro_terms(body, theta, Omega)) * dth


def _along_rise(body, J, theta0, theta):
    """Omega-bar on the gyroscopic solution at theta-bar: Omega = J / (A h)."""
    return J / (body.A * body.h(theta)[0])


@finite_result
def growth_integral(body: Body, J: float, theta0: float, theta, *, form: str = "gyro", parts: bool = False):
    """(3.45) by adaptive quadrature in theta-bar along the gyroscopic solution.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    J : float
        The Jellett constant J = A Omega h (3.17) of the rise: finite and nonzero; Omega-bar =
        J / (A h(theta-bar)) along the gyroscopic solution.
    theta0 : float
        Mean inclination at the start of the rise, radians: finite, off the poles.
    theta : float or array_like
        Mean inclinations theta-bar along the rise, radians: finite, off the poles.
    form : {"gyro", "full"}, optional
        "gyro" (the default) integrates (3.48) (whose three terms give I1, I2, I3 of
        (3.50)-(3.52)), "full" integrates (3.38) with (3.30).
    parts : bool, optional
        With ``form="gyro"``, ``parts=True`` returns I1, I2, I3 separately (default False).

    Returns
    -------
    numpy.ndarray
        The integral I from ``theta0`` to each theta-bar of ``theta``: a 1-d array, one value
        per angle; with ``parts=True`` and ``form="gyro"``, shape (len(theta), 3), the columns
        I1, I2, I3.

    Raises
    ------
    ParameterError
        If ``J`` is 0 or not finite, ``theta0`` or ``theta`` is not finite or is at a pole, or the
        result is not finite (an overflow of double precision or a singular configuration), naming
        the argument of largest magnitude.
    ValueError
        If ``form`` is neither "gyro" nor "full".

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.multiscale.growth_integral(pk.Spheroid(1.5), 6.83, 1.5607963, [1.2, 1.0]).round(6)
    array([0.747044, 3.404539])
    """
    from scipy.integrate import quad

    J = float(checked_spin("J", J))
    theta0 = float(checked_angle("theta0", theta0))
    theta = np.atleast_1d(checked_angle("theta", theta))

    def integrands(th):
        # -1/2 zeta / (dtheta/dT): the dtheta/dT factor of (3.48) cancels
        return tuple(-0.5 * term for term in _zeta_gyro_terms(body, th, _along_rise(body, J, theta0, th)))

    if form == "gyro":
        fns = [lambda x, k=k: integrands(x)[k] for k in range(3)]
    elif form == "full":
        def f_full(x):
            om = _along_rise(body, J, theta0, x)
            return -0.5 * zeta(body, x, om) / slow_rates(body, x, om)[1]

        fns = [f_full]
    else:
        raise ValueError(f"`form` must be gyro or full, got {form!r}.")
    # cumulative: integrate between consecutive targets (ordered away from theta0) and add up
    order = np.argsort(np.abs(theta - theta0))
    acc = np.zeros(len(fns))
    prev = theta0
    res = np.zeros((theta.size, len(fns)))
    for idx in order:
        th = theta[idx]
        acc = acc + np.array([quad(f, prev, th, epsabs=1e-15, epsrel=1e-13, limit=200)[0] for f in fns])
        res[idx] = acc
        prev = th
    if form == "gyro" and parts:
        return res
    return res.sum(axis=1)


@finite_result
def alpha_beta(body: Body):
    """(3.54), (3.55)."""
    A, a = body.A, body.shape_params[0]
    root = np.sqrt((A + (a - 1) ** 2) * (A + (a + 1) ** 2))
    return np.sqrt(0.5 * (A + a * a + 1 + root)), np.sqrt(0.5 * (A + a * a + 1 - root))


@finite_result
def I1_closed(body: Body, J: float, theta0: float, theta):
    """(3.53)."""
    al, be = alpha_beta(body)
    h, h0 = body.h(theta)[0], body.h(theta0)[0]
    g = (1 / al) * np.log((al + h) / (al - h) * (al - h0) / (al + h0)) + (1 / be) * np.log((h - be) / (h + be) * (h0 + be) / (h0 - be))
    return J**2 / (4 * body.A * (al**2 - be**2)) * g


@finite_result
def I2_dominant(body: Body, theta0: float, theta):
    """(3.57): the dominant part of I2 near theta-bar = 0 or pi/2 only."""
    A, C, a = body.A, body.C, body.shape_params[0]
    return C / (2 * (a * a * C - A)) * np.log((np.sin(theta) / np.sin(theta0)) ** (a * a) * np.cos(theta0) / np.cos(theta))


@finite_result
def I3_closed(theta0: float, theta):
    """(3.52)."""
    return 0.5 * np.log(np.sin(theta0) / np.sin(theta))


@finite_result
def Gamma(body: Body, J: float, theta0: float, theta, *, form: str = "gyro"):
    """(3.44) with I by quadrature and omega from (3.47) ("gyro") or (3.30) ("full")."""
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    om = _along_rise(body, J, theta0, theta)
    w = gyroscopic_nutation_frequency(body, theta, om) if form == "gyro" else np.sqrt(nutation_frequency_squared(body, theta, om))
    return w ** (-0.5) * np.exp(growth_integral(body, J, theta0, theta, form=form))


@finite_result
def amplitude_growth_closed(body: Body, J: float, theta0: float, theta):
    """(3.58)-(3.60): omega^(-1/2) sigma gamma^(J^2/(4 A (alpha^2 - beta^2))); sigma uses the
    dominant-part I2 of (3.57).

    Parameters
    ----------
    body : Spheroid
        The spheroid (its aspect ratio a and moments A, C enter the closed forms).
    J : float
        The Jellett constant J = A Omega h (3.17) of the rise; Omega-bar = J / (A h(theta-bar)).
    theta0 : float
        Mean inclination at the start of the rise, radians.
    theta : float or array_like
        Mean inclinations theta-bar along the rise, radians.

    Returns
    -------
    float or numpy.ndarray
        The amplitude factor Gamma of the nutation (3.58), of the shape of ``theta``.

    Raises
    ------
    ParameterError
        If the result is not finite (an overflow of double precision or a singular configuration),
        naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.amplitude_growth_closed(pk.Spheroid(1.5), 6.83, 1.5607963, 1.0)), 6)
    8.619004
    """
    A, C, a = body.A, body.C, body.shape_params[0]
    theta = np.asarray(theta, dtype=float)
    al, be = alpha_beta(body)
    h, h0 = body.h(theta)[0], body.h(theta0)[0]
    gam = ((al + h) / (al - h) * (al - h0) / (al + h0)) ** (1 / al) * ((h - be) / (h + be) * (h0 + be) / (h0 - be)) ** (1 / be)
    sig = ((np.sin(theta) / np.sin(theta0)) ** A * (np.cos(theta0) / np.cos(theta)) ** C) ** (0.5 / (C * a * a - A))
    om = _along_rise(body, J, theta0, theta)
    return gyroscopic_nutation_frequency(body, theta, om) ** (-0.5) * sig * gam ** (J**2 / (4 * A * (al**2 - be**2)))


@finite_result
def reaction_envelope(body: Body, J: float, theta0: float, theta, c: float, *, form: str = "closed"):
    """(3.64): 1 - |h_theta omega^2 c Gamma|, the envelope of the minima of R.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C); a :class:`~phasekit.Spheroid`
        for ``form="closed"``.
    J : float
        The Jellett constant J = A Omega h (3.17) of the rise; Omega-bar = J / (A h(theta-bar)).
    theta0 : float
        Mean inclination at the start of the rise, radians.
    theta : float or array_like
        Mean inclinations theta-bar along the rise, radians.
    c : float
        Amplitude of the initial nutation (3.46), e.g. from :func:`nutation_amplitude_phase`.
    form : {"closed", "gyro", "full"}, optional
        "closed" (the default) uses (3.47) and (3.58) (the paper's Fig. 2); "gyro" and "full"
        use (3.44) with I by quadrature of (3.48) or (3.38).

    Returns
    -------
    numpy.ndarray
        Sigma, the envelope of the minima of the normal reaction R (units M g): a 1-d array,
        one value per angle of ``theta``.

    Raises
    ------
    ParameterError
        If an argument the quadrature checks (``form`` "gyro" or "full") is invalid, as for
        :func:`growth_integral`, or the result is not finite (an overflow of double precision or a
        singular configuration), naming the argument of largest magnitude.
    ValueError
        If ``form`` is not one of "closed", "gyro", "full".

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.reaction_envelope(pk.Spheroid(1.5), 6.83, 1.5607963, [1.2, 1.0], -0.00054).round(6)
    array([0.98966 , 0.865734])
    """
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    om = _along_rise(body, J, theta0, theta)
    _, ht, _, _, _ = support_geometry(body, theta)
    if form == "closed":
        w2 = gyroscopic_nutation_frequency(body, theta, om) ** 2
        G = amplitude_growth_closed(body, J, theta0, theta)
    else:
        w2 = gyroscopic_nutation_frequency(body, theta, om) ** 2 if form == "gyro" else nutation_frequency_squared(body, theta, om)
        G = Gamma(body, J, theta0, theta, form=form)
    return 1 - np.abs(ht * w2 * c * G)
