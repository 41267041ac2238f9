"""The paper's figures of a rise, drawn with matplotlib: R(t) to the jump, the envelope Sigma
(Fig. 2), a simulated rise against the mean-state theory (Figs. 3, 4), the gap of a flight and
its maximum over Omega0 (Fig. 5) and the effective friction of a bouncing rise; and the jump
surface with trajectories (Fig. 6a), rendered off-screen with PyVista.

The panel functions draw on the axes they are given and return the artists; those that make a
whole figure return it (save it with :func:`phasekit.viz.save_figure`). Units: mass M, length
b, time sqrt(b/g).
"""

from __future__ import annotations

import contextlib
from pathlib import Path

import numpy as np

from ..viz.output import pyplot

TIME = r"time $t$ (units $\sqrt{b/g}$)"
OMEGA0 = r"initial precession rate $\Omega_0$ (units $\sqrt{g/b}$)"


def plot_reaction_to_jump(traj, *, dt: float = 0.005, title: str = ""):
    """A figure of two panels over a run to its first lift-off (dense output and the minima of
    R kept, the defaults of :func:`phasekit.simulate`): the normal reaction R(t), sampled every
    ``dt``, with its located minima and the lift-off time t_*; and the inclination theta(t).

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> fig = ps.plot_reaction_to_jump(traj, title="the standard workload")
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    samples = traj.sample(np.arange(traj.t0, traj.t_jump, dt))
    minima = traj.minima
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(samples["t"], samples["R"], lw=0.5, color="k", label=r"$R(t)$, sampled from the dense output")
    ax1.plot(minima[:, 0], minima[:, 1], ".", ms=2, color="C3", label="located minima of R")
    ax1.axhline(0.0, color="0.6", lw=0.8)
    ax1.axvline(traj.t_jump, color="C0", ls="--", lw=0.8, label=f"lift-off $t_*$ = {traj.t_jump:.6f}")
    ax1.set_ylabel(r"normal reaction $R$ (units $Mg$)")
    ax1.legend(loc="lower left", fontsize=8)
    ax2.plot(samples["t"], samples["theta"], color="k", lw=0.8)
    ax2.set_ylabel(r"inclination $\theta$ (rad)")
    ax2.set_xlabel(TIME)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def plot_envelope(ax, theta, sigma, *, label=None, **style) -> list:
    """The envelope Sigma of the minima of R (:func:`phasekit.theory.reaction_envelope`) against the mean
    inclination ``theta`` (in the order of the rise): solid up to its first zero (the jump,
    :func:`phasekit.studies.sigma_zero`), dashed beyond, where it no longer applies. ``style``
    goes to both lines, ``label`` to the solid one.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> theta = np.linspace(1.5, 0.02, 300)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_envelope(ax, theta, pk.theory.reaction_envelope(pk.Spheroid(1.5), 8.45, 1.5, theta, -0.00054), label="J = 8.45"))
    2
    """
    from .paper_checks import sigma_zero

    z = sigma_zero(theta, sigma)
    if z is None:
        return ax.plot(theta, sigma, label=label, **style)
    before = theta >= z if theta[0] >= theta[-1] else theta <= z
    return ax.plot(theta[before], sigma[before], label=label, **style) + ax.plot(theta[~before], sigma[~before], ls="--", **style)


def plot_mean_state(ax, check, *, title: str = "") -> list:
    """A simulated rise against the gyroscopic solution (3.18) (a
    :class:`phasekit.studies.EnvelopeCheck`): theta(t), its means over each fast period and the
    gyroscopic theta-bar; on a second y axis the period means of Omega and Omega-bar = J/(Ah).
    Returns both axes.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, 1.56, omega0=10.5)
    >>> chk = ps.envelope_check(pk.simulate(pk.Model(body, pk.Coulomb(0.1)), y0, 40.0), y0, -0.00054, dt=0.01)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_mean_state(ax, chk, title="prolate"))
    2
    """
    ax.plot(check.t, check.theta, color="0.6", lw=0.5, label=r"$\theta$ simulated")
    ax.plot(check.t_mid, check.theta_bar, color="k", lw=1.0, label=r"$\bar\theta$ (period means)")
    ax.plot(check.t_mid, check.theta_gyro, color="C3", lw=2, ls="--", label=r"$\bar\theta$ gyroscopic (3.18)")
    ax.set_ylabel(r"$\theta$ (rad)")
    ax.set_xlabel(TIME)
    ax2 = ax.twinx()
    ax2.plot(check.t_mid, check.Omega_bar, color="C0", lw=1.0, label=r"$\bar\Omega$ simulated")
    ax2.plot(check.t_mid, check.Omega_gyro, color="C0", lw=2, ls=":", label=r"$\bar\Omega = J/(Ah)$")
    ax2.set_ylabel(r"$\Omega$ (units $\sqrt{g/b}$)", color="C0")
    ax.set_title(title + f", J = A$\\Omega$h = {check.J:.3f}", fontsize=9)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="center left")
    return [ax, ax2]


def plot_minima_envelope(ax, check, *, title: str = "") -> list:
    """R(t) of a simulated rise with its located minima, and the envelope Sigma (3.64) at the
    simulated mean inclination with the nominal amplitude c and with c_eff (a
    :class:`phasekit.studies.EnvelopeCheck`). Returns the lines.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, 1.56, omega0=10.5)
    >>> chk = ps.envelope_check(pk.simulate(pk.Model(body, pk.Coulomb(0.1)), y0, 40.0), y0, -0.00054, dt=0.01)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_minima_envelope(ax, chk, title="prolate"))
    4
    """
    ok = np.isfinite(check.sigma)
    lines = ax.plot(check.t, check.R, color="0.5", lw=0.4, label="R simulated")
    lines += ax.plot(check.t_min, check.R_min, ".", ms=2, color="k", label="minima of R")
    lines += ax.plot(check.t_min[ok], check.sigma[ok], color="C3", lw=2, label=fr"$\Sigma$ (3.64), $c={check.c:g}$")
    lines += ax.plot(check.t_min[ok], check.sigma_fit[ok], color="C1", lw=1.5, ls="--",
                     label=fr"$\Sigma$ with $c_{{eff}}={check.c_eff:.2g}$ (fit: first 30%)")
    ax.set_title(title, fontsize=9)
    ax.set_ylabel(r"$R$ (units $Mg$)")
    ax.set_ylim(-0.1, 2.2)
    ax.legend(fontsize=7, loc="upper left")
    return lines


def plot_gap_flight(ax, t, numerical, exact, series, *, title: str = "") -> list:
    """The gap Delta during a flight against the time since lift-off ``t``: the numerical
    flight, the exact solution (4.1)+(4.12) and the series (4.22) (drawn where positive).

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> t = np.linspace(0.0, 0.01, 50)
    >>> gap = pk.theory.gap_series(11.0, 0.005, t)
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_gap_flight(ax, t, gap, gap, gap, title="(a)"))
    3
    """
    lines = ax.plot(t, numerical, color="k", lw=1.8, label="numerical flight")
    lines += ax.plot(t, exact, color="C2", lw=1, ls=":", label="exact (4.1)+(4.12)")
    lines += ax.plot(t, np.maximum(series, 0), color="C3", ls="--", label=r"series (4.22)")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(r"time since lift-off $t-t_*$ (units $\sqrt{b/g}$)")
    ax.set_ylabel(r"gap $\Delta$ (units $b$)")
    ax.legend(fontsize=8)
    return lines


def plot_gap_maxima(ax, omega0, exact, series, omega_range, *, title: str = "") -> list:
    """The maximum gap of first flights against Omega0: the exact maximum (black dots, shifted
    left by 0.3) and (4.23) (red crosses, shifted right), with the paper's bound
    (4.65/Omega0)^5 over ``omega_range`` = (first, last).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fig, ax = pk.viz.pyplot().subplots()
    >>> len(ps.plot_gap_maxima(ax, [10.0, 20.0], [1e-3, 3e-5], [1.1e-3, 3e-5], (10.0, 20.0)))
    3
    """
    omega0 = np.asarray(omega0, dtype=float)
    lines = ax.semilogy(omega0 - 0.3, exact, "k.", ms=4, label=r"$\Delta_{max}$ exact (numerical flight)")
    lines += ax.semilogy(omega0 + 0.3, series, "C3x", ms=4, label=r"$\Delta_{max}$ from (4.23)")
    oo = np.linspace(omega_range[0], omega_range[-1], 200)
    lines += ax.semilogy(oo, (4.65 / oo) ** 5, "b-", lw=1.2, label=r"bound $(4.65/\Omega_0)^5$")
    ax.set_xlabel(OMEGA0)
    ax.set_ylabel(r"maximum gap $\Delta_{max}$ (units $b$)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    return lines


def _error(r: dict, mu: float) -> float:
    """The error bar of mu_e / mu: the fit's standard error and the method's bias combined."""
    return np.hypot(r["s_fit"] / mu, 0.0 if np.isnan(r["bias"]) else r["bias"])


def plot_effective_friction(rows, control: dict, mu: float, *, title: str = ""):
    """A figure of a bouncing rise's effective friction: (a) mu_e / mu against the restitution
    e, one line per Omega0, with error bars (the fit's standard error and the method's bias)
    and the fit on a rise without a jump (``control``) as a dashed line; (b) the naive estimate
    1 - (the fraction of the rise spent in flight). ``rows``: mappings with keys ``omega0``,
    ``e``, ``mu_e``, ``s_fit``, ``bias`` and ``flight_fraction``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> rows = [dict(omega0=11.0, e=e, mu_e=0.099, s_fit=1e-4, bias=1e-3, flight_fraction=0.1) for e in (0.0, 0.6)]
    >>> fig = ps.plot_effective_friction(rows, dict(omega0=9.0, e=0.5, mu_e=0.1), 0.1)
    >>> len(fig.axes)
    2
    """
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))
    omegas = list(dict.fromkeys(r["omega0"] for r in rows))
    for k, om in enumerate(omegas):
        sub = [r for r in rows if r["omega0"] == om]
        x = np.array([r["e"] for r in sub]) + 0.012 * (k - len(omegas) / 2)
        ax.errorbar(x, [r["mu_e"] / mu for r in sub], yerr=[_error(r, mu) for r in sub], fmt="o-", ms=4, capsize=3,
                    color=f"C{k}", label=fr"$\Omega_0={om:g}$")
        bx.plot(x, [1 - r["flight_fraction"] for r in sub], "o:", ms=4, color=f"C{k}", label=fr"$\Omega_0={om:g}$")
    ax.axhline(control["mu_e"] / mu, color="0.5", ls="--", lw=1,
               label=fr"no jump ($\Omega_0={control['omega0']:g}$): fit gives {control['mu_e'] / mu:.4f}")
    for a, where in ((ax, "lower right"), (bx, "lower left")):
        a.axhline(1.0, color="k", lw=0.6)
        a.set_xlabel(r"coefficient of restitution $e$")
        a.legend(fontsize=8, loc=where, ncol=2, title=r"$\Omega_0$ in units $\sqrt{g/b}$", title_fontsize=8)
    lo = min(r["mu_e"] / mu - np.hypot(r["s_fit"] / mu, np.nan_to_num(r["bias"])) for r in rows)
    ax.set_ylim(lo - 0.6 * (1.005 - lo), 1.005)  # room below the bars for the legend
    ax.set_ylabel(r"effective friction $\mu_e/\mu$ (fit of (3.18) to $\theta(t)$)")
    ax.set_title("(a) mu_e / mu; error bars: fit error and the method's bias (fit before the first lift-off)", fontsize=9)
    bx.set_ylim(0, 1.05)
    bx.set_ylabel(r"$1 -$ (fraction of the rise spent in flight)")
    bx.set_title("(b) the naive estimate mu_e / mu ~ 1 - (flight fraction): far off", fontsize=9)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def _jump_surface_title(data) -> str:
    sc = data.scene
    what = "horizontal precession, Omega0" if sc.branch == "prolate" else "vertical spin, n0"
    exact = "no exact boundary" if data.exact_lambda is None else f"exact R = 0 at Lambda = +-{data.exact_lambda:.3f} (green)"
    return (f"Fig. 6a, {sc.branch} a = {sc.a:.4g}, Coulomb mu = {sc.mu:g}, rtol 1e-9: surface (6.3) (colour), {exact},\n"
            f"trajectories from the {what} = "
            + ", ".join(f"{v:g}" for v in sc.values) + f" (sliding-branch starts, d = {sc.seed_distance:g}; lines), "
            "R = 0 crossings (black), fixed points (red)")


def render_jump_surface(data, path, *, gltf: bool = False, html: bool = False) -> tuple:
    """Fig. 6a: a jump-surface scene computed by :func:`phasekit.compute_scene` (the surface
    (6.3), the exact boundary R = 0, trajectories from the sliding-branch starts and their
    crossings) rendered off-screen by :func:`phasekit.viz.render_scene` with its caption, to the
    PNG ``path`` and, if asked, the glTF and HTML exports beside it (same stem), each written
    under a temporary name and renamed when whole. Returns the
    :class:`phasekit.viz.pv.RenderInfo` and the exports asked for that could not be written
    (``"html"`` needs the trame packages).

    Examples
    --------
    >>> import tempfile, pathlib, phasekit as pk, phasekit.studies as ps
    >>> show = frozenset({"surface", "exact_boundary", "trajectories", "crossings"})
    >>> data = pk.compute_scene(pk.Scene("prolate", 1.5, values=(12.0,), show=show, resolution=20))
    >>> info, missing = ps.render_jump_surface(data, pathlib.Path(tempfile.mkdtemp()) / "fig6a.png")
    >>> info.n_points["surface"] > 0, missing
    (True, [])
    """
    from ..io import atomic_path
    from ..viz.pv import render_scene

    path = Path(path)
    with contextlib.ExitStack() as stack:  # every file written under a temporary name, then renamed
        png = stack.enter_context(atomic_path(path))
        extra = {k: str(stack.enter_context(atomic_path(path.with_suffix(f".{k}")))) for k, on in (("gltf", gltf), ("html", html))
                 if on}
        info = render_scene(data, png, title=_jump_surface_title(data), **extra)
        missing = [k for k, p in extra.items() if p not in info.exported]
    return info, missing
