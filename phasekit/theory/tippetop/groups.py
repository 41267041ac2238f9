"""Ueda, Sasaki & Watanabe's groups (I never flips, II inverts completely, III turns over to theta_f)
and the final angle theta_f.

The model, the units and the status of every result: :mod:`phasekit.theory.tippetop`.
"""

from __future__ import annotations

import math

import numpy as np

from .geometry import margins, params
from .inversion import jellett_of_vertical_start
from .steady import steady_state_jellett_sq


def ueda_group_limit(alpha, A, C) -> str:
    """The fast-spin classification in the sense of [USW05]'s abstract (derived here; their
    own boundaries were not seen): "I" (never flips, gamma <= 1 - alpha: the upright state is
    stable at every spin), "II" (inverts completely once spun fast enough,
    1 - alpha < gamma < 1 + alpha, the classical interval) or "III" (gamma >= 1 + alpha: the
    inverted state is never stable and a fast top settles at theta_f < pi, see ``theta_f_limit``).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.

    Returns
    -------
    {"I", "II", "III"}
        The group.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.ueda_group_limit(0.3, 0.38, 0.4)
    'II'
    """
    a, A, C = params(alpha, A, C)
    up, inv = margins(a, A, C)
    if up <= 0:
        return "I"
    if inv > 0:
        return "II"
    return "III"

def _quartic_roots(a, A, C, lam2):
    """Real roots in [-1, 1] of F(z) = alpha f(z)^2 - lam2 D(z) (sign of g(z) - lam2 where D > 0)."""
    delta = C - A
    fpoly = np.array([delta, -2.0 * C * a, A + C * a * a])
    F = a * np.polymul(fpoly, fpoly)
    F = np.polyadd(F, -lam2 * np.array([-delta, C * a]))
    F = np.trim_zeros(F, "f")
    if F.size <= 1:
        return []
    roots = np.roots(F)
    scale = max(1.0, float(np.max(np.abs(roots)))) if roots.size else 1.0
    out = []
    dF = np.polyder(F)
    for r in roots:
        if abs(r.imag) > 1e-7 * scale:
            continue
        z = float(r.real)
        for _ in range(3):  # Newton polish on the real polynomial
            d = np.polyval(dF, z)
            if d == 0:
                break
            z -= np.polyval(F, z) / d
        if -1.0 - 1e-12 <= z <= 1.0 + 1e-12:
            out.append(min(1.0, max(-1.0, z)))
    return sorted(out, reverse=True)

def _classify(a, A, C, lam2) -> tuple[str, float]:
    if not lam2 > 0:
        return "never", 0.0
    g1 = steady_state_jellett_sq(a, A, C, 1.0)
    if lam2 <= g1:
        return "never", 0.0
    # dV/dz = (D / f^2)(lam2 - g(z)) > 0 at z = 1: V falls as theta grows, until the first z
    # (going down from 1) where g(z) >= lam2, i.e. F(z) = alpha f^2 - lam2 D >= 0 (F > 0 where D <= 0).
    roots = [z for z in _quartic_roots(a, A, C, lam2) if z < 1.0]
    if roots:
        z = roots[0]
        if z > -1.0:
            return "partial", math.acos(z)
    return "full", math.pi

def ueda_group(alpha, A, C, n, *, theta0: float = 0.0) -> str:
    """Predicted fate of a top launched with phasekit's ``vertical_spin_start(theta0, n)``
    (theta0 small; for theta0 = 0, n is the spin of the upright top): "never" (stays near
    upright), "full" (ends spinning inverted, theta = pi) or "partial" (settles in the steady
    precession at theta_f < pi, see ``theta_f``).

    Derived here, not quoted (the finite-spin analogue of [USW05]'s Groups I / II / III, whose
    exact finite-spin statements were not seen). With lambda the start's Jellett integral
    (conserved) and g(z) = ``steady_state_jellett_sq``:

    * lambda^2 <= g(1) (upright stable; always so if gamma <= 1 - alpha): "never";
    * otherwise the energy descends from theta = 0 to the first steady state z = cos theta
      with g(z) >= lambda^2, which is a minimum of V: "partial" if it is interior,
      "full" if g < lambda^2 on all of [-1, 1] (no interior steady state, inverted state stable).

    For gamma in the classical interval and n -> inf this gives "full"; for gamma >= 1 + alpha
    "partial" with theta_f -> ``theta_f_limit``; for gamma <= 1 - alpha always "never".
    Validated in the tests by long simulations with a viscous friction law. Caveat: the rule
    assumes the motion stays close to the slow energy descent (small theta0, weak friction);
    where two stable states coexist (e.g. upright and intermediate) only the one reached from
    near upright is reported. It also assumes the top keeps sliding: under exact Coulomb
    friction the slip can vanish and the top then rolls, which does no work, so it inverts
    less than predicted (studies/tippe_top.py, mu = 0.3: the prediction holds in 164 of 165
    viscous runs and 108 of 165 Coulomb runs; every Coulomb exception stuck and rolled).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    n : float
        Rate of the spin of the start about the vertical, units sqrt(g/R), finite (for
        theta0 = 0, the spin of the upright top).
    theta0 : float, optional
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi]
        (default 0).

    Returns
    -------
    {"never", "full", "partial"}
        The predicted fate.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, ``theta0`` is
        outside [0, pi], or ``n`` is not finite (the error names ``n0``).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.ueda_group(0.3, 0.38, 0.4, 15.0, theta0=0.1)
    'full'
    """
    a, A, C = params(alpha, A, C)
    lam = jellett_of_vertical_start(a, A, C, theta0, n)
    return _classify(a, A, C, lam * lam)[0]

def theta_f(alpha, A, C, n, *, theta0: float = 0.0) -> float:
    """The final inclination predicted by ``ueda_group`` for ``vertical_spin_start(theta0, n)``:
    theta_f = arccos(z_f) for the "partial" outcome, where z_f is the largest root in (-1, 1) of
    the quartic alpha f(z)^2 = lambda^2 ((A - C) z + C alpha) (i.e. g(z_f) = lambda^2 with
    g'(z_f) <= 0), f(z) = A (1 - z^2) + C (z - alpha)^2; 0 for "never", pi for "full".
    Derived here, not quoted ([USW05]'s theta_f formula was not seen).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    n : float
        Rate of the spin of the start about the vertical, units sqrt(g/R), finite.
    theta0 : float, optional
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi]
        (default 0).

    Returns
    -------
    float
        theta_f, radians, in [0, pi]: 0 for "never", pi for "full".

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, ``theta0`` is
        outside [0, pi], or ``n`` is not finite (the error names ``n0``).

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.theta_f(0.3, 0.38, 0.4, 15.0, theta0=0.1), 6)
    3.141593
    """
    a, A, C = params(alpha, A, C)
    lam = jellett_of_vertical_start(a, A, C, theta0, n)
    return _classify(a, A, C, lam * lam)[1]

def theta_f_limit(alpha, A, C) -> float:
    """Limit of theta_f for n -> inf in group III (gamma > 1 + alpha):
    cos(theta_f) = C alpha / (C - A) = -alpha / (gamma - 1), the angle where D(z) = 0 (the
    steady precession rate diverges there). nan outside group III. Derived here, not quoted.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.

    Returns
    -------
    float
        The limit of theta_f, radians, in (pi/2, pi); nan outside group III.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.groups.theta_f_limit(0.3, 0.38, 0.4), 6)
    nan
    """
    a, A, C = params(alpha, A, C)
    if margins(a, A, C)[1] >= 0:
        return math.nan
    return math.acos(C * a / (C - A))
