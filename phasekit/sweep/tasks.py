"""The task runner of sweeps: :class:`TaskSpec` s whose ``after`` names the task whose result
they continue from, run by :func:`run_tasks` on a Dask client or serially, with a tqdm progress
bar; :func:`run_pending` as a study runs it (nothing started when everything is stored);
:func:`each` and :func:`chunked` build the tasks of a sweep.

Every finished result goes to ``on_result`` at once, so that a killed sweep resumes where it
stopped: the stores are in :mod:`phasekit.sweep.stores`, the Dask client and the compiled models
shipped once to each worker in :mod:`phasekit.sweep.cluster`. The rows of the threshold and map
studies are in :mod:`phasekit.studies.threshold_rows` and :mod:`phasekit.studies.outcome_maps`; the
scaffold of a study script in :mod:`phasekit.scaffold`; all of it is public as :mod:`phasekit.sweep`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial

from .._runtime.watch import check_max_wall, progress_bar, wall_deadline
from .cluster import ModelPack, call_task, make_client, shipped_pack


@dataclass
class TaskSpec:
    """One task: ``func(previous_result, *args)``.

    Parameters
    ----------
    key : str
        Identifies the task and its stored result.
    func : callable
        Called as ``func(previous_result, *args)``; returns the task's result.
    args : tuple, optional
        The further arguments of ``func``.
    after : str or None, optional
        The key of the task it continues (None: independent).
    label : str, optional
        A label for the caller; the runner does not use it.
    meta : dict, optional
        Data for the caller; the runner does not use it.
    cost : float, optional
        A relative estimate of its run time: Dask starts the costliest tasks first
        (longest-processing-time order), which keeps the workers busy to the end.

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


def run_tasks(specs: list[TaskSpec], *, store_get: Callable[[str], object | None], on_result: Callable[[TaskSpec, object], None],
              client=None, pack: ModelPack | None = None, progress: bool | None = True, desc: str = "tasks",
              max_wall: float | None = None) -> dict[str, object]:
    """Run every task not already stored; results go to ``on_result`` as they finish.

    Parameters
    ----------
    specs : list of TaskSpec
        The tasks; a task comes after the one it continues.
    store_get : callable
        ``store_get(key)`` returns a stored result or None (a stored task is skipped, and its result
        still feeds the tasks that continue from it).
    on_result : callable
        ``on_result(spec, result)``, called as each task finishes.
    client : dask.distributed.Client, optional
        Runs the tasks on Dask; None: in this process.
    pack : ModelPack, optional
        Compiled models shipped once to each worker.
    progress : bool or None, optional
        A tqdm bar (None: on a terminal or in a notebook only).
    desc : str, optional
        The bar's label.
    max_wall : float, optional
        Seconds; bounds the call: tasks not finished by then are left undone (cancelled on Dask; in
        this process the run under way ends "failed" with a reason naming the budget), and what finished
        is returned (and was passed to ``on_result``, so that a rerun resumes from it).

    Returns
    -------
    dict
        Key -> result of every task stored or finished.

    Raises
    ------
    ParameterError
        If ``max_wall`` is not a positive number.

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
        r = call_task(s.func, pack, prev, *s.args)
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
        f = client.submit(call_task, shipped_pack(s.func), pack_f, prev, *s.args, key=f"task-{abs(hash(s.key))}", pure=False,
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
    """How :func:`run_pending` ran.

    Attributes
    ----------
    computed : int
        Tasks computed in this call.
    total : int
        Tasks in all, stored ones included.
    mode : str
        How they ran, in words ("serial", "all stored", or the Dask cluster).
    left : int
        Tasks left undone when the wall budget ran out.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.sweep import tasks
    >>> str(tasks.PendingRun(3, 5, 'serial'))
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
    :class:`ModelPack`, and the tasks run on Dask or in this process.

    Parameters
    ----------
    specs : list of TaskSpec
        The tasks.
    store_get, on_result
        As for :func:`run_tasks`.
    warm_up : callable
        ``warm_up()`` compiles (or loads) every model the tasks use.
    serial : bool, optional
        True: run in this process.
    scheduler : str, optional
        Address of a Dask scheduler (:func:`make_client`).
    workers : int, optional
        Workers of a LocalCluster when no ``scheduler`` is given.
    progress, desc
        As for :func:`run_tasks`.
    max_wall : float, optional
        As for :func:`run_tasks` (the cluster's start-up counts).

    Returns
    -------
    PendingRun
        How many tasks were computed, and how.

    Raises
    ------
    ParameterError
        For an invalid ``scheduler``, ``workers`` or ``max_wall``.

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


def _apply(fn, prev, *args):
    return fn(*args)


def each(items, key: Callable, fn: Callable, *, cost: float = 1.0) -> list[TaskSpec]:
    """One independent task per item (a tuple of arguments): ``fn(*item)`` gives the row keyed
    ``key(*item)``.

    Parameters
    ----------
    items : iterable of tuple
        The arguments of each task.
    key : callable
        ``key(*item)`` gives the task's key.
    fn : callable
        ``fn(*item)`` gives the task's result.
    cost : float, optional
        The relative cost of every task (:class:`TaskSpec`).

    Returns
    -------
    list of TaskSpec
        One independent task per item.

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
    ``key(*item)``.

    Parameters
    ----------
    items : sequence of tuple
        The items.
    key : callable
        ``key(*item)`` gives the key of an item's row.
    fn : callable
        ``fn(prev, chunk, *args)`` returns the rows of a chunk.
    size : int
        Items per task.
    args : tuple, optional
        Further arguments of ``fn``.
    prefix : str, optional
        Start of each task's key.
    cost : float, optional
        The cost of every task; by default the chunk's length.

    Returns
    -------
    tuple of (list of TaskSpec, dict)
        The tasks, and their row keys: task key -> list of row keys (``members`` of :func:`stored_rows`
        and :meth:`phasekit.scaffold.Study.run`).

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
