"""A movie given a Scale is labelled in real units on every axis: the side panel's time in ms (s
for a span over 10 s), R in N (in M g without a mass), rates in rev/s, the caption's gap in mm;
without one, in the body's units. The values drawn are the run's, converted (checked against
b = 21.5 mm, g = 9.81 m/s^2, M = 57 g by hand)."""

import math

import phasekit as pk
from phasekit.viz.frames import _Panel, _Units

import numpy as np
import pytest

B, G, M = 0.0215, 9.81, 0.057  # m, m/s^2, kg
T_UNIT = math.sqrt(B / G)  # s


@pytest.fixture(scope="module")
def traj():
    body = pk.Spheroid(1.5)
    return pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.55, omega0=11.0), 6.0)


def _axes(panel):
    ax = panel.fig.axes[0]
    line = ax.get_lines()[0]
    return ax, np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)


def _labels(panel) -> list[str]:
    ax = panel.fig.axes[0]
    out = [ax.get_xlabel(), ax.get_ylabel()]
    return out + ([ax.get_zlabel()] if hasattr(ax, "get_zlabel") else [])


def test_the_R_panel_is_in_ms_and_newtons_with_a_scale_of_known_mass(traj):
    span = (0.0, traj.t)
    ts = np.linspace(*span, 3000)
    R = traj.sample(ts)["R"].to_numpy()
    body = _Panel(traj, "R", span, 200)
    weightless = _Panel(traj, "R", span, 200, pk.Scale("21.5 mm"))
    heavy = _Panel(traj, "R", span, 200, pk.Scale("21.5 mm", mass="57 g"))
    assert _labels(body) == ["t (sqrt(b/g))", "R (M g)"]
    assert _labels(weightless) == ["t (ms)", "R (M g)"]
    assert _labels(heavy) == ["t (ms)", "R (N)"]
    _, x, y = _axes(body)
    np.testing.assert_allclose(x, ts, rtol=1e-14)
    _, x, y = _axes(heavy)
    np.testing.assert_allclose(x, ts * T_UNIT * 1e3, rtol=1e-12)
    np.testing.assert_allclose(y, R * M * G, rtol=1e-12, atol=1e-15)
    _, x, y = _axes(weightless)
    np.testing.assert_allclose(y, R, rtol=1e-14)


def test_the_phase_panel_is_in_rev_per_second_and_a_long_span_in_seconds(traj):
    span = (0.0, traj.t)
    df = traj.sample(np.linspace(*span, 3000))
    panel = _Panel(traj, "phase", span, 200, pk.Scale("21.5 mm"))
    assert _labels(panel) == ["Omega (rev/s)", "theta (rad)", "n (rev/s)"]
    line = panel.fig.axes[0].get_lines()[0]
    x, y, z = (np.asarray(v, float) for v in line.get_data_3d())
    np.testing.assert_allclose(x, df["Omega"] / T_UNIT / (2 * math.pi), rtol=1e-12)
    np.testing.assert_allclose(y, df["theta"], rtol=1e-14)
    np.testing.assert_allclose(z, df["n"] / T_UNIT / (2 * math.pi), rtol=1e-12, atol=1e-12)
    assert _labels(_Panel(traj, "phase", span, 200))[0] == "Omega (sqrt(g/b))"
    big = pk.Scale("2 m")  # sqrt(b/g) = 0.45 s: six units of time are 2.7 s, sixty would be 27 s
    assert _Units(big, (0.0, 6.0)).time_unit == "ms" and _Units(big, (0.0, 60.0)).time_unit == "s"
    assert _Units(big, (0.0, 60.0)).time(60.0) == pytest.approx(60.0 * math.sqrt(2.0 / G), rel=1e-12)


def test_the_caption_units_are_simple_words(traj):
    units = _Units(pk.Scale("21.5 mm"), (0.0, traj.t))
    assert (units.time_unit, units.gap_unit, units.force_unit) == ("ms", "mm", "M g")
    assert units.gap(0.001) == pytest.approx(0.0215, rel=1e-12)  # 0.001 b = 21.5 um
    assert units.time(1.0) == pytest.approx(T_UNIT * 1e3, rel=1e-12)
    for panel in (_Panel(traj, "R", (0.0, traj.t), 200, pk.Scale("21.5 mm", mass="57 g")),
                  _Panel(traj, "phase", (0.0, traj.t), 200, pk.Scale("21.5 mm"))):
        assert all("**" not in s and "meter" not in s and "second" not in s for s in _labels(panel))
