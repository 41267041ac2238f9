"""The egg's shape (:mod:`phasekit.bodies.egg`): its meridian and exact support function, and that
support as a Chebyshev series: the interpolant of H_O(c) = h_O(acos c) at Chebyshev points by
DCT-II, the degree that meets the fit tolerance, and its evaluation by Clenshaw's recurrence (a
CasADi expression, so every backend takes it)."""

from __future__ import annotations

import functools

import numpy as np

from ..errors import ParameterError

#: aspect ratios L/B accepted
A_RANGE = (0.3, 3.0)
#: w/L must lie in [0, W_MAX): the strict-convexity limit of the curve (see the module docstring)
W_MAX = 0.5
#: every a in A_RANGE is guaranteed a fit for w/L up to this value
W_GUARANTEED = 0.08
#: allowed lengths - 1 of the Chebyshev series (eggs with equal degree share compiled models)
DEGREES = (16, 32, 64, 128, 256)
MAX_DEGREE = DEGREES[-1]
#: the series must reproduce h to this accuracy on the check grid
FIT_TOL = 1e-12
#: the needed degree is the last k with k^2 |a_k| above this fraction of max |a_k|, so that the
#: series gives rho = h + h_thetatheta to ~1e-13 (and h to ~1e-15)
CHOP_REL = 1e-14
#: interpolation degree used to measure the coefficients (twice the largest tier, so that
#: aliasing of a series that does not fit in MAX_DEGREE shows up as a long tail)
_SAMPLE_DEGREE = 2 * MAX_DEGREE


# -- the meridian ----------------------------------------------------------------------------
def _meridian(u, w):
    """Radius y(u) and its first two u-derivatives on the meridian x = -a cos(u).

    Substituting x = -(L/2) cos(u) in Narushin's formula gives y = sin(u) / sqrt(q(u)),
    q = 1 - 4 w cos(u) + 4 w^2 (w relative to L, b = 1), independent of a and smooth at both
    tips (u = 0 the fat tip, u = pi the thin tip), where y(x) itself has infinite slope.
    """
    s, c = np.sin(u), np.cos(u)
    q = 1.0 - 4.0 * w * c + 4.0 * w * w
    q1, q2 = 4.0 * w * s, 4.0 * w * c
    r = 1.0 / np.sqrt(q)
    y = s * r
    y1 = c * r - 0.5 * s * r**3 * q1
    y2 = -s * r - c * r**3 * q1 + 0.75 * s * r**5 * q1 * q1 - 0.5 * s * r**3 * q2
    return y, y1, y2


def _tangency(u, ct, st, a, w):
    """F = df/du and F_u for f(u) = a cos(u) cos(theta) + y(u) sin(theta), the height above
    the table of the meridian point u measured from the middle of the axis; and (y, y')."""
    y, y1, y2 = _meridian(u, w)
    F = -a * np.sin(u) * ct + y1 * st
    Fu = -a * np.cos(u) * ct + y2 * st
    return F, Fu, y, y1


def _contact_parameter(theta, a, w, n_sample=64, max_iter=100):
    """The meridian parameter u of the contact point at each theta (array).

    Dense sampling brackets the maximum of f (unimodal on a convex curve); a Newton iteration
    on F = 0 kept inside the bracket (bisecting when a step leaves it) follows. Once every step
    is below 1e-9 one more step brings u to rounding level (quadratic convergence); a tighter
    stopping test could cycle forever between neighbouring floats where F is rounding noise.
    """
    ct, st = np.cos(theta), np.sin(theta)
    grid = np.linspace(0.0, np.pi, n_sample + 1)
    f = a * np.cos(grid)[None, :] * ct[:, None] + _meridian(grid, w)[0][None, :] * st[:, None]
    u = grid[np.argmax(f, axis=1)]
    lo, hi = np.maximum(u - np.pi / n_sample, 0.0), np.minimum(u + np.pi / n_sample, np.pi)
    converged = False
    for _ in range(max_iter):
        F, Fu, _, _ = _tangency(u, ct, st, a, w)
        # F decreases through the root: F > 0 on its left
        lo, hi = np.where(F > 0, u, lo), np.where(F > 0, hi, u)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = u - np.where(F == 0, 0.0, F / Fu)
        new = np.where((new >= lo) & (new <= hi), new, 0.5 * (lo + hi))
        change = np.max(np.abs(new - u), initial=0.0)
        u = new
        if converged:
            return u
        converged = change < 1e-9
    raise RuntimeError("egg support function: the tangency iteration did not converge")


def support(theta, a: float, w: float, x_G: float = 0.0):
    """The support function computed directly (no fit): (h, h_theta, h_thetatheta) at theta.

    Parameters
    ----------
    theta : float or array
        Inclination of k from the vertical, in [0, pi].
    a, w : float
        Aspect ratio L/B and asymmetry w/L.
    x_G : float
        Axial coordinate of the centre of mass (0 = the middle of the axis).

    Returns
    -------
    tuple
        (h, h_theta, h_thetatheta), units b: floats for a number, arrays of the shape of
        ``theta`` otherwise.

    Raises
    ------
    RuntimeError
        If the Newton iteration for the contact point does not converge.

    Notes
    -----
    h_theta follows from the envelope theorem, h_thetatheta = -h - F_theta^2 / F_u from the
    implicit derivative of the contact point; h + h_thetatheta is the meridional radius of
    curvature at the contact point.
    """
    theta = np.asarray(theta, dtype=float)
    th = np.atleast_1d(theta).ravel()
    u = _contact_parameter(th, a, w)
    ct, st = np.cos(th), np.sin(th)
    _, Fu, y, y1 = _tangency(u, ct, st, a, w)
    h = a * np.cos(u) * ct + y * st + x_G * ct
    h1 = -a * np.cos(u) * st + y * ct - x_G * st
    Ft = a * np.sin(u) * st + y1 * ct
    h2 = -h - Ft * Ft / Fu
    out = tuple(v.reshape(theta.shape) for v in (h, h1, h2))
    return tuple(float(v) for v in out) if theta.ndim == 0 else out


# -- mass properties -------------------------------------------------------------------------
# -- the Chebyshev fit -----------------------------------------------------------------------
def _chebyshev_coefficients(a: float, w: float, degree: int) -> np.ndarray:
    """Coefficients of the degree-``degree`` interpolant of H_O(c) = h_O(acos c) at the
    Chebyshev points of the first kind, c_k = cos(theta_k), by DCT-II.

    With H = sum a_k T_k(c), h(theta) = sum a_k cos(k theta) and the meridional radius of
    curvature rho = h + h_thetatheta = sum (1 - k^2) a_k cos(k theta). a_0 and a_1 come from
    samples of h, a_k (k >= 2) from samples of rho divided by 1 - k^2: rounding noise in a_k
    is then ~eps / k^2 rather than ~eps, so that it does not grow into h_thetatheta (which
    weighs a_k by k^2). The points are generated as theta_k so that acos is never evaluated;
    the DCT replaces numpy's ``chebinterpolate``, whose Vandermonde solve lets rounding grow
    to ~1e-14 at degree 200.
    """
    import scipy.fft

    n = degree + 1
    theta = np.pi * (np.arange(n) + 0.5) / n
    h, _, h2 = support(theta, a, w)
    coef = scipy.fft.dct(h, type=2) / n
    rho = scipy.fft.dct(h + h2, type=2) / n
    k = np.arange(2, n)
    coef[2:] = rho[2:] / (1.0 - k * k)
    coef[0] *= 0.5
    return coef


def _check_grid() -> np.ndarray:
    """theta grid for the fit check: uniform in theta (fine near the poles in c) and
    uniform in c (fine at the equator in theta)."""
    return np.unique(np.concatenate([np.linspace(0.0, np.pi, 2049), np.arccos(np.linspace(-1.0, 1.0, 2049))]))


def _fit_errors(a: float, w: float, series: np.ndarray) -> tuple[float, float]:
    """Max errors of the series in h and in rho = h + h_thetatheta on the check grid, against
    the direct solve."""
    theta = _check_grid()
    k = np.arange(series.size)
    cos_k = np.cos(np.outer(theta, k))
    h, _, h2 = support(theta, a, w)
    err_h = np.max(np.abs(cos_k @ series - h))
    err_rho = np.max(np.abs(cos_k @ ((1.0 - k * k) * series) - (h + h2)))
    return float(err_h), float(err_rho)


@functools.lru_cache(maxsize=256)
def fit_support(a: float, w: float) -> tuple[tuple[float, ...], int, float, float]:
    """(coefficients of H_O, needed degree, max fit error in h, max fit error in rho).

    The series keeps every coefficient up to the chosen tier: beyond the needed degree they
    are accurate (small) and only improve h_thetatheta. Raises ParameterError (naming ``w``)
    when the series needs more than MAX_DEGREE terms.
    """
    coef = _chebyshev_coefficients(a, w, _SAMPLE_DEGREE)
    if w == 0.0:
        coef[1::2] = 0.0  # h_O is flip-symmetric: odd terms are rounding noise
    k = np.arange(coef.size)
    # k^2 |a_k| bounds the term's share of h_thetatheta (and of rho)
    big = np.flatnonzero(np.maximum(k * k, 1) * np.abs(coef) > CHOP_REL * np.abs(coef).max())
    needed = int(big[-1]) if big.size else 0
    if needed > MAX_DEGREE:
        raise ParameterError(
            "w",
            f"is too large for a = {a:g}: the support function needs a Chebyshev series of degree "
            f"{'>= ' if needed >= _SAMPLE_DEGREE else ''}{needed} "
            f"(> {MAX_DEGREE}); every a in [{A_RANGE[0]:g}, {A_RANGE[1]:g}] works up to w = {W_GUARANTEED:g}, "
            f"and a in [1, 1.5] up to w = 0.24 (the fat end flattens as w -> {W_MAX:g})",
            w,
        )
    degree = next(d for d in DEGREES if d >= needed)
    series = coef[: degree + 1].copy()
    err_h, err_rho = _fit_errors(a, w, series)
    if not err_h < FIT_TOL:
        raise ParameterError(
            "w",
            f"gives a support function whose degree-{degree} fit misses {FIT_TOL:g} (error {err_h:.3g}) for a = {a:g}",
            w,
        )
    return tuple(float(v) for v in series), needed, err_h, err_rho


def clenshaw(c, coef):
    """sum_k coef[k] T_k(c) by Clenshaw's recurrence, with + - * only (so that the expression
    translates to every backend).

    Parameters
    ----------
    c : float or casadi.SX
        The argument of the Chebyshev polynomials T_k.
    coef : sequence of float or casadi.SX
        The coefficients, coef[k] of T_k, at least one.

    Returns
    -------
    float or casadi.SX
        The sum, of the kind of ``c`` and ``coef``.
    """
    n = coef.shape[0] if hasattr(coef, "shape") else len(coef)
    if n == 1:
        return coef[0]
    b1, b2 = coef[n - 1], 0
    for k in range(n - 2, 0, -1):
        b1, b2 = coef[k] + 2 * c * b1 - b2, b1
    return coef[0] + c * b1 - b2


