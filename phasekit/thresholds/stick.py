"""The sticking boundary: the smallest seed distance d whose start does not stick and roll
(:func:`find_stick_boundary`), searched by a :class:`phasekit.thresholds.search.ThresholdSearch` over d."""

from __future__ import annotations

import time
from dataclasses import replace

from .._runtime.validate import check_choice, check_int, check_positive, check_range
from .._runtime.watch import check_max_wall, progress_bar, wall_deadline
from ..errors import ParameterError
from .definition import EVALUATION, Definition, as_body
from .result import Threshold
from .search import ThresholdSearch, run_searches


def stick_search(defn: Definition, body, value: float, *, lo: float = 1e-4, hi: float = 0.2, n_coarse: int = 8,
                 tol: float = 1e-2, levels: int = 1) -> ThresholdSearch:
    """The search :func:`find_stick_boundary` runs (validated)."""
    if not isinstance(defn, Definition):
        raise ParameterError("defn", "must be a phasekit threshold Definition", defn)
    body = as_body(body)
    value = check_positive("value", value)
    lo, hi = check_range("lo", lo, 0.0, 0.5, closed="r"), check_range("hi", hi, 0.0, 0.5, closed="r")
    if not lo < hi:
        raise ParameterError("lo", f"must be < hi = {hi:g}", lo)
    return ThresholdSearch(defn, body, lo=lo, hi=hi, guess=None, n_coarse=check_int("n_coarse", n_coarse, minimum=2),
                           window=1.5, tol=check_range("tol", tol, 1e-12, 0.5, closed="lr"),
                           levels=check_int("levels", levels, minimum=1, maximum=8),
                           job=lambda d: (replace(defn, amplitude=d), body, value),
                           flag=lambda o: None if o.jumped is None else o.kind != "stuck")


def find_stick_boundary(defn: Definition, body, value: float, *, lo: float = 1e-4, hi: float = 0.2, n_coarse: int = 8,
                        tol: float = 1e-2, levels: int = 1, engine: str = "scalar", evaluate=None,
                        max_wall: float | None = None, progress: bool | None = None) -> Threshold:
    """The sticking boundary d_min at one value of the family parameter: the smallest seed
    distance ``d`` (``defn.amplitude``) in [lo, hi] whose start does not stick and roll
    (outcome kind "stuck"), bracketed and bisected in d to relative width ``tol``.

    Parameters
    ----------
    defn : Definition
        What counts as a jump; its ``amplitude`` is replaced by each d.
    body : Body or float
        A Body or an aspect ratio a (uniform spheroid).
    value : float
        The family parameter (Omega0 or n0), > 0.
    lo, hi : float, optional
        The range of d searched, 0 < lo < hi <= 0.5.
    n_coarse : int, optional
        Points of the coarse scan, >= 2.
    tol : float, optional
        Relative width of the final bracket, in [1e-12, 0.5].
    levels : int, optional
        Bisection steps per round, in [1, 8] (as for :func:`find_threshold`).
    engine : {"scalar", "batch"}, optional
        How the runs are made.
    evaluate : callable, optional
        ``evaluate(jobs) -> outcomes``, replacing ``engine``.
    max_wall, progress
        As for :func:`find_threshold`.

    Returns
    -------
    Threshold
        A Threshold over d: ``value`` is d_min (the lowest transition from
        stuck below to not stuck above), its outcomes carry d as ``value`` and "not stuck" as
        ``jumped``.

    Raises
    ------
    ParameterError
        For an invalid argument.

    Examples
    --------
    >>> import phasekit as pk
    >>> th = pk.thresholds.find_stick_boundary(pk.Definition('sliding', 'sliding', t_max=300.0), 1.5, 17.7, tol=0.1)
    >>> th.status.value, 1e-4 < th.value < 0.2
    ('converged', True)
    """
    t0 = time.perf_counter()
    check_choice("engine", engine, EVALUATION)
    max_wall = check_max_wall(max_wall)
    search = stick_search(defn, body, value, lo=lo, hi=hi, n_coarse=n_coarse, tol=tol, levels=levels)
    with progress_bar(desc="stick boundary", progress=progress) as bar, wall_deadline(max_wall):
        run_searches([search], engine=engine, evaluate=evaluate, bar=bar)
    return search.result(time.perf_counter() - t0)
