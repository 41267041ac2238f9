"""A refused value is shown as typed: '200 deg', not only the 3.49 it became (with that number,
in phasekit's units, beside it); a plain number is shown as before."""

import math

from phasekit import cli

import pytest

from ..helpers import run_cli, strict_json

RUN = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--stop-at", "touchdown"]


@pytest.fixture(autouse=True)
def _bugs_raise(monkeypatch):
    monkeypatch.setenv(cli.DEBUG_ENV, "1")


def message(*args) -> tuple[str, str]:
    code, out, err = run_cli(*RUN, *args, "--json")
    d = strict_json(out)
    assert code == 2 and err.count("\n") == 1, err
    return d["parameter"], d["message"]


def test_an_angle_typed_in_degrees_is_shown_in_degrees_and_radians():
    flag, msg = message("--theta0", "200 deg", "--omega0", "11")
    assert flag == "--theta0" and msg == f"--theta0 must lie in (0, pi), got '200 deg' ({math.radians(200)!r} rad)."


def test_a_rate_typed_in_rev_per_s_is_shown_so():
    flag, msg = message("--theta0", "1.5", "--omega0", "1e6 rev/s", "--size", "21.5 mm")
    omega = 1e6 * 2 * math.pi * math.sqrt(0.0215 / 9.81)
    assert flag == "--omega0" and msg.endswith(f"got '1e6 rev/s' ({omega!r} in units of sqrt(g/b)).")
    assert "2.9" not in msg.split("got")[0]


@pytest.mark.parametrize("t_end, size", [("1e-320 s", "1e25 m"), ("1e300 s", "1e-25 m")])
def test_an_end_time_out_of_double_precision_is_shown_as_typed(t_end, size):
    flag, msg = message("--theta0", "1.5", "--omega0", "11", "--t-end", t_end, "--size", size)
    assert flag == "--t-end" and msg.endswith(f"got {t_end!r}.") and "express in phasekit's units" in msg


def test_a_plain_number_is_shown_as_before():
    flag, msg = message("--theta0", "4", "--omega0", "11")
    assert msg == "--theta0 must lie in (0, pi), got 4.0."
