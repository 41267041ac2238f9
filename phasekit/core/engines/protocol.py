"""The engines' protocol: :class:`Engine` (what every integrator of one smooth flow provides), what
one call of it produced (:class:`Propagation`, how it ended: :class:`End`) and the work allowance it
runs under (:class:`Budget`).
"""

from __future__ import annotations

import enum
import time
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..hybrid import CompiledFlow


class End(str, enum.Enum):
    """How one propagation ended: at the requested time, at an event, or failed (see the reason).

    Attributes
    ----------
    TIME : str
        "time": the requested end time was reached.
    EVENT : str
        "event": a guard of the flow crossed zero (:attr:`Propagation.event` says which).
    FAILED : str
        "failed": a step or wall budget ran out, or the state became non-finite (:attr:`Propagation.reason`).

    Examples
    --------
    >>> import phasekit as pk
    >>> [str(e) for e in pk.core.engines.End]
    ['time', 'event', 'failed']
    """

    TIME = "time"
    EVENT = "event"
    FAILED = "failed"

    def __str__(self) -> str:
        return self.value


@dataclass
class Budget:
    """What is left of a run's work allowance: steps and a wall-clock deadline.

    Parameters
    ----------
    steps : int
        Steps left.
    deadline : float
        A ``time.perf_counter()`` value (inf: none).
    tick : callable, optional
        Called with the time reached between chunks of a long call (a progress bar).
    keep : callable, optional
        Called with each span of dense output an engine makes (up to ~20 000 Taylor steps each);
        it returns False when the span is not to be kept (the run's memory cap,
        :mod:`phasekit.core.dense_cap`, took what it needs from it). None: every span is kept.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.Budget(steps=10, deadline=float('inf')).wall_exceeded()
    False
    """

    steps: int
    deadline: float  # time.perf_counter() value
    tick: object = None  # called with the time reached between chunks of a long call (a progress bar)
    keep: object = None  # span -> keep it in the dense output? (None: always)

    def wall_exceeded(self) -> bool:
        return time.perf_counter() > self.deadline


@dataclass
class Propagation:
    """What one call of an engine produced (filled in by the engine as it runs).

    Attributes
    ----------
    t : float
        The time reached.
    x : numpy.ndarray
        The state at ``t``.
    outcome : End
        How the call ended.
    event : int or None
        Index into the flow's guards of the event that ended it, else None.
    reason : str or None
        Why it failed, else None.
    n_steps : int
        Steps taken.
    n_rhs : int
        Evaluations of the field (for heyoka, steps times (order + 1)).
    monitored : list
        [(t, x)] where the flow's monitor crossed zero.
    dense : list
        Callables t -> states, in time order, with their spans (with ``dense=True``).

    Examples
    --------
    >>> import phasekit as pk
    >>> prop = pk.core.engines.Propagation(t=1.0, x=[0.0], outcome=pk.core.engines.End.TIME)
    >>> prop.outcome.value, prop.n_steps
    ('time', 0)
    """

    t: float
    x: np.ndarray
    outcome: End
    event: int | None = None  # index into the flow's guards
    reason: str | None = None
    n_steps: int = 0
    n_rhs: int = 0
    monitored: list = field(default_factory=list)  # [(t, x)] where the monitor crossed zero
    dense: list = field(default_factory=list)  # callables t -> states, in time order, with their spans


class Engine(Protocol):
    """An integrator of one smooth flow, to a time or the flow's first event.

    ``name`` is what the segments it integrates record; ``pointwise`` says it sees the guards
    only at output points (the stick guard is then watched in its smooth form with a rate, see
    :func:`phasekit.core.system.watched`). The batch engine
    (:class:`~phasekit.core.engines.batch.TaylorBatchEngine`) has the same name and pointwise flag, and
    its ``propagate`` takes every lane of an integrator at once.

    Attributes
    ----------
    name : str
        What the segments it integrates record.
    pointwise : bool
        Whether it sees the guards only at output points.

    Examples
    --------
    >>> import phasekit as pk
    >>> engine = pk.core.engines.engine_for('cvodes', 1e-9)
    >>> engine.name, engine.pointwise
    ('cvodes', True)
    """

    name: str
    pointwise: bool

    def propagate(self, flow: CompiledFlow, x0, t0: float, t_end: float, p, levels, *, budget: Budget,
                  dense: bool = False, resume: bool = False) -> Propagation:
        """Integrate ``flow`` from (t0, x0) to ``t_end`` or its first guard's zero.

        Parameters
        ----------
        flow : CompiledFlow
            The field, guards and monitor of one mode.
        x0 : array_like
            The start state.
        t0, t_end : float
            The start and end times.
        p : array_like
            The model's parameters.
        levels : array_like
            The guards' levels, one per guard.
        budget : Budget
            The steps and wall time left; running out ends the call with ``End.FAILED``.
        dense : bool, optional
            Keep dense output in :attr:`Propagation.dense`.
        resume : bool, optional
            Continue from where the last call on this flow stopped, without firing the event just located again.

        Returns
        -------
        Propagation
            The time and state reached and how the call ended; a failure is reported there, not raised.
        """
        ...
