"""Error types, run statuses and the input checks shared by every public entry point.

Bad input raises :class:`ValueError` at once, naming the parameter in backticks and
giving its valid range. Numerical trouble never raises from a sweep: it ends as a
result whose status is :attr:`Status.FAILED` with a reason.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence

import numpy as np

__all__ = [
    "PhasekitError",
    "ConvergenceError",
    "BracketError",
    "Status",
    "check_finite",
    "check_positive",
    "check_nonnegative",
    "check_open_interval",
    "check_choice",
    "check_vector",
]


class PhasekitError(Exception):
    """Base class of phasekit's own errors (never raised for bad input: that is ValueError)."""


class ConvergenceError(PhasekitError):
    """A Newton solve or an integration did not converge; ``result`` holds what was obtained."""

    def __init__(self, message: str, result: object = None):
        super().__init__(message)
        self.result = result


class BracketError(PhasekitError):
    """A threshold search found no sign change in the interval it was given."""


class Status(str, enum.Enum):
    """How a run ended. The value is what the JSON output prints."""

    JUMPED = "jumped"  # R reached zero with dR/dt < 0: contact lost
    COMPLETED = "completed"  # reached the end time (or the rise completed) in contact
    TOUCHDOWN = "touchdown"  # stopped at the first re-contact after a flight
    FAILED = "failed"  # the integrator could not continue; see the reason

    def __str__(self) -> str:
        return self.value


def _is_real(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def check_finite(name: str, value) -> float:
    """Return ``value`` as a float, or raise ValueError if it is not a finite real number."""
    if not _is_real(value) or not math.isfinite(float(value)):
        raise ValueError(f"`{name}` must be a finite real number, got {value!r}.")
    return float(value)


def check_positive(name: str, value) -> float:
    """A finite number > 0."""
    if not _is_real(value) or not math.isfinite(float(value)) or not float(value) > 0:
        raise ValueError(f"`{name}` must be a finite number > 0, got {value!r}.")
    return float(value)


def check_nonnegative(name: str, value) -> float:
    """A finite number >= 0."""
    if not _is_real(value) or not math.isfinite(float(value)) or not float(value) >= 0:
        raise ValueError(f"`{name}` must be a finite number >= 0, got {value!r}.")
    return float(value)


def check_open_interval(name: str, value, lo: float, hi: float, label: str | None = None) -> float:
    """A finite number strictly inside (lo, hi); ``label`` spells the interval in the message."""
    label = label or f"({lo:g}, {hi:g})"
    if not _is_real(value) or not math.isfinite(float(value)) or not lo < float(value) < hi:
        raise ValueError(f"`{name}` must lie in {label}, got {value!r}.")
    return float(value)


def check_choice(name: str, value, choices: Sequence[str]) -> str:
    """One of a fixed set of strings."""
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"`{name}` must be one of {', '.join(choices)}; got {value!r}.")
    return value


def check_vector(name: str, value, length: int) -> np.ndarray:
    """A finite real vector of the given length, returned as a float array (a copy)."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"`{name}` must be {length} finite real numbers, got {value!r}.") from None
    if arr.shape != (length,):
        raise ValueError(f"`{name}` must have exactly {length} entries, got shape {arr.shape}.")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"`{name}` must be finite, got {value!r}.")
    return arr
