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

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_mean_state, plot_minima_envelope
from phasekit.viz import pyplot

import numpy as np

MU = 0.1
Case = ps.NutationCase
PAPER_CASES = [
    Case("oblate a=2/3 n0=10", 2 / 3, 0.05, n0=10.0, c=0.00052),
    Case("oblate a=2/3 n0=10.5", 2 / 3, 0.05, n0=10.5, c=0.00052),
    Case("prolate a=3/2 Omega0=10.2", 1.5, np.pi / 2 - 0.01, omega0=10.2, c=-0.00054),
    Case("prolate a=3/2 Omega0=10.5", 1.5, np.pi / 2 - 0.01, omega0=10.5, c=-0.00054),
]
TREND = [Case(f"prolate Omega0={w:g}", 1.5, np.pi / 2 - 0.01, omega0=w, c=-0.00054) for w in (10.5, 20.0, 40.0)] + \
        [Case(f"oblate n0={n:g}", 2 / 3, 0.05, n0=n, c=0.00052) for n in (10.5, 20.0, 40.0)]


def draw(plt, runs):
    """3 rows x 2 columns (oblate | prolate): the mean state of the jumping (larger) case against
    the gyroscopic solution, then R with its minima and Sigma for the two cases of each figure."""
    fig, axes = plt.subplots(3, 2, figsize=(12, 9))
    for col, pair in enumerate((runs[0:2], runs[2:4])):
        plot_mean_state(axes[0, col], pair[1][2], title=pair[1][0].label)
        for row, (case, r, chk) in zip((1, 2), pair):
            plot_minima_envelope(axes[row, col], chk, title=f"{case.label}: {r.status.value}"
                                 + (f" at t* = {r.t_jump:.2f}" if r.t_jump else ""))
        axes[2, col].set_xlabel(r"time $t$ (units $\sqrt{b/g}$)")
    fig.suptitle(r"Figs. 3 and 4: exact dynamics (Coulomb $\mu=0.1$, rtol $10^{-9}$) against the gyroscopic solution and $\Sigma$;"
                 "\nstarts on the sliding branch with the nutation of amplitude $c$ (3.46); minima of $R$ located as events",
                 fontsize=11)
    fig.tight_layout()
    return fig


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="coarser output grid; trend in Omega0 only")
    args = st.parse(argv)
    plt = pyplot()
    dt = 0.01 if args.quick else 0.003
    trend_cases = TREND[:3] if args.quick else TREND
    runs, trends = [], []
    with st.progress(total=len(PAPER_CASES) + len(trend_cases) + 2, desc="simulations") as bar:
        for cases, out in ((PAPER_CASES, runs), (trend_cases, trends)):
            for c in cases:
                out.append((c, *c.run(400.0, dt=dt, mu=MU)))
                bar.update()
        lits = {label: pk.simulate(*pk.paper_start(k), 300.0)  # the printed starts (their charts: pk.core.choose_chart)
                for k, label in (("5.2", "(5.2) prolate Omega0=10.5"), ("5.1", "(5.1) oblate n0=10.5"))}
        bar.update(2)

    png = st.save(draw(plt, runs), "envelope_vs_simulation.png", dpi=120)
    rows = [[case.label, f"{t:.6f}", f"{th:.8f}", f"{s:.8f}", f"{rm:.8f}", f"{sf:.8f}", case.c, f"{d.c_eff:.6g}"]
            for case, _, d in runs + trends
            for t, th, s, rm, sf, ok in zip(d.t_min, d.theta_at_min, d.sigma, d.R_min, d.sigma_fit, d.valid) if ok]
    path = st.csv("envelope_vs_simulation.csv", ["case", "t", "theta_bar", "sigma", "r_min_sim", "sigma_c_eff", "c", "c_eff"],
                  rows)
    print(f"Figure {png.name}: R(t), Sigma and the gyroscopic mean state for {len(runs)} cases; table {path.name}; "
          f"{st.wall:.1f} s.")
    lines, out = ps.envelope_report([(case.label, r, d) for case, r, d in runs + trends])
    print("\n".join(lines))
    print("Jellett constants: the paper quotes J = 4, 4.2 (Fig. 3, oblate; = C n0) and 6.63, 6.83 (Fig. 4, prolate; = A Omega0 h);"
          " here J = A Omega h (3.17) throughout (docs/physics.md, pitfall 4).")
    for label, r in lits.items():
        ev = ", ".join(f"{e.name} t={e.t:.4g}" for e in r.events[:3])
        print(f"literal start {label}: {r.status.value}, events: {ev or 'none'}; theta_end = {r.euler_end[4]:.6f}")
    return out


if __name__ == "__main__":
    pk.scaffold.run_study(main)
