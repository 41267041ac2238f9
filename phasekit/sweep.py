"""Sweeps: chains of dependent tasks on Dask (or serially), the compiled model shipped to
each worker once, and every finished result written to disk at once so that a killed
sweep resumes where it stopped.

* :class:`ModelPack` snapshots this process's compiled CasADi models and heyoka
  integrators (after a warm-up) as one pickle. It is scattered to every worker once and
  installed into the worker's caches before its first task: no worker compiles anything.
* :class:`ResultStore` is a CSV file plus a JSON manifest (versions, git commit, all
  parameters). A row is appended and flushed as soon as its task finishes; on a rerun,
  rows whose key is already present are not recomputed.
* :func:`run_tasks` runs :class:`TaskSpec` s whose ``after`` names the task whose result
  they continue from (continuation in the aspect ratio), on a Dask client or serially,
  with a tqdm progress bar over finished tasks.
"""

from __future__ import annotations

import csv
import datetime as _dt
import json
import os
import pickle
import platform
import subprocess
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["ModelPack", "ResultStore", "TaskSpec", "run_tasks", "make_client", "provenance"]

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
        from .backends import TaylorBackend

        if warm is not None:
            warm()
        blob = pickle.dumps((dict(_model._CACHE), dict(TaylorBackend._memory)))
        return cls(blob, hash(blob))

    def install(self) -> None:
        """Put the snapshot into this process's caches (once per process)."""
        if self.token in _INSTALLED:
            return
        from . import model as _model
        from .backends import TaylorBackend

        models, taylor = pickle.loads(self.blob)
        for k, v in models.items():
            _model._CACHE.setdefault(k, v)
        for k, v in taylor.items():
            TaylorBackend._memory.setdefault(k, v)
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
    d = {
        "phasekit": __version__,
        "casadi": casadi.__version__,
        "heyoka": hy,
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "python": platform.python_version(),
        "git_commit": commit or None,
        "git_dirty": dirty,
        "command": " ".join(sys.argv),
    }
    if extra:
        d.update(extra)
    return d


class ResultStore:
    """Append-only CSV of finished rows (keyed by ``key``) with a JSON manifest beside it."""

    def __init__(self, csv_path: Path, manifest_path: Path, fields: list[str], meta: dict, fresh: bool = False):
        self.csv_path, self.manifest_path, self.fields = Path(csv_path), Path(manifest_path), list(fields)
        self.csv_path.parent.mkdir(parents=True, exist_ok=True)
        if fresh:
            for p in (self.csv_path, self.manifest_path):
                if p.exists():
                    p.unlink()
        self._rows: dict[str, dict] = {}
        if self.csv_path.exists():
            with open(self.csv_path, newline="") as fh:
                for row in csv.DictReader(fh):
                    if row.get("key"):
                        self._rows[row["key"]] = row
            # a header from an older layout: rewrite the file with the current one
            with open(self.csv_path, newline="") as fh:
                header = next(csv.reader(fh), [])
            if header != self.fields:
                self._rewrite()
        self.meta = dict(meta)
        self.meta["started"] = self.meta.get("started") or _dt.datetime.now().isoformat(timespec="seconds")
        self._write_manifest()

    def __contains__(self, key: str) -> bool:
        return key in self._rows

    def get(self, key: str) -> dict | None:
        return self._rows.get(key)

    def rows(self) -> list[dict]:
        return list(self._rows.values())

    def _rewrite(self) -> None:
        tmp = self.csv_path.with_suffix(".tmp")
        with open(tmp, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=self.fields, extrasaction="ignore")
            w.writeheader()
            for row in self._rows.values():
                w.writerow(row)
        os.replace(tmp, self.csv_path)

    def add(self, row: dict) -> None:
        """Append one finished row and flush it to disk before returning."""
        row = {k: ("" if row.get(k) is None else row.get(k)) for k in self.fields}
        self._rows[row["key"]] = {k: str(v) for k, v in row.items()}
        new = not self.csv_path.exists()
        with open(self.csv_path, "a", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=self.fields, extrasaction="ignore")
            if new:
                w.writeheader()
            w.writerow(row)
            fh.flush()
            os.fsync(fh.fileno())
        self._write_manifest()

    def _write_manifest(self) -> None:
        self.meta["updated"] = _dt.datetime.now().isoformat(timespec="seconds")
        self.meta["n_rows"] = len(self._rows)
        tmp = self.manifest_path.with_suffix(".tmp")
        with open(tmp, "w") as fh:
            json.dump(self.meta, fh, indent=2, default=str)
        os.replace(tmp, self.manifest_path)


@dataclass
class TaskSpec:
    """One task: ``func(pack, previous_result, *args)``; ``after`` is the key of the task it continues."""

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
              client=None, pack: ModelPack | None = None, progress: bool = True) -> dict[str, object]:
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
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover
        tqdm = None
    bar = tqdm(total=len(todo), desc="thresholds", unit="point", disable=not progress or tqdm is None, file=sys.stderr) if tqdm else None
    if client is None:
        for s in todo:  # specs are listed so that every task comes after the one it continues
            prev = results.get(s.after) if s.after else None
            r = _call(s.func, pack, prev, *s.args)
            results[s.key] = r
            on_result(s, r)
            if bar:
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
            if bar:
                bar.update()
    if bar:
        bar.close()
    return results
