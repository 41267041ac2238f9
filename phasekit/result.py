"""Small typed results: events and simulation results, with their JSON form."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .charts import EULER_NAMES, vector_to_euler
from .errors import Status

__all__ = ["EventRecord", "SimulationResult", "euler_state"]


def euler_state(chart: str, x) -> np.ndarray:
    """A chart state as the paper's (U, V, Omega, Lambda, theta, n)."""
    x = np.asarray(x, dtype=float)
    return x.copy() if chart == "euler" else vector_to_euler(x)


def _state_dict(chart, x) -> dict | None:
    if x is None:
        return None
    y = euler_state(chart, x)
    return {k: float(v) for k, v in zip(EULER_NAMES, y)}


@dataclass(frozen=True)
class EventRecord:
    """A located event: ``kind`` is one of stick, slip, lift-off, touchdown, impact, rise-complete."""

    kind: str
    t: float
    mode_before: str
    mode_after: str
    x: np.ndarray = field(repr=False, compare=False, default=None)
    detail: str = ""

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "t": float(self.t), "mode_before": self.mode_before, "mode_after": self.mode_after}
        if self.detail:
            d["detail"] = self.detail
        return d


@dataclass(frozen=True)
class SimulationResult:
    """Outcome of :func:`phasekit.simulate`.

    Attributes
    ----------
    status : Status
        ``jumped`` (R reached 0 with dR/dt < 0), ``touchdown`` (stopped at the first
        re-contact), ``completed`` (reached ``t_end``, or the rise completed) or ``failed``
        (see ``reason``).
    t_jump, x_jump
        Time and chart state of the first lift-off, or None.
    R_min : float or None
        Smallest normal reaction met (exact local minima when tracked, else over the
        located events and segment ends).
    events : tuple of EventRecord
        Every mode switch in time order (stick, slip, lift-off, ...).
    ts, ys : arrays or None
        States at the requested output times only (``t_eval``); None when none were asked.
    minima : (m, 2) array or None
        (t, R) at each local minimum of R, when tracked.
    """

    status: Status
    chart: str
    backend: str
    rtol: float
    t0: float
    t: float
    x: np.ndarray
    mode: str
    t_jump: float | None = None
    x_jump: np.ndarray | None = None
    Rdot_jump: float | None = None
    R_min: float | None = None
    reason: str | None = None
    events: tuple[EventRecord, ...] = ()
    n_steps: int = 0
    n_rhs: int = 0
    wall_s: float = 0.0
    ts: np.ndarray | None = None
    ys: np.ndarray | None = None
    minima: np.ndarray | None = None
    extra: dict = field(default_factory=dict)
    flights: tuple = ()  # phasekit.flight.Flight, one per flight

    @property
    def success(self) -> bool:
        return self.status is not Status.FAILED

    @property
    def jumped(self) -> bool:
        return self.status is Status.JUMPED

    @property
    def stuck(self) -> bool:
        """Whether the slip ever vanished (a stick event was recorded)."""
        return any(e.kind == "stick" for e in self.events)

    def events_named(self, kind: str) -> list[EventRecord]:
        return [e for e in self.events if e.kind == kind]

    @property
    def euler_end(self) -> np.ndarray:
        return euler_state(self.chart, self.x)

    @property
    def euler_ys(self) -> np.ndarray | None:
        if self.ys is None:
            return None
        return self.ys.copy() if self.chart == "euler" else np.array([vector_to_euler(z) for z in self.ys])

    def to_dict(self) -> dict:
        """JSON form in the paper's variables."""
        end = euler_state(self.chart, self.x)
        d = {
            "status": str(self.status),
            "reason": self.reason,
            "t_jump": None if self.t_jump is None else float(self.t_jump),
            "state_at_jump": _state_dict(self.chart, self.x_jump),
            "Rdot_at_jump": self.Rdot_jump,
            "R_min": None if self.R_min is None else float(self.R_min),
            "t_end": float(self.t),
            "theta_end": float(end[4]),
            "state_end": _state_dict(self.chart, self.x),
            "mode_end": self.mode,
            "stuck": self.stuck,
            "events": [e.to_dict() for e in self.events],
            "n_steps": int(self.n_steps),
            "n_rhs": int(self.n_rhs),
            "wall_s": float(self.wall_s),
            "formulation": self.chart,
            "backend": self.backend,
            "rtol": self.rtol,
        }
        d.update(self.extra)
        return d

    def __repr__(self) -> str:
        tj = f", t_jump={self.t_jump:.9g}" if self.t_jump is not None else ""
        return f"SimulationResult(status={self.status.value}{tj}, t={self.t:.6g}, events={len(self.events)}, wall_s={self.wall_s:.3g})"
