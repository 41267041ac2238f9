"""How long a body spins: runs under sliding friction and the dissipation laws
(:mod:`phasekit.friction.dissipation`) until the body rests, with their times in seconds, their
energy budgets and spin-down curves, the closed forms of the laws on a uniform sphere, and the
study's figures.

A run (:func:`spin_down_run`) is one body, one law and one start in the vector chart (regular at
theta = 0 and pi), through flights and impacts (restitution 0), to ``t_end`` or rest; it is cut
by its step and wall budgets (status "failed" and the reason, never a hang). Its row
(:class:`SpinDownRun`) holds the times of the first stick, of the rise (theta first below
``rise_deg``), of the turn over (theta first above ``over_deg``), of the spin about the vertical
stopping (the first "pivot stick") and of rest, the energy each law took and the residual of the
balance; its curve (:class:`SpinCurvePoint` rows) theta, the spin about the vertical w_Z, |w| and
the energy on a time grid. Times in seconds and rates in rev/s through the run's
:class:`phasekit.Scale`; energies in M g b.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..bodies.spheroid import Spheroid
from ..core.hybrid import Event, Mode
from ..core.model import Model
from ..core.simulate import simulate
from ..core.starts import to_chart
from ..friction.contensou import Contensou
from ..friction.dissipation import AirDrag, RollingResistance, SpinFriction
from ..friction.laws import Coulomb, RegularisedCoulomb
from ..viz.output import pyplot

#: the energy budget's law names -> the row's column
LAW_NAMES = {"sliding friction": "diss_sliding", "spin-friction": "diss_spin", "rolling-resistance": "diss_rolling",
             "air-drag": "diss_air", "patch": "diss_sliding"}  # over a patch, sliding and pivoting are one friction


@dataclass(frozen=True)
class SpinDownRun:
    """One run of :func:`spin_down_run` (times in s, angles in degrees, spins in rev/s, energies
    in M g b; a time is None when it did not happen)."""

    key: str
    body: str
    case: str
    law: str
    mu_s_mm: float
    delta_mm: float
    t_end_s: float
    rtol: float
    status: str
    reason: str
    note: str
    t_run_s: float
    theta0_deg: float
    theta_end_deg: float
    theta_min_deg: float
    theta_max_deg: float
    t_first_stick_s: float | None
    theta_range_after_stick_deg: float | None
    t_rise_s: float | None
    t_over_s: float | None
    t_spin_stop_s: float | None
    t_rest_s: float | None
    spin0_rev_s: float
    spin_end_rev_s: float
    energy_start: float
    energy_end: float
    diss_sliding: float
    diss_spin: float
    diss_rolling: float
    diss_air: float
    at_events: float
    residual: float
    n_steps: int
    n_stick: int
    n_liftoff: int
    wall_s: float


@dataclass(frozen=True)
class SpinCurvePoint:
    """One sample of a run's curve: theta (deg), the spin about the vertical w_Z and the angular
    speed |w| (rev/s), the energy (M g b) and the mode at time t_s (s)."""

    key: str
    run: str
    t_s: float
    theta_deg: float
    spin_rev_s: float
    omega_rev_s: float
    energy: float
    mode: str


def spin_down_law(scale, sliding: str, mu: float, *, eps: float = 1e-3, mu_s: str | None = None,
                  delta: str | None = None, air: dict | None = None, patch: str | None = None):
    """A sliding law ("coulomb" exact, or "regularised" with ``eps``; exact Coulomb over a contact
    patch of radius ``patch``, a length, :class:`phasekit.Contensou`) carrying the dissipation
    laws given in real units through ``scale``: spin friction ``mu_s`` and rolling resistance
    ``delta`` as lengths ("0.2 mm"), air drag as a dict of :class:`phasekit.AirDrag`'s
    coefficients in real units ({"rotation_quadratic": "1e-9 N*m*s**2"}; the Scale needs a mass)."""
    if patch is not None:
        law = Contensou(mu, scale.dimensionless(patch, "patch"))
    else:
        law = Coulomb(mu) if sliding == "coulomb" else RegularisedCoulomb(mu, eps)
    laws = []
    if mu_s is not None:
        laws.append(SpinFriction(scale.dimensionless(mu_s, "spin_friction")))
    if delta is not None:
        laws.append(RollingResistance(scale.dimensionless(delta, "rolling_resistance")))
    if air:
        kinds = {"rotation": "air_drag", "rotation_quadratic": "air_drag_quadratic", "translation": "air_drag_force",
                 "translation_quadratic": "air_drag_force_quadratic"}
        laws.append(AirDrag(**{k: scale.dimensionless(v, kinds[k]) for k, v in air.items()}))
    return law.with_dissipation(*laws) if laws else law


def _theta(X: np.ndarray) -> np.ndarray:
    return np.arctan2(np.hypot(X[:, 0], X[:, 1]), X[:, 2])


def _curve(traj, ts: np.ndarray):
    """theta, w_Z, |w|, the energy and the mode at the sorted times ``ts``, segment by segment
    (flight states carry the gap, which the energy needs)."""
    model, rows = traj.model, []
    for i, seg in enumerate(traj.segments):
        last = i == len(traj.segments) - 1
        sel = ts[(ts >= seg.t0) & ((ts < seg.t1) | (last & (ts <= seg.t1)))]
        if sel.size == 0 or not seg.dense:
            continue
        X = seg.states(sel)
        energy = model.function("energy", Mode.FLIGHT if seg.mode is Mode.FLIGHT else None)
        E = np.array([float(energy(x, model.p)) for x in X])
        w = X[:, 3:6]
        rows.append((sel, _theta(X), w[:, 2], np.linalg.norm(w, axis=1), E, [seg.mode.value] * sel.size))
    return [np.concatenate([r[j] for r in rows]) for j in range(5)] + [sum((r[5] for r in rows), [])]


def _first(traj, name: str) -> float | None:
    ev = traj.events_named(name)
    return float(ev[0].t) if ev else None


def spin_down_run(key: str, body_name: str, case: str, body, law, y0, scale, t_end_s: float, *, rtol: float = 1e-10,
                  rise_deg: float = 10.0, over_deg: float = 90.0, max_wall: float = 60.0, max_steps: int = 100_000,
                  n_curve: int = 150, early_s: float = 5.0) -> list:
    """Simulate ``body`` under ``law`` (with its dissipation laws) from the paper's state ``y0``
    in the vector chart to ``t_end_s`` seconds or rest, and measure it: ``[SpinDownRun,
    *SpinCurvePoint]`` keyed ``key`` (the curve on ``n_curve`` times over the run and as many over
    its first ``early_s`` seconds).

    Examples
    --------
    >>> import math, phasekit as pk, phasekit.studies as ps
    >>> sc, top = pk.Scale("15 mm"), pk.EccentricSphere(0.3, A=0.38, C=0.4)
    >>> y0 = pk.core.vertical_spin_start(0.1, sc.dimensionless("30 rev/s"))
    >>> law = ps.spin_down_law(sc, "coulomb", 0.3, mu_s="0.2 mm", delta="0.05 mm")
    >>> run = ps.spin_down_run("top", "tippe-top", "both", top, law, y0, sc, 60.0, n_curve=10)[0]
    >>> run.status, run.t_over_s < 1.0 < run.t_rest_s < 60.0, abs(run.residual) < 1e-8
    ('rest', True, True)
    """
    t0 = time.perf_counter()
    seconds = float(scale.unit("time").to("s").magnitude)
    rate = float(scale.unit("rate").to("rev/s").magnitude)
    events = [Event("theta", math.radians(rise_deg), direction=-1, name="rise", terminal=False),
              Event("theta", math.radians(over_deg), direction=+1, name="over", terminal=False)]
    x0 = to_chart("vector", np.asarray(y0, dtype=float))
    traj = simulate(Model(body, law, "vector"), x0, t_end_s / seconds, stop_at="rest", rtol=rtol, events=events,
                    max_wall=max_wall, max_steps=max_steps, track_minima=False, progress=False)
    span = traj.t - traj.t0
    ts = np.unique(np.concatenate([np.linspace(traj.t0, traj.t, n_curve),
                                   np.linspace(traj.t0, traj.t0 + min(span, early_s / seconds), n_curve)]))
    t, theta, wz, wn, E, modes = _curve(traj, ts)
    budget = traj.energy_budget()
    diss = dict.fromkeys(LAW_NAMES.values(), 0.0)
    for name, value in zip(budget.laws, budget.dissipated):
        diss[LAW_NAMES[name]] += float(value)
    note = (traj.to_dict().get("rests_on") or "") if not law.dissipation else ""
    values = {d.name: d.values[0] for d in law.dissipation}
    mm = float(scale.unit("length").to("mm").magnitude)
    stop = [e.t for e in traj.events if e.name == "pivot stick"]
    run = SpinDownRun(
        key, body_name, case, law.describe(), values.get("spin-friction", 0.0) * mm,
        values.get("rolling-resistance", 0.0) * mm, t_end_s, rtol, traj.status.value, traj.reason or "", note,
        traj.t * seconds, math.degrees(theta[0]), math.degrees(theta[-1]),
        math.degrees(theta.min()), math.degrees(theta.max()), _s(_first(traj, "stick"), seconds), _range_after(t, theta, traj),
        _s(_first(traj, "rise"), seconds), _s(_first(traj, "over"), seconds), _s(stop[0] if stop else None, seconds),
        _s(_first(traj, "rest"), seconds), float(wz[0]) * rate, float(wz[-1]) * rate,
        budget.energy_start, budget.energy_end, **diss, at_events=budget.at_events, residual=budget.residual,
        n_steps=int(traj.n_steps), n_stick=len(traj.events_named("stick")), n_liftoff=len(traj.events_named("lift-off")),
        wall_s=time.perf_counter() - t0)
    curve = [SpinCurvePoint(f"{key}|{i:04d}", key, *(_digits(v) for v in (float(t[i]) * seconds, math.degrees(theta[i]),
                                                                           float(wz[i]) * rate, float(wn[i]) * rate, E[i])),
                            modes[i]) for i in range(t.size)]
    return [run, *curve]


def _range_after(t, theta, traj) -> float | None:
    """How far theta moved (max - min, degrees) over the curve after the first stick: 0 for pure
    rolling without dissipation up to its small nutation."""
    stick = _first(traj, "stick")
    after = theta[t > stick] if stick is not None else theta[:0]
    return math.degrees(float(np.ptp(after))) if after.size else None


def _digits(v) -> float:
    """A curve's value to 12 significant digits (drawn, not computed with: the file stays small)."""
    return float(f"{float(v):.12g}")


def _s(t, seconds: float) -> float | None:
    return None if t is None else float(t) * seconds


def sphere_checks(rtol: float = 1e-10) -> list[dict]:
    """The closed forms of the laws on a uniform sphere (radius 1, C = 2/5, g = 1), each against
    its run (vector chart, exact Coulomb mu = 0.5): spinning in place at n0 = 3 with spin friction
    mu_s = 0.02 rests at C n0 / mu_s; rolling straight at v0 = 0.5 with rolling resistance
    delta = 0.01 decelerates at (5/7) delta and rests at 7 v0 / (5 delta); spinning in place with
    linear air drag k1 = 0.01 spins at n0 exp(-k1 t / C) at t = 40. Each row: the law, the
    quantity, the closed form, the run's value, their relative difference and the run's energy
    residual.

    Examples
    --------
    >>> import phasekit.studies as ps
    >>> all(c["rel_err"] < 1e-8 for c in ps.sphere_checks())
    True
    """
    sphere, C, out = Spheroid(1.0), 0.4, []
    spin = np.array([0, 0, 1, 0, 0, 3.0, 0, 0])
    cases = [("spin friction mu_s = 0.02, n0 = 3", SpinFriction(0.02), spin, 200.0, "t_rest = C n0 / mu_s", C * 3.0 / 0.02),
             ("rolling resistance delta = 0.01, v0 = 0.5", RollingResistance(0.01), np.array([0, 0, 1, 0, 0.5, 0, 0.5, 0]),
              200.0, "t_rest = 7 v0 / (5 delta)", 7 * 0.5 / (5 * 0.01)),
             ("air drag k1 = 0.01, n0 = 3", AirDrag(rotation=0.01), spin, 40.0, "n(40) = n0 exp(-k1 t / C)",
              3.0 * math.exp(-0.01 * 40.0 / C))]
    for name, d, x0, t_end, what, exact in cases:
        traj = simulate(Model(sphere, Coulomb(0.5).with_dissipation(d), "vector"), x0, t_end, stop_at="rest", rtol=rtol,
                        progress=False, track_minima=False)
        got = traj.t if traj.status.value == "rest" else float(traj.x[5])
        b = traj.energy_budget()
        out.append({"law": name, "quantity": what, "closed_form": exact, "phasekit": got,
                    "rel_err": abs(got - exact) / exact, "status": traj.status.value,
                    "energy_residual": b.residual / b.energy_start})
    return out


# -- figures -----------------------------------------------------------------------------------

#: line colours and styles of the runs of a figure (ten colours, then the next style)
LINESTYLES = ("-", "--", "-.", ":")
PANELS = {"theta": ("theta_deg", r"$\theta$ (deg)"), "spin": ("spin_rev_s", r"$\omega_Z$ (rev/s)"),
          "energy": ("energy", r"$E$ ($M g b$)")}


def _line(i: int) -> dict:
    import matplotlib

    return {"color": matplotlib.colormaps["tab10"](i % 10), "ls": LINESTYLES[(i // 10) % len(LINESTYLES)]}


def plot_spin_down(runs, curves, *, title: str, panels=("theta", "spin", "energy"), early_s: float | None = None):
    """A column of panels against time t in s, one line per run (labelled with its ``case``):
    theta in degrees, the spin about the vertical w_Z in rev/s, the energy E in M g b; a dot where
    the run rested, a cross where it failed. ``early_s`` adds a first column on [0, early_s]."""
    plt = pyplot()
    cols = 2 if early_s else 1
    fig, axes = plt.subplots(len(panels), cols, figsize=(6.2 * cols, 2.5 * len(panels) + 1.2), squeeze=False,
                             sharex="col")
    for i, run in enumerate(runs):
        c, style = curves[run.key], _line(i)
        end = {"rest": "o", "failed": "x"}.get(run.status)
        for j, p in enumerate(panels):
            y = c[PANELS[p][0]]
            for k in range(cols):
                axes[j, k].plot(c["t_s"], y, lw=1.2, label=run.case if j == 0 else None, **style)
                if end:
                    axes[j, k].plot(c["t_s"][-1], y[-1], end, color=style["color"], ms=6, mec="k" if end == "o" else None)
    for j, p in enumerate(panels):
        for ax in axes[j]:
            ax.set_ylabel(PANELS[p][1])
            ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel(r"$t$ (s)")
    if early_s:
        axes[0, 0].set_xlim(0, early_s)
        axes[0, 0].set_title(f"first {early_s:g} s", fontsize=9)
        axes[0, 1].set_title("whole run", fontsize=9)
    # beside the panels: with many runs a legend inside would cover the curves
    axes[0, -1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def _times(rows, attr: str) -> list:
    return [np.nan if getattr(r, attr) is None else getattr(r, attr) for r in rows]


def plot_rest_times(top_rows: dict, egg_rows: dict, *, title: str):
    """Times t (s) against a coefficient (mm), log-log. Left, the tippe top's time to rest and the
    time its spin about the vertical stopped, against mu_s (``top_rows["spin"]``) and against
    delta (``top_rows["delta"]``); right, when the egg's spin about the vertical stopped
    (``egg_rows["spin"]``) beside the estimate ``egg_rows["estimate"]`` / mu_s (s mm)."""
    plt = pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for rows, attr, marker, against in ((top_rows["spin"], "mu_s_mm", "o", r"$\mu_s$"),
                                        (top_rows["delta"], "delta_mm", "s", r"$\delta$")):
        x = [getattr(r, attr) for r in rows]
        a.plot(x, _times(rows, "t_rest_s"), marker + "-", label=f"rest, against {against}")
        a.plot(x, _times(rows, "t_spin_stop_s"), marker + "--", mfc="none",
               label=f"spin about the vertical stopped, against {against}")
    a.set_xlabel(r"coefficient $\mu_s$ or $\delta$ (mm)")
    a.set_title("tippe top", fontsize=9)
    rows = egg_rows["spin"]
    x = [r.mu_s_mm for r in rows]
    b.plot(x, _times(rows, "t_spin_stop_s"), "o", ms=7, label="phasekit: spin about the vertical stopped")
    xx = np.geomspace(min(x) / 1.5, max(x) * 1.5, 50)
    b.plot(xx, egg_rows["estimate"] / xx, "k--", lw=1, label=r"$A\,\Omega_0/(\mu_s M g)$")
    b.set_xlabel(r"spin friction $\mu_s$ (mm)")
    b.set_title("egg: exact Coulomb + spin friction", fontsize=9)
    for ax in (a, b):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel(r"$t$ (s)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
        _plain(ax)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def _plain(ax) -> None:
    """Log axes labelled 0.1, 0.2, 0.5, 1, ... rather than 10^-1, ..., without minor labels."""
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(NullFormatter())
