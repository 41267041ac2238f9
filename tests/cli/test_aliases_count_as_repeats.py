"""An option and its other name are one option: given under both names (``--chart euler
--formulation vector``) it is refused as a repeat, as ``--chart`` twice is, for every pair of
names of every command (argparse would keep the last silently)."""

import itertools

from phasekit import cli
from phasekit.cli.parser import build_parser, refuse_repeats

import pytest

from ..helpers import run_cli, strict_json

#: a valid command line of each command, and a value for each option that takes one
BASE = {"simulate": ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0", "10",
                     "--t-end", "1"],
        "animate": ["animate", "x.gif", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.5", "--omega0",
                    "10", "--t-end", "1"],
        "fixed-points": ["fixed-points", "--a", "1.5", "--mu", "0.1", "--omega0", "10"],
        "steady-states": ["steady-states", "--a", "1.5", "--mu", "0.1"],
        "gyroscopic": ["gyroscopic", "--a", "1.5", "--mu", "0.1", "--omega0", "10", "--theta0", "1.5", "--t", "0"]}
VALUES = {"chart": ("euler", "vector")}


def alias_pairs():
    """(command, first name, second name, values) for every option with several long names."""
    parser = build_parser()
    for command, p in parser.commands.items():
        for action in p._actions:
            names = [s for s in action.option_strings if s.startswith("--")]
            for a, b in itertools.permutations(names, 2):
                yield command, a, b, VALUES.get(action.dest, ())


PAIRS = list(alias_pairs())


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def test_the_options_with_two_names_are_known():
    assert {(c, a, b) for c, a, b, _ in PAIRS} == {(c, a, b) for c in ("simulate", "animate")
                                                  for a, b in (("--chart", "--formulation"), ("--formulation", "--chart"))}
    assert all(values for *_, values in PAIRS)  # each has values to give it (so that the test runs it)


@pytest.mark.parametrize("command, first, second, values", PAIRS)
def test_both_names_of_one_option_are_a_repeat(command, first, second, values):
    for extra in ([first, values[0], second, values[1]], [f"{first}={values[0]}", f"{second}={values[1]}"]):
        code, out, err = run_cli(*BASE[command], *extra, "--json")
        d = strict_json(out)
        assert code == 2 and d["parameter"] == second, (extra, err)
        assert err.count("\n") == 1 and first in err and second in err and "give it once" in err
        assert values[0] in err and values[1] in err  # both values, as typed


@pytest.mark.parametrize("command, first, second, values", PAIRS)
def test_each_name_alone_is_taken(command, first, second, values):
    """Parsed (no movie is drawn), and a simulate run uses the chart given under either name."""
    parser = build_parser()
    for flag in (first, second):
        argv = [*BASE[command], flag, values[1]]
        args = parser.parse_args(argv)
        refuse_repeats(parser.commands[command], argv)
        assert args.chart == values[1]
    if command == "simulate":
        code, out, err = run_cli(*BASE[command], second, values[1], "--json")
        assert code == 0 and strict_json(out)["chart"] == values[1], err
