"""The speed goals of issues 9, 14 and 31, as ratios measured side by side in one run (not timed tests).

Standard workload: prolate a = 1.5, mu = 0.1, Coulomb (exact stick-slip), gyroscopic start
theta0 = pi/2 - 0.01, Omega0 = 10.5, to the jump (t* = 45.256). phasekit is timed two ways:
the *sweep path* (``dense=False, track_minima=False``: what the threshold sweeps run, t* only)
and the *default options* of ``pk.simulate`` (dense output kept for ``traj.sample`` and every
minimum of R located, from the expansion of the integral of R that the integrator carries: the same
steps as the sweep path, docs/results/performance.md#the-default-path).

1. phasekit against scipy BDF on a plain NumPy right-hand side, at equal or better t* error:
   goal >= 1000x (the sweep path; the default options are printed beside it).
2. phasekit against the bare heyoka propagate on the same compiled Taylor integrator
   (``pk.baseline.taylor_integrator(model, rtol=1e-9, track_minima=False)``, ``propagate_until`` to
   the lift-off event, stopping only to renew the scales at every time unit as phasekit does: the
   same steps, the same t* to the last bit), both at rtol 1e-9: goal <= 1.35x for the sweep path,
   which is the one compared with bare heyoka (same integrator, same events); the default
   options' ratio and CVODES BDF and Adams are printed for reference.
   The default options against the sweep path, both at rtol 1e-9 and from this section: goal
   <= 2.0 (``ratio_default_sweep``). Each path is timed interleaved with bare heyoka, in two
   consecutive blocks, not with each other (a default-options run allocates its dense output,
   MBs, which slows the run after it); the same ratio through bare heyoka,
   ``ratio_default_bare_heyoka / ratio_sweep_bare_heyoka``, is printed beside it as a check on
   a change of load between the blocks.
3. A sticking (rolling) trajectory against a sliding one of the same length: goal <= 3x.
   Rolling: the paper's start (5.2), which sticks at t = 0.011 and rolls; sliding: the
   standard workload. Both to t = 40 (before the standard workload's jump), sweep path.
4. Friction over a contact patch against the point contact, the same body and start: the standard
   workload's sliding run to t = 40 under ``pk.Contensou(0.1, 0.005)`` (a patch of 0.1 mm on a body of
   b = 20 mm) and under ``pk.Coulomb(0.1)``, sweep path: goal <= 3x.

Timings: the median and the best of ``--repeats`` runs, the runs of the compared methods
interleaved so that a change in machine load hits both sides alike. On a shared machine the
best run is the better estimate of the intrinsic cost (other processes only ever add time, as
the timeit documentation notes); both ratios are printed, and a goal is reported met only
when the median ratio meets it.

    python benchmarks/bench_performance.py [--repeats N] [--json] [--report PATH]

With ``--json`` the report goes to stderr and stdout holds one JSON object with the ratios;
``--report PATH`` writes that object wrapped with the command, date, commit and machine
(``docs/data/bench_performance.json`` is the one the docs' performance page reads).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import threading
import time

import phasekit as pk
from phasekit.core.engines.scaling import next_rescale, next_scales

import _report
import heyoka as hy
import numpy as np

SWEEP = dict(dense=False, track_minima=False)
GOALS = {"scipy_bdf": 1000.0, "bare_heyoka": 1.35, "default_sweep": 2.0, "rolling_sliding": 3.0, "patch_point": 3.0}


class Timing(float):
    """A median wall time (the float value) that also carries the best run (``.best``)."""

    def __new__(cls, runs):
        t = super().__new__(cls, statistics.median(runs))
        t.best = min(runs)
        return t


def timed(fns: dict, repeats: int) -> tuple[dict, dict]:
    """Wall time of each callable over ``repeats`` interleaved rounds (after one untimed
    warm-up call each), and each one's last result."""
    out = {k: f() for k, f in fns.items()}
    # a warm-up run compiles the other contact mode in the background (phasekit's compile-ahead):
    # with a cold cache that compilation would take a core from the timed runs
    for thread in threading.enumerate():
        if thread.name == "phasekit-prefetch":
            thread.join()
    times = {k: [] for k in fns}
    for _ in range(repeats):
        for k, f in fns.items():
            t0 = time.perf_counter()
            out[k] = f()
            times[k].append(time.perf_counter() - t0)
    return {k: Timing(v) for k, v in times.items()}, out


def ms(t: Timing) -> str:
    return f"{t * 1e3:.3f} ms (best {t.best * 1e3:.3f})"


def bare_heyoka(model, y0, rtol):
    """The compiled Taylor integrator of the sliding mode, driven directly: the same integration as
    phasekit's (its scales renewed at every time unit, phasekit/core/engines/scaling.py) in the
    smallest loop that does it, so that the ratio is phasekit's own cost."""
    ta, pars = pk.baseline.taylor_integrator(model, rtol=rtol, track_minima=False, x0=y0)
    start, n = np.array(ta.state), len(y0)  # y0 in the integrator's scaled variables
    state, scales = ta.state[:n], ta.pars[len(pars) - n:]

    def run():
        ta.time = 0.0
        ta.state[:] = start
        ta.pars[:] = pars
        ta.reset_cooldowns()
        while True:
            out = ta.propagate_until(min(200.0, next_rescale(ta.time)))
            if out[0] != hy.taylor_outcome.time_limit or ta.time >= 200.0:
                return out
            x = state * scales
            scales[:] = next_scales(x, scales)
            state[:] = x / scales

    return ta, run


def scipy_vs_phasekit(model, body, y0, err, repeats, say) -> dict:
    t_sp, res = timed({"bdf": lambda: pk.baseline.solve_ivp_to_jump(y0, 200.0, a=body.a, A=body.A, C=body.C, mu=0.1, rtol=1e-9)},
                      max(1, min(3, repeats // 10)))
    t_sp, tj_sp, nfev = t_sp["bdf"], res["bdf"].t_jump, res["bdf"].n_rhs
    e_sp = err(tj_sp)
    # the loosest tolerance whose t* error is no worse than scipy's
    for rt in (1e-6, 1e-7, 1e-8, 1e-9):
        if err(pk.simulate(model, y0, 200.0, rtol=rt, **SWEEP).t_jump) <= e_sp:
            break
    t, r = timed({"sweep": lambda: pk.simulate(model, y0, 200.0, rtol=rt, **SWEEP)}, repeats)
    td, rd = timed({"default": lambda: pk.simulate(model, y0, 200.0, rtol=rt)}, repeats)
    t.update(td)
    r.update(rd)
    say("1. phasekit vs scipy BDF on a NumPy rhs (standard workload, to the jump)")
    say(f"   scipy BDF rtol 1e-9:                      {t_sp * 1e3:9.2f} ms, t* error {e_sp:.1e} ({nfev} rhs)")
    say(f"   phasekit rtol {rt:.0e}, sweep path:          {t['sweep'] * 1e3:9.3f} ms, t* error {err(r['sweep'].t_jump):.1e}"
        f"  ratio {t_sp / t['sweep']:.0f}x (goal >= {GOALS['scipy_bdf']:.0f}x; best runs {t_sp.best / t['sweep'].best:.0f}x)")
    say(f"   phasekit rtol {rt:.0e}, default options:     {t['default'] * 1e3:9.3f} ms, t* error {err(r['default'].t_jump):.1e}"
        f"  ratio {t_sp / t['default']:.0f}x (dense output + minima of R; best runs {t_sp.best / t['default'].best:.0f}x)")
    return {"scipy_bdf_ms": t_sp * 1e3, "scipy_bdf_error": e_sp, "phasekit_rtol": rt, "sweep_ms": t["sweep"] * 1e3,
            "default_ms": t["default"] * 1e3, "ratio_scipy_bdf_sweep": t_sp / t["sweep"],
            "ratio_scipy_bdf_sweep_best": t_sp.best / t["sweep"].best,
            "ratio_scipy_bdf_default": t_sp / t["default"]}


def bare_vs_phasekit(model, y0, err, repeats, say) -> dict:
    ta, bare = bare_heyoka(model, y0, 1e-9)
    # each phasekit path interleaved with bare heyoka on its own: a default-options run
    # allocates its dense output (MBs), which would slow whichever run comes next
    t, r = timed({"bare": bare, "sweep": lambda: pk.simulate(model, y0, 200.0, rtol=1e-9, **SWEEP)}, repeats)
    t_bare_jump = float(ta.time)
    td, rd = timed({"bare": bare, "default": lambda: pk.simulate(model, y0, 200.0, rtol=1e-9)}, repeats)
    t["default"], r["default"] = td["default"], rd["default"]
    if abs(t_bare_jump - r["sweep"].t_jump) > 1e-12 * t_bare_jump:  # the same integration, or the ratio means nothing
        raise RuntimeError(f"bare heyoka stopped at t = {t_bare_jump!r}, phasekit's jump is at {r['sweep'].t_jump!r}")
    cv, _ = timed({be: (lambda be=be: pk.simulate(model, y0, 200.0, rtol=1e-9, backend=be, **SWEEP))
                   for be in ("cvodes", "cvodes-adams")}, max(1, repeats // 4))
    say("2. phasekit vs the bare heyoka propagate on the same compiled integrator (rtol 1e-9, to the jump)")
    say(f"   bare heyoka propagate_until {ms(t['bare'])} (t* = {t_bare_jump:.9f}, error {err(t_bare_jump):.1e})")
    say(f"   sweep path      {ms(t['sweep'])} = {t['sweep'] / t['bare']:.2f}x bare heyoka (best runs: "
        f"{t['sweep'].best / t['bare'].best:.2f}x; goal <= {GOALS['bare_heyoka']}x; this is the compared one)")
    say(f"   default options {ms(t['default'])} = {t['default'] / td['bare']:.2f}x bare heyoka (best runs: "
        f"{t['default'].best / td['bare'].best:.2f}x; dense output + minima of R; {r['default'].n_steps} steps against "
        f"{r['sweep'].n_steps})")
    via_bare = (t["default"] / td["bare"]) / (t["sweep"] / t["bare"])
    say(f"   default options / sweep path {t['default'] / t['sweep']:.2f} (best runs {t['default'].best / t['sweep'].best:.2f}; "
        f"goal <= {GOALS['default_sweep']}; through bare heyoka {via_bare:.2f})")
    say(f"   for reference: CVODES BDF {cv['cvodes'] * 1e3:.2f} ms, CVODES Adams {cv['cvodes-adams'] * 1e3:.2f} ms (sweep path)")
    return {"bare_heyoka_ms": t["bare"] * 1e3, "sweep_rtol1e-9_ms": t["sweep"] * 1e3, "default_rtol1e-9_ms": t["default"] * 1e3,
            "ratio_sweep_bare_heyoka": t["sweep"] / t["bare"], "ratio_default_bare_heyoka": t["default"] / td["bare"],
            "ratio_sweep_bare_heyoka_best": t["sweep"].best / t["bare"].best,
            "ratio_default_bare_heyoka_best": t["default"].best / td["bare"].best,
            "ratio_default_sweep": t["default"] / t["sweep"], "ratio_default_sweep_best": t["default"].best / t["sweep"].best,
            "ratio_default_sweep_via_bare_heyoka": via_bare,
            "cvodes_bdf_ms": cv["cvodes"] * 1e3, "cvodes_adams_ms": cv["cvodes-adams"] * 1e3}


def paired(t: dict, r: dict, a: str, b: str, goal: str, title: str, say, keys: tuple[str, str, str, str]) -> dict:
    """One section's report: the runs ``a`` and ``b`` timed side by side and their ratio (goal
    ``goal``), as ``keys``: a's and b's times (ms), the median ratio and the best runs' ratio."""
    say(title)
    say(f"   {a} {ms(t[a])} ({r[a].n_steps} steps); {b} {ms(t[b])} ({r[b].n_steps} steps); "
        f"ratio {t[a] / t[b]:.2f} (best runs {t[a].best / t[b].best:.2f}; goal <= {GOALS[goal]:g})")
    return dict(zip(keys, (t[a] * 1e3, t[b] * 1e3, t[a] / t[b], t[a].best / t[b].best)))


def rolling_vs_sliding(model, y0, repeats, say) -> dict:
    y52 = np.array([7e-5, 2e-6, 10.5, -1e-4, np.pi / 2 - 1e-3, 2e-2])
    t, r = timed({"rolling": lambda: pk.simulate(model, y52, 40.0, **SWEEP),
                  "sliding": lambda: pk.simulate(model, y0, 40.0, **SWEEP)}, repeats)
    rr, rs = r["rolling"], r["sliding"]
    if not (rr.mode == "rolling" and rr.stuck and rs.mode == "sliding" and not rs.stuck):
        raise RuntimeError(f"the workloads changed: rolling run ends {rr.mode} (stuck {rr.stuck}), sliding run ends {rs.mode}")
    return paired(t, r, "rolling", "sliding", "rolling_sliding", "3. sticking (rolling) against sliding, both to t = 40 (sweep path)",
                  say, ("rolling_ms", "sliding_ms", "ratio_rolling_sliding", "ratio_rolling_sliding_best"))


def patch_vs_point(body, y0, repeats, say) -> dict:
    point, patch = pk.Model(body, pk.Coulomb(0.1)), pk.Model(body, pk.Contensou(0.1, 0.005))
    t, r = timed({"patch": lambda: pk.simulate(patch, y0, 40.0, **SWEEP),
                  "point": lambda: pk.simulate(point, y0, 40.0, **SWEEP)}, repeats)
    rp, rc = r["patch"], r["point"]
    if not (rp.t == rc.t == 40.0):
        raise RuntimeError(f"the workloads changed: the patch run ends at {rp.t} ({rp.status}), the point at {rc.t}")
    return paired(t, r, "patch", "point", "patch_point",
                  "4. friction over a contact patch against the point contact, the sliding run to t = 40 (sweep path)", say,
                  ("patch_ms", "point_ms", "ratio_patch_point", "ratio_patch_point_best"))


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter, allow_abbrev=False)
    ap.add_argument("--repeats", type=int, default=50, help="timed runs per method (default 50; scipy BDF: a tenth, at most 3)")
    ap.add_argument("--json", action="store_true", help="report on stderr; stdout: one JSON object with the ratios")
    _report.add_argument(ap)
    argv = sys.argv[1:] if argv is None else list(argv)
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error(f"argument --repeats: must be >= 1, got {args.repeats}")
    report = _report.Report(ap, args.report, __file__, argv)
    stream = sys.stderr if args.json else sys.stdout
    say = lambda line: print(line, file=stream, flush=True)  # noqa: E731

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    t_ref = pk.simulate(model, y0, 200.0, rtol=1e-15, **SWEEP).t_jump
    err = lambda tj: abs(tj - t_ref) / t_ref  # noqa: E731
    say(f"standard workload: reference t* = {t_ref:.12f} (Taylor, rtol 1e-15); median (and best) of {args.repeats} "
        f"interleaved runs; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    out = {"t_ref": t_ref, "repeats": args.repeats}
    out.update(scipy_vs_phasekit(model, body, y0, err, args.repeats, say))
    out.update(bare_vs_phasekit(model, y0, err, args.repeats, say))
    out.update(rolling_vs_sliding(model, y0, args.repeats, say))
    out.update(patch_vs_point(body, y0, args.repeats, say))
    out["goals"] = GOALS
    out["load_average"] = os.getloadavg()[0]
    out["goals_met"] = goals_met(out, "")
    out["goals_met_best_runs"] = goals_met(out, "_best")
    say("goals met (median): " + ", ".join(f"{k} {'yes' if v else 'NO'}" for k, v in out["goals_met"].items())
        + "; on the best runs: " + ", ".join(f"{k} {'yes' if v else 'NO'}" for k, v in out["goals_met_best_runs"].items()))
    report.finish(out, args.json)
    return out


def goals_met(out: dict, runs: str) -> dict:
    """Each goal against its median ratio (``runs=""``) or the ratio of the best runs (``"_best"``)."""
    return {"scipy_bdf": out[f"ratio_scipy_bdf_sweep{runs}"] >= GOALS["scipy_bdf"],
            "bare_heyoka": out[f"ratio_sweep_bare_heyoka{runs}"] <= GOALS["bare_heyoka"],
            "default_sweep": out[f"ratio_default_sweep{runs}"] <= GOALS["default_sweep"],
            "rolling_sliding": out[f"ratio_rolling_sliding{runs}"] <= GOALS["rolling_sliding"],
            "patch_point": out[f"ratio_patch_point{runs}"] <= GOALS["patch_point"]}


if __name__ == "__main__":
    pk.scaffold.run_study(main, resume="nothing was written; run it again")
