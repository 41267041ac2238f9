"""The benchmarks time the studies' own work: a study module loaded from its file."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def load(name: str):
    """``studies/<name>.py`` as a module, pickled by value so that Dask workers, which cannot
    import a study by name, receive the functions it hands them."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "studies" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    import cloudpickle

    cloudpickle.register_pickle_by_value(mod)
    return mod
