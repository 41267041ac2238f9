"""What the scripts in studies/ share: their row types, reports and single-study figures.

Not API: nothing here is documented in the API reference or counted as public; it changes with
the studies. A study imports it as ``import phasekit.studies as ps`` (Dask workers import it by
name like any module).
"""

from .atlas import (
    AtlasPanel,
    AtlasRow,
    BoundaryRow,
    atlas_edge_key,
    atlas_edges,
    atlas_grid,
    atlas_point_key,
    atlas_representatives,
    axis_values,
    bifurcation_pairs,
    is_class,
    trace_boundary,
)
from .eggs import EggDefinition, EndRow, egg_separatrix, which_end, which_end_key, which_end_starts, which_end_summary
from .figures_atlas import plot_atlas, plot_classes, signature_colours
from .figures_eggs import plot_flights, plot_threshold_against, plot_which_end
from .figures_outcome_map import OUTCOME_COLOURS, plot_outcome_map, render_jump_region
from .figures_paper import (
    plot_effective_friction,
    plot_envelope,
    plot_gap_flight,
    plot_gap_maxima,
    plot_mean_state,
    plot_minima_envelope,
    plot_reaction_to_jump,
    render_jump_surface,
)
from .figures_structure import plot_branch_planes, render_structure
from .figures_thresholds import (
    DEFINITION_STYLES,
    plot_pair_scan,
    plot_stability_map,
    plot_threshold_curves,
    plot_threshold_map,
)
from .figures_tippe import OUTCOME_STYLE, plot_hopping, plot_inversion_map, render_inversion
from .figures_work_precision import plot_cost_growth, plot_regularisation, plot_work_precision
from .linear_stability import horizontal_is_unstable, stability_grid, vertical_is_stable
from .outcome_maps import (
    OUTCOME_KINDS,
    OutcomeMapPlan,
    OutcomeRow,
    outcome_class,
    outcome_key,
    outcome_map_report,
    outcome_map_summary,
    outcome_task,
)
from .paper_checks import (
    EnvelopeCheck,
    FlightCheck,
    NutationCase,
    add_nutation,
    crossing_trend,
    envelope_check,
    envelope_report,
    first_flight,
    fit_gyroscopic_mu,
    flight_check,
    gap_ensemble,
    gap_ensemble_report,
    loglog_fit,
    rise_complete,
    sigma_zero,
    surface_crossings,
)
from .paper_pairs import PairRow, as_printed, pair_key, pair_report, pair_run, pair_runs, pair_table
from .sensitivity import prepare_definitions, sensitivity_definitions, sensitivity_parent
from .spin_down import (
    LAW_NAMES,
    SpinCurvePoint,
    SpinDownRun,
    plot_rest_times,
    plot_spin_down,
    sphere_checks,
    spin_down_law,
    spin_down_run,
)
from .stress import STRESS_COLUMNS, StressCase, invariant_drift, stress_report, stress_run
from .structure_runs import manifold_runs, settled_motion
from .threshold_reports import (
    definition_sensitivity_table,
    seed_sensitivity_table,
    threshold_against_d,
    threshold_collapse,
    threshold_grid_table,
    threshold_map_report,
    threshold_table,
)
from .threshold_rows import (
    SearchRow,
    ThresholdRow,
    group_search_tasks,
    search_job,
    threshold_chain,
    threshold_key,
    threshold_task,
)
from .tippe_inversion import InversionRun, inversion_run, inversion_summary, simulate_inversion
from .work_precision import work_precision_summary

__all__ = ['work_precision_summary', 'manifold_runs', 'settled_motion', 'prepare_definitions', 'sensitivity_definitions', 'sensitivity_parent', 'AtlasPanel', 'AtlasRow', 'BoundaryRow', 'atlas_edge_key', 'atlas_edges', 'atlas_grid', 'atlas_point_key', 'atlas_representatives', 'axis_values', 'bifurcation_pairs', 'is_class', 'trace_boundary', 'EggDefinition', 'EndRow', 'egg_separatrix', 'which_end', 'which_end_key', 'which_end_starts', 'which_end_summary', 'plot_atlas', 'plot_classes', 'signature_colours', 'OUTCOME_COLOURS', 'plot_flights', 'plot_outcome_map', 'plot_pair_scan', 'plot_stability_map', 'plot_threshold_against', 'plot_threshold_curves', 'plot_threshold_map', 'plot_which_end', 'render_jump_region', 'plot_effective_friction', 'plot_envelope', 'plot_gap_flight', 'plot_gap_maxima', 'plot_mean_state', 'plot_minima_envelope', 'plot_reaction_to_jump', 'render_jump_surface', 'plot_branch_planes', 'render_structure', 'OUTCOME_STYLE', 'plot_hopping', 'plot_inversion_map', 'render_inversion', 'DEFINITION_STYLES', 'plot_cost_growth', 'plot_regularisation', 'plot_work_precision', 'threshold_map_report', 'OUTCOME_KINDS', 'OutcomeMapPlan', 'OutcomeRow', 'SearchRow', 'ThresholdRow', 'definition_sensitivity_table', 'group_search_tasks', 'outcome_class', 'outcome_key', 'outcome_map_report', 'outcome_map_summary', 'outcome_task', 'search_job', 'seed_sensitivity_table', 'stability_grid', 'vertical_is_stable', 'horizontal_is_unstable', 'threshold_against_d', 'threshold_chain', 'threshold_collapse', 'threshold_grid_table', 'threshold_key', 'threshold_table', 'threshold_task', 'EnvelopeCheck', 'FlightCheck', 'NutationCase', 'add_nutation', 'crossing_trend', 'envelope_check', 'envelope_report', 'first_flight', 'fit_gyroscopic_mu', 'flight_check', 'gap_ensemble', 'gap_ensemble_report', 'loglog_fit', 'rise_complete', 'sigma_zero', 'surface_crossings', 'PairRow', 'as_printed', 'pair_key', 'pair_report', 'pair_run', 'pair_runs', 'pair_table', 'STRESS_COLUMNS', 'StressCase', 'invariant_drift', 'stress_report', 'stress_run', 'InversionRun', 'inversion_run', 'inversion_summary', 'simulate_inversion', 'LAW_NAMES', 'SpinCurvePoint', 'SpinDownRun', 'plot_rest_times', 'plot_spin_down', 'sphere_checks', 'spin_down_law', 'spin_down_run']
