"""A run says how it held the table: when it first stuck, how much of it rolled without slip,
how far its axis rose, and, when it ends rolling, that the answer rests on pure rolling (which
conserves energy, so the tilt cannot change)."""

import phasekit as pk
from phasekit.core.trajectory_io import PURE_ROLLING

import numpy as np
import pytest

from ..helpers import run_cli


@pytest.fixture(scope="module")
def egg_run():
    """The 60 x 45 mm egg at 25 rev/s, mu 0.2, 0.6 deg from flat: it sticks within 2 ms."""
    egg, sc = pk.core.egg_of_size("60 mm", "45 mm")
    x0 = pk.gyroscopic_start(egg, np.radians(89.4), omega0=sc.dimensionless("25 rev/s", "rate"))
    return pk.simulate(pk.Model(egg, pk.Coulomb(0.2)), x0, sc.dimensionless("2 s", "time"), stop_at="none"), sc


def test_an_egg_that_sticks_and_rolls_says_it_rests_on_pure_rolling(egg_run):
    run, sc = egg_run
    d = run.to_dict()
    [stick] = [e for e in run.events if e.name == "stick"]
    assert d["t_first_stick"] == stick.t and sc.to_real(stick.t, "time").to("ms").magnitude == pytest.approx(2.03, abs=0.01)
    assert d["rolling_fraction"] == pytest.approx((run.t - stick.t) / run.t, rel=1e-12)
    assert d["rests_on"] == PURE_ROLLING and d["mode_end"] == "rolling"
    # what the note says: while it rolls, the energy stays (no work is done), and so does the tilt
    rolling = run.sample(np.linspace(stick.t + 1e-6, run.t, 400))
    assert np.ptp(rolling["energy"]) < 1e-10 * abs(rolling["energy"].mean())
    assert abs(d["theta_change"]) < 1e-4 and d["theta_start"] == pytest.approx(np.radians(89.4), abs=1e-3)


def test_a_run_that_never_sticks_rests_on_nothing_and_reports_its_rise():
    body = pk.Spheroid(1.5)
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    run = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), x0, 200.0)
    d = run.to_dict()
    assert d["t_first_stick"] is None and d["rolling_fraction"] == 0.0 and d["rests_on"] is None
    ends = run.sample([0.0, run.t])["theta"].to_numpy()
    assert d["theta_start"] == pytest.approx(ends[0], abs=1e-12)
    assert d["theta_change"] == pytest.approx(ends[1] - ends[0], abs=1e-9) and d["theta_change"] < -0.5


def test_the_text_summary_says_it_in_words():
    code, out, err = run_cli("simulate", "--body", "egg", "--a", "1.33333", "--mu", "0.2", "--gyroscopic", "--theta0",
                             "89.4 deg", "--omega0", "25 rev/s", "--size", "22.5 mm", "--t-end", "1 s")
    assert code == 0, err
    lines = out.splitlines()
    assert PURE_ROLLING in lines and not any(ln.startswith("stuck:") for ln in lines)
    assert any(ln.startswith("the axis rose (theta fell) by ") and "first from t = " in ln for ln in lines)
