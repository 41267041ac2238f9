"""A study's files, each written whole at once (atomically, :func:`phasekit.io.atomic_path`):
its tables (:func:`write_csv`) and summaries (:func:`write_json`); figures go through
:func:`phasekit.viz.save_figure`."""

from __future__ import annotations

import csv
import json
import math
import os
from collections.abc import Mapping
from pathlib import Path

from ..io import atomic_path


def write_csv(path, header, rows) -> Path:
    """Write a whole table at once, atomically. A missing value (None or NaN) is an empty cell.

    Parameters
    ----------
    path : path-like
        The CSV file.
    header : sequence of str
        The column names.
    rows : iterable
        Sequences in the order of ``header``, or mappings (their keys outside ``header`` are left
        out, missing ones empty).

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from phasekit.scaffold.writers import write_csv
    >>> path = write_csv(pathlib.Path(tempfile.mkdtemp()) / 't.csv', ['a', 'b'], [[1, None], {'a': 2, 'b': 'x'}])
    >>> print(path.read_text(), end="")
    a,b
    1,
    2,x
    """

    def blank(v):  # one spelling of missing: an empty cell (None and NaN alike)
        return "" if v is None or (isinstance(v, float) and math.isnan(v)) else v

    def cells(row):
        if isinstance(row, Mapping):
            return [blank(row.get(k)) for k in header]
        return [blank(v) for v in row]

    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            w.writerows(cells(r) for r in rows)
            fh.flush()
            os.fsync(fh.fileno())
    return Path(path)


def write_json(path, obj, *, indent: int = 1, default=str) -> Path:
    """Write ``obj`` as JSON at once, atomically.

    Parameters
    ----------
    path : path-like
        The JSON file.
    obj : object
        What to write.
    indent : int, optional
        Indentation of ``json.dumps``.
    default : callable, optional
        Turns what JSON cannot hold into text.

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from phasekit.scaffold.writers import write_json
    >>> path = write_json(pathlib.Path(tempfile.mkdtemp()) / "s.json", {"a": 1.5})
    >>> print(path.read_text())
    {
     "a": 1.5
    }
    """
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(obj, indent=indent, default=default))
    return Path(path)
