"""The suite's Ctrl-C tests pass when the suite is started with SIGINT ignored, as `nohup cmd &`
and many job runners start it (tests/conftest.py makes the suite's own disposition)."""

import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _ignoring_sigint():
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@pytest.mark.timeout(300)
def test_the_interrupt_tests_pass_when_launched_with_sigint_ignored():
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/_runtime/test_interrupts.py",
           "tests/cli/test_one_line_failures_and_interrupts.py::test_ctrl_c_at_any_moment_of_the_start_is_one_line_and_130"]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=280, preexec_fn=_ignoring_sigint)
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert " passed" in proc.stdout and "failed" not in proc.stdout
