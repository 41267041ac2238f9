"""Shared fixtures: the prolate and oblate bodies and the standard workload; the timeout of the
generated tests."""

import os
import signal
import threading

import numpy as np
import pytest

os.environ.setdefault("MPLBACKEND", "Agg")
# a compilation's notice on stderr depends on how fast this machine compiles: tests that read
# stderr exactly must not see it (tests/core/test_compile_notice.py turns it back on)
os.environ["PHASEKIT_COMPILE_NOTICE"] = "off"
# compiling a run's other contact mode ahead is for a user's first run; the suite builds hundreds of
# models, most of which never reach that mode (tests/core/test_compile_ahead.py turns it back on)
os.environ["PHASEKIT_COMPILE_AHEAD"] = "off"

# A job runner or `nohup cmd &` starts the suite with SIGINT ignored, and an ignored signal stays
# ignored in every process started from here: the Ctrl-C tests would then test the launcher. The
# suite makes its own disposition, Python's default, which exec resets to SIG_DFL in a child.
if threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

import phasekit as pk  # noqa: E402

from .generated_inputs import hang_timer  # noqa: E402


@pytest.fixture(scope="session")
def prolate():
    return pk.Spheroid(1.5)


@pytest.fixture(scope="session")
def oblate():
    return pk.Spheroid(2.0 / 3.0)


@pytest.fixture(scope="session")
def standard_start(prolate):
    """The standard workload: a = 1.5, gyroscopic start theta0 = pi/2 - 0.01, Omega0 = 10.5."""
    return pk.gyroscopic_start(prolate, np.pi / 2 - 0.01, omega0=10.5)


@pytest.hookimpl(optionalhook=True)
def pytest_timeout_set_timer(item, settings):
    """A generated test (tests/generated_inputs.py) times out by an exception that Hypothesis lets
    through; every other test by pytest-timeout's own."""
    if getattr(getattr(item, "obj", None), "runs_generated_cases", False) and settings.method == "signal" \
            and threading.current_thread() is threading.main_thread():
        hang_timer(item, settings.timeout)
        return True
    return None
