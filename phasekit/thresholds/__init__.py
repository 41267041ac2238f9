"""Jump thresholds (``phasekit.thresholds``): what counts as a jump (:class:`Definition`), the
search for the lowest spin that jumps as an ask/tell state machine (:class:`ThresholdSearch`),
bisection or k-section with brackets kept, continuation along a parameter, and the boundary
below which a start sticks.

Examples
--------
>>> import phasekit as pk
>>> pk.thresholds.Definition('sliding', 'sliding').name
'sliding'
"""

from .threshold import (
    DEFAULT_DEFINITIONS,
    Definition,
    Outcome,
    Threshold,
    ThresholdSearch,
    continue_threshold,
    evaluate_outcomes,
    find_stick_boundary,
    find_threshold,
    run_searches,
)

__all__ = [
    "Definition", "Threshold", "DEFAULT_DEFINITIONS", "find_threshold", "continue_threshold", "find_stick_boundary",
    "ThresholdSearch", "run_searches", "evaluate_outcomes", "Outcome",
]
