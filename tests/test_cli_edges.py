"""Issue 24, item 5: the last CLI edges and known gaps, each fixed at its root and pinned here."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import phasekit as pk
from phasekit import cli

import numpy as np
import pytest

from .helpers import run_cli, strict_json

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]
GYRO = ["gyroscopic", "--mu", "0.1", "--t", "0", "10", "1000"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def _refused(args, flag):
    code, out, err = run_cli(*args)
    assert code == 2 and out.count("\n") <= 1
    d = strict_json(out) if "--json" in args else None
    assert err.count("\n") == 1 and err.startswith(f"phasekit: error: {flag} ") and "Traceback" not in err
    if d is not None:
        assert d["status"] == "error" and d["parameter"] == flag
    return err


@pytest.mark.parametrize("switch, extra", [("--json", ["--json", "--json"]), ("--gyroscopic", ["--gyroscopic", "--json"]),
                                           ("--events", ["--events", "--events"])])
def test_a_repeated_switch_is_refused_like_a_repeated_option(switch, extra):
    err = _refused([*SIM, *extra], switch)  # SIM has --gyroscopic once already
    assert "is given 2 times: give it once" in err


def test_version_with_json_is_json_and_wins_over_the_rest():
    code, out, err = run_cli("--version", *SIM, "--json")
    assert code == 0 and err == ""
    assert strict_json(out) == {"program": "phasekit", "version": pk.__version__}
    code, out, err = run_cli("--version")
    assert (code, out, err) == (0, f"phasekit {pk.__version__}\n", "")


@pytest.mark.parametrize("body, rate", [(["--a", "1.5"], ["--omega0", "1e6"]), (["--a", "0.6"], ["--n0", "1e8"]),
                                        (["--body", "egg", "--a", "1.3", "--w", "0.05"], ["--omega0", "1e6"])])
def test_the_gyroscopic_solution_takes_the_rates_its_help_states(body, rate):
    theta0 = ["--theta0", "0.05" if rate[0] == "--n0" else "1.5"]
    code, out, err = run_cli(*GYRO, *body, *rate, *theta0, "--json")
    assert code == 0, err
    d = strict_json(out)
    assert all(np.isfinite(d["theta"])) and all(np.isfinite(d["Omega"]))
    assert d["theta"][0] == float(theta0[1]) and d["theta"][-1] != d["theta"][0]  # it rises, slowly
    # beyond the range --help states: refused, naming it
    help_text = cli._build_parser().commands["gyroscopic"].format_help()
    assert "1e12" in help_text
    err = _refused([*GYRO, *body, rate[0], "1e13", *theta0, "--json"], rate[0])
    assert "1e+12" in err


def test_a_step_budget_on_cvodes_says_what_a_step_is():
    code, out, _ = run_cli(*SIM, "--backend", "cvodes", "--max-steps", "20", "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed"
    assert d["reason"].startswith(f"step limit ({d['n_steps']} steps) reached at t = ") and d["n_steps"] >= 20
    help_text = " ".join(cli._build_parser().commands["simulate"].format_help().split())
    assert "CVODES/IDAS internal steps" in help_text and "may pass it by one chunk" in help_text
    code, out, _ = run_cli(*SIM, "--backend", "taylor", "--max-steps", "20", "--json")
    assert strict_json(out)["n_steps"] == 20  # the Taylor method stops at the budget exactly


def test_an_unstable_manifold_start_without_friction_blames_mu():
    args = ["simulate", "--a", "0.6", "--mu", "0", "--unstable-manifold", "vertical", "--n0", "12", "--json"]
    err = _refused(args, "--mu")
    assert "without friction" in err and err.rstrip().endswith("got 0.0.")
    # with friction the rate is the cause, and is named
    _refused(["simulate", "--a", "0.6", "--mu", "0.1", "--unstable-manifold", "vertical", "--n0", "0.5", "--json"], "--n0")


def test_an_end_time_beyond_the_wall_budget_is_said_at_once():
    code, out, err = run_cli(*SIM, "--t-end", "1e300", "--stop-at", "none", "--max-wall", "1", "--json")
    lines = err.splitlines()
    assert lines[0].startswith("phasekit: warning: --t-end = 1e+300 cannot be reached within --max-wall = 1 s")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and "wall-time limit" in d["reason"]
    code, out, err = run_cli(*SIM, "--t-end", "300", "--json")  # a reachable end: no warning
    assert code == 0 and err == ""


@pytest.mark.parametrize("call, name", [
    (lambda b: pk.core.impact(b, [np.sin(1.0), 0, np.cos(1.0)], [0, 0, 1e308], [0, 0, -1e308], e=0.5, mu=0.1), "w"),
    (lambda b: pk.theory.flight_constants(b, [0, 0, 1e200, 0, 1.0, 1.0], 1e200), "euler_state"),
    (lambda b: pk.theory.c_xi(b, 1.0, 1e300, 0.1, 0.01, 0.0), "Omega_bar0"),
    (lambda b: pk.theory.omega2(b, 1.0, 1e300), "Omega"),
    (lambda b: pk.theory.I_quadrature(b, 1e300, 1.0, 0.5), "J"),
    (lambda b: pk.theory.Sigma(b, 1e300, 1.0, 0.5, 0.01), "J"),
    (lambda b: pk.theory.omega2(b, 0.0, 10.0), "theta"),
    (lambda b: pk.theory.omega2(b, float("nan"), 10.0), "theta"),
    (lambda b: pk.theory.I_quadrature(b, 0.0, 1.0, 0.5), "J"),
    (lambda b: pk.theory.c_xi(b, 1.0, 10.0, 0.1, float("nan"), 0.0), "dtheta0"),
    (lambda b: pk.theory.flight_constants(b, [0, 0, 10.0, 0, 1.0, 1.0], float("nan")), "W"),
])
def test_the_theory_helpers_take_no_nan_and_give_none(call, name):
    with pytest.raises(pk.ParameterError) as info:
        call(pk.Spheroid(1.5))
    assert info.value.param == name


def test_the_idas_backend_prints_nothing_of_its_own():
    code, out, err = run_cli(*SIM, "--backend", "idas", "--rtol", "1e-16", "--json")
    d = strict_json(out)
    assert code == 1 and "IDA_TOO_MUCH_ACC" in d["reason"] and err == ""
    # and at the level of the process's file descriptors too
    proc = subprocess.run([sys.executable, "-m", "phasekit", *SIM, "--backend", "idas", "--rtol", "1e-16", "--json"],
                          cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1 and proc.stderr == "" and strict_json(proc.stdout)["status"] == "failed"


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


def test_a_bad_scheduler_is_refused_when_no_work_is_left():
    pytest.importorskip("dask.distributed")
    specs = [pk.sweep.TaskSpec("k0", lambda prev: 0)]
    with pytest.raises(pk.ParameterError) as info:
        pk.sweep.run_pending(specs, store_get=lambda key: 0, on_result=lambda s, r: None, warm_up=lambda: None,
                       scheduler="tcp://127.0.0.1:1")
    assert info.value.param == "scheduler"
    ran = pk.sweep.run_pending(specs, store_get=lambda key: 0, on_result=lambda s, r: None, warm_up=lambda: None)
    assert ran.computed == 0 and ran.mode == "all stored"


def test_version_flag_help_says_json():
    assert "JSON" in json.dumps(cli._build_parser().format_help())


@pytest.mark.parametrize("argv, flag", [(["--quick", "--quick"], "--quick"), (["--out", "a", "--out=b"], "--out")])
def test_a_study_refuses_a_repeated_flag_too(argv, flag, capsys):
    from phasekit.sweep.study import study_parser

    ap = study_parser("a study", default_out=ROOT / "figures")
    with pytest.raises(SystemExit) as info:
        ap.parse_args(argv)
    err = capsys.readouterr().err
    assert info.value.code == 2 and err.count("\n") == 1 and f"error: {flag} is given 2 times: give it once" in err


def test_an_interrupt_that_compiled_code_turns_into_another_error_ends_a_study_as_interrupted(capsys):
    """CasADi's argument dispatch turns a KeyboardInterrupt into NotImplementedError ("Wrong
    number or type of arguments"), which propagated as a traceback (found at 1.2 s into a study)."""
    from phasekit.sweep.study import run_study

    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is handled by something else in this process")

    def main(argv):
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            raise NotImplementedError("Wrong number or type of arguments for function 'Function_call'") from None

    with pytest.raises(SystemExit) as info:
        run_study(main, [])
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert info.value.code == 130 and len(lines) == 1 and lines[0].startswith("interrupted:")
