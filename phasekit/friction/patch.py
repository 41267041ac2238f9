"""Coulomb friction over a circular contact patch: the Contensou coupling of sliding and spin.

A body touching the table over a disk of radius a (a Hertz patch, a flat face) with pressure p(r),
its centre slipping at v and spinning at omega about the normal, slides at rho with
u = v + omega e_z x rho. Coulomb's law at every point, traction -mu p u/|u|, gives by symmetry

    F = -mu R f(s) v/|v|,    M = -mu R a g(s) sign(omega),    s = |v| / (a |omega|)

(Contensou 1963). u vanishes at c = e_z x v/omega, a s from the centre (inside for s < 1). Both derive
from the dissipation D = mu int p |u| dA = mu R a |omega| d(s), of degree 1: F = -dD/dv,
M = -dD/domega, so d = s f + g and f = d'(s).

Exact values (:func:`patch_resultant`)
    Uniform pressure R/(pi a^2) (Contensou 1963; Zhuravlev 1998; derived again from the ring kernels
    of ``_ring_sum``), K, E complete elliptic integrals of modulus k (parameter k^2):
        s <= 1:  f = 4/(3 pi s) [(1 + s^2) E(s) - (1 - s^2) K(s)] = s 2F1(-1/2, 1/2; 2; s^2)
                 g = 4/(9 pi) [(4 - 2 s^2) E(s) - (1 - s^2) K(s)],  d = 4/(9 pi) [(7 + s^2) E(s) - 4 (1 - s^2) K(s)]
        s >= 1:  f = 4/(3 pi) [(s^2 + 1) E(1/s) - (s^2 - 1) K(1/s)] = 2F1(-1/2, 1/2; 2; 1/s^2)
                 g = 1/(4 s) 2F1(1/2, 1/2; 3; 1/s^2),  d = 4 s^3/(9 pi) [(1 + 7m) E - (1 + 3m)(1 - m) K], m = 1/s^2
    so f(s) = s f(1/s), f(1) = 8/(3 pi), g(1) = 8/(9 pi); where the elliptic forms cancel (s^2 or
    1/s^2 below 1/2) the series are summed: ~1e-15. Hertz pressure 3R/(2 pi a^2) sqrt(1 - r^2/a^2)
    has no closed form here: the patch is summed ring by ring (elliptic kernels), the radius by
    tanh-sinh quadrature split at r = a s (the kernels' logarithmic kink): ~1e-15, the same at
    levels 4 to 8. Both agree with a 2-D quadrature of the traction itself to 1e-13 (the tests).
Limits (:data:`PATCH_LIMITS`)
    s -> 0: f ~ k_v s, k_v = 1 (uniform), 3 pi/8 (Hertz): on v the patch is a regularised Coulomb law
    F = -mu R v/eps with eps = a|omega|/k_v, i.e. a|omega| (uniform), 8 a|omega|/(3 pi) (Hertz);
    g -> g0 = 2/3 (uniform), 3 pi/16 (Hertz). s -> oo: f -> 1 and g ~ k_w/s, k_w = 1/4 (uniform),
    1/5 (Hertz): M = -mu R a^2 k_w omega/|v|. Next terms: uniform f = s - s^3/8, 1 - 1/(8 s^2),
    g = 2/3 - s^2/2, 1/(4s) + 1/(48 s^3); Hertz (measured) f = 3 pi s/8 - 3 pi s^3/32, 1 - 1/(10 s^2),
    g = 3 pi/16 (1 - s^2), 1/(5 s) + 1/(70 s^3). Smooth except at s = 1 (second derivatives ~ log|1 - s|
    for uniform pressure) and at v = omega = 0 (set-valued).
Smooth approximants (:func:`patch_friction`, CasADi; ``patch_resultant(s, approximant=...)``, numpy)
    "pade1", the first-order form of Zhuravlev & Kireenkov's Pade approach (constants ours, from the
    exact limits; theirs not checked): F = -mu R k_v v/(k_v |v| + a|omega|),
    M = -mu R a g0 (a omega)/(a|omega| + (g0/k_w)|v|). "pade2", two terms matched at each end:
    w = k_v s, z = (g0/k_w) s, f = w (w + 1)/(w^2 + w + 1), g = g0 (1 + z)/(1 + z + z^2).
    "rational" (default): x = (|v|^2 - a^2 omega^2)/(|v|^2 + a^2 omega^2) in [-1, 1] (0 at s = 1),
    rho = sqrt(|v|^2 + a^2 omega^2), F = -mu R phi(x) v/rho, M = -mu R a psi(x) (a omega)/rho with
    phi, psi = sum_j c_j T_j(x) + sum_k (alpha_k delta_k^2 + beta_k delta_k x)/(x^2 + delta_k^2):
    Chebyshev degree 10 and 8 pole pairs +-i delta_k (geometric, 1e-3 to 1/2) resolving the kink at
    s = 1 (a polynomial would need degree ~100); minimax fit of the relative error with the four
    limits imposed exactly (``_fit_rational``). Only +, *, / and one sqrt: smooth away from the origin.
    Worst relative errors over the whole (|v|, a|omega|) plane, s from 1e-6 to 1e6 (20001 points
    log-spaced and 2000 within 1e-12..1e-1 of s = 1; :data:`APPROXIMANT_ERRORS`):
        =========  ================  ================  ================  ================
        law        f, uniform        g, uniform        f, Hertz          g, Hertz
        =========  ================  ================  ================  ================
        pade1      0.411 (s = 1)     0.487 (s = 0.60)  0.391 (s = 0.91)  0.479 (s = 0.54)
        pade2      0.215 (s = 1)     0.329 (s = 0.64)  0.189 (s = 0.92)  0.318 (s = 0.58)
        rational   1.7e-6 (s = 4.0)  6.6e-6 (s = 0.86)  1.4e-6 (s = 0.98)  8.2e-6 (s = 0.98)
        =========  ================  ================  ================  ================
    The Pade forms are exact at both ends but poor between them (f stays near s up to s ~ 0.8, then
    turns sharply): use "rational".
At rest (v = omega = 0, where the exact law is set-valued)
    The approximants add floor^2 to |v|^2 + a^2 omega^2 (Pade: to each), floor = 1e-9 by default (a
    speed, SIGN_EPS of :mod:`phasekit.friction.dissipation`): below it a steep viscous law F ~ -mu R
    phi v/floor, M ~ -mu R a^2 psi omega/floor, above it a change ~(floor/rho)^2/2. Sticking (both rates
    held at zero) is the simulator's mode, not this law's.
Hertz contact (:mod:`phasekit.friction.hertz`): :func:`~phasekit.friction.hertz.hertz_radius`, :func:`~phasekit.friction.hertz.hertz_ellipse`, :func:`~phasekit.friction.hertz.principal_radii`, :data:`~phasekit.friction.hertz.MATERIALS`.

References
----------
Contensou P. (1963), Couplage entre frottement de glissement et frottement de pivotement dans la theorie
de la toupie, Kreiselprobleme / Gyrodynamics (IUTAM Celerina 1962), Springer, 201-216. Zhuravlev V. Ph.
(1998), The model of dry friction in the problem of the rolling of rigid bodies, J. Appl. Math. Mech.
62(5), 705-710. Zhuravlev V. Ph., Kireenkov A. A. (2005), Pade expansions in the two-dimensional model
of Coulomb friction, Mech. Solids 40(2), 1-10. Johnson K. L. (1985), Contact Mechanics, CUP.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np
from scipy import special

from .._runtime.validate import check_choice, check_int, check_positive
from ..errors import ParameterError
from .dissipation import SIGN_EPS

PI = math.pi
#: pressure distributions over the patch: uniform R/(pi a^2), or Hertz's 3R/(2 pi a^2) sqrt(1 - r^2/a^2)
PRESSURES = ("uniform", "hertz")
#: the smooth approximants of :func:`patch_friction`
APPROXIMANTS = ("rational", "pade1", "pade2")
#: the tanh-sinh level of the ring quadrature: step 2^-level; levels 4..8 agree to ~1e-15
QUAD_LEVEL = 6


@dataclass(frozen=True)
class PatchLimits:
    """The exact limits of the patch law for one pressure distribution.

    Attributes
    ----------
    slip_slope, spin_couple, couple_slope : float
        k_v = f'(0) (near v = 0, F = -mu R k_v v/(a|omega|): eps = a|omega|/k_v), g0 = g(0) (the couple
        of pure spin is mu R a g0) and k_w = lim s g(s) (near omega = 0, M = -mu R a^2 k_w omega/|v|).
    """

    slip_slope: float
    spin_couple: float
    couple_slope: float


#: the exact limits (module notes): uniform 1, 2/3, 1/4; Hertz 3 pi/8, 3 pi/16, 1/5
PATCH_LIMITS = {"uniform": PatchLimits(1.0, 2.0 / 3.0, 0.25), "hertz": PatchLimits(3 * PI / 8, 3 * PI / 16, 0.2)}


def hyp2f1(a: float, b: float, c: float, m: np.ndarray) -> np.ndarray:
    """2F1(a, b; c; m) by its power series, for m <= 1/2 only: as many terms as make m^n < 1e-18
    (at most 60; the coefficients here are below 1)."""
    m = np.asarray(m, dtype=float)
    top = float(np.max(m, initial=0.0))
    terms = 60 if top >= 0.5 else (1 if top <= 0 else min(60, int(np.ceil(-18 / np.log10(top)))))
    term, out = np.ones_like(m), np.ones_like(m)
    for k in range(terms):
        term = term * ((a + k) * (b + k) / ((c + k) * (k + 1))) * m
        out = out + term
    return out


def _pk(p: np.ndarray) -> np.ndarray:
    """(1 - m) K(m) from the complement p = 1 - m (0 at p = 0, where K diverges logarithmically)."""
    return np.where(p > 0, p * special.ellipkm1(np.maximum(p, 1e-300)), 0.0)


def _e_minus_pk(m: np.ndarray, p: np.ndarray) -> np.ndarray:
    """E(m) - (1 - m) K(m) = (pi m/4) 2F1(1/2, 1/2; 2; m), without the cancellation at small m."""
    small = m < 0.5
    return np.where(small, PI * m / 4 * hyp2f1(0.5, 0.5, 2.0, np.where(small, m, 0.0)), special.ellipe(m) - _pk(p))


def _uniform_closed(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(f, g, d) of uniform pressure at finite s >= 0 from the closed forms (module notes)."""
    f, g, d = np.empty_like(s), np.empty_like(s), np.empty_like(s)
    inner = s <= 1.0
    si = s[inner]
    m, p = si * si, (1.0 - si) * (1.0 + si)
    E, pK = special.ellipe(m), _pk(p)
    series = m < 0.5
    with np.errstate(divide="ignore", invalid="ignore"):
        f_ell = 4 / (3 * PI * si) * ((1 + m) * E - pK)
    f[inner] = np.where(series, si * hyp2f1(-0.5, 0.5, 2.0, np.where(series, m, 0.0)), f_ell)
    g[inner] = 4 / (9 * PI) * ((4 - 2 * m) * E - pK)
    d[inner] = 4 / (9 * PI) * ((7 + m) * E - 4 * pK)
    so = s[~inner]
    m, p = 1.0 / (so * so), (so - 1.0) * (so + 1.0) / (so * so)
    E, pK = special.ellipe(m), _pk(p)
    series = m < 0.5
    mm = np.where(series, m, 0.0)
    F1, F2 = hyp2f1(-0.5, 0.5, 2.0, mm), hyp2f1(0.5, 0.5, 3.0, mm)
    fo = np.where(series, F1, 4 / (3 * PI * m) * ((1 + m) * E - pK))
    go = np.where(series, F2 / (4 * so), 4 / (9 * PI * so * m * m) * (2 * (2 * m - 1) * E - (3 * m - 2) * pK))
    f[~inner], g[~inner] = fo, go
    # d = s f + g is the same function; the elliptic form is kept where it does not cancel (s <= sqrt 2)
    d[~inner] = np.where(series, so * fo + go, 4 * so**3 / (9 * PI) * ((1 + 7 * m) * E - (1 + 3 * m) * pK))
    return f, g, d


def _tanh_sinh(level: int, t_max: float = 4.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tanh-sinh nodes on [-1, 1] as (1 + x, 1 - x, weight): distances to the (singular) ends kept exact."""
    h = 2.0**-level
    t = np.arange(-round(t_max / h), round(t_max / h) + 1) * h
    u = PI / 2 * np.sinh(t)
    w = h * PI / 2 * np.cosh(t) / np.cosh(u) ** 2
    one_minus, one_plus = 1 / (np.exp(u) * np.cosh(u)), 1 / (np.exp(-u) * np.cosh(u))
    keep = (one_minus > 0) & (one_plus > 0) & (w > 0)
    return one_plus[keep], one_minus[keep], w[keep]


def _ring_sum(s: float, pressure: str, nodes) -> np.ndarray:
    """(f, g, d) at one s > 0 summed ring by ring. A ring of radius r (a = 1), q = min(r/s, s/r), gives
    to f, g, d the angle integrals of (rho - c)/|rho - c| along c, rho.(rho - c)/|rho - c|, |rho - c|:
        r < s:  4 E(q),                 4 s [E(q) - (1 - q^2) K(q)],   P = 4 max(r, s) [2E(q) - (1 - q^2) K(q)]
        r > s:  4 [E - (1 - q^2) K]/q,  4 r E(q),                      P
    (-dP/ds, r dP/dr, P), weighted by p(r)/R r dr over [0, min(s, 1)] and [s, 1]."""
    xp, xm, w = nodes
    wr = (lambda r, one_minus_r: np.full_like(r, 1 / PI)) if pressure == "uniform" else (
        lambda r, one_minus_r: 3 / (2 * PI) * np.sqrt(one_minus_r * (1 + r)))
    out = np.zeros(3)
    top = min(s, 1.0)
    if top > 0:  # rings inside the centre of rotation, r < s
        r, s_minus_r, one_minus_r = top * xp / 2, (s - top) + top * xm / 2, (1 - top) + top * xm / 2
        p = s_minus_r * (s + r) / (s * s)
        m = np.where(p < 0.5, 1 - p, (r / s) ** 2)
        E, D = special.ellipe(m), _e_minus_pk(m, p)
        weight = w * top / 2 * wr(r, one_minus_r) * r
        out += [np.sum(weight * 4 * E), np.sum(weight * 4 * s * D), np.sum(weight * 4 * s * (E + D))]
    if s < 1:  # rings outside it
        span = 1 - s
        r, r_minus_s, one_minus_r = s + span * xp / 2, span * xp / 2, span * xm / 2
        q = s / r
        p = r_minus_s * (r + s) / (r * r)
        m = np.where(p < 0.5, 1 - p, q * q)
        E, D = special.ellipe(m), _e_minus_pk(m, p)
        # D/q = (pi q/4) 2F1(1/2, 1/2; 2; q^2) where q is small: no 0/0 as s -> 0
        D_over_q = np.where(m < 0.5, PI * q / 4 * hyp2f1(0.5, 0.5, 2.0, np.where(m < 0.5, m, 0.0)), D / q)
        weight = w * span / 2 * wr(r, one_minus_r) * r
        out += [np.sum(weight * 4 * D_over_q), np.sum(weight * 4 * r * E), np.sum(weight * 4 * r * (E + D))]
    return out


def _resultant(s, pressure, method, level, approximant):
    pressure = check_choice("pressure", pressure, PRESSURES)
    method = check_choice("method", method, ("auto", "closed", "quadrature"))
    level = check_int("level", level, minimum=2, maximum=10)
    if method == "closed" and pressure != "uniform":
        raise ParameterError("method", "can be closed only with pressure='uniform' (use 'quadrature')", method)
    try:
        arr = np.array(s, dtype=float)
    except (TypeError, ValueError):
        arr = np.array(np.nan)
    if np.any(np.isnan(arr)) or np.any(arr < 0):
        raise ParameterError("s", "must be numbers >= 0 (the ratio |v|/(a |omega|); inf allowed)", s)
    flat, lim = arr.ravel(), PATCH_LIMITS[pressure]
    if approximant is not None:
        approximant = check_choice("approximant", approximant, APPROXIMANTS)
        with np.errstate(invalid="ignore", divide="ignore"):  # s = inf: its limit is put in below
            first, second = _approximant_fg(flat * flat, np.ones_like(flat), 0.0, approximant, pressure)
        out = (np.where(np.isinf(flat), 1.0, first * flat), np.where(np.isinf(flat), 0.0, second), flat * np.nan)
    else:
        out = (np.empty_like(flat), np.empty_like(flat), np.empty_like(flat))
        inf, mid = np.isinf(flat), (flat > 0) & np.isfinite(flat)
        # the ends by their limits: pure slip (f = 1, g = 0, d = s = oo), pure spin (f = 0, g = d = g0)
        out[0][~mid], out[1][~mid] = np.where(inf[~mid], 1.0, 0.0), np.where(inf[~mid], 0.0, lim.spin_couple)
        out[2][~mid] = np.where(inf[~mid], np.inf, lim.spin_couple)
        if method == "quadrature" or pressure == "hertz":
            nodes = _tanh_sinh(level)
            vals = np.array([_ring_sum(x, pressure, nodes) for x in flat[mid]]).reshape(-1, 3)
        else:
            vals = np.array(_uniform_closed(flat[mid])).T
        for k in range(3):
            out[k][mid] = vals[:, k]
    return tuple(float(x[0]) for x in out) if arr.shape == () else tuple(x.reshape(arr.shape) for x in out)


def patch_resultant(s, pressure: str = "uniform", *, method: str = "auto", level: int = QUAD_LEVEL,
                    dissipation: bool = False, approximant: str | None = None):
    """Coulomb friction over a circular patch, F = -mu R f(s) v/|v|, M = -mu R a g(s) sign(omega):
    (f, g) at s = |v|/(a |omega|), exact or of an approximant, and the dissipation d(s) =
    int p |u| dA/(R a |omega|), F.v + M omega = -mu R a |omega| d (module notes).

    Parameters
    ----------
    s : float or array_like
        |v|/(a |omega|) >= 0; 0 is pure spin, inf pure slip.
    pressure : {"uniform", "hertz"}, optional
        The pressure over the patch (default "uniform").
    method : {"auto", "closed", "quadrature"}, optional
        "closed" (uniform only), "quadrature" (ring sum, tanh-sinh ``level`` in [2, 10], default 6) or
        "auto" (default): closed where it exists.
    level : int, optional
        See ``method``.
    dissipation : bool, optional
        Return (f, g, d) instead of (f, g) (default False).
    approximant : {"rational", "pade1", "pade2"}, optional
        The approximant's values instead (:func:`patch_friction` in numpy, a = omega = 1, no floor;
        d is NaN). Default None: exact, to ~1e-15.

    Returns
    -------
    tuple
        (f, g) or (f, g, d): floats for a number, arrays of the shape of ``s`` otherwise (ParameterError
        for s < 0 or NaN, an unknown name, or a closed form asked of Hertz pressure).

    Examples
    --------
    >>> from phasekit.friction.patch import patch_resultant
    >>> [round(x, 12) for x in patch_resultant(1.0, dissipation=True)]  # 8/(3 pi), 8/(9 pi), 32/(9 pi)
    [0.848826363157, 0.282942121052, 1.131768484209]
    >>> [round(x, 4) for x in patch_resultant(0.0, "hertz") + patch_resultant(1.0, approximant="pade1")]
    [0.0, 0.589, 0.5, 0.1818]
    """
    out = _resultant(s, pressure, method, level, approximant)
    return out if dissipation else out[:2]


#: the poles +-i delta_k of the rational approximant, in x = (|v|^2 - a^2 omega^2)/(|v|^2 + a^2 omega^2)
RATIONAL_DELTAS = tuple(float(x) for x in np.geomspace(1e-3, 0.5, 8))
#: Chebyshev degree of the rational approximant's polynomial part
RATIONAL_DEGREE = 10

#: pressure -> (phi, psi): 11 Chebyshev coefficients, then (alpha_k, beta_k) per delta_k (``_fit_rational``)
RATIONAL_COEFFICIENTS = {
    "uniform": (
        (1.035595835, -5.3627272e-06, -0.05758157737, 1.997715911e-06, 0.005489455108, -7.149334554e-07,
         -0.0005414902944, 2.482940115e-07, 2.116669772e-05, -1.00956672e-07, 7.10568838e-06, 1.704042834e-05,
         -3.337050108e-08, -3.716989214e-05, -8.949156035e-08, 6.901466088e-05, 8.65046828e-08, 1.965401898e-05,
         5.349164447e-08, 0.0005494470145, -2.412281576e-07, 0.002785250684, 3.242953308e-07, 0.01612926822,
         -8.927315864e-07, 0.08166872496, 1.022238028e-05,),
        (0.4744813857, -0.2014257279, -0.003555298774, 0.0167320468, 0.0001338233994, -0.002054248265,
         -0.0001710986774, 0.0002543967335, 6.896602242e-05, -2.493817031e-05, -1.352703575e-05, 6.992950165e-06,
         -2.125140056e-05, -2.03563339e-05, 5.164461901e-05, 1.196736579e-05, -7.519842339e-05, -0.0001136353066,
         9.119649856e-05, -0.0004453269586, -0.0001465122447, -0.002879367559, -0.000213413438, -0.01492536263,
         -0.005825116857, -0.05991752387, -0.05160697506,),
    ),
    "hertz": (
        (1.130433272, -0.08063488323, -0.05641661767, 0.006768575618, 0.005485388518, -0.0007572202789,
         -0.0006447316559, 6.847745549e-05, 6.356642392e-05, -4.119241969e-07, -2.873311704e-06, 1.282251059e-05,
         -6.418426989e-06, -3.101375663e-05, 1.528308627e-05, 4.547422623e-05, -2.328679769e-05, -4.610614446e-05,
         1.999214508e-05, 0.0001388973647, -0.0001058573717, 0.0005907320933, -0.0005877479264, 0.006492571691,
         -0.005364662809, 0.04931244916, -0.0334528518,),
        (0.3937185339, -0.2051522212, 0.01442015638, 0.01545255045, -0.00255955443, -0.001966403552, 0.0003257638591,
         0.0002871413194, -2.719812926e-05, -3.659163561e-05, 1.655897832e-06, -1.988500049e-05, -9.050949274e-06,
         4.827319327e-05, 2.210105657e-05, -7.129442671e-05, -3.101930276e-05, 7.967199641e-05, 4.680087436e-05,
         -0.0001902507632, 1.769386592e-05, -0.0005885502852, 0.0006110604338, -0.008158204629, 0.002533489012,
         -0.05509605273, -0.00915369858,),
    ),
}

#: measured worst relative errors (f, g) of each approximant over s in [1e-6, 1e6] (module notes)
APPROXIMANT_ERRORS = {
    "uniform": {"rational": (1.7e-6, 6.6e-6), "pade1": (0.412, 0.487), "pade2": (0.215, 0.330)},
    "hertz": {"rational": (1.4e-6, 8.2e-6), "pade1": (0.392, 0.479), "pade2": (0.189, 0.319)},
}


def _rational_parts(x, coeffs, deltas=RATIONAL_DELTAS):
    """sum_j c_j T_j(x) + sum_k (alpha_k delta_k^2 + beta_k delta_k x)/(x^2 + delta_k^2) with only
    +, *, /: works on numpy arrays and CasADi expressions alike."""
    cheb, poles = coeffs[:RATIONAL_DEGREE + 1], coeffs[RATIONAL_DEGREE + 1:]
    # Clenshaw's recurrence for the Chebyshev part: stable to the last digit on [-1, 1]
    b1, b2 = 0.0 * x, 0.0 * x
    for c in cheb[:0:-1]:
        b1, b2 = 2 * x * b1 - b2 + c, b1
    out = x * b1 - b2 + cheb[0]
    for k, dk in enumerate(deltas):
        out = out + (poles[2 * k] * dk * dk + poles[2 * k + 1] * dk * x) / (x * x + dk * dk)
    return out


def _approximant_fg(speed2, spin2, floor2, law: str, pressure: str):
    """(F factor, M factor): F = -mu R v * first, M = -mu R a (a omega) * second, from |v|^2 and
    a^2 omega^2; numpy or CasADi."""
    lim = PATCH_LIMITS[pressure]
    if law == "rational":
        total = speed2 + spin2 + floor2
        x = (speed2 - spin2) / total
        inv = 1 / np.sqrt(total) if isinstance(total, np.ndarray) or np.isscalar(total) else 1 / ca.sqrt(total)
        phi = _rational_parts(x, RATIONAL_COEFFICIENTS[pressure][0])
        psi = _rational_parts(x, RATIONAL_COEFFICIENTS[pressure][1])
        return phi * inv, psi * inv
    sqrt = np.sqrt if isinstance(speed2, np.ndarray) or np.isscalar(speed2) else ca.sqrt
    speed, spin = sqrt(speed2 + floor2), sqrt(spin2 + floor2)
    kv, g0 = lim.slip_slope, lim.spin_couple
    rate = g0 / lim.couple_slope
    if law == "pade1":
        return kv / (kv * speed + spin), g0 / (spin + rate * speed)
    # pade2: f = w (w + 1)/(w^2 + w + 1) with w = kv s, g = g0 (1 + z)/(1 + z + z^2) with z = rate s
    w_num, z_num = kv * speed, rate * speed
    first = kv * (w_num + spin) / (w_num * w_num + w_num * spin + spin * spin)
    second = g0 * (spin + z_num) / (spin * spin + z_num * spin + z_num * z_num)
    return first, second


def patch_friction(v, omega, mu, R, a, *, pressure: str = "uniform", approximant: str = "rational",
                   floor: float = SIGN_EPS):
    """The force and couple of Coulomb friction over the patch as smooth CasADi expressions: (F, M),
    F a 2-vector (units M g), M the couple about the normal (units M g b).

    Parameters
    ----------
    v, omega, mu, R, a : casadi.SX or casadi.MX or float
        Slip velocity of the patch's centre (a 2-vector, units sqrt(g b)), spin about the normal (units
        sqrt(g/b)), friction coefficient, normal force (units M g), patch radius (units b).
    pressure : {"uniform", "hertz"}, optional
        The pressure over the patch (default "uniform").
    approximant : {"rational", "pade1", "pade2"}, optional
        Which approximant (default "rational"; errors in :data:`APPROXIMANT_ERRORS`).
    floor : float, optional
        The speed added in quadrature at rest (module notes), in (0, 1]; default 1e-9. ParameterError
        for it out of range or an unknown name.

    Examples
    --------
    >>> import casadi as ca
    >>> from phasekit.friction.patch import patch_friction
    >>> v, w = ca.SX.sym("v", 2), ca.SX.sym("w")
    >>> F1, M1 = ca.Function("patch", [v, w], list(patch_friction(v, w, 0.3, 1.0, 0.01)))([0.01, 0.0], 1.0)
    >>> round(float(F1[0]), 4), round(float(M1) / 0.01, 4)   # s = 1: -mu 8/(3 pi), -mu 8/(9 pi)
    (-0.2546, -0.0849)
    """
    pressure = check_choice("pressure", pressure, PRESSURES)
    approximant = check_choice("approximant", approximant, APPROXIMANTS)
    floor = check_positive("floor", floor, upper=1.0)
    v = ca.vertcat(v[0], v[1]) if not isinstance(v, (ca.SX, ca.MX)) else v
    first, second = _approximant_fg(v[0] * v[0] + v[1] * v[1], a * a * omega * omega, floor * floor, approximant,
                                    pressure)
    return -mu * R * first * v, -mu * R * a * (a * omega) * second


def _fit_rational(pressure: str, degree: int = RATIONAL_DEGREE, deltas=RATIONAL_DELTAS, n_angles: int = 4001):
    """How :data:`RATIONAL_COEFFICIENTS` was made: ((phi, psi) coefficients, (phi, psi) worst errors).

    The minimax relative error of phi = f/sin(t), psi = g/cos(t), t = atan(s), on a grid uniform in t
    plus points clustered at s = 1 (x = 0), the four limits imposed exactly: a linear programme."""
    from scipy.optimize import linprog

    t = np.linspace(0, PI / 2, n_angles)[1:-1]
    near = np.geomspace(1e-9, 1e-1, 300)
    x = np.unique(np.concatenate([-np.cos(2 * t), near, -near]))
    s = np.sqrt((1 + x) / (1 - x))
    f, g = patch_resultant(s, pressure)
    lim = PATCH_LIMITS[pressure]

    def basis(xx):
        poles = [np.stack([np.full_like(xx, dk * dk), dk * xx], 1) / (xx * xx + dk * dk)[:, None] for dk in deltas]
        return np.hstack([np.polynomial.chebyshev.chebvander(xx, degree), *poles])

    out, errs = [], []
    for y, end in ((f * np.sqrt(1 + s * s) / s, (lim.slip_slope, 1.0)),
                   (g * np.sqrt(1 + s * s), (lim.spin_couple, lim.couple_slope))):
        B, ones = basis(x) / y[:, None], np.ones((len(x), 1))
        n = B.shape[1]
        res = linprog(np.r_[np.zeros(n), 1.0], A_ub=np.vstack([np.hstack([B, -ones]), np.hstack([-B, -ones])]),
                      b_ub=np.r_[np.ones(len(x)), -np.ones(len(x))], b_eq=np.array(end),
                      A_eq=np.hstack([basis(np.array([-1.0, 1.0])), np.zeros((2, 1))]),
                      bounds=[(None, None)] * n + [(0, None)], method="highs")
        out.append(tuple(float(c) for c in res.x[:-1]))
        errs.append(float(res.x[-1]))
    return tuple(out), tuple(errs)
