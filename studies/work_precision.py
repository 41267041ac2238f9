"""Error against run time for every integrator a user might pick, on the same work.

Workloads (Coulomb friction mu = 0.1, exact law; both slide throughout, so every method
integrates the same smooth field): prolate a = 1.5 from the gyroscopic start theta0 = pi/2 - 0.01,
Omega0 = 10.5, to the jump; oblate a = 2/3 from theta0 = 0.05, n0 = 10.5, to the jump.
Error: |t_jump - t_ref| / t_ref (and the max-norm state error at the jump, in the csv) against
a reference from phasekit's Taylor integrator at tol 1e-15, checked by scipy DOP853 at
rtol 1e-13 on the independent NumPy right-hand side (the difference is printed).

Methods: phasekit's Taylor integrator (heyoka), run as the sweeps run it (no dense output, no
located minima of R) and with the default options of simulate (dense output kept for sampling
and every minimum of R located); CVODES BDF and Adams and IDAS through CasADi (event
bracketing on a grid, Brent refinement; no dense output); scipy BDF, Radau, LSODA, DOP853 on a plain NumPy
right-hand side (the baseline a user writes by hand); scipy BDF, Radau (with the exact
Jacobian) and DOP853 on the compiled CasADi right-hand side. Wall time: median of repeats;
a run past the per-run cap is recorded as "capped", not dropped.

Also: (c) t_jump against the regularisation eps on a sliding start (converges) and on the
paper's start (5.2) (sticks: does not); (d) cost against simulated time and against Omega0.

Writes work_precision.png and work_precision.csv (columns workload, method, rtol, error,
state_error, wall_s, n_rhs, default, status).
"""

from __future__ import annotations

import statistics
import time

import phasekit as pk
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


def run_phasekit(body, y0, rtol, backend, cap, options=SWEEP_PATH):
    m = pk.Model(body, pk.Coulomb(MU))
    t0 = time.perf_counter()
    r = pk.simulate(m, y0, 200.0, rtol=rtol, backend=backend, **options)
    wall = time.perf_counter() - t0
    if r.status is not pk.Status.JUMPED:
        return None, None, wall, r.n_rhs, f"{r.status.value}: {r.reason}"
    return r.t_jump, r.x_jump, wall, r.n_rhs, "ok"


def run_scipy(body, y0, rtol, method, cap, *, casadi_rhs=False):
    r = pk.baseline.solve_ivp_to_jump(y0, 200.0, a=body.a, A=body.A, C=body.C, mu=MU, method=method, rtol=rtol,
                                      rhs="casadi" if casadi_rhs else "numpy", max_wall=cap)
    return r.t_jump, r.y if r.t_jump is not None else None, r.wall_s, r.n_rhs, r.status


METHODS = {
    "phasekit Taylor/heyoka (sweep path)": lambda b, y, r, cap: run_phasekit(b, y, r, "auto", cap),
    "phasekit Taylor/heyoka (default options)": lambda b, y, r, cap: run_phasekit(b, y, r, "auto", cap, {}),
    "CVODES BDF (CasADi)": lambda b, y, r, cap: run_phasekit(b, y, r, "cvodes", cap),
    "CVODES Adams (CasADi)": lambda b, y, r, cap: run_phasekit(b, y, r, "cvodes-adams", cap),
    "IDAS (CasADi)": lambda b, y, r, cap: run_phasekit(b, y, r, "idas", cap),
    "scipy BDF, NumPy rhs": lambda b, y, r, cap: run_scipy(b, y, r, "BDF", cap),
    "scipy Radau, NumPy rhs": lambda b, y, r, cap: run_scipy(b, y, r, "Radau", cap),
    "scipy LSODA, NumPy rhs": lambda b, y, r, cap: run_scipy(b, y, r, "LSODA", cap),
    "scipy DOP853, NumPy rhs": lambda b, y, r, cap: run_scipy(b, y, r, "DOP853", cap),
    "scipy BDF, CasADi rhs+jac": lambda b, y, r, cap: run_scipy(b, y, r, "BDF", cap, casadi_rhs=True),
    "scipy Radau, CasADi rhs+jac": lambda b, y, r, cap: run_scipy(b, y, r, "Radau", cap, casadi_rhs=True),
    "scipy DOP853, CasADi rhs": lambda b, y, r, cap: run_scipy(b, y, r, "DOP853", cap, casadi_rhs=True),
}
DEFAULT = "phasekit Taylor/heyoka (sweep path)"  # drawn bold


def reference(body, y0):
    m = pk.Model(body, pk.Coulomb(MU))
    r = pk.simulate(m, y0, 200.0, rtol=1e-15, **SWEEP_PATH)
    t_chk, y_chk, _, _, status = run_scipy(body, y0, 1e-13, "DOP853", 1e9)
    return r.t_jump, r.x_jump, t_chk, y_chk


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


def measure(wls, rtols, cap, repeats, bar) -> tuple[list, dict]:
    """Every method at every tolerance on every workload: error against the reference and
    median wall time."""
    rows, refs = [], {}
    for wl, (body, y0) in wls.items():
        t_ref, y_ref, t_chk, y_chk = reference(body, y0)
        bar.update()
        refs[wl] = (t_ref, abs(t_chk - t_ref) / t_ref, float(np.max(np.abs(y_chk - y_ref))))
        for name, fn in METHODS.items():
            for rt in rtols:
                bar.set_postfix_str(f"{name} @ {rt:.0e}", refresh=False)
                bar.update()
                fn(body, y0, rt, cap) if name.startswith(("phasekit", "CVODES", "IDAS")) else None  # compile/warm once
                walls, res = [], None
                for _ in range(repeats):
                    res = fn(body, y0, rt, cap)
                    walls.append(res[2])
                    if res[4] != "ok" or res[2] > 1.0:
                        break
                tj, yj, wall, nrhs, status = res
                wall = statistics.median(walls) if status == "ok" else wall
                err = abs(tj - t_ref) / t_ref if tj is not None else None
                serr = float(np.max(np.abs(np.asarray(yj) - y_ref))) if yj is not None else None
                rows.append(dict(workload=wl, method=name, rtol=rt, error=err, state_error=serr, wall_s=wall,
                                 n_rhs=nrhs, default=name == DEFAULT, status=status))
    return rows, refs


def draw_work_precision(axes, rows, refs, cap) -> None:
    markers = "os^vD<>phX*P"
    # phasekit's two rows in black (solid: sweep path, dashed: default options), the rest in the colour cycle
    styles = {name: dict(color=f"C{k}", lw=1) for k, name in enumerate(m for m in METHODS if not m.startswith("phasekit"))}
    styles[DEFAULT] = dict(color="k", lw=2.5)
    styles["phasekit Taylor/heyoka (default options)"] = dict(color="k", lw=1.5, ls="--")
    for ax, wl in zip(axes, refs):
        for k, name in enumerate(METHODS):
            mine = [r for r in rows if r["workload"] == wl and r["method"] == name]
            pts = [(r["wall_s"], max(r["error"], 1e-16)) for r in mine if r["error"] is not None]
            capped = [r for r in mine if r["status"] == "capped"]
            if pts:
                ax.loglog(*zip(*pts), marker=markers[k % len(markers)], ms=4, label=name, **styles[name])
            if capped:
                ax.loglog([cap] * len(capped), [1e-1] * len(capped), "r|", ms=12)
        ax.set_xlabel("wall time per run (s)")
        ax.set_ylabel(r"relative error of the jump time $t_*$")
        ax.set_title(f"{wl}: t* = {refs[wl][0]:.6f}" + ("; red ticks: capped runs" if any(r['status'] == 'capped' for r in rows) else ""),
                     fontsize=9)
        ax.grid(alpha=0.3, which="both")


def draw_eps(ax, eps_rows) -> None:
    for label, erows in eps_rows.items():
        xs = [e if e is not None else 1e-10 for e, *_ in erows]
        ys = [tj if tj is not None else 400.0 for _, tj, *_ in erows]
        ax.semilogx(xs, ys, "o-", label=label)
        for (e, tj, st, tstick, w), x, y in zip(erows, xs, ys):
            if tstick is not None:
                ax.annotate("stick", (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axhline(400.0, color="0.6", ls=":", lw=0.8)
    ax.set_xlabel(r"regularisation $\epsilon$ (units $\sqrt{gb}$; the exact stick-slip law plotted at $10^{-10}$)")
    ax.set_ylabel(r"jump time $t_*$ (units $\sqrt{b/g}$; 400 = no jump by $t = 400$)")
    ax.set_title(r"(c) $t_*$ against $\epsilon$: converges on the sliding start, not on the sticking one; "
                 "'stick': the slip fell below 10 eps", fontsize=9)
    ax.legend(fontsize=8, loc="center left")


def draw_cost(ax, by_T, by_om) -> None:
    from matplotlib.ticker import NullFormatter

    Ts, oms = [T for T, *_ in by_T], [o for o, *_ in by_om]
    ax.loglog(Ts, [w for _, w, _ in by_T], "o-", label=r"against simulated time $T$ ($\Omega_0=10$)")
    ax2 = ax.twiny()
    ax2.loglog(oms, [w for _, w, _ in by_om], "s--", color="C1", label=r"against $\Omega_0$ ($T=100$)")
    for a, ticks in ((ax, Ts), (ax2, oms)):  # label the measured values, plainly
        a.set_xticks(ticks, [f"{v:g}" for v in ticks])
        a.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(r"simulated time $T$ (units $\sqrt{b/g}$)")
    ax2.set_xlabel(r"initial precession rate $\Omega_0$ (units $\sqrt{g/b}$)", color="C1")
    ax.set_ylabel("wall time per run (s)")
    ax.set_title(r"(d) cost growth, $\mu = 0$ (no rise, no jump), rtol $10^{-9}$", fontsize=9)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left")


def draw(plt, rows, refs, eps_rows, by_T, by_om, cap, quick):
    fig = plt.figure(figsize=(13, 11.5))
    gs = fig.add_gridspec(3, 2, height_ratios=[1, 0.13, 1])
    top = [fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1])]
    draw_work_precision(top, rows, refs, cap)
    legend_ax = fig.add_subplot(gs[1, :])
    legend_ax.axis("off")
    legend_ax.legend(*top[0].get_legend_handles_labels(), loc="center", ncol=4, fontsize=8, frameon=False)
    draw_eps(fig.add_subplot(gs[2, 0]), eps_rows)
    draw_cost(fig.add_subplot(gs[2, 1]), by_T, by_om)
    fig.suptitle(r"Work-precision on the jump time, Coulomb $\mu=0.1$, error against Taylor at rtol $10^{-15}$"
                 + (" (quick)" if quick else ""), fontsize=11)
    fig.tight_layout()
    return fig


def report(rows, refs, eps_rows, by_T, by_om, cap, repeats, png) -> None:
    print(f"Figure {png.name}; table work_precision.csv; {len(rows)} runs, cap {cap:g} s, median of {repeats}.")
    for wl, (t_ref, chk, schk) in refs.items():
        print(f"{wl}: reference t* = {t_ref:.12f} (Taylor tol 1e-15); scipy DOP853 rtol 1e-13 on the NumPy rhs differs by "
              f"{chk:.1e} relative in t*, {schk:.1e} in the state")
    for wl in refs:
        print(f"\n{wl}: cheapest run reaching each error level")
        print(f"{'method':<42s} {'error <= 1e-6':>22s} {'error <= 1e-9':>22s}")
        for name in METHODS:
            cells = []
            for target in (1e-6, 1e-9):
                ok = [r for r in rows if r["workload"] == wl and r["method"] == name and r["error"] is not None and r["error"] <= target]
                best = min(ok, key=lambda r: r["wall_s"]) if ok else None
                cells.append(f"{best['wall_s'] * 1e3:9.2f} ms @ {best['rtol']:.0e}" if best else "not reached")
            print(f"{name:<42s} {cells[0]:>22s} {cells[1]:>22s}")
    for name in ("CVODES BDF (CasADi)", "CVODES Adams (CasADi)", DEFAULT):
        pts = [(r["rtol"], r["error"]) for r in rows if r["workload"] == next(iter(refs)) and r["method"] == name and r["error"]]
        if len(pts) > 2:
            slope = np.polyfit(np.log10([p[0] for p in pts]), np.log10([max(p[1], 1e-16) for p in pts]), 1)[0]
            print(f"error against rtol, {name}: log-log slope {slope:.2f}")
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
    st = pk.sweep.Study(__file__, __doc__, quick_help="4 tolerances, 1 repeat, 5 s cap")
    args = st.parse(argv)
    plt = pyplot()
    rtols = [1e-4, 1e-6, 1e-8, 1e-10] if args.quick else [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
    cap = 5.0 if args.quick else 30.0
    repeats = 1 if args.quick else 3
    wls = workloads()
    with st.progress(total=len(wls) * (1 + len(METHODS) * len(rtols)) + 2, desc="runs") as bar:
        rows, refs = measure(wls, rtols, cap, repeats, bar)
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
    pk.sweep.run_study(main)
