"""The rows of the threshold and map studies, and the tasks that compute them (a study-support
module: the task runner is :mod:`phasekit.sweep.tasks`).

* :class:`ThresholdRow` and :func:`threshold_task`: one threshold of a sweep over bodies, continued
  from the previous body's (studies/threshold_vs_aspect.py).
* :class:`SearchRow`, :func:`search_job`, :func:`group_search_tasks` (their stored rows: :func:`phasekit.sweep.tasks.stored_rows`): traced
  boundary points (jump thresholds, sticking boundaries), several searches per task in lock-step
  so that the batch integrator's lanes fill across them (studies/threshold_vs_mu.py, outcome_map.py).
* :class:`OutcomeRow` and :func:`outcome_task`: classified starts of an outcome map.
* What the studies read off the stored rows: :func:`outcome_map_summary` (an outcome map's
  classes and traced boundaries, checked against each other), :func:`threshold_collapse` and
  :func:`threshold_against_d` (thresholds over (a, mu) and against the seed distance).
* The stored rows as text tables (the studies' reports): :func:`threshold_table`,
  :func:`definition_sensitivity_table`, :func:`threshold_grid_table`, :func:`seed_sensitivity_table`.
* :func:`threshold_chain`: the tasks of one threshold curve, each seeded by its neighbour's.
* :class:`OutcomeMapPlan`: the tasks of an outcome map (its sampled starts and traced boundaries),
  and :func:`outcome_map_report`, its summary as text.
* :func:`stability_grid`: part I's linear-stability map of the steady states over (a, rate).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from dataclasses import asdict, dataclass, replace
from functools import partial

import numpy as np

from .._runtime.errors import SearchStatus, Status
from ..sweep.tasks import TaskSpec, chunked
from ..thresholds.threshold import (
    Definition,
    evaluate_outcomes,
    find_threshold,
    run_searches,
    stick_search,
    threshold_result,
    threshold_searches,
)

__all__ = ["ThresholdRow", "threshold_task", "threshold_key", "threshold_chain", "SearchRow", "search_job",
           "search_group_task", "group_search_tasks", "OutcomeRow", "outcome_task", "outcome_key", "OUTCOME_KINDS", "outcome_class",
           "outcome_map_summary", "OutcomeMapPlan", "outcome_map_report", "threshold_collapse", "threshold_against_d", "stability_grid", "threshold_table",
           "definition_sensitivity_table", "threshold_grid_table", "seed_sensitivity_table"]

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


# -- threshold rows --------------------------------------------------------------------------


@dataclass(frozen=True)
class ThresholdRow:
    """One threshold of a sweep, as stored (see :func:`threshold_task`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> row = ps.threshold_task(None, asdict(pk.Definition('sliding', 'sliding')), 1.5, 'main', True, dict(hi=120.0, tol=0.05))
    >>> isinstance(row, ps.ThresholdRow), row.status, round(row.threshold, 1), row.consistent
    (True, 'converged', 9.7, True)
    """

    key: str
    branch: str
    a: float
    threshold: float | None
    bracket_lo: float | None
    bracket_hi: float | None
    n_sims: int
    status: str
    definition: str
    default: bool
    group: str
    name: str
    seed: str
    amplitude: float
    eps: float | None  # the regularised law's eps; empty for exact Coulomb and viscous friction (see definition)
    mu: float
    rtol: float
    transitions: str  # JSON list of [lo, hi] brackets
    stuck_near: bool | None
    check_above_jumped: bool | None
    check_below_jumped: bool | None
    consistent: bool | None
    n_check_sims: int
    wall_s: float
    reason: str


def threshold_key(defn, a: float, search: dict) -> str:
    """Key of a stored threshold row: every input that changes the answer.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.threshold_key(pk.Definition('sliding', 'sliding'), 1.5, {'tol': 1e-3})
    'amplitude=0.01;eps=None;max_steps=20000000;mu=0.1;rise_margin=0.1;rtol=1e-09;seed=sliding;t_max=3000.0|a=1.5|search={"tol": 0.001}'
    """
    return f"{defn.key()}|a={a:.10g}|search={json.dumps(search, sort_keys=True)}"


def threshold_task(prev: ThresholdRow | None, defn_fields: dict, a: float, group: str, is_default: bool,
                   search: dict, engine: str = "scalar", levels: int = 1) -> ThresholdRow:
    """One sweep task: the threshold at aspect ratio ``a`` (the search seeded by the previous
    point's row ``prev``), then the self-consistency check (1.02 x jumps, 0.98 x does not).
    ``engine`` and ``levels`` (k-section) change the cost, not the bracket, and are not
    part of the key. Failures become a row with status "failed" and the reason.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> row = ps.threshold_task(None, asdict(pk.Definition('sliding', 'sliding')), 1.5, 'main', True, dict(hi=120.0, tol=0.05))
    >>> row.branch, row.status, round(row.threshold, 1)
    ('prolate', 'converged', 9.7)
    """
    defn = Definition(**defn_fields)
    t0 = time.perf_counter()
    base = dict(key=threshold_key(defn, a, search), branch="prolate" if a > 1 else "oblate", a=a,
                definition=defn.label, default=is_default, group=group, name=defn.name, seed=defn.seed,
                amplitude=defn.amplitude, mu=defn.mu, rtol=defn.rtol,
                eps=defn.eps or None)
    guess = prev.threshold if prev is not None else None
    try:
        th = find_threshold(defn, a, guess=guess, engine=engine, levels=levels, **search)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        return ThresholdRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, n_sims=0, status=Status.FAILED.value,
                            transitions="[]", stuck_near=None, check_above_jumped=None, check_below_jumped=None,
                            consistent=None, n_check_sims=0, wall_s=time.perf_counter() - t0,
                            reason=f"{type(exc).__name__}: {exc}")
    above = below = consistent = None
    n_check = 0
    if th.value is not None and th.status in (SearchStatus.CONVERGED, SearchStatus.NON_MONOTONE):  # not for bracket_only
        above, below = (o.jumped for o in defn.outcomes(a, [1.02 * th.value, 0.98 * th.value], engine=engine))
        n_check = 2
        consistent = bool(above) and below is False
    return ThresholdRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], n_sims=th.n_sims,
                        status=th.status.value, transitions=json.dumps([list(t) for t in th.transitions]),
                        stuck_near=th.stuck_near, check_above_jumped=above, check_below_jumped=below,
                        consistent=consistent, n_check_sims=n_check, wall_s=time.perf_counter() - t0,
                        reason=th.reason or "")


# -- search and outcome rows (the outcome map and the (a, mu) map) ------------------------------


@dataclass(frozen=True)
class SearchRow:
    """One traced boundary point, as stored: a jump threshold in the family parameter at
    seed distance ``d`` (kind "threshold"), or the sticking boundary d_min in the seed
    distance at the family parameter ``value`` (kind "stick"). ``threshold`` is the
    boundary (Omega0*/n0* or d_min), ``n_rounds`` its search's rounds of independent
    simulations, ``sens_*`` the sensitivity to d when asked (d/2 and 2d).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> job = ps.search_job(asdict(pk.Definition('sliding', 'sliding')), 1.5, dict(hi=120.0, tol=1e-2, guess=9.74))
    >>> [row] = ps.group_search_tasks([job], [1.0], per_task=1)[0][0].func(None, [job])
    >>> isinstance(row, ps.SearchRow), row.kind, row.status, round(row.threshold, 2)
    (True, 'threshold', 'converged', 9.78)
    """

    key: str
    study: str
    kind: str
    branch: str
    a: float
    mu: float
    d: float | None
    value: float | None
    threshold: float | None
    bracket_lo: float | None
    bracket_hi: float | None
    status: str
    n_sims: int
    n_rounds: int
    levels: int
    engine: str
    eps: float | None  # the regularised law's eps; empty for exact Coulomb (no regularisation)
    rtol: float
    t_max: float
    transitions: str
    stuck_near: bool
    sens_half: float | None
    sens_double: float | None
    sens_slope: float | None
    sens_shift: float | None
    sens_dominant: str
    wall_s: float
    reason: str


def search_key(defn, a: float, search: dict, kind: str = "threshold", value: float | None = None,
               sensitivity: bool = False) -> str:
    """Key of a stored search row: every input that changes the answer (the engine does not)."""
    v = "" if value is None else f"|value={value:.10g}"
    sens = "|sensitivity" if sensitivity else ""
    return f"{kind}|{defn.key()}|a={a:.10g}{v}|search={json.dumps(search, sort_keys=True)}{sens}"


def search_job(defn_fields: dict, a: float, search: dict, *, kind: str = "threshold", value: float | None = None,
               sensitivity: bool = False) -> dict:
    """One boundary point to trace, as :func:`search_group_task` takes it: a jump threshold
    at seed distance ``defn_fields["amplitude"]`` (kind "threshold"), or the sticking
    boundary d_min at the family parameter ``value`` (kind "stick"); ``search`` holds the
    keywords of :func:`phasekit.thresholds.threshold.threshold_searches` or ``stick_search``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> job = ps.search_job(asdict(pk.Definition('sliding', 'sliding')), 1.5, {'tol': 1e-3})
    >>> job['kind'], job['a'], job['search']
    ('threshold', 1.5, {'tol': 0.001})
    """
    return dict(defn=dict(defn_fields), a=float(a), search=dict(search), kind=kind, value=value, sensitivity=sensitivity)


def search_group_task(prev, jobs: list[dict], *, study: str = "", engine: str = "batch") -> list[SearchRow]:
    """Several boundary points (:func:`search_job`) traced in lock-step: each round
    simulates what every unfinished search asks for in one batch (so the batch integrator's
    lanes fill across searches); each search keeps its own rounds, bracket and result.
    Failures become rows with status "failed" and the reason."""
    t0 = time.perf_counter()
    plans, rows = [], [None] * len(jobs)
    for i, job in enumerate(jobs):
        defn = Definition(**job["defn"])
        try:
            if job["kind"] == "stick":
                searches = [stick_search(defn, job["a"], job["value"], **job["search"])]
            else:
                searches = threshold_searches(defn, job["a"], sensitivity=job["sensitivity"], **job["search"])
            plans.append((i, defn, searches))
        except Exception as exc:
            rows[i] = _search_row(job, defn, None, study, engine, 0.0, f"{type(exc).__name__}: {exc}")
    try:
        run_searches([s for _, _, ss in plans for s in ss], engine=engine)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        for i, defn, _ in plans:
            rows[i] = _search_row(jobs[i], defn, None, study, engine, time.perf_counter() - t0, f"{type(exc).__name__}: {exc}")
        return rows
    wall = (time.perf_counter() - t0) / max(1, len(plans))  # lock-step: the group's time, shared
    for i, defn, searches in plans:
        th = searches[0].result(wall) if jobs[i]["kind"] == "stick" else threshold_result(searches, wall)
        rows[i] = _search_row(jobs[i], defn, th, study, engine, wall, th.reason or "")
    return rows


def _job_key(job: dict) -> str:
    """The stored row key of a :func:`search_job`."""
    return search_key(Definition(**job["defn"]), job["a"], job["search"], job["kind"], job["value"], job["sensitivity"])


def group_search_tasks(jobs: list[dict], costs: list[float], *, per_task: int, study: str = "",
                       engine: str = "batch") -> tuple[list[TaskSpec], dict[str, list[str]]]:
    """Independent tasks of up to ``per_task`` searches each, traced in lock-step by
    :func:`search_group_task`: searches of one branch (one batch integrator) and of similar
    cost share a task. Returns the tasks (cost: the sum of their searches') and, per task
    key, the row keys it produces (a task is done when all of them are stored).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> jobs = [ps.search_job(asdict(pk.Definition('sliding', 'sliding', amplitude=d)), 1.5, {}) for d in (0.01, 0.02)]
    >>> specs, members = ps.group_search_tasks(jobs, [1.0, 2.0], per_task=2)
    >>> len(specs), [len(keys) for keys in members.values()]
    (1, [2])
    """
    task = partial(search_group_task, study=study, engine=engine)
    order = sorted(range(len(jobs)), key=lambda i: (jobs[i]["a"] > 1, -costs[i]))
    specs, members = [], {}
    for branch in (False, True):
        idx = [i for i in order if (jobs[i]["a"] > 1) == branch]
        for k in range(0, len(idx), per_task):
            part = idx[k:k + per_task]
            keys = [_job_key(jobs[i]) for i in part]
            key = "group|" + hashlib.sha256("|".join(keys).encode()).hexdigest()[:20]
            specs.append(TaskSpec(key, task, ([jobs[i] for i in part],), cost=sum(costs[i] for i in part),
                                  label=f"{len(part)} searches"))
            members[key] = keys
    return specs, members


def _search_row(job, defn, th, study, engine, wall, reason) -> SearchRow:
    kind, a = job["kind"], job["a"]
    base = dict(key=search_key(defn, a, job["search"], kind, job["value"], job["sensitivity"]), study=study, kind=kind,
                branch="prolate" if a > 1 else "oblate", a=a, mu=defn.mu, d=defn.amplitude if kind == "threshold" else None,
                value=job["value"], levels=int(job["search"].get("levels", 1)), engine=engine, rtol=defn.rtol, t_max=defn.t_max,
                eps=defn.eps or None, wall_s=wall, reason=reason)
    if th is None:
        return SearchRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, status=Status.FAILED.value, n_sims=0,
                         n_rounds=0, transitions="[]", stuck_near=False, sens_half=None, sens_double=None, sens_slope=None,
                         sens_shift=None, sens_dominant="")
    sens = th.sensitivity
    return SearchRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], status=th.status.value,
                     n_sims=th.n_sims + (0 if sens is None else sens.n_sims), n_rounds=th.n_rounds,
                     transitions=json.dumps([list(t) for t in th.transitions]),
                     stuck_near=th.stuck_near if kind == "threshold" else False,
                     sens_half=None if sens is None else sens.values[0], sens_double=None if sens is None else sens.values[2],
                     sens_slope=None if sens is None else sens.slope, sens_shift=None if sens is None else sens.shift,
                     sens_dominant="" if sens is None or sens.dominant is None else sens.dominant)


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


def threshold_chain(defn, a_values, search: dict, *, group: str = "main", is_default: bool = False,
                    engine: str = "scalar", levels: int = 1, after: str | None = None) -> list[TaskSpec]:
    """The tasks of one threshold curve (:func:`threshold_task`): one per aspect ratio, in the
    order of ``a_values`` (from far to near a = 1, where thresholds grow), each search seeded by
    the threshold before it (the first by the task ``after``, if given). Keys: :func:`threshold_key`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> specs = ps.threshold_chain(pk.Definition('sliding', 'sliding'), [2.0, 1.5], {'tol': 1e-3})
    >>> [s.after is None for s in specs]
    [True, False]
    """
    specs, prev = [], after
    for a in a_values:
        key = threshold_key(defn, a, search)
        specs.append(TaskSpec(key, threshold_task, (asdict(defn), a, group, is_default, search, engine, levels), after=prev))
        prev = key
    return specs


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


# -- what the studies read off the stored rows ----------------------------------------------------


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


def threshold_collapse(rows, mus, ref_mu: float) -> dict:
    """The collapse test of thresholds over (a, mu) (``rows``: :class:`SearchRow` at one seed
    distance): are the thresholds at every mu one factor f(mu) times those at ``ref_mu``? Per
    branch and mu: f, the geometric mean over a of T(a, mu)/T(a, ref_mu); ``spread``, the
    largest ``|ln(T / (f T_ref))|`` that remains; ``raw_spread``, the same with f = 1; ``n``, the
    aspect ratios compared. Also the largest of each over everything (``max_spread``,
    ``max_raw_spread``; None without two aspect ratios to compare).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(branch='prolate', a=a, mu=mu, threshold=t * (2 if mu == 0.5 else 1)) for a, t in ((1.5, 10.0), (2.0, 8.0))
    ...         for mu in (0.1, 0.5)]
    >>> c = ps.threshold_collapse(rows, [0.1, 0.5], 0.1)
    >>> round(c['prolate'][0.5]['f'], 6), round(c['max_spread'], 6)
    (2.0, 0.0)
    """
    out = {}
    for branch in ("prolate", "oblate"):
        ref = {r.a: r.threshold for r in rows if r.branch == branch and r.mu == ref_mu and r.threshold}
        per_mu = {}
        for mu in mus:
            ratios = [math.log(r.threshold / ref[r.a]) for r in rows
                      if r.branch == branch and r.mu == mu and r.threshold and r.a in ref]
            if len(ratios) < 2:
                continue
            lnf = float(np.mean(ratios))
            per_mu[mu] = {"f": math.exp(lnf), "spread": float(max(abs(x - lnf) for x in ratios)),
                          "raw_spread": float(max(abs(x) for x in ratios)), "n": len(ratios)}
        out[branch] = per_mu
    spreads = [v["spread"] for b in out.values() for v in b.values()]
    raw = [v["raw_spread"] for b in out.values() for v in b.values()]
    out["max_spread"] = max(spreads) if spreads else None
    out["max_raw_spread"] = max(raw) if raw else None
    return out


def threshold_against_d(rows, a_values, mus) -> dict:
    """Thresholds against the seed distance d (``rows``: :class:`SearchRow`), per aspect ratio
    in ``a_values`` and mu in ``mus`` with at least two d: the d, thresholds and statuses in the
    order of d, and the relative change per halving of d (None where a threshold is missing:
    a start that sticks has none). Keyed ``"a=1.5 mu=0.1"``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(a=1.5, mu=0.1, d=d, threshold=t, status='converged') for d, t in ((0.01, 10.0), (0.02, 8.0))]
    >>> ps.threshold_against_d(rows, [1.5], [0.1])['a=1.5 mu=0.1']['change_per_halving']
    [0.25]
    """
    out = {}
    for a in a_values:
        for mu in mus:
            pts = sorted(((r.d, r) for r in rows if abs(r.a - a) < 1e-12 and r.mu == mu and r.d is not None),
                         key=lambda q: q[0])
            if len(pts) < 2:
                continue
            ds = [d for d, _ in pts]
            th = [r.threshold for _, r in pts]
            steps = [(th[i] / th[i + 1] - 1) if th[i] and th[i + 1] else None for i in range(len(th) - 1)]
            out[f"a={a:.4g} mu={mu:.4g}"] = {"d": ds, "threshold": th, "status": [r.status for _, r in pts],
                                            "change_per_halving": steps}
    return out


def stability_grid(kind: str, a_values, rates, *, mu: float, progress=None) -> np.ndarray:
    """Part I's stability map of uniform spheroids under viscous friction ``mu``: the dimension
    of the unstable subspace (exact linearisation, :func:`phasekit.linearise`) of the
    horizontal steady precession at Omega0 (``kind="horizontal"``) or of the vertical spin at n0
    (``kind="vertical"``), for every rate in ``rates`` (rows) and aspect ratio in ``a_values``
    (columns). ``progress``: a bar advanced by one column at a time.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.stability_grid("vertical", [0.5, 2.0], [1.0, 12.0], mu=0.1).tolist()
    [[2, 2], [2, 0]]
    """
    from ..bodies.body import Spheroid
    from ..core.model import Model
    from ..friction.laws import Viscous
    from ..steady.fixedpoints import horizontal_state, linearise, vertical_state

    out = np.zeros((len(rates), len(a_values)), dtype=int)
    for j, a in enumerate(a_values):
        m = Model(Spheroid(a), Viscous(mu), "euler" if kind == "horizontal" else "vector")
        for i, s in enumerate(rates):
            x = horizontal_state(s) if kind == "horizontal" else vertical_state(s)
            out[i, j] = linearise(m, x, kind=kind).n_unstable
        if progress is not None:
            progress.update(len(rates))
    return out


# -- the stored rows as text tables (the studies' reports) -------------------------------------------


def threshold_table(rows, *, first: str) -> str:
    """The main rows of a threshold sweep (:class:`ThresholdRow` of group "main") as a text
    table, the definition named ``first`` first: definition, branch, a, threshold, status,
    simulations and the self-consistency check (1.02 x jumps, 0.98 x does not); then how many
    of the checked points pass it.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> r = Row(group="main", name="sliding", definition="sliding", branch="prolate", a=1.5, threshold=9.75,
    ...         status="converged", n_sims=30, consistent=True)
    >>> print(ps.threshold_table([r], first="sliding").splitlines()[-1])
    self-consistency (1.02 x jumps, 0.98 x does not): 1 of 1 points pass
    """
    main = [r for r in rows if r.group == "main"]
    lines = [f"{'definition':<58s} {'branch':<8s} {'a':>6s} {'threshold':>10s} {'status':<17s} {'sims':>4s} {'check':>5s}"]
    for r in sorted(main, key=lambda r: (r.name != first, r.name, r.branch, r.a)):
        check = "ok" if r.consistent else "FAIL" if r.consistent is False else "-"
        th = f"{r.threshold:.4f}" if r.threshold else "-"
        lines.append(f"{r.definition[:58]:<58s} {r.branch:<8s} {r.a:6.3f} {th:>10s} {r.status:<17s} {r.n_sims:>4d} {check:>5s}")
    bad = [r for r in main if r.consistent is False]
    checked = [r for r in main if r.consistent is not None]
    lines.append(f"self-consistency (1.02 x jumps, 0.98 x does not): {len(checked) - len(bad)} of {len(checked)} points pass")
    return "\n".join(lines)


def definition_sensitivity_table(rows, *, parent) -> str:
    """The sensitivity rows of a threshold sweep (:class:`ThresholdRow` of group "sensitivity")
    against the main row of their parent definition at the same a (``parent(row)``: its name):
    the threshold (or the status), its relative change, and whether the search stuck near it.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> rows = [Row(group="main", name="sliding", a=1.5, threshold=10.0),
    ...         Row(group="sensitivity", name="sliding-d0.02", a=1.5, threshold=10.1, status="converged", stuck_near=False)]
    >>> print(ps.definition_sensitivity_table(rows, parent=lambda r: "sliding"))
      sliding-d0.02                  a=1.5000 threshold=10.1000            vs sliding: +1.00e-02  stuck near threshold: False
    """
    ref = {(r.name, r.a): r.threshold for r in rows if r.group == "main"}
    lines = []
    for r in sorted((r for r in rows if r.group == "sensitivity"), key=lambda r: (r.name, r.a)):
        base = ref.get((parent(r), r.a))
        rel = f"{(r.threshold / base - 1):+.2e}" if r.threshold and base else "-"
        th = f"{r.threshold:.4f}" if r.threshold else r.status
        lines.append(f"  {r.name:<30s} a={r.a:.4f} threshold={th:<18s} vs {parent(r)}: {rel}  stuck near threshold: {r.stuck_near}")
    return "\n".join(lines)


def threshold_grid_table(rows, mus) -> str:
    """Thresholds over (a, mu) (:class:`SearchRow` at one seed distance) as a text table: a row
    per branch and aspect ratio, a column per mu in ``mus`` (the status where there is no
    threshold, "-" where there is no row).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> print(ps.threshold_grid_table([Row(branch="prolate", a=1.5, mu=0.1, threshold=9.75, status="converged")], [0.1, 0.5]))
    branch        a     mu=0.1     mu=0.5
    prolate   1.500     9.7500          -
    """
    lines = [f"{'branch':<8s} {'a':>6s} " + " ".join(f"{'mu=' + format(mu, '.3g'):>10s}" for mu in mus)]
    for branch in ("prolate", "oblate"):
        for a in sorted({r.a for r in rows if r.branch == branch}):
            cells = []
            for mu in mus:
                r = next((r for r in rows if r.a == a and r.mu == mu), None)
                cells.append(f"{r.threshold:10.4f}" if r and r.threshold else f"{(r.status if r else '-'):>10s}")
            lines.append(f"{branch:<8s} {a:6.3f} " + " ".join(cells))
    return "\n".join(lines)


def seed_sensitivity_table(rows) -> str:
    """The searches that measured their sensitivity to the seed distance (:class:`SearchRow`
    with ``sens_*``) as text lines, by branch and a: the threshold T*, T* at d/2 and 2d, the
    slope d ln T*/d ln d, the largest shift, the bracket's relative width, and what dominates.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from types import SimpleNamespace as Row
    >>> r = Row(branch="prolate", a=1.5, threshold=10.0, bracket_lo=9.995, bracket_hi=10.005, sens_half=10.2, sens_double=9.8,
    ...         sens_slope=-0.03, sens_shift=0.02, sens_dominant="seed distance")
    >>> print(ps.seed_sensitivity_table([r]))  # doctest: +NORMALIZE_WHITESPACE
      prolate  a= 1.500 T*= 10.0000 T*(d/2)= 10.2000 T*(2d)=  9.8000 slope=-0.030 max shift=2.000% bracket=1.0e-03
      -> seed distance
    """
    lines = []
    for r in sorted((r for r in rows if r.sens_dominant), key=lambda r: (r.branch, r.a)):
        width = r.bracket_hi / r.bracket_lo - 1
        lines.append(f"  {r.branch:<8s} a={r.a:6.3f} T*={r.threshold:8.4f} T*(d/2)={r.sens_half or float('nan'):8.4f} "
                     f"T*(2d)={r.sens_double or float('nan'):8.4f} slope={r.sens_slope if r.sens_slope is not None else float('nan'):+.3f} "
                     f"max shift={r.sens_shift if r.sens_shift is not None else float('nan'):.3%} bracket={width:.1e} -> {r.sens_dominant}")
    return "\n".join(lines)
