"""The tippe top: which tops invert, how far, how fast, and whether they hop on the way.

Question. A sphere of radius 1 with its centre of mass G at distance alpha below its centre,
moments A (transverse) and C = 0.4 (axial) about G, is spun about the vertical at n0 with its
axis tilted theta0 = 0.1 and G at rest. Does it invert fully (theta -> pi), partly (settles at
some theta_f < pi) or not at all, and does it lose contact with the table (R -> 0, a hop)?

What is run. phasekit's full model in the vector chart (regular at theta = 0 and pi), rtol
1e-10, over the grid alpha x gamma (gamma = A/C) at a few spins, under two friction laws:
viscous friction (F = -mu u: slip is dissipated whenever it is nonzero, the setting of the
classical theory) and exact Coulomb friction (stick-slip: a zero-slip top rolls, and rolling
does no work). Flights and impacts (restitution e = 0) are followed (stop_at="none"). A run
(ps.inversion_run) ends when theta reaches pi - 0.05 ("full", with its time) or at
t_end; otherwise the outcome is "never" if theta stayed below 0.3 and "partial" if not, with
theta_end the mean of theta over the last 10% of the run. A Coulomb top that alternates stick
and slip for hundreds of cycles is cut after 400 mode switches or 45 s and classified from the
span computed so far (status and reason in the CSV).

Side by side with (pk.theory.tippetop): the classical condition 1 - alpha < gamma < 1 + alpha,
the fast-spin groups I/II/III, and the finite-spin prediction for this start (ueda_group:
never / full / partial at theta_f), which assumes that the top keeps sliding and follows the
slow energy descent at fixed Jellett integral. Accuracy: Jellett's integral is checked at the
end of every run (its drift is in the CSV), and a subset is rerun at rtol 1e-12.

Outputs:
  tippe_top_map.csv/.json   one row per run (resumable: rows are appended as they finish)
  tippe_top_map.png         outcome maps, measured vs predicted
  tippe_top_hopping.png     theta, R and the gap for a top that hops while inverting
  tippe_top_scene.png       3-D view of one inversion (PyVista, off-screen)
  tippe_top_convergence.csv t_stop of the README example over rtol and eps
  tippe_top_summary.json    agreement with the predictions, hopping, accuracy checks
"""

from __future__ import annotations

import json

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_hopping, plot_inversion_map, render_inversion

C = 0.4
THETA0 = 0.1
RTOL = 1e-10
FULL = dict(alphas=(0.1, 0.2, 0.3, 0.4, 0.5), gammas=tuple(round(0.55 + 0.1 * i, 2) for i in range(11)), spins=(4.0, 8.0, 15.0),
            laws=(("viscous", 0.3), ("coulomb", 0.3)), t_end=300.0)
QUICK = dict(alphas=(0.2, 0.4), gammas=(0.75, 0.95, 1.25, 1.55), spins=(8.0,), laws=(("viscous", 0.3), ("coulomb", 0.3)),
             t_end=150.0)
#: the hopping example and the 3-D scene: the README's top
EXAMPLE = dict(alpha=0.3, A=0.38, n0=15.0, mu=0.3)


def row_key(law: str, mu: float, alpha: float, gamma: float, n0: float, t_end: float, rtol: float) -> str:
    return f"{law}|mu={mu:g}|alpha={alpha:g}|gamma={gamma:g}|n0={n0:g}|t_end={t_end:g}|rtol={rtol:g}"


def run_point(law: str, mu: float, alpha: float, gamma: float, n0: float, t_end: float, rtol: float) -> ps.InversionRun:
    """One point of the map: the top (alpha, gamma C, C) spun at n0 under the law, classified."""
    return ps.inversion_run(law, mu, alpha, gamma, n0, t_end, rtol, C=C, theta0=THETA0,
                                   key=row_key(law, mu, alpha, gamma, n0, t_end, rtol))


def hopping(r, st) -> dict:
    """theta, R and the gap of the README's top through its hops (figure), and its hops."""
    lifts, hops = r.events_named("lift-off"), r.hops
    a, A, n0, mu = EXAMPLE["alpha"], EXAMPLE["A"], EXAMPLE["n0"], EXAMPLE["mu"]
    st.save(plot_hopping(r, title=f"Tippe top alpha={a}, A={A}, C={C}, exact Coulomb mu={mu}, n0={n0}: {len(lifts)} "
                         "lift-offs (red), restitution 0"), "tippe_top_hopping.png")
    return {"n_liftoff": hops["n_liftoffs"], "first_liftoff": lifts[0].t if lifts else None,
            "theta_first_liftoff": float(lifts[0].y[4]) if lifts else None, "max_gap": hops["gap_max"],
            "longest_flight": hops["longest_flight"], "t_inverted": r.t if r.status is pk.Status.STOPPED else None}


# -- the README example: convergence in rtol and eps -----------------------------------------------
def convergence(st) -> list[dict]:
    top = pk.EccentricSphere(0.3, A=0.38, C=C)
    rows = []
    for eps in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, None):
        law = pk.Coulomb(0.3) if eps is None else pk.RegularisedCoulomb(0.3, eps)
        for rtol in (1e-8, 1e-9, 1e-10, 1e-11, 1e-12):
            r = pk.simulate(pk.Model(top, law), pk.core.vertical_spin_start(THETA0, 15.0), 30.0, rtol=rtol,
                            events=[pk.Event("theta", 0.4, name="theta=0.4")])
            rows.append({"eps": eps, "rtol": rtol, "status": str(r.status), "t_stop": r.t,
                         "n_steps": r.n_steps})
    ref = next(r["t_stop"] for r in rows if r["eps"] is None and r["rtol"] == 1e-12)
    for r in rows:
        r["diff_vs_exact_rtol1e-12"] = r["t_stop"] - ref
    st.csv("tippe_top_convergence.csv", list(rows[0]), [list(r.values()) for r in rows])
    print("README example: t_stop (theta reaches 0.4) of the tippe top alpha=0.3, A=0.38, C=0.4, mu=0.3, theta0=0.1, n0=15")
    print(f"{'eps':>8s} " + " ".join(f"{'rtol ' + format(rt, 'g'):>20s}" for rt in (1e-8, 1e-9, 1e-10, 1e-11, 1e-12)))
    for eps in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, None):
        line = [r for r in rows if r["eps"] == eps]
        print(f"{'exact' if eps is None else eps!s:>8s} " + " ".join(f"{r['t_stop']:20.15f}" for r in line))
    return rows


def check_rtol(cfg: dict, rows: list, n: int) -> list[dict]:
    """Rerun a few points at rtol 1e-12: outcome and theta_end must not move."""
    picks = sorted(rows, key=lambda r: r.key)[:: max(1, len(rows) // n)][:n]
    out = []
    for r in picks:
        q = run_point(r.law, r.mu, r.alpha, r.gamma, r.n0, cfg["t_end"], 1e-12)
        out.append({"point": r.key, "outcome_1e-10": r.outcome, "outcome_1e-12": q.outcome,
                    "theta_end_diff": abs(q.theta_end - r.theta_end)})
    return out


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, resumable=True)
    args = st.parse(argv)
    cfg = QUICK if args.quick else FULL
    conv = convergence(st)
    config = {k: list(v) if isinstance(v, tuple) else v for k, v in cfg.items()}
    store = st.store(ps.InversionRun, {"config": config, "rtol": RTOL, "theta0": THETA0, "C": C}, name="tippe_top_map")
    tasks = [(law, mu, a, g, n0) for (law, mu) in cfg["laws"] for n0 in cfg["spins"] for a in cfg["alphas"] for g in cfg["gammas"]
             if g * C >= 0.5 * C]  # C <= 2A
    specs = pk.sweep.each(tasks, lambda *t: row_key(*t, cfg["t_end"], RTOL), lambda *t: run_point(*t, cfg["t_end"], RTOL))
    st.run(specs, store, desc="tippe-top map")
    keys = {s.key for s in specs}
    rows = [r for r in store.rows() if r.key in keys]
    st.save(plot_inversion_map(rows, cfg["laws"], cfg["spins"], C=C, theta0=THETA0, title=(
        f"Tippe top spun about the vertical from $\\theta_0$ = {THETA0}, C = {C}: outcome by t = {cfg['t_end']:g}\n"
        f"markers: phasekit (vector chart, rtol {RTOL:g}); background: tippetop.ueda_group{' [quick run]' if args.quick else ''}")),
            "tippe_top_map.png")
    summary = ps.inversion_summary(rows)
    summary["rtol_check"] = check_rtol(cfg, rows, 3 if args.quick else 8)
    ex = EXAMPLE
    r = ps.simulate_inversion(pk.EccentricSphere(ex["alpha"], A=ex["A"], C=C), pk.Coulomb(ex["mu"]), ex["n0"], 200.0,
                                     theta0=THETA0, rtol=RTOL)
    summary["hopping_example"] = hopping(r, st)
    summary["scene"] = render_inversion(r, st.path("tippe_top_scene.png"), title=(
        f"Tippe top inverting: alpha={ex['alpha']}, A={ex['A']}, C={C}, exact Coulomb mu={ex['mu']}, n0={ex['n0']:g} "
        "(stem = +k, black = G)"))
    summary["convergence_t_stop_spread"] = max(c["diff_vs_exact_rtol1e-12"] for c in conv) - min(c["diff_vs_exact_rtol1e-12"] for c in conv)
    summary["wall_s"] = st.wall
    st.json("tippe_top_summary.json", summary)
    print(json.dumps(summary, indent=1, default=str))
    return summary


if __name__ == "__main__":
    pk.scaffold.run_study(main)
