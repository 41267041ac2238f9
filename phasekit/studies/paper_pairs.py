"""The paper's printed pairs of single trajectories, run under a friction law in a chart.

Fig. 3 (start (5.1), a = 2/3): n0 = 10 rises without jumping, n0 = 10.5 jumps at t* ~ 91;
Fig. 4 (start (5.2), a = 1.5): Omega0 = 10.2 rises without jumping, 10.5 jumps at t* ~ 111
(:data:`phasekit.theory.PAPER_CASES`). :func:`pair_run` runs one value of a pair under exact
or regularised Coulomb friction (mu = 0.1) in the Euler or the vector chart, to ``t_end`` or
until the rise completes (theta within 0.1 rad of its final value) or R = 0: one
:class:`PairRow`. :func:`pair_table` sets the two values of each pair side by side and says
whether the pair comes out *as printed*: the first value's rise completes without a jump, the
second jumps with t* within ``t_tolerance`` of the printed t*. Used by ``studies/paper_pairs.py``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import partial

from ..core.hybrid import Event
from ..core.simulate import simulate
from ..core.starts import paper_start, to_chart
from ..errors import PhasekitError, Status
from ..friction.laws import Coulomb, RegularisedCoulomb
from ..sweep.tasks import each
from ..theory.paper import PAPER_CASES
from .outcome_maps import outcome_class


@dataclass(frozen=True)
class PairRow:
    """One run of a printed pair (made by :func:`pair_run`): the printed start ``label`` with
    ``value`` under ``eps`` (None, an empty cell: exact Coulomb) in ``chart``; ``role`` is what
    the paper prints for the value ("no_jump" or "jump"), ``outcome`` what the run did (jump,
    rise, stuck, slow, failed: :func:`phasekit.studies.outcome_class`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> row = ps.pair_run("5.2", "jump", 10.5, 1e-3, "euler", t_end=5.0)
    >>> row.figure, row.role, row.outcome
    ('Fig. 4', 'jump', 'stuck')
    """

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


def pair_key(label: str, value: float, eps, chart: str, t_end: float) -> str:
    """The key of a run's row in a result store.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.pair_key("5.2", 10.5, None, "euler", 600.0)
    '5.2|10.5|exact|euler|t_end=600'
    """
    return f"{label}|{value:.10g}|{'exact' if eps is None else repr(eps)}|{chart}|t_end={t_end:g}"


def pair_run(label: str, role: str, value: float, eps, chart: str, *, t_end: float, max_wall: float = 300.0) -> PairRow:
    """Run the printed start ``label`` ((5.1) or (5.2)) with ``value`` under Coulomb friction
    mu = 0.1, regularised with ``eps`` (None: exact), in ``chart`` ("euler" or "vector"), to
    ``t_end`` or until the rise completes (theta within 0.1 rad of 0 prolate, pi/2 oblate) or
    R = 0, within ``max_wall`` seconds. A start the chart cannot take is a row with outcome
    "failed". See :class:`PairRow`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.pair_run("5.2", "jump", 10.5, None, "euler", t_end=5.0).outcome
    'stuck'
    """
    case = PAPER_CASES[label]
    law = Coulomb(0.1) if eps is None else RegularisedCoulomb(0.1, eps)
    model, x0 = paper_start(label, friction=law, **{case.parameter: value})
    m = model.with_chart(chart)
    x = to_chart(chart, model.chart.to_paper(x0))
    prolate = m.body.is_prolate
    ev = Event("theta", 0.1 if prolate else math.pi / 2 - 0.1, direction=-1 if prolate else +1, name="rise-complete")
    row = partial(PairRow, pair_key(label, value, eps, chart, t_end), case.figure, label, role, value, eps, chart)
    t0 = time.perf_counter()
    try:
        r = simulate(m, x, t_end, events=[ev], track_minima=False, dense=False, max_wall=max_wall)
    except PhasekitError as exc:  # e.g. a start the Euler chart cannot take
        return row("failed", 0.0, None, False, 0, None, "failed", time.perf_counter() - t0, str(exc))
    y = r.euler_end if r.status is not Status.FAILED else None
    return row(outcome_class(r.status, r.stuck), float(r.t), r.t_jump, r.stuck, len(r.events_named("stick")),
               None if y is None else float(y[4]), r.status.value, time.perf_counter() - t0, r.reason or "")


def pair_runs(eps_list, charts, *, t_end: float, max_wall: float = 300.0) -> list:
    """Tasks (:func:`phasekit.sweep.each`) of every run of both printed pairs: each value under
    each ``eps`` and exact Coulomb, in each chart, keyed by :func:`pair_key`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> specs = ps.pair_runs([1e-3], ("euler",), t_end=600.0)
    >>> len(specs), specs[0].key
    (8, '5.1|10|0.001|euler|t_end=600')
    """
    runs = [(label, role, value, eps, chart) for label, case in PAPER_CASES.items()
            for role, value in (("no_jump", case.no_jump), ("jump", case.jump))
            for eps in list(eps_list) + [None] for chart in charts]
    return each(runs, lambda label, role, value, eps, chart: pair_key(label, value, eps, chart, t_end),
                partial(pair_run, t_end=t_end, max_wall=max_wall))


def as_printed(no_jump: PairRow | None, jump: PairRow | None, t_printed: float, t_tolerance: float) -> bool:
    """Whether a pair came out as printed: the first value rose without a jump, the second
    jumped with t* within ``t_tolerance`` (relative) of ``t_printed``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.as_printed(None, None, 111.0, 0.15)
    False
    """
    return (no_jump is not None and jump is not None and no_jump.outcome == "rise" and jump.outcome == "jump"
            and abs(jump.t_jump / t_printed - 1) <= t_tolerance)


def pair_table(rows, eps_list, charts, t_tolerance: float) -> list[dict]:
    """Per (pair, chart, eps; exact Coulomb last): the two outcomes, (outcome, time) each (the
    jump time of a jump, else the time reached; None if not run), and whether the pair is
    :func:`as_printed`; ``eps`` as text ("exact" or its repr).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> tab = ps.pair_table([], [1e-3], ("euler",), 0.15)
    >>> len(tab), tab[1]["eps"], tab[1]["as_printed"]
    (4, 'exact', False)
    """
    out = []
    by = {(r.label, r.role, r.eps, r.chart): r for r in rows}
    for label, case in PAPER_CASES.items():
        for chart in charts:
            for eps in list(eps_list) + [None]:
                e = "exact" if eps is None else repr(eps)  # as the summary and report spell it
                nj, j = by.get((label, "no_jump", eps, chart)), by.get((label, "jump", eps, chart))
                out.append({"figure": case.figure, "label": label, "chart": chart, "eps": e,
                            "no_jump": None if nj is None else (nj.outcome, nj.t_end),
                            "jump": None if j is None else (j.outcome, j.t_jump if j.t_jump else j.t_end),
                            "as_printed": as_printed(nj, j, case.t_jump, t_tolerance)})
    return out


def pair_report(table) -> tuple[list[str], dict]:
    """The lines of a :func:`pair_table` as text, and the eps of each (pair, chart) for which
    the pair is as printed (keyed "label|chart").

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> lines, summary = ps.pair_report(ps.pair_table([], [1e-3], ("euler",), 0.15))
    >>> len(lines), summary
    (4, {'5.1|euler': [], '5.2|euler': []})
    """
    lines = []
    for t in table:
        nj = "-" if t["no_jump"] is None else f"{t['no_jump'][0]} (t = {t['no_jump'][1]:.1f})"
        j = "-" if t["jump"] is None else f"{t['jump'][0]} (t = {t['jump'][1]:.2f})"
        lines.append(f"  {t['figure']} ({t['label']}) {t['chart']:<6s} eps={t['eps']:<22s} first: {nj:<24s} "
                     f"second: {j:<24s}{'  AS PRINTED' if t['as_printed'] else ''}")
    hits = [t for t in table if t["as_printed"]]
    summary = {f"{t['label']}|{t['chart']}": [h["eps"] for h in hits if h["label"] == t["label"] and h["chart"] == t["chart"]]
               for t in table}
    return lines, summary
