"""Steady states (``phasekit.steady``): fixed points with exact linearisations and eigenvalue error
bounds, the steady precessions at the poles, the equator and in between, unstable manifolds,
steady rolling motions, and the whole steady-state structure of a body (parts III and IV).

Examples
--------
>>> import phasekit as pk
>>> [float(v) for v in pk.steady.horizontal_state(10.0)[:4]]
[0.0, 0.0, 10.0, 0.0]
"""

from .fixedpoints import find_fixed_point, fixed_points
from .linearisation import FixedPoint, linearise
from .manifolds import unstable_manifold_start
from .precessions import (
    horizontal_state,
    inverted_state,
    precession_angles,
    side_equilibrium,
    vertical_state,
)
from .rolling import rolling_motion
from .structure import SteadyStructure, steady_structure

__all__ = [
    "fixed_points", "find_fixed_point", "FixedPoint", "linearise",
    "horizontal_state", "vertical_state", "inverted_state", "precession_angles",
    "side_equilibrium", "unstable_manifold_start",
    "steady_structure", "SteadyStructure", "rolling_motion",
]
