"""Whether a committed table is what the code produces: a table in ``figures/`` (CSV or JSON)
against a fresh run's, cell by cell, and which study writes which table.

Cells are compared as the exact text written (a float bit for bit, as ``repr`` wrote it), never
as numbers: a table that reproduces is the same file but for the fields named in
:data:`EXCEPTED_COLUMNS` (wall times, anywhere) and :data:`PROVENANCE_FIELDS` (the top level of
a store manifest), and a CSV row whose run a wall-time budget cut (:data:`WALL_CUT_STATUS`,
:data:`WALL_CUT_REASONS`). CSV rows are matched by their ``key`` column where the table has one
(a resumable store appends rows in the order its Dask tasks finish), else by their order, and a
keyless table that holds the same rows in another order is said to (not counted as differing);
JSON fields are matched by their path. ``studies/reproduce.py`` reruns the studies and reports
with these.
"""

from __future__ import annotations

import csv
import json
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from .reproduce_owners import Ownership, owners  # noqa: F401  (studies/reproduce.py reads them as rt.owners)

#: CSV columns and JSON fields (at any depth) that are wall times, so differ on every run: not
#: compared, and named in every report
EXCEPTED_COLUMNS: dict[str, str] = {
    "wall_s": "wall time (s) of a run, a search, a task or the whole study",
    "task_s": "sum of the tasks' wall times (s) (threshold_vs_mu's summary)",
}
#: top-level fields of a store manifest (a JSON with ``git_commit`` at its top, written by
#: pk.sweep.provenance) that say how and when it was computed, not what: not compared. Only at the
#: top of a manifest: elsewhere ``phasekit`` (spin_down_summary.json's checks) and ``runs``
#: (euler_disk.json) are results.
PROVENANCE_FIELDS: dict[str, str] = {
    "phasekit": "versions", "casadi": "versions", "heyoka": "versions", "numpy": "versions", "scipy": "versions",
    "python": "versions",
    "git_commit": "the commit the rows were computed at", "git_dirty": "whether the code differed from that commit",
    "command": "the command line (its paths: the scratch folder)", "started": "dates", "updated": "dates",
    "runs": "the history of the runs that computed rows (dates, commits, commands, row counts)",
}
#: a CSV row that a wall-time budget cut (in either table) is not compared: how far its run got
#: depends on the machine's speed. Cut: its ``status`` is one of WALL_CUT_STATUS (pk.baseline's
#: runs past their cap, work_precision.csv), or a cell holds one of WALL_CUT_REASONS (simulate's
#: reasons for a run ended by ``max_wall`` or by the caller's budget)
WALL_CUT_STATUS = ("capped",)
WALL_CUT_REASONS = ("wall-time limit", "wall budget")
#: a JSON is a store manifest when its top level has this field
MANIFEST_MARK = "git_commit"
#: the column that names a CSV row
KEY_COLUMN = "key"
#: the files that are tables (figures, movies and scenes are not compared)
TABLE_SUFFIXES = (".csv", ".json")


@dataclass(frozen=True)
class Cell:
    """One differing cell: its column (or JSON field path), its row, and the two texts."""

    column: str
    row: str
    committed: str
    rerun: str

    def relative(self) -> float | None:
        """|committed - rerun| / max(|committed|, |rerun|) when both are finite numbers, else None."""
        try:
            a, b = float(self.committed), float(self.rerun)
        except ValueError:
            return None
        if not (math.isfinite(a) and math.isfinite(b)):
            return None
        scale = max(abs(a), abs(b))
        return abs(a - b) / scale if scale else 0.0


@dataclass
class TableDiff:
    """A committed table against its rerun.

    Attributes
    ----------
    name : str
        The file name.
    matched_by : str
        ``"key"`` (CSV rows by their key column), ``"order"`` (CSV rows by position) or
        ``"path"`` (JSON fields).
    n_rows, n_compared : int
        Rows (JSON: fields) of the committed table, and cells compared.
    cells : list of Cell
        Every differing cell, in the committed table's order.
    missing, extra : list of str
        Rows (JSON: fields) only in the committed table, only in the rerun.
    missing_columns, extra_columns : list of str
        CSV columns only in the committed table, only in the rerun.
    moved : list of tuple of (int, int)
        Rows matched by position whose tables hold the same rows in another order: (committed
        row, rerun row) of each row that moved, 1-based (``cells`` is then empty). Named, not a
        difference: a study may write rows in the order its tasks finish.
    cut : list of str
        Rows not compared because a wall-time budget cut their run, in either table (named, not
        a difference).
    excepted : list of str
        The excepted columns or fields this table has (not compared).
    error : str or None
        Why the tables could not be compared (a file that does not parse).
    """

    name: str
    matched_by: str = "order"
    n_rows: int = 0
    n_compared: int = 0
    cells: list[Cell] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    extra: list[str] = field(default_factory=list)
    missing_columns: list[str] = field(default_factory=list)
    extra_columns: list[str] = field(default_factory=list)
    moved: list[tuple[int, int]] = field(default_factory=list)
    cut: list[str] = field(default_factory=list)
    excepted: list[str] = field(default_factory=list)
    error: str | None = None

    @property
    def identical(self) -> bool:
        """No cell differs and no row or column is missing or extra (rows that moved or that a
        wall-time budget cut are named, not counted)."""
        return not (self.error or self.cells or self.missing or self.extra or self.missing_columns or self.extra_columns)

    def largest(self) -> tuple[float, Cell] | None:
        """The largest relative difference among the numeric cells that differ, and its cell."""
        rel = [(r, c) for c in self.cells if (r := c.relative()) is not None]
        return max(rel, key=lambda p: p[0]) if rel else None


def table_files(folder: Path) -> list[str]:
    """The names of the tables (CSV and JSON files) directly in ``folder``, sorted."""
    return sorted(p.name for p in Path(folder).iterdir() if p.is_file() and p.suffix in TABLE_SUFFIXES)


def compare_table(committed: Path, rerun: Path) -> TableDiff:
    """Compare a committed table with its rerun (by the suffix: CSV or JSON).

    Parameters
    ----------
    committed, rerun : Path
        The two files (the same name, in figures/ and in the rerun's folder).

    Returns
    -------
    TableDiff
        What differs; ``error`` set if either file does not parse.
    """
    compare = compare_json if Path(committed).suffix == ".json" else compare_csv
    try:
        return compare(Path(committed), Path(rerun))
    except (OSError, ValueError, csv.Error) as exc:  # a table that does not parse is reported, not a crash
        return TableDiff(Path(committed).name, error=f"{type(exc).__name__}: {exc}")


# -- CSV -----------------------------------------------------------------------------------------


def _unique(header: list[str]) -> list[str]:
    """Column names, a repeated one suffixed ``#2``, ``#3``: every cell has an address."""
    seen: dict[str, int] = {}
    out = []
    for name in header:
        seen[name] = seen.get(name, 0) + 1
        out.append(name if seen[name] == 1 else f"{name}#{seen[name]}")
    return out


def _read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="") as fh:  # newline="": a quoted cell may hold a line break
        lines = list(csv.reader(fh))
    return (_unique(lines[0]), lines[1:]) if lines else ([], [])


def _labelled(header: list[str], rows: list[list[str]], keyed: bool) -> dict[str, dict[str, str]]:
    """Row label -> {column: cell}. Keyed: the key (its n-th repeat ``key #n``: a store appends a
    row again when a task is rerun); else ``row n`` (1-based, after the header)."""
    out: dict[str, dict[str, str]] = {}
    seen: dict[str, int] = {}
    k = header.index(KEY_COLUMN) if keyed else -1
    for i, cells in enumerate(rows, 1):
        if keyed:
            key = cells[k] if k < len(cells) else ""
            seen[key] = seen.get(key, 0) + 1
            label = key if seen[key] == 1 else f"{key} #{seen[key]}"
        else:
            label = f"row {i}"
        out[label] = dict(zip(header, cells))
    return out


def compare_csv(committed: Path, rerun: Path) -> TableDiff:
    """Compare two CSV tables cell by cell (the exact text), the excepted columns left out.

    Parameters
    ----------
    committed, rerun : Path
        The two CSV files.

    Returns
    -------
    TableDiff
        Rows matched by the ``key`` column when both tables have one, else by position.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (d / "a.csv").write_text("key,x,wall_s\\nk1,1.5,0.2\\n")
    >>> _ = (d / "b.csv").write_text("key,x,wall_s\\nk1,1.5000000000000002,0.3\\n")
    >>> diff = compare_csv(d / "a.csv", d / "b.csv")
    >>> diff.cells, diff.excepted
    ([Cell(column='x', row='k1', committed='1.5', rerun='1.5000000000000002')], ['wall_s'])
    """
    h_c, rows_c = _read_csv(committed)
    h_r, rows_r = _read_csv(rerun)
    keyed = KEY_COLUMN in h_c and KEY_COLUMN in h_r
    diff = TableDiff(Path(committed).name, matched_by="key" if keyed else "order", n_rows=len(rows_c))
    diff.excepted = [c for c in dict.fromkeys(h_c + h_r) if c in EXCEPTED_COLUMNS]
    diff.missing_columns = [c for c in h_c if c not in h_r and c not in EXCEPTED_COLUMNS]
    diff.extra_columns = [c for c in h_r if c not in h_c and c not in EXCEPTED_COLUMNS]
    # the key column names the row (equal by construction when matched by it): not a cell compared
    columns = [c for c in h_c if c in h_r and c not in EXCEPTED_COLUMNS and not (keyed and c == KEY_COLUMN)]
    a, b = _labelled(h_c, rows_c, keyed), _labelled(h_r, rows_r, keyed)
    diff.missing = [label for label in a if label not in b]
    diff.extra = [label for label in b if label not in a]
    for label, row in a.items():
        other = b.get(label)
        if other is None:
            continue
        # a row matched by position is named by its position and, to find it, its first cell
        name = label if keyed or not h_c else f"{label} ({h_c[0]}={row.get(h_c[0], '')})"
        if _wall_cut(row) or _wall_cut(other):
            diff.cut.append(name)
            continue
        for col in columns:
            x, y = row.get(col, "(no cell)"), other.get(col, "(no cell)")  # a short row lacks its last cells
            diff.n_compared += 1
            if x != y:
                diff.cells.append(Cell(col, name, x, y))
    if not keyed and (diff.cells or diff.missing or diff.extra):
        diff.moved = _moved(list(a.values()), list(b.values()), columns)
        if diff.moved:  # the same rows in another order: say that, not every cell of every moved row
            diff.cells, diff.missing, diff.extra, diff.cut = [], [], [], []
    return diff


def _wall_cut(row: dict) -> bool:
    """Whether a wall-time budget cut this row's run (WALL_CUT_STATUS, WALL_CUT_REASONS)."""
    return row.get("status") in WALL_CUT_STATUS or any(r in v for v in row.values() for r in WALL_CUT_REASONS)


def _moved(a: list[dict], b: list[dict], columns: list[str]) -> list[tuple[int, int]]:
    """(committed row, rerun row), 1-based, of every row that moved, if the two tables hold the
    same rows (over ``columns``) in another order; else []."""
    def cells(row):
        return tuple(row.get(c) for c in columns)

    if sorted(map(cells, a)) != sorted(map(cells, b)):
        return []
    where: dict[tuple, list[int]] = {}
    for j, row in enumerate(b, 1):
        where.setdefault(cells(row), []).append(j)
    pairs = [(i, where[cells(row)].pop(0)) for i, row in enumerate(a, 1)]
    return [(i, j) for i, j in pairs if i != j]


# -- JSON ----------------------------------------------------------------------------------------


class _Number(str):
    """A JSON number kept as the text written (so 1.0 and 1 differ, as the files do)."""


def _load_json(path: Path):
    text = Path(path).read_text()
    return json.loads(text, parse_float=_Number, parse_int=_Number, parse_constant=_Number)


def _leaves(obj, path: tuple = ()) -> Iterable[tuple[tuple, str]]:
    """(path, text) of every leaf: a number as written, anything else as JSON text (so the
    number 1.5 and the string "1.5" differ); an empty container is a leaf."""
    if isinstance(obj, dict):
        if not obj:
            yield path, "{}"
        for k, v in obj.items():
            yield from _leaves(v, (*path, k))
    elif isinstance(obj, list):
        if not obj:
            yield path, "[]"
        for i, v in enumerate(obj):
            yield from _leaves(v, (*path, i))
    else:
        yield path, str(obj) if isinstance(obj, _Number) else json.dumps(obj)


def _dotted(path: tuple) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out or "(top)"


def _excepted(path: tuple, manifest: bool) -> str | None:
    """The excepted name on ``path`` (a wall-time field at any depth, provenance at the top of a manifest)."""
    hit = next((p for p in path if isinstance(p, str) and p in EXCEPTED_COLUMNS), None)
    if hit is None and manifest and path and path[0] in PROVENANCE_FIELDS:
        hit = path[0]
    return hit


def compare_json(committed: Path, rerun: Path) -> TableDiff:
    """Compare two JSON files field by field (numbers as the text written), the excepted fields
    left out.

    Parameters
    ----------
    committed, rerun : Path
        The two JSON files.

    Returns
    -------
    TableDiff
        ``cells`` name each field by its path (``summary.a=1.5.counts.jump``, ``threshold[3].w``);
        ``missing`` / ``extra`` are fields.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (d / "a.json").write_text('{"git_commit": "abc", "n": 3, "fit": {"x": 0.5}}')
    >>> _ = (d / "b.json").write_text('{"git_commit": "def", "n": 3, "fit": {"x": 0.50}}')
    >>> diff = compare_json(d / "a.json", d / "b.json")
    >>> [(c.column, c.committed, c.rerun) for c in diff.cells], diff.excepted
    ([('fit.x', '0.5', '0.50')], ['git_commit'])
    """
    a_obj, b_obj = _load_json(committed), _load_json(rerun)
    manifest = any(isinstance(o, dict) and MANIFEST_MARK in o for o in (a_obj, b_obj))
    a, b = dict(_leaves(a_obj)), dict(_leaves(b_obj))
    diff = TableDiff(Path(committed).name, matched_by="path", n_rows=len(a))
    excepted = {p: _excepted(p, manifest) for p in (*a, *b)}
    diff.excepted = list(dict.fromkeys(e for e in excepted.values() if e))
    diff.missing = [_dotted(p) for p in a if p not in b and not excepted[p]]
    diff.extra = [_dotted(p) for p in b if p not in a and not excepted[p]]
    for p, x in a.items():
        if p in b and not excepted[p]:
            diff.n_compared += 1
            if x != b[p]:
                diff.cells.append(Cell(_dotted(p), "", x, b[p]))
    return diff


# -- the report ------------------------------------------------------------------------------------


def excepted_lines() -> list[str]:
    """The excepted columns and fields, each with why: the report names them."""
    lines = ["Not compared (wall times: CSV columns, and JSON fields at any depth):"]
    lines += [f"  {name}: {why}" for name, why in EXCEPTED_COLUMNS.items()]
    lines.append(f"  CSV rows whose run a wall-time budget cut, in either table (status {' or '.join(WALL_CUT_STATUS)}, "
                 f"or a cell naming a {' or a '.join(WALL_CUT_REASONS)}): how far the run got depends on the machine")
    lines.append(f"Not compared (provenance: the top-level fields of a store manifest, a JSON with {MANIFEST_MARK!r}):")
    reasons: dict[str, list[str]] = {}
    for name, why in PROVENANCE_FIELDS.items():  # one line per reason: the versions together
        reasons.setdefault(why, []).append(name)
    lines += [f"  {', '.join(names)}: {why}" for why, names in reasons.items()]
    return lines


def by_column(cells: list[Cell]) -> list[tuple[str, int, float | None]]:
    """(column, differing cells, largest relative difference or None if none is numeric), in
    the order the columns first differ; a JSON field's list indices read ``[*]``, so that the
    same field of every element of a list is one column."""
    out: dict[str, tuple] = {}
    for c in cells:
        col = re.sub(r"\[\d+\]", "[*]", c.column) if not c.row else c.column
        n, rel = out.get(col, (0, None))
        r = c.relative()
        out[col] = (n + 1, rel if r is None else r if rel is None else max(rel, r))
    return [(col, n, rel) for col, (n, rel) in out.items()]


def _short(text: str, width: int = 90) -> str:
    """A long row key shortened in its middle: both its ends are what tells rows apart."""
    return text if len(text) <= width else f"{text[:width // 2 - 2]}...{text[-(width // 2 - 1):]}"


def _around(a: str, b: str, width: int = 70) -> tuple[str, str]:
    """Two long texts cut to the stretch where they first differ (their common start would hide it)."""
    if max(len(a), len(b)) <= width:
        return a, b
    start = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
    start = max(0, start - width // 3)

    def cut(t):
        return ("..." if start else "") + t[start:start + width] + ("..." if len(t) > start + width else "")

    return cut(a), cut(b)


def describe(diff: TableDiff, study: str, limit: int = 5) -> list[str]:
    """Report lines of one table: identical, or what differs (at most ``limit`` of each kind).

    Parameters
    ----------
    diff : TableDiff
        The comparison.
    study : str
        The study that wrote it.
    limit : int, optional
        How many differing cells, missing and extra rows to show.

    Returns
    -------
    list of str
        The first line names the table and the verdict; the others are indented.
    """
    unit = "fields" if diff.matched_by == "path" else "rows"
    how = {"key": f"rows by {KEY_COLUMN!r}", "order": "rows by order", "path": "fields by path"}[diff.matched_by]
    skip = f"; not compared: {', '.join(diff.excepted)}" if diff.excepted else ""
    head = f"{diff.name} ({study})"
    if diff.error:
        return [f"{head}: NOT COMPARED: {diff.error}"]
    notes = ""
    if diff.moved:
        notes += f"; the same {diff.n_rows} rows in another order ({len(diff.moved)} moved: committed row -> rerun row " + \
            ", ".join(f"{i} -> {j}" for i, j in diff.moved[:limit]) + (" ..." if len(diff.moved) > limit else "") + ")"
    if diff.cut:
        notes += f"; {len(diff.cut)} rows cut by a wall-time budget not compared: " + \
            ", ".join(_short(r, 60) for r in diff.cut[:limit]) + (" ..." if len(diff.cut) > limit else "")
    if diff.identical:
        return [f"{head}: identical ({diff.n_rows} {unit}, {diff.n_compared} cells, {how}{skip}){notes}"]
    parts = []
    if diff.cells:
        rows = "" if diff.matched_by == "path" else f" in {len({c.row for c in diff.cells})} of {diff.n_rows} rows"
        parts.append(f"{len(diff.cells)} of {diff.n_compared} cells differ{rows}")
        big = diff.largest()
        if big is not None:
            parts.append(f"largest relative difference {big[0]:.2g} ({big[1].column})")
    if diff.missing:
        parts.append(f"{len(diff.missing)} {unit} missing from the rerun")
    if diff.extra:
        parts.append(f"{len(diff.extra)} {unit} only in the rerun")
    if diff.missing_columns or diff.extra_columns:
        parts.append(f"columns only committed: {diff.missing_columns}, only in the rerun: {diff.extra_columns}")
    lines = [f"{head}: DIFFERS: {'; '.join(parts)} ({how}{skip}){notes}"]
    if diff.cells:
        lines.append("    by column (cells, largest relative difference): " + ", ".join(
            f"{col} {n}" + (f" ({rel:.2g})" if rel is not None else "") for col, n, rel in by_column(diff.cells)))
    for c in diff.cells[:limit]:
        where = c.column if diff.matched_by == "path" else f"{c.column} [{_short(c.row)}]"
        x, y = (t or "(empty)" for t in _around(c.committed, c.rerun))
        lines.append(f"    {where}: committed {x} rerun {y}")
    if len(diff.cells) > limit:
        lines.append(f"    ... and {len(diff.cells) - limit} more cells")
    for kind, labels in (("missing from the rerun", diff.missing), ("only in the rerun", diff.extra)):
        if labels:
            shown = ", ".join(_short(label, 60) for label in labels[:limit])
            lines.append(f"    {unit} {kind}: {shown}" + (f" ... and {len(labels) - limit} more" if len(labels) > limit else ""))
    return lines
