"""Error against run time for every integrator a user might pick, on the same work.

Workloads (Coulomb friction mu = 0.1, exact law; both slide throughout, so every method
integrates the same smooth field): prolate a = 1.5 from the gyroscopic start theta0 = pi/2 - 0.01,
Omega0 = 10.5, to the jump; oblate a = 2/3 from theta0 = 0.05, n0 = 10.5, to the jump.
Error: |t_jump - t_ref| / t_ref (and the max-norm state error at the jump, in the csv) against
a reference from phasekit's Taylor integrator at tol 1e-15, checked by scipy DOP853 at
rtol 1e-13 on the independent NumPy right-hand side (the difference is printed).

Methods (pk.baseline.JUMP_METHODS, measured by pk.baseline.work_precision): phasekit's Taylor
integrator (heyoka), run as the sweeps run it (no dense output, no located minima of R) and
with the default options of simulate (dense output kept for sampling and every minimum of R
located); CVODES BDF and Adams and IDAS through CasADi (event bracketing on a grid, Brent
refinement; no dense output); scipy BDF, Radau, LSODA, DOP853 on a plain NumPy right-hand side
(the baseline a user writes by hand); scipy BDF, Radau (with the exact Jacobian) and DOP853 on
the compiled CasADi right-hand side. Wall time: median of repeats; a run past the per-run cap
is recorded as "capped", not dropped.

Also: (c) t_jump against the regularisation eps on a sliding start (converges) and on the
paper's start (5.2) (sticks: does not); (d) cost against simulated time and against Omega0.

Writes work_precision.png and work_precision.csv (columns workload, method, rtol, error,
state_error, wall_s, n_rhs, default, status).
"""

from __future__ import annotations

import statistics

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_cost_growth, plot_regularisation, plot_work_precision
from phasekit.viz import pyplot

import numpy as np

MU = 0.1


def workloads():
    b15, b23 = pk.Spheroid(1.5), pk.Spheroid(2 / 3)
    return {
        "prolate a=1.5 Omega0=10.5": (b15, pk.gyroscopic_start(b15, np.pi / 2 - 0.01, omega0=10.5)),
        "oblate a=2/3 n0=10.5": (b23, pk.gyroscopic_start(b23, 0.05, n0=10.5)),
    }


#: what a sweep needs (t_jump only); the default options add dense output and the minima of R
SWEEP_PATH = dict(dense=False, track_minima=False)


def eps_convergence(quick):
    """t_jump against eps on the sliding standard start and on the paper's start (5.2)."""
    body = pk.Spheroid(1.5)
    starts = {"sliding start (standard workload)": pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5),
              "paper start (5.2), Omega0 = 10.5": np.array([7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2])}
    epss = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8] if quick else [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    out = {}
    for label, y0 in starts.items():
        rows = []
        for eps in epss + [None]:
            law = pk.Coulomb(MU) if eps is None else pk.RegularisedCoulomb(MU, eps)
            r = pk.simulate(pk.Model(body, law), y0, 400.0, **SWEEP_PATH)
            sticks = [e.t for e in r.events if e.name == "stick"]
            rows.append((eps, r.t_jump, r.status.value, sticks[0] if sticks else None, r.wall_s))
        out[label] = rows
    return out


def cost_growth(quick, repeats=5):
    """Wall time (median of ``repeats``) against simulated time (Omega0 = 10) and against
    Omega0 (T = 100), mu = 0: no rise and no jump, so the runs last as long as asked."""
    body = pk.Spheroid(1.5)
    m = pk.Model(body, pk.Coulomb(0.0))
    y = lambda om: pk.gyroscopic_start(body, 1.0, omega0=om) + np.array([0, 0, 0, 0.01, 0, 0])  # noqa: E731
    pk.simulate(m, y(10.0), 1.0, **SWEEP_PATH)

    def timed(om, T):
        runs = [pk.simulate(m, y(om), T, **SWEEP_PATH) for _ in range(repeats)]
        return statistics.median(r.wall_s for r in runs), runs[0].n_steps

    Ts = [10, 30, 100, 300] if quick else [10, 30, 100, 300, 1000, 3000]
    oms = [5, 10, 20, 40] if quick else [5, 10, 20, 40, 80, 160]
    by_T = [(T, *timed(10.0, float(T))) for T in Ts]
    by_om = [(om, *timed(float(om), 100.0)) for om in oms]
    return by_T, by_om


def draw(plt, rows, refs, eps_rows, by_T, by_om, cap, quick):
    fig = plt.figure(figsize=(13, 11.5))
    gs = fig.add_gridspec(3, 2, height_ratios=[1, 0.13, 1])
    top = [fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1])]
    plot_work_precision(top, rows, refs, cap)
    legend_ax = fig.add_subplot(gs[1, :])
    legend_ax.axis("off")
    legend_ax.legend(*top[0].get_legend_handles_labels(), loc="center", ncol=4, fontsize=8, frameon=False)
    plot_regularisation(fig.add_subplot(gs[2, 0]), eps_rows, t_max=400.0, title=r"(c) $t_*$ against $\epsilon$: converges on "
                        "the sliding start, not on the sticking one; 'stick': the slip fell below 10 eps")
    plot_cost_growth(fig.add_subplot(gs[2, 1]), by_T, by_om, title=r"(d) cost growth, $\mu = 0$ (no rise, no jump), rtol $10^{-9}$")
    fig.suptitle(r"Work-precision on the jump time, Coulomb $\mu=0.1$, error against Taylor at rtol $10^{-15}$"
                 + (" (quick)" if quick else ""), fontsize=11)
    fig.tight_layout()
    return fig


def report(rows, refs, eps_rows, by_T, by_om, cap, repeats, png) -> None:
    print(f"Figure {png.name}; table work_precision.csv; {len(rows)} runs, cap {cap:g} s, median of {repeats}.")
    print(ps.work_precision_summary(rows, refs))
    print("\n(c) t_jump against eps (stuck: the slip fell below 10 eps, or held at zero with the exact law):")
    for label, erows in eps_rows.items():
        print("  " + label + ": " + "; ".join(f"eps={'exact' if e is None else f'{e:g}'}: "
                                          f"{'no jump' if tj is None else f'{tj:.6f}'}{' (stuck)' if ts is not None else ''}"
                                          for e, tj, st, ts, w in erows))
    print("(d) wall time (median of 5) against simulated time: " + ", ".join(f"T={T}: {w * 1e3:.1f} ms" for T, w, _ in by_T))
    print("    wall time against Omega0 (T=100): " + ", ".join(f"{o}: {w * 1e3:.1f} ms" for o, w, _ in by_om))
    sl_T = np.polyfit(np.log([T for T, *_ in by_T][1:]), np.log([w for _, w, _ in by_T][1:]), 1)[0]
    sl_o = np.polyfit(np.log([o for o, *_ in by_om][1:]), np.log([w for _, w, _ in by_om][1:]), 1)[0]
    print(f"    log-log slopes: {sl_T:.2f} in T, {sl_o:.2f} in Omega0")


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="4 tolerances, 1 repeat, 5 s cap")
    args = st.parse(argv)
    plt = pyplot()
    rtols = [1e-4, 1e-6, 1e-8, 1e-10] if args.quick else [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
    cap = 5.0 if args.quick else 30.0
    repeats = 1 if args.quick else 3
    wls = workloads()
    with st.progress(total=len(wls) * (1 + len(pk.baseline.JUMP_METHODS) * len(rtols)) + 2, desc="runs") as bar:
        rows, refs = pk.baseline.work_precision(wls, rtols, mu=MU, cap=cap, repeats=repeats, bar=bar)
        eps_rows = eps_convergence(args.quick)
        bar.update()
        by_T, by_om = cost_growth(args.quick)
        bar.update()
    png = st.save(draw(plt, rows, refs, eps_rows, by_T, by_om, cap, args.quick), "work_precision.png", dpi=120)
    st.csv("work_precision.csv", ["workload", "method", "rtol", "error", "state_error", "wall_s", "n_rhs", "default", "status"],
           rows)
    report(rows, refs, eps_rows, by_T, by_om, cap, repeats, png)
    print(f"{st.wall:.1f} s")
    return {"rows": rows, "refs": refs, "eps": eps_rows}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
