"""Real units in and out: CLI values with units, --si, and Scale on arrays, columns and tables."""

import math

import phasekit as pk

import numpy as np
import pandas as pd
import pytest

from .helpers import run_cli, strict_json

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


def test_scale_converts_arrays_columns_and_tables():
    sc = pk.Scale("21.5 mm")
    assert f"{sc.time_unit:.4g~P}" == "46.81 ms" and "ms" in repr(sc) and "**" not in repr(sc)
    q = sc.to_real(np.array([0.0, 1.0, 2.0]), "time")
    assert str(q.units) == "millisecond"
    np.testing.assert_allclose(q.magnitude, np.array([0.0, 1.0, 2.0]) * T * 1e3, rtol=1e-14)
    np.testing.assert_allclose(sc.quantity([1.0, 2.0], "length").to("m").magnitude, [B, 2 * B], rtol=1e-14)
    col = sc.to_real(pd.Series([1.0, 3.0], name="Omega"), "rate")
    assert col.name == "Omega" and col.attrs["unit"] == "rev/s"
    np.testing.assert_allclose(col.to_numpy(), np.array([1.0, 3.0]) / T / (2 * math.pi), rtol=1e-14)
    body = pk.Spheroid(1.5)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=10.5), 3.0)
    df = traj.sample([0.0, 1.5, 3.0])
    real = sc.table(df)
    assert real.attrs["units"]["t"] == "ms" and real.attrs["units"]["X"] == "mm" and real.attrs["units"]["n"] == "rev/s"
    assert real.attrs["units"]["theta"] == "rad" and real.attrs["units"]["R"] == "M g"  # no mass given
    np.testing.assert_allclose(real["gap"], df["gap"] * B * 1e3)
    np.testing.assert_allclose(real["t"], df["t"] * T * 1e3, rtol=1e-14)
    np.testing.assert_array_equal(real["theta"], df["theta"])
    heavy = pk.Scale("21.5 mm", mass="57 g").table(df)
    np.testing.assert_allclose(heavy["R"], df["R"] * 0.057 * G, rtol=1e-12)
    assert heavy.attrs["units"]["R"] == "N"
    with pytest.raises(pk.ParameterError, match="`unit`"):
        sc.to_real(1.0, "time", unit="mm")
