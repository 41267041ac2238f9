"""The gyroscopic mean solution (section 3b): slow rise on the time scale T = mu t.

Under Coulomb friction the mean friction is F_y = -mu Vhat_P, with Vhat_P the sign of the
mean slip. At leading order in 1/Omega the mean slip of the contact point is, for any
flip-symmetric body (n from the balance A Omega cos = C n),

    Vbar_P = Omega [h_theta + (A - C) cos(theta) x_P / C],          x_P = h sin + h_theta cos,

which for the spheroid is (3.10), (A - a^2 C)/(C h) Omega sin cos. Then (3.16):

    dOmega/dT = -h_theta Vhat_P / A,        Omega dtheta/dT = h Vhat_P / A,

whose first integral is the Jellett constant J = A Omega h (3.17). For the uniform (or any)
spheroid the solution is (3.18)-(3.19): tan(theta) = -a tan(q (T - T0)),
q = a (a - 1) / (J |a - 1|), a tan(q T0) = tan(theta0).

Jellett constant: J = A Omega h here (3.17). The paper quotes J = 4 and 4.2 in Fig. 3
(oblate a = 2/3, n0 = 10, 10.5); those equal C n0, not A Omega h = C n0 a (= 2.67, 2.8):
see docs/physics.md (Jellett constant). The prolate values of Fig. 4 (6.63, 6.83) do equal A Omega0 h.
"""

from __future__ import annotations

import warnings

import numpy as np

from .._runtime.validate import check_array, check_finite, check_instance, check_positive, check_range, finite_result
from ..bodies.body import Body
from ..bodies.spheroid import Spheroid
from ..errors import ConvergenceError, ParameterError

#: tolerances scipy's DOP853 accepts (it raises tighter ones to 100 x machine epsilon)
RTOL_RANGE = (1e-14, 1e-3)


#: the largest rate (units sqrt(g/b)) a start may have: beyond it the dynamics are beyond
#: double precision (Omega^2 terms against 1) and the Taylor steps vanish
RATE_MAX = 1e5
#: the largest rate the gyroscopic (mean) solution takes: it is closed-form (or a slow-time
#: quadrature) and does not integrate the fast motion, so only overflow of A Omega^2 limits it
GYRO_RATE_MAX = 1e12


def slope_q(body: Body, theta: float) -> float:
    """h_theta / sin(theta) = -H'(cos theta), evaluated without dividing by sin(theta)."""
    return -body.height_slope(np.cos(theta))[1]


def checked_rate(name: str, value, limit: float = RATE_MAX) -> float:
    v = check_finite(name, value, nonzero=True)
    if abs(v) > limit:
        raise ParameterError(name, f"must be nonzero with |{name}| <= {limit:g}", value)
    return v


def balanced_state(body: Body, theta0: float, *, omega0=None, n0=None, limit: float = RATE_MAX) -> np.ndarray:
    """The gyroscopic balance at ``theta0`` (:func:`phasekit.gyroscopic_start`) with rates up to
    ``limit`` (the gyroscopic solution's is GYRO_RATE_MAX): (0, 0, Omega, 0, theta0, n)."""
    if not isinstance(body, Body):
        raise ParameterError("body", "must be a phasekit Body such as Spheroid(a)", body)
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both (prolate: omega0; oblate: n0)", show_value=False)
    A, C = body.A, body.C
    c = np.cos(theta0)
    q = slope_q(body, theta0)
    if omega0 is not None:
        omega0 = checked_rate("omega0", omega0, limit)
        n = (A * omega0 * c - q / omega0) / C
        if not abs(n) <= limit:
            raise ParameterError("omega0", f"is too small for a gyroscopic balance at theta0 = {theta0:g} (it needs a "
                                           f"spin |n| = {abs(n):.3g} > {limit:g})", omega0)
        return np.array([0.0, 0.0, omega0, 0.0, theta0, n])
    n0 = checked_rate("n0", n0, limit)
    if body.is_prolate:
        warnings.warn("`n0` given for a prolate body: its gyroscopic start is normally given `omega0` (the precession "
                      "rate; n then follows from the balance); with `n0`, Omega is put on the fast branch, "
                      "|Omega| ~ C n0 / (A cos theta0)", stacklevel=2)
    if c <= 0.0:
        raise ParameterError("theta0", "must lie in (0, pi/2) for a start given n0 (the fast branch)", theta0)
    disc = (C * n0) ** 2 + 4.0 * A * c * q
    if disc < 0.0:
        need = np.sqrt(max(-4.0 * A * c * q, 0.0)) / C
        raise ParameterError("n0", f"must satisfy |n0| > {need:.6g} for a gyroscopic balance at theta0 = {theta0:g}", n0)
    omega = (C * n0 + np.sign(n0) * np.sqrt(disc)) / (2.0 * A * c)
    if not abs(omega) <= limit:
        raise ParameterError("n0", f"gives a precession rate |Omega| = {abs(omega):.3g} > {limit:g} on the fast branch at "
                                   f"theta0 = {theta0:g}", n0)
    return np.array([0.0, 0.0, omega, 0.0, theta0, n0])


def _body(body) -> Body:
    return check_instance("body", body, Body, "Spheroid(1.5)")


@finite_result
def mean_slip(body: Body, theta, omega):
    """Leading-order mean slip velocity Vbar_P of the gyroscopic state (generalised (3.10))."""
    return _mean_slip(_body(body), check_array("theta", theta), check_array("omega", omega))


def _mean_slip(body: Body, theta, omega):
    h, ht, _ = body.h(theta)
    c, s = np.cos(theta), np.sin(theta)
    xP = h * s + ht * c
    return omega * (ht + (body.A - body.C) * c * xP / body.C)


@finite_result
def jellett_constant(body: Body, theta, omega):
    """J = A Omega h (3.17).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta : float or array_like
        Inclination of the symmetry axis from the vertical, radians: finite numbers.
    omega : float or array_like
        Precession rate Omega, units sqrt(g/b): finite numbers, of a shape that broadcasts with
        that of ``theta``.

    Returns
    -------
    float or numpy.ndarray
        J = A Omega h(theta), units M b^2 sqrt(g b), of the broadcast shape of ``theta`` and
        ``omega``.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``theta`` or ``omega`` is not finite real numbers (or is empty),
        or if the result is not finite (an overflow of double precision or a singular
        configuration), naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.jellett_constant(pk.Spheroid(1.5), 1.5607963, 10.5)), 6)
    6.825427
    """
    body, theta, omega = _body(body), check_array("theta", theta), check_array("omega", omega)
    return body.A * omega * body.h(theta)[0]


def _rhs(T, y, body):
    om, th = y
    h, ht, _ = body.h(th)
    v = np.sign(_mean_slip(body, th, om))
    return [-ht * v / body.A, h * v / (body.A * om)]


@finite_result
def gyroscopic_numeric(body: Body, theta0: float, omega0: float, T, *, rtol: float = 1e-13):
    """Integrate (3.16) numerically (any body): returns (theta(T), Omega(T)) at the slow
    times T (>= 0, any order), with ``rtol`` in [1e-14, 1e-3].

    Stops where the mean slip vanishes (theta reaches 0 or pi/2, the end of the rise) and
    holds the state there.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta0 : float
        Initial mean inclination of the symmetry axis from the vertical, radians, in (0, pi).
    omega0 : float
        Initial mean precession rate Omega, units sqrt(g/b): finite and nonzero.
    T : float or array_like
        Slow times T = mu t: finite numbers >= 0, at least one, in any order.
    rtol : float, optional
        Relative tolerance of scipy's DOP853, in [1e-14, 1e-3] (default 1e-13).

    Returns
    -------
    tuple of numpy.ndarray
        (theta(T), Omega(T)): two 1-d arrays, one value per slow time of ``T`` in its order.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``theta0`` is outside (0, pi), ``omega0`` is 0 or not finite,
        ``T`` is not finite numbers >= 0 (or is empty), ``rtol`` is outside [1e-14, 1e-3], or if the
        result is not finite (an overflow of double precision or a singular configuration), naming
        the argument of largest magnitude.
    ConvergenceError
        If scipy cannot integrate the mean equations (3.16).

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.theory import gyroscopic
    >>> theta, omega = gyroscopic.gyroscopic_numeric(pk.Spheroid(1.5), 1.5607963, 10.5, [0.0, 5.0])
    >>> theta.round(6)
    array([1.560796, 0.63546 ])
    """
    from scipy.integrate import solve_ivp

    body = _body(body)
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    omega0 = check_finite("omega0", omega0, nonzero=True)
    T = np.atleast_1d(check_array("T", T, nonnegative=True))
    rtol = check_range("rtol", rtol, *RTOL_RANGE, closed="lr")

    def end(T_, y, body_):
        return _mean_slip(body_, y[1], y[0])

    end.terminal = True
    sol = solve_ivp(_rhs, (0.0, float(T.max())), [omega0, theta0], args=(body,), method="DOP853",
                    rtol=rtol, atol=1e-14, dense_output=True, events=end)
    if sol.status < 0 or sol.sol is None:
        raise ConvergenceError(f"the mean equations (3.16) could not be integrated: {sol.message}")
    th, om = np.empty_like(T), np.empty_like(T)
    for k, t in enumerate(T):
        tt = min(t, sol.t[-1])
        om[k], th[k] = sol.sol(tt)
    return th, om


@finite_result
def gyroscopic_closed(a: float, J: float, theta0: float, T, *, A: float | None = None):
    """Closed form (3.18)-(3.19) for a spheroid of aspect ratio a: returns (theta(T), Omega(T)).

    After the rise ends (q (T - T0) reaches 0 or -pi/2) the state is held at the end of the rise.

    Parameters
    ----------
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis), in [1e-4, 1e4], not 1
        (a sphere does not rise).
    J : float
        The Jellett constant J = A Omega h (3.17), finite and nonzero.
    theta0 : float
        Initial mean inclination, radians: in (0, pi/2) or (pi/2, pi) (flip symmetry).
    T : float or array_like
        Slow times T = mu t: finite numbers, at least one.
    A : float, optional
        The spheroid's transverse moment of inertia about G, units M b^2 (C <= 2 A with
        C = 2/5); default the uniform spheroid's, (1 + a^2)/5. Omega = J / (A h).

    Returns
    -------
    tuple of numpy.ndarray
        (theta(T), Omega(T)), each of the shape of ``T``.

    Raises
    ------
    ParameterError
        If ``a`` is not a finite number > 0, is 1 or is outside [1e-4, 1e4], ``J`` is 0 or not
        finite, ``theta0`` is outside (0, pi), ``T`` is not finite numbers (or is empty), ``A`` is
        not a valid moment, or if the result is not finite (an overflow of double precision or a
        singular configuration), naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> theta, omega = pk.theory.gyroscopic_closed(1.5, 6.83, 1.5607963, [0.0, 5.0])
    >>> theta.round(6), omega.round(6)
    (array([1.560796, 0.636347]), array([10.507036,  7.813401]))
    """
    a = check_positive("a", a)
    if a == 1.0:
        raise ParameterError("a", "must differ from 1: a sphere does not rise (h_theta = 0; use gyroscopic_numeric)", a)
    J = check_finite("J", J, nonzero=True)
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    T = check_array("T", T)
    flip = theta0 > np.pi / 2
    th0 = np.pi - theta0 if flip else theta0
    q = a * (a - 1) / (J * abs(a - 1))
    T0 = np.arctan(np.tan(th0) / a) / q
    arg = q * (T - T0)
    # the rise runs while q (T - T0) is in (-pi/2, 0): theta -> 0 (prolate) or pi/2 (oblate)
    arg = np.clip(arg, -np.pi / 2 + 1e-300, 0.0)
    th = np.arctan(-a * np.tan(arg))
    th = np.where(arg <= -np.pi / 2, np.pi / 2, th)
    if flip:
        th = np.pi - th
    body = Spheroid(a) if A is None else Spheroid(a, A=A)
    h = body.h(th)[0]
    return th, J / (body.A * h)


@finite_result
def gyroscopic_solution(body: Body, theta0: float, *, omega0=None, n0=None, T=()) -> dict:
    """Mean theta and Omega at slow times T (>= 0, at least one) from a gyroscopic start
    (Omega0 given, or n0 with Omega on the fast branch); the closed form for spheroids
    (a != 1), (3.16) numerically otherwise.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta0 : float
        Initial inclination of the symmetry axis from the vertical, radians, in (0, pi); in
        (0, pi/2) for a start given ``n0``.
    omega0 : float, optional
        Initial precession rate Omega0, units sqrt(g/b): nonzero, abs(omega0) <= 1e12; n
        follows from the gyroscopic balance.
    n0 : float, optional
        Initial spin, units sqrt(g/b): nonzero, abs(n0) <= 1e12; Omega0 is the fast root of
        the balance. Give exactly one of ``omega0`` and ``n0``.
    T : array_like
        Slow times T = mu t: finite numbers >= 0, at least one.

    Returns
    -------
    dict
        {"theta", "Omega", "J", "Omega0", "method"}: "theta" and "Omega" are 1-d arrays, one
        value per slow time; "J" the Jellett constant A Omega0 h(theta0) (3.17); "Omega0"
        the initial precession rate; "method" "closed form (3.18)" or "numerical (3.16)".

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``theta0`` is outside (0, pi), both or neither of ``omega0`` and
        ``n0`` are given, the rate given is 0, not finite or beyond 1e12 in size, the balance has no
        solution within that bound (see :func:`phasekit.gyroscopic_start`), ``T`` is not finite
        numbers >= 0 (or is empty), or if the result is not finite (an overflow of double precision
        or a singular configuration), naming the argument of largest magnitude.
    ConvergenceError
        If the mean equations (3.16) cannot be integrated (bodies other than spheroids).

    Warns
    -----
    UserWarning
        If ``n0`` is given for a prolate body.

    Examples
    --------
    >>> import phasekit as pk
    >>> sol = pk.theory.gyroscopic_solution(pk.Spheroid(1.5), 1.5607963, omega0=10.5, T=[0.0, 5.0])
    >>> sorted(sol)
    ['J', 'Omega', 'Omega0', 'method', 'theta']
    >>> sol['theta'].round(6)
    array([1.560796, 0.63546 ])
    """
    y0 = balanced_state(body, theta0, omega0=omega0, n0=n0, limit=GYRO_RATE_MAX)  # no fast motion: any rate
    T = check_array("T", T, nonnegative=True)
    om0 = float(y0[2])
    J = float(jellett_constant(body, theta0, om0))
    if isinstance(body, Spheroid) and body.a != 1.0 and body.flip_symmetric:
        th, om = gyroscopic_closed(body.a, J, theta0, T, A=body.A)
        method = "closed form (3.18)"
    else:
        th, om = gyroscopic_numeric(body, theta0, om0, T)
        method = "numerical (3.16)"
    return {"theta": np.atleast_1d(th), "Omega": np.atleast_1d(om), "J": J, "Omega0": om0, "method": method}


@finite_result
def rise_time(a: float, J: float, theta0: float) -> float:
    """Slow time T at which the closed-form rise ends (theta reaches 0 or pi/2).

    Parameters
    ----------
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis): finite, > 0, not 1.
    J : float
        The Jellett constant J = A Omega h (3.17), finite and nonzero.
    theta0 : float
        Initial mean inclination, radians, in (0, pi).

    Returns
    -------
    float
        The slow time T = mu t of the end of the rise (3.18)-(3.19).

    Raises
    ------
    ParameterError
        If ``a`` is not a finite number > 0 or is 1, ``J`` is 0 or not finite, ``theta0`` is outside
        (0, pi), or if the result is not finite (an overflow of double precision or a singular
        configuration), naming the argument of largest magnitude.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.theory import gyroscopic
    >>> round(gyroscopic.rise_time(1.5, 6.83, 1.5607963), 6)
    7.084062
    """
    a = check_positive("a", a)
    if a == 1.0:
        raise ParameterError("a", "must differ from 1: a sphere does not rise", a)
    J = check_finite("J", J, nonzero=True)
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    q = a * (a - 1) / (J * abs(a - 1))
    th0 = min(theta0, np.pi - theta0)
    T0 = np.arctan(np.tan(th0) / a) / q
    return float(T0) if q > 0 else float(T0 + np.pi / (2 * abs(q)))
