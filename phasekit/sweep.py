"""Sweeps and studies (``phasekit.sweep``): the task machinery, the rows of the threshold and map
studies, the searches behind them, batch compilation, and the scaffold of a study script.

* Tasks (:mod:`phasekit.tasks`): :class:`TaskSpec`, :func:`run_tasks`, :func:`run_pending`,
  :class:`ResultStore`, :class:`ModelPack`, :func:`make_client`, :func:`provenance`, ...
* Rows and their tasks (:mod:`phasekit.maps`): :class:`ThresholdRow`, :class:`SearchRow`,
  :class:`OutcomeRow`, :func:`search_job`, :func:`group_search_tasks`, ..., and what the studies
  read off them: :func:`outcome_map_summary`, :func:`threshold_collapse`, ...
* The spinning egg (:mod:`phasekit.eggs`): :func:`which_end`, :class:`EndRow`, :class:`EggDefinition`, ...
* Atlases of steady-state structure (:mod:`phasekit.atlas`): :class:`AtlasRow`, :func:`trace_boundary`, ...
* Searches in lock-step (:mod:`phasekit.threshold`): :class:`ThresholdSearch`, :func:`run_searches`,
  :func:`evaluate_outcomes`, :class:`Outcome`, :class:`Sensitivity`.
* The scaffold (:mod:`phasekit.study`): :class:`Study`, :func:`run_study`, and the atomic
  writers :func:`save_figure`, :func:`write_csv`, :func:`write_json`, :func:`atomic_path`.

Examples
--------
>>> import phasekit as pk
>>> pk.sweep.TaskSpec("k", lambda prev: 1).key
'k'
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
from .batch import BatchStats, compile_batch
from .eggs import EggDefinition, EndRow, egg_separatrix, which_end, which_end_key, which_end_starts, which_end_summary
from .map_reports import threshold_map_report
from .maps import (
    OUTCOME_KINDS,
    OutcomeMapPlan,
    OutcomeRow,
    SearchRow,
    ThresholdRow,
    definition_sensitivity_table,
    group_search_tasks,
    outcome_class,
    outcome_key,
    outcome_map_report,
    outcome_map_summary,
    outcome_task,
    search_job,
    seed_sensitivity_table,
    stability_grid,
    threshold_against_d,
    threshold_chain,
    threshold_collapse,
    threshold_grid_table,
    threshold_key,
    threshold_table,
    threshold_task,
)
from .paper_pairs import PairRow, as_printed, pair_key, pair_report, pair_run, pair_runs, pair_table
from .stress import STRESS_COLUMNS, StressCase, invariant_drift, stress_report, stress_run
from .study import Study, atomic_path, run_study, save_figure, write_csv, write_json
from .tasks import (
    ModelPack,
    PendingRun,
    ResultStore,
    TaskSpec,
    chunked,
    client_evaluator,
    each,
    make_client,
    provenance,
    run_pending,
    run_tasks,
    stored_rows,
)
from .threshold import (
    Outcome,
    Sensitivity,
    ThresholdSearch,
    evaluate_outcomes,
    prepare_definitions,
    run_searches,
    sensitivity_definitions,
    sensitivity_parent,
)

__all__ = [
    # tasks on Dask or in this process, resumable from a store
    "TaskSpec", "run_tasks", "run_pending", "PendingRun", "ResultStore", "stored_rows", "each", "chunked", "ModelPack",
    "make_client", "client_evaluator", "provenance",
    # the rows of the threshold and map studies
    "ThresholdRow", "threshold_task", "threshold_key", "SearchRow", "search_job", "group_search_tasks", "OutcomeRow",
    "outcome_task", "outcome_key", "OUTCOME_KINDS", "outcome_class", "threshold_chain",
    # what the studies read off the stored rows
    "outcome_map_summary", "threshold_collapse", "threshold_against_d", "stability_grid", "threshold_table",
    "definition_sensitivity_table", "threshold_grid_table", "seed_sensitivity_table",
    # atlases of steady-state structure
    "AtlasPanel", "AtlasRow", "BoundaryRow", "axis_values", "atlas_edges", "trace_boundary", "is_class", "atlas_representatives",
    # searches in lock-step, and their simulations in batch
    "ThresholdSearch", "run_searches", "evaluate_outcomes", "Outcome", "Sensitivity", "BatchStats", "compile_batch",
    # the scaffold of a study script
    "Study", "run_study", "save_figure", "write_csv", "write_json", "atomic_path",
    # an outcome map's tasks and report
    "OutcomeMapPlan", "outcome_map_report",
    # the spinning egg: which end it rises onto, its threshold from the horizontal-like state
    "egg_separatrix", "which_end_starts", "EndRow", "which_end", "which_end_key", "which_end_summary", "EggDefinition",
    # atlases: their grid and keys, the bifurcations on their boundaries
    "atlas_grid", "atlas_point_key", "atlas_edge_key", "bifurcation_pairs",
    # the paper's printed pairs of single trajectories (studies/paper_pairs.py)
    "PairRow", "pair_key", "pair_run", "pair_runs", "as_printed", "pair_table", "pair_report",
    # stiff and extreme cases: a run checked for its status, invariants and cost (studies/stiff_extreme.py)
    "StressCase", "stress_run", "invariant_drift", "STRESS_COLUMNS", "stress_report",
    # the variants of the threshold definitions a sensitivity run compares, and their compilation
    "sensitivity_definitions", "sensitivity_parent", "prepare_definitions",
    # the report of an (a, mu) threshold map (studies/threshold_vs_mu.py)
    "threshold_map_report",
]
