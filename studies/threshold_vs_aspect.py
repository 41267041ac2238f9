"""Jump thresholds against aspect ratio (Figure 6b,c): Omega0(a) for prolate, n0(a) for oblate.

For each aspect ratio, the smallest precession rate Omega0 (prolate, from the horizontal
steady precession) or spin n0 (oblate, from the vertical spin) whose trajectory loses
contact (R = 0, dR/dt < 0) before its rise completes, under three definitions side by side
(see phasekit.thresholds.definition): (i) viscous friction; (ii) exact Coulomb friction with starts on
the sliding (gyroscopic-balance) branch at d = 0.01 from the fixed point, the DEFAULT;
(iii) the paper's literal recipe, the viscous unstable eigenvector (delta = 0.01)
integrated with Coulomb friction regularised with eps = 1e-3, 1e-4, or exact.

Each threshold is bracketed by a coarse scan (seeded by the previous aspect ratio) and
bisected to 1e-3 relative, then checked by the library (pk.find_threshold's verification): the
bracket's ends must keep their outcomes at a ten times tighter tolerance; one whose check fails is
searched again at that tolerance, and that search is the point (columns consistent, check_rtol,
first_threshold, check_worst).
Sensitivity at a = 1.5 and 2/3: d or delta in {0.005, 0.01, 0.02}, eps in {1e-4, 1e-6,
1e-8, exact}, rtol in {1e-8, 1e-10}.

Runs on Dask (LocalCluster with one single-threaded worker per core, or --scheduler ADDRESS),
the compiled model shipped to each worker once. --engine batch --levels 3 runs each round's
simulations on heyoka's batch integrator, 7 bisection midpoints at once (k-section): the
same 146 brackets, bit for bit, in fewer rounds but with 43% more simulations (measured:
3217 against 2257), which for these continuation chains costs more than it saves, so
one-by-one bisection is the default. Resumable: every finished point is appended to
threshold_vs_aspect.csv at once (manifest .json). Writes threshold_vs_aspect.png.
"""

from __future__ import annotations

from dataclasses import asdict
from functools import partial

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import DEFINITION_STYLES, plot_threshold_curves
from phasekit.thresholds import DEFAULT_DEFINITIONS

STEM = "threshold_vs_aspect"
SEARCH = dict(hi=120.0, tol=1e-3, n_coarse=8, window=1.5)
PROLATE = [3.0, 2.5, 2.0, 1.75, 1.5, 1.4, 1.3, 1.2, 1.15, 1.1, 1.075, 1.05]
OBLATE = [0.3, 0.4, 0.5, 0.6, 2 / 3, 0.7, 0.75, 0.8, 0.85, 0.9, 0.925, 0.95]
QUICK_PROLATE = [2.0, 1.5, 1.2]
QUICK_OBLATE = [0.5, 2 / 3, 0.8]
DEFAULT_NAME = "sliding"
# The paper's own brackets from single trajectories: Fig. 4 (a = 1.5, start (5.2), which is the
# viscous eigenvector with delta ~ 0.02): Omega0 = 10.2 no jump, 10.5 jump. Fig. 3 (a = 2/3,
# start (5.1), delta ~ 1e-5): n0 = 10 no jump, 10.5 jump.
PAPER_BRACKETS = {1.5: (10.2, 10.5), 2 / 3: (10.0, 10.5)}


def build_tasks(quick: bool, sensitivity: bool, engine: str = "scalar", levels: int = 1) -> list:
    """One chain per definition and branch, ordered from far to near a = 1 (thresholds grow along
    it); the sensitivity runs at a = 1.5 and 2/3 each seeded by its parent definition's point."""
    prolate, oblate = (QUICK_PROLATE, QUICK_OBLATE) if quick else (PROLATE, OBLATE)
    specs = [s for defn in DEFAULT_DEFINITIONS for a_list in (prolate, oblate) for s in ps.threshold_chain(
        defn, a_list, SEARCH, is_default=defn.name == DEFAULT_NAME, engine=engine, levels=levels)]
    for defn in ps.sensitivity_definitions(quick) if sensitivity else ():
        parent = next(d for d in DEFAULT_DEFINITIONS if d.name == ps.sensitivity_parent(defn))
        specs += [s for a in (1.5, 2 / 3) for s in ps.threshold_chain(
            defn, [a], SEARCH, group="sensitivity", engine=engine, levels=levels, after=ps.threshold_key(parent, a, SEARCH))]
    return specs


def warm_up(engine: str = "scalar") -> None:
    """Compile (or load) every model and integrator the sweep uses, so the pack carries them (the
    checks' at their tighter tolerance too); the batch integrators only for ``--engine batch``
    (from an empty cache they were 10 of 30 compilations, ~20 s, for runs that never used them)."""
    definitions = list(DEFAULT_DEFINITIONS) + ps.sensitivity_definitions(False)
    ps.prepare_definitions(definitions, (1.5, 2 / 3), engine=engine)
    ps.prepare_definitions([d.tighter() for d in definitions], (1.5,), engine="scalar")


def report(rows: list, wall: float, n_new: int, mode: str) -> dict:
    print(f"\nFigure {STEM}.png: jump thresholds against aspect ratio, mu = 0.1, 5 definitions; table {STEM}.csv.")
    print(ps.threshold_table(rows, first=DEFAULT_NAME))
    if any(r.group == "sensitivity" for r in rows):
        print("\nSensitivity at a = 1.5 (Omega0) and a = 2/3 (n0):")
        print(ps.definition_sensitivity_table(rows, parent=ps.sensitivity_parent))
    n_sims = sum(r.n_sims + r.n_check_sims for r in rows)
    sim_wall = sum(r.wall_s for r in rows)
    print(f"\n{len(rows)} points ({n_new} computed now, {mode}); {n_sims} simulations, {sim_wall:.1f} s of task time, "
          f"{wall:.1f} s wall; {n_sims / max(sim_wall, 1e-9):.0f} simulations per second per worker.")
    return {"n_sims": n_sims, "task_s": sim_wall}


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="3 aspect ratios per branch, reduced sensitivity", dask=True)
    st.parser.add_argument("--no-sensitivity", action="store_true",
                           help="skip the sensitivity runs at a = 1.5 and 2/3 (other d, delta, eps, rtol)")
    st.parser.add_argument("--engine", default="scalar", choices=("batch", "scalar"),
                           help="simulations one by one (default) or on heyoka's batch integrator; the same brackets")
    st.parser.add_argument("--levels", type=st.parser.integer(min=1, max=8), default=1,
                           help="bisection steps per round (k-section, 2^L - 1 values; 1 to 8, default 1)")
    args = st.parse(argv)
    specs = build_tasks(args.quick, not args.no_sensitivity, args.engine, args.levels)
    store = st.store(ps.ThresholdRow, {
        "search": SEARCH, "definitions": {d.name: asdict(d) for d in list(DEFAULT_DEFINITIONS) + ps.sensitivity_definitions(args.quick)},
        "default_definition": DEFAULT_NAME, "jump": "R reaches 0 with dR/dt < 0 before the rise completes",
        "rise_complete": "theta within rise_margin of the final state (0 prolate, pi/2 oblate), or t_max reached"})
    ran = st.run(specs, store, warm_up=partial(warm_up, args.engine), desc="thresholds")
    rows = store.rows(s.key for s in specs)
    st.save(plot_threshold_curves(rows, DEFAULT_DEFINITIONS, default=DEFAULT_NAME, styles=DEFINITION_STYLES, hi=SEARCH["hi"],
                                  brackets=PAPER_BRACKETS, title=r"Smallest $\Omega_0$ / $n_0$ that leads to loss of contact, "
                                  r"$\mu=0.1$" + (" (quick run)" if args.quick else "")), f"{STEM}.png")
    stats = report(rows, st.wall, ran.computed, ran.mode)
    return {"rows": rows, "wall_s": st.wall, "n_computed": ran.computed, **stats}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
