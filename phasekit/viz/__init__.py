"""Drawing (``phasekit.viz``). Nothing here imports a plotting library at import time:
matplotlib is imported by the functions that draw, pyvista only when a 3-D scene is drawn.
A study's own output (flags, folders, tables, Ctrl-C) is :mod:`phasekit.scaffold`'s.

Examples
--------
>>> import phasekit as pk
>>> pk.viz.label("theta")
'theta [rad]'
"""

from .animate import animate, film_strip, render_body
from .energy import plot_energy
from .mesh import body_mesh
from .mpl import label, plain_log_ticks, plot_events, plot_minima, plot_phase, plot_section, plot_timeseries
from .output import pyplot, save_figure
from .pv import render_scene
from .structure import plot_steady_structure

__all__ = [
    "animate", "film_strip", "render_body", "body_mesh", "render_scene",
    "plot_timeseries", "plot_events", "plot_section", "plot_phase", "plot_minima", "plot_energy", "plain_log_ticks",
    "label", "plot_steady_structure",
    "pyplot", "save_figure",
]
