"""Values with units on the command line (``--size``, ``--g``, ``'41 rev/s'``, degrees) and ``--si``
output in real units; bad units are one line naming the flag."""

import math

import pytest

from ..helpers import run_cli, strict_json

B, G = 0.0215, 9.81  # 21.5 mm, standard gravity: the time unit is sqrt(b/g) seconds
T = math.sqrt(B / G)
RUN = ["simulate", "--a", "1.5", "--mu", "0.1", "--gyroscopic", "--stop-at", "touchdown", "--json"]


def _run(*args):
    code, out, err = run_cli(*RUN, *args)
    assert code == 0, err
    return strict_json(out)


def test_cli_values_with_units_are_the_same_run_as_plain_numbers():
    """--omega0 '41 rev/s' with --size '21.5 mm' is Omega0 = 41 * 2 pi * sqrt(b/g) (computed
    here by hand), and '2460 rpm' is the same spin; angles take degrees without --size."""
    omega0 = 41 * 2 * math.pi * T
    plain = _run("--theta0", repr(math.radians(89.4)), "--omega0", repr(omega0))
    units = _run("--theta0", "89.4 deg", "--omega0", "41 rev/s", "--size", "21.5 mm")
    rpm = _run("--theta0", "89.4 deg", "--omega0", "2460 rpm", "--size", "21.5 mm", "--g", "9.81 m/s^2")
    assert units["start"]["Omega"] == pytest.approx(omega0, rel=1e-14)
    assert units["t_jump"] == pytest.approx(plain["t_jump"], rel=1e-12)
    assert rpm["t_jump"] == pytest.approx(plain["t_jump"], rel=1e-12)


def test_si_reports_times_gaps_and_spins_in_real_units():
    d = _run("--theta0", "1.5607963", "--omega0", "11", "--size", "21.5 mm", "--si")
    si = d["si"]
    assert si["units"] == {"time": "ms", "length": "mm", "speed": "m/s", "rate": "rev/s", "angle": "rad"}
    assert si["t_jump"] == pytest.approx(d["t_jump"] * T * 1e3, rel=1e-12)
    assert si["flight"]["gap_max"] == pytest.approx(d["flight"]["gap_max"] * B * 1e3, rel=1e-12)
    assert si["flight"]["duration"] == pytest.approx((d["flight"]["t_touchdown"] - d["flight"]["t_liftoff"]) * T * 1e3,
                                                     rel=1e-12)
    assert si["state_at_jump"]["Omega"] == pytest.approx(d["state_at_jump"]["Omega"] / T / (2 * math.pi), rel=1e-12)
    assert si["pose_end"]["X"] == pytest.approx(d["pose_end"]["X"] * B * 1e3, rel=1e-12)
    assert si["time_unit"] == "46.815 ms"


@pytest.mark.parametrize("args, flag, says", [
    (["--omega0", "41 rev/s"], "--omega0", "--size"),  # units without the body's size
    (["--omega0", "41 Hz", "--size", "21.5 mm"], "--omega0", "hertz"),
    (["--omega0", "41 mm", "--size", "21.5 mm"], "--omega0", "'41 mm'"),  # echoed as typed
    (["--omega0", "11", "--size", "21.5 kg"], "--size", "length"),
    (["--omega0", "11", "--size", "-3 mm"], "--size", "> 0"),
    (["--omega0", "11", "--g", "9.81 m/s^2"], "--g", "--size"),
    (["--omega0", "11", "--si"], "--si", "--size"),
    (["--omega0", "11", "--theta0", "89 m"], "--theta0", "angle"),
    (["--omega0", "11", "--t-end", "2 s"], "--t-end", "--size"),
])
def test_bad_units_are_one_line_naming_the_flag(args, flag, says):
    base = [a for a in RUN if a != "--json"]
    if "--theta0" not in args:
        args = [*args, "--theta0", "1.56"]
    code, out, err = run_cli(*base, *args, "--json")
    d = strict_json(out)
    assert code == 2 and d["status"] == "error" and d["parameter"] == flag
    assert err.count("\n") == 1 and err.startswith(f"phasekit: error: {flag}") and says in err
    assert "Traceback" not in err
