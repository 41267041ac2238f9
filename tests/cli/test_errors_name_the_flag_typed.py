"""CLI errors name the flag the user typed (exit 2, one line, strict JSON with --json), also when
several flags feed one parameter, a flag belongs to another command or is given twice."""

import argparse
import math
import subprocess
import sys

import phasekit as pk
from phasekit import cli

import pytest

from ..helpers import run_cli, run_module, strict_json, usage_error

SIM = ["simulate", "--a", "1.5", "--mu", "0.1"]
TOP = ["simulate", "--body", "tippe-top", "--offset", "0.3", "--mu", "0.3"]
GYRO = ["gyroscopic", "--a", "1.5", "--mu", "0.1", "--omega0", "10.5", "--theta0", "1.5607963"]
MINIMAL = {"simulate": SIM + ["--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
           "animate": ["animate", "x.gif", *SIM[1:], "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
           "fixed-points": ["fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "10"],
           "steady-states": ["steady-states", "--a", "1.5", "--mu", "0.1"],
           "gyroscopic": GYRO + ["--t", "0"], "cache": ["cache"]}


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")



@pytest.mark.parametrize("value", ["0", "1e6", "nan", "inf", "2e5", "-inf"])
@pytest.mark.parametrize("body", [SIM, TOP])
def test_spin_about_vertical_is_named_as_typed_not_as_n0(body, value):
    msg = usage_error([*body, "--theta0", "1.56", "--spin-about-vertical", value], "--spin-about-vertical")
    assert msg.startswith("--spin-about-vertical ") and "n0" not in msg
    assert msg.endswith(f"got {float(value)!r}.")


def test_spin_about_vertical_with_gyroscopic_names_both_flags_typed():
    msg = usage_error([*SIM, "--gyroscopic", "--theta0", "1.56", "--spin-about-vertical", "0"], "--spin-about-vertical")
    assert "--gyroscopic" in msg and "--n0" not in msg


def test_theta0_of_a_spin_about_vertical_start_is_not_called_a_state_component():
    msg = usage_error([*TOP, "--theta0", "0", "--spin-about-vertical", "10", "--formulation", "euler"], "--theta0")
    assert msg.startswith("--theta0 must lie in (0, pi)") and "--state" not in msg


def test_n0_typed_is_still_named_n0():
    msg = usage_error(["simulate", "--a", "0.6", "--mu", "0.1", "--gyroscopic", "--theta0", "0.1", "--n0", "nan"],
                      "--n0")
    assert msg.startswith("--n0 ") and msg.endswith("got nan.")


@pytest.mark.parametrize("extra, flag, got", [
    (["--a", "1.5", "--A", "0.7"], "--A", "0.7"),
    (["--a", "1.5", "--C", "0.3"], "--C", "0.3"),
    (["--a", "1.3"], "--a", "1.3"),
    (["--a", "nan"], "--a", "nan"),
    (["--body", "tippe-top", "--offset", "0.3"], "--body", "'tippe-top'"),
    (["--body", "egg", "--a", "1.5"], "--body", "'egg'"),
])
def test_paper_start_names_the_flag_that_contradicts_its_body(extra, flag, got):
    msg = usage_error(["simulate", "--mu", "0.1", "--paper-start", "5.2", *extra], flag)
    assert msg.startswith(f"{flag} ") and "--paper-start 5.2" in msg and msg.endswith(f"got {got}.")
    assert "got None" not in msg


def test_unknown_paper_start_is_named():
    msg = usage_error(["simulate", "--mu", "0.1", "--paper-start", "5.3"], "--paper-start")
    assert msg == "--paper-start must be one of 5.1, 5.2 (the paper's printed starts), got '5.3'."


def _foreign_flags():
    [sub] = [a for a in cli.build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    flags = {name: {f for f in p._option_string_actions if f.startswith("--")} for name, p in sub.choices.items()}
    return [(name, flag) for name in flags for flag in sorted(set().union(*flags.values()) - flags[name])]


@pytest.mark.parametrize("command, flag", _foreign_flags())
def test_flag_of_another_command_says_so(command, flag):
    msg = usage_error([*MINIMAL[command], flag, "1"], flag)
    assert f"{flag} is not an option of {command}: it is one of " in msg
    assert f"did you mean {flag}" not in msg


def test_json_before_any_command_is_not_suggested_as_itself():
    code, out, err = run_cli("--json")
    d = strict_json(out)
    assert code == 2 and d == {"status": "error", "parameter": "--json", "message": d["message"]}
    assert "did you mean" not in d["message"] and "--json is an option of the commands" in d["message"]
    assert err == f"phasekit: error: {d['message']}\n"


@pytest.mark.parametrize("args, flag, suggestion", [
    ([*MINIMAL["gyroscopic"], "--thet0", "1"], "--thet0", "--theta0"),
    (["fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "10", "--slip-ep", "1e-3"], "--slip-ep", "--slip-eps"),
    ([*MINIMAL["simulate"], "--max-step", "9"], "--max-step", "--max-steps"),
])
def test_did_you_mean_comes_from_the_command_in_use(args, flag, suggestion):
    assert usage_error(args, flag).endswith(f"(did you mean {suggestion}?)")


def test_near_miss_of_another_commands_flag_is_not_suggested():
    msg = usage_error([*MINIMAL["gyroscopic"], "--slip-ep", "1e-3"], "--slip-ep")
    assert "--slip-eps" not in msg and msg.endswith("(not an option of gyroscopic (see --help))")


@pytest.mark.parametrize("body, state, valid", [
    (TOP, "horizontal", "vertical, inverted"),
    (TOP, "horizontal-like", "vertical, inverted"),
    (["simulate", "--body", "egg", "--a", "1.3", "--w", "0.1", "--mu", "0.3"], "horizontal",
     "vertical, inverted, horizontal-like"),
    (SIM, "horizontal-like", "horizontal, vertical, inverted"),
    (SIM, "sideways", "horizontal, vertical, inverted"),
])
def test_unstable_manifold_of_a_state_the_body_lacks_is_bad_input(body, state, valid):
    msg = usage_error([*body, "--unstable-manifold", state, "--omega0", "10.5"], "--unstable-manifold")
    assert msg.startswith(f"--unstable-manifold must be one of {valid} for the ") and msg.endswith(f"got '{state}'.")


class _Unrun:
    """What the recorder below returns in place of a Trajectory: a run that did nothing."""

    status, flights = pk.Status.COMPLETED, ()

    def to_dict(self):
        return {"status": "completed", "reason": None}

    def flight_summary(self):
        return {"n_flights": 0}


@pytest.fixture
def started(monkeypatch):
    """run_start replaced by a recorder: what the CLI passes on, without integrating."""
    import phasekit.cli.params

    calls = []

    def record(**kw):
        calls.append(kw)
        return _Unrun(), None

    monkeypatch.setattr(phasekit.cli.params, "run_start", record)
    return calls


@pytest.mark.parametrize("body, state, family", [
    (TOP, "vertical", "--n0"), (TOP, "inverted", "--n0"), (SIM, "horizontal", "--omega0"),
    (["simulate", "--body", "egg", "--a", "1.3", "--w", "0.1", "--mu", "0.3"], "horizontal-like", "--omega0"),
])
def test_unstable_manifold_states_the_body_has_are_passed_on_unchanged(started, body, state, family):
    code, out, err = run_cli(*body, "--unstable-manifold", state, family, "10.5", "--json")
    assert code == 0 and err == "" and started[0]["start"]["state"] == state


def test_paper_start_takes_its_aspect_ratio_by_default(started):
    code, _, _ = run_cli("simulate", "--mu", "0.1", "--paper-start", "(5.2)", "--json")
    assert code == 0 and started[0]["body"].a == 1.5 and started[0]["start"]["label"] == "5.2"


def test_a_failed_solve_in_json_has_status_and_reason(monkeypatch):
    import phasekit.steady.fixedpoints as fpm

    monkeypatch.setattr(fpm, "NEWTON_RTOL", -1.0)  # no iterate can pass: Newton "fails"
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 0.1, "--omega0", 10, "--json")
    d = strict_json(out)
    assert code == 1 and d["status"] == "failed" and d["reason"] == d["message"]
    assert err == f"phasekit: error: {d['reason']}\n"


@pytest.mark.parametrize("args, flag", [
    ([*SIM, "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--stop-at", "theta=0.4", "--stop-at", "jump"],
     "--stop-at"),
    (["simulate", "--a", "1", "--a", "2", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"], "--a"),
    (["simulate", "--a=1", "--a", "2", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"], "--a"),
    (["fixed-points", "--a", "1.5", "--mu", "0.1", "--mu", "0.2", "--omega0", "10"], "--mu"),
    ([*GYRO, "--t", "0", "--t", "10"], "--t"),
    ([*SIM, "--state", "0", "0", "0", "0", "1", "0", "--state", "0", "0", "0", "0", "1", "0"], "--state"),
])
def test_repeated_option_is_refused_naming_it(args, flag):
    msg = usage_error(args, flag)
    assert msg.startswith(f"{flag} ") and "given 2 times" in msg


def test_repeated_single_value_shows_both_values():
    msg = usage_error(["simulate", "--a", "1", "--a", "2", "--mu", "0.1", "--state", "0", "0", "0", "0", "1", "0"],
                      "--a")
    assert msg == "--a takes one value and is given 2 times (got 1, then 2): give it once"


def test_repeated_switch_is_refused_before_anything_runs(started):
    """`--json --json` is refused like any repeated flag (a switch given twice was once accepted)."""
    code, out, err = run_cli(*MINIMAL["simulate"], "--json", "--json")
    d = strict_json(out)
    assert code == 2 and d["parameter"] == "--json" and d["message"] == "--json is given 2 times: give it once"
    assert err == f"phasekit: error: {d['message']}\n" and not started


def test_gyroscopic_reports_the_times_in_the_order_given():
    code, out, _ = run_cli(*GYRO, "--t", 10, 0, 40, 5, "--json")
    d = strict_json(out)
    code_sorted, out_sorted, _ = run_cli(*GYRO, "--t", 0, 5, 10, 40, "--json")
    s = strict_json(out_sorted)
    assert code == code_sorted == 0 and d["t"] == [10.0, 0.0, 40.0, 5.0]
    rank = {t: i for i, t in enumerate(s["t"])}
    for key in ("T", "theta", "Omega"):
        assert d[key] == [s[key][rank[t]] for t in d["t"]]
    assert d["theta"][1] == pytest.approx(1.5607963, abs=1e-12) and not math.isclose(d["theta"][0], d["theta"][1])


def _refused(args, flag):
    code, out, err = run_cli(*args)
    assert code == 2 and out.count("\n") <= 1
    d = strict_json(out) if "--json" in args else None
    assert err.count("\n") == 1 and err.startswith(f"phasekit: error: {flag} ") and "Traceback" not in err
    if d is not None:
        assert d["status"] == "error" and d["parameter"] == flag
    return err


# -- 7. a repeated switch, and the flag to blame ---------------------------------------------------


JUMP_RUN = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]


@pytest.mark.parametrize("switch, extra", [("--json", ["--json", "--json"]), ("--gyroscopic", ["--gyroscopic", "--json"]),
                                           ("--events", ["--events", "--events"])])
def test_a_repeated_switch_is_refused_like_a_repeated_option(switch, extra):
    err = _refused([*JUMP_RUN, *extra], switch)  # JUMP_RUN has --gyroscopic once already
    assert "is given 2 times: give it once" in err


def test_an_unstable_manifold_start_without_friction_blames_mu():
    args = ["simulate", "--a", "0.6", "--mu", "0", "--unstable-manifold", "vertical", "--n0", "12", "--json"]
    err = _refused(args, "--mu")
    assert "without friction" in err and err.rstrip().endswith("got 0.0.")
    # with friction the rate is the cause, and is named
    _refused(["simulate", "--a", "0.6", "--mu", "0.1", "--unstable-manifold", "vertical", "--n0", "0.5", "--json"], "--n0")


def test_mu_beyond_the_cap_is_a_clear_error_not_a_convergence_error():
    code, out, err = run_cli("fixed-points", "--a", 1.5, "--mu", 1e6, "--omega0", 10, "--json")
    assert code == 2 and strict_json(out)["parameter"] == "--mu"
    assert err.strip() == "phasekit: error: --mu must lie in [0, 1000], got 1000000.0."


def test_omega_is_not_taken_for_omega0_by_abbreviation():
    code, out, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega", 10,
                             "--json")
    assert code == 2 and strict_json(out)["parameter"] == "--omega"
    assert err.strip() == "phasekit: error: unrecognized arguments: --omega 10 (did you mean --omega0?)"


def test_error_names_the_flag_typed_and_prints_plain_numbers():
    code, _, err = run_cli("simulate", "--a", 1e308, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10)
    assert code == 2 and err.strip() == "phasekit: error: --a must lie in [0.0001, 10000], got 1e+308."
    code, _, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 0.0)
    assert code == 2 and err.strip().endswith("got 0.0.") and "np.float64" not in err


def test_rtol_beyond_double_precision_is_refused_instead_of_running_forever():
    code, _, err = run_cli("simulate", "--a", 1.5, "--mu", 0.1, "--gyroscopic", "--theta0", 1.5, "--omega0", 10,
                           "--rtol", 1e-300)
    assert code == 2 and err.strip() == "phasekit: error: --rtol must lie in [1e-16, 0.1], got 1e-300."


# -- a real process -----------------------------------------------------------------------------------


def test_subprocess_names_the_flag_typed_in_one_line_and_strict_json():
    p = subprocess.run([sys.executable, "-m", "phasekit", *TOP, "--theta0", "0.1", "--spin-about-vertical", "nan",
                        "--json"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    d = strict_json(p.stdout)
    assert d == {"status": "error", "parameter": "--spin-about-vertical",
                 "message": "--spin-about-vertical must be a finite nonzero number, got nan."}
    assert p.stderr.splitlines() == [f"phasekit: error: {d['message']}"]


def test_unstable_manifold_start_beyond_a_simulation_is_one_line_not_a_traceback():
    code, out, err = run_module("simulate", "--a", 1.5, "--mu", 0.1, "--unstable-manifold", "horizontal",
                                    "--omega0", 1e6)
    assert code == 2 and out == ""
    assert err.strip().splitlines() == [err.strip()] and err.startswith("phasekit: error: --omega0 ")


@pytest.mark.parametrize("flag, value", [("--mu", "1e308"), ("--omega0", "1e300"), ("--omega0", "1e-300")])
def test_extreme_values_give_one_json_error_on_stdout_and_one_line_on_stderr(flag, value):
    args = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--json"]
    args[args.index(flag) + 1] = value
    code, out, err = run_module(*args)
    d = strict_json(out)
    assert code == 2 and d["status"] == "error" and d["parameter"] == flag
    assert err.strip() == f"phasekit: error: {d['message']}" and f"got {float(value)!r}" in d["message"]


@pytest.mark.parametrize("value", ["41 rev/s", "11", "0.5 x"])
def test_a_repeated_value_names_its_flag_even_with_a_space(value):
    """argparse reports the stray value in one string of all the extras; the flag is found from
    the value as typed, so a value with a space is found too."""
    msg = usage_error(["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--omega0", "41 rev/s", value], "--omega0")
    assert f"unrecognized arguments: {value} (a value too many after --omega0, which takes one value)" in msg
