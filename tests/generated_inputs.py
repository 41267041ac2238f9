"""Generated test inputs (Hypothesis), with Hypothesis imported only when a generated test runs.

Collecting the tests imports no Hypothesis (its import and pytest's rewriting of its modules
cost about a second): a generated test is written as usual, with each strategy given as a
function that builds it, and ``st`` stands for ``hypothesis.strategies`` inside those functions::

    @generated(lambda: st.integers(0, 10), max_examples=50, derandomize=True)
    def test_something(fixture, n):
        ...

The test's own source, name and signature are what a derandomised run's examples derive from,
so such a test generates the examples that the same function under ``@settings``/``@given``
would. The strategy helpers below are shared by the generated suites of the CLI and the API.
"""

from __future__ import annotations

import importlib
import inspect
import math
import os
import signal

import numpy as np


class _Lazy:
    """A module imported on first attribute access."""

    def __init__(self, name: str):
        self._name = name

    def __getattr__(self, attr):
        if attr.startswith("_") or attr == "pytestmark":  # what pytest asks of every name in a test module
            raise AttributeError(attr)
        return getattr(importlib.import_module(self._name), attr)


st = _Lazy("hypothesis.strategies")


def generated(*strategies, **settings):
    """Run the decorated test on generated examples: ``strategies`` are functions that build the
    strategies of its last parameters (as ``@given`` takes them), ``settings`` are Hypothesis
    settings (``suppress_health_check`` by name, or "all"). Its leading parameters stay pytest
    fixtures."""

    def decorate(test):
        params = list(inspect.signature(test).parameters.values())
        fixtures = params[: len(params) - len(strategies)]

        def run(*args, **kwargs):
            import hypothesis

            options = dict(settings)
            checks = options.get("suppress_health_check")
            if checks is not None:
                options["suppress_health_check"] = list(hypothesis.HealthCheck) if checks == "all" else \
                    [hypothesis.HealthCheck[name] for name in checks]
            cases = hypothesis.settings(**options)(hypothesis.given(*(s() for s in strategies))(test))
            return cases(*args, **kwargs)

        run.__signature__ = inspect.Signature(fixtures)
        run.runs_generated_cases = True  # its timeout is a CaseHung (see hang_timer)
        for attr in ("__name__", "__qualname__", "__doc__", "__module__"):
            setattr(run, attr, getattr(test, attr))
        return run

    return decorate


#: examples per test (scale with PHASEKIT_FUZZ_SCALE, e.g. 0.2 for a smoke run, 5 for a long one)
SCALE = float(os.environ.get("PHASEKIT_FUZZ_SCALE", "1"))


class CaseHung(BaseException):
    """A generated test outlived its timeout. Hypothesis takes pytest's failures, pytest-timeout's
    among them, for a failing case, which it shrinks and replays (and hangs again); an exception of
    this kind passes through it and fails the test."""


def hang_timer(item, timeout: float) -> None:
    """Fail the generated test ``item`` with CaseHung after ``timeout`` seconds (SIGALRM, as
    pytest-timeout's signal method does); pytest-timeout cancels it through ``item.cancel_timeout``."""

    def hung(signum, frame):
        raise CaseHung(f"Timeout (>{timeout:g} s): a generated case hung")

    def cancel():
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, signal.SIG_DFL)

    item.cancel_timeout = cancel
    signal.signal(signal.SIGALRM, hung)
    signal.setitimer(signal.ITIMER_REAL, timeout)


def hang_guard(seconds: float):
    """A timeout for a generated suite that takes a small part of ``seconds`` (times SCALE, which
    scales its number of cases): a case that hangs fails the suite, instead of stopping the run."""
    import pytest

    return pytest.mark.timeout(seconds * max(1.0, SCALE))


def fuzz(n: int) -> dict:
    """The settings of a generated suite of ``n`` cases (times SCALE): derandomised, no database."""
    return dict(max_examples=max(1, int(n * SCALE)), deadline=None, derandomize=True, database=None,
                suppress_health_check=("too_slow", "filter_too_much", "function_scoped_fixture", "data_too_large"))


def report(counts: dict, title: str, path: str | None, extra: dict | None = None, lines_after=()) -> None:
    """Print the outcome counts of each suite (``pytest -s`` shows them) and write them to ``path``
    as JSON when given."""
    import collections
    import json

    total = collections.Counter()
    lines = ["", title]
    for suite, c in sorted(counts.items()):
        total.update(c)
        lines.append(f"  {suite:<28s} {sum(c.values()):5d} cases: {c['valid']:4d} valid, {c['failed']:4d} failed, "
                     f"{c['error']:4d} error")
    lines.append(f"  {'total':<28s} {sum(total.values()):5d} cases: {total['valid']:4d} valid, "
                 f"{total['failed']:4d} failed, {total['error']:4d} error")
    print("\n".join([*lines, *lines_after]))
    if path:
        with open(path, "w") as fh:
            json.dump({"suites": {k: dict(v) for k, v in counts.items()}, "total": dict(total), **(extra or {})}, fh,
                      indent=2)


def thin_suites(counts: dict) -> dict:
    """The suites whose valid results are fewer than 3 or a tenth of their cases."""
    return {suite: dict(c) for suite, c in counts.items() if c["valid"] < max(3, 0.1 * sum(c.values()))}


# -- values ---------------------------------------------------------------------------------------

SPECIAL = [0.0, -0.0, 1e-300, -1e-300, 1e-12, -1.0, 1e6, -1e6, 1e300, -1e300, math.nan, math.inf, -math.inf]


def mostly(good, *bad, n_good: int = 18):
    """``good`` in ~n_good of n_good + len(bad) cases, so that most generated cases have at
    most one bad field (st.one_of would not do: it merges repeated branches)."""
    branches = (good, *bad)
    return st.sampled_from([0] * n_good + list(range(1, len(branches)))).flatmap(lambda i: branches[i])


def weighted(*pairs):
    """One of the strategies, each with its weight: ``weighted((s1, 4), (s2, 1))``."""
    branches = [b for b, _ in pairs]
    return st.sampled_from([i for i, (_, w) in enumerate(pairs) for _ in range(w)]).flatmap(lambda i: branches[i])


def reals(*typical):
    """Mostly typical values, else an extreme one or any float at all."""
    return mostly(st.sampled_from(typical), st.sampled_from(SPECIAL), st.floats(allow_nan=True, allow_infinity=True))


def junk():
    """Text that is no number."""
    return st.sampled_from(["abc", "", "1e", "0x10", "--", "1,5", "None", "[1]", "-", "1e400", "nan(1)"])


def text_of(values):
    """A CLI value: repr of a number, rarely junk."""
    return mostly(values.map(repr), junk(), n_good=30)


def wrong():
    """Values of a wrong type or shape."""
    return st.sampled_from([None, "1.5", [1.0], (), {}, True, object(), np.array([1.0, 2.0]), 1j, b"x"])


def real_or_wrong(*typical):
    return mostly(reals(*typical), wrong(), n_good=12)


def finite_everywhere(obj) -> bool:
    if isinstance(obj, float):
        return math.isfinite(obj)
    if isinstance(obj, dict):
        return all(finite_everywhere(v) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return all(finite_everywhere(v) for v in obj)
    return True
