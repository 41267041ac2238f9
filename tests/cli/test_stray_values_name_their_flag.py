"""A value that no option takes is blamed on the option it follows, found by reading the command
line as argparse does, not by the first equal text (``--offset 0.3 --mu 0.3 0.3``: ``--mu``)."""

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

TOP = ["--body", "tippe-top", "--offset", "0.3"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


@pytest.mark.parametrize("args, flag, takes", [
    (["fixed-points", *TOP, "--mu", "0.3", "0.3", "--n0", "1.04"], "--mu", "one value"),
    (["fixed-points", *TOP, "--mu", "0.3", "--n0", "1.04", "0.3"], "--n0", "one value"),
    (["fixed-points", "--offset=0.3", "--body", "tippe-top", "--mu", "0.3", "0.3", "--n0", "1"], "--mu", "one value"),
    (["steady-states", *TOP, "--mu", "0.3", "--json", "0.3"], "--json", "no value"),
    (["simulate", "--a", "1", "--mu", "1", "--state", "0", "0", "1", "0", "1", "0", "1"], "--state", "exactly 6 numbers"),
    (["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "1.5", "1.5"], "--omega0",
     "one value"),
    (["animate", "x.gif", "--a", "1.5", "--mu", "1.5", "x.gif", "--gyroscopic", "--theta0", "1.5", "--omega0", "10"],
     "--mu", "one value"),  # the movie's file taken first, then the same text again is stray
    (["gyroscopic", "--a", "1.5", "--mu", "-1", "-1", "--omega0", "10", "--theta0", "1.5", "--t", "0"], "--mu",
     "one value"),  # a negative number is a value, not an option
])
def test_a_stray_value_names_the_option_it_follows(args, flag, takes):
    code, out, err = run_cli(*args, "--json")
    d = strict_json(out)
    assert code == 2 and d["parameter"] == flag, err
    assert err.count("\n") == 1 and f"after {flag}, which takes {takes}" in err
