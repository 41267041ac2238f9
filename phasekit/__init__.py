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
    "__version__",
]
