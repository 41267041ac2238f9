"""phasekit: the phase space of an axisymmetric rigid body spinning on a table.

Exact contact dynamics (equations (2.7) of Shimomura, Branicki & Moffatt, and an
independent singularity-free Newton-Euler form), Coulomb stick-slip and viscous friction,
located lift-off events, free flight and impacts, and the analysis built on them. The
hybrid system (modes, events, resets) is data: see :mod:`phasekit.system`.

This module is the one place users import from; drawing is in :mod:`phasekit.viz`.
"""

from . import _startup  # noqa: F401  (first: Ctrl-C during the imports below ends phasekit's programs in one line)

from .body import Body, CustomBody, EccentricSphere, MassProperties, Spheroid, uniform_mass_properties
from .egg import Egg
from .units import Scale, as_quantity, egg_of_size, tippe_top_of_size
from . import tippetop
from .charts import EULER, FLIGHT, PAPER_NAMES, VECTOR, Chart, euler_to_vector, vector_to_euler
from .errors import ConvergenceError, ParameterError, PhasekitError, Status, WorkerError
from .friction import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous, friction_law
from .hybrid import Event, Mode
from .model import OBSERVABLES, Model
from .options import BACKENDS, SolverOptions
from .settle import Settle
from .simulate import simulate, taylor_integrator
from .trajectory import SAMPLE_COLUMNS, EventRecord, Flight, Segment, Trajectory
from .pose import POSE_COLUMNS, Pose, rotation_matrix
from .tables import read_table, write_table
from .sections import poincare
from .ensemble import ensemble, rerun
from .starts import gyroscopic_start, raw_start, to_chart, vertical_spin_start
from .fixedpoints import (
    Branch,
    FixedPoint,
    continue_family,
    find_fixed_point,
    fixed_points,
    horizontal_like_angle,
    horizontal_state,
    intermediate_omega,
    intermediate_state,
    inverted_state,
    linearise,
    precession_angles,
    precession_residual,
    precession_state,
    side_equilibrium,
    vertical_state,
)
from .criteria import (
    PoleCriterion,
    equator_stability_threshold,
    horizontal_is_unstable,
    pole_stability_threshold,
    horizontal_stability_threshold,
    vertical_is_stable,
    vertical_stability_threshold,
)
from .manifolds import unstable_manifold_start, unstable_seeds
from .threshold import (
    DEFAULT_DEFINITIONS,
    Definition,
    Outcome,
    Sensitivity,
    Threshold,
    ThresholdSearch,
    continue_threshold,
    evaluate_outcomes,
    find_stick_boundary,
    find_threshold,
    run_searches,
)
from .batch import LANES, BatchStats, compile_batch, simulate_batch
from .gyroscopic import gyroscopic_closed, gyroscopic_numeric, gyroscopic_solution, jellett_constant, mean_slip, rise_time
from .multiscale import (
    Gamma,
    Gamma_closed,
    I1_closed,
    I2_dominant,
    I3_closed,
    I_quadrature,
    Sigma,
    c_xi,
    mean_over_periods,
    omega2,
    omega_gyro,
    perturbation_from_c_xi,
    slow_rates,
    zeta,
    zeta_gyro,
)
from .flight import (
    FlightConstants,
    cos_theta_exact,
    flight_constants,
    flight_invariants,
    fly,
    gap_exact,
    gap_max_series,
    gap_series,
)
from .structure import RollingMotion, SteadyBranch, SteadyStructure, bifurcation_between, rolling_motion, steady_structure
from .impact import impact
from .surface import Scene, compute_scene, exact_boundary, surface_n
from .paper import PAPER_CASES, paper_start
from .api import choose_formulation
from .baseline import numpy_normal_reaction, numpy_rhs, solve_ivp_to_jump
from .sweep import (
    ModelPack,
    OutcomeRow,
    ResultStore,
    SearchRow,
    TaskSpec,
    ThresholdRow,
    client_evaluator,
    critical_path,
    make_client,
    outcome_key,
    outcome_task,
    provenance,
    run_tasks,
    run_pending,
    PendingRun,
    group_search_tasks,
    job_key,
    search_group_task,
    store_groups,
    search_job,
    search_key,
    search_task,
    threshold_key,
    threshold_task,
)

__version__ = "0.2.0"


def __getattr__(name):
    """``pk.viz`` on first use (drawing stays out of ``import phasekit``; VTK loads only when a
    3-D view is drawn)."""
    if name == "viz":
        import importlib

        return importlib.import_module(".viz", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = [
    "Body",
    "Spheroid",
    "EccentricSphere",
    "CustomBody",
    "Egg",
    "MassProperties",
    "uniform_mass_properties",
    "Scale",
    "as_quantity",
    "egg_of_size",
    "tippe_top_of_size",
    "tippetop",
    "inverted_state",
    "precession_angles",
    "precession_residual",
    "precession_state",
    "side_equilibrium",
    "horizontal_like_angle",
    "PoleCriterion",
    "pole_stability_threshold",
    "equator_stability_threshold",
    "FrictionLaw",
    "Coulomb",
    "RegularisedCoulomb",
    "Viscous",
    "friction_law",
    "Model",
    "OBSERVABLES",
    "Chart",
    "EULER",
    "VECTOR",
    "FLIGHT",
    "PAPER_NAMES",
    "Mode",
    "Event",
    "SolverOptions",
    "Settle",
    "BACKENDS",
    "simulate",
    "Trajectory",
    "Segment",
    "EventRecord",
    "Flight",
    "SAMPLE_COLUMNS",
    "POSE_COLUMNS",
    "Pose",
    "rotation_matrix",
    "read_table",
    "write_table",
    "poincare",
    "ensemble",
    "rerun",
    "Status",
    "PhasekitError",
    "ConvergenceError",
    "WorkerError",
    "ParameterError",
    "gyroscopic_start",
    "vertical_spin_start",
    "raw_start",
    "to_chart",
    "euler_to_vector",
    "vector_to_euler",
    "FixedPoint",
    "Branch",
    "find_fixed_point",
    "fixed_points",
    "linearise",
    "continue_family",
    "steady_structure",
    "SteadyStructure",
    "SteadyBranch",
    "bifurcation_between",
    "rolling_motion",
    "RollingMotion",
    "horizontal_state",
    "vertical_state",
    "unstable_seeds",
    "unstable_manifold_start",
    "horizontal_stability_threshold",
    "vertical_stability_threshold",
    "Definition",
    "Outcome",
    "Threshold",
    "find_threshold",
    "continue_threshold",
    "gyroscopic_solution",
    "gyroscopic_closed",
    "gyroscopic_numeric",
    "jellett_constant",
    "fly",
    "impact",
    "Scene",
    "compute_scene",
    "surface_n",
    "exact_boundary",
    "taylor_integrator",
    "DEFAULT_DEFINITIONS",
    "mean_slip",
    "rise_time",
    "Gamma",
    "Gamma_closed",
    "I1_closed",
    "I2_dominant",
    "I3_closed",
    "I_quadrature",
    "Sigma",
    "c_xi",
    "mean_over_periods",
    "omega2",
    "omega_gyro",
    "perturbation_from_c_xi",
    "slow_rates",
    "zeta",
    "zeta_gyro",
    "FlightConstants",
    "cos_theta_exact",
    "flight_constants",
    "flight_invariants",
    "gap_exact",
    "gap_max_series",
    "gap_series",
    "PAPER_CASES",
    "paper_start",
    "choose_formulation",
    "numpy_normal_reaction",
    "numpy_rhs",
    "solve_ivp_to_jump",
    "ModelPack",
    "ResultStore",
    "TaskSpec",
    "ThresholdRow",
    "make_client",
    "provenance",
    "run_tasks",
    "run_pending",
    "PendingRun",
    "threshold_key",
    "threshold_task",
    "Sensitivity",
    "ThresholdSearch",
    "evaluate_outcomes",
    "find_stick_boundary",
    "run_searches",
    "LANES",
    "BatchStats",
    "compile_batch",
    "simulate_batch",
    "OutcomeRow",
    "SearchRow",
    "critical_path",
    "client_evaluator",
    "outcome_key",
    "outcome_task",
    "search_key",
    "search_task",
    "search_job",
    "search_group_task",
    "group_search_tasks",
    "store_groups",
    "job_key",
    "horizontal_is_unstable",
    "vertical_is_stable",
    "intermediate_omega",
    "intermediate_state",
    "__version__",
]
