"""Error types and the status vocabularies: one for a simulation, one for a search.

Bad input raises :class:`ParameterError` (a :class:`ValueError`) at once, naming the
parameter and its valid range. Numerical trouble is a result whose ``status`` is
:attr:`Status.FAILED` with a reason; with ``throw=True`` it raises
:class:`ConvergenceError` carrying that result instead.
"""

from __future__ import annotations

import enum

__all__ = ["PhasekitError", "ConvergenceError", "ParameterError", "WorkerError", "Status", "SearchStatus"]


class PhasekitError(Exception):
    """Base class of phasekit's own errors (bad input is :class:`ParameterError` instead).

    Parameters
    ----------
    *args
        The message, as for :class:`Exception`.

    Examples
    --------
    >>> import phasekit as pk
    >>> issubclass(pk.ConvergenceError, pk.PhasekitError), issubclass(pk.WorkerError, pk.PhasekitError)
    (True, True)
    """


class ConvergenceError(PhasekitError):
    """A Newton solve or an integration did not converge; ``result`` holds what was obtained.

    Parameters
    ----------
    message : str
        What did not converge, and why.
    result : object, optional
        What was obtained (e.g. the failed Trajectory); default None.

    Attributes
    ----------
    result : object
        As given.

    Examples
    --------
    >>> import phasekit as pk
    >>> th = pk.Definition('sliding', 'sliding')
    >>> err = pk.ConvergenceError('did not converge', result=th)
    >>> err.result is th
    True
    """

    def __init__(self, message: str, result: object = None):
        super().__init__(message)
        self.result = result


class WorkerError(PhasekitError):
    """A worker process died while it computed (killed, out of memory, a crash in compiled
    code); ``result`` holds what was obtained (e.g. the rows of an ensemble that finished).

    Parameters
    ----------
    message : str
        What happened to the worker.
    result : object, optional
        What was obtained before it died; default None.

    Attributes
    ----------
    result : object
        As given.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.WorkerError('worker died', result=[]).result
    []
    """

    def __init__(self, message: str, result: object = None):
        super().__init__(message)
        self.result = result


class ParameterError(ValueError):
    """An invalid argument. ``param`` is its name as the Python API spells it, ``expected`` the
    valid range in words and ``value`` what was given, so that a front end (the CLI) can
    re-word the message with its own flag name.

    Parameters
    ----------
    param : str
        The parameter's name as the Python API spells it.
    expected : str
        The valid range in words, e.g. "must lie in [0, 1000]".
    value : object, optional
        What was given (default None).
    show_value : bool, optional
        Whether the message ends with ", got <value>" (default True).

    Attributes
    ----------
    param, expected, value, show_value
        As given; the message is "`param` expected, got value.".

    Examples
    --------
    >>> import phasekit as pk
    >>> err = pk.ParameterError('mu', 'must lie in [0, 1000]', -1.0)
    >>> str(err), err.param
    ('`mu` must lie in [0, 1000], got -1.0.', 'mu')
    """

    def __init__(self, param: str, expected: str, value: object = None, *, show_value: bool = True):
        self.param, self.expected, self.value, self.show_value = param, expected, value, show_value
        super().__init__(self.render(f"`{param}`"))

    def render(self, name: str) -> str:
        got = f", got {plain(self.value)}" if self.show_value else ""
        return f"{name} {self.expected}{got}."


def plain(value) -> str:
    """A value as a user typed it: 0.1, not np.float64(0.1); lists and strings readable."""
    import numpy as np

    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        inner = ", ".join(plain(v) for v in value[:12]) + (", ..." if len(value) > 12 else "")
        return f"[{inner}]"
    if value is None:
        return "None"
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


class _Vocabulary(str, enum.Enum):
    """A status vocabulary: the value is what JSON and tables print, ``message`` says it in words."""

    def __new__(cls, value: str, message: str):
        obj = str.__new__(cls, value)
        obj._value_ = value
        obj.message = message
        return obj

    def __str__(self) -> str:
        return self.value

    @property
    def ok(self) -> bool:
        return self.value != "failed"


class Status(_Vocabulary):
    """How a simulation (or another computation, e.g. a steady structure) ended.

    Each member is a string (its value, what JSON and tables print) with a ``message`` saying
    it in words, and ``ok`` (False only for FAILED).

    Attributes
    ----------
    JUMPED
        "jumped": R reached 0 with dR/dt < 0: the body lost contact.
    TOUCHDOWN
        "touchdown": stopped at the first re-contact after a flight.
    STOPPED
        "stopped": a stop condition was met.
    COMPLETED
        "completed": reached the end time.
    SETTLED
        "settled": the body settled: it rolls in a steady state (the option settle).
    REST
        "rest": the body came to rest (with dissipation laws, :meth:`phasekit.Coulomb.with_dissipation`).
    FAILED
        "failed": the computation could not continue; see the reason.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.Status.JUMPED.value, pk.Status.JUMPED.message
    ('jumped', 'R reached 0 with dR/dt < 0: the body lost contact')
    """

    JUMPED = ("jumped", "R reached 0 with dR/dt < 0: the body lost contact")
    TOUCHDOWN = ("touchdown", "stopped at the first re-contact after a flight")
    STOPPED = ("stopped", "a stop condition was met")
    COMPLETED = ("completed", "reached the end time")
    SETTLED = ("settled", "the body settled: it rolls in a steady state (the option settle)")
    REST = ("rest", "the body came to rest: every motion stopped, held by friction and rolling resistance")
    FAILED = ("failed", "the computation could not continue; see the reason")


class SearchStatus(_Vocabulary):
    """How a search for a threshold or a boundary (a bisection) ended.

    Each member is a string (its value) with a ``message`` saying it in words, and ``ok``
    (False only for FAILED).

    Attributes
    ----------
    CONVERGED
        "converged": the bracket is narrower than the tolerance.
    NON_MONOTONE
        "non_monotone": more than one jump / no-jump transition.
    BRACKET_ONLY
        "bracket_only": a run failed inside the bracket; the bracket is as far as it was narrowed.
    NO_JUMP_IN_RANGE
        "no_jump_in_range": no run in the searched range jumped.
    JUMPS_AT_LOWER_BOUND
        "jumps_at_lower_bound": every run in the searched range jumped.
    FAILED
        "failed": the search could not continue; see the reason.

    Examples
    --------
    >>> import phasekit as pk
    >>> str(pk.SearchStatus.CONVERGED), pk.SearchStatus.BRACKET_ONLY.ok
    ('converged', True)
    """

    CONVERGED = ("converged", "the bracket is narrower than the tolerance")
    NON_MONOTONE = ("non_monotone", "more than one jump / no-jump transition")
    BRACKET_ONLY = ("bracket_only", "a run failed inside the bracket; the bracket is as far as it was narrowed")
    NO_JUMP_IN_RANGE = ("no_jump_in_range", "no run in the searched range jumped")
    JUMPS_AT_LOWER_BOUND = ("jumps_at_lower_bound", "every run in the searched range jumped")
    FAILED = ("failed", "the search could not continue; see the reason")
