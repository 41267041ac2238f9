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

import warnings

import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_finite, check_range, check_vector
from ..bodies.body import Body
from .charts import get_chart

__all__ = ["gyroscopic_start", "vertical_spin_start", "raw_start", "to_chart", "to_paper"]

#: the largest rate (units sqrt(g/b)) a start may have: beyond it the dynamics are beyond
#: double precision (Omega^2 terms against 1) and the Taylor steps vanish
RATE_MAX = 1e5
#: the largest rate the gyroscopic (mean) solution takes: it is closed-form (or a slow-time
#: quadrature) and does not integrate the fast motion, so only overflow of A Omega^2 limits it
GYRO_RATE_MAX = 1e12


def _q(body: Body, theta: float) -> float:
    """h_theta / sin(theta) = -H'(cos theta), evaluated without dividing by sin(theta)."""
    return -body.height_slope(np.cos(theta))[1]


def _rate(name: str, value, limit: float = RATE_MAX) -> float:
    v = check_finite(name, value, nonzero=True)
    if abs(v) > limit:
        raise ParameterError(name, f"must be nonzero with |{name}| <= {limit:g}", value)
    return v


def gyroscopic_start(body: Body, theta0: float, *, omega0: float | None = None, n0: float | None = None) -> np.ndarray:
    """A start on the slow (gyroscopic-balance) manifold.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.
    theta0 : float
        Initial inclination of the symmetry axis from the vertical, radians, in (0, pi);
        in (0, pi/2) for a start given ``n0``.
    omega0 : float, optional
        Precession rate (prolate starts near the horizontal): n follows from the balance.
        Units sqrt(g/b), nonzero with ``abs(omega0) <= 1e5``. Give exactly one of ``omega0``
        and ``n0``.
    n0 : float, optional
        Spin (oblate starts near the vertical): Omega is the fast root of the balance.
        Units sqrt(g/b), nonzero with ``abs(n0) <= 1e5``.

    Returns
    -------
    numpy.ndarray
        Shape (6,): (U, V, Omega, Lambda, theta, n) = (0, 0, Omega0, 0, theta0, n), the
        paper's state.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``theta0`` is outside (0, pi), both or neither of
        ``omega0`` and ``n0`` are given, the rate given is 0, not finite or beyond 1e5 in
        size, or the balance has no solution within that bound: ``omega0`` too small (it
        needs a spin ``abs(n) > 1e5``), ``theta0`` not in (0, pi/2) with ``n0``, ``n0`` too
        small for a gyroscopic balance at ``theta0``, or a fast root ``abs(Omega) > 1e5``.

    Warns
    -----
    UserWarning
        If ``n0`` is given for a prolate body (whose start is normally given ``omega0``).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5).round(4)
    array([ 0.    ,  0.    , 10.5   ,  0.    ,  1.5608,  0.1736])
    """
    return balanced_state(body, theta0, omega0=omega0, n0=n0)


def balanced_state(body: Body, theta0: float, *, omega0=None, n0=None, limit: float = RATE_MAX) -> np.ndarray:
    """:func:`gyroscopic_start` with rates up to ``limit`` (the gyroscopic solution's is
    GYRO_RATE_MAX)."""
    if not isinstance(body, Body):
        raise ParameterError("body", "must be a phasekit Body such as Spheroid(a)", body)
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both (prolate: omega0; oblate: n0)", show_value=False)
    A, C = body.A, body.C
    c = np.cos(theta0)
    q = _q(body, theta0)
    if omega0 is not None:
        omega0 = _rate("omega0", omega0, limit)
        n = (A * omega0 * c - q / omega0) / C
        if not abs(n) <= limit:
            raise ParameterError("omega0", f"is too small for a gyroscopic balance at theta0 = {theta0:g} (it needs a "
                                           f"spin |n| = {abs(n):.3g} > {limit:g})", omega0)
        return np.array([0.0, 0.0, omega0, 0.0, theta0, n])
    n0 = _rate("n0", n0, limit)
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


def vertical_spin_start(theta0: float, n0: float) -> np.ndarray:
    """Spun about the vertical with the centre of mass at rest: angular velocity n0 e_Z at
    inclination theta0, i.e. Omega = n0, Lambda = 0, n = n0 cos(theta0), U = V = 0 (the
    usual start of a tippe top).

    Parameters
    ----------
    theta0 : float
        Inclination of the symmetry axis from the vertical, radians, in [0, pi].
    n0 : float
        The rate of the spin about the vertical, units sqrt(g/b): nonzero, with
        ``abs(n0) <= 1e5``.

    Returns
    -------
    numpy.ndarray
        Shape (6,): (U, V, Omega, Lambda, theta, n) = (0, 0, n0, 0, theta0, n0 cos(theta0)).

    Raises
    ------
    ParameterError
        If ``theta0`` is outside [0, pi], or ``n0`` is 0, not finite or ``abs(n0) > 1e5``.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.vertical_spin_start(0.1, 15.0)
    array([ 0.        ,  0.        , 15.        ,  0.        ,  0.1       ,
           14.92506248])
    """
    theta0 = check_range("theta0", theta0, 0.0, np.pi, closed="lr", label="[0, pi]")
    n0 = _rate("n0", n0)
    return np.array([0.0, 0.0, n0, 0.0, theta0, n0 * np.cos(theta0)])


def raw_start(state, *, chart="euler") -> np.ndarray:
    """Validate a raw (U, V, Omega, Lambda, theta, n); theta in (0, pi) for the Euler chart,
    [0, pi] for the vector chart, which is regular at the poles."""
    y = check_vector("state", state, 6)
    if get_chart(chart).regular_at_poles:
        check_range("theta", y[4], 0.0, np.pi, closed="lr", label="[0, pi]")
    else:
        check_range("theta", y[4], 0.0, np.pi, label="(0, pi) in the Euler chart (the vector chart is regular at 0 and pi)")
    for i, name in ((0, "U"), (1, "V"), (2, "Omega"), (3, "Lambda"), (5, "n")):
        if abs(y[i]) > RATE_MAX:
            raise ParameterError(name, f"must satisfy |{name}| <= {RATE_MAX:g}", y[i])
    return y


def to_chart(chart, y) -> np.ndarray:
    """A state in the paper's variables expressed in the coordinates of ``chart``;
    :func:`to_paper` is its inverse.

    Parameters
    ----------
    chart : {"euler", "vector"} or Chart
        The chart: its name, or a contact chart object (:mod:`phasekit.core.charts`).
    y : array_like
        The paper's state (U, V, Omega, Lambda, theta, n): 6 finite numbers.

    Returns
    -------
    numpy.ndarray
        The state in the chart's coordinates: the same 6 numbers for "euler", (k, w, v)
        (8 numbers, the axis in the X-Z plane) for "vector".

    Raises
    ------
    ParameterError
        If ``chart`` is not "euler", "vector" or a contact chart (the flight chart, by name
        or object, is refused), or ``y`` is not 6 finite numbers.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> pk.core.to_chart("vector", [0.0, 0.0, 2.0, 0.0, np.pi / 2, 10.0]).round(3)
    array([ 1.,  0.,  0., 10.,  0.,  2.,  0.,  0.])
    """
    return get_chart(chart).from_paper(check_vector("y", y, 6))


def to_paper(chart, x) -> np.ndarray:
    """A state of ``chart`` in the paper's variables (U, V, Omega, Lambda, theta, n): the
    inverse of :func:`to_chart`.

    Parameters
    ----------
    chart : {"euler", "vector"} or Chart
        The chart of ``x``: its name, or a contact chart object (:mod:`phasekit.core.charts`).
    x : array_like
        A state of the chart: 6 numbers for "euler", 8 for "vector".

    Returns
    -------
    numpy.ndarray
        Shape (6,): (U, V, Omega, Lambda, theta, n).

    Raises
    ------
    ParameterError
        If ``chart`` is not "euler", "vector" or a contact chart (the flight chart, by name
        or object, is refused).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> x = pk.core.to_chart("vector", [0.0, 0.0, 2.0, 0.0, np.pi / 2, 10.0])
    >>> pk.core.to_paper("vector", x).round(6)
    array([ 0.      ,  0.      ,  2.      ,  0.      ,  1.570796, 10.      ])
    """
    return get_chart(chart).to_paper(np.asarray(x, dtype=float))
