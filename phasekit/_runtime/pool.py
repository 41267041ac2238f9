"""Local worker processes that cannot hang: loky's reusable executor.

Chosen on evidence (2-core machine, warm heyoka cache; issue 24):

* ``concurrent.futures.ProcessPoolExecutor`` with "spawn" (phasekit's pool before) re-imports
  the calling script in every worker. A script without ``if __name__ == "__main__":`` then
  starts workers recursively and they die; a script read from standard input
  (``python - < run.py``) cannot be re-imported at all (FileNotFoundError '<stdin>'); in both
  the parent waited forever (measured: killed after 40 s and 60 s with nothing done).
* A Dask LocalCluster (``processes=True``) re-imports ``__main__`` the same way and fails in
  both cases ("Nanny failed to start"); it starts in ~1 s.
* loky starts fresh interpreters (fork + exec: heyoka's thread pool is never inherited
  half-initialised, as a plain fork would), does not re-import ``__main__`` (functions
  defined there travel by value, cloudpickle), works from a script with or without a main
  guard, from standard input, from ``python -c`` and in a Jupyter kernel, reuses its workers
  across calls, and notices a dead worker at once (TerminatedWorkerError, ~0.1 s after a
  SIGKILL). Two workers start in 0.12 s; the first task in each imports phasekit (~0.4 s).

:func:`run_local` runs one function over many arguments on these workers and yields the
results as they come; a worker that dies raises :class:`phasekit.WorkerError` naming how it
died and which tasks had not finished. The job (model, options, ...) that every task needs is
written once to a temporary file that each worker reads once (:func:`shipped`), not pickled
into every task (a model is ~0.6 MB).
"""

from __future__ import annotations

import contextlib
import os
import pickle
import shutil
import tempfile
import time
import uuid

from ..errors import WorkerError

#: seconds an idle worker waits for more work before it exits (a second call within this time,
#: e.g. the next cell of a notebook, starts nothing)
IDLE_S = 120

_JOBS: dict = {}  # worker side: the job of the current token (one at a time)


@contextlib.contextmanager
def shipped(job):
    """Write ``job`` to a temporary file once; yields (token, path) for :func:`job_of`."""
    folder = tempfile.mkdtemp(prefix="phasekit-job-")
    try:
        path = os.path.join(folder, "job.pkl")
        with open(path, "wb") as f:
            pickle.dump(job, f, protocol=pickle.HIGHEST_PROTOCOL)
        yield uuid.uuid4().hex, path
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def job_of(token: str, path: str):
    """In a worker: the job shipped as (token, path), read from the file the first time."""
    job = _JOBS.get(token)
    if job is None:
        with open(path, "rb") as f:
            job = pickle.load(f)
        _JOBS.clear()
        _JOBS[token] = job
    return job


@contextlib.contextmanager
def main_not_reimported():
    """While processes are started with multiprocessing's "spawn" (a Dask LocalCluster), hide
    where ``__main__`` came from, so that the children do not re-import it: a script without a
    main guard would start workers recursively, and one read from standard input cannot be
    re-imported at all ('<stdin>'). What the tasks need of ``__main__`` travels by value."""
    import sys

    main = sys.modules.get("__main__")
    saved = {k: getattr(main, k) for k in ("__file__", "__spec__") if main is not None and hasattr(main, k)}
    try:
        if main is not None:
            main.__spec__ = None
            if hasattr(main, "__file__"):
                del main.__file__
        yield
    finally:
        for k, v in saved.items():
            setattr(main, k, v)


def _executor(n: int):
    from loky import get_reusable_executor

    return get_reusable_executor(max_workers=n, timeout=IDLE_S)


def _died(exc: BaseException) -> str:
    """How the workers died, in one line (loky lists their exit codes, e.g. {SIGKILL(-9)})."""
    text = " ".join(str(exc).split())
    codes = text.split("exit codes of the workers are", 1)
    return f"exit codes {codes[1].split()[0]}" if len(codes) == 2 else (text[:160] or type(exc).__name__)


def run_local(func, tasks: list[tuple], n: int, *, deadline: float | None = None, what: str = "task"):
    """Yield ``(k, func(*tasks[k]))`` as the ``n`` workers finish them.

    A worker that dies raises :class:`WorkerError` (no retry: a start that crashes its worker
    would crash the next one too), naming how it died and the tasks left; Ctrl-C or the
    ``deadline`` (a ``time.perf_counter()`` value) kill the workers, and the deadline raises
    TimeoutError whose argument lists the tasks left (so does ``WorkerError.result``).
    Results already yielded are the caller's to keep.
    """
    from concurrent.futures import FIRST_COMPLETED, wait

    from loky.process_executor import BrokenProcessPool

    ex = _executor(n)
    futures = {ex.submit(func, *args): k for k, args in enumerate(tasks)}
    pending, finished = set(futures), set()
    clean = False
    try:
        while pending:
            timeout = None if deadline is None else max(0.0, deadline - time.perf_counter())
            done, pending = wait(pending, timeout=timeout, return_when=FIRST_COMPLETED)
            if not done:
                raise TimeoutError(sorted(futures[f] for f in pending))
            for f in done:
                try:
                    result = f.result()
                except BrokenProcessPool as exc:
                    left = sorted(set(futures.values()) - finished)
                    raise WorkerError(f"a worker process died ({_died(exc)}) with {len(left)} {what}(s) unfinished: "
                                      f"{_listed(left)}", left) from None
                finished.add(futures[f])
                yield futures[f], result
        clean = True
    finally:
        if not clean:  # Ctrl-C, a deadline, a dead worker, or the caller stopped: no worker runs on
            for f in pending:
                f.cancel()
            ex.shutdown(wait=False, kill_workers=True)


def _listed(ks: list[int]) -> str:
    shown = ", ".join(map(str, ks[:12]))
    return f"{shown}, ..." if len(ks) > 12 else shown
