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

from .continuation import continue_threshold
from .definition import DEFAULT_DEFINITIONS, Definition, evaluate_outcomes
from .outcome import Outcome
from .result import Threshold
from .search import ThresholdSearch, find_threshold, run_searches
from .stick import find_stick_boundary
from .verify import Verification

__all__ = [
    "Definition", "Threshold", "DEFAULT_DEFINITIONS", "find_threshold", "continue_threshold", "find_stick_boundary",
    "ThresholdSearch", "run_searches", "evaluate_outcomes", "Outcome", "Verification",
]
