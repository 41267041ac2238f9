"""Ctrl-C that is never lost: the guard phasekit's programs (the CLI, the studies) run under.

CPython raises KeyboardInterrupt at the next line of Python after SIGINT. When that line runs
inside CasADi's Python layer, called by SWIG while it converts an argument (e.g.
``DM_from_array`` during a Function call), SWIG takes the exception for "this overload does not
fit": it tries the next one, or raises a TypeError / NotImplementedError of its own, or goes
on as if nothing happened (measured: 3 of 40 interrupts of a loop of ``steady_structure``
calls vanished, 11 became other errors). :func:`interrupt_guard` remembers the signal and
raises KeyboardInterrupt again until it gets through.

Where Python cannot raise at all (a weakref callback, as the import system's module locks have, a
``__del__``), it reports the exception through ``sys.unraisablehook`` ("Exception ignored in ...",
with a traceback) and goes on; since the guard raises the interrupt again, that report is dropped.
"""

from __future__ import annotations

import _thread
import contextlib
import io
import signal
import sys
import threading
import time


def chained_to_interrupt(exc) -> bool:
    """Is ``exc`` a KeyboardInterrupt, or raised while one was being handled?"""
    while exc is not None:
        if isinstance(exc, KeyboardInterrupt):
            return True
        exc = exc.__context__
    return False


class _Muted(io.TextIOBase):
    """A stand-in for sys.stderr that drops what is written (see :func:`interrupt_guard`)."""

    def write(self, text) -> int:
        return len(text)


#: frames the re-raise leaves alone: CasADi's Python layer (SWIG may swallow an exception raised
#: there), and the guard's own exit (``contextlib`` and this module), which must always run
_UNTOUCHED = ("casadi", "contextlib", __name__)
#: how often a Ctrl-C that has not reached the program's handler yet is raised again
RETRY_S = 0.25


def _untouched(frame) -> bool:
    return str(frame.f_globals.get("__name__", "")).startswith(_UNTOUCHED)


def _resend(stop, state: dict) -> None:
    """A simulated Ctrl-C every RETRY_S until the program has handled one (``state["handled"]``) or
    ``stop`` is set (:func:`interrupt_guard`)."""
    while not stop.wait(RETRY_S):
        if state["handled"]:
            return
        _thread.interrupt_main()


@contextlib.contextmanager
def _swallowed_interrupts_unreported():
    """Drop sys.unraisablehook's reports of a KeyboardInterrupt (raised where Python cannot raise:
    the guard raises it again)."""
    previous = sys.unraisablehook

    def hook(report) -> None:
        if not isinstance(report.exc_value, KeyboardInterrupt):
            previous(report)

    sys.unraisablehook = hook
    try:
        yield
    finally:
        sys.unraisablehook = previous


@contextlib.contextmanager
def interrupt_guard(late_s: float = 0.5, *, mute: bool = True):
    """While the block runs, Ctrl-C (SIGINT) raises KeyboardInterrupt as usual, and also:

    * (``mute``) mutes what this process writes to sys.stderr while the run winds down (Dask's
      warnings while it stops workers in mid-task, CasADi's "rhs failed: KeyboardInterrupt"),
      so that the program's one line is all that is printed;
    * makes sure the interrupt is not lost (module notes): until the block ends, the
      KeyboardInterrupt is raised again at the first line of Python outside CasADi's own frames
      that runs in a handler of another exception (where an error made of it is caught), or,
      ``late_s`` after the signal, at such a line anywhere; and every RETRY_S (a simulated
      SIGINT from a helper thread) until the program handles it (``handled``) or the block ends,
      never in its own cleanup (the ``except``, ``finally``, ``__exit__`` blocks on its way out);
      one Python had to drop is not reported (module notes). A second Ctrl-C raises at once.

    Yields a dict whose ``seen`` is True once a Ctrl-C arrived (whatever compiled code made of
    it); the program's handler of KeyboardInterrupt sets its ``handled`` to stop the re-raising.
    """
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield {}
        return
    state = {"at": None, "seen": False, "handled": False}
    stop = threading.Event()
    stderr, previous_trace = sys.stderr, sys.gettrace()

    def again(frame, event, arg):  # a trace function: runs before each line of Python in this thread
        if state["at"] is None or state["handled"]:
            return None
        if _untouched(frame):
            return again
        exc = sys.exc_info()[1]
        if chained_to_interrupt(exc):
            return again
        if exc is not None or time.monotonic() - state["at"] > late_s:
            raise KeyboardInterrupt  # (this switches tracing off: `interrupted` switches it on again)
        return again

    def arm(frame) -> None:
        f = frame
        while f is not None:  # trace the frames running now, and every frame called from now on
            f.f_trace = again
            f = f.f_back
        sys.settrace(again)

    def interrupted(signum, frame):
        state["seen"] = True
        if state["at"] is None:
            import logging

            state["at"] = time.monotonic()
            for name in ("distributed", "tornado", "asyncio"):
                logging.getLogger(name).setLevel(logging.CRITICAL + 1)
            if mute:
                sys.stderr = _Muted()
            state["watchdog"] = threading.Thread(target=_resend, args=(stop, state), name="phasekit-interrupt", daemon=True)
            state["watchdog"].start()
        if state["handled"]:
            return
        arm(frame)
        if frame is None or frame.f_code is again.__code__ or _untouched(frame) or chained_to_interrupt(sys.exc_info()[1]):
            return  # inside the trace function, where SWIG would swallow it, or in the cleanup: next time
        raise KeyboardInterrupt

    signal.signal(signal.SIGINT, interrupted)
    try:
        with _swallowed_interrupts_unreported():
            yield state
    finally:
        stop.set()
        if state.get("watchdog") is not None:  # its last simulated Ctrl-C meets `interrupted`, which lets
            state["watchdog"].join()  # it pass once handled, not the default handler (exit by SIGINT)
        if state["at"] is not None:
            state["at"] = None
            sys.settrace(previous_trace)
        sys.stderr = stderr
        signal.signal(signal.SIGINT, signal.default_int_handler)
