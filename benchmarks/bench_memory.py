"""Peak memory of a run, and the cost of the dissipation laws' bookkeeping (measured in one run).

1. Memory. Each measurement runs in a fresh process (``ru_maxrss`` is a process's peak): the
   standard workload (prolate a = 1.5, mu = 0.1, Coulomb, gyroscopic start theta0 = pi/2 - 0.01,
   Omega0 = 10.5, to the jump, default options); the dense output held per million Taylor steps
   (tracemalloc, a gyroscopic run of a = 1.5, theta0 = 1.5607963, Omega0 = 11 with ``stop_at="none"``,
   no cap) and the energy tally held in its place once ``max_dense_mb`` is passed; and a long run
   of that start (``--steps``, default 10 million Taylor steps; 1 million with ``--quick``) with the
   default options, an air drag law and 1001 ``t_eval`` times, against a run of a tenth of its
   steps: its peak resident memory, goal <= 2 GB, with its samples, events and energy budget.
2. The dissipation laws' bookkeeping: ``phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0
   1.5607963 --omega0 11 --stop-at none --t-end 10000 --max-wall 2`` with ``--air-drag 1e-6``,
   without it, and with ``--air-drag 0`` (the bookkeeping with a law that takes nothing), in one
   process, interleaved: the simulated time reached per second of each, as ratios (goal <= 1.5),
   and each command's wall time (the run and the work after it: the energy budget, the poses)
   against --max-wall (goal: within 10% with a dissipation law, the worst of the rounds).

    python benchmarks/bench_memory.py [--quick] [--steps N] [--repeats N] [--json] [--report PATH]
"""

from __future__ import annotations

import argparse
import io
import json
import resource
import subprocess
import sys
import time
import tracemalloc
from contextlib import redirect_stdout

import _report
import numpy as np

GOALS = {"long_run_peak_mb": 2000.0, "bookkeeping": 1.5, "wall_overrun": 0.10}
STEPS_PER_TIME = 42.6  # Taylor steps per time unit of the long run (measured: 269 588 steps to t = 6329)
CLI = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "11",
       "--stop-at", "none", "--t-end", "10000", "--max-wall", "2", "--json"]


def _rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KB on Linux


def _long_start(drag: bool):
    import phasekit as pk

    body = pk.Spheroid(1.5)
    law = pk.Coulomb(0.1).with_dissipation(pk.AirDrag(rotation=1e-6)) if drag else pk.Coulomb(0.1)
    return pk.Model(body, law), pk.gyroscopic_start(body, 1.5607963, omega0=11.0)


def child_standard(_=None) -> dict:
    import phasekit as pk

    body = pk.Spheroid(1.5)
    model, x0 = pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    pk.simulate(model, x0, 200.0)  # compiled (or loaded) first
    tracemalloc.start()
    traj = pk.simulate(model, x0, 200.0)
    traced = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return {"steps": traj.n_steps, "traced_peak_kb": traced[1] / 1e3, "held_kb": traced[0] / 1e3, "peak_rss_mb": _rss_mb()}


def child_per_step(t_end: float) -> dict:
    import phasekit as pk

    model, x0 = _long_start(False)
    pk.simulate(model, x0, 1.0, stop_at="none")
    out = {}
    for name, cap in (("dense", None), ("tally", 1.0)):
        tracemalloc.start()
        traj = pk.simulate(model, x0, t_end, stop_at="none", max_dense_mb=cap, max_wall=3600)
        held = tracemalloc.get_traced_memory()[0]
        tracemalloc.stop()
        out[f"{name}_mb_per_million_steps"] = held / traj.n_steps
        out["steps"] = traj.n_steps
        del traj
    for name, cap in (("dense", None), ("tally", 1.0)):  # timed without tracemalloc (which slows numpy's allocations)
        out[f"{name}_wall_s"] = pk.simulate(model, x0, t_end, stop_at="none", max_dense_mb=cap, max_wall=3600).wall_s
    out["ratio_tally_dense_wall"] = out["tally_wall_s"] / out["dense_wall_s"]  # the tally, paid in the run
    return out


def child_long(steps: int) -> dict:
    import phasekit as pk

    model, x0 = _long_start(True)
    t_end = steps / STEPS_PER_TIME
    te = np.linspace(0.0, t_end, 1001)
    t = time.perf_counter()
    traj = pk.simulate(model, x0, t_end, stop_at="none", t_eval=te, max_wall=7200, max_steps=2 * steps, progress=False)
    budget = traj.energy_budget()
    return {"steps": traj.n_steps, "status": traj.status.value, "t": traj.t, "samples": int(len(traj.ts)),
            "samples_finite": bool(np.isfinite(traj.ys).all()), "events": len(traj.events),
            "energy_residual_max": budget.residual_max, "dropped": any(s.tally for s in traj.segments),
            "wall_s": time.perf_counter() - t, "peak_rss_mb": _rss_mb()}


def child_bookkeeping(repeats: int) -> dict:
    from phasekit.cli import main

    variants = {"without": [], "drag": ["--air-drag", "1e-6"], "zero": ["--air-drag", "0"]}
    rate, overrun = {k: [] for k in variants}, {k: [] for k in variants}
    for _ in range(repeats + 1):
        for name, extra in variants.items():
            buf = io.StringIO()
            t = time.perf_counter()
            with redirect_stdout(buf):
                main([*CLI, *extra])
            wall = time.perf_counter() - t
            out = json.loads(buf.getvalue())
            rate[name].append(out["t_end"] / out["wall_s"])
            overrun[name].append(wall / 2.0 - 1.0)  # the whole command: inputs, model, run, and the work after it
    med = {k: float(np.median(v[1:])) for k, v in rate.items()}  # the first round compiles
    return {"t_per_s": med, "ratio_drag": med["without"] / med["drag"], "ratio_zero": med["without"] / med["zero"],
            "wall_overrun": {k: float(np.max(v[1:])) for k, v in overrun.items()}, **_uncapped()}


def _uncapped() -> dict:
    """The work after the drag command's run, left uncapped (as it was before --max-wall counted it)."""
    import phasekit as pk

    model, x0 = _long_start(True)
    traj = pk.simulate(model, x0, 10000.0, stop_at="none", max_wall=2.0)
    t = time.perf_counter()
    d = traj.to_dict()
    wall = time.perf_counter() - t
    return {"post_run_uncapped_s": wall, "post_run_uncapped_steps": traj.n_steps,
            "post_run_uncapped_overrun": wall / 2.0, "post_run_uncapped_has_budget": d["energy_budget"] is not None}


def _child(kind: str, arg) -> dict:
    p = subprocess.run([sys.executable, __file__, "--child", kind, str(arg)], capture_output=True, text=True, check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a long run of 1 million steps (default 10 million)")
    ap.add_argument("--steps", type=int, default=None, help="Taylor steps of the long run")
    ap.add_argument("--repeats", type=int, default=3, help="rounds of the bookkeeping commands")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    _report.add_argument(ap)
    args = ap.parse_args(argv)
    if args.child:
        fn = {"standard": child_standard, "per_step": child_per_step, "long": child_long, "bookkeeping": child_bookkeeping}
        print(json.dumps(fn[args.child[0]](float(args.child[1]) if args.child[0] == "per_step" else int(args.child[1]))))
        return 0
    rep = _report.Report(ap, args.report, __file__, sys.argv[1:] if argv is None else argv)
    steps = args.steps or (1_000_000 if args.quick else 10_000_000)
    r = {"standard": _child("standard", 0), "per_step": _child("per_step", 3000.0)}
    r["long"] = _child("long", steps)
    r["tenth"] = _child("long", steps // 10)
    r["bookkeeping"] = _child("bookkeeping", args.repeats)
    r["long_run_peak_mb"] = r["long"]["peak_rss_mb"]
    r["ratio_long_tenth_rss"] = r["long"]["peak_rss_mb"] / r["tenth"]["peak_rss_mb"]
    r["ratio_bookkeeping"] = r["bookkeeping"]["ratio_drag"]
    r["wall_overrun"] = max(r["bookkeeping"]["wall_overrun"][k] for k in ("drag", "zero"))  # with a dissipation law
    r["goals"] = GOALS
    r["goals_met"] = {"long_run_peak_mb": r["long_run_peak_mb"] <= GOALS["long_run_peak_mb"]
                      and r["long"]["samples_finite"],
                      "bookkeeping": r["ratio_bookkeeping"] <= GOALS["bookkeeping"],
                      "wall_overrun": r["wall_overrun"] <= GOALS["wall_overrun"]}
    rep.write(r)
    print(json.dumps(r, indent=1) if args.json else r)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
