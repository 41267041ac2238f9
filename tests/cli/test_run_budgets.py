"""Runs on the command line keep their budgets: ``--max-steps`` and ``--max-wall`` end a run
"failed" with a reason naming the budget (within it, for every backend), an end time beyond the
wall budget is refused at once, and what a step is for each backend is stated."""

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]


@pytest.mark.parametrize("budget, t_end, reason", [(["--max-steps", 3000], 1e5, "step limit"),
                                                   (["--max-wall", 0.3], 2e4, "wall-time")])  # 2e4 is within reach
def test_long_stop_at_none_run_ends_failed_at_its_budget(budget, t_end, reason):
    code, out, _ = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10,
                           "--stop-at", "none", "--t-end", t_end, *budget, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and reason in d["reason"] and d["t_end"] < t_end


@pytest.mark.timeout(300)  # a hang guard: the run is stopped by its budget after 0.5 s (it takes ~7 s without)
def test_wall_budget_holds_for_runs_of_many_short_segments():
    """Stick-slip chatter (mu = 1000): ~1000 segments, each far below the 20 000-step chunk
    after which the integrator checked the clock, so --max-wall 0.5 let a 7 s run complete.
    The run says that its wall budget stopped it, and where: before its end time."""
    code, out, _ = run_cli("simulate", "--a", 0.6, "--mu", 1000, "--state", 0, 0, 10, 0, 1, 0, "--max-wall", 0.5, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"].startswith("wall-time limit (0.5 s) reached at t = ")
    assert d["t_end"] < 200 and float(d["reason"].rsplit("= ", 1)[1]) == pytest.approx(d["t_end"], rel=1e-5)


def test_an_end_time_beyond_the_wall_budget_is_refused_at_once():
    """No run covers more than REACH_PER_S time units per wall-clock second: a --t-end beyond
    REACH_PER_S * --max-wall is refused before anything runs (one line, the reachable range)."""
    from phasekit.core.simulate import REACH_PER_S

    code, out, err = run_cli(*SIM, "--t-end", "1e300", "--stop-at", "none", "--max-wall", "1", "--json")
    assert code == 2 and err.count("\n") == 1
    d = strict_json(out)
    assert d["parameter"] == "--t-end" and f"must lie in (0, {REACH_PER_S:g}]" in d["message"]
    code, out, err = run_cli(*SIM, "--t-end", "300", "--json")  # a reachable end: no warning
    assert code == 0 and err == ""


@pytest.mark.parametrize("backend", ["cvodes", "cvodes-adams", "idas"])
@pytest.mark.parametrize("budget", [2, 20, 700])
def test_a_step_budget_on_cvodes_and_idas_holds(backend, budget):
    """The run ends "failed" within its budget (a chunk of output points that would pass it is
    not taken), its reason giving the count it reports."""
    code, out, _ = run_cli(*SIM, "--backend", backend, "--max-steps", budget, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["n_steps"] <= budget
    assert d["reason"].startswith(f"step limit ({d['n_steps']} steps) reached at t = ")
    assert float(d["reason"].split("t = ")[1].split()[0]) == pytest.approx(d["t_end"], rel=1e-5, abs=1e-12)


def test_what_a_step_is_is_stated_and_taylor_stops_at_the_budget_exactly():
    help_text = " ".join(cli.build_parser().commands["simulate"].format_help().split())
    assert "CVODES/IDAS internal steps" in help_text and "a chunk that would pass the budget is not taken" in help_text
    code, out, _ = run_cli(*SIM, "--backend", "taylor", "--max-steps", "20", "--json")
    assert strict_json(out)["n_steps"] == 20  # the Taylor method stops at the budget exactly


@pytest.mark.timeout(300)
def test_a_long_run_into_a_log_file_beats_and_stops_at_its_wall_budget(tmp_path):
    """With --json and stderr a file (no terminal, no bar), a run that cannot reach its end writes
    a heartbeat line on stderr every $PHASEKIT_HEARTBEAT seconds, then ends "failed" at its wall
    budget with the reason; stdout holds only the JSON."""
    import json
    import os
    import subprocess
    import sys

    err = tmp_path / "stderr.log"
    env = {**os.environ, "PHASEKIT_HEARTBEAT": "0.3", "PHASEKIT_COMPILE_NOTICE": "off"}
    cmd = [sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0",
           "1.5607963", "--omega0", "11", "--stop-at", "none", "--t-end", "1e5", "--max-wall", "2", "--json"]
    with open(err, "w") as fh:
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=fh, text=True, env=env, timeout=240)
    d = json.loads(proc.stdout)
    beats = [ln for ln in err.read_text().splitlines() if ln.startswith("phasekit: simulate: t = ")]
    assert proc.returncode == 1 and d["status"] == "failed" and "wall-time limit" in d["reason"]
    assert len(beats) >= 2 and all(" of 100000 (" in ln and "s of wall-clock time" in ln for ln in beats)
    times = [float(ln.split("t = ")[1].split(" of ")[0]) for ln in beats]
    assert times == sorted(times) and times[-1] <= d["t_end"]


def test_the_work_after_a_run_counts_in_its_wall_budget():
    """A dissipative run that spends its whole --max-wall leaves its energy budget and poses out,
    and says so; one that ends well within it has both (the same command otherwise; it runs first,
    so that the other's budget is not spent compiling)."""
    air = ["--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5607963, "--omega0", 11, "--air-drag", 1e-4,
           "--stop-at", "none", "--json"]
    code, out, _ = run_cli("simulate", *air, "--t-end", 50, "--max-wall", 60)
    d = strict_json(out)
    assert code == 0 and "post_run" not in d and d["energy_budget"]["dissipated"]["air-drag"] > 0
    assert abs(d["energy_budget"]["residual"]) < 1e-8 and set(d["pose_end"]) >= {"psi", "X", "Y"}
    code, out, _ = run_cli("simulate", *air, "--t-end", 2e4, "--max-wall", 1)
    d = strict_json(out)
    # (how far 1 s takes the run depends on the machine's load: no step count is asserted)
    assert code == 1 and d["status"] == "failed" and "wall-time limit (1 s)" in d["reason"] and d["t_end"] < 2e4
    assert d["energy_budget"] is None and "pose_end" not in d and d["post_run"]["skipped"] == ["energy budget", "poses"]
    assert d["post_run"]["reason"].startswith("--max-wall 1 s ran out after the run (") and "not computed" in d["post_run"]["reason"]


def test_the_command_s_start_is_claimed_by_its_first_run_only():
    """--max-wall counts the whole simulate command: its run's own budget counts from the command's
    start (claimed once: a run that run makes, its verification, counts from its own start), and
    the work after it gets what is left (spent)."""
    from phasekit._runtime.watch import claim_start, spent, wall_started

    assert claim_start() is None and spent() == 0.0  # outside a command
    with wall_started() as start:
        assert claim_start() == start and claim_start() is None and spent() > 0.0
    assert claim_start() is None
