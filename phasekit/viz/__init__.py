"""Drawing (``phasekit.viz``). Nothing here imports a plotting library at import time:
matplotlib is imported by the functions that draw, pyvista only when a 3-D scene is drawn.
A study's own output (flags, folders, tables, Ctrl-C) is :mod:`phasekit.sweep`'s."""

from .animate import AnimationInfo, animate, body_mesh, film_strip, render_body
from .atlas import plot_atlas, plot_classes, signature_colours
from .branches import plot_branch_planes, render_structure
from .figures import DEFINITION_STYLES, plot_cost_growth, plot_regularisation, plot_work_precision
from .maps import (
    OUTCOME_COLOURS,
    plot_flights,
    plot_outcome_map,
    plot_pair_scan,
    plot_stability_map,
    plot_threshold_against,
    plot_threshold_curves,
    plot_threshold_map,
    plot_which_end,
    render_jump_region,
)
from .mpl import LABELS, label, plain_log_ticks, plot_events, plot_minima, plot_phase, plot_section, plot_timeseries
from .output import pyplot, save_figure
from .paper import (
    plot_effective_friction,
    plot_envelope,
    plot_gap_flight,
    plot_gap_maxima,
    plot_mean_state,
    plot_minima_envelope,
    plot_reaction_to_jump,
    render_jump_surface,
)
from .pv import RenderInfo, render_scene
from .tippe import OUTCOME_STYLE, plot_hopping, plot_inversion_map, render_inversion

__all__ = [
    "animate",
    "film_strip",
    "render_body",
    "body_mesh",
    "AnimationInfo",
    "render_scene",
    "render_structure",
    "plot_branch_planes",
    "RenderInfo",
    "plot_outcome_map",
    "render_jump_region",
    "OUTCOME_COLOURS",
    "plot_threshold_curves",
    "plot_threshold_map",
    "plot_stability_map",
    "plot_pair_scan",
    "plot_which_end",
    "plot_threshold_against",
    "plot_flights",
    "plot_atlas",
    "plot_classes",
    "signature_colours",
    "plot_timeseries",
    "plot_events",
    "plot_section",
    "plot_phase",
    "plot_minima",
    "plain_log_ticks",
    "label",
    "LABELS",
    "pyplot",
    "save_figure",
    # the paper's figures of a rise
    "plot_reaction_to_jump",
    "plot_envelope",
    "plot_mean_state",
    "plot_minima_envelope",
    "plot_gap_flight",
    "plot_gap_maxima",
    "plot_effective_friction",
    "render_jump_surface",
    # accuracy and cost
    "plot_work_precision",
    "plot_regularisation",
    "plot_cost_growth",
    # the tippe top
    "plot_inversion_map",
    "plot_hopping",
    "render_inversion",
    "OUTCOME_STYLE",
    # the line styles of the threshold definitions
    "DEFINITION_STYLES",
]
