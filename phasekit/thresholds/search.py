"""The search for a jump threshold: :class:`ThresholdSearch` (an ask/tell state machine: a coarse
scan, then bisection or k-section of each transition, brackets kept), :func:`run_searches` (many
searches in lock-step, one round of simulations at a time) and :func:`find_threshold`.

What counts as a jump is in :mod:`phasekit.thresholds.definition`, the result in
:mod:`phasekit.thresholds.result`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from .._runtime.validate import check_bool, check_choice, check_int, check_positive, check_range
from .._runtime.watch import WALL_REASON, check_max_wall, deadline, passed, progress_bar, wall_deadline
from ..bodies.spheroid import Spheroid
from ..errors import ConvergenceError, ParameterError, SearchStatus
from .definition import EVALUATION, Definition, as_body, evaluate_outcomes
from .outcome import Outcome
from .result import Sensitivity, Threshold
from .verify import verify_thresholds


def _tree(lo: float, hi: float, tol: float, depth: int) -> list[float]:
    """Every midpoint sequential bisection of [lo, hi] could visit in ``depth`` steps (the
    same floating-point operations, so the walk in :meth:`_Bracket.walk` reproduces it)."""
    if depth == 0 or not hi / lo - 1 > tol:
        return []
    mid = math.sqrt(lo * hi)
    return _tree(lo, mid, tol, depth - 1) + [mid] + _tree(mid, hi, tol, depth - 1)


@dataclass
class _Bracket:
    """One transition being narrowed: [lo, hi] with the outcome at lo."""

    lo: float
    hi: float
    o_lo: Outcome
    active: bool = True
    good: bool = True

    def walk(self, results: dict, tol: float) -> None:
        """Follow sequential bisection through the outcomes of this round."""
        while self.active:
            if not self.hi / self.lo - 1 > tol:
                self.active = False
                return
            mid = math.sqrt(self.lo * self.hi)
            if mid not in results:
                return  # beyond this round's tree
            o = results[mid]
            if o.jumped is None:
                self.active, self.good = False, False
            elif o.jumped == self.o_lo.jumped:
                self.lo, self.o_lo = mid, o
            else:
                self.hi = mid


class ThresholdSearch:
    """:func:`find_threshold` as a state machine, so that many searches (and several values
    of one search) can be simulated at once: :meth:`ask` gives the values of the next round
    (mutually independent), :meth:`tell` takes their outcomes, :meth:`result` gives the
    Threshold once :attr:`done`.

    With ``levels = m`` a refinement round simulates every midpoint that sequential bisection
    could visit in its next m steps (a dyadic tree: k = 2^m - 1 values, k-section) and then
    walks the tree as bisection would: the bracket is the one sequential bisection gives, in
    ceil(steps / m) rounds instead of steps. The coarse scan is one round of ``n_coarse``
    values (more if it has to widen).

    The arguments are taken as given (:func:`find_threshold` validates them).

    Parameters
    ----------
    defn : Definition
        What counts as a jump.
    body : Body
        The body.
    lo, hi : float
        The range of the family parameter searched, 0 < lo < hi.
    guess : float or None
        A guess: the scan starts over [guess/window, guess*window] within [lo, hi].
    n_coarse : int
        Values of the coarse geometric scan.
    window : float
        Factor of the scan window around ``guess``, > 1; the window widens by ``window**2``.
    tol : float
        Relative width each bracket is narrowed to.
    levels : int, optional
        m: bisection steps per refinement round.
    job : callable, optional
        ``job(p) -> (definition, body, value)`` for a search over another parameter p of the same simulations.
    flag : callable, optional
        ``flag(outcome) -> bool or None``: what counts as "jumped" in such a search; its outcomes then carry
        p as ``value`` and the flag as ``jumped``.

    Examples
    --------
    >>> import phasekit as pk
    >>> s = pk.thresholds.ThresholdSearch(pk.Definition('sliding', 'sliding'), pk.Spheroid(1.5), lo=5.0, hi=20.0, guess=None, n_coarse=4, window=1.5, tol=1e-2)
    >>> [round(v, 4) for v in s.ask()]
    [5.0, 7.937, 12.5992, 20.0]
    """

    def __init__(self, defn, body, *, lo, hi, guess, n_coarse, window, tol, levels=1, job=None, flag=None):
        self.defn, self.body = defn, body
        # a search over another parameter p of the same simulations: job(p) -> (definition,
        # body, value) and flag(outcome) -> bool or None; its outcomes then carry p as
        # ``value`` and the flag as ``jumped``
        self.job = job or (lambda p: (defn, body, p))
        self.flag = flag
        self.lo, self.hi, self.tol, self.n_coarse, self.window = lo, hi, tol, n_coarse, window
        self.levels = levels
        self.w_lo, self.w_hi = (max(lo, guess / window), min(hi, guess * window)) if guess is not None else (lo, hi)
        self.outcomes: list[Outcome] = []
        self.phase, self.widenings, self.n_rounds = "scan", 0, 0
        self.trans: list[tuple[float, float]] = []
        self.brackets: list[_Bracket] = []
        self._asked: list[float] = []
        self.stopped: str | None = None  # why the search was ended before it finished

    @property
    def done(self) -> bool:
        return self.phase == "done"

    def ask(self) -> list[float]:
        """The values to simulate next (empty once done)."""
        while not self.done:
            if self.phase == "scan":
                known = {o.value for o in self.outcomes}
                vals = [float(v) for v in np.geomspace(self.w_lo, self.w_hi, self.n_coarse) if float(v) not in known]
                if vals:
                    self._asked = vals
                    return vals
                self._after_scan()
            else:
                vals = [v for b in self.brackets if b.active for v in _tree(b.lo, b.hi, self.tol, self.levels)]
                if vals:
                    self._asked = vals
                    return vals
                self.phase = "done"
        return []

    def stop(self, reason: str) -> None:
        """End the search where it is (a wall budget ran out): its result keeps the bracket it
        has, with status BRACKET_ONLY (FAILED before any transition was found) and ``reason``.

        Parameters
        ----------
        reason : str
            Why the search was stopped.
        """
        if self.phase == "scan":
            self._after_scan()
        if not self.done:
            self.phase, self.stopped = "done", reason

    def describe(self) -> str:
        """Where the search stands, in a few words (a progress bar's postfix)."""
        live = [b for b in self.brackets if b.active]
        if live:
            return f"bracket [{live[0].lo:.6g}, {live[0].hi:.6g}]"
        return f"scan [{self.w_lo:.4g}, {self.w_hi:.4g}]" if self.phase == "scan" else self.phase

    def tell(self, outcomes) -> None:
        """Take the outcomes of the values :meth:`ask` gave last.

        Parameters
        ----------
        outcomes : sequence of Outcome
            One per value, in the order asked.

        Raises
        ------
        ValueError
            If the number of outcomes differs from the number of values asked.
        """
        outcomes = list(outcomes)
        if len(outcomes) != len(self._asked):
            raise ValueError("tell() needs the outcomes of the values ask() gave, in order")
        outcomes = [replace(o, value=v) if o.value != v else o for o, v in zip(outcomes, self._asked)]
        self.n_rounds += 1
        self._asked = []
        # a run cut by the caller's wall budget decides nothing: the search ends where it is, saying so
        # (read as "no outcome", the cut runs below a threshold made the scan see jumps everywhere)
        cut = next((o.reason for o in outcomes if (o.reason or "").startswith(WALL_REASON)), None)
        if self.flag is not None:
            outcomes = [replace(o, jumped=self.flag(o)) for o in outcomes]
        self.outcomes.extend(outcomes)
        if cut is not None:
            if self.phase == "scan":
                self._after_scan()  # the transitions among the runs that ended
            self.phase, self.stopped = "done", cut.split(" at t = ")[0]
            return
        if self.phase == "scan":
            self._after_scan()
        else:
            results = {o.value: o for o in outcomes}
            for b in self.brackets:
                b.walk(results, self.tol)
            if not any(b.active for b in self.brackets):
                self.phase = "done"

    def _after_scan(self) -> None:
        """Transitions on the scan so far; widen the window or go on to refine them."""
        self.widenings += 1
        scan = sorted((o for o in self.outcomes if o.jumped is not None), key=lambda o: o.value)
        self.trans = [(scan[k].value, scan[k + 1].value) for k in range(len(scan) - 1) if scan[k].jumped != scan[k + 1].jumped]
        stop = bool(self.trans) or not scan or self.widenings >= 30
        if not stop and not scan[0].jumped:  # no jump anywhere yet: look higher, up to hi
            stop = self.w_hi >= self.hi
            self.w_lo, self.w_hi = self.w_hi, min(self.hi, self.w_hi * self.window**2)
        elif not stop:  # jumps everywhere yet: look lower, down to lo
            stop = self.w_lo <= self.lo
            self.w_lo, self.w_hi = max(self.lo, self.w_lo / self.window**2), self.w_lo
        if stop:
            first = {}
            for o in self.outcomes:
                first.setdefault(o.value, o)
            self.brackets = [_Bracket(lo, hi, first[lo]) for lo, hi in self.trans]
            self.phase = "refine" if self.brackets else "done"

    def result(self, wall_s: float = 0.0) -> Threshold:
        """The Threshold of the search so far (call it once :attr:`done`).

        Parameters
        ----------
        wall_s : float, optional
            Wall time to record, seconds.

        Returns
        -------
        Threshold
            The value, bracket, status and outcomes.
        """
        a = self.body.a
        outs, n = tuple(self.outcomes), len(self.outcomes)
        if self.stopped is not None and not self.trans:
            return Threshold(a, None, (None, None), SearchStatus.FAILED, n, (), outs, wall_s,
                             f"{self.stopped} before a transition was found", n_rounds=self.n_rounds)
        if self.stopped is not None and any(b.active for b in self.brackets):
            first = next(b for b in self.brackets if b.active)
            return Threshold(a, math.sqrt(first.lo * first.hi) if not first.o_lo.jumped else None, (first.lo, first.hi),
                             SearchStatus.BRACKET_ONLY, n, tuple((b.lo, b.hi) for b in self.brackets), outs, wall_s,
                             f"{self.stopped}: the bracket is as far as it was narrowed", n_rounds=self.n_rounds)
        if not self.trans:
            valid = [o for o in self.outcomes if o.jumped is not None]
            if not valid:
                reason = next((o.reason for o in self.outcomes if o.reason), "no run succeeded")
                return Threshold(a, None, (None, None), SearchStatus.FAILED, n, (), outs, wall_s, reason, n_rounds=self.n_rounds)
            if all(o.jumped for o in valid):
                return Threshold(a, None, (None, self.lo), SearchStatus.JUMPS_AT_LOWER_BOUND, n, (), outs, wall_s, n_rounds=self.n_rounds)
            return Threshold(a, None, (self.hi, None), SearchStatus.NO_JUMP_IN_RANGE, n, (), outs, wall_s, n_rounds=self.n_rounds)
        brackets = [(b.lo, b.hi) for b in self.brackets]
        ok = all(b.good for b in self.brackets)
        # the threshold: the lowest transition from no jump (below) to jump (above)
        ups = [(b.lo, b.hi) for b in self.brackets if not b.o_lo.jumped]
        first = ups[0] if ups else brackets[0]
        status = SearchStatus.BRACKET_ONLY if not ok else (SearchStatus.NON_MONOTONE if len(brackets) > 1 else SearchStatus.CONVERGED)
        value = math.sqrt(first[0] * first[1]) if ups else None
        reason = None if ok else next((o.reason for o in self.outcomes if o.jumped is None), None)
        return Threshold(a, value, first, status, n, tuple(brackets), outs, wall_s, reason, n_rounds=self.n_rounds)


def run_searches(searches, *, engine: str = "scalar", evaluate=None, stats=None, bar=None) -> int:
    """Drive searches in lock-step: each round simulates the values every unfinished search
    asks for, all at once (on the batch integrator with ``engine="batch"``, or through
    ``evaluate(jobs) -> outcomes`` with jobs (definition, body, value), e.g. on a cluster).
    A wall budget in force (:func:`phasekit._runtime.watch.wall_deadline`) that has run out ends every
    search between rounds (:meth:`ThresholdSearch.stop`).

    Parameters
    ----------
    searches : sequence of ThresholdSearch
        The searches; they are advanced in place.
    engine : {"scalar", "batch"}, optional
        How the runs are made when ``evaluate`` is not given.
    evaluate : callable, optional
        ``evaluate(jobs) -> outcomes``, replacing ``engine``.
    stats : BatchStats, optional
        Filled with what the batch integrator did.
    bar : tqdm, optional
        Counts the runs.

    Returns
    -------
    int
        The number of rounds.

    Examples
    --------
    >>> import phasekit as pk
    >>> searches = [pk.thresholds.ThresholdSearch(pk.Definition('sliding', 'sliding'), pk.Spheroid(a), lo=5.0, hi=20.0, guess=g, n_coarse=4, window=1.5, tol=1e-2) for a, g in ((1.5, 9.74), (1.75, 8.16))]
    >>> rounds = pk.thresholds.run_searches(searches, engine='batch')
    >>> [round(s.result().value, 2) for s in searches]
    [9.78, 8.13]
    """
    rounds = 0
    while True:
        asks = [(s, s.ask()) for s in searches if not s.done]
        asks = [(s, v) for s, v in asks if v]
        if not asks:
            return rounds
        if passed():
            budget = deadline()[1]
            for s, _ in asks:
                s.stop(f"{WALL_REASON} (max_wall = {budget:g} s) ran out")
            return rounds
        jobs = [s.job(x) for s, vals in asks for x in vals]
        outs = evaluate(jobs) if evaluate is not None else evaluate_outcomes(jobs, engine=engine, stats=stats)
        k = 0
        for s, vals in asks:
            s.tell(outs[k:k + len(vals)])
            k += len(vals)
        rounds += 1
        if bar is not None:
            bar.update(len(jobs))
            bar.set_postfix_str(searches[len(searches) // 2].describe(), refresh=False)


def threshold_searches(defn: Definition, body, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
                       n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3, levels: int = 1,
                       sensitivity: bool = False) -> list[ThresholdSearch]:
    """The searches :func:`find_threshold` runs (validated): the threshold search, and with
    ``sensitivity`` the same search at the seed distance halved and doubled (list order
    d/2, d, 2d). Run them, alone or with other searches, by :func:`run_searches`."""
    if not isinstance(defn, Definition):
        raise ParameterError("defn", "must be a phasekit threshold Definition", defn)
    body = as_body(body)
    if isinstance(body, Spheroid) and body.a == 1.0 and body.flip_symmetric:
        raise ParameterError("a", "must differ from 1 (a sphere has no jump threshold: h_theta = 0)", body.a)
    tol = check_range("tol", tol, 1e-12, 0.5, closed="lr")
    n_coarse = check_int("n_coarse", n_coarse, minimum=2, maximum=1000)
    levels = check_int("levels", levels, minimum=1, maximum=8)
    window = check_range("window", window, 1.0, 1e3, closed="r")
    hi = check_positive("hi", hi)
    lo = defn.lower_bound(body) if lo is None else check_positive("lo", lo)
    if not lo < hi:
        raise ParameterError("lo", f"must be < hi = {hi:g}", lo)
    if guess is not None:
        guess = check_positive("guess", guess)
    kw = dict(lo=lo, hi=hi, guess=guess, n_coarse=n_coarse, window=window, tol=tol, levels=levels)
    main = ThresholdSearch(defn, body, **kw)
    if not sensitivity:
        return [main]
    d = defn.amplitude
    return [ThresholdSearch(replace(defn, amplitude=d / 2), body, **kw), main,
            ThresholdSearch(replace(defn, amplitude=min(2 * d, 0.5)), body, **kw)]


def threshold_result(searches: list[ThresholdSearch], wall_s: float = 0.0, *, run: bool = False, **run_kw) -> Threshold:
    """The Threshold of finished :func:`threshold_searches` (with the sensitivity if asked); ``run``
    runs them first (:func:`run_searches` with ``run_kw``)."""
    if run:
        run_searches(searches, **run_kw)
    if len(searches) == 1:
        return searches[0].result(wall_s)
    main = searches[1]
    th = main.result(wall_s)
    amps = tuple(s.defn.amplitude for s in searches)
    sens = Sensitivity.from_thresholds(amps, [s.result() for s in searches])
    return replace(th, sensitivity=sens, n_rounds=max(s.n_rounds for s in searches))


def find_threshold(defn: Definition, body, *, lo: float | None = None, hi: float = 60.0, guess: float | None = None,
                   n_coarse: int = 8, window: float = 1.5, tol: float = 1e-3, levels: int = 1, engine: str = "scalar",
                   sensitivity: bool = False, evaluate=None, throw: bool = False, max_wall: float | None = None,
                   progress: bool | None = None, verify: bool = True) -> Threshold:
    """Bracket and bisect the jump/no-jump transition in Omega0 (prolate) or n0 (oblate), and
    check the answer.

    A coarse geometric scan (over [lo, hi], or over [guess/window, guess*window], widened until
    a transition shows) finds every transition on the grid; each is then bisected to relative
    width ``tol``. Then (``verify``) the bracket's ends are run again at a ten times tighter
    tolerance: the result carries the verdict (:class:`phasekit.thresholds.Verification`), and a
    search whose check fails is repeated at that tolerance (:func:`phasekit.thresholds.verify.verify_thresholds`).

    Parameters
    ----------
    defn : Definition
        What counts as a jump.
    body : Body or float
        A Body or an aspect ratio a (uniform spheroid); not a sphere.
    lo, hi : float, optional
        The range searched, 0 < lo < hi; ``lo`` is by default ``defn.lower_bound(body)``.
    guess : float, optional
        A guess from a neighbouring body, > 0.
    n_coarse : int, optional
        Points of the coarse scan, in [2, 1000].
    window : float, optional
        Factor of the scan window around ``guess``, in (1, 1000].
    tol : float, optional
        Relative width of the final bracket, in [1e-12, 0.5].
    levels : int, optional
        m in [1, 8]: bisect m steps per round by simulating the 2^m - 1 midpoints those
        steps could need at once (k-section; the same bracket as bisection in fewer rounds, at
        more simulations).
    engine : {"scalar", "batch"}, optional
        "scalar" (one :func:`simulate` per value) or "batch" (heyoka's SIMD batch integrator,
        :mod:`phasekit.core.batch`).
    sensitivity : bool, optional
        True also searches at the seed distance (``defn.amplitude``) halved and doubled, in the same
        rounds, and fills :attr:`Threshold.sensitivity`.
    evaluate : callable, optional
        ``evaluate(jobs)`` replaces both engines (jobs: (definition, body, value); e.g. a cluster's map).
    throw : bool, optional
        Raise ConvergenceError instead of returning status FAILED.
    max_wall : float, optional
        Seconds; bounds the whole search: a run under way when it runs out ends
        "failed", and the search returns the bracket it has (status BRACKET_ONLY, or FAILED
        before a transition was found) with a reason naming the budget.
    progress : bool, optional
        A bar of the runs with the current bracket (None: on a terminal or in a notebook only).
    verify : bool, optional
        Check the answer (default); False returns the raw search (``verification`` None).

    Returns
    -------
    Threshold
        The value, bracket, status, the outcomes simulated and the verification.

    Raises
    ------
    ParameterError
        For an invalid argument.
    ConvergenceError
        With ``throw=True``, if the search fails (status FAILED).

    Examples
    --------
    >>> import phasekit as pk
    >>> th = pk.find_threshold(pk.Definition('sliding', 'sliding'), 1.5, hi=120.0, guess=9.74, tol=1e-2)
    >>> th.status.value, round(th.value, 2), th.bracket[0] < th.value < th.bracket[1], th.verified
    ('converged', 9.78, True, True)
    """
    t0 = time.perf_counter()
    check_choice("engine", engine, EVALUATION)
    check_bool("verify", verify)
    max_wall = check_max_wall(max_wall)
    searches = threshold_searches(defn, body, lo=lo, hi=hi, guess=guess, n_coarse=n_coarse, window=window, tol=tol,
                                  levels=levels, sensitivity=sensitivity)
    main = searches[1] if sensitivity else searches[0]
    with progress_bar(desc=_bar_label(searches[0]), progress=progress) as bar, wall_deadline(max_wall):
        run_searches(searches, engine=engine, evaluate=evaluate, bar=bar)
        th = threshold_result(searches)
        if verify and not passed():
            def research(d, b, g):
                return threshold_result([ThresholdSearch(d, b, lo=main.lo, hi=main.hi, guess=g, n_coarse=main.n_coarse,
                                                         window=main.window, tol=main.tol, levels=main.levels)], run=True,
                                        engine=engine, evaluate=evaluate)

            [th] = verify_thresholds([(defn, main.body, th)], engine=engine, evaluate=evaluate, research=research)
    th = replace(th, wall_s=time.perf_counter() - t0)
    if throw and th.status is SearchStatus.FAILED:
        raise ConvergenceError(f"threshold search failed: {th.reason}", th)
    return th


def _bar_label(search: ThresholdSearch) -> str:
    a = search.body.a
    return "threshold" + (f" a={a:g}" if not math.isnan(a) else "")
