"""The paper's closed forms, criteria and printed cases (``phasekit.theory``).

What the analysis of Shimomura, Branicki & Moffatt (and parts I, III, IV of the series) gives in
closed form, against which the simulations are checked: the stability criteria of the steady
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
from .flight import FlightConstants, flight_constants, fly, gap_exact, gap_max_series, gap_series
from .gyroscopic import gyroscopic_closed, gyroscopic_solution, jellett_constant
from .jump_surface import exact_boundary, surface_n
from .multiscale import (  # noqa: F401  (the paper's symbols, aliases of the descriptive names)
    Gamma_closed,
    I_quadrature,
    Sigma,
    amplitude_growth_closed,
    c_xi,
    growth_integral,
    gyroscopic_nutation_frequency,
    mean_over_periods,
    nutation_amplitude_phase,
    nutation_frequency_squared,
    nutation_perturbation,
    omega2,
    omega_gyro,
    perturbation_from_c_xi,
    reaction_envelope,
    slow_rates,
)
from .paper import PAPER_CASES, PaperCase

__all__ = [
    "vertical_stability_threshold", "horizontal_stability_threshold",
    "pole_stability_threshold", "PoleCriterion",
    "jellett_constant", "gyroscopic_solution", "gyroscopic_closed",
    "nutation_frequency_squared", "gyroscopic_nutation_frequency", "slow_rates", "growth_integral",
    "amplitude_growth_closed", "reaction_envelope", "nutation_amplitude_phase", "nutation_perturbation", "mean_over_periods",
    "flight_constants", "FlightConstants", "gap_exact", "gap_series", "gap_max_series", "fly",
    "surface_n", "exact_boundary", "PAPER_CASES", "PaperCase",
]
