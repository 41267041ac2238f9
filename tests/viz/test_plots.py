"""The matplotlib helpers draw the sampled data, and refuse bad arguments naming them."""

import phasekit as pk

import numpy as np
import pytest

from ..helpers import raises_param

NAN, INF = float("nan"), float("inf")
B = pk.Spheroid(1.5)


@pytest.fixture(scope="module")
def traj():
    return pk.simulate(pk.Model(B, pk.Coulomb(0.1)), pk.gyroscopic_start(B, 1.5, omega0=12.0), 20.0)


@pytest.fixture()
def ax():
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def _mpl_bad_calls():
    from phasekit.viz import plain_log_ticks, plot_events, plot_minima, plot_phase, plot_section, plot_timeseries

    return [
        ("names", lambda ax, tr: plot_timeseries(ax, tr, ["RR"])),
        ("names", lambda ax, tr: plot_timeseries(ax, tr, [])),
        ("names", lambda ax, tr: plot_timeseries(ax, tr, 5)),
        ("ax", lambda ax, tr: plot_timeseries(None, tr, ["R"])),
        ("traj", lambda ax, tr: plot_timeseries(ax, "traj", ["R"])),
        ("n", lambda ax, tr: plot_timeseries(ax, tr, "R", n=0)),
        ("times", lambda ax, tr: plot_timeseries(ax, tr, "R", times=[NAN])),
        ("set_labels", lambda ax, tr: plot_timeseries(ax, tr, "R", set_labels="yes")),
        ("style", lambda ax, tr: plot_timeseries(ax, tr, "R", colr="r")),
        ("x", lambda ax, tr: plot_phase(ax, tr, "Theta", "Lambda")),
        ("y", lambda ax, tr: plot_phase(ax, tr, "theta", ["Lambda"])),
        ("ax", lambda ax, tr: plot_phase(object(), tr, "theta", "Lambda")),
        ("traj", lambda ax, tr: plot_phase(ax, None, "theta", "Lambda")),
        ("df", lambda ax, tr: plot_section(ax, tr, "theta", "Lambda")),
        ("x", lambda ax, tr: plot_section(ax, tr.sample([0.0, 1.0]), "thta", "Lambda")),
        ("c", lambda ax, tr: plot_section(ax, tr.sample([0.0, 1.0]), "theta", "Lambda", c="time")),
        ("ax", lambda ax, tr: plot_section(None, tr.sample([0.0, 1.0]), "theta", "Lambda")),
        ("ax", lambda ax, tr: plot_events(None, tr)),
        ("traj", lambda ax, tr: plot_events(ax, [])),
        ("names", lambda ax, tr: plot_events(ax, tr, 5)),
        ("ax", lambda ax, tr: plot_minima(None, tr)),
        ("traj", lambda ax, tr: plot_minima(ax, None)),
        ("axis", lambda ax, tr: plain_log_ticks(ax, "z")),
        ("ax", lambda ax, tr: plain_log_ticks(None)),
    ]


@pytest.mark.parametrize("k", range(24))
def test_plots_reject(k, ax, traj):
    calls = _mpl_bad_calls()
    assert len(calls) == 24
    name, call = calls[k]
    raises_param(name, lambda: call(ax, traj))


def test_plots_valid_draw_the_sampled_data(ax, traj):
    from phasekit.viz import plot_phase, plot_section, plot_timeseries

    ts = np.linspace(0.0, 20.0, 11)
    df = traj.sample(ts)
    (line,) = plot_timeseries(ax, traj, "R", times=ts)
    np.testing.assert_array_equal(line.get_xdata(), ts)
    np.testing.assert_array_equal(line.get_ydata(), df["R"])
    assert ax.get_ylabel() == "R [M g]"
    (curve,) = plot_phase(ax, traj, "theta", "Lambda", times=ts)
    np.testing.assert_array_equal(curve.get_ydata(), df["Lambda"])
    art = plot_section(ax, df, "theta", "Omega")
    np.testing.assert_array_equal(art.get_offsets(), df[["theta", "Omega"]].to_numpy())
    # the first point of the curve is the start: theta0 = 1.5 given to gyroscopic_start
    assert curve.get_xdata()[0] == pytest.approx(1.5, abs=1e-12)
