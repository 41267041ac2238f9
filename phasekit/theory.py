"""The paper's closed forms, criteria and printed cases (``phasekit.theory``).

What the analysis of Shimomura, Branicki & Moffatt (and parts I, III, IV of the series) gives in
closed form, against which the simulations are checked: the stability criteria of the steady
states, the steady states themselves, the gyroscopic (mean) solution of the rise (3.18), the
multiscale envelope Sigma (3.64) of the minima of R, the free flight and its gap (section 4),
the impact law, the jump surface (6.3), the paper's printed starts, and the tippe top's
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
from .fixedpoints import (
    horizontal_like_angle,
    horizontal_state,
    intermediate_omega,
    intermediate_state,
    inverted_state,
    precession_angles,
    side_equilibrium,
    vertical_state,
)
from .flight import FlightConstants, flight_constants, fly, gap_exact, gap_max_series, gap_series
from .gyroscopic import gyroscopic_closed, gyroscopic_numeric, gyroscopic_solution, jellett_constant, rise_time
from .impact import ImpactResult, impact
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
from .paper_checks import (
    EnvelopeCheck,
    FlightCheck,
    NutationCase,
    add_nutation,
    crossing_trend,
    envelope_check,
    envelope_report,
    first_flight,
    fit_gyroscopic_mu,
    flight_check,
    gap_ensemble,
    gap_ensemble_report,
    loglog_fit,
    rise_complete,
    sigma_zero,
    surface_crossings,
)
from .structure import RollingMotion, manifold_runs, rolling_motion, settled_motion
from .surface import exact_boundary, surface_n
from .tippe_inversion import InversionRun, inversion_run, inversion_summary, simulate_inversion

__all__ = [
    # stability criteria of the steady states
    "vertical_stability_threshold", "vertical_is_stable", "horizontal_stability_threshold", "horizontal_is_unstable",
    "pole_stability_threshold", "PoleCriterion", "equator_stability_threshold",
    # the steady states
    "horizontal_state", "vertical_state", "inverted_state", "intermediate_state", "intermediate_omega",
    "precession_angles", "side_equilibrium", "horizontal_like_angle", "rolling_motion", "RollingMotion",
    # the gyroscopic (mean) solution of the rise
    "jellett_constant", "gyroscopic_solution", "gyroscopic_closed", "gyroscopic_numeric", "rise_time",
    # the multiscale analysis: fast frequency, slow rates, the envelope Sigma
    "omega2", "omega_gyro", "slow_rates", "I_quadrature", "Gamma_closed", "Sigma", "c_xi", "perturbation_from_c_xi",
    "mean_over_periods",
    # a simulated rise against the mean-state theory: the start with a nutation, Sigma's zero, the effective friction
    "rise_complete", "add_nutation", "sigma_zero", "envelope_check", "EnvelopeCheck", "fit_gyroscopic_mu",
    # free flight and impact; a simulated flight against them
    "flight_constants", "FlightConstants", "gap_exact", "gap_series", "gap_max_series", "fly", "impact", "ImpactResult",
    "flight_check", "FlightCheck",
    # the jump surface
    "surface_n", "exact_boundary",
    # the paper's printed cases, and the tippe top
    "PAPER_CASES", "PaperCase", "tippetop",
    # the tippe top's inversion simulated and classified beside the predictions of tippetop
    "simulate_inversion", "inversion_run", "InversionRun", "inversion_summary",
    # runs against the steady-state structure: from a branch state's unstable manifold, and what a run settles into
    "manifold_runs", "settled_motion",
    # the jump surface (6.3) against simulated crossings, and the trend of its error
    "surface_crossings", "crossing_trend", "loglog_fit",
    # a rise from the sliding branch with a nutation, beside the gyroscopic solution and Sigma
    "NutationCase", "envelope_report",
    # first flights, and the largest gaps of an ensemble of them against (4.23) and the paper's bound
    "first_flight", "gap_ensemble", "gap_ensemble_report",
]
