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
import hashlib
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

__all__ = ["ModelPack", "ResultStore", "TaskSpec", "run_tasks", "run_pending", "PendingRun", "make_client", "provenance", "ThresholdRow",
           "threshold_task", "threshold_key", "critical_path", "SearchRow", "search_task", "search_job", "search_group_task", "group_search_tasks", "store_groups", "job_key", "search_key", "OutcomeRow",
           "outcome_task", "outcome_key", "client_evaluator"]

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
        from .batch import _Integrators

        if warm is not None:
            warm()
        blob = pickle.dumps((dict(_model._CACHE), dict(TaylorEngine._memory), dict(_Integrators.memory)))
        return cls(blob, hash(blob))

    def install(self) -> None:
        """Put the snapshot into this process's caches (once per process)."""
        if self.token in _INSTALLED:
            return
        from . import model as _model
        from .backends import TaylorEngine
        from .batch import _Integrators

        models, taylor, batch = pickle.loads(self.blob)
        for k, v in models.items():
            _model._CACHE.setdefault(k, v)
        for k, v in taylor.items():
            TaylorEngine._memory.setdefault(k, v)
        for k, v in batch.items():
            _Integrators.memory.setdefault(k, v)
        _INSTALLED.add(self.token)

    @property
    def size_mb(self) -> float:
        return len(self.blob) / 1e6


CODE_PATHS = ("phasekit", "studies", "benchmarks", "pyproject.toml")


def provenance(extra: dict | None = None) -> dict:
    """Versions, git commit and command line: what a result was obtained with. ``git_dirty``
    says whether the code (CODE_PATHS) differs from that commit."""
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
    so resumed and re-plotted results still say what computed them."""

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
    workers busy to the end."""

    key: str
    func: Callable
    args: tuple = ()
    after: str | None = None
    label: str = ""
    meta: dict = field(default_factory=dict)
    cost: float = 1.0


def _call(func, pack, prev, *args):
    if pack is not None:
        pack.install()
    return func(prev, *args)


def make_client(scheduler: str | None = None, workers: int | None = None, *, timeout: float = 5.0):
    """A Dask client: to a running scheduler, or a LocalCluster with one single-threaded
    worker process per core. Returns (client, cluster or None).

    A ``scheduler`` address that is malformed, or where no Dask scheduler answers within
    ``timeout`` seconds, raises :class:`ParameterError` (parameter ``scheduler``) at once, as
    does a ``workers`` count below 1."""
    import asyncio
    import concurrent.futures
    import logging

    from dask.distributed import Client, LocalCluster

    from .errors import ParameterError
    from .pool import main_not_reimported

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
        with main_not_reimported():  # spawn would re-import the calling script (see phasekit.pool)
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
    """
    from .watch import check_max_wall, progress_bar, wall_deadline

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

    pack_f = client.scatter(pack, broadcast=True) if pack is not None else None
    futures, by_future = {}, {}
    for s in todo:
        prev = futures.get(s.after, results.get(s.after)) if s.after else None
        f = client.submit(_call, s.func, pack_f, prev, *s.args, key=f"task-{abs(hash(s.key))}", pure=False,
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
    """How :func:`run_pending` ran: ``computed`` of ``total`` tasks, ``mode`` in words."""

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
    for :func:`run_tasks` (the cluster's start-up counts)."""
    t0 = time.perf_counter()
    pending = [s for s in specs if store_get(s.key) is None]
    if not pending:
        if scheduler is not None:  # a bad address is bad input whether or not there is work left
            make_client(scheduler, workers)[0].close()
        return PendingRun(0, len(specs), "all stored")
    pack = ModelPack.build(warm_up)
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


def _evaluate_part(pack, jobs, engine):
    from .threshold import evaluate_outcomes

    if pack is not None:
        pack.install()
    return evaluate_outcomes(jobs, engine=engine)


def client_evaluator(client, *, engine: str = "batch", pack: ModelPack | None = None, parts: int | None = None):
    """``evaluate(jobs)`` for :func:`phasekit.find_threshold` and
    :func:`phasekit.threshold.run_searches` on a Dask client: each round's simulations are
    split into one part per worker (interleaved, so the parts cost about the same) and run
    there on ``engine``. With k-section (``levels`` > 1) a single search then uses every
    worker: parallel bracketing when the workers have nothing else to do."""
    n = parts or max(1, len(client.scheduler_info()["workers"]))
    pack_f = client.scatter(pack, broadcast=True) if pack is not None else None

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
    eps: float | None  # the regularised law's eps; empty for exact Coulomb and viscous friction (see definition)
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
                   search: dict, engine: str = "scalar", levels: int = 1) -> ThresholdRow:
    """One sweep task: the threshold at aspect ratio ``a`` (the search seeded by the previous
    point's row ``prev``), then the self-consistency check (1.02 x jumps, 0.98 x does not).
    ``engine`` and ``levels`` (k-section) change the cost, not the bracket, and are not
    part of the key. Failures become a row with status "failed" and the reason."""
    from .threshold import Definition, find_threshold

    defn = Definition(**defn_fields)
    t0 = time.perf_counter()
    base = dict(key=threshold_key(defn, a, search), branch="prolate" if a > 1 else "oblate", a=a,
                definition=defn.label, default=is_default, group=group, name=defn.name, seed=defn.seed,
                amplitude=defn.amplitude, mu=defn.mu, rtol=defn.rtol,
                eps=defn.eps or None)
    guess = prev.threshold if prev is not None else None
    try:
        th = find_threshold(defn, a, guess=guess, engine=engine, levels=levels, **search)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        return ThresholdRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, n_sims=0, status=Status.FAILED.value,
                            transitions="[]", stuck_near=None, check_above_jumped=None, check_below_jumped=None,
                            consistent=None, n_check_sims=0, wall_s=time.perf_counter() - t0,
                            reason=f"{type(exc).__name__}: {exc}")
    above = below = consistent = None
    n_check = 0
    if th.value is not None and th.status in (Status.CONVERGED, Status.NON_MONOTONE):  # not for bracket_only
        above, below = (o.jumped for o in defn.outcomes(a, [1.02 * th.value, 0.98 * th.value], engine=engine))
        n_check = 2
        consistent = bool(above) and below is False
    return ThresholdRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], n_sims=th.n_sims,
                        status=th.status.value, transitions=json.dumps([list(t) for t in th.transitions]),
                        stuck_near=th.stuck_near, check_above_jumped=above, check_below_jumped=below,
                        consistent=consistent, n_check_sims=n_check, wall_s=time.perf_counter() - t0,
                        reason=th.reason or "")


def row_dict(row) -> dict:
    return asdict(row)


# -- search and outcome rows (the outcome map and the (a, mu) map) ------------------------------


def critical_path(specs: list[TaskSpec], rounds: dict[str, int]) -> int:
    """The longest chain of dependent simulation rounds: a task's own rounds (``rounds[key]``)
    plus those of the task it continues (``after``), maximised over tasks."""
    by_key = {s.key: s for s in specs}
    memo: dict[str, int] = {}

    def depth(key: str) -> int:
        if key not in memo:
            s = by_key.get(key)
            memo[key] = rounds.get(key, 0) + (depth(s.after) if s is not None and s.after else 0)
        return memo[key]

    return max((depth(s.key) for s in specs), default=0)


@dataclass(frozen=True)
class SearchRow:
    """One traced boundary point, as stored: a jump threshold in the family parameter at
    seed distance ``d`` (kind "threshold"), or the sticking boundary d_min in the seed
    distance at the family parameter ``value`` (kind "stick"). ``threshold`` is the
    boundary (Omega0*/n0* or d_min), ``n_rounds`` its search's rounds of independent
    simulations, ``sens_*`` the sensitivity to d when asked (d/2 and 2d)."""

    key: str
    study: str
    kind: str
    branch: str
    a: float
    mu: float
    d: float | None
    value: float | None
    threshold: float | None
    bracket_lo: float | None
    bracket_hi: float | None
    status: str
    n_sims: int
    n_rounds: int
    levels: int
    engine: str
    eps: float | None  # the regularised law's eps; empty for exact Coulomb (no regularisation)
    rtol: float
    t_max: float
    transitions: str
    stuck_near: bool
    sens_half: float | None
    sens_double: float | None
    sens_slope: float | None
    sens_shift: float | None
    sens_dominant: str
    wall_s: float
    reason: str


def search_key(defn, a: float, search: dict, kind: str = "threshold", value: float | None = None,
               sensitivity: bool = False) -> str:
    """Key of a stored search row: every input that changes the answer (the engine does not)."""
    v = "" if value is None else f"|value={value:.10g}"
    sens = "|sensitivity" if sensitivity else ""
    return f"{kind}|{defn.key()}|a={a:.10g}{v}|search={json.dumps(search, sort_keys=True)}{sens}"


def search_job(defn_fields: dict, a: float, search: dict, *, kind: str = "threshold", value: float | None = None,
               sensitivity: bool = False) -> dict:
    """One boundary point to trace, as :func:`search_group_task` takes it: a jump threshold
    at seed distance ``defn_fields["amplitude"]`` (kind "threshold"), or the sticking
    boundary d_min at the family parameter ``value`` (kind "stick"); ``search`` holds the
    keywords of :func:`phasekit.threshold.threshold_searches` or ``stick_search``."""
    return dict(defn=dict(defn_fields), a=float(a), search=dict(search), kind=kind, value=value, sensitivity=sensitivity)


def search_task(prev, defn_fields: dict, a: float, search: dict, *, kind: str = "threshold", value: float | None = None,
                study: str = "", engine: str = "batch", sensitivity: bool = False) -> SearchRow:
    """One boundary point of a map, independent of ``prev`` (see :func:`search_job`)."""
    job = search_job(defn_fields, a, search, kind=kind, value=value, sensitivity=sensitivity)
    return search_group_task(prev, [job], study=study, engine=engine)[0]


def search_group_task(prev, jobs: list[dict], *, study: str = "", engine: str = "batch") -> list[SearchRow]:
    """Several boundary points (:func:`search_job`) traced in lock-step: each round
    simulates what every unfinished search asks for in one batch (so the batch integrator's
    lanes fill across searches); each search keeps its own rounds, bracket and result.
    Failures become rows with status "failed" and the reason."""
    from .threshold import Definition, run_searches, stick_search, threshold_result, threshold_searches

    t0 = time.perf_counter()
    plans, rows = [], [None] * len(jobs)
    for i, job in enumerate(jobs):
        defn = Definition(**job["defn"])
        try:
            if job["kind"] == "stick":
                searches = [stick_search(defn, job["a"], job["value"], **job["search"])]
            else:
                searches = threshold_searches(defn, job["a"], sensitivity=job["sensitivity"], **job["search"])
            plans.append((i, defn, searches))
        except Exception as exc:
            rows[i] = _search_row(job, defn, None, study, engine, 0.0, f"{type(exc).__name__}: {exc}")
    try:
        run_searches([s for _, _, ss in plans for s in ss], engine=engine)
    except Exception as exc:  # a sweep tabulates failures instead of stopping
        for i, defn, _ in plans:
            rows[i] = _search_row(jobs[i], defn, None, study, engine, time.perf_counter() - t0, f"{type(exc).__name__}: {exc}")
        return rows
    wall = (time.perf_counter() - t0) / max(1, len(plans))  # lock-step: the group's time, shared
    for i, defn, searches in plans:
        th = searches[0].result(wall) if jobs[i]["kind"] == "stick" else threshold_result(searches, wall)
        rows[i] = _search_row(jobs[i], defn, th, study, engine, wall, th.reason or "")
    return rows


def job_key(job: dict) -> str:
    """The stored row key of a :func:`search_job`."""
    from .threshold import Definition

    return search_key(Definition(**job["defn"]), job["a"], job["search"], job["kind"], job["value"], job["sensitivity"])


def group_search_tasks(jobs: list[dict], costs: list[float], *, per_task: int, study: str = "",
                       engine: str = "batch") -> tuple[list[TaskSpec], dict[str, list[str]]]:
    """Independent tasks of up to ``per_task`` searches each, traced in lock-step by
    :func:`search_group_task`: searches of one branch (one batch integrator) and of similar
    cost share a task. Returns the tasks (cost: the sum of their searches') and, per task
    key, the row keys it produces (a task is done when all of them are stored)."""
    from functools import partial

    task = partial(search_group_task, study=study, engine=engine)
    order = sorted(range(len(jobs)), key=lambda i: (jobs[i]["a"] > 1, -costs[i]))
    specs, members = [], {}
    for branch in (False, True):
        idx = [i for i in order if (jobs[i]["a"] > 1) == branch]
        for k in range(0, len(idx), per_task):
            part = idx[k:k + per_task]
            keys = [job_key(jobs[i]) for i in part]
            key = "group|" + hashlib.sha256("|".join(keys).encode()).hexdigest()[:20]
            specs.append(TaskSpec(key, task, ([jobs[i] for i in part],), cost=sum(costs[i] for i in part),
                                  label=f"{len(part)} searches"))
            members[key] = keys
    return specs, members


def store_groups(store: "ResultStore", members: dict[str, list[str]]):
    """(store_get, on_result) for grouped tasks: a group is done when all its rows are
    stored; a finished group's rows are added (those not stored yet)."""

    def get(key):
        if key not in members:
            return store.get(key)
        rows = [store.get(k) for k in members[key]]
        return rows if all(r is not None for r in rows) else None

    def on_result(spec, result):
        for r in result if isinstance(result, list) else [result]:
            if r.key not in store:
                store.add(r)

    return get, on_result


def _search_row(job, defn, th, study, engine, wall, reason) -> SearchRow:
    kind, a = job["kind"], job["a"]
    base = dict(key=search_key(defn, a, job["search"], kind, job["value"], job["sensitivity"]), study=study, kind=kind,
                branch="prolate" if a > 1 else "oblate", a=a, mu=defn.mu, d=defn.amplitude if kind == "threshold" else None,
                value=job["value"], levels=int(job["search"].get("levels", 1)), engine=engine, rtol=defn.rtol, t_max=defn.t_max,
                eps=defn.eps or None, wall_s=wall, reason=reason)
    if th is None:
        return SearchRow(**base, threshold=None, bracket_lo=None, bracket_hi=None, status=Status.FAILED.value, n_sims=0,
                         n_rounds=0, transitions="[]", stuck_near=False, sens_half=None, sens_double=None, sens_slope=None,
                         sens_shift=None, sens_dominant="")
    sens = th.sensitivity
    return SearchRow(**base, threshold=th.value, bracket_lo=th.bracket[0], bracket_hi=th.bracket[1], status=th.status.value,
                     n_sims=th.n_sims + (0 if sens is None else sens.n_sims), n_rounds=th.n_rounds,
                     transitions=json.dumps([list(t) for t in th.transitions]),
                     stuck_near=th.stuck_near if kind == "threshold" else False,
                     sens_half=None if sens is None else sens.values[0], sens_double=None if sens is None else sens.values[2],
                     sens_slope=None if sens is None else sens.slope, sens_shift=None if sens is None else sens.shift,
                     sens_dominant="" if sens is None or sens.dominant is None else sens.dominant)


@dataclass(frozen=True)
class OutcomeRow:
    """One sampled start of an outcome map: its class ("jump", "rise", "stuck", "slow",
    "failed"), when it ended (``t_end``; ``t_jump`` for a jump) and where (``theta_end``,
    ``rise_fraction``: the share of the rise done when it ended)."""

    key: str
    study: str
    branch: str
    a: float
    mu: float
    d: float
    value: float
    outcome: str
    t_jump: float | None
    t_end: float
    theta_end: float | None
    rise_fraction: float | None
    stuck: bool
    status: str
    wall_s: float
    reason: str


def outcome_key(defn, a: float, value: float) -> str:
    return f"outcome|{defn.key()}|a={a:.10g}|value={value:.10g}"


def outcome_task(prev, defn_fields: dict, points: list, *, study: str = "", engine: str = "batch") -> list[OutcomeRow]:
    """Classify a list of starts (a, d, value) of one definition (d replaces its amplitude),
    all at once on the batch integrator."""
    from dataclasses import replace

    from .threshold import Definition, evaluate_outcomes

    defn = Definition(**defn_fields)
    jobs = [(replace(defn, amplitude=d), a, v) for a, d, v in points]
    outs = evaluate_outcomes(jobs, engine=engine)
    rows = []
    for (d_defn, a, v), o in zip(jobs, outs):
        rows.append(OutcomeRow(key=outcome_key(d_defn, a, v), study=study, branch="prolate" if a > 1 else "oblate", a=a,
                               mu=d_defn.mu, d=d_defn.amplitude, value=v, outcome=o.kind,
                               t_jump=o.t if o.jumped else None, t_end=o.t, theta_end=o.theta, rise_fraction=o.rise_fraction,
                               stuck=o.stuck, status=o.status.value, wall_s=o.wall_s, reason=o.reason or ""))
    return rows
