"""Euler's disk to its end: the exponents of its finite-time singularity under each dissipation law.

Question. A thin disk spinning on its rim falls to its face faster and faster. Moffatt (2000,
Nature 404, 833) put the loss in the air layer under the disk and found the tilt falling as
(t0 - t)^(1/3) and the precession rate growing as (t0 - t)^(-1/6). What do phasekit's laws give,
run to the end rather than assumed quasi-static, and where does each model stop being valid?

What is run. pk.Disk(0.0) (a thin uniform disk, A = 1/4, C = 1/2), launched spinning in place at
theta = 30 deg (G at rest, the contact point rolling round the rim: Omega = 1/sqrt(A sin theta),
n = 0), exact Coulomb friction mu = 10 (high enough to roll: the drift off spinning in place
needs up to |F|/R ~ 4), the Euler chart, rtol 1e-10, dense output, to face down (theta = 1e-3)
or t_end, with each law alone: the air layer (pk.friction.AirLayer, k = 1e-4), rolling resistance
(delta = 0.01; mu = 1000, the largest accepted, so that it rolls to the end, and face down at
theta = 1e-6: theta ~ (t0 - t)^2 needs the deeper end for two decades of t0 - t), spin friction
(mu_s = 0.02), and sliding (mu = 0.1, the rim slipping at the start: an extra spin 0.5 about
the axis). Fits: log(theta) and log(Omega) against log(t0 - t) on
a window of t0 - t (fractions of t0) with t0 extrapolated (the end that makes the log-log line
straightest) and, for comparison, t0 = the face-down time; 95% intervals from the regression's
standard error. Closed forms: the energy balance on the spin-in-place manifold (docs/physics.md).

Outputs:
  euler_disk.json              every run's numbers (the fits, t0 against the quasi-static one,
                               the largest |F|/R, the lowest R, the energy balance)
  euler_disk_table.csv         the docs' table
  euler_disk_exponents.png     log-log theta and Omega against t0 - t with the fitted lines
  euler_disk.gif               the air-layer disk's last 30 time units, to face down, with R(t)
"""

from __future__ import annotations

import json
import math

import phasekit as pk
from phasekit.studies.euler_disk import THIN, disk_report, end_curves, plot_exponents, run_disk
from phasekit.viz import animate

RTOL = 1e-10
#: law -> (coefficient, mu, t_end, window of t0 - t as fractions of t0, extra spin, max_steps, face-down angle)
FULL = {"air-layer": (1e-4, 10.0, 1e4, (3e-3, 0.3), 0.0, 2_000_000, 1e-3),
        "rolling-resistance": (0.01, 1000.0, 1e4, (1e-3, 0.3), 0.0, 2_000_000, 1e-6),
        "spin-friction": (0.02, 10.0, 3000.0, None, 0.0, 2_000_000, 1e-3),
        "sliding": (0.0, 0.1, 300.0, None, 0.5, 2_000_000, 1e-3)}
QUICK = {"air-layer": FULL["air-layer"], "rolling-resistance": (0.05, 1000.0, 1e3, (1e-3, 0.3), 0.0, 400_000, 1e-6),
         "spin-friction": (0.2, 10.0, 100.0, None, 0.0, 200_000, 1e-3), "sliding": (0.0, 0.1, 50.0, None, 0.5, 200_000, 1e-3)}
MAX_WALL = 120.0


def _num(x) -> str:
    return "none (no finite-time end)" if x is None else f"{x:.6g}"


def _cell(x) -> str:
    return "" if x is None else f"{x:.6g}"


def _fit(f) -> str:
    return "" if f is None else f"{f['exponent']:.4f} +- {f['ci95']:.4f}"


def table(reports: dict) -> list[list]:
    rows = []
    for law, r in reports.items():
        rows.append([law, f"{r['coefficient']:g}", f"{r['mu']:g}", r["status"], f"{r['t_end']:.6g}",
                     "" if r.get("t0_fit") is None else f"{r['t0_fit']:.6g}", _cell(r["t0_quasi_static"]),
                     _fit(r.get("fit_theta")), _fit(r.get("fit_omega")),
                     "" if r.get("expected") is None else f"{r['expected'][0]:.4g} / {r['expected'][1]:.4g}",
                     "" if r.get("decades") is None else f"{r['decades']:.2f}", f"{r['max_friction_ratio']:.3g}",
                     f"{r['R_min']:.3g}", f"{r['residual_max']:.1e}"])
    return rows


HEADER = ["law", "coefficient", "mu", "status", "end (face down or t_end)", "t0 fitted", "t0 quasi-static (empty: no end)",
          "theta exponent (95%)", "Omega exponent (95%)", "closed form", "decades fitted", "max |F| over R", "min R",
          "energy residual (largest along the run)"]


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="a larger rolling resistance and shorter runs of the laws with no end")
    st.parser.add_argument("--json", action="store_true", help="print the numbers as JSON on stdout (nothing else)")
    args = st.parse(argv)
    cfg = QUICK if args.quick else FULL
    reports, curves, runs = {}, {}, {}
    for law, (coef, mu, t_end, window, spin, steps, flat) in cfg.items():
        traj = runs[law] = run_disk(law, coef, mu, t_end=t_end, rtol=RTOL, max_steps=steps, max_wall=MAX_WALL, spin=spin,
                                    flat_angle=flat)
        rep = disk_report(traj, law, coef, mu, window=window or (0.03, 0.9))
        rep["spin_extra"] = spin
        reports[law] = rep
        curves[law] = end_curves(traj, rep.get("t0_fit", traj.t))
    title = (f"Thin disk (A = {THIN.A:g}, C = {THIN.C:g}) launched spinning in place at 30 deg, exact Coulomb, rtol "
             f"{RTOL:g}; fits with t0 extrapolated, 95% intervals; grey: the fitted lines over their windows, dotted: the "
             f"closed-form slopes\nBelow its window the air-layer disk falls over from theta ~ 0.04 (Omega collapses, R "
             f"falls to 0.2); spin friction stops the spin about the vertical and sliding sticks: the disk then rolls on "
             f"with no loss" + (" [quick run]" if args.quick else ""))
    st.save(plot_exponents(curves, reports, title=title), "euler_disk_exponents.png")
    st.csv("euler_disk_table.csv", HEADER, table(reports))
    out = {"rtol": RTOL, "config": json.loads(json.dumps(cfg)), "runs": reports,
           "max_energy_residual": max(r["residual_max"] for r in reports.values())}  # no wall time: rerun, same bytes
    st.json("euler_disk.json", out)
    air = runs["air-layer"]
    animate(air, st.path("euler_disk.gif"), frames=6 if args.quick else 60, fps=12, t_span=(max(air.t0, air.t - 30.0), air.t),
            window_size=(360, 300), panel="R", progress=st.show and not args.json,
            title=f"Euler's disk, air layer k = {cfg['air-layer'][0]:g}: its end")
    if args.json:
        print(json.dumps(out, default=str))
        return out
    for law, r in reports.items():
        print(f"{law:19s} {r['status']:9s} end {r['t_end']:9.4f}  t0 fit {r.get('t0_fit', math.nan):9.4f}  "
              f"quasi-static {_num(r['t0_quasi_static']):>9s}  theta {_fit(r.get('fit_theta')):18s} Omega "
              f"{_fit(r.get('fit_omega')):18s} max|F|/R {r['max_friction_ratio']:.3g}  min R {r['R_min']:.3g}  "
              f"residual {r['residual']:.1e} (largest along the run {r['residual_max']:.1e})")
    print(f"wall {st.wall:.0f} s")
    return out


if __name__ == "__main__":
    pk.scaffold.run_study(main)
