"""Benchmark: the threshold sweep engine on the (a, mu) map, serial against a 2-worker Dask
LocalCluster, and the default Fig. 6b,c curves.

In one run (compiled code loaded before any timing, "warm cache"):

1. The (a, mu) map of studies/threshold_vs_mu.py (its --quick grid with --quick): every
   search is an independent task (no continuation chain), each a coarse scan plus k-section
   rounds on heyoka's batch integrator. Printed: the total number of simulations, the
   critical path (the most rounds of mutually dependent simulations any search needed: the
   sweep's depth), the available parallelism (simulations / critical path), the wall time
   serial (this process) and on a LocalCluster of 2 single-threaded workers (cluster start
   excluded, printed separately), and the parallel efficiency serial / (2 x Dask). Both runs
   must give the same thresholds (checked).
2. The default Fig. 6b,c curves: the default definition at the 24 aspect ratios of
   studies/threshold_vs_aspect.py, bisected to 1e-3 (independent searches, 3 per task
   traced in lock-step, k-section with 7 values per round on the batch integrator), on the
   same 2 workers: ``default_curve_wall_s``; also serially. Then, serially, the engine
   variants batch mode and k-section are measured against: one search at a time with the
   scalar engine and plain bisection (the old engine without its chains), batch mode with
   bisection and with k-section, each one search per task or all 24 in lock-step (so that
   the batch lanes fill across searches).

Goals (``goals``, and ``goals_met`` for this run): 2-worker efficiency >= 0.95, parallelism
>= 64, the default curves on 2 workers within 10 s.

    python benchmarks/bench_threshold_sweep.py [--quick] [--json] [--report PATH]

With --json the last line of stdout is one JSON object with the keys simulations,
critical_path, parallelism, wall_serial_s, wall_dask_s, efficiency, default_curve_wall_s, goals,
goals_met (and more); everything else goes to stderr. ``--report PATH`` writes that object
wrapped with the command, date, commit and machine (``docs/data/bench_threshold_sweep.json`` is
the one the docs' performance page reads).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from dataclasses import asdict
from functools import partial

import phasekit as pk
import phasekit.studies as ps

import _report
from _studies import load

GOALS = {"efficiency": 0.95, "parallelism": 64.0, "default_curve_wall_s": 10.0}


def _timed(func, prev, *args):
    """Run a task and measure its CPU time (this process) next to its wall time: on a shared
    machine the difference is the time other jobs took from it."""
    c0, w0 = time.process_time(), time.perf_counter()
    out = func(prev, *args)
    return out, time.process_time() - c0, time.perf_counter() - w0


def run(specs, client=None, pack=None, times=None) -> tuple[dict, float]:
    """Run the tasks (nothing stored), return {row key: row} and the wall time; ``times``
    (a dict) gets the tasks' summed CPU and wall time."""
    timed = [pk.sweep.TaskSpec(s.key, partial(_timed, s.func), s.args, s.after, s.label, s.meta, s.cost) for s in specs]
    t0 = time.perf_counter()
    res = pk.sweep.run_tasks(timed, store_get=lambda k: None, on_result=lambda s, r: None, client=client, pack=pack,
                       progress=False)
    wall = time.perf_counter() - t0
    if times is not None:
        times["task_cpu_s"] = sum(r[1] for r in res.values())
        times["task_wall_s"] = sum(r[2] for r in res.values())
        times["longest_task_s"] = max(r[2] for r in res.values())
    rows = [r[0] for r in res.values()]
    return {x.key: x for rs in rows for x in (rs if isinstance(rs, list) else [rs])}, wall


def default_curve_specs(aspect, engine: str, levels: int, per_task: int):
    """The default definition at the 24 aspect ratios, independent searches, ``per_task``
    of them traced in lock-step per task."""
    search = dict(aspect.SEARCH, levels=levels)
    defn = next(d for d in pk.thresholds.DEFAULT_DEFINITIONS if d.name == aspect.DEFAULT_NAME)
    a_list = aspect.PROLATE + aspect.OBLATE
    jobs = [ps.search_job(asdict(defn), a, search) for a in a_list]
    specs, _ = ps.group_search_tasks(jobs, [1.0 / abs(a - 1.0) for a in a_list], per_task=per_task, study="bench",
                                     engine=engine)
    return specs


def summary(rows: dict) -> dict:
    rows = list(rows.values())
    return {"searches": len(rows), "simulations": sum(r.n_sims for r in rows),
            "critical_path": max(r.n_rounds for r in rows), "task_s": sum(r.wall_s for r in rows),
            "not_converged": sum(r.status != "converged" for r in rows)}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the quick (a, mu) grid of the study")
    ap.add_argument("--json", action="store_true", help="one JSON object on the last line of stdout")
    ap.add_argument("--per-task", type=int, default=1, help="searches per Dask task on the (a, mu) map (default 1)")
    _report.add_argument(ap)
    argv = sys.argv[1:] if argv is None else list(argv)
    args = ap.parse_args(argv)
    if args.per_task < 1:
        ap.error(f"argument --per-task: must be >= 1, got {args.per_task}")
    report = _report.Report(ap, args.report, __file__, argv)
    log = sys.stderr if args.json else sys.stdout
    with contextlib.redirect_stdout(log):
        out = measure(args.quick, log, args.per_task)
    report.finish(out, args.json)
    return out


def measure(quick: bool, log, per_task: int = 1) -> dict:
    mu_study, aspect = load("threshold_vs_mu"), load("threshold_vs_aspect")
    load_avg = os.getloadavg()
    specs, _ = mu_study.build_tasks(quick, "batch", per_task=per_task)
    pack = pk.sweep.ModelPack.build(mu_study.warm_up)  # compile or load everything before timing
    t_serial, t_dask = {}, {}
    serial_rows, wall_serial = run(specs, times=t_serial)
    load_mid = os.getloadavg()
    t0 = time.perf_counter()
    client, cluster = pk.sweep.make_client(workers=2)
    cluster_start = time.perf_counter() - t0
    try:
        client.run(pk.sweep.ModelPack.install, pack)  # the workers get the compiled code before timing
        dask_rows, wall_dask = run(specs, client, pack, times=t_dask)
        load_end = os.getloadavg()
        same = all(serial_rows[k].threshold == dask_rows[k].threshold for k in serial_rows)
        curve_rows, curve_dask = run(default_curve_specs(aspect, "batch", 3, per_task=3), client, pack)
    finally:
        client.close()
        cluster.close()
    m = summary(serial_rows)
    _, curve_serial = run(default_curve_specs(aspect, "batch", 3, per_task=3))
    variants = {}
    for engine, levels, group in (("scalar", 1, 1), ("batch", 1, 1), ("batch", 1, 24), ("batch", 3, 1), ("batch", 3, 24)):
        specs_v = default_curve_specs(aspect, engine, levels, group)
        rows, wall = run(specs_v)
        variants[f"{engine}, levels={levels}, {len(specs_v)} tasks"] = {**summary(rows), "wall_serial_s": wall}
    c = summary(curve_rows)
    res = {
        "simulations": m["simulations"],
        "critical_path": m["critical_path"],
        "parallelism": m["simulations"] / m["critical_path"],
        "wall_serial_s": wall_serial,
        "wall_dask_s": wall_dask,
        "efficiency": wall_serial / (2 * wall_dask),
        "default_curve_wall_s": curve_dask,
        "default_curve_serial_s": curve_serial,
        "default_curve_simulations": c["simulations"],
        "default_curve_critical_path": c["critical_path"],
        "cluster_start_s": cluster_start,
        "searches": m["searches"],
        "not_converged": m["not_converged"],
        "same_thresholds_serial_and_dask": same,
        "engine_variants_default_curve": variants,
        "grid": "quick" if quick else "full",
        "tasks": len(specs),
        "searches_per_task": per_task,
        "serial_task_times": t_serial,
        "dask_task_times": t_dask,
        "efficiency_cpu": t_serial["task_cpu_s"] / (2 * wall_dask),
        "load_average_at_start": load_avg,
        "load_average_after_serial": load_mid,
        "load_average_after_dask": load_end,
        "cpu_count": os.cpu_count(),
        "goals": GOALS,
    }
    res["goals_met"] = {"efficiency": res["efficiency"] >= GOALS["efficiency"],
                        "parallelism": res["parallelism"] >= GOALS["parallelism"],
                        "default_curve_wall_s": curve_dask <= GOALS["default_curve_wall_s"]}
    print(f"\n=== threshold sweep benchmark ({res['grid']} (a, mu) grid: {m['searches']} searches) ===", file=log)
    print(f"simulations {res['simulations']}, critical path {res['critical_path']} rounds, "
          f"parallelism {res['parallelism']:.0f} (goal >= {GOALS['parallelism']:g})", file=log)
    print(f"wall serial {wall_serial:.1f} s, Dask 2 workers {wall_dask:.1f} s (cluster start {cluster_start:.1f} s more): "
          f"efficiency {res['efficiency']:.2f} (goal >= {GOALS['efficiency']}); same thresholds: {same}", file=log)
    print(f"default Fig. 6b,c curves (24 a, bisection to 1e-3): {curve_dask:.1f} s on 2 workers (goal <= {GOALS['default_curve_wall_s']:g} s), "
          f"{curve_serial:.1f} s serial; {c['simulations']} simulations, critical path {c['critical_path']} rounds", file=log)
    for k, v in variants.items():
        print(f"  default curve, {k:<30s}: {v['simulations']:4d} simulations, critical path {v['critical_path']:2d} rounds, "
              f"serial {v['wall_serial_s']:.1f} s", file=log)
    print(f"tasks: {len(specs)} of {per_task} search(es); serial: task CPU {t_serial['task_cpu_s']:.1f} s, "
          f"task wall {t_serial['task_wall_s']:.1f} s; Dask: task CPU {t_dask['task_cpu_s']:.1f} s, task wall "
          f"{t_dask['task_wall_s']:.1f} s, longest task {t_dask['longest_task_s']:.1f} s", file=log)
    print(f"load average (1 min) at start {load_avg[0]:.2f}, after the serial run {load_mid[0]:.2f}, after the Dask run "
          f"{load_end[0]:.2f}, on {os.cpu_count()} cores", file=log)
    print("goals met: " + ", ".join(f"{k} {'yes' if v else 'NO'}" for k, v in res["goals_met"].items()), file=log)
    return res


if __name__ == "__main__":
    main()
