"""Euler's disk to its end: a thin disk launched spinning in place, run under one dissipation law
until its face comes down, and the power laws of its tilt and precession rate against t0 - t.

On the spin-in-place manifold of a thin uniform disk (G at rest, the contact point rolling round
the rim, the spin n about the axis zero) Omega^2 = 1 / (A sin(theta)) exactly (units sqrt(g/b))
and the energy is E = (3/2) sin(theta) (M g b): Moffatt's (3/2) M g a sin(alpha) with
Omega^2 sin(alpha) = 4 g/a. A law whose power on the manifold is P(theta) then moves theta by
(3/2) cos(theta) dtheta/dt = P, a balance integrated here in closed form (:func:`quasi_static`),
which gives each law's end t0 and its exponents (docs/physics.md):

- air layer (Moffatt), P = -k Omega^2 / sin = -k / (A s^2), s = sin(theta): s^3 = (2k/A)(t0 - t),
  theta ~ (t0 - t)^(1/3), Omega ~ (t0 - t)^(-1/6);
- rolling resistance, P = -delta R |w_h| = -delta Omega s cos (R = 1): ds/dt = -(2 delta /
  (3 sqrt(A))) sqrt(s) cos, theta ~ (t0 - t)^2, Omega ~ (t0 - t)^(-1);
- spin friction, P = -mu_s |w_Z| = -mu_s Omega s^2: s^(-1/2) grows linearly in t, no finite t0
  (theta ~ t^-2, Omega ~ t): the face comes down only in infinite time;
- sliding: spinning in place needs no friction (G at rest), so the rim does not slip and nothing
  is lost.

The runs (:func:`run_disk`) use exact Coulomb friction, the Euler chart (theta stays in (0, pi))
and dense output; :func:`fit_power_law` fits log(theta) and log(Omega) against log(t0 - t).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize, special, stats

from ..bodies.edged import FLAT_ANGLE, Disk
from ..core.model import Model
from ..core.simulate import simulate
from ..friction.dissipation import AirLayer, RollingResistance, SpinFriction
from ..friction.laws import Coulomb
from ..steady.precessions import intermediate_omega, precession_state
from ..viz.output import pyplot

THIN = Disk(0.0)
#: the closed-form exponents of theta and of Omega against t0 - t (None: no finite-time end)
EXPONENTS = {"air-layer": (1 / 3, -1 / 6), "rolling-resistance": (2.0, -1.0), "spin-friction": None, "sliding": None}


def spin_in_place(theta: float) -> np.ndarray:
    """The thin disk spinning in place at ``theta``, rolling: (U, V, Omega, Lambda, theta, n) with
    U = V = Lambda = n = 0 and Omega = 1/sqrt(A sin(theta)) (the steady precession with G at rest,
    :func:`phasekit.steady.precessions.precession_state`)."""
    return precession_state(THIN, theta, omega0=intermediate_omega(THIN, theta))


def quasi_static(law: str, coef: float, theta0: float, theta: np.ndarray | float | None = None):
    """The quasi-static end of a thin disk spinning in place from ``theta0`` under one law: the
    time t(theta) at which it passes ``theta`` (default: the time t0 of theta = 0), from the energy
    balance (3/2) d sin(theta)/dt = P(theta) on the manifold (module notes). Spin friction: t to
    ``theta`` (t0 is infinite); sliding: infinite."""
    A = THIN.A
    s0 = math.sin(theta0)
    s = 0.0 if theta is None else np.sin(theta)
    if law == "air-layer":
        return A * (s0**3 - s**3) / (2 * coef)
    if law == "rolling-resistance":  # int ds / sqrt(s (1 - s^2)) = (1/2) B(s^2; 1/4, 1/2)
        def part(x):
            return 0.5 * special.betainc(0.25, 0.5, x * x) * special.beta(0.25, 0.5)
        return 3 * math.sqrt(A) / (2 * coef) * (part(s0) - part(s))
    if law == "spin-friction":
        return math.inf if theta is None else 3 * math.sqrt(A) / coef * (s**-0.5 - s0**-0.5)
    return math.inf


def run_disk(law: str, coef: float, mu: float, *, theta0: float = math.pi / 6, t_end: float = 1e4, rtol: float = 1e-10,
             max_steps: int = 2_000_000, max_wall: float = 120.0, spin: float = 0.0, flat_angle: float = FLAT_ANGLE):
    """The thin disk spinning in place at ``theta0`` (plus ``spin`` about its axis: the rim then
    slips at that speed) under exact Coulomb friction ``mu`` and one law ("air-layer" k,
    "rolling-resistance" delta, "spin-friction" mu_s, or "sliding": none), in the Euler chart with
    dense output, to face down (``flat_angle``) or ``t_end``: the trajectory."""
    laws = {"air-layer": AirLayer, "rolling-resistance": RollingResistance, "spin-friction": SpinFriction}
    friction = Coulomb(mu) if law == "sliding" else Coulomb(mu).with_dissipation(laws[law](coef))
    m = Model(THIN if flat_angle == FLAT_ANGLE else Disk(0.0, flat_angle=flat_angle), friction, "euler")
    y0 = spin_in_place(theta0) + np.array([0.0, 0.0, 0.0, 0.0, 0.0, spin])
    return simulate(m, y0, t_end, rtol=rtol, stop_at="none", dense=True, max_steps=max_steps,
                    max_wall=max_wall)


def fit_power_law(tau: np.ndarray, y: np.ndarray) -> dict:
    """log|y| = p log(tau) + c by least squares: the exponent p, its 95% confidence half-width
    (Student t with the regression's standard error) and r^2."""
    fit = stats.linregress(np.log(tau), np.log(np.abs(y)))
    half = stats.t.ppf(0.975, len(tau) - 2) * fit.stderr
    return {"exponent": float(fit.slope), "ci95": float(half), "r2": float(fit.rvalue**2), "n": int(len(tau))}


def end_fit(t: np.ndarray, theta: np.ndarray, p_guess: float, t_hi: float) -> float:
    """t0 extrapolated from the run: the end that makes log(theta) straightest against log(t0 - t)
    over the samples ``t``, searched in (max t, max t + ``t_hi``) (theta^(1/p) linear in t gives
    the start of the search)."""
    def bend(t0):
        x = np.log(t0 - t)
        return stats.linregress(x, np.log(theta)).stderr

    lin = stats.linregress(t, theta ** (1 / p_guess))
    guess = -lin.intercept / lin.slope
    lo = t.max() + 1e-9 * max(1.0, t.max())
    hi = t.max() + t_hi
    res = optimize.minimize_scalar(bend, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10 * hi})
    return float(res.x if bend(res.x) <= bend(min(max(guess, lo), hi)) else min(max(guess, lo), hi))


def _finite(x: float) -> float | None:
    """None for an infinite time (strict JSON has no Infinity)."""
    return float(x) if math.isfinite(x) else None


#: |F|/R levels whose first crossing a report gives (a table's mu is ~0.1-1)
FRICTION_LEVELS = (0.3, 1.0)


def _friction_ratio(traj) -> dict:
    """max |F|/R, the first time it exceeds each of FRICTION_LEVELS, and min R, over samples
    uniform in t and log-spaced towards the end (where the end's rates grow)."""
    span = traj.t - traj.t0
    ts = np.unique(np.concatenate([np.linspace(traj.t0, traj.t, 4001), traj.t - np.geomspace(1e-7 * span, span, 2000)]))
    m, s, X = traj.model, traj.sample(ts), traj.states(ts)
    ratio, R = np.empty(len(ts)), np.empty(len(ts))
    for mode in sorted(set(s["mode"])):
        sel = np.asarray(s["mode"] == mode)
        F = np.asarray(m.evaluate("friction", X[sel], mode), dtype=float).reshape(-1, 2)
        R[sel] = np.asarray(m.evaluate("R", X[sel], mode), dtype=float).reshape(-1)
        ratio[sel] = np.hypot(F[:, 0], F[:, 1]) / R[sel]
    first = {f"{lv:g}": (float(ts[np.argmax(ratio > lv)]) if np.any(ratio > lv) else None) for lv in FRICTION_LEVELS}
    return {"max_friction_ratio": float(ratio.max()), "t_max_friction_ratio": float(ts[np.argmax(ratio)]),
            "t_friction_ratio_above": first, "R_min": float(R.min()), "t_R_min": float(ts[np.argmin(R)])}


def disk_report(traj, law: str, coef: float, mu: float, *, window: tuple[float, float], n_fit: int = 60) -> dict:
    """The numbers of one run: its end (the face-down time and t0 extrapolated), the exponents of
    theta and of Omega against t0 - t over ``window`` (t0 - t between the two, as fractions of
    t0), the quasi-static t0, the largest |F|/R and its time, the lowest R, and the balance."""
    theta0 = float(traj.sample([traj.t0])["theta"].iloc[0])
    ends = [e for e in traj.events if e.name == "face down"]
    t_face = ends[0].t if ends else None
    budget = traj.energy_budget()
    slips = [e.t for e in traj.events if e.name == "slip" and e.t > traj.t0]
    sticks = [e.t for e in traj.events if e.name == "stick" and e.t > traj.t0]
    pivots = [e.t for e in traj.events if e.name == "pivot stick"]
    end = traj.sample([traj.t])
    out = {"law": law, "coefficient": coef, "mu": mu, "theta0": theta0, "status": traj.status.value,
           "reason": traj.reason, "t_end": traj.t, "t_face_down": t_face, "t0_quasi_static": _finite(quasi_static(law, coef, theta0)),
           **_friction_ratio(traj), "t_first_slip": slips[0] if slips else None,
           "t_first_stick": sticks[0] if sticks else None, "t_pivot_stick": pivots[0] if pivots else None,
           "theta_end": float(end["theta"].iloc[0]), "Omega_end": float(end["Omega"].iloc[0]),
           "energy_start": budget.energy_start, "energy_end": budget.energy_end,
           "residual": budget.residual / budget.energy_start,
           "residual_max": budget.residual_max / budget.energy_start, "n_steps": traj.n_steps, "n_events": len(traj.events)}
    expected = EXPONENTS[law]
    if expected is None or t_face is None:
        return out
    t_lo = t_face * (1 - window[1])  # the window in t, from t0 = t_face
    tt = t_face - t_face * np.logspace(math.log10(window[0]), math.log10(window[1]), n_fit)
    s = traj.sample(np.sort(tt))
    t, th, om = s["t"].to_numpy(), s["theta"].to_numpy(), s["Omega"].to_numpy()
    t0 = end_fit(t, th, expected[0], t_face - t_lo)
    # the closed form's own exponents over the same range of theta (cos(theta) bends it at 30 deg)
    grid = np.linspace(th.min(), th.max(), n_fit)
    tau = np.array([quasi_static(law, coef, g) for g in grid])
    out.update(t0_fit=t0, window=list(window), fit_window_tau=[float((t0 - t).min()), float((t0 - t).max())], fit_theta=fit_power_law(t0 - t, th), fit_omega=fit_power_law(t0 - t, om),
               fit_theta_face=fit_power_law(t_face - t, th), fit_omega_face=fit_power_law(t_face - t, om),
               expected=list(expected), quasi_static_theta=fit_power_law(tau, grid),
               quasi_static_omega=fit_power_law(tau, 1 / np.sqrt(THIN.A * np.sin(grid))),
               decades=float(np.log10((t0 - t).max() / (t0 - t).min())))
    return out


def end_curves(traj, t0: float, n: int = 300) -> dict:
    """theta and Omega at ``n`` instants log-spaced in t0 - t (from 1e-5 t0 to the start, inside
    the run), and theta and the energy on a uniform grid of t (for the figure)."""
    tau = np.logspace(math.log10(1e-5 * t0), math.log10(t0 - traj.t0), n)
    t = np.sort(t0 - tau)
    t = t[(t >= traj.t0) & (t <= traj.t)]
    s = traj.sample(t)
    u = traj.sample(traj.t0 + np.concatenate([[0.0], np.geomspace(1e-3 * (traj.t - traj.t0), traj.t - traj.t0, 600)]))
    return {"tau": t0 - s["t"].to_numpy(), "theta": s["theta"].to_numpy(), "Omega": s["Omega"].to_numpy(),
            "t_lin": u["t"].to_numpy(), "theta_lin": u["theta"].to_numpy(), "energy_lin": u["energy"].to_numpy()}


def plot_exponents(curves: dict, reports: dict, *, title: str):
    """Log-log theta and Omega against t0 - t (t0 extrapolated) for the laws with a finite-time
    end, with the fitted lines over their windows (black) and the closed-form slope (dotted), and
    the energy against t for every law."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    colours = {"air-layer": "C0", "rolling-resistance": "C3", "spin-friction": "C2", "sliding": "C7"}
    for law, rep in reports.items():
        c, cur = colours[law], curves[law]
        axes[2].plot(cur["t_lin"], cur["energy_lin"] / rep["energy_start"], color=c, label=f"{law} ({rep['coefficient']:g})"
                     if law != "sliding" else f"sliding (mu {rep['mu']:g})")
        if "fit_theta" not in rep:
            continue
        order = np.argsort(cur["tau"])
        for ax, key, fit, p in ((axes[0], "theta", rep["fit_theta"], rep["expected"][0]),
                                (axes[1], "Omega", rep["fit_omega"], rep["expected"][1])):
            tau_c, y_c = cur["tau"][order], np.abs(cur[key][order])
            ax.loglog(tau_c, y_c, color=c, lw=1.2, label=f"{law} ({rep['coefficient']:g}): fitted {fit['exponent']:.3f} "
                      f"+- {fit['ci95']:.1g}, closed form {p:.4g}")
            lo, hi = rep["fit_window_tau"]
            tau = np.logspace(math.log10(lo), math.log10(hi), 20)
            mid = math.sqrt(lo * hi)
            y_mid = float(np.exp(np.interp(math.log(mid), np.log(tau_c), np.log(y_c))))
            ax.loglog(tau, y_mid * (tau / mid) ** fit["exponent"], color="k", lw=2.2, alpha=0.5)
            ax.loglog(tau, y_mid * (tau / mid) ** p, color="k", lw=0.8, ls=":")
    axes[0].set(xlabel="t0 - t (sqrt(b/g))", ylabel="theta (rad)", title="tilt against t0 - t")
    axes[1].set(xlabel="t0 - t (sqrt(b/g))", ylabel="Omega (sqrt(g/b))", title="precession rate against t0 - t")
    axes[2].set(xlabel="t (sqrt(b/g))", ylabel="energy / energy at the start", title="energy: every law",
                ylim=(0, 1.05))
    axes[2].set_xscale("symlog", linthresh=1.0)
    axes[2].set_xlim(left=0.0)
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="lower left" if ax is axes[2] else "best")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig
