"""When the tippe top inverts: the classical interval, Jellett's quantity of a start, the spin for a
Jellett value and the thresholds of a full inversion.

The model, the units and the status of every result: :mod:`phasekit.theory.tippetop`.
"""

from __future__ import annotations

import math

import numpy as np

from ..._runtime.validate import check_finite, check_positive, check_range, check_real
from ...errors import ParameterError
from .geometry import margins, params, theta0_of
from .steady import jellett_threshold, steady_state_jellett_sq


def inversion_interval(alpha) -> tuple[float, float]:
    """The open interval of gamma = A/C (moments about G) in which the tippe top inverts
    when spun fast enough: (1 - alpha, 1 + alpha).

    Source: [RR14], Sec. 1 (Introduction), first paragraph: "1 - alpha < gamma = I1/I3 <
    1 + alpha" with I1, I3 "the main moments of inertia" (quoted). That the moments are about
    the centre of mass G is not spelt out in the sentence seen; it is confirmed here by
    derivation (derived here, not quoted): the upright spinning state can be destabilised by
    spin iff A > C(1 - alpha) (``upright_unstable_spin`` finite) and the inverted one can be
    stabilised iff A < C(1 + alpha) (``inverted_stable_spin`` finite), both with A, C about G;
    with these moments the derivation also reproduces [RR14]'s lambda_thres exactly.
    For moments about the geometric centre O (A_O = A + alpha^2, C_O = C, parallel-axis
    theorem, m = R = 1) the same condition reads
    C_O (1 - alpha) + alpha^2 < A_O < C_O (1 + alpha) + alpha^2; see ``moments_about_G``.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in [0, 1).

    Returns
    -------
    tuple of float
        (1 - alpha, 1 + alpha): the bounds of gamma = A/C.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside [0, 1).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.inversion.inversion_interval(0.3)
    (0.7, 1.3)
    """
    a = check_range("alpha", alpha, 0.0, 1.0, closed="l", label="[0, 1)")
    return (1.0 - a, 1.0 + a)

def classical_inversion(alpha, A, C) -> bool:
    """True iff 1 - alpha < A/C < 1 + alpha (moments about G), the condition for the top to
    invert fully when spun fast enough ([RR14] Sec. 1, quoted; see ``inversion_interval``).
    Equivalent to ``ueda_group_limit(...) == "II"``.

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
    bool
        True iff 1 - alpha < A/C < 1 + alpha.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.theory.tippetop.classical_inversion(0.3, 0.38, 0.4)
    True
    """
    a, A, C = params(alpha, A, C)
    up, inv = margins(a, A, C)
    return up > 0 and inv > 0

def moments_about_G(alpha, A_O, C_O) -> tuple[float, float]:
    """Convert moments about the geometric centre O to moments about G (units m R^2):
    A = A_O - alpha^2, C = C_O (parallel-axis theorem; G lies on the axis, so C is unchanged).
    Elementary, derived here.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in [0, 1).
    A_O : float
        Transverse moment of inertia about O, units m R^2, finite > 0 and > alpha^2.
    C_O : float
        Axial moment of inertia about O (= about G), units m R^2, finite > 0.

    Returns
    -------
    tuple of float
        (A, C) = (A_O - alpha^2, C_O), the moments about G, units m R^2.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside [0, 1), ``A_O`` or ``C_O`` is not a finite number > 0, or
        ``A_O`` <= alpha^2 (A about G would be <= 0).

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(v, 6) for v in pk.theory.tippetop.inversion.moments_about_G(0.3, 0.5, 0.4)]
    [0.41, 0.4]
    """
    a = check_range("alpha", alpha, 0.0, 1.0, closed="l", label="[0, 1)")
    A_O, C_O = check_positive("A_O", A_O), check_positive("C_O", C_O)
    A = A_O - a * a
    if A <= 0:
        raise ParameterError("A_O", f"must exceed alpha^2 = {a * a:g} (A about G would be <= 0)", A_O)
    return A, C_O


# ----------------------------------------------------------------- Jellett and V

def jellett_of_vertical_start(alpha, A, C, theta0, n0) -> float:
    """Jellett's integral of phasekit's standard start ``vertical_spin_start(theta0, n0)``
    (angular velocity n0 e_Z at inclination theta0, G at rest: Omega = n0, n = n0 cos theta0):

        lambda = n0 [A sin^2(theta0) + C cos(theta0) (cos(theta0) - alpha)].

    This is phasekit's ``jellett`` output (= -L.r_P = L.(e_Z - alpha k)); derived here.
    At theta0 = 0 it is C n0 (1 - alpha), the Jellett integral of the upright top spinning at n0.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    theta0 : float
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi].
    n0 : float
        Rate of the spin about the vertical, units sqrt(g/R), finite.

    Returns
    -------
    float
        Jellett's integral lambda of the start, units m R^2 sqrt(g/R).

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, ``theta0`` is
        outside [0, pi], or ``n0`` is not finite.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.jellett_of_vertical_start(0.3, 0.38, 0.4, 0.1, 15.0), 6)
    4.206002
    """
    a, A, C = params(alpha, A, C)
    th = theta0_of(theta0)
    n0 = check_finite("n0", n0)
    return n0 * (A * math.sin(th) ** 2 + C * math.cos(th) * (math.cos(th) - a))

def spin_for_jellett(alpha, A, C, jellett, theta0=0.0) -> float:
    """The n0 >= 0 of ``vertical_spin_start(theta0, n0)`` whose Jellett integral has modulus
    |jellett| (inf if the start's Jellett factor vanishes at this theta0). Derived here.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    jellett : float
        Jellett's integral lambda, units m R^2 sqrt(g/R): a real number (inf allowed: the
        spin is then inf); only abs(jellett) matters.
    theta0 : float, optional
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi]
        (default 0).

    Returns
    -------
    float
        The spin n0 >= 0, units sqrt(g/R); inf if the start's Jellett factor
        A sin^2(theta0) + C cos(theta0) (cos(theta0) - alpha) vanishes or ``jellett`` is infinite.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, ``jellett``
        is not a real number (or is NaN), or ``theta0`` is outside [0, pi].

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.inversion.spin_for_jellett(0.3, 0.38, 0.4, 6.0, theta0=0.1), 6)
    21.39799
    """
    a, A, C = params(alpha, A, C)
    th = theta0_of(theta0)
    lam = check_real("jellett", jellett)
    if not math.isfinite(lam):
        return math.inf
    factor = A * math.sin(th) ** 2 + C * math.cos(th) * (math.cos(th) - a)
    return math.inf if factor == 0.0 else abs(lam) / abs(factor)

def full_inversion_jellett(alpha, A, C) -> float:
    """The least abs(lambda) above which ``ueda_group`` is "full" for every larger lambda:
    sqrt(max over z in [-1, 1] of g(z)) (inf unless gamma is in the classical interval).
    It equals [RR14]'s ``jellett_threshold`` whenever g attains its maximum at z = -1 (e.g.
    always for gamma >= 1, where g is decreasing); it is larger when the upright instability
    (g(1)) or an interior maximum of g is the binding constraint. Derived here.
    g'(z) has the sign of -(4 D^2 + (A - C) f), a convex quadratic, so the interior extrema
    are the (at most two) roots of 3 (C-A)^2 z^2 - 6 (C-A) C alpha z + 4 C^2 alpha^2 - (C-A)(A + C alpha^2).

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
        The least such abs(lambda), units m R^2 sqrt(g/R); inf unless 1 - alpha < A/C < 1 + alpha.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.inversion.full_inversion_jellett(0.3, 0.38, 0.4), 6)
    0.989563
    """
    a, A, C = params(alpha, A, C)
    if not classical_inversion(a, A, C):
        return math.inf
    cand = [1.0, -1.0]
    delta = C - A
    if delta != 0.0:
        q = np.roots([3 * delta * delta, -6 * delta * C * a, 4 * C * C * a * a - delta * (A + C * a * a)])
        cand += [float(r.real) for r in q if abs(r.imag) < 1e-12 and -1.0 < r.real < 1.0]
    return math.sqrt(max(steady_state_jellett_sq(a, A, C, z) for z in cand))

def full_inversion_spin(alpha, A, C, *, theta0: float = 0.0) -> float:
    """n_c: the initial spin of ``vertical_spin_start(theta0, n)`` above which full inversion
    is predicted (``full_inversion_jellett`` converted with the start's Jellett factor).
    The analogue of [USW05]'s n_c (their formula not seen; derived here).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    theta0 : float, optional
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi]
        (default 0).

    Returns
    -------
    float
        n_c, units sqrt(g/R); inf unless gamma is in the classical interval, or if the start's
        Jellett factor vanishes at this theta0.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, or ``theta0``
        is outside [0, pi].

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.full_inversion_spin(0.3, 0.38, 0.4, theta0=0.1), 6)
    3.529109
    """
    return spin_for_jellett(alpha, A, C, full_inversion_jellett(alpha, A, C), theta0)

def critical_spin_from_jellett(alpha, A, C, theta0) -> float:
    """The n0 at which the Jellett integral of ``vertical_spin_start(theta0, n0)`` equals
    [RR14]'s lambda_thres (``jellett_threshold``):

        n0 = lambda_thres / |A sin^2 theta0 + C cos theta0 (cos theta0 - alpha)|

    (inf if gamma >= 1 + alpha or the factor vanishes). At theta0 = 0 this is
    (1 + alpha)^2 sqrt(alpha / (C (1 + alpha - gamma))) / (1 - alpha). This is where the inverted
    state becomes stable; full inversion of that start additionally needs the upright state to
    be unstable and no intermediate steady state in the way -- see ``full_inversion_spin``,
    which equals this value whenever max g = g(-1).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    theta0 : float
        Inclination of the start ``vertical_spin_start(theta0, n0)``, radians, in [0, pi].

    Returns
    -------
    float
        The spin n0, units sqrt(g/R); inf if gamma >= 1 + alpha or the factor vanishes.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, or ``theta0``
        is outside [0, pi].

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.inversion.critical_spin_from_jellett(0.3, 0.38, 0.4, 0.1), 6)
    3.529109
    """
    return spin_for_jellett(alpha, A, C, jellett_threshold(alpha, A, C), theta0)
