"""A :class:`~phasekit.core.trajectory.Trajectory` in other forms: the tables of its sampled
observables and pose (:func:`sample_table`, :func:`pose_table`, built on :func:`observable_table`;
each column's unit and long name in ``attrs``) and of its events, the JSON form in the paper's
variables with the run's inputs (:func:`trajectory_dict`, which :func:`phasekit.rerun` reads back)
and the sampled table with those inputs (:func:`run_table`) as an xarray Dataset and as CSV,
Parquet and NetCDF files (written by :mod:`phasekit.io.tables`, read back by
:func:`phasekit.read_table`: ``pk.rerun(pk.read_table(path).attrs["run"])`` repeats the run). The
Trajectory's methods (``sample``, ``pose``, ``events_table``, ``to_dict``, ``to_xarray``,
``to_netcdf``, ``to_parquet``, and its records' ``to_dict``) delegate here; each function takes
the trajectory (or the record) first.
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_int
from ..errors import ParameterError, Status
from .charts import FLIGHT, PAPER_NAMES
from .energy import has_budget
from .observables import evaluate_function
from .pose import POSE_COLUMNS
from .units import COLUMN_KINDS, Scale

#: the observables of a state (columns of :func:`observable_table`)
STATE_COLUMNS = (*PAPER_NAMES, "R", "energy", "jellett", "slip", "L_Z", "h", "gap")
#: phasekit's unit of each kind of quantity (mass M, length b, gravity g; units.KINDS)
KIND_UNITS = {"length": "b", "time": "sqrt(b/g)", "rate": "sqrt(g/b)", "speed": "sqrt(g b)", "force": "M g",
              "energy": "M g b", "angular_momentum": "M sqrt(g b^3)"}
#: the unit of each column of a sampled table (CF attribute ``units``): angles in radians, the
#: mode (text) none
UNITS = {"t": KIND_UNITS["time"], "mode": "", **{c: KIND_UNITS[k] for c, k in COLUMN_KINDS.items()},
         "theta": "rad", "psi": "rad", "phi": "rad"}
#: what each column of a sampled table is (CF attribute ``long_name``), in the paper's words
LONG_NAMES = {
    "t": "time", "mode": "contact mode in force (sliding, rolling or flight)",
    "U": "velocity of G along e_X, the horizontal projection of the axis",
    "V": "velocity of G along e_Y = e_Z x e_X", "Omega": "precession rate of the axis, dpsi/dt",
    "Lambda": "nutation rate, dtheta/dt", "theta": "inclination of the axis from the vertical",
    "n": "spin n = w.k about the axis", "R": "normal reaction of the table (0 in flight)",
    "energy": "total energy (kinetic + potential)", "jellett": "Jellett's integral -L.GP",
    "slip": "slip speed |u_P| of the contact point", "L_Z": "vertical angular momentum about G",
    "h": "height of G above the table (in flight h(theta), the gap excluded)",
    "gap": "height of the lowest point above the table (0 in contact)", "psi": "azimuth of the axis",
    "phi": "spin angle about the axis", "X": "position of G on the table, X", "Y": "position of G on the table, Y",
    "X_P": "contact point on the table (in flight: below the lowest point), X",
    "Y_P": "contact point on the table (in flight: below the lowest point), Y",
}
#: what a run that ends rolling without slip rests on (exact Coulomb friction's rolling mode does
#: no work: with no dissipation law nothing dissipates, so the energy stays and the body cannot settle;
#: its tilt may still oscillate as it rolls)
PURE_ROLLING = ("pure rolling: energy is conserved while the body rolls without slipping (no force does work), so "
                "it cannot rise or settle; a regularised or viscous friction law, spin friction or rolling "
                "resistance (CLI: --slip-eps EPS, --friction viscous, --spin-friction MU_S, --rolling-resistance "
                "DELTA) changes this")
#: what the "rolling" modes are, by law: zero slip held exactly (exact Coulomb), or a regularised law's
#: slip below 10 eps, followed on its slow manifold (it creeps) or by its own field
HOLDING = {"exact": "rolling without slip", "creep": "creeping (slip of order eps on the regularised law's slow manifold)",
           "slow": "slipping slowly (slip below 10 eps, the regularised law's own field)",
           "patch": "sticking (over a contact patch only where the slip and the spin about the normal both vanish)"}


#: the modes without slip: rolling, rolling with the spin held by spin friction, and pivoting (the
#: rolling held by rolling resistance: the body spins in place)
NO_SLIP = ("rolling", "rolling_no_pivot", "pivoting")


def _holding(law, pivoting: bool) -> str:
    """What the no-slip modes are called (:data:`HOLDING`), "rolling or pivoting" once it pivoted."""
    patch = any(d.needs_contact_point for d in law.dissipation)
    word = HOLDING["exact" if law.has_rolling_mode else "creep" if law.creeps else "patch" if patch else "slow"]
    return word.replace("rolling without slip", "rolling or pivoting without slip") if pivoting else word


def contact_summary(traj) -> dict:
    """How a run held the table: the time of its first stick, the fraction of the run spent in a
    no-slip mode (:data:`NO_SLIP`; for a regularised law that creeps, the creep) and
    what that is called (``holding``), theta at the start and its change (negative: the axis
    turned towards the upward vertical), the contact's passages between a compound body's pieces
    (``passages``: "ball -> stem at t = ...") and the piece it ends on (``piece_end``, None on a
    body of one piece), and ``rests_on`` (:data:`PURE_ROLLING`) when the
    run reached its end time rolling under exact Coulomb friction with no dissipation law (then no
    energy is lost while it rolls), else None."""
    span = traj.t - traj.t0
    rolling = sum(s.t1 - s.t0 for s in traj.segments if s.mode.value in NO_SLIP)
    pivoting = any(s.mode.value == "pivoting" and s.t1 > s.t0 for s in traj.segments)
    sticks = [e.t for e in traj.events if e.name == "stick"]
    theta0 = float(traj.model.chart.to_paper(traj.x0)[4])
    law = traj.model.friction
    pure = str(traj.mode).startswith("rolling") and law.has_rolling_mode and not law.dissipation \
        and str(traj.status) == "completed"
    moves = {p.name for p in traj.model.body.transfers}
    passages = [f"{e.detail} at t = {e.t:.6g}" for e in traj.events if e.name in moves and e.detail]
    theta_end = float(traj.model.chart.to_paper(traj.x)[4])
    # the piece under it at the end, from its tilt (a bounce train at a switch may end without a passage)
    ends = [tr.to_piece for tr in traj.model.body.transfers if (theta_end - tr.theta) * tr.direction > 0]
    return {"t_first_stick": float(sticks[0]) if sticks else None, "piece_end": ends[0] if ends else None,
            "rolling_fraction": float(rolling / span) if span > 0 else None, "holding": _holding(law, pivoting),
            "theta_start": theta0, "theta_change": theta_end - theta0,
            "passages": passages, "rests_on": PURE_ROLLING if pure else None}


def _within_budget(work, skipped: list, name: str):
    """``work()``, or None when the wall budget in force ran out in it (``skipped`` then gets
    (name, why)): the work after a run (its energy budget, its poses) counts in the CLI's
    --max-wall (:func:`phasekit._runtime.watch.wall_deadline`)."""
    try:
        return work()
    except TimeoutError as exc:
        skipped.append((name, f"{exc} after the run: its {name} not computed"))
        return None


def _dissipation_summary(traj, skipped: list) -> dict:
    """With dissipation laws, where the energy went and when the body came to rest:
    ``energy_budget`` (:meth:`~phasekit.core.trajectory.Trajectory.energy_budget`, units M g b;
    None only for a run made with dense=False (a run past ``max_dense_mb`` has one, from its tally); a run that ended at its start has one, with nothing lost) and ``t_rest`` (the "rest" event's time, or None); an empty dict
    for a model without them (its JSON is as before)."""
    face = getattr(traj, "face", None)
    if not traj.model.friction.dissipation and face is None:
        return {}
    dense = has_budget(traj)
    rest = [e.t for e in traj.events if e.name in ("rest", "at rest")]
    return {"t_rest": float(rest[-1]) if rest else None,
            "energy_budget": _within_budget(lambda: traj.energy_budget().to_dict(), skipped, "energy budget") if dense
            else None}


#: the scalars of a run's outcome and inputs that a run's table carries as attributes of their own
RUN_SCALARS = ("status", "reason", "t_jump", "n_flights", "stop_at", "restitution", "t_end")
#: its structured inputs, each an attribute (all of them, and more, are in the attribute "run")
RUN_INPUTS = ("model", "start", "options", "pose0")


def _describe(df):
    """``df`` with the unit and long name of each of its columns in ``attrs``."""
    df.attrs["units"] = {c: UNITS[c] for c in df.columns if c in UNITS}
    df.attrs["long_names"] = {c: LONG_NAMES[c] for c in df.columns if c in LONG_NAMES}
    return df


def observable_table(model, parts):
    """A :meth:`~phasekit.core.trajectory.Trajectory.sample`-style DataFrame from ``parts``.

    Parameters
    ----------
    model : Model
        The model the states belong to.
    parts : sequence of (Mode, array_like, array_like)
        (mode, times, states in that mode's chart) in time order.

    Returns
    -------
    pandas.DataFrame
        Columns ``t``, ``mode`` and :data:`STATE_COLUMNS`, one row per time.
    """
    import pandas as pd

    n = sum(len(ts) for _, ts, _ in parts)
    cols = {name: np.empty(n) for name in STATE_COLUMNS}
    t_all, modes = np.empty(n), np.empty(n, dtype=object)
    i = 0
    for mode, ts, X in parts:
        X = np.asarray(X, dtype=float).reshape(len(ts), -1)
        sel = slice(i, i + len(ts))
        t_all[sel], modes[sel] = ts, mode.value
        P = evaluate_function(model.function("paper", mode), model.p, X)
        for j, name in enumerate(PAPER_NAMES):
            cols[name][sel] = np.reshape(P, (len(ts), -1))[:, j]
        for name in ("R", "energy", "jellett", "L_Z", "h", "gap"):
            cols[name][sel] = evaluate_function(model.observable(name, mode), model.p, X)
        cols["slip"][sel] = evaluate_function(model.observable("slip_speed", mode), model.p, X)
        i += len(ts)
    return pd.DataFrame({"t": t_all, "mode": modes, **cols})


def sample_table(traj, ts):
    """The rows of :meth:`~phasekit.core.trajectory.Trajectory.sample` at the checked times ``ts``:
    the observables of each segment's states, then the pose.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    ts : numpy.ndarray
        Times inside the run, already checked.

    Returns
    -------
    pandas.DataFrame
        Columns ``t``, ``mode``, :data:`STATE_COLUMNS` and the pose columns; ``attrs["units"]``
        and ``attrs["long_names"]`` give each column's unit (:data:`UNITS`, phasekit's) and
        what it is (:data:`LONG_NAMES`).
    """
    idx = traj._locate(ts)
    parts = []
    for k in np.unique(idx):
        sel = idx == k
        seg = traj.segments[k]
        parts.append((seg.mode, ts[sel], seg.states(ts[sel])))
    df = observable_table(traj.model, parts)
    for name, values in traj._pose(idx, ts).items():
        df[name] = values
    return _describe(df)


def pose_table(traj, ts):
    """The rows of :meth:`~phasekit.core.trajectory.Trajectory.pose` at the checked times ``ts``.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    ts : numpy.ndarray
        Times inside the run, already checked.

    Returns
    -------
    pandas.DataFrame
        Column ``t`` and the pose columns, their units and long names in ``attrs``.
    """
    import pandas as pd

    return _describe(pd.DataFrame({"t": ts, **traj._pose(traj._locate(ts), ts)}))


def event_dict(event) -> dict:
    """The JSON form of an :class:`~phasekit.core.records.EventRecord` (its ``to_dict``).

    Parameters
    ----------
    event : EventRecord
        The event.

    Returns
    -------
    dict
        ``kind``, ``t``, ``mode_before``, ``mode_after``, and ``detail`` and ``state`` (paper's variables) when set.
    """
    d = {"kind": event.name, "t": float(event.t), "mode_before": event.mode_before, "mode_after": event.mode_after}
    if event.detail:
        d["detail"] = event.detail
    if event.y is not None:
        d["state"] = {k: float(v) for k, v in zip(PAPER_NAMES, event.y)}
    return d


def flight_dict(flight) -> dict:
    """The JSON form of a :class:`~phasekit.core.records.Flight` (its ``to_dict``).

    Parameters
    ----------
    flight : Flight
        The flight.

    Returns
    -------
    dict
        Its times, gap maximum, ``W_star`` and ``Omega_star``.
    """
    return {"t_liftoff": flight.t_liftoff, "t_touchdown": flight.t_touchdown, "gap_max": flight.gap_max,
            "t_gap_max": flight.t_gap_max, "W_star": flight.W_star, "Omega_star": flight.Omega_star}


def trajectory_dict(traj, *, events: bool = True) -> dict:
    """JSON form in the paper's variables, with the inputs (model, start, options): what
    :meth:`~phasekit.core.trajectory.Trajectory.to_dict` returns.

    Parameters
    ----------
    traj : Trajectory
        The run.
    events : bool, optional
        Include the event log (with each event's pose when there is dense output).

    Returns
    -------
    dict
        The outcome, the end state, counts, flights and hops, and the inputs of the run.
    """
    chart = traj.model.chart
    y_end = chart.to_paper(traj.x)
    xj = traj.x_jump
    d = {
        "status": str(traj.status),
        "reason": traj.reason,
        "t_jump": traj.t_jump,
        "state_at_jump": None if xj is None else dict(zip(PAPER_NAMES, map(float, chart.to_paper(xj)))),
        "Rdot_at_jump": traj.Rdot_jump,
        "R_min": traj.R_min,
        "t_end": float(traj.t),
        "theta_end": float(y_end[4]),
        "state_end": dict(zip(PAPER_NAMES, map(float, y_end))),
        "mode_end": traj.mode,
        "stuck": traj.stuck,  # ever held zero slip (not "did not rise": see contact_summary)
        **contact_summary(traj),
        **_dissipation_summary(traj, skipped := []),
        "n_events": len(traj.events),
        "n_steps": int(traj.n_steps),
        "n_rhs": int(traj.n_rhs),
        "wall_s": float(traj.wall_s),
        "chart": chart.name,
        "formulation": chart.name,  # the old name of "chart", kept for readers of older output
        "backend": traj.backend,
        "rtol": traj.options.rtol,
        "approximations": [a.to_dict() for a in traj.approximations],
        "verification": None if traj.verification is None else traj.verification.to_dict(),
    }
    stops = [e for e in traj.events if e.mode_after == "end" and e.name not in ("lift-off", "touchdown")]
    if traj.status is Status.STOPPED and stops:
        d["t_stop"], d["stopped_by"] = stops[-1].t, stops[-1].name
    poses = _within_budget(lambda: event_poses(traj), skipped, "poses") if events else None
    if skipped:  # the wall budget's rest, after the run, ran out (the CLI's --max-wall counts this work)
        d["post_run"] = {"skipped": [s for s, _ in skipped], "reason": skipped[0][1]}
    if events:
        d["events"] = [e.to_dict() for e in traj.events]
        if poses is not None:
            for e, pose in zip(d["events"], poses[:-1]):
                e["pose"] = pose
    if poses is not None:
        d["pose_end"] = poses[-1]
    d.update(_face_dict(traj))
    fl = traj.flights
    if fl:
        d["flight"] = fl[0].to_dict()
        d["n_flights"] = len(fl)
        d["hops"] = traj.hops
    d["model"] = traj.model.to_dict()
    d["start"] = dict(zip(PAPER_NAMES, map(float, chart.to_paper(traj.x0) if traj.x0.size == chart.n_states
                                               else FLIGHT.to_paper(traj.x0))))
    d["start_chart_state"] = traj.x0.tolist()
    d["t0"] = traj.t0
    d["t_end_requested"] = traj.t_end
    d["stop_at"] = traj.stop_at
    d["restitution"] = traj.restitution
    d["user_events"] = [e.to_dict() for e in traj.user_events]
    d["options"] = traj.options.to_dict()
    d["pose0"] = traj.pose0.to_dict()
    return d


def _face_dict(traj) -> dict:
    """Lying flat (:mod:`phasekit.core.face`): the face phase, and the start mode of a run started on it."""
    if getattr(traj, "face", None) is None:
        return {}
    return {"face": traj.face.to_dict(), **({} if traj.segments else {"start_mode": "face"})}


def event_poses(traj) -> list[dict] | None:
    """The pose at each event and at the end (None without dense output).

    Parameters
    ----------
    traj : Trajectory
        The run.

    Returns
    -------
    list of dict or None
        One pose per event, then the pose at the end.
    """
    if (not traj.segments and getattr(traj, "face", None) is None) or not all(s.dense for s in traj.segments):
        return None
    ts = np.array([e.t for e in traj.events] + [traj.t])
    ts = np.clip(ts, traj.t0, traj.t)
    order = np.argsort(ts, kind="stable")
    cols = traj._pose(traj._locate(ts[order]), ts[order])
    out = [None] * len(ts)
    for rank, i in enumerate(order):
        out[i] = {name: float(cols[name][rank]) for name in POSE_COLUMNS}
    return out


def events_table(traj, name: str | None = None):
    """The recorded events (or those called ``name``) as a DataFrame: ``t``, ``event``,
    ``mode_before``, ``mode_after`` and the paper's state at the event (what
    :meth:`~phasekit.core.trajectory.Trajectory.events_table` returns).

    Parameters
    ----------
    traj : Trajectory
        The run.
    name : str, optional
        Only the events of this name.

    Returns
    -------
    pandas.DataFrame
        One row per event.
    """
    import pandas as pd

    rows = [{"t": e.t, "event": e.name, "mode_before": e.mode_before, "mode_after": e.mode_after,
             **dict(zip(PAPER_NAMES, e.y if e.y is not None else [np.nan] * len(PAPER_NAMES)))}
            for e in traj.events if name is None or e.name == name]
    return pd.DataFrame(rows, columns=["t", "event", "mode_before", "mode_after", *PAPER_NAMES])


def _times(traj, times, n):
    if times is not None:
        return times
    n = check_int("n", n, minimum=2, maximum=10_000_000)
    return np.linspace(traj.t0, traj.t, n)


def run_table(traj, times=None, *, n: int = 2001, scale=None):
    """The run sampled at ``times`` (default ``n`` instants uniform over it), with what repeats
    it: the table its files hold.

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    times : array_like, optional
        The sampling times, inside the run.
    n : int, optional
        The number of instants without ``times``, in [2, 1e7].
    scale : Scale, optional
        The columns in real units (:meth:`phasekit.Scale.table`: t in ms, lengths in mm, rates
        in rev/s, ...; forces and energies only with the Scale's mass), each column's unit in
        ``attrs["units"]`` and the scale in ``attrs["scale"]`` (b, g and mass as text); the
        other attributes (the outcome, such as ``t_jump``, the inputs, the events and ``run``)
        stay in phasekit's units. Default: phasekit's units (t in sqrt(b/g), ...).

    Returns
    -------
    pandas.DataFrame
        :func:`sample_table`'s table; in ``attrs`` each column's unit and long name, the
        outcome (:data:`RUN_SCALARS` that are not None), the inputs (:data:`RUN_INPUTS`), the
        event log (``events``) and the whole :func:`trajectory_dict` without events (``run``:
        ``pk.rerun(df.attrs["run"])`` repeats the run).

    Raises
    ------
    ParameterError
        For an invalid ``n``, a time outside the run, or a ``scale`` that is not a Scale.
    """
    if scale is not None and not isinstance(scale, Scale):
        raise ParameterError("scale", "must be a phasekit Scale such as pk.Scale('21.5 mm'), or None", scale)
    df = traj.sample(_times(traj, times, n))
    d = trajectory_dict(traj, events=False)
    df.attrs.update({k: d[k] for k in RUN_SCALARS if d.get(k) is not None})
    df.attrs.update({k: d[k] for k in RUN_INPUTS})
    df.attrs["events"] = [e.to_dict() for e in traj.events]
    df.attrs["run"] = d
    if scale is None:
        return df
    df = scale.table(df)
    df.attrs["scale"] = {"b": f"{scale.b:~P}", "g": f"{scale.g:~P}", "mass": None if scale.mass is None else f"{scale.mass:~P}"}
    return df


def trajectory_xarray(traj, times=None, *, n: int = 2001, scale=None):
    """The run sampled at ``times`` (default ``n`` instants uniform over it) as an xarray
    Dataset (:meth:`~phasekit.core.trajectory.Trajectory.to_xarray`): :func:`run_table` as its
    NetCDF file holds it (:mod:`phasekit.io.netcdf`).

    Parameters
    ----------
    traj : Trajectory
        The run, with its dense output.
    times : array_like, optional
        The sampling times, inside the run.
    n : int, optional
        The number of instants without ``times``, in [2, 1e7].
    scale : Scale, optional
        Real units, as for :func:`run_table`.

    Returns
    -------
    xarray.Dataset
        The sampled run: coordinate ``t``, one variable per column (with ``units`` and
        ``long_name``); the outcome as global attributes, the inputs and the whole result as
        JSON in ``phasekit_json``.

    Raises
    ------
    PhasekitError
        If the packages for NetCDF files (``phasekit[data]``) are missing.
    ParameterError
        For an invalid ``n`` or a time outside the run.
    """
    from ..io.tables import table_dataset

    return table_dataset(run_table(traj, times, n=n, scale=scale))
