"""Kill-safe result stores of sweeps: every finished result is written to disk at once, so that a
killed sweep resumes where it stopped.

* :class:`ResultStore` is a CSV file of typed rows (a dataclass per table) plus a JSON
  manifest (versions, git commit, all parameters). A row is appended, flushed and synced as
  soon as its task finishes; on a rerun every stored row is checked (field count, types) and
  a broken one (a kill in mid-write) is dropped and recomputed.
* :func:`stored_rows` gives the ``store_get`` and ``on_result`` of :func:`phasekit.sweep.run_tasks`
  over one or more stores; :func:`provenance` what a result was obtained with.
"""

from __future__ import annotations

import csv
import dataclasses
import datetime as _dt
import io
import json
import math
import os
import platform
import subprocess
import sys
import typing
from pathlib import Path

CODE_PATHS = ("phasekit", "studies", "benchmarks", "pyproject.toml")


def provenance(extra: dict | None = None) -> dict:
    """Versions, git commit and command line: what a result was obtained with. ``git_dirty``
    says whether the code (CODE_PATHS) differs from that commit.

    Parameters
    ----------
    extra : dict, optional
        Further entries, added last (they override the ones above).

    Returns
    -------
    dict
        The versions of phasekit, casadi, heyoka, numpy, scipy and Python, ``git_commit`` and
        ``git_dirty`` (None where git cannot tell) and ``command``.

    Examples
    --------
    >>> import phasekit as pk
    >>> d = pk.sweep.provenance({'study': 'demo'})
    >>> d['study'], d['phasekit'] == pk.__version__
    ('demo', True)
    """
    import casadi
    import numpy
    import scipy

    from .. import __version__

    try:
        import heyoka

        hy = heyoka.__version__
    except Exception:  # pragma: no cover
        hy = None
    root = Path(__file__).resolve().parents[2]  # the repository
    try:
        commit = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10).stdout.strip()
        # the code differs from the commit (a study's own result files, rewritten as it runs, do not count)
        dirty = bool(subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no", "--",
                                     *CODE_PATHS], capture_output=True, text=True, timeout=10).stdout.strip())
    except Exception:
        commit, dirty = None, None
    d = {"phasekit": __version__, "casadi": casadi.__version__, "heyoka": hy, "numpy": numpy.__version__,
         "scipy": scipy.__version__, "python": platform.python_version(), "git_commit": commit or None,
         "git_dirty": dirty, "command": " ".join(sys.argv)}
    if extra:
        d.update(extra)
    return d


# -- typed rows ------------------------------------------------------------------------------


def _parse(text: str, typ):
    """A CSV cell back to its field type; ValueError if it does not parse."""
    args = typing.get_args(typ)
    if type(None) in args:
        if text == "":
            return None
        typ = next(a for a in args if a is not type(None))
    if typ is bool:
        if text not in ("True", "False"):
            raise ValueError(f"not a bool: {text!r}")
        return text == "True"
    if typ is int:
        return int(text)
    if typ is float:
        v = float(text)
        if math.isnan(v):
            raise ValueError("NaN")
        return v
    if typ is str:
        return text
    raise TypeError(f"unsupported field type {typ!r}")


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    return str(value)


def row_from_cells(row_type, cells: list[str]):
    """Build a typed row from CSV cells; ValueError when the count or a type is off."""
    flds = dataclasses.fields(row_type)
    if len(cells) != len(flds):
        raise ValueError(f"{len(cells)} fields, expected {len(flds)}")
    hints = typing.get_type_hints(row_type)
    return row_type(**{f.name: _parse(c, hints[f.name]) for f, c in zip(flds, cells)})


RUN_FIELDS = ("started", "git_commit", "git_dirty", "command", "phasekit", "heyoka", "casadi")
MAX_RUNS = 50  # the manifest keeps the last runs of a study


class ResultStore:
    """Append-only CSV of finished typed rows (keyed by their ``key`` field) with a JSON
    manifest beside it. Safe against a kill at any moment: rows are appended whole (one
    write, flushed and fsynced) and every row is checked when the file is read back. The
    manifest's ``runs`` lists every run that computed rows (commit, command, rows added), so
    resumed results still say what computed them; a run that only reads stored rows (a redraw)
    leaves the manifest untouched unless it annotates it with something new.

    Parameters
    ----------
    csv_path : path-like
        The CSV file of rows; its directory is created if needed.
    manifest_path : path-like
        The JSON manifest.
    row_type : type
        The dataclass of a row: fields of type bool, int, float or str (optionally None), one named ``key``.
    meta : dict
        The manifest's entries (e.g. :func:`provenance` and the study's parameters).
    fresh : bool, optional
        True: delete both files first and start empty.

    Attributes
    ----------
    dropped : int
        Rows dropped on reading the file back (torn or of another type); they are recomputed.

    Examples
    --------
    >>> import phasekit as pk
    >>> import dataclasses, tempfile, pathlib
    >>> Row = dataclasses.make_dataclass('Row', [('key', str), ('value', float)], frozen=True)
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> store = pk.sweep.ResultStore(d / 'rows.csv', d / 'rows.json', Row, {'study': 'demo'})
    >>> store.add(Row('x', 1.5)); 'x' in store, store.get('x').value
    (True, 1.5)
    """

    def __init__(self, csv_path: Path, manifest_path: Path, row_type, meta: dict, fresh: bool = False):
        self.csv_path, self.manifest_path, self.row_type = Path(csv_path), Path(manifest_path), row_type
        self.fields = [f.name for f in dataclasses.fields(row_type)]
        self.csv_path.parent.mkdir(parents=True, exist_ok=True)
        if fresh:
            for p in (self.csv_path, self.manifest_path):
                if p.exists():
                    p.unlink()
        self._rows: dict[str, object] = {}
        self.dropped = 0
        if self.csv_path.exists():
            self._load()
        # a resumed study keeps the history of its runs: which code and command computed how many rows
        prev = self._read_manifest() if self._rows else {}
        runs = list(prev.get("runs") or ([{k: prev.get(k) for k in RUN_FIELDS}] if prev else []))[-(MAX_RUNS - 1):]
        now = _dt.datetime.now().isoformat(timespec="seconds")
        self._run = {**{k: meta.get(k) for k in RUN_FIELDS}, "started": now, "rows_at_start": len(self._rows), "rows_added": 0}
        self.meta = dict(meta)
        self.meta["started"] = prev.get("started") or self.meta.get("started") or now
        self.meta["runs"] = [*runs, self._run]
        # only a run that computes something writes the manifest: redrawing from stored rows leaves
        # it (and a committed result's provenance) as it is
        self._stored = prev
        if not prev:
            self._write_manifest()

    def _read_manifest(self) -> dict:
        try:
            prev = json.loads(self.manifest_path.read_text())
        except (OSError, ValueError):
            return {}
        return prev if isinstance(prev, dict) else {}

    def _load(self) -> None:
        text = self.csv_path.read_text()
        lines = list(csv.reader(io.StringIO(text)))
        header, body = (lines[0], lines[1:]) if lines else ([], [])
        if body and not text.endswith("\n"):
            # rows are written whole with their newline: a last line without one was cut by a
            # kill, even when its cells still parse (a cut inside the last, free-text field)
            body.pop()
            self.dropped += 1
        for cells in body:
            try:
                row = row_from_cells(self.row_type, cells)
            except (ValueError, TypeError):
                self.dropped += 1  # a torn or foreign row: recompute it
                continue
            self._rows[row.key] = row
        if header != self.fields or self.dropped or not text.endswith("\n"):
            self._rewrite()

    def __contains__(self, key: str) -> bool:
        return key in self._rows

    def get(self, key: str):
        return self._rows.get(key)

    def rows(self, keys=None) -> list:
        """The stored rows in the order they were stored; with ``keys``, only those whose key is
        among them (e.g. the rows of this run's tasks, out of a store that holds more).

        Parameters
        ----------
        keys : iterable of str, optional
            The keys of the rows wanted.

        Returns
        -------
        list
            The rows.
        """
        if keys is None:
            return list(self._rows.values())
        keys = set(keys)
        return [r for r in self._rows.values() if r.key in keys]

    def _line(self, row) -> str:
        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerow([_cell(getattr(row, f)) for f in self.fields])
        return buf.getvalue()

    def _rewrite(self) -> None:
        tmp = self.csv_path.with_name(self.csv_path.name + f".{os.getpid()}.tmp")
        with open(tmp, "w", newline="") as fh:
            fh.write(",".join(self.fields) + "\n")
            fh.writelines(self._line(r) for r in self._rows.values())
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, self.csv_path)

    def add(self, row) -> None:
        """Append one finished row and make it durable before returning.

        Parameters
        ----------
        row : row_type
            The row; it replaces a stored row of the same key.

        Raises
        ------
        TypeError
            If ``row`` is not of the store's row type.
        """
        if not isinstance(row, self.row_type):
            raise TypeError(f"expected a {self.row_type.__name__}, got {type(row).__name__}")
        self._rows[row.key] = row
        self._run["rows_added"] += 1
        if not self.csv_path.exists():
            self._rewrite()
        else:
            with open(self.csv_path, "a", newline="") as fh:
                fh.write(self._line(row))  # one write of a whole line
                fh.flush()
                os.fsync(fh.fileno())
        self._write_manifest()

    def annotate(self, **fields) -> None:
        """Add fields (e.g. a study's summary) to the manifest and write it.

        Parameters
        ----------
        **fields
            The entries to add.
        """
        self.meta.update(fields)
        changed = any(self._stored.get(k) != json.loads(json.dumps(v, default=str)) for k, v in fields.items())
        if self._run["rows_added"] or not self._stored or changed:
            self._write_manifest()

    def _write_manifest(self) -> None:
        self.meta["updated"] = _dt.datetime.now().isoformat(timespec="seconds")
        self.meta["n_rows"] = len(self._rows)
        tmp = self.manifest_path.with_name(self.manifest_path.name + f".{os.getpid()}.tmp")
        with open(tmp, "w") as fh:
            json.dump(self.meta, fh, indent=2, default=str)
        os.replace(tmp, self.manifest_path)


def stored_rows(stores, members: dict | None = None):
    """(store_get, on_result) for :func:`run_tasks` over one or more :class:`ResultStore`: a task
    is done when all its rows are stored (``members[task key]``: their keys; a task not in
    ``members`` writes the one row keyed like the task, which ``store_get`` returns, so that a
    task continuing it gets it); each finished row goes to the store of its type, once.

    Parameters
    ----------
    stores : iterable of ResultStore
        The stores, one per row type.
    members : dict, optional
        Task key -> the keys of its rows (e.g. from :func:`chunked`).

    Returns
    -------
    tuple of (callable, callable)
        ``store_get(key)`` (the stored row, the list of a task's rows, or None) and
        ``on_result(spec, result)`` (``result`` a row or a list of rows).

    Examples
    --------
    >>> import phasekit as pk
    >>> import dataclasses, tempfile, pathlib
    >>> Row = dataclasses.make_dataclass('Row', [('key', str), ('value', float)], frozen=True)
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> store = pk.sweep.ResultStore(d / 'rows.csv', d / 'rows.json', Row, {})
    >>> get, on_result = pk.sweep.stores.stored_rows([store], {'task': ['x', 'y']})
    >>> on_result(None, [Row('x', 1.0), Row('y', 2.0)]); [r.value for r in get('task')]
    [1.0, 2.0]
    """
    stores, members = list(stores), members or {}

    def find(key):
        return next((r for r in (st.get(key) for st in stores) if r is not None), None)

    def get(key):
        if key not in members:
            return find(key)
        rows = [find(k) for k in members[key]]
        return rows if all(r is not None for r in rows) else None

    def on_result(spec, result):
        for row in result if isinstance(result, list) else [result]:
            store = next(st for st in stores if isinstance(row, st.row_type))
            if row.key not in store:
                store.add(row)

    return get, on_result
