"""Benchmark: one trajectory to the jump, phasekit against scipy BDF on a NumPy right-hand side.

Standard workload (issues 2 and 9): prolate a = 1.5, mu = 0.1, Coulomb friction, gyroscopic
start theta0 = pi/2 - 0.01, Omega0 = 10.5. Both run at rtol 1e-9 in the same process; the
error of each t_jump is measured against phasekit at rtol 1e-13 (checked against CVODES at
rtol 1e-12). Prints times, errors and the speed ratio. Not a test: timings live here.

    python benchmarks/bench_jump.py [--repeats N]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import phasekit as pk
from phasekit.baseline import solve_ivp_to_jump


def median_time(fn, repeats):
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args(argv)
    body = pk.Spheroid(1.5)
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    model = pk.Model(body, pk.Coulomb(0.1))

    ref = pk.simulate(model, y0, 200.0, rtol=1e-13, track_minima=False).t_jump
    check = pk.simulate(model, y0, 200.0, rtol=1e-12, backend="cvodes", track_minima=False).t_jump
    pk.simulate(model, y0, 200.0, track_minima=False)  # compile (or load) once, outside the timing

    t_pk, r = median_time(lambda: pk.simulate(model, y0, 200.0, rtol=1e-9, track_minima=False), args.repeats)
    t_sp, (tj_sp, _, nfev) = median_time(
        lambda: solve_ivp_to_jump(y0, 200.0, a=1.5, A=body.A, C=body.C, mu=0.1, method="BDF", rtol=1e-9),
        max(1, args.repeats // 2),
    )
    print(f"reference t_jump (phasekit rtol 1e-13) = {ref:.12f}; CVODES rtol 1e-12 differs by {abs(check - ref):.2e}")
    print(f"phasekit default ({r.backend}), rtol 1e-9: {t_pk * 1e3:9.2f} ms   t_jump error {abs(r.t_jump - ref):.2e}")
    print(f"scipy BDF, NumPy rhs, rtol 1e-9:     {t_sp * 1e3:9.2f} ms   t_jump error {abs(tj_sp - ref):.2e}  ({nfev} rhs)")
    print(f"speed ratio scipy/phasekit = {t_sp / t_pk:.0f}x")


if __name__ == "__main__":
    main()
