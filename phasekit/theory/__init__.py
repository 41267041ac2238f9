"""The paper's closed forms, criteria and printed cases (``phasekit.theory``).

What the analysis of Shimomura, Branicki & Moffatt (and parts I, III, IV of the series) gives in
closed form, needing no simulator (this layer sits below :mod:`phasekit.core`, which uses the
gyroscopic balance and the printed cases for its starts); the simulations are checked against it: the stability criteria of the steady
states, the gyroscopic (mean) solution of the rise (3.18), the
multiscale envelope Sigma (3.64) of the minima of R, the free flight and its gap (section 4),
the jump surface (6.3), the paper's printed starts, and the tippe top's
theory (:mod:`phasekit.theory.tippetop`).

Examples
--------
>>> import phasekit as pk
>>> round(pk.theory.horizontal_stability_threshold(pk.Spheroid(1.5).A, pk.Spheroid(1.5).C, 1.5), 6)
2.236068
"""

from . import tippetop  # noqa: F401  (the tippe top's theory, pk.theory.tippetop)
from .criteria import (
    PoleCriterion,
    horizontal_stability_threshold,
    pole_stability_threshold,
    vertical_stability_threshold,
)
from .flight import flight_constants, gap_exact, gap_max_series, gap_series
from .gyroscopic import gyroscopic_closed, gyroscopic_solution, jellett_constant
from .jump_surface import surface_n
from .multiscale import (
    amplitude_growth_closed,
    gyroscopic_nutation_frequency,
    reaction_envelope,
    slow_rates,
)
from .nutation import mean_over_periods, nutation_perturbation
from .paper import PAPER_CASES

__all__ = [
    "vertical_stability_threshold", "horizontal_stability_threshold",
    "pole_stability_threshold", "PoleCriterion",
    "jellett_constant", "gyroscopic_solution", "gyroscopic_closed",
    "gyroscopic_nutation_frequency", "slow_rates", "amplitude_growth_closed", "reaction_envelope",
    "nutation_perturbation", "mean_over_periods", "flight_constants", "gap_exact", "gap_series", "gap_max_series",
    "surface_n", "PAPER_CASES",
]
