"""The CLI never shows a traceback: an unexpected exception, a solver failure and a warning are one
line on stderr (exit 1, 1, 0), Ctrl-C at any moment is one line and exit 130."""

import os
import pathlib
import signal
import subprocess
import sys
import time

from phasekit import cli

import pytest

from ..helpers import run_cli, run_module, strict_json

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


REST = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0]  # released from rest, tilted: `--state 0 0 0 0 1.0 0`
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]


def test_unexpected_exception_is_one_line_with_exit_1(monkeypatch):
    monkeypatch.delenv(cli.DEBUG_ENV)

    def boom(args):
        raise RuntimeError("a bug\nwith a second line")

    monkeypatch.setitem(cli.COMMANDS, "fixed-points", boom)
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--json")
    assert code == 1 and strict_json(out)["status"] == "failed"
    line = "phasekit: error: internal error: RuntimeError: a bug (please report it; set PHASEKIT_DEBUG=1 for the traceback)"
    assert err.strip().splitlines() == [line]
    monkeypatch.setenv(cli.DEBUG_ENV, "1")  # and tests see the real exception
    with pytest.raises(RuntimeError):
        run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10)


def test_interrupt_is_one_line_with_exit_130(monkeypatch):
    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setitem(cli.COMMANDS, "simulate", interrupted)
    code, out, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--state", *REST, "--json")
    assert code == 130 and strict_json(out)["status"] == "interrupted" and len(err.strip().splitlines()) == 1


def test_solver_failure_is_one_line_with_exit_1(monkeypatch):
    import phasekit.steady.fixedpoints as fpm

    monkeypatch.setattr(fpm, "NEWTON_RTOL", -1.0)  # no iterate can pass: Newton "fails"
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--json")
    assert code == 1 and strict_json(out)["status"] == "failed"
    [line] = err.strip().splitlines()
    assert line.startswith("phasekit: error: Newton did not converge to a horizontal fixed point with Omega = 10: ")


@pytest.mark.parametrize("extra, flag", [(["--restitution", "0.5"], "--restitution"),
                                         (["--slip-eps", "1e-3", "--friction", "viscous"], "--slip-eps")])
def test_options_without_effect_warn_in_one_line_on_stderr(extra, flag):
    code, out, err = run_module("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5,
                                    "--omega0", 10, "--t-end", 5, "--json", *extra)
    assert code == 0 and strict_json(out)["status"] == "completed"
    [line] = err.strip().splitlines()
    assert line.startswith(f"phasekit: warning: {flag} has no effect")


@pytest.mark.parametrize("which", ["cli", "study"])
def test_ctrl_c_at_any_moment_of_the_start_is_one_line_and_130(which, tmp_path):
    """SIGINT from 0.3 s to 1.2 s after launch: during the imports, while the run starts, and
    while it computes; always exit 130 and one line on stderr."""
    if which == "cli":
        hopping = [a if a != "10.5" else "30" for a in SIM]  # hops to t = 400: a few seconds of work
        cmd = [sys.executable, "-m", "phasekit", *hopping, "--t-end", "400", "--stop-at", "none", "--restitution", "0.5"]
    else:
        # a study that runs for tens of seconds, so that every delay interrupts it
        cmd = [sys.executable, str(ROOT / "studies" / "steady_structure.py"), "--quick", "--serial", "--no-scene",
               "--no-progress", "--fresh", "--out", str(tmp_path)]
    for delay in (0.3, 0.5, 0.8, 1.2):  # (the first ~30 ms, before Python runs any of phasekit, are out of reach)
        proc = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            time.sleep(delay)
            assert proc.poll() is None, ("ended before the interrupt", delay, proc.communicate())
            proc.send_signal(signal.SIGINT)
            out, err = proc.communicate(timeout=60)
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.communicate()
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert proc.returncode == 130 and len(lines) == 1 and "Traceback" not in err, (delay, err)
        assert "interrupted" in lines[0]
