"""Sweeps: tasks on Dask (or serially), the compiled models shipped to each worker once, and
every finished result written to disk at once so that a killed sweep resumes where it stopped.

* :class:`ModelPack` snapshots this process's compiled CasADi models and heyoka
  integrators (after a warm-up) as one pickle. It is scattered to every worker once and
  installed into the worker's caches before its first task: no worker compiles anything.
* :class:`ResultStore` is a CSV file of typed rows (a dataclass per table) plus a JSON
  manifest (versions, git commit, all parameters). A row is appended, flushed and synced as
  soon as its task finishes; on a rerun every stored row is checked (field count, types) and
  a broken one (a kill in mid-write) is dropped and recomputed.
* :func:`run_tasks` runs :class:`TaskSpec` s whose ``after`` names the task whose result
  they continue from, on a Dask client or serially, with a tqdm progress bar.
* :class:`ThresholdRow` and :func:`threshold_task`: one threshold of a sweep as a row.
"""

from __future__ import annotations

import csv
import dataclasses
import datetime as _dt
import io
import json
import math
import os
import pickle
import platform
import subprocess
import sys
import time
import typing
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .errors import Status

__all__ = ["ModelPack", "ResultStore", "TaskSpec", "run_tasks", "make_client", "provenance", "ThresholdRow",
           "threshold_task", "threshold_key"]

_INSTALLED: set[int] = set()


class ModelPack:
    """Compiled models and integrators of one process, ready to ship to workers."""

    def __init__(self, blob: bytes, token: int):
        self.blob = blob
        self.token = token

    @classmethod
    def build(cls, warm: Callable[[], None] | None = None) -> "ModelPack":
        """Run ``warm`` (simulations that touch every model and integrator the sweep uses),
        then snapshot the caches."""
        from . import model as _model
        from .backends import TaylorEngine

        if warm is not None:
            warm()
        blob = pickle.dumps((dict(_model._CACHE), dict(TaylorEngine._memory)))
        return cls(blob, hash(blob))

    def install(self) -> None:
        """Put the snapshot into this process's caches (once per process)."""
        if self.token in _INSTALLED:
            return
        from . import model as _model
        from .backends import TaylorEngine

        models, taylor = pickle.loads(self.blob)
        for k, v in models.items():
            _model._CACHE.setdefault(k, v)
        for k, v in taylor.items():
            TaylorEngine._memory.setdefault(k, v)
        _INSTALLED.add(self.token)

    @property
    def size_mb(self) -> float:
        return len(self.blob) / 1e6


def provenance(extra: dict | None = None) -> dict:
    """Versions, git commit and command line: what a result was obtained with."""
    import casadi
    import numpy
    import scipy

    from . import __version__

    try:
        import heyoka

        hy = heyoka.__version__
    except Exception:  # pragma: no cover
        hy = None
    root = Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = bool(subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                                    capture_output=True, text=True, timeout=10).stdout.strip())
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


class ResultStore:
    """Append-only CSV of finished typed rows (keyed by their ``key`` field) with a JSON
    manifest beside it. Safe against a kill at any moment: rows are appended whole (one
    write, flushed and fsynced) and every row is checked when the file is read back."""

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
        self.meta = dict(meta)
        self.meta["started"] = self.meta.get("started") or _dt.datetime.now().isoformat(timespec="seconds")
        self._write_manifest()

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

    def rows(self) -> list:
        return list(self._rows.values())

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
        """Append one finished row and make it durable before returning."""
        if not isinstance(row, self.row_type):
            raise TypeError(f"expected a {self.row_type.__name__}, got {type(row).__name__}")
        self._rows[row.key] = row
        if not self.csv_path.exists():
            self._rewrite()
        else:
            with open(self.csv_path, "a", newline="") as fh:
                fh.write(self._line(row))  # one write of a whole line
                fh.flush()
                os.fsync(fh.fileno())
        self._write_manifest()

    def _write_manifest(self) -> None:
        self.meta["updated"] = _dt.datetime.now().isoformat(timespec="seconds")
        self.meta["n_rows"] = len(self._rows)
        tmp = self.manifest_path.with_name(self.manifest_path.name + f".{os.getpid()}.tmp")
        with open(tmp, "w") as fh:
            json.dump(self.meta, fh, indent=2, default=str)
        os.replace(tmp, self.manifest_path)


# -- tasks -----------------------------------------------------------------------------------


@dataclass
class TaskSpec:
    """One task: ``func(previous_result, *args)``; ``after`` is the key of the task it continues."""

    key: str
    func: Callable
    args: tuple = ()
    after: str | None = None
    label: str = ""
    meta: dict = field(default_factory=dict)


def _call(func, pack, prev, *args):
    if pack is not None:
        pack.install()
    return func(prev, *args)


def make_client(scheduler: str | None = None, workers: int | None = None):
    """A Dask client: to a running scheduler, or a LocalCluster with one single-threaded
    worker process per core. Returns (client, cluster or None)."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler), None
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def run_tasks(specs: list[TaskSpec], *, store_get: Callable[[str], object | None], on_result: Callable[[TaskSpec, object], None],
              client=None, pack: ModelPack | None = None, progress: bool = True, desc: str = "tasks") -> dict[str, object]:
    """Run every task not already stored; results go to ``on_result`` as they finish.

    ``store_get(key)`` returns a stored result (the task is then skipped, and its result
    still feeds the tasks that continue from it).
    """
    results: dict[str, object] = {}
    todo = []
    for s in specs:
        stored = store_get(s.key)
        if stored is not None:
            results[s.key] = stored
        else:
            todo.append(s)
    from tqdm import tqdm

    bar = tqdm(total=len(todo), desc=desc, unit="task", disable=not progress, file=sys.stderr)
    try:
        if client is None:
            for s in todo:  # specs are listed so that every task comes after the one it continues
                prev = results.get(s.after) if s.after else None
                r = _call(s.func, pack, prev, *s.args)
                results[s.key] = r
                on_result(s, r)
                bar.update()
        else:
            from dask.distributed import as_completed

            pack_f = client.scatter(pack, broadcast=True) if pack is not None else None
            futures, by_future = {}, {}
            for s in todo:
                prev = futures.get(s.after, results.get(s.after)) if s.after else None
                f = client.submit(_call, s.func, pack_f, prev, *s.args, key=f"task-{abs(hash(s.key))}", pure=False)
                futures[s.key] = f
                by_future[f] = s
            for f in as_completed(list(futures.values())):
                s = by_future[f]
                r = f.result()
                results[s.key] = r
                on_result(s, r)
                bar.update()
    finally:
        bar.close()
    return results


# -- threshold rows --------------------------------------------------------------------------


@dataclass(frozen=True)
class ThresholdRow:
    """One threshold of a sweep, as stored (see :func:`threshold_task`)."""

    key: str
    branch: str
    a: float
    threshold: float | None
    bracket_lo: float | None
    bracket_hi: float | None
    n_sims: int
    status: str
    definition: str
    default: bool
    group: str
    name: str
    seed: str
    amplitude: float
    eps: str  # a number, "exact", or "" (viscous)
    mu: float
    rtol: float
    transitions: str  # JSON list of [lo, hi] brackets
    stuck_near: bool | None
    check_above_jumped: bool | None
    check_below_jumped: bool | None
    consistent: bool | None
    n_check_sims: int
    wall_s: float
    reason: str


def threshold_key(defn, a: float, search: dict) -> str:
    """Key of a stored threshold row: every input that changes the answer."""
    return f"{defn.key()}|a={a:.10g}|search={json.dumps(search, sort_keys=True)}"


def threshold_task(prev: ThresholdRow | None, defn_fields: dict, a: float, group: str, is_default: bool,
                   search: dict) -> ThresholdRow:
    """One sweep task: the threshold at aspect ratio ``a`` (the search seeded by the previous
    point's row ``prev``), then the self-consistency check (1.02 x jumps, 0.98 x does not).
    Failures become a row with status "failed" and the reason."""
    from .threshold import Definition, find_threshold

    defn = Definition(**defn_fields)
    t0 = time.perf_counter()
    base = dict(key=threshold_key(defn, a, search), branch="prolate" if a > 1 else "oblate", a=a,
                definition=defn.label, default=is_default, group=group, name=defn.name, seed=defn.seed,
                amplitude=defn.amplitude, mu=defn.mu, rtol=defn.rtol,
                eps=repr(defn.eps) if defn.eps else ("exact" if defn.seed != "viscous" else ""))
    guess = prev.threshold if prev is not None else None
    try:
        th = find_threshold(defn, a, guess=guess, **search)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        return ThresholdRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, n_sims=0, status=Status.FAILED.value,
                            transitions="[]", stuck_near=None, check_above_jumped=None, check_below_jumped=None,
                            consistent=None, n_check_sims=0, wall_s=time.perf_counter() - t0,
                            reason=f"{type(exc).__name__}: {exc}")
    above = below = consistent = None
    n_check = 0
    if th.value is not None and th.status in (Status.CONVERGED, Status.NON_MONOTONE):  # not for bracket_only
        above, below = defn.outcome(a, 1.02 * th.value).jumped, defn.outcome(a, 0.98 * th.value).jumped
        n_check = 2
        consistent = bool(above) and below is False
    return ThresholdRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], n_sims=th.n_sims,
                        status=th.status.value, transitions=json.dumps([list(t) for t in th.transitions]),
                        stuck_near=th.stuck_near, check_above_jumped=above, check_below_jumped=below,
                        consistent=consistent, n_check_sims=n_check, wall_s=time.perf_counter() - t0,
                        reason=th.reason or "")


def row_dict(row) -> dict:
    return asdict(row)
