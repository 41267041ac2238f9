"""Thresholds along a family of bodies (:func:`continue_threshold`), each search seeded by the
previous result."""

from __future__ import annotations

from .._runtime.watch import WALL_REASON, check_max_wall, passed, progress_bar, wall_deadline
from ..errors import SearchStatus
from .definition import Definition, as_body
from .result import Threshold
from .search import find_threshold


def continue_threshold(defn: Definition, bodies, *, max_wall: float | None = None, progress: bool | None = None,
                       **kw) -> list[Threshold]:
    """Thresholds along a list of bodies (or aspect ratios), each search seeded by the previous
    result.

    Parameters
    ----------
    defn : Definition
        What counts as a jump.
    bodies : iterable of Body or float
        The bodies, or aspect ratios of uniform spheroids, in the order searched.
    max_wall : float, optional
        Seconds; bounds the whole continuation: a search under way when it runs out returns its
        bracket, and the bodies after it a FAILED Threshold saying so.
    progress : bool, optional
        A bar over the bodies.
    **kw
        Keywords of :func:`find_threshold` (not ``guess`` or ``progress``).

    Returns
    -------
    list of Threshold
        One per body, in order.

    Raises
    ------
    ParameterError
        For an invalid argument.
    ConvergenceError
        With ``throw=True`` in ``kw``, if a search fails.

    Examples
    --------
    >>> import phasekit as pk
    >>> ths = pk.thresholds.continue_threshold(pk.Definition('sliding', 'sliding'), [1.75, 1.5], hi=120.0, tol=1e-2)
    >>> [th.status.value for th in ths]
    ['converged', 'converged']
    """
    max_wall = check_max_wall(max_wall)
    bodies = list(bodies)
    out, guess = [], None
    with progress_bar(len(bodies), desc="thresholds", unit="body", progress=progress) as bar, \
            wall_deadline(max_wall):
        for b in bodies:
            if passed():
                why = f"not searched: {WALL_REASON} (max_wall = {max_wall:g} s) ran out"
                out.append(Threshold(as_body(b).a, None, (None, None), SearchStatus.FAILED, 0,
                                     reason=why))
                continue
            th = find_threshold(defn, b, guess=guess, progress=False, **kw)
            out.append(th)
            if th.value is not None:
                guess = th.value
            bar.update()
            bar.set_postfix_str(f"last {th.status.value} {th.value if th.value is None else format(th.value, '.6g')}",
                                refresh=False)
    return out
