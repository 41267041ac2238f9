"""Ensembles: one model, many starts, one table; and rerunning any result from its inputs.

:func:`ensemble` runs :func:`phasekit.simulate` from every start and returns a pandas
DataFrame with one row per start (the start in the paper's variables, the status, t_jump,
R_min, the reason for a failure, ...). Each row is exactly what a single ``pk.simulate``
call with the same arguments gives: the runs are independent and deterministic.

Where the runs go
-----------------
* Local processes by default: loky's reusable executor (:mod:`phasekit._runtime.pool`, where the
  measurements behind the choice are). It works from a script with or without a main guard,
  from standard input, ``python -c`` and a Jupyter kernel; a worker that dies ends the call at
  once with :class:`phasekit.WorkerError` (the finished rows in its ``result``). Workers read
  the model once and load the compiled integrators from the on-disk cache (~/.cache/phasekit),
  warmed by one run in this process first, so no worker compiles anything.
* Dask when ``scheduler`` is given: an address ("tcp://host:8786"), a
  ``dask.distributed.Client``, or a cluster object (anything with ``scheduler_address``).
* ``processes=1`` (or a single start) runs in this process.

A tqdm progress bar is written to stderr where a person watches (a terminal or a notebook;
``progress=True`` forces it, False turns it off). ``max_wall`` bounds each run (as in
:func:`phasekit.simulate`), ``max_wall_total`` the whole call.
"""

from __future__ import annotations

import inspect
import os
import time
import warnings
from dataclasses import fields, replace

import numpy as np

from .._runtime.pool import job_of, run_local, shipped
from .._runtime.validate import check_finite, check_int, check_vector
from .._runtime.watch import WALL_REASON, check_max_wall, progress_bar, wall_deadline
from ..core.charts import FLIGHT, PAPER_NAMES
from ..core.hybrid import Event
from ..core.model import Model
from ..core.options import SolverOptions
from ..core.simulate import simulate, solver_options
from ..errors import ParameterError, Status, WorkerError
from .cluster import make_client

#: columns of an ensemble row after the start (i, U, V, Omega, Lambda, theta, n)
ROW_COLUMNS = ("status", "reason", "t_jump", "R_min", "t_end", "theta_end", "mode_end", "n_events", "stuck", "n_steps",
               "n_liftoffs", "n_flights", "t_flight", "longest_flight", "gap_max", "wall_s")
#: keywords of :func:`phasekit.simulate` an ensemble passes on (``t_eval`` and ``throw`` are not
#: per-row quantities: an ensemble tabulates failures)
PASSED = ("t0", "stop_at", "restitution", "mode", "options")


def summary_row(traj, events=()) -> dict:
    """The row of one trajectory: its start (paper variables), how it ended, and the first
    time of each user event (column ``t_<event name>``, None if it never fired)."""
    start = traj.to_dict(events=False)["start"]
    row = {name: start[name] for name in PAPER_NAMES}
    hops = traj.hops
    row.update(status=traj.status.value, reason=traj.reason, t_jump=traj.t_jump, R_min=traj.R_min, t_end=traj.t,
               theta_end=float(traj.euler_end[4]), mode_end=traj.mode, n_events=len(traj.events), stuck=traj.stuck,
               n_steps=int(traj.n_steps), **{k: hops[k] for k in ("n_liftoffs", "n_flights", "t_flight",
                                                                 "longest_flight", "gap_max")},
               wall_s=float(traj.wall_s))
    for ev in events:
        hit = next((e.t for e in traj.events if e.name == ev.name), None)
        row[f"t_{ev.name}"] = hit
    return row


# -- worker side -----------------------------------------------------------------------------


def _run_shipped(token: str, path: str, i: int, x0) -> tuple[int, dict]:
    return _run_one(i, x0, job_of(token, path))


def _run_one(i: int, x0, job: dict) -> tuple[int, dict]:
    try:
        with warnings.catch_warnings():  # said once, by the check in the calling process
            warnings.simplefilter("ignore")
            traj = simulate(job["model"], x0, job["t_end"], events=job["events"], progress=False, **job["kwargs"])
        return i, summary_row(traj, job["events"])
    except Exception as exc:  # a worker never loses a row: it reports the failure
        return i, {"status": Status.FAILED.value, "reason": f"{type(exc).__name__}: {exc}"}


# -- the parent ------------------------------------------------------------------------------


def _starts(model: Model, starts) -> np.ndarray:
    """Starts as an (m, n_states) array in ``model.chart``; a DataFrame is read from its
    paper-variable columns."""
    if hasattr(starts, "columns"):
        missing = [c for c in PAPER_NAMES if c not in starts.columns]
        if missing:
            raise ParameterError("starts", f"as a table needs the columns {', '.join(PAPER_NAMES)} (missing "
                                           f"{', '.join(missing)})", show_value=False)
        return np.array([model.chart.from_paper(check_vector("starts", r, 6))
                         for r in starts[list(PAPER_NAMES)].to_numpy(dtype=float)]).reshape(-1, model.n_states)
    if np.ndim(starts) == 1 and all(np.ndim(x) == 0 for x in starts):
        raise ParameterError("starts", f"must be a list of starts, each a state of {model.n_states} numbers (for one "
                                       "start x0, pass [x0])", show_value=False)
    try:
        rows = [check_vector("starts", x, model.n_states) for x in starts]
    except TypeError:
        raise ParameterError("starts", f"must be a sequence of states of {model.n_states} numbers", starts) from None
    if not rows:
        raise ParameterError("starts", "must hold at least one start", show_value=False)
    return np.array(rows)


#: steps of the run that checks an ensemble's arguments in this process before any worker starts
CHECK_STEPS = 2000
CONNECT_TIMEOUT = 10  # seconds to reach a scheduler before the address is called bad


def _client(scheduler):
    """(client, owned): a Dask client for an address, a Client or a cluster."""
    from dask.distributed import Client

    if isinstance(scheduler, str):  # checked there: a bad or silent address is a ParameterError naming it
        return make_client(scheduler, timeout=CONNECT_TIMEOUT)[0], True
    if isinstance(scheduler, Client):
        return scheduler, False
    if hasattr(scheduler, "scheduler_address"):
        return Client(scheduler), True
    raise ParameterError("scheduler", "must be a Dask scheduler address, a dask.distributed.Client or a cluster",
                         scheduler)


def ensemble(model: Model, starts, t_end: float, *, events=(), scheduler=None, processes: int | None = None,
             progress: bool | None = None, max_wall_total: float | None = None, **simulate_kwargs):
    """Simulate ``model`` from every start; one row per start.

    Parameters
    ----------
    model : Model
    starts : sequence of arrays, or DataFrame
        States in ``model.chart`` (as :func:`phasekit.simulate` takes them), or a table with
        the paper's columns U, V, Omega, Lambda, theta, n.
    t_end : float
        End time of every run.
    events : sequence of Event
        User events of every run; the first time each fired is the column ``t_<name>``.
    scheduler : str, dask Client or cluster, optional
        Run on Dask instead of local processes.
    processes : int, optional
        Local worker processes (default: the number of cores, at most the number of starts);
        1 runs in this process.
    progress : bool or None
        A progress bar on stderr; None (default): only on a terminal or in a notebook.
    max_wall_total : float, optional
        Wall budget of the whole call in seconds: rows not finished by then (their workers
        are stopped) are "failed" with a reason naming it. ``max_wall`` bounds each run.
    **simulate_kwargs
        ``t0``, ``stop_at``, ``restitution``, ``mode``, ``options`` and any field of
        :class:`phasekit.SolverOptions` (``rtol=...``, ``max_steps=...``). ``dense``
        defaults to False here (no dense output is needed for the table).

    Returns
    -------
    pandas.DataFrame
        Columns ``i`` (position in ``starts``), U, V, Omega, Lambda, theta, n (the start),
        then :data:`ROW_COLUMNS` and ``t_<event>`` per user event. ``df.attrs["inputs"]``
        holds the model, the starts in the model's chart, t_end, the events and the solver
        options, so that :func:`rerun` can repeat any row.

    Raises
    ------
    WorkerError
        A worker process died (killed, out of memory): at once, naming how and the rows left;
        its ``result`` is the table with those rows "failed".

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> model = pk.Model(body, pk.Coulomb(0.1))
    >>> starts = [pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=w) for w in (10.5, 12.0)]
    >>> df = pk.ensemble(model, starts, 200.0, processes=1, progress=False)
    >>> list(df["status"])
    ['jumped', 'jumped']
    """
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model such as Model(Spheroid(1.5), Coulomb(0.1))", model)
    X = _starts(model, starts)
    t_end = check_finite("t_end", t_end)
    events = _events(events)
    if processes is not None:
        processes = check_int("processes", processes, minimum=1)
    max_wall_total = check_max_wall(max_wall_total, "max_wall_total")
    job = {"model": model, "t_end": t_end, "events": events, "kwargs": _kwargs(simulate_kwargs)}
    _check_run(job, X[0])
    t0 = time.perf_counter()
    rows: dict = {}
    with progress_bar(len(X), desc="ensemble", progress=progress) as bar, wall_deadline(max_wall_total) as end:
        try:
            _run_rows(job, X, rows, bar, end, scheduler, min(processes or os.cpu_count() or 1, len(X)))
        except TimeoutError:
            why = f"not finished: {WALL_REASON} (max_wall_total = {max_wall_total:g} s) ran out"
            for i in range(len(X)):
                rows.setdefault(i, {"status": Status.FAILED.value, "reason": why})
        except WorkerError as exc:
            for i in exc.result:
                rows.setdefault(i, {"status": Status.FAILED.value, "reason": f"not finished: {exc}"})
            raise WorkerError(f"ensemble: {exc} (the finished rows are in this error's .result; rerun the others, "
                              "or pass processes=1)", _table(model, X, rows, job, time.perf_counter() - t0)) from None
    return _table(model, X, rows, job, time.perf_counter() - t0)


def _events(events) -> tuple:
    events = tuple(events)
    for ev in events:
        if not isinstance(ev, Event):
            raise ParameterError("events", "must be phasekit Event objects, e.g. pk.Event('theta', 0.4)", ev)
    if len({ev.name for ev in events}) != len(events):
        raise ParameterError("events", "must have distinct names (each names a column t_<name>)", show_value=False)
    return events


def _check_run(job: dict, x0) -> None:
    """The arguments are checked here, once (a worker would report them as a failed row each),
    and the integrators of the first mode compiled (workers then load them from the disk
    cache): a short run of the first start."""
    kwargs = job["kwargs"]
    try:
        simulate(job["model"], x0, job["t_end"], events=job["events"], progress=False,
                 **{**kwargs, "options": replace(kwargs["options"], max_steps=CHECK_STEPS)})
    except ParameterError as exc:
        if exc.param == "x0":
            raise ParameterError("starts", f"row 0 {exc.expected}", x0) from None
        raise


def _run_rows(job: dict, X: np.ndarray, rows: dict, bar, end: float, scheduler, n_proc: int) -> None:
    """Fill ``rows`` on Dask, in this process or on local workers; TimeoutError at ``end``."""
    if scheduler is not None:
        _on_dask(scheduler, job, X, bar, rows)
    elif n_proc <= 1:
        for i, x in enumerate(X):
            if time.perf_counter() > end:
                raise TimeoutError
            rows[i] = _run_one(i, x, job)[1]
            bar.update()
    else:
        _on_processes(n_proc, job, X, bar, rows, end)


def _kwargs(given: dict) -> dict:
    kw = {k: given.pop(k) for k in list(given) if k in PASSED}
    for key in ("t_eval", "throw", "events"):
        if key in given:
            raise ParameterError(key, "is not an ensemble option (an ensemble tabulates one row per start)",
                                 show_value=False)
    given.setdefault("dense", False)
    opts = solver_options(kw.pop("options", None), **given)  # unknown names are an error here
    return {**kw, "options": opts}


def _on_processes(n: int, job: dict, X: np.ndarray, bar, rows: dict, end: float) -> None:
    """Rows into ``rows`` as the local workers finish them (:mod:`phasekit._runtime.pool`)."""
    with shipped(job) as (token, path):
        tasks = [(token, path, i, x) for i, x in enumerate(X)]
        for _, (i, row) in run_local(_run_shipped, tasks, n, deadline=None if end == float("inf") else end,
                                     what="start"):
            rows[i] = row
            bar.update()


def _on_dask(scheduler, job: dict, X: np.ndarray, bar, rows: dict) -> None:
    from dask.distributed import as_completed

    client, owned = _client(scheduler)
    try:
        job_f = client.scatter(job, broadcast=True)
        futures = [client.submit(_run_one, i, x, job_f, pure=False) for i, x in enumerate(X)]
        for f in as_completed(futures):
            i, row = f.result()
            rows[i] = row
            bar.update()
    finally:
        if owned:
            client.close()


def _table(model: Model, X: np.ndarray, rows: dict, job: dict, wall: float):
    import pandas as pd

    ev_cols = [f"t_{ev.name}" for ev in job["events"]]
    cols = ["i", *PAPER_NAMES, *ROW_COLUMNS, *ev_cols]
    out = []
    for i, x in enumerate(X):
        row = {"i": i, **dict(zip(PAPER_NAMES, map(float, model.chart.to_paper(x))))}
        row.update(rows[i])
        out.append(row)
    df = pd.DataFrame(out).reindex(columns=cols)
    opts = job["kwargs"]["options"]
    df.attrs["inputs"] = {
        "model": model.to_dict(), "starts_chart": X.tolist(), "t_end": job["t_end"],
        "events": [ev.to_dict() for ev in job["events"]], "options": opts.to_dict(),
        **{k: v for k, v in job["kwargs"].items() if k != "options"},
    }
    df.attrs["wall_s"] = wall
    return df


# -- rerun -------------------------------------------------------------------------------------


def _model_from(d: dict, model: Model | None) -> Model:
    if model is None:
        return Model.from_dict(d)
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model", model)
    return model


def _events_from(items) -> list[Event]:
    return [Event(e["on"], e["level"], direction=e["direction"], terminal=e["terminal"], name=e["name"]) for e in items]


def rerun(source, index: int | None = None, *, model: Model | None = None, **overrides):
    """Repeat a run from the inputs a result carries.

    Parameters
    ----------
    source : dict, DataFrame or Series
        A :meth:`Trajectory.to_dict` (or the CLI's ``simulate --json`` output, parsed), a
        DataFrame returned by :func:`ensemble` together with ``index``, or one row of it
        (``df.iloc[k]``, ``df.loc[k]``, a row of a filtered table: it carries its ``i``).
    index : int, optional
        The row (``i``) of an ensemble table to repeat.
    model : Model, optional
        Needed for a user-defined body or friction law, which cannot be rebuilt from their
        description; built-in ones are rebuilt from ``source["model"]``.
    **overrides
        Keywords of :func:`phasekit.simulate` to change (e.g. ``dense=True`` for sampling,
        ``t_end=10.0`` for a shorter run); one it does not take raises :class:`ParameterError`
        naming it.

    Returns
    -------
    Trajectory
        With the same start, end time, stop rule, events and solver options, hence the same
        numbers (t_jump to the last digit).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> pk.rerun(traj.to_dict()).t_jump == traj.t_jump
    True
    """
    accepted = (set(inspect.signature(simulate).parameters) - {"model", "x0", "option_fields"}) \
        | {f.name for f in fields(SolverOptions)}
    for key in overrides:  # a wrong keyword is named, not a TypeError from deep inside
        if key not in accepted:
            raise ParameterError(key, f"is not a keyword of phasekit.simulate (one of: {', '.join(sorted(accepted))})",
                                 show_value=False)
    given = {k: overrides.pop(k) for k in ("t_end", "events") if k in overrides}
    try:
        m, x0, t_end, events, kw = _rerun_inputs(source, index, model, overrides)
    except (KeyError, TypeError, AttributeError, IndexError) as exc:  # a dict or table that is not a whole result
        raise ParameterError("source", f"is not a complete result: {type(exc).__name__} {exc}", show_value=False) from None
    return simulate(m, x0, given.get("t_end", t_end), events=given.get("events", events), **kw)


def _rerun_inputs(source, index, model, overrides):
    """(model, start, t_end, events, keywords) of :func:`rerun`."""
    row = hasattr(source, "attrs") and hasattr(source, "index") and not hasattr(source, "columns")
    if row and index is None:
        if "i" not in source.index:  # a row of an ensemble table names its start
            raise ParameterError("source", "is a Series without the column 'i' of an ensemble table", show_value=False)
        index = int(source["i"])
    if row or (hasattr(source, "attrs") and hasattr(source, "columns")):
        inputs = source.attrs.get("inputs")
        if inputs is None:
            raise ParameterError("source", "is a table without the inputs of an ensemble (df.attrs['inputs'])",
                                 show_value=False)
        if index is None:
            raise ParameterError("index", "is required to rerun a row of an ensemble table", show_value=False)
        index = check_int("index", index, minimum=0, maximum=len(inputs["starts_chart"]) - 1)
        m = _model_from(inputs["model"], model)
        kw = {k: inputs[k] for k in PASSED if k in inputs and k != "options"}
        kw.update(inputs["options"])
        kw.update(overrides)
        x0 = np.array(inputs["starts_chart"][index])
        return m, x0, inputs["t_end"], _events_from(inputs["events"]), kw
    if not isinstance(source, dict) or "start_chart_state" not in source:
        raise ParameterError("source", "must be a Trajectory.to_dict() (or simulate --json output) or an ensemble "
                                       "table", show_value=False)
    m = _model_from(source["model"], model)
    kw = dict(t0=source["t0"], stop_at=source["stop_at"], restitution=source["restitution"], **source["options"])
    if source.get("pose0") is not None:
        kw["pose0"] = source["pose0"]
    if len(source["start_chart_state"]) == FLIGHT.n_states != m.n_states:
        kw["mode"] = "flight"
    if source.get("start_mode") == "face":  # started lying on its face (vertical_spin_start with mode="face")
        kw["mode"] = "face"
    kw.update(overrides)
    return m, np.array(source["start_chart_state"]), source["t_end_requested"], \
        _events_from(source.get("user_events") or []), kw
