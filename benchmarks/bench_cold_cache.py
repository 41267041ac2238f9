"""The main study from an empty compile cache against the same run with the cache warm, and how
many times each integrator was compiled.

``studies/threshold_vs_aspect.py --fresh`` runs twice in fresh processes sharing one new cache
directory (``$PHASEKIT_CACHE``): first empty (every integrator compiled: the Dask workers and the
main process share each build through a lock on its file), then warm (everything loaded). Goal
(issue 45): the cold run within 1.3 times the warm one, each integrator compiled once on the
machine (the cache's build log, ``builds.log``, has one line per build). Whole-command wall
times, so run this alone; about 5 minutes on 2 cores.

    python benchmarks/bench_cold_cache.py [--json] [--report PATH]

``--report PATH`` writes the report wrapped with the command, date, commit and machine
(``docs/data/bench_cold_cache.json`` is the one the docs' performance page reads).
"""

from __future__ import annotations

import argparse
import collections
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import _report

STUDY = _report.ROOT / "studies" / "threshold_vs_aspect.py"
GOALS = {"cold_over_warm": 1.3, "builds_per_integrator": 1}


def timed_study(cache: str, out: str) -> float:
    """Wall time of the main study from scratch (``--fresh``) with ``cache`` as its compile cache."""
    env = {**os.environ, "PHASEKIT_CACHE": cache, "MPLBACKEND": "Agg"}
    t0 = time.perf_counter()
    run = subprocess.run([sys.executable, str(STUDY), "--fresh", "--out", out, "--no-progress"], capture_output=True,
                         text=True, env=env, timeout=3600)
    wall = time.perf_counter() - t0
    if run.returncode != 0:
        raise SystemExit(f"bench_cold_cache: the study failed ({run.returncode}): {run.stderr.strip()[-400:]}")
    return wall


def builds(cache: str) -> list[tuple[str, str]]:
    """(integrator file, what) for each build the cache's log records."""
    log = Path(cache) / "builds.log"
    lines = log.read_text().splitlines() if log.is_file() else []
    return [(f[0], f[3]) for f in (line.split("\t") for line in lines) if len(f) == 4]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout, the report on stderr")
    _report.add_argument(ap)
    args = ap.parse_args(argv)
    report = _report.Report(ap, args.report, __file__, sys.argv[1:] if argv is None else argv)
    stream = sys.stderr if args.json else sys.stdout
    with tempfile.TemporaryDirectory(prefix="phasekit-cold-") as tmp:
        cache = os.path.join(tmp, "cache")
        cold = timed_study(cache, os.path.join(tmp, "cold"))
        cold_builds = builds(cache)
        warm = timed_study(cache, os.path.join(tmp, "warm"))
        warm_builds = builds(cache)[len(cold_builds):]
    per_file = collections.Counter(f for f, _ in cold_builds)
    kinds = collections.Counter(what.replace(", in the background,", "") for _, what in cold_builds)
    result = {"cold_s": cold, "warm_s": warm, "cold_over_warm": cold / warm, "integrators": len(per_file),
              "builds": len(cold_builds), "most_builds_of_one_integrator": max(per_file.values(), default=0),
              "builds_by_kind": dict(kinds), "builds_when_warm": len(warm_builds), "goals": GOALS}
    result["goals_met"] = {"cold_over_warm": result["cold_over_warm"] <= GOALS["cold_over_warm"],
                           "builds_per_integrator": result["most_builds_of_one_integrator"] <= GOALS["builds_per_integrator"]}
    print(f"main study --fresh: empty cache {cold:.1f} s, warm cache {warm:.1f} s, ratio {cold / warm:.2f} "
          f"(goal <= {GOALS['cold_over_warm']})", file=stream)
    print(f"{len(cold_builds)} builds of {len(per_file)} integrators (most builds of one: "
          f"{result['most_builds_of_one_integrator']}); with the cache warm: {len(warm_builds)}", file=stream)
    for what, k in sorted(kinds.items()):
        print(f"  {k:3d}  {what}", file=stream)
    report.finish(result, args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
