"""Simulations checked against the paper's theory (``phasekit.theory``).

The event that ends a rise, the nutation of amplitude c and phase xi (3.46) added to a start on
the sliding branch, the mean inclination at which the envelope Sigma (3.64) first reaches zero
(the predicted jump), a simulated rise set beside the gyroscopic solution (3.18) and Sigma
(:class:`EnvelopeCheck`), the friction coefficient that makes (3.18) fit a simulated theta(t)
best (the effective friction of a bouncing rise), a simulated first flight beside the gap
of section 4 (:class:`FlightCheck`), and the flights of an ensemble of perturbed starts
(:func:`gap_ensemble`). A rise from the sliding branch with a nutation is a
:class:`NutationCase`; the error of the jump surface (6.3) at simulated crossings, and its
trend in the start value, :func:`surface_crossings` and :func:`crossing_trend`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..bodies.body import Body
from ..core.hybrid import Event
from ..core.simulate import simulate
from ..theory.flight import flight_constants, gap_exact, gap_max_series, gap_series
from ..theory.gyroscopic import gyroscopic_closed, jellett_constant
from ..theory.multiscale import (
    amplitude_growth_closed,
    gyroscopic_nutation_frequency,
    reaction_envelope,
    slow_rates,
)
from ..theory.nutation import mean_over_periods, nutation_perturbation

#: the share of the minima of R on which the effective amplitude c_eff is fitted (the rest tests it)
FIT_SHARE = 0.3


def rise_complete(body: Body) -> Event:
    """The event that ends a rise once it is complete (no jump any more): theta falls through
    0.05 (a prolate body, rising from the horizontal) or rises through pi/2 - 0.05 (an oblate
    one, rising from the vertical).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.rise_complete(pk.Spheroid(1.5)).name
    'rise-complete'
    """
    if body.is_prolate:
        return Event("theta", 0.05, direction=-1, name="rise-complete")
    return Event("theta", np.pi / 2 - 0.05, direction=+1, name="rise-complete")


def add_nutation(body: Body, start, mu: float, c: float, xi: float = 0.0) -> np.ndarray:
    """A sliding-branch ``start`` (gyroscopic balance, :func:`phasekit.gyroscopic_start`; the
    paper's state (U, V, Omega, Lambda, theta, n)) with the O(mu) mean state and the nutation of
    amplitude ``c`` and phase ``xi`` added: the drift U = F_y / Omega of (2.7b) and the rise rate
    mu dtheta/dT of (3.16b) (without them the start carries an extra nutation of a few times c),
    then theta', Lambda' (3.46) and Omega' (3.27).

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> y = ps.add_nutation(body, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 0.1, -0.00054)
    >>> y.shape, bool(abs(y[4] - (np.pi / 2 - 0.01)) < 1e-3)
    ((6,), True)
    """
    theta0, om_bar0 = float(start[4]), float(start[2])
    th_p, lam_p, om_p = nutation_perturbation(body, theta0, om_bar0, mu, c, xi)
    y = np.array(start, dtype=float)
    _, dth_dT, vhat, _ = slow_rates(body, theta0, om_bar0)
    y[0] += -mu * vhat / om_bar0
    y[3] += mu * dth_dT
    y[4] += th_p
    y[3] += lam_p
    y[2] += om_p
    return y


def sigma_zero(theta, sigma) -> float | None:
    """The mean inclination at which the envelope ``sigma`` (sampled at ``theta``, in the order
    of the rise) first reaches 0, interpolated linearly: the predicted jump; None if it does not.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> theta = np.linspace(1.5, 0.02, 500)
    >>> z = ps.sigma_zero(theta, pk.theory.reaction_envelope(pk.Spheroid(1.5), 8.45, 1.5, theta, -0.00054))
    >>> 0.02 < z < 1.5
    True
    """
    k = np.flatnonzero(sigma <= 0)
    if k.size == 0:
        return None
    k = k[0]
    if k == 0:
        return float(theta[0])
    return float(theta[k - 1] + (theta[k] - theta[k - 1]) * sigma[k - 1] / (sigma[k - 1] - sigma[k]))


@dataclass(frozen=True)
class EnvelopeCheck:
    """A simulated rise beside the gyroscopic solution (3.18) and the envelope Sigma (3.64)
    (made by :func:`envelope_check`). Arrays: ``t``, ``theta``, ``R`` (the run sampled every
    dt); ``t_min``, ``R_min`` (the located minima of R); ``t_mid``, ``theta_bar``,
    ``Omega_bar`` (means over each fast period, between successive minima, (3.6)) and
    ``theta_gyro``, ``Omega_gyro`` ((3.18) at the same times); ``theta_at_min`` (theta-bar
    interpolated at each minimum), ``valid`` (the minima inside the averaged span), ``sigma``
    (Sigma with the nominal ``c``) and ``sigma_fit`` (with ``c_eff``, fitted on the first 30%
    of the valid minima). ``J`` = A Omega h (3.17) of the unperturbed start.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), ps.add_nutation(body, y0, 0.1, -0.00054), 60.0)
    >>> chk = ps.envelope_check(traj, y0, -0.00054, dt=0.01)
    >>> len(chk.errors()), bool(chk.valid.any())
    (6, True)
    """

    t: np.ndarray
    theta: np.ndarray
    R: np.ndarray
    t_min: np.ndarray
    R_min: np.ndarray
    t_mid: np.ndarray
    theta_bar: np.ndarray
    Omega_bar: np.ndarray
    theta_gyro: np.ndarray
    Omega_gyro: np.ndarray
    theta_at_min: np.ndarray
    valid: np.ndarray
    sigma: np.ndarray
    sigma_fit: np.ndarray
    c: float
    c_eff: float
    J: float

    def errors(self) -> tuple[float, float, float, float, float, float]:
        """RMS and max of: the gyroscopic theta-bar - the period means of theta; Sigma(c) - the
        minima of R; Sigma(c_eff) - the minima of R over the part of the rise not used to fit
        c_eff."""
        e_th = self.theta_bar - self.theta_gyro
        ok = self.valid & np.isfinite(self.sigma)
        e_s = self.R_min[ok] - self.sigma[ok]
        idx = np.flatnonzero(ok)
        late = idx[max(3, int(FIT_SHARE * idx.size)):]
        e_f = self.R_min[late] - self.sigma_fit[late]
        rms = lambda e: float(np.sqrt(np.mean(e**2))) if e.size else float("nan")  # noqa: E731
        mx = lambda e: float(np.max(np.abs(e))) if e.size else float("nan")  # noqa: E731
        return rms(e_th), mx(e_th), rms(e_s), mx(e_s), rms(e_f), mx(e_f)


def envelope_check(traj, start, c: float, *, dt: float) -> EnvelopeCheck:
    """Set a simulated rise of a spheroid (with dense output and its minima of R, the defaults
    of :func:`phasekit.simulate`) beside the gyroscopic solution and the envelope Sigma of the
    sliding-branch ``start`` (the paper's state, before :func:`add_nutation`) with nutation
    amplitude ``c``, sampled every ``dt``: see :class:`EnvelopeCheck`. The
    effective amplitude c_eff is fitted on the first 30% of the minima only, so that the rest of
    the rise tests the growth law Gamma(theta-bar) out of sample.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, 1.56, omega0=10.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), y0, 40.0)
    >>> ps.envelope_check(traj, y0, -0.00054, dt=0.01).J > 0
    True
    """
    model = traj.model
    body, mu = model.body, model.friction.mu
    theta0, om_bar0 = float(start[4]), float(start[2])
    J = float(jellett_constant(body, theta0, om_bar0))
    ts = np.arange(0.0, traj.t, dt)
    ys = traj.states(ts)  # the Euler chart: the paper's (U, V, Omega, Lambda, theta, n)
    theta, Omega = ys[:, 4], ys[:, 2]
    tm, Rm = traj.minima[:, 0], traj.minima[:, 1]
    t_mid, th_bar = mean_over_periods(ts, theta, tm)
    _, om_bar = mean_over_periods(ts, Omega, tm)
    th_gyro, om_gyro = gyroscopic_closed(body.a, J, theta0, mu * t_mid)
    # Sigma at the simulated mean inclination at each minimum of R
    th_at_min = np.interp(tm, t_mid, th_bar) if t_mid.size else np.full_like(tm, np.nan)
    valid = (tm >= t_mid[0]) & (tm <= t_mid[-1]) if t_mid.size else np.zeros_like(tm, bool)
    sig = np.full_like(tm, np.nan)
    sig_fit = np.full_like(tm, np.nan)
    c_eff = np.nan
    if valid.any():
        sig[valid] = reaction_envelope(body, J, theta0, th_at_min[valid], c, form="closed")
        idx = np.flatnonzero(valid)
        early = idx[: max(3, int(FIT_SHARE * idx.size))]
        th_e = th_at_min[early]
        om_e = J / (body.A * body.h(th_e)[0])
        scale = np.abs(body.h(th_e)[1] * gyroscopic_nutation_frequency(body, th_e, om_e) ** 2 * amplitude_growth_closed(body, J, theta0, th_e))
        c_eff = float(np.median((1 - Rm[early]) / scale)) * np.sign(c)
        sig_fit[valid] = reaction_envelope(body, J, theta0, th_at_min[valid], c_eff, form="closed")
    return EnvelopeCheck(ts, theta, model.normal_reaction(ys), tm, Rm, t_mid, th_bar, om_bar, th_gyro, om_gyro, th_at_min,
                         valid, sig, sig_fit, c, c_eff, J)


@dataclass(frozen=True)
class NutationCase:
    """A rise of a uniform spheroid (aspect ratio ``a``) under Coulomb friction from the sliding
    branch at inclination ``theta0`` (gyroscopic balance; ``omega0`` prolate or ``n0`` oblate,
    :func:`phasekit.gyroscopic_start`), with the nutation of amplitude ``c`` and phase ``xi``
    (:func:`add_nutation`); ``label`` names it in tables.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> case = ps.NutationCase("prolate", 1.5, np.pi / 2 - 0.01, omega0=10.5, c=-0.00054)
    >>> traj, chk = case.run(40.0, dt=0.01)
    >>> traj.status.value, chk.c == case.c
    ('jumped', True)
    """

    label: str
    a: float
    theta0: float
    omega0: float | None = None
    n0: float | None = None
    c: float = 0.0
    xi: float = 0.0

    def run(self, t_max: float, *, dt: float, mu: float = 0.1):
        """The rise (to the jump, or until it is complete, :func:`rise_complete`, or ``t_max``)
        and, sampled every ``dt``, its :func:`envelope_check`: (Trajectory, EnvelopeCheck)."""
        from ..bodies.spheroid import Spheroid
        from ..core.model import Model
        from ..core.starts import gyroscopic_start
        from ..friction.laws import Coulomb

        body = Spheroid(self.a)
        y0 = gyroscopic_start(body, self.theta0, omega0=self.omega0, n0=self.n0)
        r = simulate(Model(body, Coulomb(mu)), add_nutation(body, y0, mu, self.c, self.xi), t_max,
                     events=[rise_complete(body)])
        return r, envelope_check(r, y0, self.c, dt=dt)


def envelope_report(runs) -> tuple[list[str], dict]:
    """Rows (label, Trajectory, :class:`EnvelopeCheck`) as the lines of a text table (what the
    errors are and a header first): status, t*, the Jellett constant J, c_eff / c and the RMS
    and max of each error of :meth:`EnvelopeCheck.errors`; and, by label, those errors followed
    by c_eff / c.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> case = ps.NutationCase("prolate", 1.5, np.pi / 2 - 0.01, omega0=10.5, c=-0.00054)
    >>> lines, errors = ps.envelope_report([(case.label, *case.run(40.0, dt=0.01))])
    >>> len(lines), len(errors["prolate"])
    (3, 7)
    """
    lines = ["errors over the rise up to the jump: theta = gyroscopic theta-bar - simulated period means;"
             " S(c) = minima of R - Sigma with the nominal c; S(c_eff) = the same with c fitted on the first 30% of the"
             " rise, over the other 70%"]
    lines += [f"{'case':<28s} {'status':<9s} {'t*':>7s} {'J=AOh':>7s} {'c_eff/c':>7s} {'theta RMS':>9s} {'max':>8s} "
             f"{'S(c) RMS':>9s} {'max':>8s} {'S(c_eff) RMS':>12s} {'max':>8s}"]
    out = {}
    for label, r, d in runs:
        e = d.errors()
        out[label] = e + (d.c_eff / d.c,)
        tj = f"{r.t_jump:.2f}" if r.t_jump else "-"
        lines.append(f"{label:<28s} {r.status.value:<9s} {tj:>7s} {d.J:7.3f} {d.c_eff / d.c:7.2f} "
                     f"{e[0]:9.2e} {e[1]:8.2e} {e[2]:9.2e} {e[3]:8.2e} {e[4]:12.2e} {e[5]:8.2e}")
    return lines, out


def fit_gyroscopic_mu(ts, theta, a: float, J: float, theta0: float, mu0: float) -> tuple[float, float]:
    """The friction coefficient mu for which the gyroscopic solution (3.18) of a spheroid of
    aspect ratio ``a`` (slow time T = mu t) fits the simulated ``theta`` at ``ts`` best (least
    squares, from ``mu0``): (mu, its standard error). On a rise with bouncing: the effective
    friction mu_e.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> ts = np.linspace(0.0, 100.0, 50)
    >>> theta = pk.theory.gyroscopic_closed(1.5, 6.8, 1.5, 0.1 * ts)[0]
    >>> round(ps.fit_gyroscopic_mu(ts, theta, 1.5, 6.8, 1.5, 0.08)[0], 6)
    0.1
    """
    from scipy.optimize import curve_fit

    f = lambda t, mu: gyroscopic_closed(a, J, theta0, mu * t)[0]  # noqa: E731
    p, cov = curve_fit(f, ts, theta, p0=[mu0])
    return float(p[0]), float(np.sqrt(cov[0, 0]))


@dataclass(frozen=True)
class FlightCheck:
    """A simulated first flight beside the gap of section 4 (made by :func:`flight_check`):
    ``flight`` (the :class:`phasekit.core.Flight`), the time since lift-off ``t`` and at those times
    the gap of the flight integrated again at a tight tolerance (``numerical``), the exact
    solution (4.1)+(4.12) (``exact``) and the series (4.22) with the computed Omega* and W*
    (``series``); the largest gap by (4.23) (``gap_max_series``), its relative error against the
    flight's (``rel_error``), and the largest difference of the series from the exact curve
    relative to its maximum (``curve_error``).

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=20.0), 400.0,
    ...                    stop_at="touchdown")
    >>> chk = ps.flight_check(traj, n=50)
    >>> chk.t.shape, abs(chk.rel_error) < 0.5
    ((50,), True)
    """

    flight: object
    t: np.ndarray
    numerical: np.ndarray
    exact: np.ndarray
    series: np.ndarray
    gap_max_series: float
    rel_error: float
    curve_error: float


def flight_check(traj, *, n: int = 400, rtol: float = 1e-13) -> FlightCheck:
    """Set the first flight of ``traj`` (a run to its first touchdown) beside the theory of the
    flight, at ``n`` times over the flight; the numerical gap comes from the flight integrated
    again from the jump at ``rtol`` (:func:`phasekit.simulate` from the lift-off in the flight mode, its dense output). See :class:`FlightCheck`.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 400.0,
    ...                    stop_at="touchdown")
    >>> ps.flight_check(traj, n=50).curve_error < 0.5
    True
    """
    model, fl = traj.model, traj.flights[0]
    T = fl.t_touchdown - fl.t_liftoff
    te = fl.t_liftoff + np.linspace(0, T, n)
    # the flight again at rtol, its states (with the gap, index 8) from the dense output
    flight = simulate(model, traj.x_jump, traj.t_jump + 2 * T, t0=traj.t_jump, mode="flight", stop_at="touchdown", rtol=rtol)
    gaps = flight.segments[0].states(te)[:, 8]
    tt = te - fl.t_liftoff
    exact = gap_exact(model.body, flight_constants(model.body, traj.x_jump, fl.W_star), tt)
    series = gap_series(fl.Omega_star, fl.W_star, tt)
    gm, _ = gap_max_series(fl.Omega_star, fl.W_star)
    return FlightCheck(fl, tt, gaps, exact, series, gm, gm / fl.gap_max - 1, float(np.max(np.abs(series - exact)) / np.max(exact)))


def surface_crossings(branch: str, a: float, values, d: float = 0.01, *, bar=None) -> list:
    """The R = 0 crossing (a :class:`phasekit.scenes.scene.Crossing`, with the error in n of the jump
    surface (6.3) there) of the trajectory from each family value in ``values`` (Omega0 prolate,
    n0 oblate), started on the sliding branch at distance ``d`` of a uniform spheroid of aspect
    ratio ``a`` under Coulomb friction mu = 0.1; a start that does not jump has none. One
    trajectory at a time (crossings only: no dense output); ``bar`` (a progress bar) is updated
    after each.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [c.value for c in ps.surface_crossings("prolate", 1.5, [12.0])]
    [12.0]
    """
    from ..scenes.scene import Scene, compute_scene

    out = []
    for v in values:
        out += compute_scene(Scene(branch, a, values=(v,), seed_distance=d, show=frozenset({"crossings"}))).crossings
        if bar is not None:
            bar.update()
    return out


def loglog_fit(x, y) -> tuple[float, float, float]:
    """The slope of log y against log x (least squares), its standard error, and the
    correlation coefficient of log x and log y.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> x = np.array([1.0, 2.0, 4.0, 8.0])
    >>> [round(v, 6) for v in ps.loglog_fit(x, 3 * x**-2 * (1 + 0.01 * np.array([1, -1, 1, -1])))][::2]
    [-2.005771, -0.999983]
    """
    X, Y = np.log(x), np.log(y)
    (slope, _), cov = np.polyfit(X, Y, 1, cov=True)
    return float(slope), float(np.sqrt(cov[0, 0])), float(np.corrcoef(X, Y)[0, 1])


def crossing_trend(crossings) -> tuple:
    """Whether the error in n of the jump surface (6.3) at ``crossings`` (of one branch, from
    several start values, :func:`surface_crossings`) has a trend in the start value: the
    smallest, median and largest error, the :func:`loglog_fit` of the error against the start
    value (slope, standard error, r), and the log-log slopes of its two factors, the geometric
    error / ``Lambda*^2`` and ``|Lambda*|`` (the error is ``(A/C) h_tt Lambda*^2 / (Omega* h_theta
    sin theta* n*)``, the Lambda^2 term that (6.3) drops).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fit = ps.crossing_trend(ps.surface_crossings("prolate", 1.5, [12.0, 20.0, 30.0]))
    >>> len(fit), bool(fit[0] <= fit[1] <= fit[2])
    (8, True)
    """
    v, e, lam = (np.array([getattr(c, k) for c in crossings]) for k in ("value", "rel_error", "Lambda"))
    return (e.min(), np.median(e), e.max(), *loglog_fit(v, e), loglog_fit(v, e / lam**2)[0], loglog_fit(v, np.abs(lam))[0])


def first_flight(model, x0, t_max: float = 400.0):
    """The run from ``x0`` to its first touchdown (status "touchdown"), or until its rise is
    complete (:func:`rise_complete`: status "stopped", no jump) or ``t_max``; without dense
    output or minima of R.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> traj = ps.first_flight(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=20.0))
    >>> traj.status.value, len(traj.flights)
    ('touchdown', 1)
    """

    return simulate(model, x0, t_max, stop_at="touchdown", events=[rise_complete(model.body)], track_minima=False, dense=False)


def gap_ensemble(model, omegas, n_each: int, seed: int, *, amplitude: float = 0.05, bar=None) -> list[tuple]:
    """First flights (:func:`first_flight`) from ``n_each`` random perturbations of amplitude
    ``amplitude`` (uniform on the unit sphere of (U, V, Omega, Lambda, theta, n), drawn in
    turn from one generator seeded with ``seed``) of the horizontal steady precession at each
    Omega0 in ``omegas``. One tuple per run: (Omega0, member, status, the flight's largest gap,
    the largest gap by (4.23), W*, Omega*, stuck), NaN where the run did not touch down;
    ``bar`` (a progress bar) is updated after each run.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> recs = ps.gap_ensemble(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)), [20.0], 2, seed=1)
    >>> [(r[0], r[1], r[2]) for r in recs]
    [(20.0, 0, 'touchdown'), (20.0, 1, 'touchdown')]
    """
    from ..errors import Status
    from ..steady.precessions import horizontal_state

    rng = np.random.default_rng(seed)
    recs = []
    for om in omegas:
        for j in range(n_each):
            v = rng.standard_normal(6)
            v /= np.linalg.norm(v)
            r = first_flight(model, horizontal_state(om) + amplitude * v)
            if bar is not None:
                bar.update()
            if r.status is not Status.TOUCHDOWN:
                recs.append((om, j, r.status.value, np.nan, np.nan, np.nan, np.nan, r.stuck))
                continue
            fl = r.flights[0]
            gm, _ = gap_max_series(fl.Omega_star, fl.W_star)
            recs.append((om, j, "touchdown", fl.gap_max, gm, fl.W_star, fl.Omega_star, r.stuck))
    return recs


def gap_ensemble_report(recs, omegas) -> tuple[list[str], dict]:
    """The runs of :func:`gap_ensemble` in a few lines of text: how many did not jump, how many
    largest gaps (exact, and by (4.23)) exceed the paper's bound (4.65/Omega0)^5, and the median
    relative error of (4.23) at each Omega0; and the counts (``over_exact``, ``over_series``,
    ``n``: the runs that touched down).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> lines, counts = ps.gap_ensemble_report([(20.0, 0, "touchdown", 2e-7, 2.2e-7, 0.1, 20.0, False)], [20.0])
    >>> lines[-1], counts
    ('  Omega0 =  20.0: 0.100 (1 runs)', {'over_exact': 0, 'over_series': 0, 'n': 1})
    """
    om, exact, series = np.array([(q[0], q[3], q[4]) for q in recs], dtype=float).T
    ok = np.isfinite(exact)
    over_exact, over_series = (int(np.sum(g[ok] > (4.65 / om[ok]) ** 5)) for g in (exact, series))
    n_stuck = sum(1 for q in recs if q[2] != "touchdown")
    touch = [q for q in recs if q[2] == "touchdown"]
    lines = [f"ensemble of {len(recs)} runs ({n_stuck} without a jump: stuck or rose without losing contact).",
             f"points above the bound (4.65/Omega0)^5: {over_exact} of {int(ok.sum())} (exact Delta_max), "
             f"{over_series} of {int(ok.sum())} ((4.23) estimate, as plotted in the paper)",
             "median relative error of (4.23) against the exact maximum, by Omega0:"]
    for w in omegas:
        er = [abs(q[4] / q[3] - 1) for q in touch if q[0] == w]
        if er:
            lines.append(f"  Omega0 = {w:5.1f}: {np.median(er):.3f} ({len(er)} runs)")
    return lines, {"over_exact": over_exact, "over_series": over_series, "n": int(ok.sum())}
