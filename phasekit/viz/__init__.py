"""Drawing and study output. Nothing here imports a plotting library at import time:
matplotlib is imported by the functions that draw, pyvista only when a 3-D scene is drawn."""

from .mpl import LABELS, label, plain_log_ticks, plot_events, plot_minima, plot_phase, plot_section, plot_timeseries
from .output import atomic_path, output_dir, progress, pyplot, run_study, save_figure, study_parser, write_csv
from .pv import RenderInfo, render_scene
from .branches import render_structure
from .animate import AnimationInfo, animate, body_mesh, film_strip, render_body

__all__ = [
    "animate",
    "film_strip",
    "render_body",
    "body_mesh",
    "AnimationInfo",
    "render_scene",
    "render_structure",
    "RenderInfo",
    "plot_timeseries",
    "plot_events",
    "plot_section",
    "plot_phase",
    "plot_minima",
    "plain_log_ticks",
    "label",
    "LABELS",
    "study_parser",
    "output_dir",
    "pyplot",
    "save_figure",
    "write_csv",
    "atomic_path",
    "progress",
    "run_study",
]
