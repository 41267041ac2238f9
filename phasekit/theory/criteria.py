"""Closed-form stability criteria of the spins about the vertical and of the horizontal
precession (weak sliding friction), for the spheroid and for any body at its poles.

Each is derived where it is defined and checked against the exact linearisations in the tests
(tests/steady/test_stability_criteria.py, tests/steady/test_steady_states_of_any_body.py)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_choice, check_finite, check_positive


def _moments(A, C, a) -> tuple[float, float, float]:
    return check_positive("A", A), check_positive("C", C), check_positive("a", a)


def vertical_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Spin n0 at which the vertical spin changes stability under friction (any mu > 0).

    Small tilts ~exp(i sigma t) of a spin n about the vertical obey, without friction,
    A sigma^2 - C n sigma + (a - 1/a) = 0 (stable iff C^2 n^2 > 4 A (a - 1/a), the sleeping
    top). The contact point does not slip for sigma = n / a^2; friction damps or drives a
    mode according to the side of that frequency it lies on, so stability changes where a
    frictionless mode crosses it: (a^2 C - A) n^2 = a^3 (a^2 - 1). For the uniform spheroid
    this is n0 = sqrt(5 a^3). Returns None when there is no crossing.

    Parameters
    ----------
    A : float
        Transverse moment of inertia about the centre of mass G, units M b^2, finite > 0.
    C : float
        Axial moment of inertia about G, units M b^2, finite > 0.
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis), finite > 0.

    Returns
    -------
    float or None
        The spin n0, units sqrt(g/b): sqrt(a^3 (a^2 - 1) / (a^2 C - A)); None when
        a^2 C = A or (a^2 - 1) / (a^2 C - A) <= 0.

    Raises
    ------
    ParameterError
        If ``A``, ``C`` or ``a`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> b = pk.Spheroid(0.6)
    >>> round(pk.theory.vertical_stability_threshold(b.A, b.C, b.a), 6)
    1.03923
    """
    A, C, a = _moments(A, C, a)
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt(a**3 * (a * a - 1) / D))


def horizontal_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Precession rate at which the horizontal steady precession changes stability under weak
    friction: (a^2 C - A) Omega0^2 = a^2 - 1 (Omega0 = sqrt(5) for every uniform spheroid).
    The zero-slip crossing of the frictionless tilt oscillation, as at the vertical; found from
    the exact linearisations (stability_map study) and tested. It holds for viscous friction up to
    a coefficient of about 0.8 (a = 1.5, measured); above, a second mode goes unstable first and
    the threshold falls (mu = 1: 1.9652, mu = 5: 1.4710). :func:`equator_stability_threshold` is
    the same criterion for any flip-symmetric body. None when there is no crossing.

    Parameters
    ----------
    A : float
        Transverse moment of inertia about the centre of mass G, units M b^2, finite > 0.
    C : float
        Axial moment of inertia about G, units M b^2, finite > 0.
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis), finite > 0.

    Returns
    -------
    float or None
        The precession rate Omega0, units sqrt(g/b): sqrt((a^2 - 1) / (a^2 C - A)); None when
        a^2 C = A or (a^2 - 1) / (a^2 C - A) <= 0.

    Raises
    ------
    ParameterError
        If ``A``, ``C`` or ``a`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> b = pk.Spheroid(1.5)
    >>> round(pk.theory.horizontal_stability_threshold(b.A, b.C, b.a), 6)
    2.236068
    """
    A, C, a = _moments(A, C, a)
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt((a * a - 1) / D))


@dataclass(frozen=True)
class PoleCriterion:
    """Stability of the spin about the vertical at a pole (theta = 0 "upright" or pi "inverted")
    under sliding friction, from the local geometry: h0 = h, h2 = h_thetatheta at the pole and the
    radius of curvature rho = h0 + h2 of the surface at the contact point.

    The spin n0 state is stable iff n0^2 rho (A rho - C h0) < h2 h0^2; ``threshold`` is the
    abs(n0) where that changes (None: never), ``stable_above`` whether the fast side is stable.

    Rolling (exact Coulomb friction holding the contact, no slip), the fast-top condition: with
    zeta the horizontal part of k, the contact point lies h2 zeta from G horizontally and
    -h0 below it; no slip makes v_G = h0 zeta' - i n rho zeta (complex notation, i = e_Z x),
    and the torque about G then gives (A + h0^2) zeta'' - i (C + h0 rho) n zeta' - h2 zeta = 0.
    Its modes exp(i sigma t) are neutral iff (C + h0 rho)^2 n0^2 + 4 (A + h0^2) h2 >= 0:
    always where h2 > 0 (G at its lowest), else above ``rolling_threshold``
    2 sqrt((A + h0^2)(-h2)) / (C + h0 rho). On a point (rho = 0, h0 = -h2 = l, A + l^2 = A' the
    moment about the point) this is the classical fast-top condition C^2 n^2 > 4 A' M g l.

    Attributes
    ----------
    pole : {"upright", "inverted"}
        The pole: theta = 0 ("upright") or pi ("inverted").
    h0 : float
        h at the pole, units b.
    h2 : float
        h_thetatheta at the pole, units b.
    rho : float
        Radius of curvature h0 + h2 of the surface at the contact point, units b.
    A, C : float
        The body's transverse and axial moments of inertia about G, units M b^2.
    threshold : float or None
        abs(n0) at which the stability changes, sqrt(h2 h0^2 / (rho (A rho - C h0))), units
        sqrt(g/b); None when there is no such spin.
    stable_above : bool
        Whether the spins above ``threshold`` are the stable ones (A rho - C h0 < 0).
    rolling_threshold : float or None
        abs(n0) above which the spin is stable rolling (exact Coulomb friction), the fast-top
        condition: 2 sqrt((A + h0^2)(-h2)) / (C + h0 rho), units sqrt(g/b); None when h2 >= 0
        (stable rolling at every spin, or degenerate).

    Examples
    --------
    >>> import phasekit as pk
    >>> crit = pk.theory.pole_stability_threshold(pk.Spheroid(0.6))
    >>> isinstance(crit, pk.theory.PoleCriterion), crit.pole
    (True, 'upright')
    >>> top = pk.theory.pole_stability_threshold(pk.bodies.Cone(1.5, on="tip"), "inverted")
    >>> top.threshold, round(top.rolling_threshold, 6), top.stable_rolling(9.0)   # C^2 n^2 > 4 A' l
    (None, 8.660254, True)
    """

    pole: str
    h0: float
    h2: float
    rho: float
    A: float
    C: float

    @property
    def threshold(self) -> float | None:
        den = self.rho * (self.A * self.rho - self.C * self.h0)
        num = self.h2 * self.h0**2
        if den == 0.0 or num / den <= 0.0:
            return None
        return float(np.sqrt(num / den))

    @property
    def stable_above(self) -> bool:
        return self.A * self.rho - self.C * self.h0 < 0

    def stable(self, n0: float) -> bool:
        n0 = check_finite("n0", n0)
        return bool(n0 * n0 * self.rho * (self.A * self.rho - self.C * self.h0) < self.h2 * self.h0**2)

    @property
    def rolling_threshold(self) -> float | None:
        if not self.h2 < 0.0:
            return None
        return float(2.0 * np.sqrt((self.A + self.h0**2) * -self.h2) / (self.C + self.h0 * self.rho))

    def stable_rolling(self, n0: float) -> bool:
        """Whether the spin ``n0`` is stable rolling (exact Coulomb friction): the fast-top
        condition (C + h0 rho)^2 n0^2 + 4 (A + h0^2) h2 > 0 (class notes).

        Parameters
        ----------
        n0 : float
            The spin, units sqrt(g/b).

        Returns
        -------
        bool
            True where the rolling modes are neutral (h2 = 0, n0 = 0: degenerate, False).

        Examples
        --------
        >>> import phasekit as pk
        >>> crit = pk.theory.pole_stability_threshold(pk.bodies.Cone(1.5, on="tip"), "inverted")
        >>> crit.stable_rolling(8.0), crit.stable_rolling(-9.0)
        (False, True)
        """
        n0 = check_finite("n0", n0)
        return bool((self.C + self.h0 * self.rho) ** 2 * n0 * n0 + 4.0 * (self.A + self.h0**2) * self.h2 > 0.0)

    def to_dict(self, n0: float | None = None) -> dict:
        d = {"criterion": "stable under sliding friction iff n0^2 rho (A rho - C h0) < h2 h0^2",
             "h0": self.h0, "h2": self.h2, "rho": self.rho, "critical_spin": self.threshold,
             "stable_above_critical_spin": self.stable_above,
             "rolling_criterion": "stable rolling (exact Coulomb) iff (C + h0 rho)^2 n0^2 + 4 (A + h0^2) h2 > 0",
             "rolling_critical_spin": self.rolling_threshold}
        if n0 is not None:
            d["stable_under_sliding_friction"] = self.stable(n0)
            d["stable_rolling"] = self.stable_rolling(n0)
        return d


def pole_stability_threshold(body, pole: str = "upright") -> PoleCriterion:
    """The closed-form stability criterion of the spin about the vertical at a pole, any body.

    Derived here (the argument of :func:`vertical_stability_threshold`, for a general support
    function). Near the pole h = h0 + h2 delta^2 / 2, so the contact point lies h2 xi from the
    axis through G (xi the horizontal part of k) and the frictionless small tilts ~exp(i sigma t)
    of a spin n obey A sigma^2 - C n sigma - h2 = 0. The slip of such a mode is proportional to
    h0 (n - sigma) + n h2, zero for sigma = n rho / h0. A linear mode of the dissipative system
    can be neutral (purely imaginary) only if it does no work, i.e. does not slip, so stability
    changes exactly where a frictionless mode has sigma = n rho / h0:

        n^2 rho (A rho - C h0) = h2 h0^2,

    for every sliding law that dissipates whenever it slips (viscous, regularised Coulomb) and
    every friction coefficient. Spheroid: h0 = a, h2 = (1 - a^2)/a, rho = 1/a gives
    (a^2 C - A) n^2 = a^3 (a^2 - 1). Eccentric sphere: rho = 1, h0 = 1 -+ alpha, h2 = +-alpha give
    phasekit.theory.tippetop's upright_unstable_spin and inverted_stable_spin. Under exact Coulomb
    friction the zero-slip state rolls and the linearisation is neutral (phasekit.steady.linearisation).

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(0.6)``.
    pole : {"upright", "inverted"}, optional
        The pole: theta = 0 ("upright", the default) or theta = pi ("inverted").

    Returns
    -------
    PoleCriterion
        The pole's h0, h2 and rho with the body's A and C; its ``threshold`` is the critical
        abs(n0) and its ``stable(n0)`` the criterion at a spin n0.

    Raises
    ------
    ParameterError
        If ``pole`` is not "upright" or "inverted".

    Examples
    --------
    >>> import phasekit as pk
    >>> crit = pk.theory.pole_stability_threshold(pk.EccentricSphere(0.3, A=0.38, C=0.4))
    >>> crit.pole, round(crit.threshold, 6), crit.stable(20.0)
    ('upright', 1.212436, False)
    """
    check_choice("pole", pole, ("upright", "inverted"))
    h0, _, h2 = body.h(0.0 if pole == "upright" else np.pi)
    return PoleCriterion(pole, float(h0), float(h2), float(h0 + h2), float(body.A), float(body.C))


def equator_stability_threshold(body) -> float | None:
    """Omega0 at which the horizontal precession of a body with h_theta(pi/2) = 0 changes
    stability, in the weak-friction regime: Omega0^2 (C rho_m / h_e - A) = h2 with h_e = h(pi/2),
    h2 = h_thetatheta(pi/2), rho_m = h_e + h2 (spheroid: (a^2 C - A) Omega0^2 = a^2 - 1).

    Derived here from the linearisation about the horizontal state: stability changes where the
    frictionless tilt oscillation has zero slip. Measured (tests): exact for viscous friction
    below a body-dependent coefficient (a = 1.5 uniform: the threshold is sqrt(5) for every
    mu <= 0.8); above it a second mode goes unstable first and the threshold falls (mu = 1:
    1.9652, mu = 5: 1.4710). None when the body is not balanced at pi/2 or there is no crossing.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C), e.g. ``Spheroid(1.5)``.

    Returns
    -------
    float or None
        The precession rate Omega0, units sqrt(g/b): sqrt(h2 / (C rho_m / h_e - A)); None when
        h_theta(pi/2) != 0 (to 1e-14) or there is no crossing.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.theory import criteria
    >>> round(criteria.equator_stability_threshold(pk.Spheroid(1.5)), 6)
    2.236068
    """
    he, h1, h2 = body.h(np.pi / 2)
    if abs(h1) > 1e-14:
        return None
    den = body.C * (he + h2) / he - body.A
    if den == 0.0 or h2 / den <= 0.0:
        return None
    return float(np.sqrt(h2 / den))
