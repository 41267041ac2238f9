"""The wall budget of the steady-state searches: :func:`phasekit.steady_structure` and the CLI's
reports take ``max_wall`` (phasekit._runtime.watch sets it as a deadline for everything computed
inside, a caller's earlier deadline kept), and the searches check it between their Newton solves
and linearisations (each a few milliseconds), so a budget holds to about that.
"""

from __future__ import annotations

import time

from .._runtime.watch import WALL_REASON, deadline

__all__ = ["spend_wall"]


def spend_wall() -> None:
    """Raise TimeoutError, its message naming the budget, once the deadline in force has passed;
    return at once when there is none."""
    d = deadline()
    if d is not None and time.perf_counter() > d[0]:
        raise TimeoutError(f"{WALL_REASON} (max_wall = {d[1]:g} s) ran out")
