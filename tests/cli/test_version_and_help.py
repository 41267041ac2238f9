"""``--version`` and ``--help``: the version alone or as JSON, and help texts that state what the
commands accept."""

import json

import phasekit as pk
from phasekit import cli

import numpy as np
import pytest

from ..helpers import run_cli, run_module, strict_json


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    """An unexpected exception inside the CLI is a test failure, not a one-line message."""
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


SIM = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5607963", "--omega0", "10.5"]
GYRO = ["gyroscopic", "--mu", "0.1", "--t", "0", "10", "1000"]


def _refused(args, flag):
    code, out, err = run_cli(*args)
    assert code == 2 and out.count("\n") <= 1
    d = strict_json(out) if "--json" in args else None
    assert err.count("\n") == 1 and err.startswith(f"phasekit: error: {flag} ") and "Traceback" not in err
    if d is not None:
        assert d["status"] == "error" and d["parameter"] == flag
    return err


def test_version_with_json_is_json_and_wins_over_the_rest():
    code, out, err = run_cli("--version", *SIM, "--json")
    assert code == 0 and err == ""
    assert strict_json(out) == {"program": "phasekit", "version": pk.__version__}
    code, out, err = run_cli("--version")
    assert (code, out, err) == (0, f"phasekit {pk.__version__}\n", "")


def test_version_flag():
    code, out, _ = run_module("--version")
    assert code == 0 and out.strip() == f"phasekit {pk.__version__}"


def test_version_flag_help_says_json():
    assert "JSON" in json.dumps(cli.build_parser().format_help())


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
    help_text = cli.build_parser().commands["gyroscopic"].format_help()
    assert "1e12" in help_text
    err = _refused([*GYRO, *body, rate[0], "1e13", *theta0, "--json"], rate[0])
    assert "1e+12" in err


def _help_examples(text: str) -> list[str]:
    """The command lines of a help text's examples, continuation lines joined."""
    body = text.split("examples:", 1)[1]
    joined = body.replace("\\\n", " ")
    return [ln.strip() for ln in joined.splitlines() if ln.strip().startswith("phasekit ")]


def test_every_help_example_is_one_command_that_parses():
    """Each example of `phasekit --help` and of its commands' help is one command line (none runs
    into the next) that the parser accepts as written."""
    import shlex

    parser = cli.build_parser()
    examples = _help_examples(parser.format_help()) + _help_examples(parser.commands["animate"].format_help())
    assert len(examples) >= 10
    for text in (parser.format_help(), parser.commands["animate"].format_help()):
        for raw in text.split("examples:", 1)[1].splitlines():  # a lost line break leaves a gap
            assert "   " not in raw.strip() and len(raw) <= 110, raw
    for line in examples:
        words = shlex.split(line)
        assert words.count("phasekit") == 1, line
        parser.parse_args(words[1:])  # raises (a UsageError) on a line that does not parse
