"""Performance, robustness, the reproduction table and the README's blocks, for pkdocs.facts."""

from __future__ import annotations

from collections import Counter

from .fmt import fixed, sci, sig, table
from .registry import group, values
from .sources import Sources

# -- performance (studies/work_precision.py, stiff_extreme.py, benchmarks/) ---------------------------

#: the integration benchmark's ratios, as its report names them: (key, what, its goal's key, the goal's sense)
BENCH_RATIOS = [
    ("ratio_scipy_bdf_sweep", "scipy BDF (NumPy rhs, rtol 1e-9) / phasekit's sweep path at the loosest rtol as accurate (above)",
     "scipy_bdf", ">="),
    ("ratio_scipy_bdf_default", "scipy BDF / phasekit with the default options (dense output, every minimum of R)", None, ""),
    ("ratio_sweep_bare_heyoka", "phasekit's sweep path / bare heyoka `propagate_until`, the same steps (rtol 1e-9)",
     "bare_heyoka", "<="),
    ("ratio_default_bare_heyoka", "phasekit's default options / bare heyoka (rtol 1e-9)", None, ""),
    ("ratio_default_sweep", "phasekit's default options / its sweep path (rtol 1e-9)", "default_sweep", "<="),
    ("ratio_rolling_sliding", "a rolling trajectory / a sliding one of the same length", "rolling_sliding", "<="),
    ("ratio_patch_point", "friction over a contact patch / at a point, the same sliding run", "patch_point", "<="),
]

NOT_MEASURED = "not measured"


def _bench(src: Sources, name: str) -> dict | None:
    """A benchmark's report in docs/data/, or None when it has not been measured (the page says so)."""
    try:
        return src.report(name)
    except LookupError:
        return None


def _bench_note(b: dict | None, name: str, extra: str = "") -> str:
    """Markdown: the command as code (a role's plain text would get its ``--`` turned into a dash)."""
    if b is None:
        return f"{NOT_MEASURED.capitalize()}: `docs/data/{name}` is not there (the benchmark writes it with `--report`)."
    return f"Measured by `{b['command']}` on {b['machine']}, {b['measured']} (commit {b['commit']}{extra}):"


def _bench_block(prefix: str, note: str, rows: list | None, header: list[str]) -> dict:
    """``<prefix>_note``, ``<prefix>_table`` and ``<prefix>_report`` (the note above the table, the page's block)."""
    t = table(header, rows) if rows is not None else ""
    return {f"{prefix}_note": note, f"{prefix}_table": t, f"{prefix}_report": f"{note}\n\n{t}".strip()}


def _goal_row(r: dict, what: str, shown: str, value: float, goal: str | None, sense: str, unit: str = "") -> list:
    """A table row: what, the measured value as shown, its goal and whether this run met it."""
    g = r.get("goals", {}).get(goal) if goal else None
    if g is None:
        return [what, shown, "", ""]
    met = r.get("goals_met", {}).get(goal)
    if met is None:  # a report from before the goal was checked by the benchmark
        met = value >= g if sense == ">=" else value <= g
    return [what, shown, f"{sense} {g:g}{unit}", "yes" if met else "**no**"]


def bench_performance(src: Sources) -> dict:
    b = _bench(src, "bench_performance.json")
    if b is None:
        return _bench_block("bench", _bench_note(b, "bench_performance.json"), None, [])
    r = dict(b["result"])
    # the same two medians the benchmark divides (older reports have the times, not the ratio)
    r.setdefault("ratio_default_sweep", r["default_rtol1e-9_ms"] / r["sweep_rtol1e-9_ms"])
    rows = [[f"sweep path (rtol {sci(r['phasekit_rtol'], 0)}), one run to the jump", f"{sig(r['sweep_ms'], 2)} ms", "", ""],
            [f"default options (rtol {sci(r['phasekit_rtol'], 0)})", f"{sig(r['default_ms'], 2)} ms", "", ""],
            ["scipy BDF on a NumPy right-hand side (rtol 1e-9)", f"{sig(r['scipy_bdf_ms'], 3)} ms", "", ""]]
    rows += [_goal_row(r, what, sig(r[key], 3), r[key], goal, sense) for key, what, goal, sense in BENCH_RATIOS if key in r]
    return _bench_block("bench", _bench_note(b, "bench_performance.json", f"; median of {r['repeats']} interleaved runs"),
                        rows, ["standard prolate workload, to the jump", "measured", "goal", "met"])


def bench_sweep(src: Sources) -> dict:
    b = _bench(src, "bench_threshold_sweep.json")
    if b is None:
        return _bench_block("sweep", _bench_note(b, "bench_threshold_sweep.json"), None, [])
    r = b["result"]
    rows = [["simulations", f"{r['simulations']} ({r['searches']} searches, {r['grid']} grid)", "", ""],
            ["critical path", f"{r['critical_path']} rounds", "", ""],
            _goal_row(r, "parallelism (simulations / critical path)", sig(r["parallelism"], 3), r["parallelism"],
                      "parallelism", ">="),
            ["wall time serial", f"{sig(r['wall_serial_s'], 3)} s", "", ""],
            ["wall time on 2 workers", f"{sig(r['wall_dask_s'], 3)} s (cluster start {sig(r['cluster_start_s'], 2)} s more)",
             "", ""],
            _goal_row(r, "efficiency: serial / (2 x 2 workers)", fixed(r["efficiency"], 2), r["efficiency"], "efficiency", ">="),
            ["same thresholds serial and on 2 workers", "yes" if r["same_thresholds_serial_and_dask"] else "**no**", "", ""],
            _goal_row(r, "default Fig. 6b,c curves on 2 workers", f"{sig(r['default_curve_wall_s'], 3)} s",
                      r["default_curve_wall_s"], "default_curve_wall_s", "<=", " s")]
    return _bench_block("sweep", _bench_note(b, "bench_threshold_sweep.json"), rows,
                        ["the (a, mu) map", "measured", "goal", "met"])


def bench_structure(src: Sources) -> dict:
    b = _bench(src, "bench_steady_structure.json")
    if b is None:
        return _bench_block("structure", _bench_note(b, "bench_steady_structure.json"), None, [])
    r = b["result"]
    n = len(r["structure_wall_s"])
    rows = [[f"one body's structure (the slowest of {n} pairs of body and law, median of 5 calls)",
             f"{sig(r['structure_worst_s'] * 1e3, 3)} ms", "", ""],
            ["atlas", f"{r['bodies']} bodies, {r['boundary_points']} boundary points ({r['grid']} atlas)", "", ""],
            ["atlas wall time serial", f"{sig(r['atlas_wall_serial_s'], 3)} s", "", ""],
            ["atlas wall time on 2 workers", f"{sig(r['atlas_wall_dask_s'], 3)} s (cluster start "
             f"{sig(r['cluster_start_s'], 2)} s more)", "", ""],
            _goal_row(r, "efficiency: serial / (2 x 2 workers)", fixed(r["efficiency"], 2), r["efficiency"], "efficiency", ">="),
            ["same signatures serial and on 2 workers", "yes" if r["same_signatures_serial_and_dask"] else "**no**", "", ""]]
    return _bench_block("structure", _bench_note(b, "bench_steady_structure.json"), rows,
                        ["steady-state structure", "measured", "goal", "met"])


def bench_first_run(src: Sources) -> dict:
    b = _bench(src, "bench_first_run.json")
    if b is None:
        return _bench_block("first_run", _bench_note(b, "bench_first_run.json"), None, [])
    r = b["result"]
    rows = [[f"{name}: `{v['command']}`", f"{fixed(v['first_s'], 1)} s", f"{fixed(v['second_s'], 1)} s", str(v["notices"]), ""]
            for name, v in r["bodies"].items()]
    what, shown, goal, met = _goal_row(r, "the slowest first run", f"{fixed(r['worst_first_s'], 1)} s", r["worst_first_s"],
                                       "first_s", "<=", " s")
    rows.append([what, shown, "", "", f"{goal}: {met}"])
    return _bench_block("first_run", _bench_note(b, "bench_first_run.json"), rows,
                        ["body: command", "first run (empty caches)", "second run", "compile notices on stderr", "goal: met"])


def bench_cold_cache(src: Sources) -> dict:
    b = _bench(src, "bench_cold_cache.json")
    if b is None:
        return _bench_block("cold_cache", _bench_note(b, "bench_cold_cache.json"), None, [])
    r = b["result"]
    kinds = ", ".join(f"{what.replace('the Taylor integrator of the ', '')} {k}" for what, k in sorted(r["builds_by_kind"].items()))
    rows = [["main study `--fresh`, empty compile cache", f"{fixed(r['cold_s'], 1)} s", "", ""],
            ["the same, cache warm", f"{fixed(r['warm_s'], 1)} s", "", ""],
            _goal_row(r, "empty / warm", fixed(r["cold_over_warm"], 2), r["cold_over_warm"], "cold_over_warm", "<="),
            [f"builds, empty cache ({r['integrators']} integrators: {kinds}); with the cache warm: {r['builds_when_warm']}",
             str(r["builds"]), "", ""],
            _goal_row(r, "most builds of one integrator", str(r["most_builds_of_one_integrator"]),
                      r["most_builds_of_one_integrator"], "builds_per_integrator", "<=")]
    return _bench_block("cold_cache", _bench_note(b, "bench_cold_cache.json"), rows,
                        ["main study from an empty cache", "measured", "goal", "met"])


def bench_memory(src: Sources) -> dict:
    b = _bench(src, "bench_memory.json")
    if b is None:
        return _bench_block("memory", _bench_note(b, "bench_memory.json"), None, [])
    r = b["result"]
    st, ps, lg, k = r["standard"], r["per_step"], r["long"], r["bookkeeping"]
    rows = [["the standard workload (to the jump, default options): the process's peak",
             f"{fixed(st['peak_rss_mb'], 0)} MB", "", ""],
            ["... one run of it, traced (tracemalloc peak)", f"{fixed(st['traced_peak_kb'], 0)} KB", "", ""],
            ["dense output held per million Taylor steps (no cap)", f"{fixed(ps['dense_mb_per_million_steps'], 0)} MB", "", ""],
            ["past `max_dense_mb`: the energy tally held per million steps",
             f"{fixed(ps['tally_mb_per_million_steps'], 1)} MB", "", ""],
            ["... the run's wall time with the tally, against keeping the dense output",
             f"{fixed(ps['ratio_tally_dense_wall'], 2)}x", "", ""],
            _goal_row(r, f"a long run of {lg['steps']} steps (status {lg['status']}, {lg['samples']} samples, "
                         f"{lg['events']} events, energy residual {sci(lg['energy_residual_max'], 1)}): peak resident",
                      f"{fixed(r['long_run_peak_mb'], 0)} MB", r["long_run_peak_mb"], "long_run_peak_mb", "<=", " MB"),
            ["... its peak against a run of a tenth of its steps", f"{fixed(r['ratio_long_tenth_rss'], 2)}", "", ""],
            _goal_row(r, "air drag's bookkeeping: time simulated per second, without / with the law",
                      f"{fixed(r['ratio_bookkeeping'], 2)}", r["ratio_bookkeeping"], "bookkeeping", "<="),
            ["... without / with a zero coefficient", f"{fixed(k['ratio_zero'], 2)}", "", ""],
            _goal_row(r, "the commands with a dissipation law: wall time past --max-wall 2 s (the run and the work "
                         "after it), a fraction of it, the worst round",
                      f"{fixed(r['wall_overrun'], 2)}", r["wall_overrun"], "wall_overrun", "<="),
            ["... the command without the law", f"{fixed(k['wall_overrun']['without'], 2)}", "", ""],
            ["... the work after the drag run left uncapped (as before), a fraction of --max-wall",
             f"{fixed(k['post_run_uncapped_overrun'], 2)} ({k['post_run_uncapped_steps']} steps)", "", ""]]
    return _bench_block("memory", _bench_note(b, "bench_memory.json"), rows, ["measured", "value", "goal", "met"])


def _study_profile(t) -> dict:
    """Where the main study's task time goes, by threshold definition (its committed table keeps
    each search's simulations and wall time)."""
    t = t.assign(sims=t["n_sims"] + t["n_check_sims"])
    g = t.groupby("name", sort=False).agg(points=("a", "size"), sims=("sims", "sum"), task=("wall_s", "sum"),
                                          longest=("wall_s", "max"))
    g = g.sort_values("task", ascending=False)
    total = float(g["task"].sum())
    rows = [[name, int(r.points), int(r.sims), sig(r.task, 3), f"{100 * r.task / total:.0f}%", sig(r.longest, 3)]
            for name, r in g.iterrows()]
    return {"study_task_s": sig(total, 3), "study_sims": int(g["sims"].sum()),
            "study_table": table(["definition", "points", "simulations", "task time (s)", "share", "longest search (s)"], rows)}


@group("performance")
def performance(src: Sources) -> dict:
    w = src.csv("work_precision.csv")
    ok = w[w["status"] == "ok"]
    out = {}
    for wl, key in (("prolate", "prolate"), ("oblate", "oblate")):
        sel = ok[ok["workload"].str.startswith(wl)]
        rows = []
        for method in dict.fromkeys(w["method"]):
            cells = []
            for tol in (1e-6, 1e-9):
                m = sel[(sel["method"] == method) & (sel["error"] <= tol)]
                if len(m):
                    r = m.loc[m["wall_s"].idxmin()]
                    cells.append(f"{sig(r['wall_s'] * 1e3, 3)} ms (rtol {sci(r['rtol'], 0)})")
                else:
                    cells.append("not reached")
            rows.append([method, *cells])
        out[f"{key}_workload"] = sel["workload"].iloc[0] if len(sel) else ""
        out[f"{key}_table"] = table(["method", "error <= 1e-6", "error <= 1e-9"], rows)
    out["n_capped"] = int((w["status"] == "capped").sum())
    s = src.csv("stiff_extreme.csv")
    out["stiff_n"] = len(s)
    out["stiff_status"] = ", ".join(f"{k} {v}" for k, v in Counter(s["status"]).most_common())
    out["stiff_all_finite"] = "yes" if s["finite"].astype(str).eq("True").all() else "no"
    inv = s[s["case"].str.startswith("mu = 0")]
    out["stiff_drift"] = sci(inv["invariant_drift"].max(), 0)
    fail = s[s["status"] == "failed"]
    out["stiff_failed"] = "; ".join(f"{r.case}: {r.reason}" for r in fail.itertuples()) or "none"
    out.update(_study_profile(src.csv("threshold_vs_aspect.csv")))
    for bench in (bench_performance, bench_sweep, bench_structure, bench_first_run, bench_cold_cache, bench_memory):
        out.update(bench(src))
    return out


# -- robustness (tests/cli/test_generated_command_lines.py, tests/contracts/test_generated_api_calls.py)

OUTCOMES = [("valid", "valid result"), ("failed", "failed, with a reason"), ("error", "clear error")]


def _fuzz_table(rep: dict) -> tuple[str, int, dict]:
    rows = []
    for name in sorted(rep["suites"]):
        c = rep["suites"][name]
        rows.append([name, *(c.get(k, 0) for k, _ in OUTCOMES)])
    total = rep["total"]
    n = sum(total.get(k, 0) for k, _ in OUTCOMES)
    extra = {k: v for k, v in total.items() if k not in dict(OUTCOMES)}
    rows.append([f"**total: {n} cases**", *(f"**{total.get(k, 0)}**" for k, _ in OUTCOMES)])
    return table(["cases", *(label for _, label in OUTCOMES)], rows), n, extra


@group("robustness")
def robustness(src: Sources) -> dict:
    out = {}
    for key, name in (("cli", "fuzz.json"), ("api", "fuzz.api.json")):
        rep = src.report(name)
        t, n, extra = _fuzz_table(rep)
        out[f"{key}_table"], out[f"{key}_n"] = t, n
        out[f"{key}_other"] = sum(extra.values())
        out[f"{key}_scale"] = f"{rep.get('scale', 1):g}"
    return out


# -- the reproduction table: the paper against phasekit, with the measurement where they differ ------


@group("repro")
def repro(src: Sources) -> dict:
    p, a, m, t, e = (values(src, g) for g in ("pairs", "aspect", "mu", "theory", "egg"))
    rows = [*_repro_starts(p), *_repro_thresholds(a, m), *_repro_figures(t, a), *_repro_flight_surface_bodies(t, e),
            _euler_disk_row(src.json("euler_disk.json")["runs"]["air-layer"])]
    header = ["quantity", 'paper (its words "in quotes"; the rest our reading)', "phasekit (measured)", "data"]
    return {"table": table(header, rows), "n_rows": len(rows)}


def _repro_starts(p: dict) -> list:
    """The reproduction table's rows of the printed starts."""
    return [
        [
            "start (5.2), Omega0 = 10.5",
            "rises, jumps at t* ~ 111 (Fig. 4b)",
            f"exact Coulomb: {p['p52_exact']}; regularised: eps = 1e-2 jumps at {p['p52_eps1e-2']}, 1e-3 at "
            f"{p['p52_eps1e-3']}, 1e-4 at {p['p52_eps1e-4']}; {p['p52_last_jump']}; eps <= {p['p52_stuck_below']}: "
            f"sticks, no jump to t = {p['t_end']}",
            "paper_pairs.csv",
        ],
        [
            "start (5.2) vs the unstable eigenvector",
            '"approximately" the unstable direction',
            "rounds to the horizontal state + 0.02 x the viscous unstable eigenvector in every component, but the two "
            "starts jump at different times",
            "gallery: paper_start_rounding.py",
        ],
        [
            "Fig. 3 pair (5.1): n0 = 10 / 10.5, regularised",
            "10 rises, 10.5 jumps at t* ~ 91",
            f"{p['fig3']}; exact Coulomb and {p['fig3_stuck']}: both stick",
            "paper_pairs.csv",
        ],
        [
            "Fig. 4 pair (5.2): Omega0 = 10.2 / 10.5, regularised",
            "10.2 rises, 10.5 jumps at t* ~ 111",
            f"{p['fig4']}; exact Coulomb and {p['fig4_stuck']}: both stick",
            "paper_pairs.csv",
        ],
        ["start (5.1), n0 = 10.5", "jumps at t* ~ 91 (Fig. 3d)", f"exact Coulomb: {p['p51_exact']}", "paper_pairs.csv"],
    ]


def _repro_thresholds(a: dict, m: dict) -> list:
    """The reproduction table's rows of the thresholds."""
    return [
        [
            "prolate a = 1.5 threshold",
            "10.2 < Omega0* < 10.5 (Fig. 4, delta ~ 0.02)",
            f"literal recipe, eps = 1e-3: {a['a15_literal-eps1e-3']}; eps = 1e-4: {a['a15_literal-eps1e-4']}; exact: "
            f"{a['a15_literal-exact']}; default (sliding branch, d = 0.01): {a['a15']}",
            "threshold_vs_aspect.csv",
        ],
        [
            "oblate a = 2/3 threshold",
            "10 < n0* < 10.5 (Fig. 3, delta ~ 1e-5)",
            f"literal recipe, eps = 1e-3: {a['a23_literal-eps1e-3']}; exact: {a['a23_literal-exact']}; "
            f"default: {a['a23']}",
            "threshold_vs_aspect.csv",
        ],
        [
            "Fig. 6b,c trend",
            "thresholds rise as a -> 1",
            f"rise toward a = 1 on both branches: {a['prolate_at2']} ... {a['prolate_near1']}; {a['oblate_far']} ... "
            f"{a['oblate_near1']}; shallow minima {a['prolate_min']} and {a['oblate_min']}; every value depends on the "
            f"seed distance d (a = 1.5, d = 0.005 / 0.01 / 0.02: {a['d_spread_a15']})",
            "threshold_vs_aspect.csv",
        ],
        [
            "threshold against friction",
            "mu = 0.1 only",
            f"within {m['within_mid']} of mu = 0.1 for mu = {m['mid_range']}, up to {m['rise_500']} at mu = 0.5 "
            "(starts stick); no collapse with one factor f(mu)",
            "threshold_vs_mu.csv",
        ],
    ]


def _repro_figures(t: dict, a: dict) -> list:
    """The reproduction table's rows of Figs. 2-4 and the J of Figs. 3, 4."""
    return [
        [
            "Fig. 2",
            "Sigma's minimum falls with J and turns negative",
            f"same; {t['fig2']} (theta-bar0 = pi/2 - 1e-4)",
            "closed forms, computed",
        ],
        [
            "Fig. 3 (a = 2/3, n0 = 10)",
            "rises without jumping",
            f"from the sliding branch (d = 0.01) it jumps, at t* = {t['js_oblate_10']} (a different start; the "
            "printed one "
            "sticks)",
            "jump_surface.csv",
        ],
        [
            "Fig. 4a (a = 1.5, Omega0 = 10.2)",
            "rises without jumping",
            f"from the sliding branch (d = 0.01) already Omega0 = 10 jumps, at t* = {t['js_prolate_10']} (threshold "
            f"{a['a15']})",
            "jump_surface.csv",
        ],
        [
            "J in Figs. 3, 4",
            "4, 4.2; 6.63, 6.83",
            f"A Omega h: {t['J_fig3']} (the quoted oblate values are C n0 = {t['J_fig3_Cn0']}); {t['J_fig4']}",
            "closed form (3.17)",
        ],
    ]


def _repro_flight_surface_bodies(t: dict, e: dict) -> list:
    """The reproduction table's rows of the flight (4.23), the jump surface (6.3), section 7 and the egg's jumps."""
    return [
        [
            "(4.23) against the exact flight",
            "differences decrease with Omega0 (Fig. 5a-c)",
            f"median relative error of the largest gap {t['fig5_median_error']}, {t['fig5_members']} perturbed starts "
            "per Omega0",
            "figure5_gap.csv",
        ],
        [
            "Fig. 5d bound (4.65/Omega0)^5",
            "bounds the (4.23) points",
            f"{t['fig5_423_above']} of {t['fig5_n']} (4.23) points above it; {t['fig5_exact_above']} of {t['fig5_n']} "
            "exact maxima above it",
            "figure5_gap.csv",
        ],
        [
            "(6.3) detects the jump",
            '"very well", better with Omega0',
            f"relative error in n <= {t['js_max_error']} (<= {t['js_trend_max_error']} over {t['js_trend_n']} "
            "starts); no "
            f"trend in Omega0 (fitted slope {t['js_slope_prolate']} prolate, {t['js_slope_oblate']} oblate)",
            "jump_surface.csv, jump_surface_trend.csv",
        ],
        [
            "effective friction with bouncing (section 7)",
            "conjecture: mu_e somewhat below mu",
            f"mu_e / mu = {t['mu_e_range']}",
            "bouncing.csv",
        ],
        [
            "egg jumps (Mitsui et al. 2006, cited)",
            'abstract: "the durations of the first loss of contact are measured"; as Science News reported it: '
            '"a fraction of a millimeter off the surface for up to a few hundredths of a second" at up to 2,500 rpm '
            "(our reading: 0.05-0.5 mm, 5-30 ms)",
            f"hen's-egg-sized body (57 x 43 mm, uniform, mu = 0.1): thresholds {e['thr_rev_w0.05']}-{e['thr_rev_w0']} "
            f"rev/s; first flights {e['first_gap_range_um']} micrometres; the highest hops, late in the rise, "
            f"{e['hop_gap_range']} mm for {e['hop_ms_range']} ms",
            "egg_real_units.csv, egg_jumps.csv",
        ],
    ]


def _euler_disk_row(air: dict) -> list:
    """Moffatt's air layer under Euler's disk against studies/euler_disk.py's run."""
    th, om = air["fit_theta"], air["fit_omega"]
    return [
        "Euler's disk, air layer (Moffatt 2000, cited)",
        'as the encyclopaedias quote him: "Omega ~ (t0 - t)^-1/6"; the tilt alpha ~ (t0 - t)^(1/3) and '
        f"t0 = {sig(air['t0_quasi_static'], 5)} for this launch are our reading of the same quasi-static balance",
        f"thin disk from 30 deg, k = {air['coefficient']:g}: alpha ~ (t0 - t)^{th['exponent']:.4f} +- {th['ci95']:.4f}, "
        f"Omega ~ (t0 - t)^{om['exponent']:.4f} +- {om['ci95']:.4f} over {air['decades']:.2f} decades; "
        f"t0 = {sig(air['t0_fit'], 5)} (the disk drifts off spinning in place)",
        "euler_disk.json",
    ]


# -- blocks of the README (tests/contracts/test_readme.py checks that the README holds them as generated) ------


@group("readme")
def readme(src: Sources) -> dict:
    s, r, e = values(src, "steady"), values(src, "robustness"), values(src, "egg")
    out = {
        "steady_counts": table(
            ["body", "classes of steady-state structure found", "part III"],
            [
                [
                    "spheroid with its centre of mass displaced along the axis",
                    s["spheroid_classes"],
                    s["part_iii_spheroid"],
                ],
                ["tippe top", s["tippe_classes"], s["part_iii_tippe"]],
            ],
        )
    }
    rows = []
    for key, label in (
        ("cli", "`tests/cli/test_generated_command_lines.py` (command lines)"),
        ("api", "`tests/contracts/test_generated_api_calls.py` (API calls)"),
    ):
        rep = src.report("fuzz.json" if key == "cli" else "fuzz.api.json")["total"]
        rows.append([label, r[f"{key}_n"], *(rep.get(k, 0) for k, _ in OUTCOMES), r[f"{key}_other"]])
    out["robustness_counts"] = table(
        ["generated cases", "cases", *(label for _, label in OUTCOMES), "anything else"], rows
    )
    out["egg_jumps"] = (
        f"A hen's-egg-sized body (57 x 43 mm, uniform, exact Coulomb mu = 0.1) first jumps at {e['thr_rev_w0']} rev/s "
        f"(w = 0; {e['thr_rev_w0.05']} rev/s with the asymmetry w = 0.05). Its first flights are micrometres high "
        f"({e['first_gap_range_um']} um over every lever tried: spin, friction, asymmetry, start), but it keeps "
        "hopping "
        f"through the rise, and its highest hops, late in the rise, leave the table by {e['hop_gap_range']} mm for "
        f"{e['hop_ms_range']} ms at any spin, start or asymmetry, with or without rebounds: inside our reading "
        "(0.05-0.5 mm, 5-30 ms) of Science News's report that the egg-shaped bodies of Mitsui et al. 2006 "
        '(Proc. R. Soc. A 462, 2897) "leaped a fraction of a millimeter off the surface for up to a few hundredths '
        'of a second". The paper\'s abstract says it measured "the durations of the first loss of contact", and '
        "phasekit's first flights are below that reading; the real bodies' friction and restitution are not known "
        "here."
    )
    return out
