"""What the commands print: the JSON of a run (its keys, the state at the jump, flights, the chart),
strict JSON on stdout and nothing else, non-finite values named, a short human summary, and a
reader that leaves early."""

from __future__ import annotations

import contextlib
import io
import json
import os
import pathlib
import re
import subprocess
import sys

import phasekit as pk
from phasekit import cli
from phasekit.cli import main

import numpy as np
import pytest

from ..helpers import run_cli, strict_json

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]


def run_json(args):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(args)
    return code, json.loads(out.getvalue())


def test_simulate_json_keys():
    code, d = run_json(["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", str(np.pi / 2 - 0.01),
                        "--omega0", "10.5", "--t-end", "200", "--json"])
    assert code == 0
    for key in ("status", "t_jump", "state_at_jump", "R_min", "theta_end", "n_rhs", "wall_s", "events", "formulation"):
        assert key in d
    assert d["status"] == "jumped" and set(d["state_at_jump"]) == {"U", "V", "Omega", "Lambda", "theta", "n"}
    assert d["events"][-1]["kind"] == "lift-off"
    # the printed state at the jump has R = 0 (recomputed here from the model, not read back)
    import phasekit as pk

    y = np.array([d["state_at_jump"][k] for k in pk.core.PAPER_NAMES])
    assert abs(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)).normal_reaction(y)) < 1e-8


@pytest.mark.parametrize("which, extra", [("horizontal", ["--omega0", "12"]), ("vertical", ["--n0", "12"])])
def test_simulate_from_unstable_manifold(which, extra):
    a = "1.5" if which == "horizontal" else "0.6"
    code, d = run_json(["simulate", "--a", a, "--mu", "0.1", "--friction", "viscous", "--unstable-manifold", which,
                        *extra, "--delta", "0.01", "--t-end", "100", "--json"])
    assert code == 0 and d["seed"]["fixed_point"]["kind"] == which
    assert d["formulation"] == ("euler" if which == "horizontal" else "vector")
    assert abs(d["theta_end"] - d["start"]["theta"]) > 0.1  # it left the fixed point


def test_stop_at_touchdown_json():
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", str(np.pi / 2 - 0.01),
                     "--omega0", "11", "--t-end", "300", "--stop-at", "touchdown", "--json"])
    d = json.loads(out.getvalue())
    assert code == 0 and d["status"] == "touchdown"
    fl = d["flight"]
    assert set(fl) >= {"t_touchdown", "gap_max", "t_gap_max", "W_star", "Omega_star"}
    assert d["t_jump"] < fl["t_gap_max"] < fl["t_touchdown"] < d["t_jump"] + 0.1


def test_gyroscopic_cli_json():
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["gyroscopic", "--a", "1.5", "--mu", "0.1", "--omega0", "10.5", "--theta0", "1.5", "--t", "0", "10", "20", "--json"])
    d = json.loads(out.getvalue())
    assert code == 0 and len(d["theta"]) == len(d["Omega"]) == 3
    assert d["J"] == pytest.approx(0.65 * 10.5 * pk.Spheroid(1.5).h(1.5)[0])
    assert d["theta"][0] == pytest.approx(1.5) and d["theta"][2] < d["theta"][1] < 1.5


def test_the_chart_and_its_old_name_formulation():
    args = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "1",
            "--json"]
    for flag in ("--chart", "--formulation"):
        code, out, err = run_cli(*args, flag, "vector")
        d = json.loads(out)
        assert code == 0 and d["chart"] == d["formulation"] == d["model"]["chart"] == "vector"
    code, out, err = run_cli(*args, "--formulation", "polar")
    assert code == 2 and "--formulation" in err
    code, out, err = run_cli(*args, "--chart", "polar")
    assert code == 2 and "--chart" in err
    d = json.loads(run_cli(*args)[1])
    d["model"].pop("chart")
    d["model"]["formulation"] = "euler"  # an old result's key
    assert pk.rerun(d).model.chart.name == "euler"
    assert np.allclose(pk.core.to_paper("vector", pk.core.to_chart("vector", [0, 0, 2.0, 0, 1.0, 5.0])), [0, 0, 2.0, 0, 1.0, 5.0])


def test_stdout_is_strict_json_for_a_run_that_computes(tmp_path):
    # a fresh compiled-integrator cache: compiling must not print on stdout either
    p = subprocess.run([sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic",
                        "--theta0", "1.5", "--omega0", "10", "--t-end", "30", "--json"], capture_output=True, text=True,
                       timeout=300, cwd=ROOT, env={**__import__("os").environ, "PHASEKIT_CACHE": str(tmp_path)})
    assert p.returncode == 0 and strict_json(p.stdout)["status"] == "jumped"


def test_non_finite_result_ends_failed_saying_where(monkeypatch):
    monkeypatch.setitem(cli.COMMANDS, "gyroscopic",
                        lambda args: {"status": "completed", "theta": [1.0, float("nan")], "J": 1.0})
    code, out, _ = run_cli("gyroscopic", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--theta0", 1.5, "--t", 0, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"] == "non-finite value in the result at theta[1]"
    assert d["theta"] == [1.0, None]


def test_the_idas_backend_prints_nothing_of_its_own():
    code, out, err = run_cli(*SIM, "--backend", "idas", "--rtol", "1e-16", "--json")
    d = strict_json(out)
    assert code == 1 and "IDA_TOO_MUCH_ACC" in d["reason"] and err == ""
    # and at the level of the process's file descriptors too
    proc = subprocess.run([sys.executable, "-m", "phasekit", *SIM, "--backend", "idas", "--rtol", "1e-16", "--json"],
                          cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1 and proc.stderr == "" and strict_json(proc.stdout)["status"] == "failed"


def test_human_output_is_a_short_summary_and_events_lists_every_event():
    args = ["simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10, "--stop-at", "none",
            "--t-end", 40]
    code, out, _ = run_cli(*args)
    n_events = int(re.search(r"^(\d+) events", out, re.M).group(1))
    # with a line for all flights, one for the approximations the run used and the wall clock
    assert code == 0 and n_events > 30 and len(out.splitlines()) <= 13
    assert re.search(r"^approximations: minima of R$", out, re.M)  # e = 0: a touchdown without rebound is exact
    code, out_events, _ = run_cli(*args, "--events")
    assert len(out_events.splitlines()) == len(out.splitlines()) + n_events


def test_reader_closing_the_pipe_early_ends_quietly_without_a_traceback():
    # `phasekit ... | head -c 20`: the reader leaves before the JSON is written
    p = subprocess.Popen([sys.executable, "-m", "phasekit", "simulate", "--a", "1.5", "--mu", "0.1", "--state", "0", "0",
                          "0", "0", "1.0", "0", "--t-end", "1", "--json"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()
    err = p.stderr.read().decode()
    assert p.wait(timeout=120) == 1
    assert "Traceback" not in err and "BrokenPipe" not in err
