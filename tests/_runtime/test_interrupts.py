"""Ctrl-C under :func:`phasekit._runtime.interrupts.interrupt_guard`: one exit, nothing else printed."""

import subprocess
import sys
import textwrap

import pytest

# A SIGINT that lands where Python cannot raise (a weakref callback, as the import system's module
# locks have; a __del__): CPython prints "Exception ignored in ..." with a traceback and goes on.
# The guard raises the interrupt again, so the program still ends interrupted; the report of the
# swallowed one must not reach stderr.
SCRIPT = textwrap.dedent("""
    import signal, sys, time, weakref
    from phasekit._runtime.interrupts import interrupt_guard

    class Body:
        def __del__(self):
            signal.raise_signal(signal.SIGINT)
            sum(range(10_000))  # Python lines, where the handler runs and raises

    class Key:
        pass

    def callback(ref):
        signal.raise_signal(signal.SIGINT)
        sum(range(10_000))

    with interrupt_guard(mute=False) as guard:
        try:
            if sys.argv[1] == "weakref":
                key = Key()
                ref = weakref.ref(key, callback)
                del key
            else:
                Body()
            deadline = time.monotonic() + 10
            while time.monotonic() < deadline:
                time.sleep(0.01)
            print("not interrupted", file=sys.stderr)
        except KeyboardInterrupt:
            guard["handled"] = True
            print("interrupted", file=sys.stderr)
""")


@pytest.mark.parametrize("where", ["weakref", "del"])
def test_an_interrupt_python_cannot_raise_is_raised_again_and_not_reported(where):
    proc = subprocess.run([sys.executable, "-c", SCRIPT, where], capture_output=True, text=True, timeout=60)
    assert proc.stderr.splitlines() == ["interrupted"], proc.stderr

