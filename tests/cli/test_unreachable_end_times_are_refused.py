"""An end time that the wall budget cannot reach (no run covers more than REACH_PER_S time units
per wall-clock second) is refused at once by simulate and animate alike, in one line with the
reachable range (in seconds too when typed with units), instead of running for all of --max-wall."""

import math
import re

from phasekit import cli
from phasekit.core.simulate import REACH_PER_S

import pytest

from ..helpers import run_cli, strict_json

START = ["--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--stop-at", "none"]
COMMANDS = {"simulate": ["simulate"], "animate": ["animate", "{tmp}/never-written.gif"]}


def _command(command, tmp_path):
    return [a.format(tmp=tmp_path) for a in COMMANDS[command]]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.timeout(120)  # a hang guard: a refusal takes no time; a run would take --max-wall
@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("t_end, wall", [("1e300", None), ("6.1e7", None), ("1001", "0.01"), ("1e308", "1e300")])
def test_an_unreachable_end_time_is_refused_at_once(command, t_end, wall, tmp_path):
    budget = 600.0 if wall is None else float(wall)
    extra = [] if wall is None else ["--max-wall", wall]
    code, out, err = run_cli(*_command(command, tmp_path), *START, "--t-end", t_end, *extra, "--json")
    d = strict_json(out)
    assert code == 2 and d["parameter"] == "--t-end" and err.count("\n") == 1, err
    reach = REACH_PER_S * budget
    assert f"must lie in (0, {reach:g}]" in d["message"] and f"--max-wall {budget:g} s" in d["message"]
    assert not list(tmp_path.iterdir())  # no movie: the refusal comes before any work


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_an_end_time_with_units_is_refused_in_its_units_too(command, tmp_path):
    code, out, err = run_cli(*_command(command, tmp_path), *START, "--t-end", "1e9 s", "--size", "21.5 mm", "--json")
    d = strict_json(out)
    assert code == 2 and d["parameter"] == "--t-end"
    seconds = REACH_PER_S * 600 * math.sqrt(0.0215 / 9.81)  # the reachable end in seconds, by hand
    assert "'1e9 s'" in d["message"] and f"= {seconds:.3g} s" in d["message"]


def test_an_end_time_within_reach_runs_and_its_wall_budget_says_where_it_stopped():
    """At the edge of reach the run is not refused: it runs, and ends by its wall budget."""
    code, out, err = run_cli("simulate", *START, "--t-end", f"{REACH_PER_S * 0.05:g}", "--max-wall", "0.05", "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and "wall-time limit" in d["reason"], err
    assert "cannot be reached" not in err
    stopped = float(re.search(r"at t = ([-+.\deE]+)", d["reason"]).group(1))
    assert stopped == pytest.approx(d["t_end"], rel=1e-5) and 0 < d["t_end"] < REACH_PER_S * 0.05
