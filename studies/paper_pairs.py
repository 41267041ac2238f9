"""The paper's single-trajectory pairs under regularised Coulomb friction.

Fig. 3 (a = 2/3, start (5.1)): n0 = 10 rises without jumping, n0 = 10.5 jumps at t* ~ 91.
Fig. 4 (a = 1.5, start (5.2)): Omega0 = 10.2 rises without jumping, 10.5 jumps at t* ~ 111.
Under exact Coulomb friction both printed starts stick at once (they have almost no slip).
For which eps of the regularised law F = -mu R u / sqrt(|u|^2 + eps^2) (mu = 0.1), and in which
chart (the paper's Euler angles (2.7), or the singularity-free vector form), does each pair
come out as printed? Scan: eps = 10^(-k/4), k = 4 ... 32 (1e-1 ... 1e-8, quarter decades), and
exact Coulomb, in both charts; each run to t = 600 or until the rise completes (theta within
0.1 rad of its final value) or R = 0.

"As printed": the first value's rise completes without a jump, and the second value jumps
with t* within 15% of the printed t*. Writes paper_pairs.csv (one row per run, resumable) and
paper_pairs.png, and prints the table.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass
from functools import partial

import phasekit as pk
from phasekit.viz import plot_pair_scan

STEM = "paper_pairs"
T_END = 600.0
T_TOLERANCE = 0.15  # "t* ~ 91": the printed jump times are read off the figures
EPS_FULL = [10.0 ** (-k / 4) for k in range(4, 33)]
EPS_QUICK = [10.0 ** -k for k in range(1, 9)]
CHARTS = ("euler", "vector")
MAX_WALL = 300.0


@dataclass(frozen=True)
class PairRow:
    """One run: the printed start ``label`` with ``value`` under eps (empty: exact Coulomb) in ``chart``."""

    key: str
    figure: str
    label: str
    role: str  # "no_jump" or "jump": what the paper prints for this value
    value: float
    eps: float | None  # None (an empty cell): exact Coulomb
    chart: str
    outcome: str  # jump, rise, stuck, slow, failed
    t_end: float
    t_jump: float | None
    stuck: bool
    n_stick: int
    theta_end: float | None
    status: str
    wall_s: float
    reason: str


def row_key(label: str, value: float, eps, chart: str) -> str:
    return f"{label}|{value:.10g}|{'exact' if eps is None else repr(eps)}|{chart}|t_end={T_END:g}"


def run_one(label: str, role: str, value: float, eps, chart: str) -> PairRow:
    case = pk.theory.PAPER_CASES[label]
    law = pk.Coulomb(0.1) if eps is None else pk.RegularisedCoulomb(0.1, eps)
    model, x0 = pk.paper_start(label, friction=law, **{case.parameter: value})
    m = model.with_chart(chart)
    x = pk.to_chart(chart, model.chart.to_paper(x0))
    prolate = m.body.is_prolate
    ev = pk.Event("theta", 0.1 if prolate else math.pi / 2 - 0.1, direction=-1 if prolate else +1, name="rise-complete")
    row = partial(PairRow, row_key(label, value, eps, chart), case.figure, label, role, value, eps, chart)
    t0 = time.perf_counter()
    try:
        r = pk.simulate(m, x, T_END, events=[ev], track_minima=False, dense=False, max_wall=MAX_WALL)
    except pk.PhasekitError as exc:  # e.g. a start the Euler chart cannot take
        return row("failed", 0.0, None, False, 0, None, "failed", time.perf_counter() - t0, str(exc))
    y = r.euler_end if r.status is not pk.Status.FAILED else None
    return row(pk.sweep.outcome_class(r.status, r.stuck), float(r.t), r.t_jump, r.stuck, len(r.events_named("stick")),
               None if y is None else float(y[4]), r.status.value, time.perf_counter() - t0, r.reason or "")


def as_printed(no_jump: PairRow | None, jump: PairRow | None, t_printed: float) -> bool:
    return (no_jump is not None and jump is not None and no_jump.outcome == "rise" and jump.outcome == "jump"
            and abs(jump.t_jump / t_printed - 1) <= T_TOLERANCE)


def table(rows, eps_list) -> list[dict]:
    """Per (pair, chart, eps): the two outcomes and whether the pair is as printed."""
    out = []
    by = {(r.label, r.role, r.eps, r.chart): r for r in rows}
    for label, case in pk.theory.PAPER_CASES.items():
        for chart in CHARTS:
            for eps in list(eps_list) + [None]:
                e = "exact" if eps is None else repr(eps)  # as the summary and report spell it
                nj, j = by.get((label, "no_jump", eps, chart)), by.get((label, "jump", eps, chart))
                out.append({"figure": case.figure, "label": label, "chart": chart, "eps": e,
                            "no_jump": None if nj is None else (nj.outcome, nj.t_end),
                            "jump": None if j is None else (j.outcome, j.t_jump if j.t_jump else j.t_end),
                            "as_printed": as_printed(nj, j, case.t_jump)})
    return out


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, resumable=True)
    args = st.parse(argv)
    eps_list = EPS_QUICK if args.quick else EPS_FULL
    store = st.store(PairRow, {"t_end": T_END, "eps": eps_list, "charts": CHARTS, "t_tolerance": T_TOLERANCE,
                               "max_wall": MAX_WALL, "rtol": pk.SolverOptions().rtol})
    runs = [(label, role, value, eps, chart) for label, case in pk.theory.PAPER_CASES.items()
            for role, value in (("no_jump", case.no_jump), ("jump", case.jump))
            for eps in list(eps_list) + [None] for chart in CHARTS]
    specs = pk.sweep.each(runs, lambda label, role, value, eps, chart: row_key(label, value, eps, chart), run_one)
    rows, ran = st.sweep(specs, store, desc="paper pairs")
    tab = table(rows, eps_list)
    st.save(plot_pair_scan(rows, tab, pk.theory.PAPER_CASES, charts=CHARTS, t_end=T_END, t_tolerance=T_TOLERANCE, title=(
        r"The paper's trajectory pairs under regularised Coulomb friction ($\mu$ = 0.1, rtol $10^{-9}$; "
        r"markers above the axis: no jump)" + (" (quick run)" if args.quick else ""))), f"{STEM}.png")
    print(f"\n{STEM}: {len(rows)} runs ({ran.computed} now), {st.wall:.1f} s")
    for t in tab:
        nj = "-" if t["no_jump"] is None else f"{t['no_jump'][0]} (t = {t['no_jump'][1]:.1f})"
        j = "-" if t["jump"] is None else f"{t['jump'][0]} (t = {t['jump'][1]:.2f})"
        print(f"  {t['figure']} ({t['label']}) {t['chart']:<6s} eps={t['eps']:<22s} first: {nj:<24s} second: {j:<24s}"
              f"{'  AS PRINTED' if t['as_printed'] else ''}")
    hits = [t for t in tab if t["as_printed"]]
    summary = {f"{t['label']}|{t['chart']}": [h["eps"] for h in hits if h["label"] == t["label"] and h["chart"] == t["chart"]]
               for t in tab}
    store.annotate(as_printed=summary)
    print(json.dumps({"as_printed": summary}))
    return {"rows": rows, "table": tab, "as_printed": summary}


if __name__ == "__main__":
    pk.sweep.run_study(main)
