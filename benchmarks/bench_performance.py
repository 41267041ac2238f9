"""The speed goals of issue 9, as ratios measured side by side in one run (not timed tests).

1. The default path against scipy BDF on a plain NumPy right-hand side, on the standard
   workload (prolate a = 1.5, mu = 0.1, Coulomb, gyroscopic start theta0 = pi/2 - 0.01,
   Omega0 = 10.5, to the jump), at equal or better t_jump error: goal >= 1000x.
2. The default path against the fastest compiled integrator measured in the same run (the raw
   heyoka propagate on the same compiled Taylor integrator, CVODES BDF and Adams): goal <= 2x.
3. A sticking (rolling) trajectory against a sliding one of the same length: goal <= 3x.
   Rolling: the paper's start (5.2), which sticks at t = 0.011 and rolls; sliding: the
   standard workload. Both to t = 40 (before the standard workload's jump at 45.26).

    python benchmarks/bench_performance.py [--repeats N]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import phasekit as pk
from phasekit.backends import TaylorBackend
from phasekit.baseline import solve_ivp_to_jump
from phasekit.modes import Mode, mode_events


def timed(fn, repeats):
    out, ts = None, []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts), out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=20)
    args = ap.parse_args(argv)
    body = pk.Spheroid(1.5)
    m = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    t_ref = pk.simulate(m, y0, 200.0, rtol=1e-15, track_minima=False).t_jump
    err = lambda tj: abs(tj - t_ref) / t_ref  # noqa: E731

    # 1. scipy BDF on NumPy at rtol 1e-9 (its usual setting), then the default at the loosest
    # tolerance whose error is no worse
    t_sp, (tj_sp, _, nfev) = timed(lambda: solve_ivp_to_jump(y0, 200.0, a=1.5, A=body.A, C=body.C, mu=0.1, rtol=1e-9),
                                   max(1, args.repeats // 10))
    e_sp = err(tj_sp)
    chosen = None
    for rt in (1e-6, 1e-7, 1e-8, 1e-9):
        pk.simulate(m, y0, 200.0, rtol=rt, track_minima=False)
        t_pk, r = timed(lambda: pk.simulate(m, y0, 200.0, rtol=rt, track_minima=False), args.repeats)
        if err(r.t_jump) <= e_sp:
            chosen = (rt, t_pk, err(r.t_jump))
            break
    rt, t_pk, e_pk = chosen
    print("1. default path vs scipy BDF on a NumPy rhs (standard workload)")
    print(f"   scipy BDF rtol 1e-9: {t_sp * 1e3:9.2f} ms, t* error {e_sp:.1e} ({nfev} rhs)")
    print(f"   phasekit rtol {rt:.0e}: {t_pk * 1e3:9.3f} ms, t* error {e_pk:.1e}")
    print(f"   ratio {t_sp / t_pk:.0f}x (goal >= 1000x)")
    # same tolerance, for reference
    t_pk9, r9 = timed(lambda: pk.simulate(m, y0, 200.0, rtol=1e-9, track_minima=False), args.repeats)
    print(f"   (at the same rtol 1e-9: {t_pk9 * 1e3:.3f} ms, error {err(r9.t_jump):.1e}, ratio {t_sp / t_pk9:.0f}x)")

    # 2. fastest compiled integrator in this run, at the default's tolerance 1e-9
    eng = TaylorBackend(m, 1e-9)
    evs = mode_events(m, Mode.SLIDING)
    t_raw, _ = timed(lambda: eng.propagate(Mode.SLIDING, y0, 0.0, 200.0, evs, m.p, max_steps=10**6), args.repeats)
    for be in ("cvodes", "cvodes-adams"):
        pk.simulate(m, y0, 200.0, rtol=1e-9, backend=be, track_minima=False)
    t_bdf, _ = timed(lambda: pk.simulate(m, y0, 200.0, rtol=1e-9, backend="cvodes", track_minima=False), max(1, args.repeats // 4))
    t_ad, _ = timed(lambda: pk.simulate(m, y0, 200.0, rtol=1e-9, backend="cvodes-adams", track_minima=False), max(1, args.repeats // 4))
    fastest = min(t_raw, t_bdf, t_ad)
    print("2. default path vs the fastest compiled integrator (rtol 1e-9)")
    print(f"   raw heyoka propagate {t_raw * 1e3:.3f} ms; CVODES BDF {t_bdf * 1e3:.2f} ms; CVODES Adams {t_ad * 1e3:.2f} ms")
    print(f"   default path {t_pk9 * 1e3:.3f} ms = {t_pk9 / fastest:.2f}x the fastest (goal <= 2x)")

    # 3. rolling against sliding over the same time
    y52 = np.array([7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2])
    pk.simulate(m, y52, 40.0, track_minima=False)
    t_roll, rr = timed(lambda: pk.simulate(m, y52, 40.0, track_minima=False), args.repeats)
    t_slide, rs = timed(lambda: pk.simulate(m, y0, 40.0, track_minima=False), args.repeats)
    assert rr.mode == "rolling" and rr.stuck and rs.mode == "sliding" and not rs.stuck
    print("3. sticking (rolling) against sliding, both to t = 40")
    print(f"   rolling {t_roll * 1e3:.3f} ms ({rr.n_steps} steps); sliding {t_slide * 1e3:.3f} ms ({rs.n_steps} steps); "
          f"ratio {t_roll / t_slide:.2f} (goal <= 3)")


if __name__ == "__main__":
    main()
