"""The outcome maps (studies/outcome_map.py): their rows, the tasks that compute them, and what
the study reads off them (a study-support module: the task runner is :mod:`phasekit.sweep.tasks`).

* :data:`OUTCOME_KINDS` and :func:`outcome_class`: the classes of a start.
* :class:`OutcomeRow` and :func:`outcome_task`: classified starts of an outcome map.
* :class:`OutcomeMapPlan`: the tasks of an outcome map (its sampled starts and traced boundaries,
  :class:`phasekit.studies.SearchRow`).
* :func:`outcome_map_summary`: an outcome map's classes and traced boundaries, checked against
  each other, and :func:`outcome_map_report`, its summary as text.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from functools import partial

import numpy as np

from ..errors import Status
from ..sweep.tasks import TaskSpec, chunked
from ..thresholds.definition import Definition, evaluate_outcomes
from .threshold_rows import group_search_tasks, search_job

#: the classes of an :class:`OutcomeRow`, in the order the studies count and draw them
OUTCOME_KINDS = ("stuck", "rise", "jump", "slow", "failed")


def outcome_class(status: Status, stuck: bool) -> str:
    """The class (:data:`OUTCOME_KINDS`) of a run that stops at a jump or at the end of the rise
    (an event that stops it): "jump" (it lost contact), "rise" (stopped: the rise completed),
    "failed", else "stuck" or "slow" by whether it stuck on the way.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.outcome_class(pk.Status.STOPPED, False), ps.outcome_class(pk.Status.COMPLETED, True)
    ('rise', 'stuck')
    """
    if status is Status.JUMPED:
        return "jump"
    if status is Status.STOPPED:
        return "rise"
    if status is Status.FAILED:
        return "failed"
    return "stuck" if stuck else "slow"


# -- outcome rows ------------------------------------------------------------------------------


@dataclass(frozen=True)
class OutcomeRow:
    """One sampled start of an outcome map: its class ("jump", "rise", "stuck", "slow",
    "failed"), when it ended (``t_end``; ``t_jump`` for a jump) and where (``theta_end``,
    ``rise_fraction``: the share of the rise done when it ended).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> rows = ps.outcome_task(None, [(1.5, 0.01, 12.0)], asdict(pk.Definition("sliding", "sliding")))
    >>> isinstance(rows[0], ps.OutcomeRow), rows[0].outcome
    (True, 'jump')
    """

    key: str
    study: str
    branch: str
    a: float
    mu: float
    d: float
    value: float
    outcome: str
    t_jump: float | None
    t_end: float
    theta_end: float | None
    rise_fraction: float | None
    stuck: bool
    status: str
    wall_s: float
    reason: str


def outcome_key(defn, a: float, value: float) -> str:
    """Key of a stored outcome row: the definition (with its seed distance), a and the value.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.outcome_key(pk.Definition('sliding', 'sliding'), 1.5, 12.0).startswith('outcome|')
    True
    """
    return f"outcome|{defn.key()}|a={a:.10g}|value={value:.10g}"


def outcome_task(prev, points: list, defn_fields: dict, *, study: str = "", engine: str = "batch") -> list[OutcomeRow]:
    """Classify a list of starts (a, d, value) of one definition (d replaces its amplitude),
    all at once on the batch integrator (a task of :func:`phasekit.sweep.chunked` starts).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> rows = ps.outcome_task(None, [(1.5, 0.01, 12.0), (1.5, 0.01, 4.0)], asdict(pk.Definition("sliding", "sliding")))
    >>> [(r.value, r.outcome) for r in rows]
    [(12.0, 'jump'), (4.0, 'stuck')]
    """
    defn = Definition(**defn_fields)
    jobs = [(replace(defn, amplitude=d), a, v) for a, d, v in points]
    outs = evaluate_outcomes(jobs, engine=engine)
    rows = []
    for (d_defn, a, v), o in zip(jobs, outs):
        rows.append(OutcomeRow(key=outcome_key(d_defn, a, v), study=study, branch="prolate" if a > 1 else "oblate", a=a,
                               mu=d_defn.mu, d=d_defn.amplitude, value=v, outcome=o.kind,
                               t_jump=o.t if o.jumped else None, t_end=o.t, theta_end=o.theta, rise_fraction=o.rise_fraction,
                               stuck=o.stuck, status=o.status.value, wall_s=o.wall_s, reason=o.reason or ""))
    return rows


@dataclass(frozen=True)
class OutcomeMapPlan:
    """The tasks of an outcome map (studies/outcome_map.py): starts of ``definition`` at seed
    distance d in ``d_range`` (log-spaced) and family parameter (Omega0 or n0) from
    ``value_span[0]`` to ``value_span[1]`` times the definition's lower bound at each aspect
    ratio, classified in chunks (:func:`outcome_task`); and the boundaries traced between them
    (:func:`search_job`, several in lock-step per task): the jump threshold along d-lines
    (``threshold_search``) and the sticking boundary d_min along value-lines (``stick_search``),
    with value-lines added where d_min turns a corner (:meth:`corners`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> plan = ps.OutcomeMapPlan(pk.Definition("sliding", "sliding"), {}, {}, (1e-3, 0.2), (2.0, 12.0))
    >>> specs, keys = plan.grid_tasks([1.5], n_value=3, n_d=2, chunk=4)
    >>> len(specs), sum(len(k) for k in keys.values())
    (2, 6)
    >>> specs, members = plan.boundary_tasks({("threshold", 1.5, 0.01), ("stick", 1.5, 8.0)}, per_task=2)
    >>> len(specs), sum(len(k) for k in members.values())
    (1, 2)
    """

    definition: Definition
    threshold_search: dict
    stick_search: dict
    d_range: tuple
    value_span: tuple
    steep: float = 2.0  # the d_min ratio between neighbouring value-lines above which a line is added between them
    study: str = ""
    engine: str = "batch"

    def value_range(self, a: float) -> tuple[float, float]:
        """The family parameter's range at aspect ratio ``a``."""
        lo = self.definition.lower_bound(a)
        return self.value_span[0] * lo, self.value_span[1] * lo

    def grid_tasks(self, maps, *, n_value: int, n_d: int, chunk: int) -> tuple[list[TaskSpec], dict]:
        """Tasks of ``chunk`` sampled starts each (an ``n_d`` x ``n_value`` grid per aspect ratio
        in ``maps``); returns them and each task's row keys."""
        base = self.definition
        task = partial(outcome_task, study=self.study, engine=self.engine)
        specs, keys = [], {}
        for a in maps:
            vs = np.geomspace(*self.value_range(a), n_value)
            points = [(a, float(d), float(v)) for d in np.geomspace(*self.d_range, n_d) for v in vs]
            s, k = chunked(points, lambda aa, d, v: outcome_key(replace(base, amplitude=d), aa, v), task, size=chunk,
                           args=(asdict(base),), prefix=f"grid|a={a:.10g}", cost=3.0)
            specs += s
            keys.update(k)
        return specs, keys

    def lines(self, a_values, *, d_first: float, n_d: int, n_value: int) -> set:
        """The boundaries to trace at each aspect ratio: ``n_d`` d-lines from ``d_first`` to the
        top of the d range and ``n_value`` value-lines over the value range, as
        ``(kind, a, d or value)``."""
        points = set()
        for a in a_values:
            points |= {("threshold", a, float(d)) for d in np.geomspace(d_first, self.d_range[1], n_d)}
            points |= {("stick", a, float(v)) for v in np.geomspace(*self.value_range(a), n_value)}
        return points

    def boundary_tasks(self, points, *, per_task: int) -> tuple[list[TaskSpec], dict]:
        """The tasks tracing ``points`` (:meth:`lines`), ``per_task`` searches each
        (:func:`group_search_tasks`); returns them and each task's row keys."""
        jobs, costs = [], []
        for kind, a, x in sorted(points):
            if kind == "threshold":
                jobs.append(search_job(asdict(replace(self.definition, amplitude=x)), a, self.threshold_search))
                costs.append(1.0 + 0.3 / abs(a - 1))
            else:
                jobs.append(search_job(asdict(self.definition), a, self.stick_search, kind="stick", value=x))
                costs.append(3.0)
        return group_search_tasks(jobs, costs, per_task=per_task, study=self.study, engine=self.engine)

    def corners(self, searches, maps) -> set:
        """Where the traced sticking boundary of a map turns a corner (d_min changes by more than
        a factor ``steep`` between neighbouring value-lines, or one of them sticks at every d): a
        new value-line halfway (geometrically), so that the boundary is traced there too, not
        drawn as a straight line across the corner."""
        points = set()
        for a in maps:
            st = sorted((s.value, self.d_range[1] if s.status == "no_jump_in_range" else s.threshold)
                        for s in searches if s.kind == "stick" and abs(s.a - a) < 1e-12)
            for (v1, d1), (v2, d2) in zip(st, st[1:]):
                if d1 and d2 and max(d1 / d2, d2 / d1) > self.steep and v2 / v1 > 1.01:
                    points.add(("stick", a, float(math.sqrt(v1 * v2))))
        return points


# -- what the study reads off the stored rows ----------------------------------------------------


def outcome_map_summary(points, searches, a: float) -> dict:
    """An outcome map at aspect ratio ``a`` from its rows (``points``: :class:`OutcomeRow`,
    ``searches``: :class:`SearchRow`; other aspect ratios are left out): the count of each
    class, the traced jump threshold against d and d_min against the family parameter (value,
    boundary, status), the ranges of t* and of the share of the rise done at the jump, and
    ``grid_disagreements``: the sampled starts against the traced threshold (interpolated
    log-log between its d-lines) with a 3% margin: how many were checked (inside the traced d
    range), contradict it (jump more than 3% below it, or do not jump more than 3% above),
    or lie within the margin.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> rows = ps.outcome_task(None, [(1.5, 0.01, 12.0), (1.5, 0.01, 4.0)], asdict(pk.Definition("sliding", "sliding")))
    >>> s = ps.outcome_map_summary(rows, [], 1.5)
    >>> s["counts"]["jump"], s["counts"]["stuck"], s["grid_disagreements"]["checked"]
    (1, 1, 0)
    """
    pts = [p for p in points if abs(p.a - a) < 1e-12]
    mine = [s for s in searches if abs(s.a - a) < 1e-12]
    jp = [p for p in pts if p.outcome == "jump"]
    return {"counts": {k: sum(p.outcome == k for p in pts) for k in OUTCOME_KINDS},
            "threshold_vs_d": sorted((s.d, s.threshold, s.status) for s in mine if s.kind == "threshold"),
            "d_min_vs_value": sorted((s.value, s.threshold, s.status) for s in mine if s.kind == "stick"),
            "t_jump_range": [min((p.t_jump for p in jp), default=None), max((p.t_jump for p in jp), default=None)],
            "rise_fraction_range": [min((p.rise_fraction for p in jp), default=None),
                                    max((p.rise_fraction for p in jp), default=None)],
            "grid_disagreements": _disagreements(pts, mine)}


def _disagreements(pts, searches, margin: float = 0.03) -> dict:
    th = sorted((s.d, s.threshold) for s in searches if s.kind == "threshold" and s.status == "converged")
    if len(th) < 2:
        return {"checked": 0, "contradicting": 0, "within_margin": 0}
    ld, lt = np.log([d for d, _ in th]), np.log([t for _, t in th])
    checked = bad = close = 0
    for p in pts:
        if p.outcome == "failed" or not ld[0] <= math.log(p.d) <= ld[-1]:
            continue
        t = math.exp(np.interp(math.log(p.d), ld, lt))
        checked += 1
        if abs(p.value / t - 1) <= margin:
            close += 1
        elif (p.value < t and p.outcome == "jump") or (p.value > t and p.outcome != "jump"):
            bad += 1
    return {"checked": checked, "contradicting": bad, "within_margin": close}


def outcome_map_report(summary: dict) -> str:
    """Outcome maps' summaries (:func:`outcome_map_summary`, keyed by map) as text: per map its
    classes, the ranges of t* and of the rise share at the jump, the sampled starts against the
    traced threshold, and the traced boundaries.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = {"counts": {"jump": 1}, "t_jump_range": [1.0, 1.0], "rise_fraction_range": [0.5, 0.5],
    ...      "grid_disagreements": {}, "threshold_vs_d": [(0.01, 9.75, "converged")], "d_min_vs_value": []}
    >>> print(ps.outcome_map_report({"a=1.5": s}).splitlines()[1])
        jump threshold against d: d=0.01: 9.75
    """
    lines = []
    for k, v in summary.items():
        lines.append(f"  {k}: classes {v['counts']}; t* {v['t_jump_range']}; rise share at the jump {v['rise_fraction_range']}; "
                     f"sampled starts against the traced threshold (3% margin): {v['grid_disagreements']}")
        lines.append("    jump threshold against d: " + ", ".join(f"d={d:.3g}: {t:.4g}" if t else f"d={d:.3g}: {s}"
                                                              for d, t, s in v["threshold_vs_d"]))
        lines.append("    d_min against the family parameter: " + ", ".join(f"{x:.3g}: {t:.3g}" if t else f"{x:.3g}: {s}"
                                                                        for x, t, s in v["d_min_vs_value"]))
    return "\n".join(lines)
