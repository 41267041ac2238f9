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

from .._runtime.validate import check_finite, check_range, check_vector
from ..bodies.body import Body
from ..bodies.spheroid import Spheroid
from ..errors import ParameterError
from ..friction.laws import Coulomb, FrictionLaw
from ..theory.gyroscopic import RATE_MAX, balanced_state, checked_rate
from ..theory.paper import PAPER_CASES
from .charts import get_chart
from .model import Model


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


def vertical_spin_start(theta0: float, n0: float, *, v0: float = 0.0) -> np.ndarray:
    """Spun about the vertical with the centre of mass at rest: angular velocity n0 e_Z at
    inclination theta0, i.e. Omega = n0, Lambda = 0, n = n0 cos(theta0), U = V = 0 (the
    usual start of a tippe top); or with G sliding at ``v0`` along e_X. With theta0 = 0 (or pi)
    and ``simulate(..., mode="face")`` it is the start of a body lying on its face, sliding at v0
    and spinning at n0 (:mod:`phasekit.core.face`).

    Parameters
    ----------
    theta0 : float
        Inclination of the symmetry axis from the vertical, radians, in [0, pi].
    n0 : float
        The rate of the spin about the vertical, units sqrt(g/b): nonzero, with
        ``abs(n0) <= 1e5``.
    v0 : float, optional
        The velocity of G along e_X, units sqrt(g b), ``abs(v0) <= 1e5`` (default 0).

    Returns
    -------
    numpy.ndarray
        Shape (6,): (U, V, Omega, Lambda, theta, n) = (v0, 0, n0, 0, theta0, n0 cos(theta0)).

    Raises
    ------
    ParameterError
        If ``theta0`` is outside [0, pi], ``n0`` is 0, not finite or ``abs(n0) > 1e5``, or ``v0``
        is not finite or ``abs(v0) > 1e5``.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.vertical_spin_start(0.1, 15.0)
    array([ 0.        ,  0.        , 15.        ,  0.        ,  0.1       ,
           14.92506248])
    >>> disk = pk.Disk(0.0)                     # on its face: sliding at 1, spinning at 3, to rest
    >>> traj = pk.simulate(pk.Model(disk, pk.Coulomb(0.3)), pk.core.vertical_spin_start(0.0, 3.0, v0=1.0), 50.0,
    ...                    mode="face")
    >>> traj.status.value, round(traj.face.t_stop_slide, 4), round(traj.face.t_stop_spin, 4)
    ('rest', 8.5113, 8.5113)
    """
    theta0 = check_range("theta0", theta0, 0.0, np.pi, closed="lr", label="[0, pi]")
    n0 = checked_rate("n0", n0)
    v0 = check_range("v0", v0, -RATE_MAX, RATE_MAX, closed="lr", label=f"[-{RATE_MAX:g}, {RATE_MAX:g}]")
    return np.array([v0, 0.0, n0, 0.0, theta0, n0 * np.cos(theta0)])


def axis_spin_start(body: Body, theta0: float, n0: float, *, mu: float | None = None) -> tuple[np.ndarray, str | None]:
    """A top as people launch it: spun about its own axis at n0, tilted theta0, with the slow
    precession if there is one, else none (and a note saying so).

    On a point (the contact on the axis, x_P = 0: a cone on its tip) the slow precession is the
    Lagrange top's steady one, exact while friction holds the point: the slow root of
    (A + l^2) cos(theta) Omega^2 - C n Omega - l = 0 (l = h_theta / sin(theta), G circling the
    vertical through the point at V = -l Omega sin(theta)); it exists iff
    C^2 n^2 >= 4 (A + l^2) l |cos(theta)| (the fast-top condition at that tilt) and needs the
    friction l Omega^2 sin(theta) <= mu. On any other body it is the slow root of the gyroscopic
    balance (3.14c), A cos(theta) sin(theta) Omega^2 - C n sin(theta) Omega - h_theta = 0, with G
    at rest (a leading-order balance: the top nutates a little about it). At a pole the spin is
    about the vertical, Omega = 0.

    Parameters
    ----------
    body : Body
        The top, e.g. ``Cone(1.5, on="tip")``.
    theta0 : float
        The tilt, radians in [0, pi] (a cone on its tip: near pi).
    n0 : float
        The spin about the axis, units sqrt(g/b): nonzero, ``abs(n0) <= 1e5``.
    mu : float, optional
        The friction coefficient (exact Coulomb): a point's precession needing more friction
        than that is not used.

    Returns
    -------
    (numpy.ndarray, str or None)
        The state (U, V, Omega, Lambda, theta, n) and None, or the state with zero precession
        (Omega = 0, G at rest) and a note on why there is no slow precession.

    Raises
    ------
    ParameterError
        If ``theta0`` is outside [0, pi], or ``n0`` is 0, not finite or ``abs(n0) > 1e5``.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> from phasekit.core.starts import axis_spin_start
    >>> y, note = axis_spin_start(pk.bodies.Cone(1.5, on="tip"), np.pi - 0.1, 30.0)
    >>> [round(float(v), 4) for v in y], note      # Omega ~ -l / (C n): slow, G circling the tip
    ([0.0, 0.0143, -0.1277, 0.0, 3.0416, 30.0], None)
    """
    theta0 = check_range("theta0", theta0, 0.0, np.pi, closed="lr", label="[0, pi]")
    n0 = checked_rate("n0", n0)
    s, c = np.sin(theta0), np.cos(theta0)
    if s < 1e-12:
        return np.array([0.0, 0.0, 0.0, 0.0, theta0, n0]), None
    h, ht = (float(v) for v in body.h(theta0)[:2])
    point = abs(h * s + ht * c) <= 1e-12 * (1.0 + abs(h))  # x_P = 0: the contact on the axis
    if point:
        lever = ht / s
        big, a2, a0 = body.C * n0, (body.A + lever * lever) * c, -lever
    else:
        big, a2, a0 = body.C * n0 * s, body.A * c * s, -ht
    disc = big * big - 4.0 * a2 * a0
    none = np.array([0.0, 0.0, 0.0, 0.0, theta0, n0])
    if disc < 0.0:
        what = "C^2 n^2 < 4 (A + l^2) l |cos(theta)|" if point else "the gyroscopic balance has no real root"
        return none, (f"no slow precession at this spin and tilt ({what}): started spinning about its axis with "
                      "zero precession")
    omega = 2.0 * a0 / (big + np.copysign(np.sqrt(disc), big))  # the slow root, without cancellation
    if point:
        if mu is not None and lever * omega * omega * s > mu:
            return none, (f"its slow precession Omega = {omega:.4g} needs friction {lever * omega * omega * s:.3g} > "
                          f"mu = {mu:g} at the point: started with zero precession")
        return np.array([0.0, -lever * omega * s, omega, 0.0, theta0, n0]), None
    return np.array([0.0, 0.0, omega, 0.0, theta0, n0]), None


def rolled_start(body: Body, theta0: float, speed: float) -> np.ndarray:
    """Rolled along the table at ``speed`` without slip, tilted theta0 (a coin rolled on its edge:
    theta0 = pi/2): Omega = Lambda = 0, the spin n = speed / x_P about the axis, V = -n x_P, with
    x_P = h sin(theta) + h_theta cos(theta) the contact's distance from G along the table
    (phasekit.steady.rolling: a steady straight rolling where h_theta = 0, else a start that
    leans and curves).

    Parameters
    ----------
    body : Body
        The body, e.g. ``Disk(0.1)`` (a coin).
    theta0 : float
        The tilt, radians in (0, pi).
    speed : float
        The speed of G, units sqrt(g b): nonzero, ``abs(speed) <= 1e5`` (its sign: the way it rolls).

    Returns
    -------
    numpy.ndarray
        Shape (6,): (U, V, Omega, Lambda, theta, n) = (0, -speed, 0, 0, theta0, speed / x_P).

    Raises
    ------
    ParameterError
        If ``theta0`` is outside (0, pi), ``speed`` is 0, not finite or beyond 1e5, or the
        contact is on the axis there (x_P = 0: a point cannot roll).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> from phasekit.core.starts import rolled_start
    >>> rolled_start(pk.Disk(0.1), np.pi / 3, 2.0).round(6)
    array([ 0.      , -2.      ,  0.      ,  0.      ,  1.047198,  2.      ])
    """
    theta0 = check_range("theta0", theta0, 0.0, np.pi, label="(0, pi)")
    speed = checked_rate("speed", speed)
    h, ht = (float(v) for v in body.h(theta0)[:2])
    x_p = h * np.sin(theta0) + ht * np.cos(theta0)
    if abs(x_p) <= 1e-12 * (1.0 + abs(h)):
        raise ParameterError("theta0", "puts the contact on the axis (a point): it cannot roll", theta0)
    n = speed / x_p
    if abs(n) > RATE_MAX:
        raise ParameterError("speed", f"needs a spin |n| = {abs(n):.3g} > {RATE_MAX:g}", speed)
    return np.array([0.0, -n * x_p, 0.0, 0.0, theta0, n])


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

    See Also
    --------
    to_paper
        its inverse
    phasekit.Model
        its ``chart`` (``from_paper``, ``to_paper``) is what these call

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


#: the keywords of :func:`paper_start`
KEYWORDS = ("n0", "omega0", "friction")


def paper_start(label: str, *, n0: float | None = None, omega0: float | None = None,
                friction: FrictionLaw | None = None, **unknown) -> tuple[Model, np.ndarray]:
    """The printed start (5.1) or (5.2) with its model, digit for digit.

    Parameters
    ----------
    label : {"5.1", "5.2"}
        The equation number (``"(5.2)"`` is accepted too).
    n0 : float, optional
        (5.1) only: the spin (default 10.5, printed as jumping); Omega = C n0 / A.
    omega0 : float, optional
        (5.2) only: the precession rate (default 10.5, printed as jumping).
    friction : FrictionLaw, optional
        Default: exact Coulomb friction with mu = 0.1 (the paper's law).
    **unknown
        None: any other keyword raises :class:`ParameterError` naming it.

    Returns
    -------
    (Model, ndarray)
        The model (uniform spheroid a = 2/3 in the vector chart for (5.1), which starts 4e-6
        from the vertical; a = 3/2 in the Euler chart for (5.2)) and the start in its chart.

    Notes
    -----
    Which start each number of the README uses:

    * "(5.2) sticks at t = 0.011 and never rises" (exact Coulomb) and "jumps at 42.25 / 52.34 /
      156.59 for eps = 1e-2 / 1e-3 / 1e-4" (``RegularisedCoulomb(0.1, eps)``): this start,
      ``paper_start("5.2", friction=...)``.
    * "(5.1) sticks at t = 1.1e-4": ``paper_start("5.1")``.
    * The *literal* threshold definition (10.22 at a = 1.5 with eps = 1e-3) and
      "64.16 (sticking at 0.022)": the unrounded eigenvector start
      ``unstable_manifold_start(..., delta=0.01 or 0.02)``, not this one.

    The eigenvector start at delta = 0.02 rounds to (5.2) component by component, but its
    theta offset is 1.15e-3 (printed 1e-3), and rounding that component alone moves the jump
    (eps = 1e-3) from t = 64.16 to 52.34; rounding U, V or Lambda moves it by < 0.02, n by
    0.9. What sets t_jump is the transverse slip of the contact point at the start, u_Y: the
    residue of terms of size 0.01-0.02 that nearly cancel, -0.0072 for the eigenvector and
    -0.0036 for (5.2) (both below 10 eps: the regularised law starts them stuck; exact
    Coulomb sticks at t = 0.022 and 0.011). t_jump is close to one curve of u_Y, peaked at
    u_Y ~ -0.007, so inside the rounding box t_jump spans 46.8-61.7 across theta's interval,
    46.8-67.2 across n's, and 44.9-67.8 over a 15 x 15 grid of (theta, n) (one of 225 runs
    does not jump by t = 300); the eigenvector start sits on the peak, (5.2) on its flank.
    The printed digits fix t_jump only to about +-10 (``examples/paper_start_rounding.py``).

    Examples
    --------
    >>> import phasekit as pk
    >>> model, x0 = pk.paper_start("5.2")
    >>> model
    Model(Spheroid(a=1.5), coulomb(mu=0.1), chart='euler')
    """
    if unknown:
        name = sorted(unknown)[0]
        raise ParameterError(name, f"is not a keyword of paper_start (valid keywords: {', '.join(KEYWORDS)})",
                             unknown[name])
    given = label
    if isinstance(label, str) and label.startswith("(") and label.endswith(")"):
        label = label[1:-1]
    if not isinstance(label, str) or label not in PAPER_CASES:
        raise ParameterError("label", f"must be one of {', '.join(PAPER_CASES)} (or in parentheses, \"(5.2)\")", given)
    case = PAPER_CASES[label]
    other = "omega0" if case.parameter == "n0" else "n0"
    if (omega0 if other == "omega0" else n0) is not None:
        raise ParameterError(other, f"does not apply to ({label}), which takes {case.parameter}", show_value=False)
    value = n0 if case.parameter == "n0" else omega0
    value = case.jump if value is None else check_finite(case.parameter, value, nonzero=True)
    if friction is not None and not isinstance(friction, FrictionLaw):
        raise ParameterError("friction", "must be a phasekit FrictionLaw such as Coulomb(0.1)", friction)
    law = Coulomb(0.1) if friction is None else friction
    chart = "vector" if label == "5.1" else "euler"
    return Model(Spheroid(case.a), law, chart), to_chart(chart, case.state(value))
