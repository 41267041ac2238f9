"""phasekit: the phase space of any convex body of revolution spinning on a table.

Exact contact dynamics (equations (2.7) of Shimomura, Branicki & Moffatt, and an
independent singularity-free Newton-Euler form), Coulomb stick-slip and viscous friction,
located lift-off events, free flight and impacts, and the analysis built on them.

This module re-exports the names a user starts from. Everything has its home in a subpackage,
lowest layer first (the order is checked by import-linter, see docs/architecture.md):
:mod:`phasekit.errors` (the errors and statuses, a public module), :mod:`phasekit.io` (tables on
disk), :mod:`phasekit.bodies` and :mod:`phasekit.friction`, :mod:`phasekit.theory` (the papers'
closed forms), :mod:`phasekit.core` (model, hybrid system, engines, simulate, trajectory, starts,
pose, units), :mod:`phasekit.scenes` (jump-surface scenes) and :mod:`phasekit.baseline` (scipy and
bare heyoka, for comparison), :mod:`phasekit.steady` (fixed points, manifolds, steady-state
structure), :mod:`phasekit.thresholds`, :mod:`phasekit.sweep` (tasks, stores, Dask, ensembles) and
:mod:`phasekit.viz` (drawing; loads matplotlib or VTK only when something is drawn), side by side,
:mod:`phasekit.scaffold` (the study scaffold, above both) and :mod:`phasekit.cli`.
"""

from ._runtime import startup as _startup  # noqa: F401  (first: Ctrl-C during the imports below ends phasekit's programs in one line)

# isort: split
from . import baseline, bodies, core, friction, io, scenes, steady, sweep, theory, thresholds  # noqa: F401  (the public namespaces)
from .bodies import Cone, CustomBody, Disk, EccentricSphere, Egg, Spheroid, TippeTop
from .core import Event, Model, Scale, SolverOptions, gyroscopic_start, paper_start, simulate
from .errors import ConvergenceError, ParameterError, PhasekitError, SearchStatus, Status, WorkerError
from .friction import (
    AirDrag,
    AirLayer,
    Contensou,
    Coulomb,
    RegularisedCoulomb,
    RollingResistance,
    SpinFriction,
    Viscous,
)
from .io import read_table, write_table
from .scenes import Scene, compute_scene
from .steady import fixed_points, steady_structure
from .sweep import ensemble, rerun
from .thresholds import Definition, find_threshold

#: the one place the version is written (pyproject.toml reads it from here)
__version__ = "0.2.0"


def __getattr__(name):
    """``pk.viz`` and ``pk.scaffold`` (which draws) on first use: drawing stays out of
    ``import phasekit`` (VTK loads only when a 3-D view is drawn)."""
    if name in ("viz", "scaffold"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    # bodies and friction laws
    "Spheroid", "EccentricSphere", "Egg", "Disk", "Cone", "TippeTop", "CustomBody", "Coulomb", "RegularisedCoulomb", "Viscous", "Contensou",
    "RollingResistance", "SpinFriction", "AirDrag", "AirLayer",
    # the model, simulations and their starts
    "Model", "Event", "SolverOptions", "simulate", "ensemble", "rerun",
    "gyroscopic_start", "paper_start",
    # steady states, thresholds, scenes, real units, tables
    "fixed_points", "steady_structure", "Definition", "find_threshold",
    "Scene", "compute_scene", "Scale", "read_table", "write_table",
    # errors and statuses
    "PhasekitError", "ConvergenceError", "ParameterError", "WorkerError", "Status", "SearchStatus",
]
