"""The first run of every built-in body, with empty caches: what a new user waits for.

Each body's ``phasekit simulate`` command, as a user types it, is run in a fresh process with an
empty cache directory (``$PHASEKIT_CACHE``, which also holds heyoka's object code), so it compiles
its integrators; then once more in a fresh process, which loads them. Times are the whole command
(interpreter start, imports, compiling, the run, the output). Goal (issue 31): every first run
within 5 s on a quiet 2-core machine, and a line on stderr for any compilation over a second (the
report counts those lines). The first run is not a ratio: run this alone.

    python benchmarks/bench_first_run.py [--json] [--report PATH]

With ``--json`` the report goes to stderr and stdout holds one JSON object; ``--report PATH``
writes it wrapped with the command, date, commit and machine
(``docs/data/bench_first_run.json`` is the one the docs' performance page reads).
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

import _report

#: each built-in body's command (the egg's is issue 31's, in SI units)
BODIES = {
    "spheroid": "--body spheroid --a 1.5 --mu 0.1 --gyroscopic --theta0 1.2 --omega0 8 --t-end 10",
    "tippe top": "--body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --theta0 0.1 --spin-about-vertical 15 --t-end 10",
    "tippe top, ball alone": "--body tippe-top --stem-length 0 --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --theta0 0.1 "
                             "--spin-about-vertical 15 --t-end 10",
    "egg": "--body egg --a 1.33333 --mu 0.2 --gyroscopic --theta0 '89.4 deg' --omega0 '25 rev/s' --size '22.5 mm' --si "
           "--t-end '10 s'",
    "disk": "--body disk --mu 0.3 --gyroscopic --theta0 1.2 --omega0 8 --t-end 10",
    "cone": "--body cone --mu 0.3 --gyroscopic --theta0 1.2 --omega0 8 --t-end 10",
}
GOALS = {"first_s": 5.0}


def timed_run(args: str, cache: str) -> tuple[float, str]:
    """Wall time of ``phasekit simulate ARGS`` in a new process with ``cache`` as its cache, and its stderr."""
    env = {**os.environ, "PHASEKIT_CACHE": cache}
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "phasekit", "simulate", *shlex.split(args)], capture_output=True, text=True,
                         env=env, timeout=900)
    wall = time.perf_counter() - t0
    if out.returncode != 0:
        raise SystemExit(f"bench_first_run: `phasekit simulate {args}` failed: {out.stderr.strip()}")
    return wall, out.stderr


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout, the report on stderr")
    _report.add_argument(ap)
    args = ap.parse_args(argv)
    report = _report.Report(ap, args.report, __file__, sys.argv[1:] if argv is None else argv)
    stream = sys.stderr if args.json else sys.stdout
    bodies = {}
    for name, cmd in BODIES.items():
        with tempfile.TemporaryDirectory(prefix="phasekit-first-run-") as cache:
            first, err = timed_run(cmd, cache)
            second, _ = timed_run(cmd, cache)
        compiled = [float(s) for s in re.findall(r"phasekit: compiled in ([\d.]+) s", err)]
        bodies[name] = {"command": f"phasekit simulate {cmd}", "first_s": first, "second_s": second,
                        "notices": err.count("phasekit: compiling"), "longest_noticed_compile_s": max(compiled, default=0.0)}
        print(f"{name:24s} first run {first:5.2f} s, second {second:5.2f} s, {bodies[name]['notices']} compile notices",
              file=stream, flush=True)
    worst = max(b["first_s"] for b in bodies.values())
    result = {"bodies": bodies, "worst_first_s": worst, "goals": GOALS, "goals_met": {"first_s": worst <= GOALS["first_s"]}}
    print(f"slowest first run {worst:.2f} s (goal <= {GOALS['first_s']:g} s: {'met' if worst <= GOALS['first_s'] else 'NOT met'})",
          file=stream, flush=True)
    report.finish(result, args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
