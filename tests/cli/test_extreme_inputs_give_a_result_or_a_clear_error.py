"""Extreme inputs (tiny and huge moments, sizes, gravities, rates, friction and end times) give a
result or one clear line naming a flag typed: never a numpy warning ("overflow encountered in
dot" leaked as a ``phasekit: warning:`` line from a moment C = 1e-300), never a traceback."""

import re

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

VISCOUS = ["--mu", "0.1", "--friction", "viscous"]
CASES = [
    ["fixed-points", "--body", "tippe-top", "--offset", "0.3", *VISCOUS, "--omega0", "10", "--C", "1e-300"],
    ["fixed-points", "--a", "1e-4", "--mu", "1000", "--friction", "viscous", "--omega0", "1e12", "--C", "1e-300"],
    ["fixed-points", "--a", "1.5", *VISCOUS, "--omega0", "10", "--A", "1e-150", "--C", "1e-150"],
    ["fixed-points", "--a", "1e4", "--mu", "1000", "--omega0", "1e12"],
    ["gyroscopic", "--a", "1.5", "--mu", "1000", "--omega0", "1e12", "--theta0", "1.56", "--t", "0", "1e300"],
    ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "11", "--stop-at",
     "touchdown", "--X0", "1e300", "--size", "1e10 m", "--si"],
    ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "1e300 rev/s", "--size",
     "1e-30 m"],
    ["simulate", "--a", "1.5", "--mu", "1000", "--friction", "viscous", "--gyroscopic", "--theta0", "1.5", "--omega0",
     "1e5", "--t-end", "1e-3"],
    ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "11", "--t-end", "2 s",
     "--size", "1e30 m", "--g", "1e-30 m/s^2", "--si"],
]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.timeout(300)  # a hang guard
@pytest.mark.parametrize("args", CASES, ids=range(len(CASES)))
def test_a_result_or_one_clear_line(args):
    code, out, err = run_cli(*args, "--json")
    assert "encountered" not in err and "RuntimeWarning" not in err and "Traceback" not in err, err
    d = strict_json(out)
    if code == 2:
        assert err.count("\n") == 1 and d["parameter"] in args
        assert all(f in args or f in cli.build_parser().known_flags
                   for f in re.findall(r"--[A-Za-z][\w-]*", d["message"]))
    else:
        assert code in (0, 1) and (code == 0) == (d.get("status") != "failed")  # (gyroscopic has no status)
        assert not [ln for ln in err.splitlines() if "warning" in ln]
