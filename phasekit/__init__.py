"""phasekit: the phase space of any convex body of revolution spinning on a table.

Exact contact dynamics (equations (2.7) of Shimomura, Branicki & Moffatt, and an
independent singularity-free Newton-Euler form), Coulomb stick-slip and viscous friction,
located lift-off events, free flight and impacts, and the analysis built on them. The
hybrid system (modes, events, resets) is data: see :mod:`phasekit.system`.

This module holds what a user needs; the rest is in named sub-namespaces, imported on first
use: :mod:`phasekit.theory` (the paper's closed forms and criteria), :mod:`phasekit.sweep`
(tasks, stores, searches and the scaffold of a study), :mod:`phasekit.engines` (the integrators
and how to add one), :mod:`phasekit.baseline` (scipy and bare heyoka, for comparison) and
:mod:`phasekit.viz` (drawing; loads matplotlib or VTK only when something is drawn).
"""

from . import _startup  # noqa: F401  (first: Ctrl-C during the imports below ends phasekit's programs in one line)
from .batch import simulate_batch
from .body import Body, CustomBody, EccentricSphere, Spheroid
from .charts import PAPER_NAMES, choose_chart
from .egg import Egg
from .ensemble import ensemble, rerun
from .errors import ConvergenceError, ParameterError, PhasekitError, SearchStatus, Status, WorkerError
from .fixedpoints import FixedPoint, find_fixed_point, fixed_points, linearise
from .friction import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous
from .hybrid import Event, Mode
from .manifolds import unstable_manifold_start, unstable_seeds
from .model import OBSERVABLES, Model
from .options import SolverOptions
from .paper import paper_start
from .pose import Pose
from .sections import poincare
from .settle import Settle
from .simulate import simulate
from .starts import gyroscopic_start, to_chart, to_paper, vertical_spin_start
from .structure import SteadyStructure, bifurcation_between, steady_structure
from .surface import Scene, compute_scene
from .tables import read_table, write_table
from .threshold import (
    DEFAULT_DEFINITIONS,
    Definition,
    Threshold,
    continue_threshold,
    find_stick_boundary,
    find_threshold,
)
from .trajectory import EventRecord, Flight, Segment, Trajectory
from .units import Scale, egg_of_size, tippe_top_of_size

#: the one place the version is written (pyproject.toml reads it from here)
__version__ = "0.2.0"

#: the public sub-namespaces, imported on first use (``pk.theory.Sigma``, ``pk.viz.animate``)
SUBMODULES = ("theory", "sweep", "engines", "baseline", "viz")


def __getattr__(name):
    """``pk.theory``, ``pk.sweep``, ``pk.engines``, ``pk.baseline`` and ``pk.viz`` on first use
    (drawing stays out of ``import phasekit``; VTK loads only when a 3-D view is drawn)."""
    if name in SUBMODULES:
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    # bodies and friction laws
    "Body", "Spheroid", "EccentricSphere", "CustomBody", "Egg", "FrictionLaw", "Coulomb", "RegularisedCoulomb", "Viscous",
    # the model, its hybrid system and the solver options
    "Model", "OBSERVABLES", "Mode", "Event", "SolverOptions", "Settle",
    # simulations and their results
    "simulate", "simulate_batch", "Trajectory", "Segment", "EventRecord", "Flight", "poincare", "ensemble", "rerun",
    # starts and the state's charts
    "gyroscopic_start", "vertical_spin_start", "paper_start", "PAPER_NAMES", "to_chart", "to_paper", "choose_chart",
    # fixed points, manifolds and the steady-state structure
    "fixed_points", "find_fixed_point", "FixedPoint", "linearise", "unstable_manifold_start", "unstable_seeds",
    "steady_structure", "SteadyStructure", "bifurcation_between",
    # thresholds and maps
    "Definition", "Threshold", "find_threshold", "continue_threshold", "find_stick_boundary", "DEFAULT_DEFINITIONS",
    # scenes, real units, where the body is, tables
    "Scene", "compute_scene", "Scale", "egg_of_size", "tippe_top_of_size", "Pose", "read_table", "write_table",
    # errors and statuses
    "PhasekitError", "ConvergenceError", "ParameterError", "WorkerError", "Status", "SearchStatus",
]
