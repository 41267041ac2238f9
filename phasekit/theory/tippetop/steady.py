"""The tippe top's steady states: the effective potential, the steady precessions and the spins
at which the upright and the inverted states change stability.

The model, the units and the status of every result: :mod:`phasekit.theory.tippetop`.
"""

from __future__ import annotations

import math

import numpy as np

from ..._runtime.validate import check_finite, check_range
from ...errors import ParameterError
from .geometry import D_of, f_of, margins, params


def effective_potential(alpha, A, C, jellett, theta):
    """V(theta; lambda) = lambda^2 / (2 (A sin^2 theta + C (cos theta - alpha)^2)) + 1 - alpha cos theta,
    the least energy compatible with inclination theta and Jellett integral lambda (derived
    here). Its critical points are the steady spinning states; minima are stable.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    jellett : float
        Jellett's integral lambda, units m R^2 sqrt(g/R), finite.
    theta : float or array_like
        Inclination of the symmetry axis from the vertical, radians; may be an array.

    Returns
    -------
    float or numpy.ndarray
        V(theta; lambda), units m g R, of the shape of ``theta``.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, or
        ``jellett`` is not finite.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.tippetop.steady.effective_potential(0.3, 0.38, 0.4, 6.0, 1.0)), 6)
    62.446725
    """
    a, A, C = params(alpha, A, C)
    lam = check_finite("jellett", jellett)
    z = np.cos(np.asarray(theta, dtype=float))
    return lam * lam / (2.0 * f_of(z, a, A, C)) + 1.0 - a * z

def steady_state_jellett_sq(alpha, A, C, z):
    """g(z) = alpha f(z)^2 / D(z): the squared Jellett integral of the steady state at
    cos(theta) = z (inf where D(z) = (A - C) z + C alpha <= 0, i.e. no intermediate steady
    state at that angle). g(1) and g(-1) are the stability boundaries of the upright and the
    inverted state. Derived here.

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    z : float or array_like
        cos(theta) of the steady state, in [-1, 1]; may be an array.

    Returns
    -------
    float or numpy.ndarray
        g(z), in the units of lambda^2, of the shape of ``z`` (a float for a number); inf where
        D(z) <= 0.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(float(pk.theory.tippetop.steady.steady_state_jellett_sq(0.3, 0.38, 0.4, 0.5)), 6)
    0.247094
    """
    a, A, C = params(alpha, A, C)
    z = np.asarray(z, dtype=float)
    D = D_of(z, a, A, C)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(D > 0, a * f_of(z, a, A, C) ** 2 / np.where(D > 0, D, 1.0), np.inf)
    return out if out.ndim else float(out)

def steady_precession(alpha, A, C, theta) -> dict:
    """The intermediate steady state at inclination theta in (0, pi) (derived here): the body
    turns about the axis through G and P, w = Omega (e_Z - alpha k), with G at rest and P not
    sliding, precessing at Omega (> 0 branch) where Omega^2 = alpha / ((A - C) cos theta + C alpha).

    Parameters
    ----------
    alpha : float
        Distance OG of the centre of mass from the centre of the sphere, units R, in (0, 1).
    A : float
        Transverse moment of inertia about G (I1), units m R^2, finite > 0.
    C : float
        Axial moment of inertia about G (I3), units m R^2, finite > 0.
    theta : float
        Inclination of the symmetry axis from the vertical, radians, in (0, pi).

    Returns
    -------
    dict
        dict(Omega, n, jellett, D) with spin n = w.k = Omega (cos theta - alpha) and
        jellett = Omega (A sin^2 theta + C (cos theta - alpha)^2); Omega > 0 (units sqrt(g/R))
        and D = (A - C) cos theta + C alpha > 0.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), ``A`` or ``C`` is not a finite number > 0, ``theta`` is
        outside (0, pi), or no steady state exists at this theta (D <= 0).

    Examples
    --------
    >>> import phasekit as pk
    >>> {k: round(float(v), 6) for k, v in pk.theory.tippetop.steady.steady_precession(0.3, 0.38, 0.4, 1.0).items()}
    {'Omega': 1.65753, 'n': 0.398308, 'jellett': 0.484274, 'D': 0.109194}
    """
    a, A, C = params(alpha, A, C)
    th = check_range("theta", theta, 0.0, math.pi, label="(0, pi)")
    z = math.cos(th)
    D = D_of(z, a, A, C)
    if D <= 0:
        raise ParameterError("theta", f"admits no steady precession for these moments ((A - C) cos(theta) + C alpha = {D:.6g} <= 0)", theta)
    Om = math.sqrt(a / D)
    return {"Omega": Om, "n": Om * (z - a), "jellett": Om * f_of(z, a, A, C), "D": D}


# ------------------------------------------------------- 2/3. critical Jellett and spins

def upright_unstable_jellett(alpha, A, C) -> float:
    """abs(lambda) above which the upright spinning state (theta = 0) is unstable:
    lambda_up = sqrt(alpha C (1 - alpha)^4 / (gamma - 1 + alpha)) = sqrt(g(1)), inf (always
    stable) if gamma = A/C <= 1 - alpha. Derived here, not quoted (mirror image of [RR14]'s
    lambda_thres under alpha -> -alpha).

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
        lambda_up = sqrt(g(1)), units m R^2 sqrt(g/R); inf if gamma = A/C <= 1 - alpha.

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.steady.upright_unstable_jellett(0.3, 0.38, 0.4), 6)
    0.339482
    """
    a, A, C = params(alpha, A, C)
    den = margins(a, A, C)[0]
    return math.inf if den <= 0 else math.sqrt(a * C * C * (1.0 - a) ** 4 / den)

def jellett_threshold(alpha, A, C) -> float:
    """[RR14]'s threshold of Jellett's integral, in units m = g = R = 1:

        lambda_thres = sqrt(C alpha) (1 + alpha)^2 / sqrt(1 + alpha - gamma),  gamma = A/C,

    quoted from the abstract of [RR14] (sqrt(m g R^3 I3 alpha) (1+alpha)^2 / sqrt(1+alpha-gamma)),
    where it is the threshold above which the minimum of their effective potential moves
    from near theta = 0 to near theta = pi (stated with 1 - alpha^2 < gamma < 1).
    Derived here independently: it is exactly the boundary lambda^2 = g(-1) above which the
    inverted spinning state is stable (for gamma < 1 + alpha) -- this agreement is what fixes
    the correspondence lambda_[RR14] = phasekit ``jellett`` (up to sign).
    The threshold is in terms of abs(lambda); phasekit's ``jellett`` is lambda itself.

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
        lambda_thres, units m R^2 sqrt(g/R); inf if gamma >= 1 + alpha (the inverted state is
        then never stable).

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.steady.jellett_threshold(0.3, 0.38, 0.4), 6)
    0.989563
    """
    a, A, C = params(alpha, A, C)
    den = margins(a, A, C)[1]  # = C (1 + alpha - gamma)
    return math.inf if den <= 0 else math.sqrt(C * a) * (1.0 + a) ** 2 / math.sqrt(den / C)

def upright_unstable_spin(alpha, A, C) -> float:
    """Spin n (about the symmetry axis, = angular velocity) of the upright state theta = 0
    above which that state is unstable under sliding friction:

        n_up = (1 - alpha) sqrt(alpha / (A - C (1 - alpha))),   inf if A <= C (1 - alpha).

    Derived here, not quoted: lambda = C n (1 - alpha) at theta = 0 and lambda^2 > g(1). Checked
    in the tests against the eigenvalues of the linearised full equations (viscous friction),
    which change sign exactly there, independently of the friction coefficient.

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
        n_up, units sqrt(g/R); inf if A <= C (1 - alpha) (the upright state is then stable at
        every spin).

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.upright_unstable_spin(0.3, 0.38, 0.4), 6)
    1.212436
    """
    a, A, C = params(alpha, A, C)
    den = margins(a, A, C)[0]
    return math.inf if den <= 0 else (1.0 - a) * math.sqrt(a / den)

def inverted_stable_spin(alpha, A, C) -> float:
    """|spin| of the inverted state theta = pi (spinning on the 'stem' side, G above O) above
    which that state is stable:

        n_inv = (1 + alpha) sqrt(alpha / (C (1 + alpha) - A)),   inf if A >= C (1 + alpha).

    Derived here, not quoted (lambda = -C n (1 + alpha) at theta = pi, lambda^2 > g(-1)); it is
    [RR14]'s lambda_thres divided by C (1 + alpha). Note this is the spin IN the inverted state;
    the initial spin needed is ``critical_spin_from_jellett`` / ``full_inversion_spin``.

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
        n_inv, units sqrt(g/R); inf if A >= C (1 + alpha) (the inverted state is then never
        stable).

    Raises
    ------
    ParameterError
        If ``alpha`` is outside (0, 1), or ``A`` or ``C`` is not a finite number > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> round(pk.theory.tippetop.inverted_stable_spin(0.3, 0.38, 0.4), 6)
    1.903005
    """
    a, A, C = params(alpha, A, C)
    den = margins(a, A, C)[1]
    return math.inf if den <= 0 else (1.0 + a) * math.sqrt(a / den)


# ------------------------------------------------------------ Ueda-type classification
