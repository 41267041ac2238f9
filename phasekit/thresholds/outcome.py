"""What one trajectory of a threshold search gave (:class:`Outcome`): jumped or not, and how it ended."""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import Status


@dataclass(frozen=True)
class Outcome:
    """One trajectory of a threshold search: did it jump, and how did it end.

    Attributes
    ----------
    value : float
        The family parameter of the run (Omega0 or n0).
    jumped : bool or None
        Whether it jumped; None if the run failed.
    status : Status
        jumped; stopped = the rise completed; completed = reached t_max; settled =
        the body settled in contact (the definition's ``settle`` rule); rest = the body came
        to rest (dissipation laws); failed.
    t : float
        The time the run ended.
    stuck : bool
        Whether the body held zero slip at some time (:attr:`phasekit.core.Trajectory.stuck`).
    reason : str or None
        The run's ``reason`` (e.g. why it failed or settled), or None.
    wall_s : float
        Wall time of the run, seconds.
    theta : float or None
        The inclination where it ended (at lift-off for a jump); None for a failed run.
    rise_fraction : float or None
        How much of the rise from theta0 to the final state (0 prolate, pi/2 oblate) was done.

    Examples
    --------
    >>> import phasekit as pk
    >>> o = pk.thresholds.evaluate_outcomes([(pk.Definition('sliding', 'sliding'), 1.5, 12.0)])[0]
    >>> isinstance(o, pk.thresholds.Outcome), o.kind, o.how
    (True, 'jump', 'jumped')
    """

    value: float
    jumped: bool | None  # None: the run failed
    status: Status
    t: float
    stuck: bool
    reason: str | None
    wall_s: float
    theta: float | None = None
    rise_fraction: float | None = None

    @property
    def how(self) -> str:
        return {Status.JUMPED: "jumped", Status.STOPPED: "rise-complete", Status.COMPLETED: "t_max",
                Status.SETTLED: "settled", Status.REST: "rest"}.get(self.status, "failed")

    @property
    def kind(self) -> str:
        """The outcome map's classes: "jump" (lost contact before the rise completed),
        "rise" (the rise completed in contact), "stuck" (neither by t_max: the body stuck and
        rolls), "slow" (neither, without sticking) or "failed"."""
        if self.jumped is None:
            return "failed"
        if self.jumped:
            return "jump"
        if self.status is Status.STOPPED:
            return "rise"
        return "stuck" if self.stuck else "slow"
