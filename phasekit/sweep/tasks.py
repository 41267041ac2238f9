"""The task runner of sweeps: tasks on Dask (or serially), the compiled models shipped to each worker
once, and every finished result written to disk at once so that a killed sweep resumes where it stopped.

* :class:`ModelPack` snapshots this process's compiled CasADi models and integrators (after a
  warm-up) as one pickle. It is scattered to every worker once and installed into the worker's
  caches before its first task: no worker compiles anything.
* :class:`ResultStore` is a CSV file of typed rows (a dataclass per table) plus a JSON
  manifest (versions, git commit, all parameters). A row is appended, flushed and synced as
  soon as its task finishes; on a rerun every stored row is checked (field count, types) and
  a broken one (a kill in mid-write) is dropped and recomputed.
* :func:`run_tasks` runs :class:`TaskSpec` s whose ``after`` names the task whose result
  they continue from, on a Dask client or serially, with a tqdm progress bar;
  :func:`run_pending` as a study runs it (nothing started when everything is stored).

The rows of the threshold and map studies are in :mod:`phasekit.studies.maps`; the scaffold of a study
script in :mod:`phasekit.sweep.study`; all of it is public as :mod:`phasekit.sweep`.
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
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

from .._runtime.errors import ParameterError
from .._runtime.pool import main_not_reimported
from .._runtime.watch import check_max_wall, progress_bar, wall_deadline
from ..core import engines, model
from ..thresholds.threshold import evaluate_outcomes

__all__ = ["ModelPack", "ResultStore", "TaskSpec", "run_tasks", "run_pending", "PendingRun", "make_client", "provenance",
           "client_evaluator", "stored_rows", "each", "chunked"]

_INSTALLED: set[int] = set()


class ModelPack:
    """Compiled models and integrators of one process, ready to ship to workers.

    Examples
    --------
    >>> import phasekit as pk
    >>> pack = pk.sweep.ModelPack.build(lambda: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    >>> pack.install(); pack.size_mb > 0
    True
    """

    def __init__(self, blob: bytes, token: int):
        self.blob = blob
        self.token = token

    @classmethod
    def build(cls, warm: Callable[[], None] | None = None) -> "ModelPack":
        """Run ``warm`` (simulations that touch every model and integrator the sweep uses),
        then snapshot the caches."""
        if warm is not None:
            warm()
        blob = pickle.dumps((model.snapshot(), engines.snapshot()))
        return cls(blob, hash(blob))

    def install(self) -> None:
        """Put the snapshot into this process's caches (once per process)."""
        if self.token in _INSTALLED:
            return
        compiled_models, integrators = pickle.loads(self.blob)
        model.install(compiled_models)
        engines.install(integrators)
        _INSTALLED.add(self.token)

    @property
    def size_mb(self) -> float:
        return len(self.blob) / 1e6


CODE_PATHS = ("phasekit", "studies", "benchmarks", "pyproject.toml")


def provenance(extra: dict | None = None) -> dict:
    """Versions, git commit and command line: what a result was obtained with. ``git_dirty``
    says whether the code (CODE_PATHS) differs from that commit.

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
    root = Path(__file__).resolve().parents[1]
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
    manifest's ``runs`` lists every run that used the file (commit, command, rows added),
    so resumed and re-plotted results still say what computed them.

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
        among them (e.g. the rows of this run's tasks, out of a store that holds more)."""
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
        """Append one finished row and make it durable before returning."""
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
        """Add fields (e.g. a study's summary) to the manifest and write it."""
        self.meta.update(fields)
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
    """One task: ``func(previous_result, *args)``; ``after`` is the key of the task it
    continues (None: independent). ``cost`` is a relative estimate of its run time: Dask
    starts the costliest tasks first (longest-processing-time order), which keeps the
    workers busy to the end.

    Examples
    --------
    >>> import phasekit as pk
    >>> spec = pk.sweep.TaskSpec('b', lambda prev, x: prev + x, (2,), after='a')
    >>> spec.after, spec.func(1, *spec.args)
    ('a', 3)
    """

    key: str
    func: Callable
    args: tuple = ()
    after: str | None = None
    label: str = ""
    meta: dict = field(default_factory=dict)
    cost: float = 1.0


class _ByValue:
    """A task function pickled by value: Dask checks only the task's own module against
    cloudpickle's by-value registry, so a function from a module registered there (a study
    loaded from its file, as the benchmarks do) would go by reference and fail to import on
    the worker (``No module named ...``), killing it again at every restart."""

    def __init__(self, func):
        import cloudpickle

        self.blob = cloudpickle.dumps(func)

    def load(self):
        return pickle.loads(self.blob)


def _shipped(func):
    import cloudpickle

    by_value = getattr(func, "__module__", None) in cloudpickle.list_registry_pickle_by_value()
    return _ByValue(func) if by_value else func


def _call(func, pack, prev, *args):
    if isinstance(func, _ByValue):
        func = func.load()
    if pack is not None:
        pack.install()
    return func(prev, *args)


def make_client(scheduler: str | None = None, workers: int | None = None, *, timeout: float = 5.0):
    """A Dask client: to a running scheduler, or a LocalCluster with one single-threaded
    worker process per core. Returns (client, cluster or None).

    A ``scheduler`` address that is malformed, or where no Dask scheduler answers within
    ``timeout`` seconds, raises :class:`ParameterError` (parameter ``scheduler``) at once, as
    does a ``workers`` count below 1.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.sweep.make_client('tcp://127.0.0.1:1', timeout=0.5)  # doctest: +IGNORE_EXCEPTION_DETAIL
    Traceback (most recent call last):
        ...
    phasekit._runtime.errors.ParameterError: `scheduler` must be the address of a running Dask scheduler, like tcp://127.0.0.1:8786, but no scheduler answered there within 0.5 s, got 'tcp://127.0.0.1:1'.
    """
    import asyncio
    import concurrent.futures
    import logging

    from dask.distributed import Client, LocalCluster

    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError("workers", "must be an integer >= 1 (or None: one per core)", workers)
    if scheduler is not None and not (isinstance(scheduler, str) and scheduler.strip()):
        raise ParameterError("scheduler", "must be the address of a running Dask scheduler, like tcp://127.0.0.1:8786",
                             scheduler)
    if scheduler:
        def refuse(why: str) -> ParameterError:
            return ParameterError("scheduler", f"must be the address of a running Dask scheduler, like "
                                  f"tcp://127.0.0.1:8786, but {why}", scheduler)

        async def identity():  # ask before building a Client: a failed Client leaves noise at exit
            from distributed.core import rpc

            r = rpc(scheduler, timeout=timeout)
            try:
                return await asyncio.wait_for(r.identity(), timeout)
            finally:
                await r.close_rpc()

        with concurrent.futures.ThreadPoolExecutor(1) as pool:  # its own event loop, even under a running one
            try:
                info = pool.submit(asyncio.run, identity()).result()
            except ValueError as exc:  # the address itself ("missing port number", "unknown address scheme")
                raise refuse(str(exc).rstrip(".")) from None
            except OSError:  # refused, unreachable, timed out (TimeoutError is an OSError)
                raise refuse(f"no scheduler answered there within {timeout:g} s") from None
            except Exception as exc:
                raise refuse(f"what answered there is not a Dask scheduler ({type(exc).__name__})") from None
        if not isinstance(info, dict) or info.get("type") != "Scheduler":
            raise refuse("what answered there is not a Dask scheduler")
        try:
            return Client(scheduler, timeout=timeout), None
        except OSError:
            raise refuse(f"no scheduler answered there within {timeout:g} s") from None
    import signal
    import threading

    n = workers or os.cpu_count() or 1
    # The worker processes ignore SIGINT (an ignored signal stays ignored in a child): Ctrl-C
    # in a terminal goes to every process of the group, and this process, not each worker
    # with its own traceback, ends the run and closes the cluster.
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main_thread else None
    try:
        # no dashboard, the scheduler's small HTTP server on any free port (8787 may be taken);
        # Dask's own warnings off (e.g. each task cancelled when a run is stopped): errors stay
        with main_not_reimported():  # spawn would re-import the calling script (see phasekit._runtime.pool)
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                   scheduler_kwargs={"dashboard_address": ":0"}, silence_logs=logging.ERROR)
    finally:
        if main_thread and previous is not None:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


def run_tasks(specs: list[TaskSpec], *, store_get: Callable[[str], object | None], on_result: Callable[[TaskSpec, object], None],
              client=None, pack: ModelPack | None = None, progress: bool | None = True, desc: str = "tasks",
              max_wall: float | None = None) -> dict[str, object]:
    """Run every task not already stored; results go to ``on_result`` as they finish.

    ``store_get(key)`` returns a stored result (the task is then skipped, and its result
    still feeds the tasks that continue from it). ``max_wall`` (seconds) bounds the call:
    tasks not finished by then are left undone (cancelled on Dask; in this process the run
    under way ends "failed" with a reason naming the budget), and what finished is returned
    (and was passed to ``on_result``, so that a rerun resumes from it).

    Examples
    --------
    >>> import phasekit as pk
    >>> specs = [pk.sweep.TaskSpec('a', lambda prev: 1), pk.sweep.TaskSpec('b', lambda prev: prev + 1, after='a')]
    >>> pk.sweep.run_tasks(specs, store_get=lambda key: None, on_result=lambda s, r: None, progress=False)
    {'a': 1, 'b': 2}
    """
    max_wall = check_max_wall(max_wall)
    results: dict[str, object] = {}
    todo = []
    for s in specs:
        stored = store_get(s.key)
        if stored is not None:
            results[s.key] = stored
        else:
            todo.append(s)
    with progress_bar(len(todo), desc=desc, unit="task", progress=progress) as bar, wall_deadline(max_wall) as end:
        if client is None:
            _run_here(todo, results, on_result, pack, bar, end)
        else:
            _run_on(client, todo, results, on_result, pack, bar, end)
    return results


def _run_here(todo, results, on_result, pack, bar, end) -> None:
    order = {s.key: i for i, s in enumerate(todo)}
    independent = sorted((s for s in todo if not s.after), key=lambda s: (-s.cost, order[s.key]))
    chained = [s for s in todo if s.after]
    for s in independent + chained:  # every chained task comes after the one it continues
        if time.perf_counter() > end:
            return
        prev = results.get(s.after) if s.after else None
        r = _call(s.func, pack, prev, *s.args)
        results[s.key] = r
        on_result(s, r)
        bar.update()


def _run_on(client, todo, results, on_result, pack, bar, end) -> None:
    from dask.distributed import as_completed

    # hash=False: a key of its own per scatter. With the default content hash, scattering the same
    # pack again just after the previous run released it races with that release and the new
    # tasks fail with "lost dependencies" (dask/distributed#8576; seen in a benchmark's second run).
    pack_f = client.scatter(pack, broadcast=True, hash=False) if pack is not None else None
    futures, by_future = {}, {}
    for s in todo:
        prev = futures.get(s.after, results.get(s.after)) if s.after else None
        f = client.submit(_call, _shipped(s.func), pack_f, prev, *s.args, key=f"task-{abs(hash(s.key))}", pure=False,
                          priority=int(round(1000 * s.cost)))
        futures[s.key] = f
        by_future[f] = s
    timeout = None if end == float("inf") else max(0.0, end - time.perf_counter())
    try:
        for f in as_completed(list(futures.values()), timeout=timeout):
            s = by_future[f]
            r = f.result()
            results[s.key] = r
            on_result(s, r)
            bar.update()
    except TimeoutError:  # the wall budget: what is not done stays undone (a rerun resumes)
        client.cancel([f for f in futures.values() if not f.done()])


@dataclass(frozen=True)
class PendingRun:
    """How :func:`run_pending` ran: ``computed`` of ``total`` tasks, ``mode`` in words.

    Examples
    --------
    >>> import phasekit as pk
    >>> str(pk.sweep.PendingRun(3, 5, 'serial'))
    '3 of 5 tasks computed now (serial)'
    """

    computed: int
    total: int
    mode: str
    left: int = 0  # tasks left undone when the wall budget ran out

    def __str__(self) -> str:
        end = f"; {self.left} left undone: the wall budget ran out (rerun to resume)" if self.left else ""
        return f"{self.computed} of {self.total} tasks computed now ({self.mode}){end}"


def run_pending(specs: list[TaskSpec], *, store_get: Callable[[str], object | None],
                on_result: Callable[[TaskSpec, object], None], warm_up: Callable[[], None], serial: bool = False,
                scheduler: str | None = None, workers: int | None = None, progress: bool | None = True,
                desc: str = "tasks", max_wall: float | None = None) -> PendingRun:
    """:func:`run_tasks` as a study runs it: nothing is compiled and no cluster is started
    when every task is stored; otherwise ``warm_up`` compiles the models once into a
    :class:`ModelPack`, and the tasks run on Dask (:func:`make_client`: ``scheduler`` or a
    LocalCluster of ``workers``), or in this process with ``serial=True``; ``max_wall`` as
    for :func:`run_tasks` (the cluster's start-up counts).

    Examples
    --------
    >>> import phasekit as pk
    >>> specs = [pk.sweep.TaskSpec('a', lambda prev: 1)]
    >>> str(pk.sweep.run_pending(specs, store_get=lambda key: None, on_result=lambda s, r: None, warm_up=lambda: None, serial=True, progress=False))
    '1 of 1 tasks computed now (serial)'
    """
    t0 = time.perf_counter()
    pending = [s for s in specs if store_get(s.key) is None]
    if not pending:
        if scheduler is not None:  # a bad address is bad input whether or not there is work left
            make_client(scheduler, workers)[0].close()
        return PendingRun(0, len(specs), "all stored")
    # in this process the compiled code is here already: a pack is built only to ship it
    pack = None if serial else ModelPack.build(warm_up)
    if serial:
        warm_up()
    client = cluster = None
    mode = "serial"
    if not serial:
        client, cluster = make_client(scheduler, workers)
        mode = f"dask: {len(client.scheduler_info()['workers'])} workers, model pack {pack.size_mb:.1f} MB shipped once"
    try:
        done = run_tasks(specs, store_get=store_get, on_result=on_result, client=client, pack=pack, progress=progress,
                         desc=desc, max_wall=None if max_wall is None else max(1e-3, max_wall - (time.perf_counter() - t0)))
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    left = sum(1 for s in pending if s.key not in done)
    return PendingRun(len(pending) - left, len(specs), mode, left)


def stored_rows(stores, members: dict | None = None):
    """(store_get, on_result) for :func:`run_tasks` over one or more :class:`ResultStore`: a task
    is done when all its rows are stored (``members[task key]``: their keys; a task not in
    ``members`` writes the one row keyed like the task, which ``store_get`` returns, so that a
    task continuing it gets it); each finished row goes to the store of its type, once.

    Examples
    --------
    >>> import phasekit as pk
    >>> import dataclasses, tempfile, pathlib
    >>> Row = dataclasses.make_dataclass('Row', [('key', str), ('value', float)], frozen=True)
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> store = pk.sweep.ResultStore(d / 'rows.csv', d / 'rows.json', Row, {})
    >>> get, on_result = pk.sweep.stored_rows([store], {'task': ['x', 'y']})
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


def _apply(fn, prev, *args):
    return fn(*args)


def each(items, key: Callable, fn: Callable, *, cost: float = 1.0) -> list[TaskSpec]:
    """One independent task per item (a tuple of arguments): ``fn(*item)`` gives the row keyed
    ``key(*item)``.

    Examples
    --------
    >>> import phasekit as pk
    >>> [s.key for s in pk.sweep.each([(1, 2), (3, 4)], lambda a, b: f"{a}+{b}", lambda a, b: a + b)]
    ['1+2', '3+4']
    """
    return [TaskSpec(key(*item), partial(_apply, fn), tuple(item), cost=cost) for item in items]


def chunked(items, key: Callable, fn: Callable, *, size: int, args: tuple = (), prefix: str = "chunk",
            cost: float | None = None) -> tuple[list[TaskSpec], dict[str, list[str]]]:
    """Items in tasks of ``size``: ``fn(prev, chunk, *args)`` returns the rows of a chunk, keyed
    ``key(*item)``. Returns the tasks (cost: the chunk's length unless given) and their row keys
    (``members`` of :func:`stored_rows` and :meth:`phasekit.sweep.Study.run`).

    Examples
    --------
    >>> import phasekit as pk
    >>> specs, members = pk.sweep.chunked([(1,), (2,), (3,)], lambda x: f"x={x}", None, size=2)
    >>> [len(s.args[0]) for s in specs], list(members.values())
    ([2, 1], [['x=1', 'x=2'], ['x=3']])
    """
    specs, members = [], {}
    for i in range(0, len(items), size):
        part = items[i:i + size]
        spec = TaskSpec(f"{prefix}|{i}|{key(*part[0])}", fn, (part, *args), cost=float(len(part)) if cost is None else cost)
        specs.append(spec)
        members[spec.key] = [key(*item) for item in part]
    return specs, members


def _evaluate_part(pack, jobs, engine):
    if pack is not None:
        pack.install()
    return evaluate_outcomes(jobs, engine=engine)


def client_evaluator(client, *, engine: str = "batch", pack: ModelPack | None = None, parts: int | None = None):
    """``evaluate(jobs)`` for :func:`phasekit.find_threshold` and
    :func:`phasekit.thresholds.threshold.run_searches` on a Dask client: each round's simulations are
    split into one part per worker (interleaved, so the parts cost about the same) and run
    there on ``engine``. With k-section (``levels`` > 1) a single search then uses every
    worker: parallel bracketing when the workers have nothing else to do.

    Examples
    --------
    >>> import phasekit as pk
    >>> import inspect
    >>> list(inspect.signature(pk.sweep.client_evaluator).parameters)
    ['client', 'engine', 'pack', 'parts']
    """
    n = parts or max(1, len(client.scheduler_info()["workers"]))
    pack_f = client.scatter(pack, broadcast=True, hash=False) if pack is not None else None  # see _run_on

    def evaluate(jobs):
        chunks = [list(range(i, len(jobs), n)) for i in range(n)]
        chunks = [c for c in chunks if c]
        futures = [client.submit(_evaluate_part, pack_f, [jobs[j] for j in c], engine, pure=False) for c in chunks]
        out = [None] * len(jobs)
        for c, part in zip(chunks, client.gather(futures)):
            for j, o in zip(c, part):
                out[j] = o
        return out

    return evaluate
