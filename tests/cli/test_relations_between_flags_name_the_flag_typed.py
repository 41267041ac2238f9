"""An error about a relation between flags names the flag(s) the user typed, and says which
value is the body's default: ``--A 1e-300`` with the default C = 0.4 violates C <= 2A (the library
names ``C``, which was not typed). Every command that builds a body, and every start that
needs a rate, is checked."""

import re

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

LAW = ["--mu", "0.1", "--friction", "viscous"]
COMMANDS = {"fixed-points": ["fixed-points", *LAW, "--omega0", "10"],
            "steady-states": ["steady-states", *LAW],
            "simulate": ["simulate", *LAW, "--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--t-end", "1"],
            "gyroscopic": ["gyroscopic", "--mu", "0.1", "--omega0", "10", "--theta0", "1.5", "--t", "0"]}
#: (body flags, the body's default A, its default C)
BODIES = {"spheroid": (["--a", "1.5"], 0.65, 0.4), "tippe-top": (["--body", "tippe-top", "--offset", "0.3", "--stem-length", "0"], 0.31, 0.4)}


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def refused(args) -> dict:
    """Exit 2, one line, the flag it is about was typed and is named first (others may be named
    as advice); returns the JSON error."""
    code, out, err = run_cli(*args, "--json")
    d = strict_json(out)
    assert code == 2 and err.count("\n") == 1, err
    named = re.findall(r"--[A-Za-z][\w-]*", d["message"])
    assert d["parameter"] in args and named[0] in args, (named, args)
    return d


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("body", sorted(BODIES))
def test_a_moment_below_half_the_default_other_names_the_one_typed(command, body):
    flags, A, C = BODIES[body]
    d = refused([*COMMANDS[command], *flags, "--A", "1e-300"])
    assert d["parameter"] == "--A"
    assert d["message"].startswith(f"--A 1e-300 with the default C = {C:g} violates C <= 2A")
    assert f"--A >= {C / 2:g}" in d["message"]
    d = refused([*COMMANDS[command], *flags, "--C", "1.4"])
    assert d["parameter"] == "--C" and d["message"].startswith(f"--C 1.4 with the default A = {A:g} violates C <= 2A")
    assert f"--C <= {2 * A:g}" in d["message"]


def test_two_moments_typed_name_both():
    d = refused([*COMMANDS["fixed-points"], "--a", "1.5", "--A", "0.3", "--C", "0.7"])
    assert d["parameter"] == "--C" and d["message"].startswith("--C 0.7 with --A 0.3 violates C <= 2A")


def test_a_moment_too_small_for_double_precision_is_refused():
    """C = 1e-300 met C <= 2A but gave a 'state' with residual 4e+283 and an overflow warning."""
    d = refused([*COMMANDS["fixed-points"], "--body", "tippe-top", "--offset", "0.3", "--C", "1e-300"])
    assert d["parameter"] == "--C" and d["message"].startswith("--C must be at least 1e-06")
    d = refused([*COMMANDS["fixed-points"], "--a", "1.5", "--A", "1e-300", "--C", "1e-300"])
    assert d["parameter"] == "--A"


@pytest.mark.parametrize("args, flag, says", [
    (["--unstable-manifold", "vertical", "--omega0", "3"], "--omega0", "given by --n0"),
    (["--unstable-manifold", "horizontal", "--n0", "3"], "--n0", "given by --omega0"),
    (["--unstable-manifold", "horizontal"], "--unstable-manifold", "needs --omega0"),
    (["--unstable-manifold", "inverted"], "--unstable-manifold", "needs --n0"),
    (["--gyroscopic", "--theta0", "1.5"], "--gyroscopic", "exactly one of --omega0"),
    (["--gyroscopic", "--omega0", "10"], "--gyroscopic", "needs --theta0"),
    (["--spin-about-vertical", "10"], "--spin-about-vertical", "needs --theta0"),
    (["--gyroscopic", "--theta0", "1.5", "--omega0", "10", "--n0", "10"], "--n0", "exactly one of --omega0"),
])
def test_a_start_that_needs_a_rate_names_what_was_typed(args, flag, says):
    d = refused(["simulate", "--a", "1.5", "--mu", "0.1", *args])
    assert d["parameter"] == flag and says in d["message"]
