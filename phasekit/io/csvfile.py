"""CSV tables and their sidecar ``x.csv.json``.

The CSV itself stays plain (one header line, a missing cell empty, numbers as Python prints them,
True/False), so that any program reads it; what CSV cannot say goes in a JSON file beside it, named
after it with ``.json`` appended::

    {"phasekit_table": 1, "csv": "x.csv", "sha256": "<hash of x.csv>",
     "columns": [{"name": "t", "dtype": "float64", "units": "ms", "long_name": "time"}, ...],
     "attrs": {"status": "jumped", "run": {...}}}

Both are written atomically, the sidecar first; it names the hash of its CSV, so that a sidecar
left beside another version of the CSV (a kill between the two renames, a CSV edited by hand) is
noticed and ignored with a warning rather than applied. A CSV without a (matching) sidecar, as the
study tables in figures/ are, is read by inference: True/False as booleans, numbers as numbers.
"""

from __future__ import annotations

import hashlib
import json
import warnings
from pathlib import Path

from ..errors import PhasekitError
from .atomic import atomic_path
from .schema import MARK, Schema, check_text, dumps, infer_dtypes, restore, schema_from_json


def sidecar(path) -> Path:
    """The sidecar of the CSV file ``path``: ``x.csv`` -> ``x.csv.json``."""
    path = Path(path)
    return path.with_name(path.name + ".json")


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def write_csv(df, schema: Schema, path: Path) -> None:
    """Write ``df`` (checked as ``schema``) and its sidecar, each atomically."""
    check_text(df, schema, "CSV", forbidden="\r")  # a carriage return ends a row for CSV readers
    plain = df.copy(deep=False)
    plain.attrs = {}
    with atomic_path(path) as tmp:
        plain.to_csv(tmp, index=False, na_rep="")
        meta = {MARK: 1, "csv": path.name, "sha256": _sha256(tmp),
                "columns": [schema.column(c) for c in schema.columns], "attrs": schema.attrs}
        with atomic_path(sidecar(path)) as side:
            side.write_text(dumps(meta, indent=1) + "\n", encoding="utf-8")


def _schema(path: Path) -> Schema | None:
    """The sidecar's schema, if there is one and it describes this very file."""
    side = sidecar(path)
    if not side.exists():
        return None
    try:
        meta = json.loads(side.read_text(encoding="utf-8"))
        ok = isinstance(meta, dict) and meta.get(MARK) == 1 and meta.get("sha256") == _sha256(path)
    except (OSError, ValueError):
        ok = False
    if not ok:
        warnings.warn(f"{side.name} does not describe {path.name} (it was written for another version of it): "
                      "read without it (dtypes inferred, no units or attributes)", stacklevel=4)
        return None
    return schema_from_json(meta)


def read_csv(path: Path):
    """The table of the CSV file ``path``: as its sidecar describes it, or by inference."""
    import pandas as pd

    schema = _schema(path)
    if schema is None:
        return infer_dtypes(pd.read_csv(path, keep_default_na=False, na_values=[""]))
    # floats and booleans as text, converted by restore: Python's float() rounds every decimal
    # correctly (pandas' own parser did not before pandas 3)
    dtype = {name: "object" if d in ("float32", "float64", "bool") else d for name, d in schema.dtypes.items()}
    df = pd.read_csv(path, dtype=dtype, keep_default_na=False, na_values=[""])
    if list(df.columns) != schema.columns:
        raise PhasekitError(f"{path.name}: its header {list(df.columns)} is not that of its sidecar")
    return restore(df, schema)
