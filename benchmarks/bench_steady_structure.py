"""Benchmark: the steady-state structure of one body, and the atlas of classes on the sweep engine.

In one run (compiled functions built before any timing, "warm"):

1. ``pk.steady_structure`` for a displaced spheroid, a tippe top and an egg under viscous and
   exact Coulomb friction (branches, ends, stability along them with located changes, statics,
   families): the median of 5 calls each, and against the pointwise way a user took before
   it: ``pk.fixed_points`` at 200 values of Omega0 (which gives states, not the branches'
   ends nor where stability changes). Goal: every structure well under a second.
2. The atlases of studies/steady_structure.py at its committed resolution (or --quick): the
   grid of signatures (independent tasks) and the bisection of the class boundaries (one task
   per chunk of edges; it needs the grid: critical path 2 phases), serial in this process and
   on a LocalCluster of 2 single-threaded workers (cluster start excluded, printed). Printed:
   bodies, tasks, parallelism (tasks of the larger phase / 1), wall times, the 2-worker
   efficiency serial / (2 x Dask); both runs must give the same signatures (checked).

   Goal (``goals``, and ``goals_met`` for this run): the atlas's 2-worker efficiency >= 0.85.

    python benchmarks/bench_steady_structure.py [--quick] [--json] [--report PATH]

With --json the last line of stdout is one JSON object (structure_wall_s, atlas_wall_serial_s,
atlas_wall_dask_s, efficiency, parallelism, goals, goals_met, ...); everything else goes to
stderr. ``--report PATH`` writes that object wrapped with the command, date, commit and machine
(``docs/data/bench_steady_structure.json`` is the one the docs' performance page reads).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time

import phasekit as pk

import _report
import numpy as np
from _studies import load

BODIES = {"spheroid a=1.5 offset=0.2": lambda: pk.Spheroid(1.5, offset=0.2),
          "tippe top 0.3, A/C 0.95": lambda: pk.EccentricSphere(0.3, A=0.38, C=0.4),
          "egg 1.3, w=0.05": lambda: pk.Egg(1.3, 0.05)}
LAWS = {"viscous 0.1": lambda: pk.Viscous(0.1), "coulomb 0.1": lambda: pk.Coulomb(0.1)}
GOALS = {"efficiency": 0.85}


def time_structures() -> dict:
    out = {}
    for bname, make_body in BODIES.items():
        body = make_body()
        for lname, make_law in LAWS.items():
            law = make_law()
            pk.steady_structure(body, law)  # warm: compiled functions
            times = []
            for _ in range(5):
                t0 = time.perf_counter()
                s = pk.steady_structure(body, law)
                times.append(time.perf_counter() - t0)
            model = pk.Model(body, law)
            oms = np.geomspace(0.5, 20.0, 200)
            pk.fixed_points(model, omega0=float(oms[0]))
            t0 = time.perf_counter()
            n_states = sum(len(pk.fixed_points(model, omega0=float(w))) for w in oms)
            pointwise = time.perf_counter() - t0
            out[f"{bname}, {lname}"] = {"structure_s": float(np.median(times)), "signature": s.signature,
                                        "samples": int(sum(b.theta.size for b in s.branches)),
                                        "pointwise_200_s": pointwise, "pointwise_states": n_states,
                                        "ratio_pointwise_over_structure": pointwise / float(np.median(times))}
    return out


def atlas_specs(study, quick: bool):
    g = study.QUICK if quick else study.FULL
    pts = study.grid_points(g)
    specs = [pk.sweep.TaskSpec(f"atlas|{i}", study.signatures, (pts[i:i + g["chunk"]],), cost=1.0)
             for i in range(0, len(pts), g["chunk"])]
    return g, pts, specs


def run(specs, client=None) -> tuple[list, float]:
    t0 = time.perf_counter()
    res = pk.sweep.run_tasks(specs, store_get=lambda k: None, on_result=lambda s, r: None, client=client, progress=False)
    return [row for rows in res.values() for row in rows], time.perf_counter() - t0


def edge_specs(study, rows, g):
    edges = study.boundary_edges(rows)
    return [pk.sweep.TaskSpec(f"edges|{i}", study.trace, (edges[i:i + 40], g["xtol"]), cost=1.0)
            for i in range(0, len(edges), 40)]


def measure(quick: bool, log) -> dict:
    study = load("steady_structure")
    load_avg = os.getloadavg()
    structures = time_structures()
    g, pts, specs = atlas_specs(study, quick)
    rows_serial, grid_serial = run(specs)
    especs = edge_specs(study, rows_serial, g)
    bounds_serial, edges_serial = run(especs)
    t0 = time.perf_counter()
    client, cluster = pk.sweep.make_client(workers=2)
    cluster_start = time.perf_counter() - t0
    try:
        client.run(lambda: study.structure_at("tippe-top", 0.3, 0.95))  # warm the workers' compiled functions
        rows_dask, grid_dask = run(specs, client)
        _, edges_dask = run(especs, client)
    finally:
        client.close()
        cluster.close()
    same = sorted((r.key, r.signature) for r in rows_serial) == sorted((r.key, r.signature) for r in rows_dask)
    worst = max(v["structure_s"] for v in structures.values())
    res = {
        "structure_wall_s": structures,
        "structure_worst_s": worst,
        "bodies": len(pts),
        "grid_tasks": len(specs),
        "edge_tasks": len(especs),
        "boundary_points": len(bounds_serial),
        "parallelism": max(len(specs), len(especs)),
        "critical_path_phases": 2,
        "atlas_wall_serial_s": grid_serial + edges_serial,
        "atlas_wall_dask_s": grid_dask + edges_dask,
        "grid_wall_serial_s": grid_serial,
        "grid_wall_dask_s": grid_dask,
        "edges_wall_serial_s": edges_serial,
        "edges_wall_dask_s": edges_dask,
        "efficiency": (grid_serial + edges_serial) / (2 * (grid_dask + edges_dask)),
        "same_signatures_serial_and_dask": same,
        "cluster_start_s": cluster_start,
        "grid": "quick" if quick else "full",
        "load_average_at_start": load_avg,
        "load_average_at_end": os.getloadavg(),
        "cpu_count": os.cpu_count(),
        "goals": GOALS,
    }
    res["goals_met"] = {"efficiency": res["efficiency"] >= GOALS["efficiency"]}
    print(f"\n=== steady-state structure benchmark ({res['grid']} atlas) ===", file=log)
    for k, v in structures.items():
        print(f"  {k:<42s} {v['structure_s'] * 1e3:7.1f} ms  ({v['samples']} samples, {v['signature']}); 200 pointwise "
              f"fixed_points calls {v['pointwise_200_s'] * 1e3:7.1f} ms (x{v['ratio_pointwise_over_structure']:.1f})", file=log)
    print(f"worst structure {worst:.3f} s (goal: well under 1 s)", file=log)
    print(f"atlas: {len(pts)} bodies in {len(specs)} tasks, {len(bounds_serial)} boundary points in {len(especs)} tasks; "
          f"serial {res['atlas_wall_serial_s']:.1f} s, Dask 2 workers {res['atlas_wall_dask_s']:.1f} s (cluster start "
          f"{cluster_start:.1f} s more): efficiency {res['efficiency']:.2f} (goal >= {GOALS['efficiency']}); same signatures: {same}", file=log)
    print(f"load average (1 min) at start {load_avg[0]:.2f}, at the end {res['load_average_at_end'][0]:.2f}, on "
          f"{os.cpu_count()} cores", file=log)
    return res


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the quick atlas grid of the study")
    ap.add_argument("--json", action="store_true", help="one JSON object on the last line of stdout")
    _report.add_argument(ap)
    argv = sys.argv[1:] if argv is None else list(argv)
    args = ap.parse_args(argv)
    report = _report.Report(ap, args.report, __file__, argv)
    log = sys.stderr if args.json else sys.stdout
    with contextlib.redirect_stdout(log):
        out = measure(args.quick, log)
    report.finish(out, args.json)
    return out


if __name__ == "__main__":
    main()
