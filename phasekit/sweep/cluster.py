"""Sweeps on Dask: the client (:func:`make_client`: a running scheduler or a LocalCluster), the
compiled models shipped to each worker once, and task functions shipped so that workers can run them.

* :class:`ModelPack` snapshots this process's compiled CasADi models and integrators (after a
  warm-up) as one pickle. It is scattered to every worker once and installed into the worker's
  caches before its first task: no worker compiles anything.
* A task runs on a worker as ``call_task(func, pack, prev, *args)``; a function from a module in
  cloudpickle's by-value registry travels pickled by value (``shipped_pack``), since the worker
  could not import it by name.
* :func:`client_evaluator` runs the simulations of threshold searches on a client.
"""

from __future__ import annotations

import os
import pickle
from collections.abc import Callable

from .._runtime.pool import main_not_reimported
from ..core import fields
from ..core.engines import cache as integrator_cache
from ..errors import ParameterError
from ..thresholds.definition import evaluate_outcomes

_INSTALLED: set[int] = set()


class ModelPack:
    """Compiled models and integrators of one process, ready to ship to workers.

    Parameters
    ----------
    blob : bytes
        The pickled snapshot of the caches (as :meth:`build` makes it).
    token : int
        Identifies the snapshot: a process installs a token once.

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
        then snapshot the caches.

        Parameters
        ----------
        warm : callable, optional
            ``warm()``; None: snapshot the caches as they are.

        Returns
        -------
        ModelPack
            The snapshot, with a token from its hash.
        """
        if warm is not None:
            warm()
        blob = pickle.dumps((fields.snapshot(), integrator_cache.snapshot()))
        return cls(blob, hash(blob))

    def install(self) -> None:
        """Put the snapshot into this process's caches (once per process)."""
        if self.token in _INSTALLED:
            return
        compiled_models, integrators = pickle.loads(self.blob)
        fields.install(compiled_models)
        integrator_cache.install(integrators)
        _INSTALLED.add(self.token)

    @property
    def size_mb(self) -> float:
        return len(self.blob) / 1e6


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


def shipped_pack(func):
    import cloudpickle

    by_value = getattr(func, "__module__", None) in cloudpickle.list_registry_pickle_by_value()
    return _ByValue(func) if by_value else func


def call_task(func, pack, prev, *args):
    if isinstance(func, _ByValue):
        func = func.load()
    if pack is not None:
        pack.install()
    return func(prev, *args)


def make_client(scheduler: str | None = None, workers: int | None = None, *, timeout: float = 5.0):
    """A Dask client: to a running scheduler, or a LocalCluster with one single-threaded
    worker process per core. Returns (client, cluster or None).

    Parameters
    ----------
    scheduler : str, optional
        Address of a running Dask scheduler (None: a LocalCluster); one that is malformed, or where no Dask
        scheduler answers within ``timeout`` seconds, raises :class:`ParameterError` at once.
    workers : int, optional
        Worker processes of the LocalCluster; a count below 1 raises :class:`ParameterError`.
    timeout : float, optional

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.sweep.make_client('tcp://127.0.0.1:1', timeout=0.5)  # doctest: +IGNORE_EXCEPTION_DETAIL
    Traceback (most recent call last):
        ...
    phasekit.errors.ParameterError: `scheduler` must be the address of a running Dask scheduler, like tcp://127.0.0.1:8786, but no scheduler answered there within 0.5 s, got 'tcp://127.0.0.1:1'.
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
        # no dashboard, the scheduler's HTTP server on a free port; Dask's log lines off (cancelled tasks,
        # a heartbeat racing a Ctrl-C's shutdown): a task's failure reaches the client as its exception
        with main_not_reimported():  # spawn would re-import the calling script (see phasekit._runtime.pool)
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                   scheduler_kwargs={"dashboard_address": ":0"}, silence_logs=logging.CRITICAL)
    finally:
        if main_thread and previous is not None:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


def _evaluate_part(pack, jobs, engine):
    if pack is not None:
        pack.install()
    return evaluate_outcomes(jobs, engine=engine)


def client_evaluator(client, *, engine: str = "batch", pack: ModelPack | None = None, parts: int | None = None):
    """``evaluate(jobs)`` for :func:`phasekit.find_threshold` and
    :func:`phasekit.thresholds.run_searches` on a Dask client: each round's simulations are
    split into one part per worker (interleaved, so the parts cost about the same) and run
    there on ``engine``. With k-section (``levels`` > 1) a single search then uses every
    worker: parallel bracketing when the workers have nothing else to do.

    Parameters
    ----------
    client : dask.distributed.Client
        The client the simulations run on.
    engine : {"batch", "scalar"}, optional
        How each part's simulations are made (:func:`phasekit.thresholds.evaluate_outcomes`).
    pack : ModelPack, optional
        Compiled models, scattered once to every worker.
    parts : int, optional
        Parts per round; by default one per worker.

    Returns
    -------
    callable
        ``evaluate(jobs) -> list of Outcome``, jobs (definition, body, value), outcomes in order.

    Examples
    --------
    >>> import phasekit as pk
    >>> import inspect
    >>> from phasekit.sweep import cluster
    >>> list(inspect.signature(cluster.client_evaluator).parameters)
    ['client', 'engine', 'pack', 'parts']
    """
    n = parts or max(1, len(client.scheduler_info()["workers"]))
    pack_f = client.scatter(pack, broadcast=True, hash=False) if pack is not None else None  # see _run_on in tasks.py

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
