"""The steady states of (2.7) in closed form (part I of the series), for any body: the spins at
the poles, the horizontal precession and the precessions located on the body's profile.

Classes of steady states of (2.7)
---------------------------------
vertical       theta = 0, spin n0 about the vertical, U = V = 0 (resting on the end at -k).
               The Euler chart is singular there, so it is found and linearised in the
               vector chart (k = e_Z, w = n0 e_Z, v = 0).
inverted       theta = pi: k = -e_Z, w = n0 k (spin n = w.k = n0), v = 0, resting on the end
               at +k. For a flip-symmetric body (h(pi - theta) = h(theta)) this is the vertical
               state with k reversed, so it is reported only for bodies without that symmetry.
               The state is exact (r_P is vertical at both poles); it is linearised in the
               vector chart.
horizontal     steady precession with the axis horizontal: U = V = Lambda = n = 0,
               theta = pi/2, any Omega0. It exists only where h_theta(pi/2) = 0 (flip-symmetric
               bodies): otherwise G is not above P when the axis is horizontal.
intermediate   steady precession at 0 < theta* < pi: Lambda = U = V = 0, zero slip
               V_P = 0, i.e. n = Omega (cos theta - h_theta / x_P), and the torque balance
               (2.7d) with R = 1 and no friction force:
                   Omega^2 = h_theta / (sin theta [(A - C) cos theta + C h_theta / x_P]),
               a family in theta* where the right-hand side is positive. Nothing here assumes
               flip symmetry (derived from (2.7a-f) with U = V = Lambda = 0: (2.7a, b) give
               F = 0, (2.7c, e, f) hold identically, (2.4) gives the spin, (2.7d) the rate).
horizontal-like for a body with h_theta(pi/2) != 0 (an egg), the member of the Omega-family
               that continues the horizontal state: the branch that leaves the static
               equilibrium lying on the side (theta_1, where h_theta = 0) at Omega -> 0 and tends,
               as Omega -> infinity, to theta_2 where (A - C) cos theta x_P + C h_theta = 0
               (the rate diverges there). For a flip-symmetric body theta_1 = theta_2 = pi/2.
All of them have zero slip, so friction does no work on them and they exist for every law.

Locating the precessions. With q = h_theta / sin(theta) = -H'(cos theta) and the azimuthal
radius of curvature rho_2 = x_P / sin(theta) (both regular at the poles), the states with
rate Omega0 are the roots in theta of the smooth function

    G_Omega(theta) = q rho_2 - Omega0^2 [(A - C) cos(theta) rho_2 + C q],

and those with spin n0 (n = Omega z / rho_2, z = h cos - h_theta sin) the roots of

    G_n(theta) = q z^2 - n0^2 rho_2 [(A - C) cos(theta) rho_2 + C q].

They are bracketed on a fine grid and refined by Brent's method, then polished by Newton on
the full equations (:func:`phasekit.steady.find_fixed_point`, in phasekit.steady.fixedpoints).
For the eccentric sphere G_n is alpha (cos - alpha)^2 - n0^2 ((A - C) cos + C alpha),
phasekit.theory.tippetop's steady states.
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_finite


def horizontal_state(omega0: float) -> np.ndarray:
    """(U, V, Omega, Lambda, theta, n) = (0, 0, Omega0, 0, pi/2, 0).

    Parameters
    ----------
    omega0 : float
        Precession rate Omega0.

    Returns
    -------
    numpy.ndarray
        The Euler-chart state (U, V, Omega, Lambda, theta, n).

    Raises
    ------
    ParameterError
        If `omega0` is not a finite real number.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.steady.horizontal_state(10.0).round(6)
    array([ 0.      ,  0.      , 10.      ,  0.      ,  1.570796,  0.      ])
    """
    return np.array([0.0, 0.0, check_finite("omega0", omega0), 0.0, np.pi / 2, 0.0])


def vertical_state(n0: float) -> np.ndarray:
    """Vector-chart state k = e_Z, w = n0 e_Z, v = 0 (theta = 0).

    Parameters
    ----------
    n0 : float
        Spin about the vertical.

    Returns
    -------
    numpy.ndarray
        The vector-chart state (k_x, k_y, k_z, w_x, w_y, w_z, v_x, v_y).

    Raises
    ------
    ParameterError
        If `n0` is not a finite real number.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.steady.vertical_state(10.0)
    array([ 0.,  0.,  1.,  0.,  0., 10.,  0.,  0.])
    """
    return np.array([0.0, 0.0, 1.0, 0.0, 0.0, check_finite("n0", n0), 0.0, 0.0])


def inverted_state(n0: float) -> np.ndarray:
    """Vector-chart state k = -e_Z, w = n0 k = -n0 e_Z, v = 0 (theta = pi, spin w.k = n0).
    An exact steady state of every body (the contact point lies straight below G).

    Parameters
    ----------
    n0 : float
        Spin w.k.

    Returns
    -------
    numpy.ndarray
        The vector-chart state (k_x, k_y, k_z, w_x, w_y, w_z, v_x, v_y).

    Raises
    ------
    ParameterError
        If `n0` is not a finite real number.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.steady.inverted_state(10.0).round(6)
    array([  0.,   0.,  -1.,   0.,   0., -10.,   0.,   0.])
    """
    return np.array([0.0, 0.0, -1.0, 0.0, 0.0, -check_finite("n0", n0), 0.0, 0.0])


def precession_geometry(body, theta):
    h, ht, _ = body.h(theta)
    s, c = np.sin(theta), np.cos(theta)
    return h, ht, s, c, h * s + ht * c


def _regular(body, theta):
    """(q, rho_2, z, D) at theta (arrays): q = h_theta / sin = -H'(cos), rho_2 = x_P / sin,
    z = h cos - h_theta sin, D = (A - C) cos rho_2 + C q; all regular at the poles."""
    theta = np.asarray(theta, dtype=float)
    c = np.cos(theta)
    H, dH = _height_slope_many(body, c)
    q = -dH
    with np.errstate(invalid="ignore"):  # NaN where H' diverges: an edged body's end (a face), off its range
        h, ht, s = H, q * np.sin(theta), np.sin(theta)
        rho2 = h + q * c  # x_P / sin = h + h_theta cos / sin
        z = h * c - ht * s
        D = (body.A - body.C) * c * rho2 + body.C * q
    return q, rho2, z, D


def _height_slope_many(body, c):
    """(H, dH/dc) at an array of c, by the body's compiled slope function mapped over c."""
    from ..bodies.body import slope_function

    c = np.atleast_1d(np.asarray(c, dtype=float))
    shape = np.asarray(body.shape_params, dtype=float)
    H, dH = slope_function(body).map(c.size)(c[None, :], np.tile(shape[:, None], (1, c.size)))
    return np.asarray(H).ravel(), np.asarray(dH).ravel()


def precession_residual(body, theta, *, omega0: float | None = None, n0: float | None = None):
    """G_Omega(theta) (given ``omega0``) or G_n(theta) (given ``n0``): zero exactly where a
    steady precession with that rate or spin exists (module notes). ``theta`` may be an array."""
    q, rho2, z, D = _regular(body, theta)
    if omega0 is not None:
        out = q * rho2 - omega0 * omega0 * D
    else:
        out = q * z * z - n0 * n0 * rho2 * D
    return out if np.ndim(theta) else float(out[0])


#: spins below this are spin 0: the two states with spin +n0 and -n0 near a point of spin 0
#: (z = 0) differ in tilt by ~n0, which rounding cannot resolve, so one is listed (Omega >= 0)
SPIN_FLOOR = 1e-12


def precession_angles(body, *, omega0: float | None = None, n0: float | None = None, theta_range=None,
                      n_grid: int = 4001) -> list[float]:
    """Every theta strictly inside ``theta_range`` (default (0, pi), or (0, pi/2) for a
    flip-symmetric body) at which a steady precession with rate ``omega0`` (or spin ``n0``)
    exists: sign changes of :func:`precession_residual` on ``n_grid`` points (the ends of the
    range included, so a root next to a pole is found), refined by Brent's method to ~1e-15, and
    pairs of roots between two grid points (a dip of the residual toward zero, located and tested).
    For a flip-symmetric body the residual is divided by cos(theta), its factor from the
    horizontal family at pi/2 (where it vanishes identically), so precessions however close to
    pi/2 are found and pi/2 itself is not; with ``n0`` = 0 (|n0| < SPIN_FLOOR) the roots are
    those of q (the tilted static equilibria) and of z on a branch (spin 0, n = Omega z / rho_2),
    which the residual has only as double roots (none where z = 0 identically, the thin disk's
    precessions, which all have spin 0: a continuum). For a body with an edge the scan also
    takes EDGE_PROBES from each end, where a face coming down crowds the states.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).
    omega0 : float, optional
        Precession rate; exactly one of ``omega0`` and ``n0`` is given.
    n0 : float, optional
        Spin.
    theta_range : tuple of float, optional
        (lo, hi), radians; the end points themselves are not roots.
    n_grid : int, optional
        Number of grid points over ``theta_range``.

    Returns
    -------
    list of float
        The angles, radians, in increasing order.

    Raises
    ------
    ValueError
        If not exactly one of ``omega0`` and ``n0`` is given.

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(t, 6) for t in pk.steady.precession_angles(pk.Egg(1.3, 0.05), omega0=6.0)]
    [0.51274, 1.756111]
    """
    if (omega0 is None) == (n0 is None):
        raise ValueError("give exactly one of `omega0` or `n0`.")
    flip = bool(body.flip_symmetric)
    if theta_range is None:
        theta_range = (0.0, np.pi / 2) if flip else (0.0, np.pi)
    grid = np.linspace(theta_range[0], theta_range[1], n_grid)
    if body.theta_range is not None:  # a body with an edge: H' may diverge at an end (a face), where the states crowd
        grid = np.union1d(grid, np.concatenate([theta_range[0] + EDGE_PROBES, theta_range[1] - EDGE_PROBES]))
    if n0 is not None and abs(n0) < SPIN_FLOOR:
        statics = _angles(lambda t: _reduced(_regular(body, t)[0], t, flip), grid)
        if _spinless(body, grid):  # n = 0 all along (the thin disk spinning in place): a continuum, not states
            return statics
        spinless = _angles(lambda t: _reduced(_regular(body, t)[2], t, flip), grid)
        return sorted(statics + [t for t in spinless if _omega_squared(body, t) > 0.0])
    # the spin residual has a double root where z = 0 (n changes sign): a pair of states with
    # spin +-n0 straddles it, found from z's own root however close together they are
    double = None if n0 is None else (lambda t: _reduced(_regular(body, t)[2], t, flip))
    return _angles(lambda t: _reduced(precession_residual(body, t, omega0=omega0, n0=n0), t, flip), grid, double)


#: the distances from an end of an edged body's range added to the scan: roots within the first
#: grid step of a face coming down (Omega^2 ~ 1 / (A sin theta) there) bracketed down to 1e-7
EDGE_PROBES = np.geomspace(1e-7, 1e-3, 9)
#: z within this of 0, relative to rho_2, at every scanned theta: n = Omega z / rho_2 = 0 all along
SPINLESS_RTOL = 1e-12


def _spinless(body, grid) -> bool:
    """Whether n = 0 on every steady precession of ``body`` (z = 0 at every finite point of
    ``grid``: H = k sqrt(1 - c^2), the thin disk, whose precessions all spin in place)."""
    with np.errstate(all="ignore"):
        _, rho2, z, _ = _regular(body, grid)
        ok = np.isfinite(z) & np.isfinite(rho2)
        return bool(ok.any() and np.all(np.abs(z[ok]) <= SPINLESS_RTOL * np.abs(rho2[ok])))


def root_float(body, theta: float, *, omega0: float | None = None, n0: float | None = None) -> float:
    """The float within 16 floats of ``theta`` (a root of :func:`precession_residual` found by
    any route) at which the residual (as :func:`precession_angles` scans it) is smallest: the
    same float from any estimate a few floats off, so that every route that finds a state
    polishes it from the same start and ends at the same state, bit for bit."""
    flip = bool(body.flip_symmetric)
    lo = hi = float(theta)
    below, above = [], []
    for _ in range(16):
        lo, hi = float(np.nextafter(lo, -np.inf)), float(np.nextafter(hi, np.inf))
        below.append(lo)
        above.append(hi)
    ts = np.array(below[::-1] + [float(theta)] + above)
    ts = ts[(ts > 0.0) & (ts < np.pi)]
    if n0 is not None and abs(n0) < SPIN_FLOOR:
        q, _, z, _ = _regular(body, ts)
        r = _reduced(_reduced(q * z, ts, flip), ts, flip)
    else:
        r = _reduced(precession_residual(body, ts, omega0=omega0, n0=n0), ts, flip)
    r = np.where(np.isfinite(r), np.abs(r), np.inf)
    return float(ts[int(np.argmin(r))]) if np.isfinite(r).any() else float(theta)


def _reduced(values, theta, flip: bool):
    """``values`` divided by cos(theta) for a flip-symmetric body (the horizontal family's factor:
    the residual, q and z are odd about pi/2 there), as they are otherwise."""
    return values / np.cos(theta) if flip else values


def _omega_squared(body, theta: float) -> float:
    q, rho2, _, D = (float(v[0]) for v in _regular(body, np.array([theta])))
    return q * rho2 / D if D != 0.0 else float("inf")


def _angles(fun, grid: np.ndarray, double=None) -> list[float]:
    """The roots of ``fun`` (vectorised) strictly inside the range of ``grid``: sign changes
    refined by Brent's method, exact zeros at grid points, and pairs of roots between grid
    points where |fun| dips toward zero without a sign change (the dip's extremum is located,
    as the root of ``double`` where that changes sign there (a factor whose square divides
    ``fun`` up to a small term: located to rounding, which minimising |fun| is not), else by
    Brent's minimisation, and tested)."""
    from scipy.optimize import brentq, minimize_scalar

    g = np.asarray(fun(grid), dtype=float)
    f = lambda t: float(np.asarray(fun(np.array([t])), dtype=float)[0])  # noqa: E731
    sgn = np.sign(g)
    roots = [float(t) for t in grid[1:-1][sgn[1:-1] == 0.0]]
    for k in np.flatnonzero(sgn[:-1] * sgn[1:] < 0):
        roots.append(float(brentq(f, grid[k], grid[k + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps)))
    a = np.abs(g)
    dips = np.flatnonzero((a[1:-1] < a[:-2]) & (a[1:-1] < a[2:]) & (sgn[:-2] == sgn[1:-1]) & (sgn[1:-1] == sgn[2:])
                          & (sgn[1:-1] != 0) & np.isfinite(a[1:-1])) + 1
    for k in dips:
        lo, hi = grid[k - 1], grid[k + 1]
        d = None if double is None else np.asarray(double(np.array([lo, hi])), dtype=float)
        if d is not None and d[0] * d[1] < 0:
            t0 = brentq(lambda t: float(np.asarray(double(np.array([t])))[0]), lo, hi, xtol=1e-16, rtol=4 * np.finfo(float).eps)
            low = sgn[k] * f(t0)
        else:
            res = minimize_scalar(lambda t, s=sgn[k]: s * f(t), bounds=(lo, hi), method="bounded", options={"xatol": 1e-14})
            t0, low = float(res.x), res.fun
        if low < 0:
            roots += [float(brentq(f, lo, t0, xtol=1e-15)), float(brentq(f, t0, hi, xtol=1e-15))]
    return sorted(r for r in roots if grid[0] < r < grid[-1])


def precession_state(body, theta: float, *, omega0: float | None = None, n0: float | None = None) -> np.ndarray:
    """The steady precession at ``theta`` with rate ``omega0`` or spin ``n0`` (Euler chart):
    (0, 0, Omega, 0, theta, n) with n = Omega z / rho_2 (zero slip). ``theta`` should be one
    of :func:`precession_angles`; no check that the torque balance holds is made here. Given
    ``n0``, Omega = n0 rho_2 / z, or where z is within rounding of 0 (near a point of spin 0)
    the same rate from the curve, sign(n0 z) sqrt(q rho_2 / D) (Omega >= 0 for |n0| < SPIN_FLOOR)."""
    q, rho2, z, D = (float(v[0]) for v in _regular(body, np.array([theta])))
    if omega0 is not None:
        om = float(omega0)
        n = om * z / rho2
    else:
        n = float(n0)
        if abs(z) > 1e-8 * abs(D):
            om = n * rho2 / z
        else:
            sign = -1.0 if n * z < 0 and abs(n) >= SPIN_FLOOR else 1.0
            om = sign * float(np.sqrt(max(q * rho2 / D, 0.0))) if D != 0.0 else 0.0
    return np.array([0.0, 0.0, om, 0.0, float(theta), n])


def side_equilibrium(body) -> tuple[float, float]:
    """(theta_1, theta_2) nearest pi/2: theta_1 where h_theta = 0 (the body at rest on its side),
    theta_2 where (A - C) cos(theta) x_P + C h_theta = 0 (the fast-precession limit of the
    horizontal-like state). Both are pi/2 for a flip-symmetric body.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).

    Returns
    -------
    tuple of float
        (theta_1, theta_2), radians; NaN for an angle where no sign change is found in (0, pi).

    Examples
    --------
    >>> import phasekit as pk
    >>> [round(t, 6) for t in pk.steady.side_equilibrium(pk.Egg(1.3, 0.05))]
    [1.676232, 1.74775]
    """
    from scipy.optimize import brentq

    if body.flip_symmetric:
        return np.pi / 2, np.pi / 2
    grid = np.linspace(1e-3, np.pi - 1e-3, 2001)
    out = []
    for idx in (0, 3):
        v = _regular(body, grid)[idx]
        k = np.flatnonzero(np.sign(v[:-1]) * np.sign(v[1:]) <= 0)
        if k.size == 0:
            out.append(float("nan"))
            continue
        k = k[np.argmin(np.abs(grid[k] - np.pi / 2))]
        f = lambda t, i=idx: float(_regular(body, np.array([t]))[i][0])  # noqa: E731
        out.append(float(brentq(f, grid[k], grid[k + 1], xtol=1e-15)))
    return out[0], out[1]


#: a precession within this of [theta_1, theta_2] continues the horizontal state
HORIZONTAL_LIKE_WINDOW = 0.25


def horizontal_like_angle(body, thetas) -> float | None:
    """Among precession angles ``thetas`` of one Omega-family, the one continuing the
    horizontal state of a body with h_theta(pi/2) != 0: the nearest to the interval between
    theta_1 and theta_2 (:func:`side_equilibrium`), if within HORIZONTAL_LIKE_WINDOW. The
    symmetric pitchfork of the spheroid (the intermediate family branching off the horizontal
    state at the stability threshold) unfolds for such a body: at slow precession the state
    near theta_1 (the body lying on its side) continues the horizontal state, at fast
    precession the unstable state near theta_2 does. None for flip-symmetric bodies.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).
    thetas : sequence of float
        Precession angles of one Omega-family, radians (:func:`precession_angles`).

    Returns
    -------
    float or None
        The angle, or None if no angle is within the window (or ``thetas`` is empty).

    Examples
    --------
    >>> import phasekit as pk
    >>> egg = pk.Egg(1.3, 0.05)
    >>> round(pk.steady.precessions.horizontal_like_angle(egg, pk.steady.precession_angles(egg, omega0=6.0)), 6)
    1.756111
    """
    if body.flip_symmetric or not len(thetas):
        return None
    th1, th2 = side_equilibrium(body)
    lo, hi = min(th1, th2), max(th1, th2)
    dist = [max(lo - t, t - hi, 0.0) for t in thetas]
    k = int(np.argmin(dist))
    return float(thetas[k]) if dist[k] <= HORIZONTAL_LIKE_WINDOW else None


def intermediate_omega(body, theta: float) -> float | None:
    """Omega of the intermediate steady precession at theta, or None where it does not exist.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).
    theta : float
        Tilt of the axis, radians, in (0, pi).

    Returns
    -------
    float or None
        The positive rate Omega, or None where Omega^2 would not be positive.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.steady import precessions
    >>> round(precessions.intermediate_omega(pk.Spheroid(1.5), 1.0), 6)
    2.068755
    """
    h, ht, s, c, xP = precession_geometry(body, theta)
    denom = s * ((body.A - body.C) * c + body.C * ht / xP)
    if denom == 0.0 or ht / denom <= 0.0:
        return None
    return float(np.sqrt(ht / denom))


def intermediate_state(body, theta: float) -> np.ndarray | None:
    """The intermediate steady precession at theta (Omega > 0 root), or None.

    Parameters
    ----------
    body : Body
        The body (a support function h(theta) and moments A, C).
    theta : float
        Tilt of the axis, radians, in (0, pi).

    Returns
    -------
    numpy.ndarray or None
        The Euler-chart state (U, V, Omega, Lambda, theta, n), or None where it does not exist.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.steady import precessions
    >>> precessions.intermediate_state(pk.Spheroid(1.5), 1.0).round(6)
    array([0.      , 0.      , 2.068755, 0.      , 1.      , 2.514945])
    """
    om = intermediate_omega(body, theta)
    if om is None:
        return None
    h, ht, s, c, xP = precession_geometry(body, theta)
    return np.array([0.0, 0.0, om, 0.0, theta, om * (c - ht / xP)])
