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
ends when theta reaches pi - 0.05 ("full", with its time) or at t_end; otherwise the outcome
is "never" if theta stayed below 0.3 and "partial" if not, with theta_end the mean of theta
over the last 10% of the run.

Side by side with (phasekit.tippetop): the classical condition 1 - alpha < gamma < 1 + alpha,
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
import math
import time
from dataclasses import dataclass
from pathlib import Path

import phasekit as pk
from phasekit.viz import pyplot, save_figure

import numpy as np

C = 0.4
THETA0 = 0.1
THETA_FULL = math.pi - 0.05
THETA_NEVER = 0.3
RTOL = 1e-10
FULL = dict(alphas=(0.1, 0.2, 0.3, 0.4, 0.5), gammas=tuple(round(0.55 + 0.1 * i, 2) for i in range(11)), spins=(4.0, 8.0, 15.0),
            laws=(("viscous", 0.3), ("coulomb", 0.3)), t_end=300.0)
QUICK = dict(alphas=(0.2, 0.4), gammas=(0.75, 0.95, 1.25, 1.55), spins=(8.0,), laws=(("viscous", 0.3), ("coulomb", 0.3)),
             t_end=150.0)
#: the hopping example and the 3-D scene: the README's top
EXAMPLE = dict(alpha=0.3, A=0.38, n0=15.0, mu=0.3)


@dataclass(frozen=True)
class MapRow:
    """One run of the inversion map (key: law, mu, alpha, gamma, n0, t_end, rtol)."""

    key: str
    law: str
    mu: float
    alpha: float
    gamma: float
    A: float
    n0: float
    outcome: str  # full | partial | never | failed
    theta_end: float | None
    theta_max: float | None
    t_full: float | None
    t_run: float
    R_min: float | None
    n_liftoff: int
    n_stick: int
    t_first_stick: float | None
    classical: bool
    group: str  # fast-spin group I / II / III
    predicted: str  # never | full | partial (ueda_group for this start)
    theta_f_predicted: float
    n_full_predicted: float  # spin above which full inversion is predicted (inf: never)
    jellett_drift: float | None
    status: str
    reason: str
    wall_s: float


def row_key(law: str, mu: float, alpha: float, gamma: float, n0: float, t_end: float, rtol: float) -> str:
    return f"{law}|mu={mu:g}|alpha={alpha:g}|gamma={gamma:g}|n0={n0:g}|t_end={t_end:g}|rtol={rtol:g}"


def make_law(name: str, mu: float):
    return pk.Viscous(mu) if name == "viscous" else pk.Coulomb(mu)


#: exact Coulomb: a top that has settled in a tilted rolling state can alternate stick and slip
#: for hundreds of cycles (each slip onset from zero slip needs tiny Taylor steps: 0.3-1 s per
#: cycle measured). A map run is cut after this many mode switches or this wall time and
#: classified from the span computed so far (its status and reason are kept in the CSV).
MAP_MAX_SWITCHES = 400
MAP_MAX_WALL = 45.0


def simulate_top(alpha, A, n0, law, t_end, rtol, dense=True, restitution=0.0, max_switches=200_000, max_wall=300.0):
    top = pk.EccentricSphere(alpha, A=A, C=C)
    model = pk.Model(top, law, "vector")
    x0 = pk.to_chart("vector", pk.vertical_spin_start(THETA0, n0))
    stop = pk.Event("theta", THETA_FULL, direction=+1, name="inverted")
    return pk.simulate(model, x0, t_end, rtol=rtol, stop_at="none", restitution=restitution, events=[stop], dense=dense,
                       max_switches=max_switches, max_wall=max_wall)


def run_point(law_name: str, mu: float, alpha: float, gamma: float, n0: float, t_end: float, rtol: float) -> MapRow:
    t0 = time.perf_counter()
    A = gamma * C
    tt = pk.theory.tippetop
    pred = dict(classical=tt.classical_inversion(alpha, A, C), group=tt.ueda_group_limit(alpha, A, C),
                predicted=tt.ueda_group(alpha, A, C, n0, theta0=THETA0), theta_f_predicted=tt.theta_f(alpha, A, C, n0, theta0=THETA0),
                n_full_predicted=tt.full_inversion_spin(alpha, A, C, theta0=THETA0))
    key = row_key(law_name, mu, alpha, gamma, n0, t_end, rtol)
    r = simulate_top(alpha, A, n0, make_law(law_name, mu), t_end, rtol, max_switches=MAP_MAX_SWITCHES, max_wall=MAP_MAX_WALL)
    cut = r.status is pk.Status.FAILED and bool(r.events_named("stick")) and r.t > 2 * r.events_named("stick")[0].t
    if (r.status is pk.Status.FAILED and not cut) or not r.segments:
        return MapRow(key, law_name, mu, alpha, gamma, A, n0, "failed", None, None, None, r.t, r.R_min, 0, 0, None,
                      **pred, jellett_drift=None, status=str(r.status), reason=r.reason or "", wall_s=time.perf_counter() - t0)
    df = r.sample(np.linspace(r.t0, r.t, 4001))
    theta = df["theta"].to_numpy()
    lam0 = tt.jellett_of_vertical_start(alpha, A, C, THETA0, n0)
    drift = float(np.max(np.abs(df["jellett"].to_numpy() - lam0)))
    kinds = [e.name for e in r.events]
    sticks = r.events_named("stick")
    if r.status is pk.Status.STOPPED:
        outcome, t_full = "full", r.t
    else:
        outcome, t_full = ("never" if theta.max() < THETA_NEVER else "partial"), None
    theta_end = float(np.mean(theta[int(0.9 * theta.size):]))
    return MapRow(key, law_name, mu, alpha, gamma, A, n0, outcome, theta_end, float(theta.max()), t_full, r.t, r.R_min,
                  kinds.count("lift-off"), len(sticks), sticks[0].t if sticks else None, **pred, jellett_drift=drift,
                  status=str(r.status), reason=r.reason or "", wall_s=time.perf_counter() - t0)


# -- figures ------------------------------------------------------------------------------------
OUTCOME_STYLE = {"full": ("#1a9850", "o"), "partial": ("#fdae61", "s"), "never": ("#d73027", "x"), "failed": ("k", "?")}


def plot_map(rows: list[MapRow], cfg: dict, path: Path, quick: bool) -> None:
    plt = pyplot()
    laws, spins = cfg["laws"], cfg["spins"]
    fig, axes = plt.subplots(len(laws), len(spins), figsize=(max(4.4 * len(spins) + 1.0, 10.0), 4.0 * len(laws) + 1.2),
                             squeeze=False, sharex=True, sharey=True)
    al = np.linspace(0.0, 0.55, 200)
    ag, gg = np.meshgrid(np.linspace(0.02, 0.55, 160), np.linspace(0.5, 1.6, 160))
    code = {"never": 0, "partial": 1, "full": 2}
    from matplotlib.colors import ListedColormap

    cmap = ListedColormap(["#f4a582", "#fee090", "#a6dba0"])
    for i, (law, mu) in enumerate(laws):
        for j, n0 in enumerate(spins):
            ax = axes[i, j]
            pred = np.vectorize(lambda a, g: code[pk.theory.tippetop.ueda_group(a, g * C, C, n0, theta0=THETA0)])(ag, gg)
            ax.contourf(ag, gg, pred, levels=[-0.5, 0.5, 1.5, 2.5], cmap=cmap, alpha=0.8)
            ax.plot(al, 1 - al, "k--", lw=1)
            ax.plot(al, 1 + al, "k--", lw=1)
            pts = [r for r in rows if r.law == law and r.mu == mu and r.n0 == n0]
            for r in pts:
                color, marker = OUTCOME_STYLE[r.outcome]
                ax.scatter(r.alpha, r.gamma, c=color, marker=marker, s=46, edgecolors="k" if marker != "x" else None,
                           linewidths=0.6, zorder=3)
                if r.outcome != r.predicted and r.outcome != "failed":
                    ax.scatter(r.alpha, r.gamma, facecolors="none", edgecolors="m", s=150, linewidths=1.4, zorder=4)
                if r.n_liftoff:
                    ax.annotate("h", (r.alpha, r.gamma), xytext=(4, 4), textcoords="offset points", fontsize=7, color="b")
                if r.outcome == "partial":
                    ax.annotate(f"{r.theta_end:.2f}", (r.alpha, r.gamma), xytext=(-9, -11), textcoords="offset points",
                                fontsize=5.5, color="0.25")
            ax.set_title(f"{law} $\\mu$={mu:g}, $n_0$={n0:g}", fontsize=10)
            ax.set_xlim(0.0, 0.55)
            ax.set_ylim(0.5, 1.6)
            if i == len(laws) - 1:
                ax.set_xlabel(r"$\alpha$ = OG / radius")
            if j == 0:
                ax.set_ylabel(r"$\gamma = A/C$ (moments about G)")
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(color=c, label=f"predicted {k}") for k, c in zip(("never", "partial", "full"), cmap.colors)]
    handles += [Line2D([], [], color=OUTCOME_STYLE[k][0], marker=OUTCOME_STYLE[k][1], ls="none", label=f"phasekit: {k}")
                for k in ("full", "partial", "never")]
    handles += [Line2D([], [], color="k", ls="--", label=r"classical $\gamma = 1 \pm \alpha$"),
                Line2D([], [], color="m", marker="o", mfc="none", ls="none", ms=10, label="disagrees with prediction"),
                Line2D([], [], color="b", marker="$h$", ls="none", label="hopped (lost contact)"),
                Line2D([], [], color="0.25", marker="$0.0$", ls="none", ms=12, label=r"$\theta$ reached (partial)")]
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle(f"Tippe top spun about the vertical from $\\theta_0$ = {THETA0}, C = {C}: outcome by t = {cfg['t_end']:g}\n"
                 f"markers: phasekit (vector chart, rtol {RTOL:g}); background: tippetop.ueda_group"
                 f"{' [quick run]' if quick else ''}", fontsize=11)
    fig.tight_layout(rect=(0, 0.1, 1, 0.95))
    save_figure(fig, path)


def plot_hopping(r, path: Path) -> dict:
    plt = pyplot()
    ts = np.linspace(r.t0, r.t, 20001)
    df = r.sample(ts)
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    axes[0].plot(ts, df["theta"], "k", lw=1)
    axes[0].axhline(math.pi, color="0.6", ls=":")
    axes[0].set_ylabel(r"$\theta$ (rad)")
    R = np.where(df["mode"] == "flight", np.nan, df["R"])
    axes[1].plot(ts, R, "C0", lw=0.8)
    axes[1].axhline(0.0, color="r", lw=0.8)
    axes[1].set_ylabel(r"$R$ (units $Mg$)")
    axes[2].semilogy(ts, np.where(df["gap"] > 0, df["gap"], np.nan), "C3", lw=1)
    axes[2].set_ylabel("gap (units b)")
    axes[2].set_xlabel(r"$t$ (units $\sqrt{b/g}$)")
    lifts = [e.t for e in r.events_named("lift-off")]
    for t in lifts:
        axes[1].axvline(t, color="r", alpha=0.15, lw=0.6)
    a, A, n0, mu = EXAMPLE["alpha"], EXAMPLE["A"], EXAMPLE["n0"], EXAMPLE["mu"]
    axes[0].set_title(f"Tippe top alpha={a}, A={A}, C={C}, exact Coulomb mu={mu}, n0={n0}: {len(lifts)} lift-offs "
                      f"(red), restitution 0", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path)
    fl = r.flights
    return {"n_liftoff": len(lifts), "first_liftoff": lifts[0] if lifts else None,
            "theta_first_liftoff": float(r.events_named("lift-off")[0].y[4]) if lifts else None,
            "max_gap": max((f.gap_max or 0.0) for f in fl) if fl else 0.0,
            "longest_flight": max(((f.t_touchdown or r.t) - f.t_liftoff) for f in fl) if fl else 0.0,
            "t_inverted": r.t if r.status is pk.Status.STOPPED else None}


def render_inversion(r, path: Path, alpha: float) -> dict:
    """A 3-D scene of one inversion. Left: the path of the axis k(t) drawn on a sphere of radius
    1.3 around the ball's centre (the stem's direction, from the north pole to the south pole),
    coloured by time. Right: the top at six instants side by side on the table (ball, stem along
    +k, centre of mass G in black), each at its computed height (h(theta) + gap)."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    ts = np.linspace(r.t0, r.t, 12000)
    X = r.states(ts)
    k = X[:, 0:3] / np.linalg.norm(X[:, 0:3], axis=1)[:, None]
    df = r.sample(ts)
    zG = (df["h"] + df["gap"]).to_numpy()
    pl = pv.Plotter(off_screen=True, window_size=[1500, 820])
    pl.set_background("white")
    n_snap, dx = 6, 2.7
    x_left = -3.4
    pl.add_mesh(pv.Plane(center=(0.5 * (x_left + (n_snap - 1) * dx), 0.0, 0.0), direction=(0, 0, 1),
                         i_size=(n_snap - 1) * dx - x_left + 3.0, j_size=3.4), color="#e0e0e0")
    centre = np.array([x_left, 0.0, 1.0 + 0.3])
    path_pts = centre + 1.3 * k
    line = pv.lines_from_points(path_pts)
    line["t"] = ts
    pl.add_mesh(line, scalars="t", cmap="viridis", line_width=2.5, scalar_bar_args=dict(title="t (units sqrt(b/g))",
                color="k", vertical=False, position_x=0.05, position_y=0.08, width=0.3, title_font_size=14,
                label_font_size=12))
    pl.add_mesh(pv.Sphere(radius=1.0, center=centre, theta_resolution=48, phi_resolution=48), color="#9ecae1", opacity=0.3)
    pl.add_point_labels([centre + np.array([0.0, 0.0, 1.75])], ["axis k(t)"], font_size=16, text_color="k", shape=None,
                        show_points=False)
    picks = np.linspace(0, len(ts) - 1, n_snap).astype(int)
    for j, i in enumerate(picks):
        ball = np.array([j * dx, 0.0, zG[i]]) + alpha * k[i] * np.array([0.0, 0.0, 1.0])  # the ball's centre O
        G = ball - alpha * k[i]
        pl.add_mesh(pv.Sphere(radius=1.0, center=ball, theta_resolution=48, phi_resolution=48), color="#fdae6b", opacity=0.45)
        pl.add_mesh(pv.Cylinder(center=ball + 1.12 * k[i], direction=k[i], radius=0.13, height=0.3), color="#8c2d04")
        pl.add_mesh(pv.Sphere(radius=0.08, center=G), color="k")
        pl.add_point_labels([np.array([j * dx, 0.0, 2.75])], [f"t={ts[i]:.1f}, theta={df['theta'].iloc[i]:.2f}"], font_size=14,
                            text_color="k", shape=None, show_points=False)
    pl.add_text(f"Tippe top inverting: alpha={alpha}, A={EXAMPLE['A']}, C={C}, exact Coulomb mu={EXAMPLE['mu']}, "
                f"n0={EXAMPLE['n0']:g} (stem = +k, black = G)", font_size=12, color="k", position="upper_left")
    pl.enable_parallel_projection()
    mid = 0.5 * (x_left + (n_snap - 1) * dx)
    pl.camera_position = [(mid, -30.0, 9.0), (mid, 0.0, 1.0), (0, 0, 1)]
    pl.camera.parallel_scale = 5.6
    img = pl.screenshot(str(path), return_img=True)
    pl.close()
    return {"image_std": float(img.std()), "theta_snapshots": [float(df["theta"].iloc[i]) for i in picks]}


# -- the README example: convergence in rtol and eps -----------------------------------------------
def convergence(st) -> list[dict]:
    top = pk.EccentricSphere(0.3, A=0.38, C=C)
    rows = []
    for eps in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, None):
        law = pk.Coulomb(0.3) if eps is None else pk.RegularisedCoulomb(0.3, eps)
        for rtol in (1e-8, 1e-9, 1e-10, 1e-11, 1e-12):
            r = pk.simulate(pk.Model(top, law), pk.vertical_spin_start(THETA0, 15.0), 30.0, rtol=rtol,
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


def summarise(rows: list[MapRow]) -> dict:
    ok = [r for r in rows if r.outcome != "failed"]
    out = {"n_runs": len(rows), "n_failed": len(rows) - len(ok), "max_jellett_drift": max((r.jellett_drift for r in ok), default=None)}
    for law in sorted({r.law for r in ok}):
        sub = [r for r in ok if r.law == law]
        agree = [r for r in sub if r.outcome == r.predicted]
        dis = [r for r in sub if r.outcome != r.predicted]
        out[law] = {"n": len(sub), "agree": len(agree), "disagree": len(dis),
                    "hopped": sum(1 for r in sub if r.n_liftoff), "stuck": sum(1 for r in sub if r.n_stick),
                    "by_outcome": {k: sum(1 for r in sub if r.outcome == k) for k in ("full", "partial", "never")},
                    "disagreements": [f"alpha={r.alpha:g} gamma={r.gamma:g} n0={r.n0:g}: measured {r.outcome} (theta_end "
                                      f"{r.theta_end:.3f}), predicted {r.predicted} (theta_f {r.theta_f_predicted:.3f})"
                                      + (f", stuck at t={r.t_first_stick:.3g}" if r.t_first_stick is not None else "")
                                      for r in dis]}
        partial = [r for r in sub if r.outcome == r.predicted == "partial"]
        if partial:
            out[law]["partial_theta_error_max"] = max(abs(r.theta_end - r.theta_f_predicted) for r in partial)
    return out


def check_rtol(cfg: dict, rows: list[MapRow], n: int) -> list[dict]:
    """Rerun a few points at rtol 1e-12: outcome and theta_end must not move."""
    picks = sorted(rows, key=lambda r: r.key)[:: max(1, len(rows) // n)][:n]
    out = []
    for r in picks:
        q = run_point(r.law, r.mu, r.alpha, r.gamma, r.n0, cfg["t_end"], 1e-12)
        out.append({"point": r.key, "outcome_1e-10": r.outcome, "outcome_1e-12": q.outcome,
                    "theta_end_diff": abs(q.theta_end - r.theta_end)})
    return out


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, resumable=True)
    args = st.parse(argv)
    cfg = QUICK if args.quick else FULL
    conv = convergence(st)
    store = st.store(MapRow, {"config": {k: list(v) if isinstance(v, tuple) else v for k, v in cfg.items()},
                              "rtol": RTOL, "theta0": THETA0, "C": C}, name="tippe_top_map")
    tasks = [(law, mu, a, g, n0) for (law, mu) in cfg["laws"] for n0 in cfg["spins"] for a in cfg["alphas"] for g in cfg["gammas"]
             if g * C >= 0.5 * C]  # C <= 2A
    specs = pk.sweep.each(tasks, lambda *t: row_key(*t, cfg["t_end"], RTOL), lambda *t: run_point(*t, cfg["t_end"], RTOL))
    st.run(specs, store, desc="tippe-top map")
    keys = {s.key for s in specs}
    rows = [r for r in store.rows() if r.key in keys]
    plot_map(rows, cfg, st.path("tippe_top_map.png"), args.quick)
    summary = summarise(rows)
    summary["rtol_check"] = check_rtol(cfg, rows, 3 if args.quick else 8)
    ex = EXAMPLE
    r = simulate_top(ex["alpha"], ex["A"], ex["n0"], pk.Coulomb(ex["mu"]), 200.0, RTOL)
    summary["hopping_example"] = plot_hopping(r, st.path("tippe_top_hopping.png"))
    summary["scene"] = render_inversion(r, st.path("tippe_top_scene.png"), ex["alpha"])
    summary["convergence_t_stop_spread"] = max(c["diff_vs_exact_rtol1e-12"] for c in conv) - min(c["diff_vs_exact_rtol1e-12"] for c in conv)
    summary["wall_s"] = st.wall
    st.json("tippe_top_summary.json", summary)
    print(json.dumps(summary, indent=1, default=str))
    return summary


if __name__ == "__main__":
    pk.sweep.run_study(main)
