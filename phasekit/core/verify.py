"""How far a run is from converged: :func:`check_run` repeats it at a ten times tighter tolerance
in the other chart (a second formulation of the same equations) and measures the difference of
its outcome, event times, end state, position and orientation (:class:`RunCheck`).

A run is "converged to ~X" when the repeat ends the same way through the same events and X, the
largest relative difference of what both report, is its estimated error; "not converged" when
the outcome or the sequence of events differs. The other chart is the vector chart for a run in
the paper's variables, and the paper's variables for a vector-chart run unless it comes within
1e-5 of a pole (where they are singular, :data:`phasekit.core.charts.POLE_MARGIN`), which is
then repeated in its own chart. ``Trajectory.verify()`` and ``simulate(..., verify=True)`` are the
entries.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

import numpy as np

from ..errors import Status
from .charts import POLE_MARGIN
from .pose import rotation_matrix

#: the repeat runs at the run's tolerance divided by this
CHECK_TIGHTER = 10


@dataclass(frozen=True)
class RunCheck:
    """A run against its repeat at rtol / 10 in the other chart.

    Attributes
    ----------
    verdict : {"converged", "not converged"}
        "converged": same outcome, same sequence of events.
    rtol : float
        The repeat's tolerance.
    chart : str
        The repeat's chart.
    outcome : tuple of str
        The two statuses (the run's, the repeat's).
    event_time : float or None
        The largest difference of a matched event's time, relative to max(1, t) (units sqrt(b/g)).
    end_state : float or None
        The difference of the end states in the paper's variables, |dy| / |y| (2-norm).
    position : float or None
        The distance between the two positions of G at the end, units b (None without dense output).
    position_rel : float or None
        ``position`` over the distance of G from where it started (or 1 b if it moved less).
    orientation : float or None
        The angle of the rotation between the two end orientations, radians.
    worst : float or None
        The largest of the relative measures above: the run's estimated error ("converged to ~worst").
    detail : str
        The verdict in words.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 200.0)
    >>> check = traj.verify()
    >>> check.verdict, check.chart, check.worst < 1e-7
    ('converged', 'vector', True)
    """

    verdict: str
    rtol: float
    chart: str
    outcome: tuple[str, str]
    event_time: float | None
    end_state: float | None
    position: float | None
    position_rel: float | None
    orientation: float | None
    worst: float | None
    detail: str

    @property
    def converged(self) -> bool:
        return self.verdict == "converged"

    def to_dict(self) -> dict:
        return asdict(self)


def _other_chart(traj) -> str:
    if traj.model.chart.name == "euler":
        return "vector"
    thetas = [traj.model.chart.theta(traj.x0), *(traj.model.chart.theta(s.x1) for s in traj.segments if s.mode.value != "flight")]
    near_pole = min(min(t, np.pi - t) for t in thetas) < 10 * POLE_MARGIN
    return "vector" if near_pole else "euler"


def _repeat(traj, chart: str, rtol: float):
    """``traj`` run again by its own runner (:func:`phasekit.simulate`) at ``rtol`` in ``chart``, with dense output."""
    model = traj.model.with_chart(chart)
    x0 = traj.x0 if traj.x0.size != traj.model.n_states else model.chart.from_paper(traj.model.chart.to_paper(traj.x0))
    opts = replace(traj.options, rtol=rtol, atol=None if traj.options.atol is None else traj.options.atol / CHECK_TIGHTER,
                   dense=True)
    on_face = getattr(traj, "face", None) is not None and not traj.segments  # started lying flat
    mode = "flight" if traj.x0.size != traj.model.n_states else "face" if on_face else None
    return traj.runner(model, x0, traj.t_end, t0=traj.t0, stop_at=traj.stop_at, restitution=traj.restitution,
                       events=list(traj.user_events), options=opts, pose0=traj.pose0, progress=False, mode=mode)


def _ends(traj):
    """(paper state at the end, position of G, rotation matrix) of a run; the last two None without dense output."""
    y = traj.model.chart.to_paper(traj.x)
    if not (traj.segments and all(s.dense for s in traj.segments)):
        return y, None, None
    pose = traj.pose([traj.t]).iloc[0]
    return y, np.array([pose["X"], pose["Y"]]), rotation_matrix(pose["psi"], y[4], pose["phi"])


def check_run(traj, *, factor: float = CHECK_TIGHTER) -> RunCheck:
    """Repeat ``traj`` at rtol / ``factor`` in the other chart and measure the difference (module notes).

    Parameters
    ----------
    traj : Trajectory
        The run to check.
    factor : float, optional
        How much tighter the repeat's tolerance is (default 10).

    Returns
    -------
    RunCheck
        The verdict and the measured differences.
    """
    if traj.runner is None:
        raise ValueError("this Trajectory has no runner to repeat it (made by hand, not by simulate)")
    rtol = max(traj.options.rtol / factor, 1e-16)
    chart = _other_chart(traj)
    other = _repeat(traj, chart, rtol)
    if other.status is Status.FAILED and traj.status is not Status.FAILED and chart != traj.model.chart.name:
        chart, other = traj.model.chart.name, _repeat(traj, traj.model.chart.name, rtol)  # the other chart could not follow it
    outcome = (str(traj.status), str(other.status))
    names = ([e.name for e in traj.events], [e.name for e in other.events])
    if outcome[0] != outcome[1] or names[0] != names[1]:
        what = "outcome differs" if outcome[0] != outcome[1] else "events differ"
        detail = (f"not converged: {what} ({outcome[0]} with {len(names[0])} events at rtol {traj.options.rtol:g}, "
                  f"{outcome[1]} with {len(names[1])} at rtol {rtol:g} in the {chart} chart)")
        return RunCheck("not converged", rtol, chart, outcome, None, None, None, None, None, None, detail)
    dt = max((abs(a.t - b.t) / max(1.0, abs(a.t)) for a, b in zip(traj.events, other.events)), default=0.0)
    dt = max(dt, abs(traj.t - other.t) / max(1.0, abs(traj.t)))
    (y1, g1, r1), (y2, g2, r2) = _ends(traj), _ends(other)
    dy = float(np.linalg.norm(y1 - y2) / max(np.linalg.norm(y1), 1e-300))
    pos = rel = ang = None
    if g1 is not None and g2 is not None:
        pos = float(np.linalg.norm(g1 - g2))
        start = traj.pose([traj.t0]).iloc[0]
        rel = pos / max(1.0, float(np.hypot(g1[0] - start["X"], g1[1] - start["Y"])))
        ang = float(2.0 * np.arcsin(min(1.0, np.linalg.norm(r1 - r2) / (2.0 * np.sqrt(2.0)))))  # |R1 - R2|_F = 2 sqrt(2) sin(angle/2)
    worst = max(v for v in (dt, dy, rel, ang) if v is not None)
    detail = (f"converged to ~{worst:.1e}: the repeat at rtol {rtol:g} in the {chart} chart ends {outcome[1]} through the "
              f"same {len(names[0])} events (event times {dt:.1e}, end state {dy:.1e}"
              + ("" if pos is None else f", position of G {pos:.1e} b ({rel:.1e}), orientation {ang:.1e} rad") + ")")
    return RunCheck("converged", rtol, chart, outcome, dt, dy, pos, rel, ang, worst, detail)
