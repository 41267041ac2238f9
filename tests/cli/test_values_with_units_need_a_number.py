"""A value typed with units must have its number: pint reads a unit alone ("mm", "rev/s") as one
of it, so ``--size mm`` was 1 mm. Every flag of every command that takes a value with units
refuses one without a number, in one line naming the flag."""

from phasekit import cli
from phasekit.cli.options import quantity_text, real_or_units
from phasekit.cli.parser import build_parser

import pytest

from ..helpers import run_cli, strict_json

RUN = ["--a", "1.5", "--mu", "0.1", "--gyroscopic", "--theta0", "1.56", "--omega0", "11", "--stop-at", "touchdown",
       "--size", "21.5 mm"]
#: a unit without its number for each kind of value, and the same with a number (accepted)
BARE = {"--thickness": ("cm", "1.2 cm"), "--flat-angle": ("deg", "0.05 deg"), "--height": ("cm", "4 cm"), "--stem-length": ("mm", "6 mm"), "--air-layer": ("N*m*s", "1e-9 N*m*s"), "--stem-radius": ("mm", "3.2 mm"), "--radius": ("cm", "3.7 cm"), "--theta0": ("deg", "89 deg"), "--omega0": ("rev/s", "41 rev/s"), "--n0": ("rpm", "2000 rpm"),
        "--spin-about-vertical": ("rev/s", "10 rev/s"), "--spun-about-axis": ("rev/s", "40 rev/s"),
        "--spun-on-edge": ("rev/s", "5 rev/s"), "--rolled": ("m/s", "0.3 m/s"), "--t-end": ("s", "0.5 s"), "--psi0": ("deg", "30 deg"),
        "--phi0": ("turn", "0.5 turn"), "--X0": ("mm", "3 mm"), "--Y0": ("cm", "1 cm"), "--size": ("mm", "21.5 mm"),
        "--g": ("m/s^2", "9.81 m/s^2"), "--mass": ("g", "57 g"), "--rolling-resistance": ("mm", "0.2 mm"),
        "--spin-friction": ("um", "50 um"), "--patch": ("um", "50 um"), "--air-drag": ("N*m*s", "1e-7 N*m*s"),
        "--air-drag-quadratic": ("N*m*s^2", "1e-9 N*m*s^2"), "--air-drag-force": ("N*s/m", "1e-4 N*s/m"),
        "--air-drag-force-quadratic": ("kg/m", "0.001 kg/m")}

#: the starts that take a value with units (another start given with them is left out)
STARTS = ("--spin-about-vertical", "--spun-about-axis", "--spun-on-edge", "--rolled")


def unit_flags(command: str) -> set[str]:
    """The flags of ``command`` that take a value with units (by their parser type)."""
    parser = build_parser().commands[command]
    return {f for a in parser._actions if a.type in (real_or_units, quantity_text) for f in a.option_strings}


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def test_every_flag_with_units_is_covered():
    assert unit_flags("simulate") == unit_flags("animate") == set(BARE)
    # the steady states take the body's lengths and the rate that picks a family with units too (--size, --g)
    steady = {"--thickness", "--flat-angle", "--height", "--stem-length", "--stem-radius", "--radius", "--omega0",
              "--n0", "--size", "--g"}
    assert unit_flags("fixed-points") == unit_flags("steady-states") == steady
    assert unit_flags("gyroscopic") == set()


@pytest.mark.parametrize("command", ["simulate", "animate"])
@pytest.mark.parametrize("flag", sorted(BARE))
def test_a_unit_without_its_number_is_refused(command, flag):
    bare = BARE[flag][0]
    args = [command, *(["x.gif"] if command == "animate" else []), *RUN]
    args = [a for i, a in enumerate(args) if not (a == flag or (i and args[i - 1] == flag))]  # the flag once
    args = [a for i, a in enumerate(args)
            if flag not in STARTS or a not in ("--gyroscopic", "--omega0") and args[i - 1] != "--omega0"]
    code, out, err = run_cli(*args, flag, bare, "--json")
    d = strict_json(out)
    assert code == 2 and d["status"] == "error" and d["parameter"] == flag
    assert err.count("\n") == 1 and err.startswith(f"phasekit: error: argument {flag}: ") and repr(bare) in err
    assert "needs its number" in err


@pytest.mark.parametrize("flag", sorted(BARE))
def test_the_same_unit_with_a_number_is_read(flag):
    """The parser's types take the value with its number (the run's own checks come later)."""
    parser = build_parser().commands["simulate"]
    kind = parser._option_string_actions[flag].type
    assert kind(BARE[flag][1]) == BARE[flag][1]
    assert kind("inf mm") == "inf mm"  # refused later as not finite, naming the flag
    assert kind("(2 mm * 8 mm)**0.5") == "(2 mm * 8 mm)**0.5"  # a number written as a product


def test_a_unit_alone_is_not_one_of_it():
    code, out, err = run_cli("simulate", *RUN[:-2], "--size", "mm", "--si", "--json")
    assert code == 2 and strict_json(out)["parameter"] == "--size"
    code, out, err = run_cli("simulate", *RUN[:-2], "--size", "1 mm", "--si", "--json")
    assert code == 0 and strict_json(out)["si"]["b"] == "1 mm"
