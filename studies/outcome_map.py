"""Outcome map: where a start on the sliding branch sticks, rises, or jumps.

For an aspect ratio a, the start is the default definition's (exact Coulomb friction, mu =
0.1, on the sliding, gyroscopic-balance, branch at distance d from the fixed point: theta0 =
pi/2 - d with Omega0 given, prolate; theta0 = d with n0 given, oblate), with d log-spaced
from 1e-3 (starts that stick) to 0.2. Each start is classified:

    stuck  the body stuck (zero slip) and had not completed its rise by t = 3000: it rolls
    rise   the rise completed (theta within 0.1 rad of its final value) without losing contact
    jump   R reached 0 (dR/dt < 0) before that: t* and the share of the rise done then

The boundaries are traced, not read off the grid: the jump threshold Omega0*(d) / n0*(d) by a
bracketed bisection in the family parameter along each d-line (to 1e-3 relative), and the
sticking boundary d_min(Omega0) by a bisection in d along each Omega0-line (to 1e-2
relative). Maps for a = 1.5 and a = 2/3 (figures/outcome_map.png, .csv; the traced points in
outcome_map_boundaries.csv), and a 3-D scene of the jump region over (a, Omega0 or n0, d)
(figures/jump_region.png): its two boundary surfaces, computed on an (a, d) and an
(a, Omega0) grid only, with the jumping starts of the two maps.

Every start runs on heyoka's SIMD batch integrator (starts that stick are followed through
the rolling mode in batch too; see phasekit.core.batch). Dask LocalCluster (or --scheduler),
resumable: finished rows are appended to the CSV files at once and skipped on a rerun.
"""

from __future__ import annotations

import json
from dataclasses import asdict

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_outcome_map, render_jump_region

import numpy as np

STEM = "outcome_map"
BASE = pk.Definition("sliding", "sliding")
D_RANGE = (1e-3, 0.2)
#: threshold searches to 1e-3, d_min to 1e-2; the family parameter from 2x to 12x the lower bound (1.05 x the
#: stability threshold); a value-line is added where d_min changes by more than a factor 2 between neighbours
PLAN = ps.OutcomeMapPlan(BASE, dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5, levels=3),
                               dict(lo=1e-4, hi=0.2, tol=1e-2, n_coarse=8, levels=3), D_RANGE, (2.0, 12.0), steep=2.0, study=STEM)
FULL = dict(maps=[1.5, 2 / 3], n_value=28, n_d=24, d_lines=10, stick_lines=8, refine=3,
            scene_a=[0.5, 0.6, 2 / 3, 0.75, 0.8, 1.2, 1.35, 1.5, 1.75, 2.0, 2.5], scene_d=6, scene_v=5, chunk=48, per_task=8)
QUICK = dict(maps=[1.5, 2 / 3], n_value=10, n_d=8, d_lines=5, stick_lines=4, refine=1,
             scene_a=[0.6, 2 / 3, 0.8, 1.3, 1.5, 2.0], scene_d=4, scene_v=3, chunk=40, per_task=6)


def warm_up() -> None:
    for a in (1.5, 2 / 3):
        BASE.prepare(a, engine="batch")


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, dask=True)
    st.parser.add_argument("--no-scene", action="store_true", help="skip the 3-D scene")
    args = st.parse(argv)
    g = QUICK if args.quick else FULL
    meta = {"definition": asdict(BASE), "threshold_search": PLAN.threshold_search, "stick_search": PLAN.stick_search,
            "d_range": D_RANGE, "value_span": PLAN.value_span, "grid": g,
            "classes": {"stuck": "stuck and not risen by t_max", "rise": "rise completed in contact",
                        "jump": "R = 0 before the rise completed"}}
    out_store = st.store(ps.OutcomeRow, meta)
    search_store = st.store(ps.SearchRow, meta, name=f"{STEM}_boundaries")
    gspecs, grid_keys = PLAN.grid_tasks(g["maps"], n_value=g["n_value"], n_d=g["n_d"], chunk=g["chunk"])
    lines = PLAN.lines(g["maps"], d_first=2e-3, n_d=g["d_lines"], n_value=g["stick_lines"]) | \
        PLAN.lines(g["scene_a"], d_first=4e-3, n_d=g["scene_d"], n_value=g["scene_v"])
    sspecs, members = PLAN.boundary_tasks(lines, per_task=g["per_task"])
    how = str(st.run(gspecs + sspecs, out_store, search_store, members={**grid_keys, **members}, warm_up=warm_up,
                     desc="outcome map"))
    points = out_store.rows(k for ks in grid_keys.values() for k in ks)
    searches = search_store.rows(k for ks in members.values() for k in ks)
    for level in range(g["refine"]):  # each level depends on the last: resumable, since its lines follow from stored rows
        extra = PLAN.corners(searches, g["maps"])
        if not extra:
            break
        rspecs, rmembers = PLAN.boundary_tasks(extra, per_task=g["per_task"])
        members.update(rmembers)
        how += f"; corners of d_min, level {level + 1}: " + str(st.run(rspecs, out_store, search_store, members=members,
                                                                       warm_up=warm_up, desc="outcome map"))
        searches = search_store.rows(k for ks in members.values() for k in ks)
    st.save(plot_outcome_map(points, searches, g["maps"], d_top=D_RANGE[1], title=(
        r"Outcome of sliding-branch starts, exact Coulomb $\mu$ = 0.1, rtol $10^{-9}$; "
        r"thresholds bisected to $10^{-3}$, $d_{min}$ to $10^{-2}$" + (" (quick run)" if args.quick else ""))), f"{STEM}.png")
    counts = {} if args.no_scene else render_jump_region(
        points, searches, st.path("jump_region.png"), scene_a=g["scene_a"], value_range=PLAN.value_range, d_range=D_RANGE,
        threshold_d=np.geomspace(4e-3, D_RANGE[1], g["scene_d"]),
        stick_values=lambda a: np.geomspace(*PLAN.value_range(a), g["scene_v"]), quick=args.quick,
        caption="surfaces: jump threshold {name}*(a, d) (bisected to 1e-3) and sticking\n"
                "boundary d_min(a, {name}) (to 1e-2); sliding-branch starts at distance d,\n"
                f"exact Coulomb mu = {BASE.mu:g}, rtol {BASE.rtol:g}; dots: jumping starts, colour t* (sqrt(b/g))")
    summary = {f"a={a:.4g}": ps.outcome_map_summary(points, searches, a) for a in g["maps"]}
    wall = st.wall
    n_sims = sum(s.n_sims for s in searches) + len(points)
    print(f"\n{STEM}: {len(points)} sampled starts, {len(searches)} traced boundary points; {how}; {wall:.1f} s wall")
    print(ps.outcome_map_report(summary))
    search_store.annotate(summary=summary, scene=counts)
    print(json.dumps({"wall_s": wall, "n_sims": n_sims, "n_points": len(points), "n_searches": len(searches)}))
    return {"points": points, "searches": searches, "summary": summary, "wall_s": wall}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
