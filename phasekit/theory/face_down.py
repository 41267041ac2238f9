"""A disk sliding and spinning on its face: the terminal motion of the Contensou coupling.

A flat disk of radius r (units b; mass M = 1, g = 1, so the normal force is R = 1) lies on its face,
its centre sliding at speed v and the disk spinning at omega about the vertical. Coulomb friction over
the face (:mod:`phasekit.friction.patch`, uniform pressure) gives a force along -v (the path is
straight) and a couple against omega:

    dv/dt = -mu f(eps),     kappa r domega/dt = -mu g(eps),     eps = v/(r omega),

with I = kappa M r^2. The full disk has kappa = 1/2. An annulus r_i = beta r < rho < r bearing with
uniform pressure R/(pi r^2 (1 - beta^2)) is the full disk minus the inner one (the traction is local):

    f_beta(eps) = [f(eps) - beta^2 f(eps/beta)]/(1 - beta^2),
    g_beta(eps) = [g(eps) - beta^3 g(eps/beta)]/(1 - beta^2),

and so d_beta with beta^3. Its inertia (:func:`inertia_factor`): "washer", mass spread uniformly over
the annulus, kappa = (1 + beta^2)/2 (taken to be the annular disk of Weidman & Malhotra, whose eps*
runs over the same range); or "disk", a full uniform disk bearing on an annular rim (a recessed
base), kappa = 1/2, whose eps* grows past 1 and diverges as beta -> 1 (kappa meets k_w = (1 + beta^2)/4).

The ratio. With ln omega as the clock (it decreases: d ln omega/dt = -mu g/(kappa r omega) < 0),

    d eps/d(ln omega) = kappa f(eps)/g(eps) - eps = h(eps),

independent of mu and r. As omega falls, eps moves against the sign of h: it leaves 0 when
h'(0) = kappa k_v/g0 - 1 < 0 (full disk: 3/4 - 1) and leaves oo when kappa f/g ~ (kappa/k_w) eps
grows faster than eps, kappa > k_w (full disk: f -> 1, g ~ 1/(4 eps), h ~ eps). So eps tends to the
zero eps* of kappa f(eps) = eps g(eps) (:func:`terminal_ratio`), attracting where h'(eps*) > 0.
Then v and omega both decrease at rates bounded below while v/(r omega) stays bounded and away
from 0: they vanish at the same instant, T = int_0^omega0 kappa r/(mu g(eps)) domega
(:func:`stop_time`). Goyal, Ruina & Papadopoulos (1991) and Weidman & Malhotra found the same three
regimes: eps -> 0 for kappa k_v/g0 > 1 (k = sqrt(kappa) > sqrt(2/3) for uniform pressure), eps -> oo
for kappa < k_w (k < 1/2), a finite eps* between.

Numbers: the full disk's eps* = 0.6530017892 (0.653001789205598 by mpmath at 30 digits), with
h'(eps*) = 0.615. Farkas, Bartels, Unger & Wolf (2003) give 0.653: their paper was not read here;
Weidman & Malhotra's abstract, reviewing it, says the terminal ratio "is always 1.0 for the ring and
0.653 for the uniform disk", and Weidman's 2017 Newton Institute abstract says the annular disk's
"ranges from 0.653 to 1 as the radius ratio eta = Rin/Rout varies from 0 to 1". The washer's
eps*(beta): 0.6530 (0), 0.6595 (0.1), 0.7044 (0.3), 0.7745 (0.5), 0.8580 (0.7), 0.9508 (0.9),
0.9950 (0.99), 0.9995 (0.999), towards 1, where the ring's f and g meet at eps = 1 (both 2/pi).

Energy. E = v^2/2 + kappa r^2 omega^2/2 changes at the power F.v + M omega = -mu r omega d_beta(eps),
d the patch's dissipation (:func:`phasekit.friction.patch.patch_resultant`), which :func:`slide_to_rest`
integrates alongside to check the balance.

References
----------
Farkas Z., Bartels G., Unger T., Wolf D. E. (2003), Frictional coupling between sliding and spinning
motion, Phys. Rev. Lett. 90, 248302. DOI 10.1103/PhysRevLett.90.248302.
Weidman P. D., Malhotra C. P., On the terminal motion of sliding spinning disks with uniform Coulomb
friction (abstract: nd.ics.org.ru/authors_nd/detail/334-patrick_weidman; Physica D 233 (2007) 1-13
by secondary citations, not checked). Also: Regimes of terminal motion of sliding spinning disks,
Phys. Rev. Lett. 95, 264303 (2005).
Goyal S., Ruina A., Papadopoulos J. (1991), Planar sliding with dry friction, parts 1 and 2, Wear 143,
307-330 and 331-352.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .._runtime.validate import check_choice, check_positive, check_range
from ..errors import ParameterError
from ..friction.patch import patch_resultant

#: how the annulus' mass is spread: "washer" (over the annulus) or "disk" (a full disk on an annular rim)
MASS_DISTRIBUTIONS = ("washer", "disk")
#: the largest inner/outer ratio: beyond it the difference quotients of the annulus lose > 8 digits
RATIO_MAX = 0.9999


def _check_ratio(ratio) -> float:
    return check_range("ratio", ratio, 0.0, RATIO_MAX, closed="lr", label=f"[0, {RATIO_MAX:g}]")


def inertia_factor(ratio: float = 0.0, mass: str = "washer") -> float:
    """kappa = I/(M r^2) about the axis for an annulus of inner/outer radius ratio beta.

    Parameters
    ----------
    ratio : float, optional
        beta = r_i/r in [0, 0.9999] (default 0: the full disk).
    mass : {"washer", "disk"}, optional
        "washer" (default): uniform over the annulus, kappa = (1 + beta^2)/2; "disk": a full uniform
        disk whose face bears only on the annulus, kappa = 1/2.

    Returns
    -------
    float
        kappa.

    Raises
    ------
    ParameterError
        If ``ratio`` is not in [0, 0.9999] or ``mass`` is unknown.

    Examples
    --------
    >>> from phasekit.theory.face_down import inertia_factor
    >>> inertia_factor(0.0), inertia_factor(0.5), inertia_factor(0.5, "disk")
    (0.5, 0.625, 0.5)
    """
    ratio = _check_ratio(ratio)
    mass = check_choice("mass", mass, MASS_DISTRIBUTIONS)
    return 0.5 * (1 + ratio * ratio) if mass == "washer" else 0.5


def annulus_resultant(eps, ratio: float = 0.0):
    """(f, g, d) of uniform pressure over an annulus, normalised by mu R, mu R r and mu R r |omega|.

    Parameters
    ----------
    eps : float or array_like
        v/(r omega) >= 0, r the outer radius.
    ratio : float, optional
        beta = r_i/r in [0, 0.9999] (default 0: the full disk).

    Returns
    -------
    tuple
        (f, g, d) of the shape of ``eps`` (module notes).

    Raises
    ------
    ParameterError
        If ``eps`` is negative or ``ratio`` is out of range.

    Examples
    --------
    >>> from phasekit.theory.face_down import annulus_resultant
    >>> [round(float(x), 10) for x in annulus_resultant(0.0, 0.5)]   # g(0) = (2/3)(1 + b + b^2)/(1 + b)
    [0.0, 0.7777777778, 0.7777777778]
    """
    ratio = _check_ratio(ratio)
    f, g, d = patch_resultant(eps, dissipation=True)
    if ratio == 0.0:
        return f, g, d
    fi, gi, di = patch_resultant(np.asarray(eps, dtype=float) / ratio, dissipation=True)
    den = 1 - ratio * ratio
    b2, b3 = ratio * ratio, ratio**3
    return (f - b2 * fi) / den, (g - b3 * gi) / den, (d - b3 * di) / den


def ratio_rate(eps, ratio: float = 0.0, kappa: float | None = None):
    """h(eps) = d eps/d(ln omega) = kappa f(eps)/g(eps) - eps (module notes).

    Parameters
    ----------
    eps : float or array_like
        v/(r omega) >= 0.
    ratio : float, optional
        beta = r_i/r (default 0).
    kappa : float, optional
        I/(M r^2); default :func:`inertia_factor` of ``ratio`` (a washer).

    Returns
    -------
    float or numpy.ndarray
        h(eps).

    Raises
    ------
    ParameterError
        If ``eps`` is negative, ``ratio`` out of range or ``kappa`` not > 0.

    Examples
    --------
    >>> from phasekit.theory.face_down import ratio_rate
    >>> round(float(ratio_rate(1.0)), 6)   # full disk: (1/2)(8/(3 pi))/(8/(9 pi)) - 1
    0.5
    """
    kappa = inertia_factor(ratio) if kappa is None else check_positive("kappa", kappa)
    f, g, _ = annulus_resultant(eps, ratio)
    return kappa * f / g - np.asarray(eps, dtype=float)


@dataclass(frozen=True)
class TerminalRatio:
    """The terminal ratio eps* = v/(r omega) of a face-down disk and how it was found.

    Attributes
    ----------
    eps : float
        eps*, the zero of h(eps) = kappa f/g - eps.
    bracket : tuple of float
        (lo, hi): h changes sign over it, and it holds the only sign change on the scanned grid.
    slope : float
        h'(eps*) (central difference): > 0 means eps* attracts as omega -> 0.
    status : str
        "converged" (brentq to 1e-14), or "bracket_only" when the scan found more than one zero
        (then ``eps`` is the one in ``bracket`` nearest the full disk's).
    """

    eps: float
    bracket: tuple[float, float]
    slope: float
    status: str

    @property
    def attracting(self) -> bool:
        return self.slope > 0

    def __repr__(self) -> str:
        return f"TerminalRatio(eps={self.eps:.10g}, slope={self.slope:.4g}, status={self.status!r})"


def terminal_ratio(ratio: float = 0.0, kappa: float | None = None) -> TerminalRatio:
    """The terminal ratio eps* of kappa f(eps) = eps g(eps) (module notes).

    Parameters
    ----------
    ratio : float, optional
        beta = r_i/r in [0, 0.9999] (default 0: the full disk).
    kappa : float, optional
        I/(M r^2); default the washer's (1 + beta^2)/2.

    Returns
    -------
    TerminalRatio
        eps*, its bracket, h'(eps*) and a status.

    Raises
    ------
    ParameterError
        If ``ratio`` or ``kappa`` is out of range, or h has no zero in [1e-6, 1e6] (kappa outside
        the finite-ratio regime: eps -> 0 or eps -> oo).

    Examples
    --------
    >>> from phasekit.theory.face_down import terminal_ratio
    >>> round(terminal_ratio().eps, 10)
    0.6530017892
    """
    ratio = _check_ratio(ratio)
    kappa = inertia_factor(ratio) if kappa is None else check_positive("kappa", kappa)
    grid = np.geomspace(1e-6, 1e6, 1201)
    h = ratio_rate(grid, ratio, kappa)
    changes = np.flatnonzero(np.sign(h[:-1]) != np.sign(h[1:]))
    if changes.size == 0:
        regime = "eps -> 0 (v stops first)" if h[-1] < 0 else "eps -> oo (the spin stops first)"
        raise ParameterError("kappa", f"gives no terminal ratio in [1e-6, 1e6]: {regime}", kappa)
    k = int(changes[np.argmin(np.abs(np.log(grid[changes] / 0.65)))])
    lo, hi = float(grid[k]), float(grid[k + 1])
    eps = brentq(lambda e: float(ratio_rate(e, ratio, kappa)), lo, hi, xtol=1e-15, rtol=1e-14)
    step = 1e-6 * eps
    slope = float(ratio_rate(eps + step, ratio, kappa) - ratio_rate(eps - step, ratio, kappa)) / (2 * step)
    return TerminalRatio(eps, (lo, hi), slope, "converged" if changes.size == 1 else "bracket_only")


def stop_time(v0: float, omega0: float, *, mu: float, r: float = 1.0, ratio: float = 0.0, mass: str = "washer",
              rtol: float = 1e-12) -> float:
    """The instant at which the disk stops, computed in the clock tau = ln(omega0/omega).

    d eps/d tau = -h(eps) and dt/d tau = kappa r omega0 e^(-tau)/(mu g(eps)), integrated to tau = 60
    (the remaining time is below e^-60 of the total); independent of :func:`slide_to_rest`'s time
    integration.

    Parameters
    ----------
    v0 : float
        Initial speed of the centre, > 0 (units sqrt(g b)).
    omega0 : float
        Initial spin, > 0 (units sqrt(g/b)).
    mu : float
        Friction coefficient, > 0.
    r : float, optional
        Outer radius (units b), default 1.
    ratio : float, optional
        beta = r_i/r (default 0).
    mass : {"washer", "disk"}, optional
        The annulus' mass distribution (default "washer").
    rtol : float, optional
        Relative tolerance of the integration (default 1e-12).

    Returns
    -------
    float
        The stopping time T (units sqrt(b/g)).

    Raises
    ------
    ParameterError
        If a value is out of range.

    Examples
    --------
    >>> from phasekit.theory.face_down import stop_time
    >>> round(stop_time(1.0, 1e-12, mu=0.5), 6)   # (almost) pure sliding: v0/(mu g)
    2.0
    """
    v0, omega0, mu, r = (check_positive(n, x) for n, x in (("v0", v0), ("omega0", omega0), ("mu", mu), ("r", r)))
    kappa = inertia_factor(ratio, mass)

    def rhs(tau, y):
        f, g, _ = annulus_resultant(y[0], ratio)
        return [-(kappa * f / g - y[0]), kappa * r * omega0 * np.exp(-tau) / (mu * g)]

    sol = solve_ivp(rhs, (0.0, 60.0), [v0 / (r * omega0), 0.0], method="DOP853", rtol=rtol, atol=1e-14)
    return float(sol.y[1, -1])


@dataclass(frozen=True)
class FaceDownRun:
    """A face-down disk integrated in time until (almost) at rest.

    Attributes
    ----------
    ts : numpy.ndarray
        (n,) times of the steps.
    ys : numpy.ndarray
        (n, 3): speed v, spin omega and the work W = int (F.v + M omega) dt done on the disk,
        integrated from the patch's dissipation (not from f and g).
    energy_error : float
        max |E(t) - E(0) - W(t)| / E(0) along the run, E = v^2/2 + kappa r^2 omega^2/2.
    t_stop_slide, t_stop_spin : float
        When v and omega reach zero, each extrapolated from the last step at its final
        deceleration (v/(mu f) and kappa r omega/(mu g) beyond it).
    eps_end : float
        v/(r omega) at the last step.
    status : str
        "at_rest" (v + r omega fell below 1e-10 of its start) or the solver's message.
    """

    ts: np.ndarray
    ys: np.ndarray
    energy_error: float
    t_stop_slide: float
    t_stop_spin: float
    eps_end: float
    status: str

    def __repr__(self) -> str:
        return (f"FaceDownRun(t_stop_slide={self.t_stop_slide:.10g}, t_stop_spin={self.t_stop_spin:.10g}, "
                f"eps_end={self.eps_end:.8g}, status={self.status!r})")


def slide_to_rest(v0: float, omega0: float, *, mu: float, r: float = 1.0, ratio: float = 0.0, mass: str = "washer",
                  rtol: float = 1e-12, until: float = 1e-10) -> FaceDownRun:
    """Integrate dv/dt = -mu f, kappa r domega/dt = -mu g (and the work) until v + r omega falls
    below ``until`` of its start.

    Parameters
    ----------
    v0, omega0 : float
        Initial speed and spin, > 0.
    mu : float
        Friction coefficient, > 0.
    r : float, optional
        Outer radius (units b), default 1.
    ratio : float, optional
        beta = r_i/r (default 0: the full disk).
    mass : {"washer", "disk"}, optional
        The annulus' mass distribution (default "washer").
    rtol : float, optional
        Relative tolerance of DOP853 (default 1e-12).
    until : float, optional
        The stop, as a fraction of v0 + r omega0, in (0, 0.1] (default 1e-10).

    Returns
    -------
    FaceDownRun
        The run, its energy balance and both stopping times.

    Raises
    ------
    ParameterError
        If a value is out of range.

    Examples
    --------
    >>> from phasekit.theory.face_down import slide_to_rest
    >>> run = slide_to_rest(1.0, 3.0, mu=0.3)
    >>> run.status, round(run.eps_end, 5), abs(run.t_stop_slide - run.t_stop_spin) < 1e-8
    ('at_rest', 0.653, True)
    """
    v0, omega0, mu, r = (check_positive(n, x) for n, x in (("v0", v0), ("omega0", omega0), ("mu", mu), ("r", r)))
    until = check_range("until", until, 0.0, 0.1, closed="r", label="(0, 0.1]")
    kappa = inertia_factor(ratio, mass)
    scale = v0 + r * omega0

    def rhs(t, y):
        v, w = max(y[0], 0.0), max(y[1], 0.0)
        if w == 0.0:  # a trial step past the spin's end (the event stops the run before): pure sliding
            return [-mu if v > 0 else 0.0, 0.0, -mu * v]
        f, g, d = annulus_resultant(v / (r * w), ratio)
        return [-mu * f, -mu * g / (kappa * r), -mu * r * w * d]

    def rest(t, y):
        return y[0] + r * y[1] - until * scale

    rest.terminal, rest.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 10 * scale / mu * (1 + 1 / kappa)), [v0, omega0, 0.0], method="DOP853", rtol=rtol,
                    atol=1e-14 * scale, events=rest)
    ts, ys = sol.t, sol.y.T.copy()
    energy = 0.5 * ys[:, 0] ** 2 + 0.5 * kappa * r * r * ys[:, 1] ** 2
    err = float(np.max(np.abs(energy - energy[0] - ys[:, 2])) / energy[0])
    v, w = ys[-1, 0], ys[-1, 1]
    eps = v / (r * w)
    f, g, _ = annulus_resultant(eps, ratio)
    status = "at_rest" if sol.status == 1 else str(sol.message)
    return FaceDownRun(ts, ys, err, float(ts[-1] + v / (mu * f)), float(ts[-1] + kappa * r * w / (mu * g)),
                       float(eps), status)
