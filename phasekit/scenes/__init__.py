"""Scenes of the jump surface (``phasekit.scenes``): what the simulations and the model give, drawn
against the closed forms of :mod:`phasekit.theory`. A :class:`Scene` says which elements to draw
(the surface (6.3), the exact boundary R = 0, trajectories and their crossings of it, fixed
points); :func:`compute_scene` computes their data (simulating only when trajectories or crossings
are asked for) and :func:`phasekit.viz.render_scene` draws it; :func:`exact_boundary` is R = 0 by
root finding on the model's normal reaction.

Examples
--------
>>> import phasekit as pk
>>> pk.scenes.exact_boundary(pk.Spheroid(1.5), 0.1, 12.0, 1.0).round(6)
array([10.20507])
"""

from .boundary import exact_boundary
from .scene import Scene, compute_scene

__all__ = ["Scene", "compute_scene", "exact_boundary"]
