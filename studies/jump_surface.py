"""Figure 6a: the jump surface (6.3) with trajectories in (Omega, theta, n), rendered off-screen.

Prolate a = 1.5 and oblate a = 2/3, Coulomb mu = 0.1: trajectories started next to the
horizontal steady precession (prolate) or the vertical spin (oblate), on the sliding branch at
distance 0.01 (the default threshold definition; the literal eigenvector seed sticks, see
README), ending where R = 0 (black points). Surface: (6.3) coloured by n; green wireframe: the
exact boundary R = 0 of (6.1) at the median |Lambda| of the crossings (at Lambda = 0 it is (6.3)).

Also tabulates, for more Omega0 values, the relative error in n of (6.3) at each crossing
(crossings only: no dense output), and measures whether that error has a trend in the start
value: a log-log fit over 41 log-spaced starts per branch (11 with --quick) from 10 (prolate)
or 9 (oblate) to 40, for the seed distances d = 0.005, 0.01, 0.02, split into its two factors:
the error is (A/C) h_tt Lambda*^2 / (Omega* h_theta sin theta* n*), the Lambda^2 term that
(6.3) drops, so it is set by the nutation rate Lambda* at the crossing.

Writes jump_surface.png (prolate), jump_surface_oblate.png, jump_surface.csv (the table),
jump_surface_trend.csv (the fit's crossings), and with --gltf / --html an interactive export
of the prolate scene.
"""

from __future__ import annotations

import sys

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import render_jump_surface

import numpy as np

ALL = frozenset({"surface", "exact_boundary", "trajectories", "crossings", "fixed_points", "axes", "colorbar"})
#: starts of the error table: (branch, a, Omega0 or n0 values)
TABLE = (("prolate", 1.5, (10.0, 11.0, 12.5, 15.0, 17.5, 20.0, 25.0, 30.0, 40.0)),
         ("oblate", 2 / 3, (9.0, 10.0, 12.5, 15.0, 17.5, 20.0, 25.0, 30.0, 40.0)))
#: the trend fit: seed distances d of the sliding-branch starts, and the range of the starts
TREND_D = (0.005, 0.01, 0.02)
TREND_RANGE = {"prolate": (1.5, 10.0, 40.0), "oblate": (2 / 3, 9.0, 40.0)}


def render(scenes, st, bar) -> tuple[dict, list]:
    """Compute and draw each scene (Fig. 6a); the exports asked for that could not be written."""
    infos, missing = {}, []
    for stem, sc in scenes.items():
        data = pk.compute_scene(sc)
        exports = {"gltf": st.args.gltf, "html": st.args.html} if stem == "jump_surface" else {}
        info, miss = render_jump_surface(data, st.path(f"{stem}.png"), **exports)
        infos[stem] = (data, info)
        missing += miss
        bar.update()
    return infos, missing


def trend(starts, bar) -> tuple[list, list]:
    """Fits over many starts per (branch, d): of the error, of its geometric factor
    error / Lambda*^2, and of |Lambda*|."""
    rows, fits = [], []
    for branch, (a, lo, hi) in TREND_RANGE.items():
        values = np.round(np.geomspace(lo, hi, starts), 4)
        for d in TREND_D:
            cs = ps.surface_crossings(branch, a, values, d, bar=bar)
            rows += [(branch, a, d, c.value, c.t, c.Omega, c.theta, c.n, c.Lambda, c.rel_error) for c in cs]
            fits.append((branch, d, len(cs), len(values), *ps.crossing_trend(cs)))
    return rows, fits


def report(infos, table, fits, starts) -> None:
    for stem, (data, info) in infos.items():
        print(f"Figure {stem}.png: {data.scene.branch} a = {data.scene.a:g}; {data.n_simulations} trajectories; "
              f"points drawn {info.n_points}")
    print("\nrelative error in n of (6.3) at the simulated crossing (R = 0, dR/dt < 0):")
    print(f"{'branch':<8s} {'start':>6s} {'t_cross':>8s} {'theta*':>7s} {'n*':>8s} {'Lambda*':>8s} {'rel err':>9s}")
    for row in table:
        print(f"{row[0]:<8s} {row[2]:6.1f} {row[3]:8.2f} {row[5]:7.4f} {row[6]:8.4f} {row[7]:8.4f} {row[9]:9.2e}")
    for branch in ("prolate", "oblate"):
        rows = [r for r in table if r[0] == branch]
        slope = ps.loglog_fit([r[2] for r in rows], [r[9] for r in rows])[0]
        print(f"{branch}: log-log trend of the error against the start value: slope {slope:.2f} "
              f"(these {len(rows)} starts only; see the fit below)")
    print(f"\nfit over {starts} log-spaced starts per branch and seed distance d: log-log slope of the error against "
          "the start value (+- standard error, r: correlation), and of its factors error/Lambda*^2 and |Lambda*|")
    print(f"{'branch':<8s} {'d':>5s} {'jumps':>7s} {'min err':>8s} {'median':>8s} {'max err':>8s} {'slope':>13s} {'r':>6s} "
          f"{'err/L^2':>8s} {'|L*|':>6s}")
    for br, d, n, m, lo, med, hi, s, se, r, s_geo, s_lam in fits:
        print(f"{br:<8s} {d:5.3f} {n:3d}/{m:<3d} {lo:8.1e} {med:8.1e} {hi:8.1e} {s:+6.2f} +- {se:4.2f} {r:+6.2f} {s_geo:+8.2f} {s_lam:+6.2f}")


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="coarser surface, every other start in the error table, 11 starts in the fit")
    st.parser.add_argument("--gltf", action="store_true", help="also write jump_surface.gltf (the prolate scene)")
    st.parser.add_argument("--html", action="store_true", help="also write jump_surface.html (needs the trame packages)")
    args = st.parse(argv)
    res, starts = (60, 11) if args.quick else (140, 41)
    scenes = {
        "jump_surface": pk.Scene("prolate", 1.5, values=(10.0, 12.0, 15.0, 20.0, 30.0), show=ALL, resolution=res),
        "jump_surface_oblate": pk.Scene("oblate", 2 / 3, values=(9.0, 10.0, 12.0, 15.0, 20.0), show=ALL, resolution=res),
    }
    table_starts = [(branch, a, vals[::2] if args.quick else vals) for branch, a, vals in TABLE]
    n_runs = len(scenes) + sum(len(v) for *_, v in table_starts) + starts * len(TREND_RANGE) * len(TREND_D)
    with st.progress(total=n_runs, desc="scenes and crossings") as bar:
        infos, missing = render(scenes, st, bar)
        table = [(branch, a, c.value, c.t, c.Omega, c.theta, c.n, c.Lambda, c.n_surface, c.rel_error)
                 for branch, a, vals in table_starts for c in ps.surface_crossings(branch, a, vals, bar=bar)]
        trend_rows, fits = trend(starts, bar)
    st.csv("jump_surface.csv", ["branch", "a", "start", "t_cross", "Omega", "theta", "n", "Lambda", "n_63", "rel_error_n"], table)
    st.csv("jump_surface_trend.csv", ["branch", "a", "d", "start", "t_cross", "Omega", "theta", "n", "Lambda", "rel_error_n"],
           trend_rows)
    report(infos, table, fits, starts)
    print(f"{st.wall:.1f} s")
    if missing:  # asked for, not written: say so and fail (after everything else was written)
        sys.stderr.write(f"error: the {' and '.join(missing)} export could not be written (--html needs the trame packages)\n")
        raise SystemExit(1)
    return {"infos": infos, "table": table, "fits": fits}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
