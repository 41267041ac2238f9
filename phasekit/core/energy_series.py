"""The energy budget of a run as a time series: the mechanical energy, the energy each law has
taken out so far, the energy lost at events so far, and the balance, at every Taylor step's end
or at the times asked (:meth:`phasekit.core.Trajectory.energy_series`).

The same quadrature as :func:`phasekit.core.energy.energy_budget` (Gauss-Legendre on each Taylor
step of the dense output); at a time inside a step, the part of the step before it is integrated
by the same rule on [step start, t], so the series at any time is the budget of the run up to it.
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_times
from ..errors import ParameterError
from .energy import FACE_LAW, GAUSS_NODES, energy_budget, gauss_powers, law_names, require_dense, step_bounds
from .face_table import face_split
from .observables import evaluate_function


def energy_series(traj, times=None):
    """The energy budget along a run, one row per time (units M g b); see
    :meth:`phasekit.core.Trajectory.energy_series`."""
    if getattr(traj, "face", None) is not None:
        return _with_face(traj, times)
    model = traj.model
    names = law_names(model)
    if not traj.segments and traj.mode_stop is not None:  # it ended at its start: nothing lost, ever
        ts = np.array([traj.t0]) if times is None else _times_at_start(traj, times)
        e = float(model.function("energy", traj.mode_stop)(traj.x_stop, model.p))
        return _table(names, ts, np.full(ts.size, e), np.zeros((ts.size, len(names))), np.zeros(ts.size), e)
    require_dense(traj)
    ts = None if times is None else traj._check_times(times)
    steps = [_segment_steps(model, seg, len(names)) for seg in traj.segments]
    energies = [model.function("energy", seg.mode) for seg in traj.segments]
    # what the laws took out before each segment: each segment's last cumulative sum, as its rows end
    before = np.cumsum([np.zeros(len(names))] + [np.cumsum(s[3], axis=0)[-1] if len(s[3]) else np.zeros(len(names))
                                                 for s in steps[:-1]], axis=0)
    jumps = np.cumsum([0.0] + [float(energies[k](traj.segments[k].x1, model.p))
                               - float(energies[k + 1](traj.segments[k + 1].x0, model.p))
                               for k in range(len(steps) - 1)])
    e_start = float(energies[0](traj.segments[0].x0, model.p))
    parts = []
    idx = None if ts is None else traj._locate(ts)
    for k, seg in enumerate(traj.segments):
        if ts is None:
            t, done = _at_step_ends(seg, steps[k])
        elif np.any(idx == k):
            t, done = _at_times(model, seg, steps[k], ts[idx == k])
        else:
            continue
        E = np.atleast_1d(evaluate_function(energies[k], model.p, seg.states(t))).reshape(-1)
        parts.append((t, E, before[k] + done, np.full(t.size, jumps[k])))
    if not parts:  # no time asked
        return _table(names, np.zeros(0), np.zeros(0), np.zeros((0, len(names))), np.zeros(0), e_start)
    t, E, lost, at_events = (np.concatenate(c) for c in zip(*parts))
    return _table(names, t, E, lost, at_events, e_start)


def _with_face(traj, times):
    """The series of a run that lies flat at its end (:mod:`phasekit.core.face`): the segments' rows
    (the face's friction 0 there), then the face phase's at its steps' ends or at the times asked in
    it: each law's total before the landing, the landing at events, the face's friction its work."""
    face, names = traj.face, (*law_names(traj.model), FACE_LAW)
    ts = None if times is None else traj._check_times(times)
    before, on = (None, None) if ts is None else face_split(traj, ts)
    if on is None:
        on = np.concatenate([[face.t0], [p[1] for p in face.pieces]]) if face.pieces else np.array([face.t0])
    head = energy_series(_without_face(traj), before) if traj.segments else None
    budget = energy_budget(traj)
    Y = face.states(on)
    lost = np.column_stack([np.tile(budget.dissipated[:-1], (on.size, 1)), -Y[:, 6]])
    tail = _table(names, on, face.contact.energy(Y), lost, np.full(on.size, budget.at_events), budget.energy_start)
    if head is None:
        return tail
    import pandas as pd

    head.insert(len(names) + 1, FACE_LAW, 0.0)
    return pd.concat([head, tail], ignore_index=True)


def _without_face(traj):
    from dataclasses import replace

    return replace(traj, face=None)


def _times_at_start(traj, times) -> np.ndarray:
    ts = np.atleast_1d(np.asarray(check_times("times", times, allow_empty=True)))
    bad = ts[ts != traj.t0]
    if bad.size:
        value = float(bad[0]) if bad.size == 1 else [float(bad[0]), float(bad[-1])]
        raise ParameterError("times", f"must lie in the simulated span [{traj.t0:.10g}, {traj.t0:.10g}] "
                                      f"({bad.size} outside): the run ended at its start", value)
    return ts


def _segment_steps(model, seg, n_laws: int):
    """The steps of a segment: (span index, start, end, energy each law took out in the step)."""
    out = []
    for i, span in enumerate(seg.dense):
        a, b = step_bounds(span)
        if len(b):
            out.append((np.full(len(b), i), a, b, _step_work(model, seg.mode, span, a, b)))
    if not out:
        return np.zeros(0, dtype=int), np.zeros(0), np.zeros(0), np.zeros((0, n_laws))
    return tuple(np.concatenate(c) for c in zip(*out))


def _step_work(model, mode, span, a, b) -> np.ndarray:
    """Minus the integral of each law's power over each interval [a, b]: (intervals, laws)."""
    w, vals = gauss_powers(model, mode, span, a, b)
    return -(w[:, None] * vals).reshape(len(b), GAUSS_NODES, -1).sum(axis=1)


def _at_step_ends(seg, steps):
    """The segment's start and every step's end, with the energy each law took out since the start."""
    _, _, b, work = steps
    lost = np.cumsum(work, axis=0)
    return np.concatenate([[seg.t0], b]), np.vstack([np.zeros((1, work.shape[1])), lost])


def _at_times(model, seg, steps, ts):
    """The times ``ts`` (inside the segment, sorted), with the energy each law took out since its start:
    the whole steps before each time, then the part of its step up to it by the same quadrature."""
    span_of, a, b, work = steps
    lost = np.zeros((ts.size, work.shape[1]))
    if not b.size:
        return ts, lost
    j = np.clip(np.searchsorted(b, ts, side="left"), 0, b.size - 1)
    done = np.vstack([np.zeros((1, work.shape[1])), np.cumsum(work, axis=0)])
    lost += done[j]
    cut = ts > a[j]
    for i in np.unique(span_of[j[cut]]):
        sel = cut & (span_of[j] == i)
        lost[sel] += _step_work(model, seg.mode, seg.dense[i], a[j[sel]], np.minimum(ts[sel], b[j[sel]]))
    return ts, lost


def _table(names, t, E, lost, at_events, e_start):
    import pandas as pd

    lost = np.asarray(lost, dtype=float).reshape(t.size, len(names))
    df = pd.DataFrame({"t": t, "energy": E})
    for i, name in enumerate(names):
        df[name] = lost[:, i]
    df["at_events"] = at_events
    df["residual"] = e_start - E - lost.sum(axis=1) - at_events
    return df
