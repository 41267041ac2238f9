"""Figure 5: the gap Delta(t) during the first flight, and its maximum over Omega0.

(a-c) prolate a = 1.5, Coulomb mu = 0.1 (exact stick-slip), started on the sliding branch
(theta0 = pi/2 - 0.01, gyroscopic balance) with Omega0 = 11, 20, 30: the gap from the
numerical flight, from the exact solution (4.1)+(4.12), and the series (4.22) with the
computed Omega* and W*. (d) Delta_max for an ensemble of random perturbations of amplitude
0.05 (uniform on the unit sphere of (U, V, Omega, Lambda, theta, n), seeded) of the horizontal
steady precession, for Omega0 from 10 to 40: the exact maximum of the flight and (4.23), with
the paper's bound (4.65/Omega0)^5; prints how many points exceed it. Writes figure5_gap.png and
figure5_gap.csv (one row per ensemble member).
"""

from __future__ import annotations

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_gap_flight, plot_gap_maxima
from phasekit.viz import pyplot

import numpy as np

MU, A_RATIO = 0.1, 1.5


def flights_abc(axes, model, body) -> list:
    """(a-c): the first flight from the sliding-branch start for Omega0 = 11, 20, 30, drawn
    and tabulated."""
    print("Figure 5a-c: first flight from the sliding-branch start (theta0 = pi/2 - 0.01)")
    print(f"{'Omega0':>6s} {'t*':>8s} {'W*':>9s} {'Omega*':>8s} {'W* Omega*':>9s} {'flight':>8s} {'Dmax exact':>11s} "
          f"{'(4.23)':>11s} {'rel err':>8s} {'(4.22) curve err':>16s}")
    rows_abc = []
    for ax, om in zip(axes, (11.0, 20.0, 30.0)):
        r = ps.first_flight(model, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=om))
        chk = ps.flight_check(r)  # the flight again at rtol 1e-13, and the theory of section 4
        fl, gm, rel, curve = chk.flight, chk.gap_max_series, chk.rel_error, chk.curve_error
        rows_abc.append((om, rel, curve, fl.W_star * fl.Omega_star))
        print(f"{om:6.1f} {r.t_jump:8.3f} {fl.W_star:9.5f} {fl.Omega_star:8.3f} {fl.W_star * fl.Omega_star:9.4f} "
              f"{fl.t_touchdown - fl.t_liftoff:8.5f} {fl.gap_max:11.4e} {gm:11.4e} {rel:+8.3f} {curve:16.3e}")
        title = (fr"({'abc'[len(rows_abc) - 1]}) $\Omega_0={om:g}$: $W_*={fl.W_star:.4f}$, $\Omega_*={fl.Omega_star:.2f}$; "
                 fr"$\Delta_{{max}}$ of (4.23) {100 * rel:+.1f}%")
        plot_gap_flight(ax, chk.t, chk.numerical, chk.exact, chk.series, title=title)
    return rows_abc


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="Omega0 step 5 instead of 2.5, 5 members each instead of 10")
    st.parser.add_argument("--seed", type=st.parser.integer(min=0), default=2006,
                           help="seed of the ensemble's perturbations (default 2006)")
    args = st.parse(argv)
    plt = pyplot()
    body = pk.Spheroid(A_RATIO)
    model = pk.Model(body, pk.Coulomb(MU))
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    rows_abc = flights_abc(axes.flat[:3], model, body)
    omegas = np.arange(10.0, 41.0, 5.0 if args.quick else 2.5)
    n_each = 5 if args.quick else 10
    with st.progress(total=len(omegas) * n_each, desc="ensemble") as bar:
        recs = ps.gap_ensemble(model, omegas, n_each, args.seed, bar=bar)
    om, exact, series = np.array([(q[0], q[3], q[4]) for q in recs], dtype=float).T
    ok = np.isfinite(exact)
    plot_gap_maxima(axes[1, 1], om[ok], exact[ok], series[ok], omegas,
                    title=f"(d) {int(ok.sum())} jumps from perturbations of amplitude 0.05 (seed {args.seed})")
    fig.suptitle(r"Fig. 5: the gap during the first flight; prolate $a=1.5$, Coulomb $\mu=0.1$" "\n"
                 r"(a-c) from the sliding-branch start $\theta_0=\pi/2-0.01$, flight integrated at rtol $10^{-13}$; "
                 r"(d) from random perturbations of the horizontal steady precession, rtol $10^{-9}$", fontsize=10)
    fig.tight_layout()
    png = st.save(fig, "figure5_gap.png", dpi=120)
    st.csv("figure5_gap.csv", ["omega0", "member", "status", "gap_max_exact", "gap_max_4_23", "W_star", "Omega_star", "stuck", "bound"],
           [[*q, (4.65 / q[0]) ** 5] for q in recs])
    lines, counts = ps.gap_ensemble_report(recs, omegas)
    print(f"\nFigure {png.name}; " + "\n".join(lines))
    print(f"{st.wall:.1f} s")
    return {"abc": rows_abc, **counts}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
