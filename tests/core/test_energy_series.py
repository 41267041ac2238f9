"""The energy budget as a time series (Trajectory.energy_series) and drawn (pk.viz.plot_energy):
against a closed form (a sphere spinning in place under spin friction), the balance at every
row of runs with every law on and with impacts, the last row against energy_budget(), the
values at arbitrary times against the budgets of the same runs stopped there, and bad times.

The runs with every law on are those of tests/core/test_energy_budget.py (euler chart): a
prolate spheroid a = 1.5 that sticks and slips again (mu = 0.2; 11 events by t = 30) and one
that hops (mu = 0.1, Omega0 = 15, e = 0.5; ~900 events by t = 60). Measured: |residual| at most
4e-13 and 2.4e-10 of their 1.2 and 74 units of energy; each run stopped at an arbitrary time
t_end takes the same Taylor steps (the last cut short), so its budget is the series' row at
t_end to ~1e-14.
"""

import phasekit as pk
from phasekit.core import vertical_spin_start

import numpy as np
import pytest

SPHERE = pk.EccentricSphere(0.0)  # radius 1, G at the centre, C = 2/5 (units M, b, g)
PROLATE = pk.Spheroid(1.5)
BUDGET = dict(max_wall=120.0, max_steps=500_000)
LAW_NAMES = ["sliding friction", "rolling-resistance", "spin-friction", "air-drag"]


def _laws(scale):
    return (pk.RollingResistance(5e-3 * scale), pk.SpinFriction(2e-3 * scale),
            pk.AirDrag(1e-4 * scale, 1e-4 * scale, 1e-4 * scale, 1e-4 * scale))


def _stick_slip(t_end=30.0):
    m = pk.Model(PROLATE, pk.Coulomb(0.2).with_dissipation(*_laws(1.0)), "euler")
    return pk.simulate(m, m.chart.from_paper([0.0, 0.0, 0.5, 0.0, 1.0, 0.0]), t_end, stop_at="rest", **BUDGET)


def _hopping(t_end=60.0):
    m = pk.Model(PROLATE, pk.Coulomb(0.1).with_dissipation(*_laws(0.2)), "euler")
    x0 = m.chart.from_paper(pk.gyroscopic_start(PROLATE, np.pi / 2 - 0.01, omega0=15.0))
    return pk.simulate(m, x0, t_end, stop_at="rest", restitution=0.5, **BUDGET)


RUNS = {"stick-slip": _stick_slip, "hopping": _hopping}


@pytest.fixture(scope="module", params=list(RUNS))
def run(request):
    return request.param, RUNS[request.param]()


# -- a closed form ------------------------------------------------------------------------------


def _spinning_sphere(mu_s, n0):
    m = pk.Model(SPHERE, pk.Coulomb(0.3).with_dissipation(pk.SpinFriction(mu_s)), "euler")
    return pk.simulate(m, m.chart.from_paper([0.0, 0.0, n0, 0.0, np.pi / 2, 0.0]), 4.0 * SPHERE.C * abs(n0) / mu_s,
                       stop_at="rest", **BUDGET)


@pytest.mark.timeout(300)
@pytest.mark.parametrize("mu_s, n0", [(0.02, 3.0), (0.05, -1.3)])
def test_a_sphere_spinning_in_place_loses_its_energy_quadratically_to_spin_friction(mu_s, n0):
    """Spinning in place about the vertical (v = 0, R = 1, G at height 1): spin friction's couple
    -mu_s sign(w) e_Z gives C dw/dt = -mu_s sign(w), so w(t) = n0 - sign(n0) mu_s t / C until
    t* = C |n0| / mu_s; the energy is E(t) = 1 + C w(t)^2 / 2 and spin friction has taken out
    C (n0^2 - w(t)^2) / 2, the rest nothing. At the step ends and at times inside steps."""
    C = SPHERE.C
    r = _spinning_sphere(mu_s, n0)
    assert r.status is pk.Status.REST, r.reason
    t_rest = C * abs(n0) / mu_s
    chosen = np.array([0.0, 0.0137, 0.31, 0.5 * np.sqrt(2.0), 0.577, 0.93]) * t_rest
    for df in (r.energy_series(), r.energy_series(chosen)):
        t = df["t"].to_numpy()
        w = n0 - np.sign(n0) * mu_s * np.minimum(t, t_rest) / C
        assert len(df) >= 5 and t[-1] <= t_rest * (1 + 1e-9)
        assert df["energy"].to_numpy() == pytest.approx(1.0 + C * w ** 2 / 2, rel=1e-9, abs=1e-12)
        assert df["spin-friction"].to_numpy() == pytest.approx(C * (n0 ** 2 - w ** 2) / 2, rel=1e-9, abs=1e-12)
        assert np.max(np.abs(df["sliding friction"].to_numpy())) < 1e-12
        assert np.all(df["at_events"].to_numpy() == 0.0)
    assert np.array_equal(r.energy_series(chosen[::-1])["t"].to_numpy(), np.sort(chosen))  # sorted
    assert list(r.energy_series().columns) == ["t", "energy", "sliding friction", "spin-friction", "at_events",
                                               "residual"]


# -- the balance along runs with every law on ---------------------------------------------------


@pytest.mark.timeout(300)
def test_the_balance_holds_at_every_row_and_the_laws_only_take_energy_out(run):
    kind, traj = run
    df = traj.energy_series()
    E0 = df["energy"].iloc[0]
    assert list(df.columns) == ["t", "energy", *LAW_NAMES, "at_events", "residual"]
    assert len(df) > traj.n_steps // 2 and np.all(np.diff(df["t"].to_numpy()) >= 0.0)
    assert df["t"].iloc[0] == traj.t0 and df["t"].iloc[-1] == traj.t
    lost = E0 - df["energy"].iloc[-1]
    assert lost > 0.1 * E0
    # the residual is the balance, recomputed here from the other columns
    balance = E0 - df["energy"] - df[LAW_NAMES].sum(axis=1) - df["at_events"]
    assert np.allclose(df["residual"], balance, rtol=0, atol=1e-13 * E0)
    assert np.max(np.abs(df["residual"])) <= 1e-8 * lost
    laws = df[LAW_NAMES].to_numpy()
    assert np.all(laws[0] == 0.0) and np.all(laws[-1] > 0.0)  # every law acted
    assert np.all(np.diff(laws, axis=0) >= -1e-12 * E0)  # and only took energy out
    # the energy lost at events changes at events only: from a segment's last row to the next one's first
    t, jumps = df["t"].to_numpy(), np.diff(df["at_events"].to_numpy())
    # a boundary is the pair (one segment's end, the next one's start), so a segment of one step whose two
    # rows are the ends of its neighbours' boundaries is not taken for one
    pairs = {(a.t1, b.t0) for a, b in zip(traj.segments[:-1], traj.segments[1:])}
    at_event = np.array([(t0, t1) in pairs for t0, t1 in zip(t[:-1], t[1:])])
    assert np.count_nonzero(at_event) == len(traj.segments) - 1
    assert np.all(jumps[~at_event] == 0.0) and np.count_nonzero(jumps) > 0.5 * (len(traj.segments) - 1)
    if kind == "hopping":  # impacts at e = 0.5: a good share of what was lost
        assert df["at_events"].iloc[-1] > 0.1 * lost and jumps.max() > 1e-4


@pytest.mark.timeout(300)
def test_the_last_row_is_the_energy_budget(run):
    _, traj = run
    b = traj.energy_budget()
    last = traj.energy_series().iloc[-1]
    assert last["t"] == traj.t
    assert last["energy"] == b.energy_end
    scale = b.energy_start * 1e-13
    for name, value in zip(b.laws, b.dissipated):
        assert abs(last[name] - value) <= scale, name
    assert abs(last["at_events"] - b.at_events) <= scale
    assert abs(last["residual"] - b.residual) <= scale
    assert np.max(np.abs(traj.energy_series()["residual"])) == pytest.approx(b.residual_max, rel=1e-6)


@pytest.mark.timeout(300)
def test_the_series_at_a_time_is_the_budget_of_the_same_run_stopped_there(run):
    """A run stopped at t_end takes the same steps, the last cut short: its energy_budget() is an
    independent account of the first t_end time units (its own quadrature of its own steps)."""
    kind, traj = run
    chosen = traj.t * np.array([0.1234, 0.4567, 0.789])
    df = traj.energy_series(chosen)
    assert np.array_equal(df["t"].to_numpy(), chosen)
    E0 = traj.energy_budget().energy_start
    for t_end, (_, row) in zip(chosen, df.iterrows()):
        b = RUNS[kind](t_end).energy_budget()
        assert b.energy_start == E0
        assert abs(row["energy"] - b.energy_end) <= 1e-12 * E0, t_end
        assert np.allclose(row[list(b.laws)].to_numpy(dtype=float), b.dissipated, rtol=0, atol=1e-12 * E0), t_end
        assert abs(row["at_events"] - b.at_events) <= 1e-12 * E0, t_end


@pytest.mark.timeout(300)
def test_the_series_at_the_step_ends_is_the_series_at_those_times(run):
    _, traj = run
    df = traj.energy_series()
    starts = [s.t0 for s in traj.segments[1:]]  # a time at an event is the state before the reset
    picked = df[~np.isin(df["t"], starts) | np.r_[True, df["t"].to_numpy()[1:] != df["t"].to_numpy()[:-1]]]
    picked = picked.reset_index(drop=True)
    again = traj.energy_series(picked["t"].to_numpy())
    assert np.allclose(again.to_numpy(), picked.to_numpy(), rtol=1e-13, atol=1e-14 * df["energy"].iloc[0])


# -- bad times, runs without dense output -------------------------------------------------------


@pytest.mark.parametrize("times", [[-0.5], [1.0, 31.0], [np.nan], [1.0, np.inf], "soon", [[1.0, 2.0]]])
def test_times_outside_the_run_or_not_finite_are_named(times):
    with pytest.raises(pk.ParameterError) as err:
        _stick_slip(30.0).energy_series(times)
    assert err.value.param == "times"


def test_a_run_without_dense_output_has_no_series_as_it_has_no_budget():
    m = pk.Model(PROLATE, pk.Coulomb(0.2).with_dissipation(*_laws(1.0)), "euler")
    r = pk.simulate(m, m.chart.from_paper([0.0, 0.0, 0.5, 0.0, 1.0, 0.0]), 5.0, dense=False)
    with pytest.raises(pk.ParameterError) as budget:
        r.energy_budget()
    for times in (None, [1.0]):
        with pytest.raises(pk.ParameterError) as series:
            r.energy_series(times)
        assert str(series.value) == str(budget.value) and series.value.param == "traj"


def test_a_run_that_ends_at_its_start_lost_nothing_at_its_one_instant():
    """A flat disk spun about the vertical at a tilt lifts off at t = 0 (R < 0 there): no segment;
    one row, the energy of the start, nothing lost; any other time is outside the run."""
    m = pk.Model(pk.Disk(0.0), pk.Coulomb(0.5).with_dissipation(pk.RollingResistance(0.02)))
    with pytest.warns(UserWarning, match="leaves the table"):
        r = pk.simulate(m, m.chart.from_paper(vertical_spin_start(0.5, 4.0)), 40.0)
    assert r.t == r.t0 == 0.0 and not r.segments
    df = r.energy_series()
    assert len(df) == 1 and df["energy"].iloc[0] == r.energy_budget().energy_start
    assert df[["sliding friction", "rolling-resistance", "at_events", "residual"]].to_numpy().tolist() == [[0.0] * 4]
    assert len(r.energy_series([0.0, 0.0])) == 2
    with pytest.raises(pk.ParameterError) as err:
        r.energy_series([1e-3])
    assert err.value.param == "times"
    ax = pk.viz.plot_energy(r)
    assert [line.get_label() for line in ax.get_lines()] == ["energy", "sliding friction", "rolling-resistance"]
    pk.viz.pyplot().close(ax.figure)


def test_an_empty_list_of_times_gives_an_empty_table_with_the_columns():
    df = _stick_slip(5.0).energy_series([])
    assert len(df) == 0 and list(df.columns) == ["t", "energy", *LAW_NAMES, "at_events", "residual"]


# -- drawn ------------------------------------------------------------------------------------


@pytest.mark.timeout(300)
def test_plot_energy_draws_the_energy_and_one_line_per_mechanism(run):
    kind, traj = run
    plt = pk.viz.pyplot()
    ax = pk.viz.plot_energy(traj)
    try:
        lines = {line.get_label(): line for line in ax.get_lines()}
        expected = ["energy", *LAW_NAMES] + (["at events"] if kind == "hopping" else [])
        # stick-slip: the slip starts on the friction cone's edge from zero slip (mode "edge"), with no nudge,
        # so nothing is gained or lost at its events beyond rounding, and no "at events" line is drawn
        if kind == "stick-slip":
            assert any(s.mode.value == "edge" for s in traj.segments)
            assert abs(traj.energy_budget().at_events) < 1e-9
        assert list(lines) == expected
        assert "t" in ax.get_xlabel() and "sqrt(b/g)" in ax.get_xlabel()
        assert "energy" in ax.get_ylabel() and "M g b" in ax.get_ylabel()
        assert [t.get_text() for t in ax.get_legend().get_texts()] == expected
        x, y = lines["energy"].get_data()
        assert x[0] == traj.t0 and x[-1] == traj.t and np.all(np.diff(x) >= 0.0)
        assert y[-1] == pytest.approx(traj.energy_budget().energy_end, rel=1e-14)
        assert lines["spin-friction"].get_ydata()[-1] == pytest.approx(traj.energy_budget().dissipated[2], rel=1e-12)
    finally:
        plt.close(ax.figure)
    fig, mine = plt.subplots()
    try:
        chosen = np.linspace(traj.t0, traj.t, 17)
        assert pk.viz.plot_energy(traj, chosen, ax=mine) is mine
        assert np.array_equal(mine.get_lines()[0].get_xdata(), chosen)
    finally:
        plt.close(fig)


def test_plot_energy_names_a_bad_argument():
    traj = _stick_slip(5.0)
    m = pk.Model(PROLATE, pk.Coulomb(0.2).with_dissipation(*_laws(1.0)), "euler")
    plain = pk.simulate(m, m.chart.from_paper([0.0, 0.0, 0.5, 0.0, 1.0, 0.0]), 5.0, dense=False)
    for call, name in [(lambda: pk.viz.plot_energy(None), "traj"), (lambda: pk.viz.plot_energy(traj, ax="axes"), "ax"),
                       (lambda: pk.viz.plot_energy(traj, [99.0]), "times"), (lambda: pk.viz.plot_energy(plain), "traj")]:
        with pytest.raises(pk.ParameterError) as err:
            call()
        assert err.value.param == name
