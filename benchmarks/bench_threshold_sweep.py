"""Benchmark: the threshold study serial against Dask LocalCluster with 2 workers.

Runs studies/threshold_vs_aspect.py twice from scratch (--fresh) into temporary directories,
in this process (serial) and on a LocalCluster of 2 single-threaded workers, and prints both
wall times, the speed-up and simulations per second. Compilation happens once, before the
timing (both runs load the compiled integrators from the caches).

    python benchmarks/bench_threshold_sweep.py [--quick]
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def load_study():
    spec = importlib.util.spec_from_file_location("threshold_vs_aspect", ROOT / "studies" / "threshold_vs_aspect.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["threshold_vs_aspect"] = mod
    spec.loader.exec_module(mod)
    return mod


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="time the --quick study instead of the default one")
    args = ap.parse_args(argv)
    study = load_study()
    extra = ["--quick"] if args.quick else []
    study.warm_up()  # compile (or load) everything once, outside both timings
    out = {}
    for label, opts in (("serial", ["--serial"]), ("dask-2", ["--workers", "2"])):
        with tempfile.TemporaryDirectory() as tmp:
            res = study.main(["--fresh", "--no-progress", "--out", tmp, *opts, *extra])
        out[label] = res
    s, d = out["serial"], out["dask-2"]
    print("\n=== threshold study benchmark" + (" (quick)" if args.quick else " (default)") + " ===")
    for label, r in out.items():
        print(f"{label:>7s}: wall {r['wall_s']:7.1f} s, {r['n_sims']} simulations, {r['n_sims'] / r['wall_s']:.1f} simulations/s")
    print(f"speed-up dask-2 / serial = {s['wall_s'] / d['wall_s']:.2f}x")


if __name__ == "__main__":
    main()
