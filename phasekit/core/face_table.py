"""The face phase of a run (:mod:`phasekit.core.face`) in the run's tables: sampled rows and poses.

Lying flat, the paper's state is the face's (:meth:`phasekit.core.face.FacePhase.paper_states`), R = M g,
the gap 0; the pose carries on from the landing: G moves with v (turned from the chart's axes at the
landing to the table's), the spin angle phi turns with w, the azimuth psi stays, and the contact
point is the face's centre, below G.
"""

from __future__ import annotations

import numpy as np

from .charts import PAPER_NAMES
from .pose import POSE_COLUMNS
from .trajectory_io import STATE_COLUMNS, _describe, sample_table


def landing_pose(traj) -> dict:
    """psi, phi, X, Y at the start of the face phase: the pose at the landing, or the run's pose0."""
    if traj.segments:
        row = traj._pose_track(np.array([len(traj.segments) - 1]), np.array([traj.face.t0]))
        return {k: float(np.ravel(row[k])[0]) for k in ("psi", "phi", "X", "Y")}
    p = traj.pose0
    return {"psi": p.psi, "phi": p.phi, "X": p.X, "Y": p.Y}


def face_pose(traj, ts) -> dict:
    """The pose columns at times ``ts`` inside the face phase."""
    face = traj.face
    Y = face.states(ts)
    p0 = landing_pose(traj)
    turn = np.exp(1j * (p0["psi"] - face.contact.psi))
    xy = complex(p0["X"], p0["Y"]) + turn * (Y[:, 3] + 1j * Y[:, 4])
    X, Yc = xy.real, xy.imag
    return {"psi": np.full(len(ts), p0["psi"]), "phi": p0["phi"] + Y[:, 5], "X": X, "Y": Yc, "X_P": X.copy(),
            "Y_P": Yc.copy()}


def face_split(traj, ts):
    """(times of the segments, times of the face phase): a time at the landing belongs to the segment
    that ends there."""
    if traj.face is None:
        return ts, ts[:0]
    on = ts > traj.face.t0 if traj.segments else np.ones(ts.shape, dtype=bool)
    return ts[~on], ts[on]


def face_table(traj, ts):
    """:meth:`phasekit.core.Trajectory.sample`'s rows at the checked times ``ts``: those of the segments
    (:func:`phasekit.core.trajectory_io.sample_table`), then those of the face phase."""
    import pandas as pd

    before, on = face_split(traj, ts)
    if not on.size:
        return sample_table(traj, ts)
    face = traj.face
    Y = face.states(on)
    cols = {"t": on, "mode": np.full(len(on), "face", dtype=object)}
    P = face.paper_states(Y)
    cols.update({name: P[:, j] for j, name in enumerate(PAPER_NAMES)})
    cols.update(face.observables(Y))
    cols = {k: cols[k] for k in ("t", "mode", *STATE_COLUMNS)}
    cols.update(face_pose(traj, on))
    rows = pd.DataFrame(cols)
    if before.size:
        rows = pd.concat([sample_table(traj, before), rows], ignore_index=True)
    return _describe(rows[[c for c in ("t", "mode", *STATE_COLUMNS, *POSE_COLUMNS) if c in rows.columns]])
