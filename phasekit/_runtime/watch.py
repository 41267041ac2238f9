"""Long calls report and end: progress bars where a person waits, and wall budgets.

Progress
--------
``progress=None`` (the default of every long call) shows a tqdm bar on stderr only where a
person is watching: stderr is a terminal, or the call runs in a Jupyter kernel (where tqdm
draws a widget if ipywidgets is installed, else text). ``progress=True`` asks for a bar
anyway (a log file then gets tqdm's lines), ``progress=False`` turns it off. Where no bar is
shown, the CLI asks for a heartbeat (:func:`heartbeats`): a line every few seconds of a long run.

Wall budgets
------------
``max_wall`` of a search, a map or an ensemble is a deadline for the whole call.
:func:`wall_deadline` sets it for everything computed inside (a context variable, so nested
calls keep the earliest), and :func:`phasekit.simulate` ends a run that reaches it with
status "failed" and a reason naming the budget; the caller then returns what it has, with a
status that says the budget ran out.
"""

from __future__ import annotations

import contextlib
import contextvars
import math
import sys
import time

from .validate import check_positive

#: the start of the reason of a run or a search ended by the caller's wall budget
WALL_REASON = "the call's wall budget"

#: seconds between heartbeat lines where no bar is shown (None: none; the CLI sets it, see :func:`heartbeats`)
_HEARTBEAT: contextvars.ContextVar[float | None] = contextvars.ContextVar("phasekit_heartbeat", default=None)


@contextlib.contextmanager
def heartbeats(every: float):
    """Within the block, a long run that shows no bar (stderr a file, no terminal) writes one
    line on stderr every ``every`` seconds: how far it is and for how long it has run. The CLI
    sets it, so a run with --json into a log is not silent; the library's default is silent."""
    token = _HEARTBEAT.set(float(every))
    try:
        yield
    finally:
        _HEARTBEAT.reset(token)


class Heartbeat:
    """One stderr line every ``every`` s of wall time: "phasekit: simulate: t = ... of ...", written
    whole (a line per call to write)."""

    def __init__(self, t0: float, t_end: float, desc: str, every: float):
        self.t0, self.t_end, self.desc, self.every = t0, t_end, desc, every
        self.start = time.perf_counter()
        self.due = self.start + every

    def __call__(self, t: float) -> None:
        now = time.perf_counter()
        if now < self.due:
            return
        self.due = now + self.every
        span = self.t_end - self.t0
        done = f" ({100 * (t - self.t0) / span:.0f}%)" if math.isfinite(span) and span > 0 else ""
        sys.stderr.write(f"phasekit: {self.desc}: t = {t:.6g} of {self.t_end:.6g}{done} after {now - self.start:.0f} s "
                         "of wall-clock time\n")
        sys.stderr.flush()


def heartbeat(t0: float, t_end: float, desc: str) -> Heartbeat | None:
    """The heartbeat of a run where :func:`heartbeats` asked for one, else None."""
    every = _HEARTBEAT.get()
    return None if every is None else Heartbeat(t0, t_end, desc, every)

_DEADLINE: contextvars.ContextVar[tuple[float, float] | None] = contextvars.ContextVar("phasekit_deadline", default=None)


def in_jupyter() -> bool:
    """Does this process run a Jupyter (IPython) kernel?"""
    shell = sys.modules.get("IPython")
    if shell is None or "ipykernel" not in sys.modules:
        return False
    try:
        ip = shell.get_ipython()
    except Exception:  # an IPython too old or too new to ask: assume no kernel
        return False
    return ip is not None and type(ip).__name__ == "ZMQInteractiveShell"


def show_progress(progress) -> bool:
    """Resolve a ``progress`` argument: None shows a bar only on a terminal or in a notebook."""
    if progress is None:
        try:
            tty = sys.stderr.isatty()
        except (AttributeError, ValueError):  # a closed or replaced stderr
            tty = False
        return tty or in_jupyter()
    if not isinstance(progress, bool):
        from ..errors import ParameterError

        raise ParameterError("progress", "must be True, False or None (a bar on a terminal or in a notebook only)",
                             progress)
    return progress


def progress_bar(total=None, *, iterable=None, desc: str = "", unit: str = "run", progress=None, delay: float = 0.0):
    """phasekit's one progress bar: a tqdm bar on stderr (stdout stays the caller's report; a widget
    in a notebook when ipywidgets is there), over ``iterable`` if given, cleared when done;
    disabled per :func:`show_progress`; shown only after ``delay`` seconds."""
    enabled = show_progress(progress)
    if enabled and in_jupyter():
        try:
            import ipywidgets  # noqa: F401  (tqdm.notebook needs it; without it tqdm warns and draws text)
            from tqdm.notebook import tqdm
        except ImportError:
            from tqdm import tqdm
    else:
        from tqdm import tqdm
    return tqdm(iterable, total=total, desc=desc, unit=unit, disable=not enabled, file=sys.stderr, leave=False,
                dynamic_ncols=True, delay=delay)


def check_max_wall(value, name: str = "max_wall") -> float | None:
    """None (no budget) or a wall time in seconds > 0."""
    return None if value is None else check_positive(name, value)


@contextlib.contextmanager
def wall_deadline(max_wall: float | None):
    """Within the block, every run ends by ``max_wall`` seconds from now (or an earlier
    deadline set outside). Yields the deadline as a ``time.perf_counter()`` value (inf: none)."""
    outer = _DEADLINE.get()
    if max_wall is None:
        yield outer[0] if outer else math.inf
        return
    mine = (time.perf_counter() + max_wall, max_wall)
    token = _DEADLINE.set(mine if outer is None or mine[0] < outer[0] else outer)
    try:
        yield _DEADLINE.get()[0]
    finally:
        _DEADLINE.reset(token)


#: [start, unclaimed] of the command that runs a simulation (the CLI's): its first run's own wall
#: budget counts from that start (:func:`claim_start`)
_STARTED: contextvars.ContextVar[list | None] = contextvars.ContextVar("phasekit_started", default=None)


@contextlib.contextmanager
def wall_started():
    """Within the block, the first run's own wall budget (``max_wall``) counts from now, not from the
    run's start: the CLI sets it, so that the work before a run (the inputs, the model) and after it
    (its energy budget, its poses: :func:`spent`) count in --max-wall. Yields the start
    (``time.perf_counter()``)."""
    token = _STARTED.set([time.perf_counter(), True])
    try:
        yield _STARTED.get()[0]
    finally:
        _STARTED.reset(token)


def claim_start() -> float | None:
    """The start of :func:`wall_started`'s block the first time it is asked (the command's run),
    None after (a run that run makes, its verification, counts from its own start) or outside one."""
    holder = _STARTED.get()
    if holder is None or not holder[1]:
        return None
    holder[1] = False
    return holder[0]


def spent() -> float:
    """Seconds since :func:`wall_started`'s block began (0 outside one)."""
    holder = _STARTED.get()
    return 0.0 if holder is None else time.perf_counter() - holder[0]


def deadline() -> tuple[float, float] | None:
    """The deadline in force, (``time.perf_counter()`` value, the budget in seconds), or None."""
    return _DEADLINE.get()


def passed() -> bool:
    """Has the deadline in force passed?"""
    d = _DEADLINE.get()
    return d is not None and time.perf_counter() > d[0]


def check_deadline() -> None:
    """Raise TimeoutError, its message naming the wall budget, once the deadline in force has
    passed; return at once when there is none. The steady-state searches call it between their
    Newton solves and linearisations (each a few milliseconds), so a budget holds to about that."""
    d = _DEADLINE.get()
    if d is not None and time.perf_counter() > d[0]:
        raise TimeoutError(f"{WALL_REASON} (max_wall = {d[1]:g} s) ran out")
