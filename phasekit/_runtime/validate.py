"""Input checks shared by every public entry point.

Each returns the value converted (float, array, ...) or raises :class:`ParameterError`
naming the parameter, its valid range and the value given, in plain numbers.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError


def _is_real(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def check_real(name: str, value) -> float:
    """Any real number (inf allowed), as a float."""
    if not _is_real(value) or math.isnan(float(value)):
        raise ParameterError(name, "must be a real number", value)
    return float(value)


def check_finite(name: str, value, *, nonzero: bool = False) -> float:
    """A finite real number (``nonzero``: and not 0)."""
    if not _is_real(value) or not math.isfinite(float(value)) or (nonzero and float(value) == 0.0):
        raise ParameterError(name, "must be a finite nonzero number" if nonzero else "must be a finite real number", value)
    return float(value)


def check_positive(name: str, value, *, upper: float | None = None) -> float:
    """A finite number > 0 (and <= ``upper`` when given)."""
    if not _is_real(value) or not math.isfinite(float(value)) or not float(value) > 0:
        what = f"must lie in (0, {upper:g}]" if upper is not None else "must be a finite number > 0"
        raise ParameterError(name, what, value)
    if upper is not None and float(value) > upper:
        raise ParameterError(name, f"must lie in (0, {upper:g}]", value)
    return float(value)


def check_nonnegative(name: str, value, *, upper: float | None = None) -> float:
    """A finite number >= 0 (and <= ``upper`` when given)."""
    ok = _is_real(value) and math.isfinite(float(value)) and float(value) >= 0
    if not ok or (upper is not None and float(value) > upper):
        what = f"must lie in [0, {upper:g}]" if upper is not None else "must be a finite number >= 0"
        raise ParameterError(name, what, value)
    return float(value)


def check_range(name: str, value, lo: float, hi: float, *, closed: str = "", label: str | None = None) -> float:
    """A finite number in the interval from lo to hi; ``closed`` holds "l" and/or "r" for
    closed ends; ``label`` spells the interval in the message (e.g. "(0, pi)")."""
    if not _is_real(value) or not math.isfinite(float(value)):
        ok = False
    else:
        v = float(value)
        ok = (lo <= v if "l" in closed else lo < v) and (v <= hi if "r" in closed else v < hi)
    if not ok:
        label = label or f"{'[' if 'l' in closed else '('}{lo:g}, {hi:g}{']' if 'r' in closed else ')'}"
        raise ParameterError(name, f"must lie in {label}", value)
    return float(value)


def check_int(name: str, value, *, minimum: int = 0, maximum: int | None = None) -> int:
    """An integer >= minimum (and <= maximum)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        if _is_real(value) and math.isfinite(float(value)) and float(value) == int(value):
            value = int(value)
        else:
            raise ParameterError(name, f"must be an integer >= {minimum}", value)
    value = int(value)
    if value < minimum or (maximum is not None and value > maximum):
        rng = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ParameterError(name, f"must be an integer {rng}", value)
    return value


def check_bool(name: str, value) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise ParameterError(name, "must be True or False", value)
    return bool(value)


def check_choice(name: str, value, choices: Sequence[str]) -> str:
    """One of a fixed set of strings."""
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(name, f"must be one of {', '.join(choices)}", value)
    return value


def check_vector(name: str, value, length: int) -> np.ndarray:
    """A finite real vector of the given length, returned as a float array (a copy)."""
    if value is None or isinstance(value, (str, bytes, dict)):
        raise ParameterError(name, f"must be {length} finite real numbers", value)
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, f"must be {length} finite real numbers", value) from None
    if arr.shape != (length,):
        raise ParameterError(name, f"must have exactly {length} entries (got shape {arr.shape})", value, show_value=False)
    if not np.all(np.isfinite(arr)):
        raise ParameterError(name, f"must be {length} finite real numbers", arr)
    return arr


def check_times(name: str, value, *, allow_empty: bool = False) -> np.ndarray:
    """A 1-d array of finite times, sorted."""
    if value is None or isinstance(value, (str, bytes, dict)):
        raise ParameterError(name, "must be a list of finite times", value)
    try:
        arr = np.atleast_1d(np.array(value, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(name, "must be a list of finite times", value) from None
    if arr.ndim != 1 or not np.all(np.isfinite(arr)):
        raise ParameterError(name, "must be a list of finite times", value)
    if arr.size == 0 and not allow_empty:
        raise ParameterError(name, "must hold at least one time", value)
    return np.sort(arr)


def check_array(name: str, value, *, allow_empty: bool = False, nonnegative: bool = False, ndim: int | None = None) -> np.ndarray:
    """Finite real numbers (a scalar or an array of any shape, order kept) as a float array;
    ``nonnegative``: all >= 0; ``ndim``: of exactly that many dimensions."""
    what = "finite numbers >= 0" if nonnegative else "finite real numbers"
    if value is None or isinstance(value, (str, bytes, dict, set, bool, np.bool_)):
        raise ParameterError(name, f"must be {what}", value)
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, f"must be {what}", value) from None
    if ndim is not None and arr.ndim != ndim:
        raise ParameterError(name, f"must be a {ndim}-d array of {what} (got shape {arr.shape})", show_value=False)
    if arr.size == 0 and not allow_empty:
        raise ParameterError(name, "must hold at least one value", value)
    if not np.all(np.isfinite(arr)) or (nonnegative and np.any(arr < 0)):
        raise ParameterError(name, f"must be {what}", arr)
    return arr


def check_instance(name: str, value, cls: type, example: str):
    """An instance of ``cls`` (``example`` shows how to make one, e.g. "Spheroid(1.5)")."""
    if not isinstance(value, cls):
        raise ParameterError(name, f"must be a phasekit {cls.__name__} such as {example}", value)
    return value


def _all_finite(out) -> bool:
    """Are all numbers in a result finite (scalars, arrays, sequences, dicts, dataclasses)?"""
    import dataclasses

    if out is None or isinstance(out, (bool, np.bool_, str)):
        return True
    if isinstance(out, (int, float, np.integer, np.floating, complex, np.complexfloating)):
        return bool(np.isfinite(out))
    if isinstance(out, np.ndarray):
        return out.dtype.kind not in "fc" or bool(np.all(np.isfinite(out)))
    if isinstance(out, dict):
        return all(_all_finite(v) for v in out.values())
    if isinstance(out, (list, tuple)):
        return all(_all_finite(v) for v in out)
    if dataclasses.is_dataclass(out):
        return all(_all_finite(getattr(out, f.name)) for f in dataclasses.fields(out))
    return True


def _magnitude(value) -> float:
    try:
        a = np.abs(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        return -1.0
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else -1.0


_NESTED = threading.local()


def finite_result(func):
    """Decorate a theory helper: a result that is not finite (an overflow of double precision,
    or a singular configuration) is a ParameterError naming the argument of largest magnitude,
    never a NaN or inf handed back (nor an OverflowError)."""
    import functools
    import inspect

    sig = inspect.signature(func)

    @functools.wraps(func)
    def checked(*args, **kwargs):
        if getattr(_NESTED, "depth", 0):  # called by another checked helper: that one names its own argument
            return func(*args, **kwargs)
        _NESTED.depth = 1
        try:
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                out = func(*args, **kwargs)
        except (OverflowError, FloatingPointError, ZeroDivisionError):
            out, ok = None, False
        else:
            ok = _all_finite(out)
        finally:
            _NESTED.depth = 0
        if ok:
            return out
        bound = sig.bind(*args, **kwargs).arguments
        sizes = {k: _magnitude(v) for k, v in bound.items() if k != "body"}
        name = max(sizes, key=sizes.get) if sizes else next(iter(bound), "arguments")
        if sizes.get(name, -1.0) > 1e10:
            raise ParameterError(name, "is too large in size: the result overflows double precision", bound[name])
        raise ParameterError(name, "gives a non-finite result here (a singular configuration of the theory)",
                             bound.get(name))

    return checked
