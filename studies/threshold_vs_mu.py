"""Jump thresholds over (aspect ratio a, friction coefficient mu), both branches.

For each (a, mu): the smallest Omega0 (prolate) / n0 (oblate) whose trajectory loses contact
before its rise completes, under the default definition (exact Coulomb friction, starts on
the sliding branch at d = 0.01) with mu from 0.02 to 0.5 (7 values, log-spaced by 5^(1/3),
including the paper's 0.1). Each threshold is an independent search (coarse scan of 8
values over [1.05 x the stability threshold, 120], then bisection to 1e-3 relative by
k-section: 7 values per round on heyoka's SIMD batch integrator). At a = 1.5 and 2/3 the
seed distance d is varied (0.0025 ... 0.04) at every mu, to see whether a d-independent
limit of the threshold exists. The collapse test: does one factor f(mu) map every curve
threshold(a) onto the mu = 0.1 one? f is fitted (geometric mean over a) and the spread
that remains is reported.

Runs on Dask (LocalCluster with one worker per core, or --scheduler ADDRESS), the compiled
models shipped once; resumable: every finished search is appended to threshold_vs_mu.csv at
once (manifest .json). Writes threshold_vs_mu.png.
"""

from __future__ import annotations

import json
from dataclasses import asdict, replace
from functools import partial

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_threshold_map

STEM = "threshold_vs_mu"
SEARCH = dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5, levels=3)
MU = [float(0.1 * 5.0 ** (k / 3)) for k in range(-3, 4)]  # 0.02 ... 0.5, log-spaced, with 0.1
PROLATE = [1.1, 1.2, 1.3, 1.5, 1.75, 2.0, 2.5, 3.0]
OBLATE = [0.3, 0.4, 0.5, 0.6, 2 / 3, 0.75, 0.8, 0.9]
D_LINES = {"a": [1.5, 2 / 3], "d": [0.0025, 0.005, 0.01, 0.02, 0.04]}
QUICK = dict(mu=[0.02, 0.1, 0.5], prolate=[1.2, 1.5, 2.0], oblate=[0.5, 2 / 3, 0.8],
             d_lines={"a": [1.5], "d": [0.005, 0.01, 0.02]}, d_mu=[0.02, 0.5])
BASE = pk.Definition("sliding", "sliding")
MU_REF = 0.1


def grid(quick: bool) -> dict:
    if quick:
        return dict(mu=QUICK["mu"], a=QUICK["prolate"] + QUICK["oblate"], d_lines=QUICK["d_lines"], d_mu=QUICK["d_mu"])
    return dict(mu=MU, a=PROLATE + OBLATE, d_lines=D_LINES, d_mu=MU)


def definitions(quick: bool) -> list[tuple[pk.Definition, float]]:
    """(definition, a) of every search: the (a, mu) map at d = 0.01 and the d-lines."""
    g = grid(quick)
    out = [(replace(BASE, mu=mu), a) for mu in g["mu"] for a in g["a"]]
    for mu in g["d_mu"]:
        for a in g["d_lines"]["a"]:
            out += [(replace(BASE, mu=mu, amplitude=d), a) for d in g["d_lines"]["d"] if d != BASE.amplitude]
    return out


def build_tasks(quick: bool, engine: str, per_task: int | None = None):
    """Independent tasks of several searches each (traced in lock-step, so that the batch
    integrator's lanes fill across searches); the cost estimate (slower rise at small mu,
    longer scans near a = 1) groups similar searches and orders the Dask queue longest
    first. Returns the tasks and the row keys of each."""
    jobs, costs = [], []
    for defn, a in definitions(quick):
        # at the paper's mu the threshold's sensitivity to d (d/2 and 2d) is measured too
        sens = defn.mu == MU_REF and defn.amplitude == BASE.amplitude
        jobs.append(ps.search_job(asdict(defn), a, SEARCH, sensitivity=sens))
        # measured: the slow rise at small mu and the stick-slip chatter near the end of the
        # rise at large mu are the costly searches, and scans near a = 1 are long
        costs.append(((MU_REF / defn.mu) ** 0.5 + defn.mu / MU_REF) * (1.0 + 0.2 / abs(a - 1.0)) * (3 if sens else 1))
    # One search per task by default: a few chattering searches cost as much as all the others
    # (measured: one group of 10 took 36% of the map), so lock-step groups unbalance the workers.
    per_task = per_task or 1
    return ps.group_search_tasks(jobs, costs, per_task=per_task, study=STEM, engine=engine)


def warm_up(engine: str = "batch") -> None:
    """Compile (or load) every integrator the sweep uses, so the pack carries them (the batch
    ones only for the batch engine)."""
    for a in (1.5, 2 / 3):
        BASE.prepare(a, engine=engine)


def report(rows, g, coll, dl, wall, mode, n_new) -> dict:
    print(f"\n{STEM}: {len(rows)} searches ({n_new} computed now, {mode}), {wall:.1f} s wall")
    print("\n".join(ps.threshold_map_report(rows, g["mu"], coll, dl, d0=BASE.amplitude, mu_ref=MU_REF)))
    n_sims = sum(r.n_sims for r in rows)
    return {"n_sims": n_sims, "task_s": sum(r.wall_s for r in rows), "critical_path": max((r.n_rounds for r in rows), default=0)}


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, dask=True)
    st.parser.add_argument("--engine", default="batch", choices=("batch", "scalar"), help="simulations in batch (default) or one by one")
    st.parser.add_argument("--per-task", type=st.parser.integer(min=1), default=None,
                           help="searches per Dask task, traced in lock-step (default 1)")
    args = st.parse(argv)
    g = grid(args.quick)
    specs, members = build_tasks(args.quick, args.engine, args.per_task)
    store = st.store(ps.SearchRow, {
        "search": SEARCH, "definition": asdict(BASE), "mu": g["mu"], "a": g["a"], "d_lines": g["d_lines"], "d_mu": g["d_mu"],
        "engine": args.engine, "jump": "R reaches 0 with dR/dt < 0 before the rise completes (theta within 0.1 of its end)"})
    keys = {k for ks in members.values() for k in ks}
    n_new = sum(k not in store for k in keys)
    mode = str(st.run(specs, store, members=members, warm_up=partial(warm_up, args.engine), desc="thresholds (a, mu)"))
    rows = store.rows(keys)
    coll = ps.threshold_collapse([r for r in rows if r.d == BASE.amplitude], g["mu"], MU_REF)
    dl = ps.threshold_against_d(rows, g["d_lines"]["a"], g["d_mu"])
    st.save(plot_threshold_map(rows, g["mu"], coll, d0=BASE.amplitude, d_lines=g["d_lines"], d_mu=g["d_mu"], title=(
        r"Jump thresholds over $(a, \mu)$: exact Coulomb friction, sliding-branch starts at $d$ = 0.01 "
        r"(bottom right: $d$ varies), bisection to $10^{-3}$, rtol $10^{-9}$" + (" (quick run)" if args.quick else ""))),
        f"{STEM}.png")
    wall = st.wall
    stats = report(rows, g, coll, dl, wall, mode, n_new)
    summary = {"collapse": {b: {f"{mu:.4g}": v for mu, v in coll[b].items()} for b in ("prolate", "oblate")},
               "max_spread": coll["max_spread"], "max_raw_spread": coll["max_raw_spread"], "d_lines": dl, **stats}
    store.annotate(summary=summary)
    print(json.dumps({"wall_s": wall, **stats}))
    return {"rows": rows, "wall_s": wall, "n_computed": n_new, "specs": specs, **summary}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
