"""A refused command line prints its one error line and nothing else: the warnings a command
raises are held until its inputs are accepted (``--restitution inf`` with ``--stop-at jump``
warned that it has no effect, then was refused). An accepted one still warns, once, before the
result."""

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "1"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.parametrize("args, flag", [
    ([*SIM, "--restitution", "inf"], "--restitution"),  # warned "no effect with --stop-at jump", then refused
    ([*SIM, "--restitution", "0.5", "--rtol", "7"], "--rtol"),
    ([*SIM, "--atol", "-1", "--backend", "taylor"], "--atol"),  # warned "no effect with --backend taylor"
    ([*SIM, "--slip-eps", "1e-3", "--friction", "viscous", "--t-end", "1e300"], "--t-end"),
    (["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "2", "--n0", "10"], "--theta0"),  # the
    # library warns that --n0 is unusual for a prolate body, then refuses the inclination it goes with
    (["fixed-points", "--a", "1.5", "--mu", "-1", "--friction", "viscous", "--slip-eps", "1e-3", "--omega0", "1"],
     "--mu"),
])
def test_a_refusal_is_the_only_line(args, flag):
    for extra in ([], ["--json"]):
        code, out, err = run_cli(*args, *extra)
        assert code == 2 and err.count("\n") == 1 and err.startswith("phasekit: error: "), err
        assert flag in err and "warning" not in err
        if extra:
            assert strict_json(out)["parameter"] == flag


def test_an_accepted_command_line_still_warns_once_before_its_result():
    code, out, err = run_cli(*SIM, "--restitution", "0.5", "--atol", "1e-12", "--backend", "taylor")
    assert code == 0 and out.startswith("status: ")
    assert err.splitlines() == [
        "phasekit: warning: --restitution has no effect with --stop-at jump (impacts happen with --stop-at none or "
        "--stop-at NAME=VALUE)",
        "phasekit: warning: --atol has no effect with --backend taylor (the Taylor method has the one tolerance --rtol)"]
