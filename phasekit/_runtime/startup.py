"""Ctrl-C while phasekit's own programs start: one line and exit code 130, not a traceback.

The CLI (``phasekit``, ``python -m phasekit``) and the studies (``python studies/NAME.py``)
spend their first second importing numpy, CasADi, heyoka and matplotlib, before their own
handler (:func:`phasekit.cli.main`, :func:`phasekit.scaffold.run_study`) is in place. This module is
the first thing ``import phasekit`` runs; when the program is one of those, importing it installs a SIGINT
handler that prints one line and exits with 130 until :func:`started` hands Ctrl-C back to
Python's default (KeyboardInterrupt, which those handlers turn into their own one line). Any
other program (a user's script, a notebook, the tests) is left alone.
"""

from __future__ import annotations

import os
import signal
import sys
import threading

EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report it


def _is_ours() -> bool:
    """Is the running program phasekit's CLI or one of its studies?"""
    argv = list(getattr(sys, "orig_argv", sys.argv))
    if len(argv) >= 3 and argv[1] == "-m" and argv[2].split(".")[0] == "phasekit":
        return True
    script = sys.argv[0] if sys.argv else ""
    if os.path.basename(script) == "phasekit":  # the console script
        return True
    if script.endswith(".py"):
        here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the repository
        return os.path.dirname(os.path.abspath(script)) == os.path.join(here, "studies")
    return False


def _interrupted(signum, frame):
    try:
        sys.stderr.write("\ninterrupted while starting: nothing was computed or written; run the command again\n")
        sys.stderr.flush()
    finally:
        os._exit(EXIT_INTERRUPTED)  # mid-import: nothing to clean up, and no traceback on the way out


def install() -> None:
    """Install the start-up handler if this program is phasekit's own (main thread only)."""
    if threading.current_thread() is threading.main_thread() and _is_ours() \
            and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _interrupted)


install()  # on import: this module is the first that ``import phasekit`` runs


def started() -> None:
    """The program's own Ctrl-C handling is in place: give SIGINT back to Python's default."""
    if threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGINT) is _interrupted:
        signal.signal(signal.SIGINT, signal.default_int_handler)
