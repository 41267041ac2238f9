"""The rows of the threshold searches, and the tasks that compute them (a study-support module:
the task runner is :mod:`phasekit.sweep.tasks`).

* :class:`ThresholdRow` and :func:`threshold_task`: one threshold of a sweep over bodies, continued
  from the previous body's (studies/threshold_vs_aspect.py); :func:`threshold_chain`: the tasks of
  one threshold curve, each seeded by its neighbour's.
* :class:`SearchRow`, :func:`search_job`, :func:`group_search_tasks` (their stored rows: :func:`phasekit.sweep.stores.stored_rows`): traced
  boundary points (jump thresholds, sticking boundaries), several searches per task in lock-step
  so that the batch integrator's lanes fill across them (studies/threshold_vs_mu.py, outcome_map.py).
"""

from __future__ import annotations

import hashlib
import json
import time
from dataclasses import asdict, dataclass, replace
from functools import partial

from ..errors import Status
from ..sweep.tasks import TaskSpec
from ..thresholds.definition import Definition
from ..thresholds.result import Threshold
from ..thresholds.search import ThresholdSearch, find_threshold, run_searches, threshold_result, threshold_searches
from ..thresholds.stick import stick_search
from ..thresholds.verify import verify_thresholds

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
    check_above_jumped: bool | None  # the bracket's upper end at check_rtol (it jumped in the search)
    check_below_jumped: bool | None  # the bracket's lower end at check_rtol (it did not jump in the search)
    consistent: bool | None  # the library's verdict: "verified" (phasekit.thresholds.verify)
    n_check_sims: int
    wall_s: float
    reason: str
    check_rtol: float | None  # the tolerance of the check of the reported bracket
    first_threshold: float | None  # the first search's threshold, where it failed its check and was searched again
    check_worst: float | None  # the largest relative change of a bracket end's end time at check_rtol


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
    point's row ``prev``), checked by the library (:func:`phasekit.find_threshold`'s verification:
    the bracket's ends at a ten times tighter tolerance, the search repeated there if they change
    their outcome). ``engine`` and ``levels`` (k-section) change the cost, not the bracket, and are
    not part of the key. Failures become a row with status "failed" and the reason.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> from dataclasses import asdict
    >>> row = ps.threshold_task(None, asdict(pk.Definition('sliding', 'sliding')), 1.5, 'main', True, dict(hi=120.0, tol=0.05))
    >>> row.branch, row.status, round(row.threshold, 1), row.consistent
    ('prolate', 'converged', 9.7, True)
    """
    defn = Definition(**defn_fields)
    t0 = time.perf_counter()
    base = dict(key=threshold_key(defn, a, search), branch="prolate" if a > 1 else "oblate", a=a,
                definition=defn.label, default=is_default, group=group, name=defn.name, seed=defn.seed,
                amplitude=defn.amplitude, mu=defn.mu, rtol=defn.rtol, eps=defn.eps or None)
    guess = prev.threshold if prev is not None else None
    try:
        th = find_threshold(defn, a, guess=guess, engine=engine, levels=levels, **search)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        return ThresholdRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, n_sims=0, status=Status.FAILED.value,
                            transitions="[]", stuck_near=None, check_above_jumped=None, check_below_jumped=None,
                            consistent=None, n_check_sims=0, wall_s=time.perf_counter() - t0,
                            reason=f"{type(exc).__name__}: {exc}", check_rtol=None, first_threshold=None, check_worst=None)
    v = th.verification
    final = {c.side: c for c in v.checks[:2]} if v is not None else {}
    return ThresholdRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1],
                        n_sims=th.n_sims, status=th.status.value,
                        transitions=json.dumps([list(t) for t in th.transitions]), stuck_near=th.stuck_near,
                        check_above_jumped=final["hi"].jumped if final else None,
                        check_below_jumped=final["lo"].jumped if final else None,
                        consistent=None if v is None else v.verified, n_check_sims=0 if v is None else len(v.checks),
                        wall_s=time.perf_counter() - t0, reason=th.reason or ("" if v is None or v.verified else v.detail),
                        check_rtol=final["hi"].rtol if final else None, first_threshold=None if v is None else v.first_value,
                        check_worst=None if v is None else v.worst)


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


# -- search rows (the outcome map and the (a, mu) map) ------------------------------------------


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
    verified: bool | None = None  # the library's check of a threshold (phasekit.thresholds.verify); None: not checked
    check_worst: float | None = None  # the largest relative change of a bracket end's end time at rtol / 10
    first_threshold: float | None = None  # the first search's threshold, where its check failed and it was searched again


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
    keywords of :func:`phasekit.thresholds.search.threshold_searches` or ``stick_search``.

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
    simulates what every unfinished search asks for in one call (so the batch integrator's
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
    results = {i: searches[0].result() if jobs[i]["kind"] == "stick" else threshold_result(searches) for i, _, searches in plans}
    checked = [i for i, _, _ in plans if jobs[i]["kind"] == "threshold"]
    try:  # the library's check of every threshold of the group, in one round (re-searches one by one)
        done = verify_thresholds([(Definition(**jobs[i]["defn"]), searches_of(plans, i)[0].body, results[i]) for i in checked],
                                 engine=engine, research=partial(_research, plans=plans, engine=engine))
        results.update(zip(checked, done))
    except Exception as exc:  # the unchecked results stand, saying why
        results = {i: replace(th, reason=th.reason or f"not verified: {type(exc).__name__}: {exc}") for i, th in results.items()}
    wall = (time.perf_counter() - t0) / max(1, len(plans))  # lock-step: the group's time, shared
    for i, defn, _ in plans:
        th = replace(results[i], wall_s=wall)
        rows[i] = _search_row(jobs[i], defn, th, study, engine, wall, th.reason or "")
    return rows


def searches_of(plans, i: int) -> list:
    """The searches of job ``i`` in :func:`search_group_task`'s plans (the threshold's own first)."""
    searches = next(ss for j, _, ss in plans if j == i)
    return [searches[1], searches[0], searches[2]] if len(searches) == 3 else searches


def _research(d, body, guess, *, plans, engine) -> Threshold:
    """A threshold search repeated (:func:`phasekit.thresholds.verify.verify_thresholds`) with the range of the
    group's search of that body."""
    main = next(searches_of(plans, i)[0] for i, _, _ in plans if searches_of(plans, i)[0].body is body)
    again = ThresholdSearch(d, body, lo=main.lo, hi=main.hi, guess=guess, n_coarse=main.n_coarse, window=main.window,
                            tol=main.tol, levels=main.levels)
    return threshold_result([again], run=True, engine=engine)


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
    sens, v = th.sensitivity, getattr(th, "verification", None)
    base.update(verified=None if v is None else v.verified, check_worst=None if v is None else v.worst,
                first_threshold=None if v is None else v.first_value)
    return SearchRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], status=th.status.value,
                     n_sims=th.n_sims + (0 if sens is None else sens.n_sims), n_rounds=th.n_rounds,
                     transitions=json.dumps([list(t) for t in th.transitions]),
                     stuck_near=th.stuck_near if kind == "threshold" else False,
                     sens_half=None if sens is None else sens.values[0], sens_double=None if sens is None else sens.values[2],
                     sens_slope=None if sens is None else sens.slope, sens_shift=None if sens is None else sens.shift,
                     sens_dominant="" if sens is None or sens.dominant is None else sens.dominant)
