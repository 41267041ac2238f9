"""Sweeps (``phasekit.sweep``): many independent runs, resumable and on many cores. Tasks and
their dependencies (:class:`TaskSpec`, :func:`run_tasks`), kill-safe result stores
(:class:`ResultStore`: typed rows appended and fsynced, a torn row dropped on resume), Dask
clients and the model shipped once per worker (:func:`make_client`, :class:`ModelPack`),
ensembles of starts (:func:`ensemble`, :func:`rerun`). The scaffold of a study script
that runs them is :mod:`phasekit.scaffold`.

Examples
--------
>>> import phasekit as pk
>>> pk.sweep.TaskSpec("k", lambda prev: 1).key
'k'
"""

from .cluster import ModelPack, make_client
from .ensemble import ensemble, rerun
from .stores import ResultStore, provenance
from .tasks import TaskSpec, chunked, each, run_pending, run_tasks

__all__ = [
    "TaskSpec", "run_tasks", "run_pending", "ResultStore", "each", "chunked", "ModelPack",
    "make_client", "provenance", "ensemble", "rerun",
]
