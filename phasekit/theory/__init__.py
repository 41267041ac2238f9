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

from . import tippetop
from .criteria import (
    PoleCriterion,
    equator_stability_threshold,
    horizontal_is_unstable,
    horizontal_stability_threshold,
    pole_stability_threshold,
    vertical_is_stable,
    vertical_stability_threshold,
)
from .flight import FlightConstants, flight_constants, fly, gap_exact, gap_max_series, gap_series
from .gyroscopic import gyroscopic_closed, gyroscopic_numeric, gyroscopic_solution, jellett_constant, rise_time
from .multiscale import (
    Gamma_closed,
    I_quadrature,
    Sigma,
    c_xi,
    mean_over_periods,
    omega2,
    omega_gyro,
    perturbation_from_c_xi,
    slow_rates,
)
from .paper import PAPER_CASES, PaperCase
from .surface import exact_boundary, surface_n

__all__ = [
    "vertical_stability_threshold", "vertical_is_stable", "horizontal_stability_threshold", "horizontal_is_unstable",
    "pole_stability_threshold", "PoleCriterion", "equator_stability_threshold",
    "jellett_constant", "gyroscopic_solution", "gyroscopic_closed", "gyroscopic_numeric", "rise_time",
    "omega2", "omega_gyro", "slow_rates", "I_quadrature", "Gamma_closed", "Sigma", "c_xi", "perturbation_from_c_xi",
    "mean_over_periods",
    "flight_constants", "FlightConstants", "gap_exact", "gap_series", "gap_max_series", "fly",
    "surface_n", "exact_boundary", "PAPER_CASES", "PaperCase", "tippetop",
]
