"""Runs on the command line keep their budgets: ``--max-steps`` and ``--max-wall`` end a run
"failed" with a reason naming the budget, an end time beyond the wall budget is said at once,
and what a step is for each backend is stated."""

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]


@pytest.mark.parametrize("budget, reason", [(["--max-steps", 3000], "step limit"), (["--max-wall", 0.3], "wall-time")])
def test_long_stop_at_none_run_ends_failed_at_its_budget(budget, reason):
    code, out, _ = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10,
                           "--stop-at", "none", "--t-end", 1e5, *budget, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and reason in d["reason"] and d["t_end"] < 1e5


@pytest.mark.timeout(300)  # a hang guard: the run is stopped by its budget after 0.5 s (it takes ~7 s without)
def test_wall_budget_holds_for_runs_of_many_short_segments():
    """Stick-slip chatter (mu = 1000): ~1000 segments, each far below the 20 000-step chunk
    after which the integrator checked the clock, so --max-wall 0.5 let a 7 s run complete.
    The run says that its wall budget stopped it, and where: before its end time."""
    code, out, _ = run_cli("simulate", "--a", 0.6, "--mu", 1000, "--state", 0, 0, 10, 0, 1, 0, "--max-wall", 0.5, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"].startswith("wall-time limit (0.5 s) reached at t = ")
    assert d["t_end"] < 200 and float(d["reason"].rsplit("= ", 1)[1]) == pytest.approx(d["t_end"], rel=1e-5)


def test_an_end_time_beyond_the_wall_budget_is_said_at_once():
    code, out, err = run_cli(*SIM, "--t-end", "1e300", "--stop-at", "none", "--max-wall", "1", "--json")
    lines = err.splitlines()
    assert lines[0].startswith("phasekit: warning: --t-end = 1e+300 cannot be reached within --max-wall = 1 s")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and "wall-time limit" in d["reason"]
    code, out, err = run_cli(*SIM, "--t-end", "300", "--json")  # a reachable end: no warning
    assert code == 0 and err == ""


def test_a_step_budget_on_cvodes_says_what_a_step_is():
    code, out, _ = run_cli(*SIM, "--backend", "cvodes", "--max-steps", "20", "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed"
    assert d["reason"].startswith(f"step limit ({d['n_steps']} steps) reached at t = ") and d["n_steps"] >= 20
    help_text = " ".join(cli._build_parser().commands["simulate"].format_help().split())
    assert "CVODES/IDAS internal steps" in help_text and "may pass it by one chunk" in help_text
    code, out, _ = run_cli(*SIM, "--backend", "taylor", "--max-steps", "20", "--json")
    assert strict_json(out)["n_steps"] == 20  # the Taylor method stops at the budget exactly
