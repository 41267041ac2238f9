"""The hybrid system as data: modes, flows, events, resets.

In the language of hybrid dynamical systems (a flow map on a flow set, a jump map on a
jump set), a run of phasekit is a sequence of *segments*: the body follows one smooth
vector field (a :class:`Flow`, one per :class:`Mode`) until the first *event* (a guard
crossing zero), whose *reset* maps the state into the next mode. :func:`phasekit.simulate`
is one short loop over these objects; the declarations of phasekit's own modes, events
and resets are in :mod:`phasekit.core.system`, and a user's event is one more :class:`Event`.

Nothing here knows the physics, and nothing here imports the model or the integrators.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from .._runtime.validate import check_bool, check_finite, check_nonnegative
from ..errors import ParameterError, Status


class Mode(str, enum.Enum):
    """Contact modes; the simulator switches between them only at located events.

    Attributes
    ----------
    SLIDING : Mode
        Value "sliding": smooth while the slip u != 0 (Coulomb), or everywhere (viscous,
        regularised).
    ROLLING : Mode
        Value "rolling": zero slip held by static friction: exact Coulomb's no-slip mode, or,
        for a regularised law, the stretch where the slip is below 10 eps (same field).
    FLIGHT : Mode
        Value "flight": no contact: gravity and torque-free rotation, until the gap closes.
    SLIDING_NO_PIVOT, ROLLING_NO_PIVOT : Mode
        Values "sliding_no_pivot", "rolling_no_pivot": as SLIDING and ROLLING, with the spin
        about the normal held at zero by spin friction (:class:`phasekit.SpinFriction`).
    SLIDING_NO_ROLL, PIVOTING : Mode
        Values "sliding_no_roll", "pivoting": as SLIDING and ROLLING, with the rolling part of
        the angular velocity held at zero by rolling resistance (:class:`phasekit.RollingResistance`);
        without slip the body then only spins about the normal, in place.
    FACE : Mode
        Value "face": an edged body lying flat on its face, sliding and spinning under Coulomb
        friction over the face (:mod:`phasekit.core.face`), after its "face down" with
        ``stop_at="rest"``, or from a start lying flat with ``mode="face"``.
    EDGE : Mode
        Value "edge": exact Coulomb's contact sliding on the edge of the friction cone, |F| = mu R,
        at a slip below 1e-3 whose direction the dynamics decides (:mod:`phasekit.core.cone_edge`).
    OFF_EDGE : Mode
        Value "off_edge": SLIDING's field after the slip has left the cone's edge, watched for its
        return there (SLIDING itself is not, so that the runs that never reach the edge keep their
        integrator).

    Examples
    --------
    >>> import phasekit as pk
    >>> [m.value for m in pk.core.Mode]
    ['sliding', 'rolling', 'flight', 'sliding_no_pivot', 'rolling_no_pivot', 'sliding_no_roll', 'pivoting', 'face', 'edge',
     'off_edge']
    """

    SLIDING = "sliding"
    ROLLING = "rolling"
    FLIGHT = "flight"
    SLIDING_NO_PIVOT = "sliding_no_pivot"
    ROLLING_NO_PIVOT = "rolling_no_pivot"
    SLIDING_NO_ROLL = "sliding_no_roll"
    PIVOTING = "pivoting"
    FACE = "face"
    EDGE = "edge"
    OFF_EDGE = "off_edge"

    @property
    def free(self) -> "Mode":
        """The mode with nothing held by spin friction or rolling resistance (SLIDING for
        SLIDING_NO_PIVOT, ROLLING for PIVOTING, ...)."""
        return _FREE.get(self, self)

    def held(self, kind: str) -> "Mode":
        """The mode with ``kind`` ("pivot" or "roll") held, from SLIDING or ROLLING."""
        return _HELD.get((self, kind), self)

    def __str__(self) -> str:
        return self.value


_FREE = {Mode.SLIDING_NO_PIVOT: Mode.SLIDING, Mode.ROLLING_NO_PIVOT: Mode.ROLLING, Mode.SLIDING_NO_ROLL: Mode.SLIDING,
         Mode.PIVOTING: Mode.ROLLING}
_HELD = {(Mode.SLIDING, "pivot"): Mode.SLIDING_NO_PIVOT, (Mode.ROLLING, "pivot"): Mode.ROLLING_NO_PIVOT,
         (Mode.SLIDING, "roll"): Mode.SLIDING_NO_ROLL, (Mode.ROLLING, "roll"): Mode.PIVOTING}


@dataclass(frozen=True)
class Flow:
    """One smooth vector field: the model function ``field`` (e.g. "rhs_sliding").

    ``monitor`` = (function, direction): record (t, x) wherever that function crosses zero
    in that direction without stopping (the minima of R, the maximum of the gap).
    ``engine`` forces an integrator for this flow; ``stiff`` makes "auto" pick CVODES.
    ``contact``: the body touches the table (a run that stops at the first lift-off, as
    :func:`phasekit.core.simulate_batch`'s do, stays in the contact flows).
    """

    mode: Mode
    field: str
    monitor: tuple[str, int] | None = None
    engine: str | None = None
    stiff: bool = False
    contact: bool = True


@dataclass(frozen=True)
class Event:
    """A guard crossing zero: ``on`` (an observable or a model function) minus ``level``.

    Parameters
    ----------
    on : str
        What to watch: any observable of :data:`phasekit.core.observables.OBSERVABLES` ("theta", "R",
        "Lambda", "energy", ...) or an internal guard function.
    level : float
        The value at which it fires (a run-time parameter: changing it never recompiles).
    direction : -1, 0 or +1
        Fire on downward crossings only, either, or upward only.
    terminal : bool
        True: the segment ends here; the ``reset`` maps to the next mode, or, without one,
        the run ends with status ``stop``. False: recorded, and the run goes on.
    name : str, optional
        How it is recorded (default "<on>=<level>").
    reset : Reset, optional
        The reset map of a terminal event: called with the model, the event, the mode and
        the state where it fired, it returns the :class:`Transition` to the next mode
        (default None: the run ends with status ``stop``).
    stop : Status
        The status a terminal event without a ``reset`` ends the run with (default
        ``Status.STOPPED``, "stopped").
    modes : iterable of Mode, optional
        The modes that watch it (default: all).
    rate : str, optional
        A model function giving the guard's rate, which lets pointwise integrators find
        a dip that crosses zero between two output points.
    arm_after : float
        The guard is not watched until this long after its mode starts; if it is already
        past its zero then, it fires at once.

    Raises
    ------
    ParameterError
        If ``on`` is not a non-empty string, ``level`` is not finite, ``direction`` is not
        -1, 0 or +1, ``terminal`` is not a bool, ``arm_after`` is negative or not finite,
        ``modes`` holds something that is not a mode, ``rate`` is neither None nor a non-empty
        string, or ``stop`` is not a :class:`phasekit.Status`.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.Event("theta", 0.4).name                      # stop when theta first reaches 0.4
    'theta=0.4'
    >>> pk.Event("Lambda", 0.0, direction=+1, terminal=False).to_dict()   # a Poincare section
    {'name': 'Lambda=0', 'on': 'Lambda', 'level': 0.0, 'direction': 1, 'terminal': False}
    """

    on: str
    level: float = 0.0
    direction: int = 0
    terminal: bool = True
    name: str | None = None
    reset: "Reset | None" = field(default=None, compare=False)
    stop: Status = Status.STOPPED
    modes: frozenset | None = None
    rate: str | None = None
    arm_after: float = 0.0

    def __post_init__(self):
        if not isinstance(self.on, str) or not self.on:
            raise ParameterError("on", "must name an observable such as 'theta', 'R' or 'Lambda'", self.on)
        object.__setattr__(self, "level", check_finite("level", self.level))
        if self.direction not in (-1, 0, 1) or isinstance(self.direction, bool):
            raise ParameterError("direction", "must be -1, 0 or +1", self.direction)
        object.__setattr__(self, "terminal", check_bool("terminal", self.terminal))
        object.__setattr__(self, "arm_after", check_nonnegative("arm_after", self.arm_after))
        if self.name is None:
            object.__setattr__(self, "name", f"{self.on}={self.level:g}")
        if self.modes is not None:
            try:
                modes = frozenset(Mode(m) for m in self.modes)
            except (ValueError, TypeError):
                raise ParameterError("modes", f"must be modes among {', '.join(m.value for m in Mode)}", self.modes) from None
            object.__setattr__(self, "modes", modes)
        if self.rate is not None and (not isinstance(self.rate, str) or not self.rate):
            raise ParameterError("rate", "must be None or the name of a model function giving the guard's rate", self.rate)
        if not isinstance(self.stop, Status):
            raise ParameterError("stop", "must be a phasekit Status", self.stop)

    def watches(self, mode: Mode) -> bool:
        return self.modes is None or mode in self.modes

    def to_dict(self) -> dict:
        return {"name": self.name, "on": self.on, "level": self.level, "direction": self.direction, "terminal": self.terminal}


@dataclass(frozen=True)
class Record:
    """One line of a trajectory's event log (see :class:`phasekit.core.records.EventRecord`)."""

    name: str
    mode_before: str
    mode_after: str
    x: np.ndarray | None = None  # in the chart of mode_after (or of mode_before for "start")
    detail: str = ""


@dataclass(frozen=True)
class Transition:
    """What a reset decides: go on in ``mode`` from (t, x), or stop with ``stop``.

    ``records`` are logged in order (the first names the event itself); ``resume`` means the
    guard was only grazed and the segment continues unchanged; ``carried``: the reset carried
    the state on along the current field to (t, x) (an extrapolation to an exact zero), so the
    segment that ended at the event extends to it."""

    mode: Mode | None
    t: float
    x: np.ndarray
    records: tuple[Record, ...] = ()
    stop: Status | None = None
    reason: str | None = None
    resume: bool = False
    carried: bool = False


class Reset(Protocol):
    """A reset map: called with the model, the event and the state where it fired."""

    def __call__(self, model, event: Event, mode: Mode, t: float, x: np.ndarray) -> Transition: ...


@dataclass(frozen=True)
class HybridSystem:
    """Flows per mode, the events (each watched by some modes), and the rule that picks
    the mode a state starts in (``initial(model, t, x) -> Transition``)."""

    flows: tuple[Flow, ...]
    events: tuple[Event, ...]
    initial: object

    def flow(self, mode: Mode) -> Flow:
        for f in self.flows:
            if f.mode is mode:
                return f
        raise KeyError(mode)

    def events_of(self, mode: Mode) -> tuple[Event, ...]:
        return tuple(e for e in self.events if e.watches(mode))

    @property
    def contact_flows(self) -> tuple[Flow, ...]:
        return tuple(f for f in self.flows if f.contact)


# -- what the integrators see ------------------------------------------------------------------


@dataclass(frozen=True)
class CompiledGuard:
    """A guard as a CasADi function g(x, p, level), its direction and optional rate(x, p)."""

    name: str
    function: object
    direction: int
    rate: object = None
    signature: str = ""


@dataclass(frozen=True)
class CompiledFlow:
    """Everything an integrator needs for one segment: the field f(x, p), the guards, the
    monitor, and signatures that key compiled-integrator caches. Built by the model."""

    mode: Mode
    field: object
    n_states: int
    guards: tuple[CompiledGuard, ...]
    monitor: CompiledGuard | None
    signature: str
    rate_hint: object = None  # x -> fastest rotation rate (pointwise integrators' grid)
    #: P(x, p) whose time derivative is the monitor's function (R for dR/dt), or None: the Taylor
    #: engine then finds the monitor's zeros from P's expansion (:mod:`phasekit.core.engines.roots`)
    monitor_primitive: object = None
