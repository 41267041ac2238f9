"""A threshold that checks itself: the outcomes at its bracket's ends, run again at a ten times
tighter tolerance (:func:`verify_thresholds`), and the :class:`Verification` a :class:`Threshold`
carries.

The bracket (lo, hi) of a search says "lo does not jump, hi does" at the definition's tolerance.
If both ends keep their outcomes at rtol / 10 the threshold is set by the body, not by the
integration error: verdict "verified", with the largest relative change of the two runs' end
times as a measure of how far from converged they are. Where an end changes its outcome, the
same end is also run in the other chart at rtol / 10 (a second formulation, to tell an
ill-conditioned outcome from an integration defect), and the whole search is repeated at rtol /
10, seeded by the first result, and its bracket checked the same way at rtol / 100: if that
holds, the re-search is the answer (verdict "verified", ``first_value`` the search that failed),
otherwise the verdict is "not verified" and says why. Measured on the main study (docs/results/
maps.md): near a = 1 the paper's recipe at eps = 1e-4 gave thresholds up to 8% low before the
Taylor integrators scaled their states (:mod:`phasekit.core.engines.scaling`); this check is what
would have caught it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

from ..errors import SearchStatus
from .definition import Definition, evaluate_outcomes
from .outcome import Outcome
from .result import Threshold

#: the check runs at the search's tolerance divided by this
TIGHTER = 10
#: statuses with a bracket whose ends can be checked
CHECKED = (SearchStatus.CONVERGED, SearchStatus.NON_MONOTONE)


@dataclass(frozen=True)
class CheckRun:
    """One run of a check: the family parameter ``value`` at a bracket end (``side`` "lo", which did
    not jump in the search, or "hi", which did), at tolerance ``rtol`` in ``chart`` (None: the start's
    choice), whether it ``jumped`` (None: failed) and its end time ``t``; ``t_search`` is the search's
    own run's end time there."""

    value: float
    side: str
    rtol: float
    chart: str | None
    jumped: bool | None
    t: float
    t_search: float

    @property
    def agrees(self) -> bool:
        """Did it keep the outcome the search saw (lo: no jump; hi: jump)?"""
        return self.jumped is (self.side == "hi")

    @property
    def change(self) -> float:
        """Relative change of the end time against the search's run at the same value."""
        return abs(self.t - self.t_search) / max(abs(self.t_search), 1e-300)


@dataclass(frozen=True)
class Verification:
    """What a threshold's check found.

    Attributes
    ----------
    verdict : {"verified", "not verified"}
        "verified": the bracket ends keep their outcomes at a ten times tighter tolerance (after a
        re-search, if ``first_value`` is set).
    checks : tuple of CheckRun
        Every run of the check, in the order made.
    worst : float or None
        The largest relative change of an end time between a bracket end's run and its check (the
        runs that kept their outcome): how far from converged those runs are.
    first_value : float or None
        The first search's threshold, when its check failed and a re-search at rtol / 10 replaced it.
    detail : str
        The verdict in words: what was checked and what disagreed.

    Examples
    --------
    >>> import phasekit as pk
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    >>> th.verification.verdict, len(th.verification.checks), th.verification.worst < 1e-6
    ('verified', 2, True)
    """

    verdict: str
    checks: tuple[CheckRun, ...]
    worst: float | None
    first_value: float | None = None
    detail: str = ""

    @property
    def verified(self) -> bool:
        return self.verdict == "verified"

    def to_dict(self) -> dict:
        out = asdict(self)
        out["checks"] = [asdict(c) for c in self.checks]
        return out


def _ends(th: Threshold) -> tuple[Outcome, Outcome] | None:
    """The search's own outcomes at the ends of the reported bracket."""
    lo, hi = th.bracket
    at = {o.value: o for o in th.outcomes}
    if lo is None or hi is None or lo not in at or hi not in at:
        return None
    return at[lo], at[hi]


def _other_chart(defn: Definition, body, value: float) -> str:
    model, _ = defn.start(body, value)
    return "vector" if model.chart.name == "euler" else "euler"


def _runs(jobs, engine, evaluate) -> list[Outcome]:
    return evaluate(jobs) if evaluate is not None else evaluate_outcomes(jobs, engine=engine)


def _check_jobs(defn: Definition, body, th: Threshold, factor: float):
    ends = _ends(th)
    tight = defn.tighter(factor)
    return ends, [(tight, body, ends[0].value), (tight, body, ends[1].value)] if ends else []


def _verdict(th: Threshold, defn: Definition, checks: list[CheckRun], extra: list[CheckRun], first=None) -> Threshold:
    ok = all(c.agrees for c in checks)
    kept = [c.change for c in checks if c.agrees and c.jumped is not None]
    worst = max(kept) if kept else None
    words = ", ".join(f"{c.side} = {c.value:.6g} {'jumps' if c.jumped else 'does not jump' if c.jumped is False else 'failed'}"
                      f" at rtol {c.rtol:g}{'' if c.chart is None else f' ({c.chart} chart)'}" for c in (*checks, *extra))
    if ok:
        detail = (f"re-searched at rtol {checks[0].rtol * TIGHTER:g} (the search at rtol {defn.rtol:g} gave {first:.6g} and "
                  f"failed its check); " if first is not None else "") + f"bracket ends kept their outcomes: {words}"
    else:
        detail = f"a bracket end changed its outcome: {words}"
    v = Verification("verified" if ok else "not verified", tuple((*checks, *extra)), worst, first, detail)
    return replace(th, verification=v)


def verify_thresholds(items, *, engine: str = "scalar", evaluate=None, research=None) -> list[Threshold]:
    """Check each threshold search's answer (module notes) and return the Thresholds with their
    :class:`Verification` (re-searched where the check failed).

    Parameters
    ----------
    items : sequence of (Definition, Body, Threshold)
        What was searched and what the search gave; a Threshold without a bracket to check (status
        other than converged or non_monotone) is returned as it is.
    engine : {"scalar", "batch"}, optional
        How the check's runs are made (all checks of one stage in one call).
    evaluate : callable, optional
        ``evaluate(jobs) -> outcomes``, replacing ``engine`` (a cluster's map).
    research : callable, optional
        ``research(defn, body, guess) -> Threshold``: the search repeated for a failed check (with the
        caller's range and tolerance); None: no re-search, the verdict is "not verified".

    Returns
    -------
    list of Threshold
        One per item, in order.
    """
    items = list(items)
    out = [th for _, _, th in items]
    todo = [(i, d, b, th) for i, (d, b, th) in enumerate(items) if th.status in CHECKED and _ends(th) is not None]
    plan = [(i, d, b, th, *_check_jobs(d, b, th, TIGHTER)) for i, d, b, th in todo]
    outs = _runs([j for *_, jobs in plan for j in jobs], engine, evaluate)
    failed = []
    for k, (i, d, b, th, ends, jobs) in enumerate(plan):
        checks = [CheckRun(e.value, side, jobs[0][0].rtol, d.chart, o.jumped, o.t, e.t)
                  for e, side, o in zip(ends, ("lo", "hi"), outs[2 * k:2 * k + 2])]
        if all(c.agrees for c in checks):
            out[i] = _verdict(th, d, checks, [])
        else:
            failed.append((i, d, b, th, checks))
    if not failed:
        return out
    # a second formulation at the disagreeing ends, then the search again at rtol / 10
    arbiters = [(k, c, replace(d.tighter(TIGHTER), chart=_other_chart(d, b, c.value)), b) for k, (_, d, b, _, cs) in enumerate(failed)
                for c in cs if not c.agrees]
    other = _runs([(dd, b, c.value) for _, c, dd, b in arbiters], engine, evaluate)
    extra = {k: [] for k in range(len(failed))}
    for (k, c, dd, _), o in zip(arbiters, other):
        extra[k].append(CheckRun(c.value, c.side, dd.rtol, dd.chart, o.jumped, o.t, c.t_search))
    for k, (i, d, b, th, checks) in enumerate(failed):
        out[i] = _verdict(th, d, checks, extra[k])
        if research is None:
            continue
        again = research(d.tighter(TIGHTER), b, th.value)
        if again.status not in CHECKED or _ends(again) is None:
            continue
        ends, jobs = _check_jobs(d.tighter(TIGHTER), b, again, TIGHTER)
        o2 = _runs(jobs, engine, evaluate)
        checks2 = [CheckRun(e.value, side, jobs[0][0].rtol, d.chart, o.jumped, o.t, e.t)
                   for e, side, o in zip(ends, ("lo", "hi"), o2)]
        if all(c.agrees for c in checks2):
            out[i] = _verdict(replace(again, n_sims=again.n_sims + th.n_sims), d, checks2, [*checks, *extra[k]],
                              first=th.value)
    return out
