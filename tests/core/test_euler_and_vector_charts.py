"""The singularity-free vector chart against the Euler chart (2.7): conversions (finite next to
the pole), the same trajectories and jumps, runs through the vertical, and the automatic choice."""

import phasekit as pk
from phasekit.core import charts, choose_chart

import numpy as np
import pytest


def test_conversions_round_trip():
    rng = np.random.default_rng(5)
    for _ in range(20):
        y = np.array([*rng.standard_normal(4), rng.uniform(0.01, np.pi - 0.01), rng.standard_normal()])
        np.testing.assert_allclose(charts.vector_to_euler(charts.euler_to_vector(y)), y, rtol=1e-12, atol=1e-12)


def test_vector_to_euler_is_finite_next_to_the_pole():
    for th in (1e-8, 1e-12):
        y = charts.vector_to_euler(charts.euler_to_vector([0.0, 0.0, 14.0, 0.0, th, 10.0]))
        assert np.all(np.isfinite(y)) and y[2] == pytest.approx(14.0, rel=1e-6)


@pytest.mark.parametrize(
    "a, start",
    # prolate: its vector-chart integrator (~13 s cold), the full run only (so is
    # tests/core/test_jump_time_convergence.py's check of the same jump in both charts)
    [pytest.param(1.5, dict(theta0=np.pi / 2 - 0.01, omega0=10.5), marks=pytest.mark.slow),
     (2 / 3, dict(theta0=0.05, n0=10.5))],
    ids=["prolate", "oblate"],
)
def test_charts_agree_on_trajectory_and_jump(a, start):
    body = pk.Spheroid(a)
    y0 = pk.gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
    y0[3] = 1e-3  # some nutation, so the comparison is not of a quiet state
    runs = {}
    for chart in ("euler", "vector"):
        m = pk.Model(body, pk.Coulomb(0.1), chart)
        runs[chart] = pk.simulate(m, pk.core.to_chart(chart, y0), 300.0, rtol=1e-12, t_eval=[10.0, 20.0])
    e, v = runs["euler"], runs["vector"]
    assert e.status is v.status is pk.Status.JUMPED
    assert abs(e.t_jump - v.t_jump) / e.t_jump < 1e-7
    np.testing.assert_allclose(v.euler_ys, e.euler_ys, rtol=1e-7, atol=1e-7)
    assert e.ts.tolist() == [10.0, 20.0]


@pytest.fixture(scope="module")
def vertical_rise():
    """Oblate a = 0.6 spinning about the vertical, n0 = 12, tilted by 1e-6 (viscous friction:
    under exact Coulomb the near-vertical slip vanishes and the body rolls, see the next test)."""
    body = pk.Spheroid(0.6)
    m = pk.Model(body, pk.Viscous(0.1), "vector")
    d = 1e-6
    z0 = np.array([np.sin(d), 0.0, np.cos(d), 0.0, 0.0, 12.0, 0.0, 0.0])
    rise = pk.Event("theta", np.pi / 2 - 0.05, direction=+1, name="rise-complete")
    r_vert = pk.simulate(m, z0, 3000.0, rtol=1e-9, events=[rise])
    y_away = pk.gyroscopic_start(body, 0.05, n0=12.0)
    r_away = pk.simulate(m, pk.core.to_chart("vector", y_away), 3000.0, rtol=1e-9, events=[rise])
    return r_vert, r_away


def test_vertical_start_runs_through_the_rise(vertical_rise):
    r_vert, r_away = vertical_rise
    # viscous friction: the oscillations of R do not grow enough to lose contact, and the rise
    # from 1e-6 off the vertical completes (theta passes pi/2 - 0.05) within the time allowed
    assert r_vert.status is pk.Status.STOPPED and r_vert.events[-1].name == "rise-complete"
    assert r_vert.x_jump is None and r_vert.R_min > 0
    assert abs(r_vert.euler_end[4] - (np.pi / 2 - 0.05)) < 1e-9
    # steps per unit of simulated time comparable with a start away from the vertical
    rate_vert, rate_away = r_vert.n_steps / r_vert.t, r_away.n_steps / r_away.t
    print(f"vertical start: {r_vert.n_steps} steps over t = {r_vert.t:.1f}; start at 0.05: {r_away.n_steps} over t = {r_away.t:.1f}")
    assert rate_vert < 2 * rate_away


def test_exact_coulomb_near_vertical_sticks():
    m = pk.Model(pk.Spheroid(0.6), pk.Coulomb(0.1), "vector")
    d = 1e-6
    r = pk.simulate(m, [np.sin(d), 0.0, np.cos(d), 0.0, 0.0, 12.0, 0.0, 0.0], 50.0)
    assert r.stuck and r.mode == "rolling" and r.euler_end[4] < 1e-5


def test_vector_chart_starts_exactly_at_the_pole():
    m = pk.Model(pk.Spheroid(0.6), pk.Viscous(0.1), "vector")
    r = pk.simulate(m, [0.0, 0.0, 1.0, 0.0, 0.0, 12.0, 0.0, 0.0], 20.0)
    assert r.status is pk.Status.COMPLETED and np.all(np.isfinite(r.x))
    assert r.euler_end[4] == 0.0  # an exact equilibrium stays put


def test_frictionless_invariants_in_vector_chart_through_the_vertical():
    body = pk.Spheroid(1.5)
    m = pk.Model(body, pk.Coulomb(0.0), "vector")
    # tilted 0.05 and nodding towards the vertical with little precession: theta swings
    # through (near) zero, where the Euler chart is singular
    z0 = charts.euler_to_vector([0.0, 0.0, 0.3, -0.4, 0.05, 6.0])
    te = np.linspace(0.0, 1000.0, 20001)
    r = pk.simulate(m, z0, 1000.0, rtol=1e-13, t_eval=te, stop_at="none")
    assert r.status is pk.Status.COMPLETED
    theta = np.arccos(np.clip(r.ys[:, 2] / np.linalg.norm(r.ys[:, :3], axis=1), -1, 1))
    assert theta.min() < 0.01  # passes near the vertical
    for name in ("energy", "L_Z", "spin"):
        q = m.evaluate(name, r.ys)
        assert np.max(np.abs(q - q[0])) / abs(q[0]) < 1e-9, name
    assert np.max(np.abs(np.linalg.norm(r.ys[:, :3], axis=1) - 1)) < 1e-10  # |k| kept


def test_auto_formulation_choice():
    assert choose_chart(0.5) == "euler"
    assert choose_chart(1e-7) == "vector" and choose_chart(np.pi - 1e-7) == "vector"
    assert choose_chart(0.5, "vector") == "vector"
