"""Figures 3 and 4: the exact dynamics against the gyroscopic solution and the envelope Sigma.

Cases (Coulomb friction, mu = 0.1, exact stick-slip):
  oblate a = 2/3, n0 = 10 and 10.5, c = 0.00052;  prolate a = 3/2, Omega0 = 10.2 and 10.5,
  c = -0.00054 (the paper's values), each started on the sliding branch (gyroscopic balance;
  theta-bar0 = 0.05 oblate, pi/2 - 0.01 prolate) with the nutation of amplitude c and phase
  xi = 0 (3.46), (3.27). The paper's printed starts (5.1), (5.2) are run too: they stick.
For each case: R(t) with the envelope Sigma (3.64) at the simulated mean inclination, and
the simulated theta, Omega, n with the gyroscopic theta-bar, Omega-bar, n-bar (3.18).
Means: the average over each fast period (between successive located minima of R), (3.6).
Errors (RMS and max over the rise up to the jump) of the gyroscopic theta-bar and of Sigma
against the simulated minima of R, and their trend in Omega0 (10.5, 20, 40) and n0.
Writes envelope_vs_simulation.png and envelope_vs_simulation.csv (columns case, t, theta_bar,
sigma, r_min_sim, sigma_c_eff, c, c_eff).
"""

from __future__ import annotations

from dataclasses import dataclass

import phasekit as pk
from phasekit.viz import pyplot

import numpy as np

MU = 0.1


@dataclass
class Case:
    label: str
    a: float
    theta0: float
    omega0: float | None = None
    n0: float | None = None
    c: float = 0.0
    xi: float = 0.0


PAPER_CASES = [
    Case("oblate a=2/3 n0=10", 2 / 3, 0.05, n0=10.0, c=0.00052),
    Case("oblate a=2/3 n0=10.5", 2 / 3, 0.05, n0=10.5, c=0.00052),
    Case("prolate a=3/2 Omega0=10.2", 1.5, np.pi / 2 - 0.01, omega0=10.2, c=-0.00054),
    Case("prolate a=3/2 Omega0=10.5", 1.5, np.pi / 2 - 0.01, omega0=10.5, c=-0.00054),
]
TREND = [Case(f"prolate Omega0={w:g}", 1.5, np.pi / 2 - 0.01, omega0=w, c=-0.00054) for w in (10.5, 20.0, 40.0)] + \
        [Case(f"oblate n0={n:g}", 2 / 3, 0.05, n0=n, c=0.00052) for n in (10.5, 20.0, 40.0)]


def run_case(case: Case, t_max: float, dt: float):
    body = pk.Spheroid(case.a)
    y0 = pk.gyroscopic_start(body, case.theta0, omega0=case.omega0, n0=case.n0)
    om_bar0 = float(y0[2])
    th_p, lam_p, om_p = pk.theory.perturbation_from_c_xi(body, case.theta0, om_bar0, MU, case.c, case.xi)
    y = y0.copy()
    # O(mu) mean state: the drift U = F_y / Omega of (2.7b) and the rise rate mu dtheta/dT of (3.16b);
    # without them the start carries an extra nutation of a few times c.
    _, dth_dT, vhat, _ = pk.theory.slow_rates(body, case.theta0, om_bar0)
    y[0] += -MU * vhat / om_bar0
    y[3] += MU * dth_dT
    y[4] += th_p
    y[3] += lam_p
    y[2] += om_p
    model = pk.Model(body, pk.Coulomb(MU))
    # the rise is complete when theta passes 0.05 (prolate, falling) or pi/2 - 0.05 (oblate, rising)
    rise = (pk.Event("theta", 0.05, direction=-1, name="rise-complete") if case.a > 1 else
            pk.Event("theta", np.pi / 2 - 0.05, direction=+1, name="rise-complete"))
    r = pk.simulate(model, y, t_max, events=[rise])  # dense output (the default), sampled below
    J = float(pk.theory.jellett_constant(body, case.theta0, om_bar0))
    ts = np.arange(0.0, r.t, dt)
    ys = r.states(ts)  # the Euler chart: the paper's (U, V, Omega, Lambda, theta, n)
    theta, Omega = ys[:, 4], ys[:, 2]
    tm, Rm = r.minima[:, 0], r.minima[:, 1]
    # fast-period means between successive minima of R
    t_mid, th_bar = pk.theory.mean_over_periods(ts, theta, tm)
    _, om_bar = pk.theory.mean_over_periods(ts, Omega, tm)
    th_gyro, om_gyro = pk.theory.gyroscopic_closed(case.a, J, case.theta0, MU * t_mid)
    # Sigma at the simulated mean inclination at each minimum of R
    th_at_min = np.interp(tm, t_mid, th_bar) if t_mid.size else np.full_like(tm, np.nan)
    valid = (tm >= t_mid[0]) & (tm <= t_mid[-1]) if t_mid.size else np.zeros_like(tm, bool)
    sig = np.full_like(tm, np.nan)
    sig_fit = np.full_like(tm, np.nan)
    c_eff = np.nan
    if valid.any():
        sig[valid] = pk.theory.Sigma(body, J, case.theta0, th_at_min[valid], case.c, form="closed")
        # effective amplitude of the start: fitted on the first 30% of the minima only, so that
        # the rest of the rise tests the growth law Gamma(theta-bar) out of sample
        idx = np.flatnonzero(valid)
        early = idx[: max(3, int(0.3 * idx.size))]
        th_e = th_at_min[early]
        om_e = J / (body.A * body.h(th_e)[0])
        scale = np.abs(body.h(th_e)[1] * pk.theory.omega_gyro(body, th_e, om_e) ** 2 * pk.theory.Gamma_closed(body, J, case.theta0, th_e))
        c_eff = float(np.median((1 - Rm[early]) / scale)) * np.sign(case.c)
        sig_fit[valid] = pk.theory.Sigma(body, J, case.theta0, th_at_min[valid], c_eff, form="closed")
    return dict(case=case, body=body, res=r, ts=ts, theta=theta, R=model.normal_reaction(ys), tm=tm, Rm=Rm, t_mid=t_mid,
                th_bar=th_bar, om_bar=om_bar, th_gyro=th_gyro, om_gyro=om_gyro, th_at_min=th_at_min, sigma=sig,
                sigma_fit=sig_fit, c_eff=c_eff, J=J, omega_fast=float(np.sqrt(pk.theory.omega2(body, case.theta0, om_bar0))), valid=valid)


def errors(d):
    """RMS and max of: gyroscopic theta-bar - period-mean theta; Sigma(c) - minima of R;
    Sigma(c_eff) - minima of R over the part of the rise not used to fit c_eff."""
    e_th = d["th_bar"] - d["th_gyro"]
    ok = d["valid"] & np.isfinite(d["sigma"])
    e_s = d["Rm"][ok] - d["sigma"][ok]
    idx = np.flatnonzero(ok)
    late = idx[max(3, int(0.3 * idx.size)):]
    e_f = d["Rm"][late] - d["sigma_fit"][late]
    rms = lambda e: float(np.sqrt(np.mean(e**2))) if e.size else float("nan")  # noqa: E731
    mx = lambda e: float(np.max(np.abs(e))) if e.size else float("nan")  # noqa: E731
    return rms(e_th), mx(e_th), rms(e_s), mx(e_s), rms(e_f), mx(e_f)


def literal_starts():
    out = []
    b15, b23 = pk.Spheroid(1.5), pk.Spheroid(2 / 3)
    for label, body, y, t_max in [
        ("(5.2) prolate Omega0=10.5", b15, [7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2], 300.0),
        ("(5.1) oblate n0=10.5", b23, [8e-7, 4e-6, 0.4 * 10.5 / b23.A, 1e-5, 4e-6, 10.5], 300.0),
    ]:
        chart = pk.choose_chart(y[4])
        m = pk.Model(body, pk.Coulomb(MU), chart)
        r = pk.simulate(m, pk.to_chart(chart, y), t_max)
        out.append((label, r))
    return out


def draw(plt, runs):
    """3 rows x 2 columns (oblate | prolate): the mean state against the gyroscopic solution,
    then R with its minima and Sigma for the two cases of each figure."""
    fig, axes = plt.subplots(3, 2, figsize=(12, 9))
    for col, pair in enumerate((runs[0:2], runs[2:4])):
        d = pair[1]  # the jumping (larger) case for the mean-state panel
        ax = axes[0, col]
        ax.plot(d["ts"], d["theta"], color="0.6", lw=0.5, label=r"$\theta$ simulated")
        ax.plot(d["t_mid"], d["th_bar"], color="k", lw=1.0, label=r"$\bar\theta$ (period means)")
        ax.plot(d["t_mid"], d["th_gyro"], color="C3", lw=2, ls="--", label=r"$\bar\theta$ gyroscopic (3.18)")
        ax.set_ylabel(r"$\theta$ (rad)")
        ax.set_xlabel(r"time $t$ (units $\sqrt{b/g}$)")
        ax2 = ax.twinx()
        ax2.plot(d["t_mid"], d["om_bar"], color="C0", lw=1.0, label=r"$\bar\Omega$ simulated")
        ax2.plot(d["t_mid"], d["om_gyro"], color="C0", lw=2, ls=":", label=r"$\bar\Omega = J/(Ah)$")
        ax2.set_ylabel(r"$\Omega$ (units $\sqrt{g/b}$)", color="C0")
        ax.set_title(d["case"].label + f", J = A$\\Omega$h = {d['J']:.3f}", fontsize=9)
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="center left")
        for row, d in zip((1, 2), pair):
            ax = axes[row, col]
            ax.plot(d["ts"], d["R"], color="0.5", lw=0.4, label="R simulated")
            ax.plot(d["tm"], d["Rm"], ".", ms=2, color="k", label="minima of R")
            ok = np.isfinite(d["sigma"])
            ax.plot(d["tm"][ok], d["sigma"][ok], color="C3", lw=2, label=fr"$\Sigma$ (3.64), $c={d['case'].c:g}$")
            ax.plot(d["tm"][ok], d["sigma_fit"][ok], color="C1", lw=1.5, ls="--",
                    label=fr"$\Sigma$ with $c_{{eff}}={d['c_eff']:.2g}$ (fit: first 30%)")
            st = d["res"].status.value + (f" at t* = {d['res'].t_jump:.2f}" if d["res"].t_jump else "")
            ax.set_title(f"{d['case'].label}: {st}", fontsize=9)
            ax.set_ylabel(r"$R$ (units $Mg$)")
            ax.set_ylim(-0.1, 2.2)
            ax.legend(fontsize=7, loc="upper left")
        axes[2, col].set_xlabel(r"time $t$ (units $\sqrt{b/g}$)")
    fig.suptitle(r"Figs. 3 and 4: exact dynamics (Coulomb $\mu=0.1$, rtol $10^{-9}$) against the gyroscopic solution and $\Sigma$;"
                 "\nstarts on the sliding branch with the nutation of amplitude $c$ (3.46); minima of $R$ located as events",
                 fontsize=11)
    fig.tight_layout()
    return fig


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, quick_help="coarser output grid; trend in Omega0 only")
    args = st.parse(argv)
    plt = pyplot()
    dt = 0.01 if args.quick else 0.003
    trend_cases = TREND[:3] if args.quick else TREND
    runs, trends = [], []
    with st.progress(total=len(PAPER_CASES) + len(trend_cases) + 2, desc="simulations") as bar:
        for cases, out in ((PAPER_CASES, runs), (trend_cases, trends)):
            for c in cases:
                out.append(run_case(c, 400.0, dt))
                bar.update()
        lits = literal_starts()
        bar.update(2)

    png = st.save(draw(plt, runs), "envelope_vs_simulation.png", dpi=120)
    rows = [[d["case"].label, f"{t:.6f}", f"{th:.8f}", f"{s:.8f}", f"{rm:.8f}", f"{sf:.8f}", d["case"].c, f"{d['c_eff']:.6g}"]
            for d in runs + trends
            for t, th, s, rm, sf, ok in zip(d["tm"], d["th_at_min"], d["sigma"], d["Rm"], d["sigma_fit"], d["valid"]) if ok]
    path = st.csv("envelope_vs_simulation.csv", ["case", "t", "theta_bar", "sigma", "r_min_sim", "sigma_c_eff", "c", "c_eff"],
                  rows)
    print(f"Figure {png.name}: R(t), Sigma and the gyroscopic mean state for {len(runs)} cases; table {path.name}; "
          f"{st.wall:.1f} s.")
    print("errors over the rise up to the jump: theta = gyroscopic theta-bar - simulated period means;"
          " S(c) = minima of R - Sigma with the nominal c; S(c_eff) = the same with c fitted on the first 30% of the"
          " rise, over the other 70%")
    print(f"{'case':<28s} {'status':<9s} {'t*':>7s} {'J=AOh':>7s} {'c_eff/c':>7s} {'theta RMS':>9s} {'max':>8s} "
          f"{'S(c) RMS':>9s} {'max':>8s} {'S(c_eff) RMS':>12s} {'max':>8s}")
    out = {}
    for d in runs + trends:
        e = errors(d)
        out[d["case"].label] = e + (d["c_eff"] / d["case"].c,)
        tj = f"{d['res'].t_jump:.2f}" if d["res"].t_jump else "-"
        print(f"{d['case'].label:<28s} {d['res'].status.value:<9s} {tj:>7s} {d['J']:7.3f} {d['c_eff'] / d['case'].c:7.2f} "
              f"{e[0]:9.2e} {e[1]:8.2e} {e[2]:9.2e} {e[3]:8.2e} {e[4]:12.2e} {e[5]:8.2e}")
    print("Jellett constants: the paper quotes J = 4, 4.2 (Fig. 3, oblate; = C n0) and 6.63, 6.83 (Fig. 4, prolate; = A Omega0 h);"
          " here J = A Omega h (3.17) throughout (docs/physics.md, pitfall 4).")
    for label, r in lits:
        ev = ", ".join(f"{e.name} t={e.t:.4g}" for e in r.events[:3])
        print(f"literal start {label}: {r.status.value}, events: {ev or 'none'}; theta_end = {r.euler_end[4]:.6f}")
    return out


if __name__ == "__main__":
    pk.sweep.run_study(main)
