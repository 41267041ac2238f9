"""steady-states and fixed-points take --max-wall as simulate does (seconds, a finite number
> 0, default 600, the same one-line refusal), pass it on to their reports, and a search that runs
out of it ends "failed" (exit 1) with the reason naming the budget."""

import phasekit.cli.params
from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

COMMANDS = {"fixed-points": ["fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "10"],
            "steady-states": ["steady-states", "--a", "1.5", "--mu", "0.1"]}
SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"]
REPORTS = {"fixed-points": "fixed_points_report", "steady-states": "steady_structure_report"}


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("given, passed", [([], 600.0), (["--max-wall", "2.5"], 2.5)])
def test_the_budget_is_passed_on(monkeypatch, command, given, passed):
    seen = []
    monkeypatch.setattr(phasekit.cli.params, REPORTS[command], lambda **kw: seen.append(kw) or {"status": "completed"})
    code, out, err = run_cli(*COMMANDS[command], *given, "--json")
    assert code == 0 and seen[0]["max_wall"] == passed, err


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf", "x"])
def test_a_bad_budget_is_refused_as_simulate_refuses_it(command, value):
    code, out, err = run_cli(*COMMANDS[command], "--max-wall", value, "--json")
    d = strict_json(out)
    assert code == 2 and d["parameter"] == "--max-wall" and err.count("\n") == 1
    assert d["message"] == strict_json(run_cli(*SIM, "--max-wall", value, "--json")[1])["message"]


@pytest.mark.timeout(300)  # a hang guard: the budget is a microsecond
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_search_that_runs_out_of_its_budget_says_so(command):
    """A spheroid with its centre of mass off centre: a search over theta, which checks its
    budget between its Newton solves."""
    args = [COMMANDS[command][0], "--a", "1.5", "--offset", "0.2", "--mu", "0.1", "--friction", "viscous",
            *(["--omega0", "10"] if command == "fixed-points" else [])]
    code, out, err = run_cli(*args, "--max-wall", "1e-6", "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and "max_wall = 1e-06 s" in d["reason"], (d.get("reason"), err)
    code, out, err = run_cli(*args, "--max-wall", "1e-6")
    assert code == 1 and out.startswith("status: failed (") and "max_wall = 1e-06 s" in out.splitlines()[0]
