"""phasekit: the phase space of a rigid spheroid spinning on a table.

Exact contact dynamics (equations (2.7) of Shimomura, Branicki & Moffatt, and an
independent singularity-free Newton-Euler form), Coulomb stick-slip and viscous
friction, located lift-off events, and the analysis built on them.

This module is the one place users import from.
"""

from .body import Body, Spheroid
from .charts import EULER_NAMES, euler_to_vector, vector_to_euler
from .errors import BracketError, ConvergenceError, PhasekitError, Status
from .friction import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous, friction_law
from .model import STICK_SLIP, Model
from .modes import Mode
from .result import EventRecord, SimulationResult
from .simulate import BACKEND_CHOICES, DEFAULT_RTOL, simulate
from .starts import balance_residual, gyroscopic_start, raw_start, to_chart
from .fixedpoints import Branch, FixedPoint, continue_family, find_fixed_point, fixed_points, linearise
from .manifolds import (
    horizontal_stability_threshold,
    unstable_manifold_start,
    unstable_seeds,
    vertical_stability_threshold,
)
from .threshold import Definition, Threshold, continue_threshold, find_threshold
from .gyroscopic import gyroscopic_closed, gyroscopic_numeric, gyroscopic_solution, jellett_constant
from .flight import Flight, FlightModel, fly
from .impact import impact
from .surface import Scene, compute_scene, exact_boundary, surface_n

__version__ = "0.1.0"

__all__ = [
    "Body",
    "Spheroid",
    "FrictionLaw",
    "Coulomb",
    "RegularisedCoulomb",
    "Viscous",
    "friction_law",
    "Model",
    "Mode",
    "STICK_SLIP",
    "simulate",
    "SimulationResult",
    "EventRecord",
    "Status",
    "PhasekitError",
    "ConvergenceError",
    "BracketError",
    "gyroscopic_start",
    "raw_start",
    "balance_residual",
    "to_chart",
    "euler_to_vector",
    "vector_to_euler",
    "EULER_NAMES",
    "DEFAULT_RTOL",
    "BACKEND_CHOICES",
    "FixedPoint",
    "Branch",
    "find_fixed_point",
    "fixed_points",
    "linearise",
    "continue_family",
    "unstable_seeds",
    "unstable_manifold_start",
    "horizontal_stability_threshold",
    "vertical_stability_threshold",
    "Definition",
    "Threshold",
    "find_threshold",
    "continue_threshold",
    "gyroscopic_solution",
    "gyroscopic_closed",
    "gyroscopic_numeric",
    "jellett_constant",
    "Flight",
    "FlightModel",
    "fly",
    "impact",
    "Scene",
    "compute_scene",
    "surface_n",
    "exact_boundary",
    "__version__",
]
