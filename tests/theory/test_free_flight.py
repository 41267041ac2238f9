"""Free flight: the exact solution (4.12), the t^3 gap and its series (4.22)-(4.23), the touchdown
located, and continuity of velocities and accelerations at lift-off."""

import phasekit as pk
from phasekit.core import charts
from phasekit.core.resets import flight_state
from phasekit.theory import flight_constants, gap_exact, gap_max_series, gap_series
from phasekit.theory.flight import cos_theta_exact, flight_invariants

import numpy as np
import pytest


def flight_of(m, r, **kw):
    """The first flight after the jump of ``r``: (summary, trajectory)."""
    f = pk.simulate(m, r.x_jump, r.t_jump + 1.0, t0=r.t_jump, mode="flight", stop_at="touchdown", **kw)
    return f.flights[0], f


@pytest.fixture(scope="module")
def jump11():
    body = pk.Spheroid(1.5)
    m = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0)
    r = pk.simulate(m, y0, 300.0, rtol=1e-12)
    assert r.status is pk.Status.JUMPED
    return body, m, r


def test_numerical_flight_equals_closed_form_4_12(jump11):
    body, m, r = jump11
    fl, traj = flight_of(m, r, rtol=1e-14)
    ts = r.t_jump + np.linspace(0, fl.t_touchdown - r.t_jump, 200)
    xs = traj.segments[0].states(ts)
    k = flight_constants(body, r.x_jump, fl.W_star)
    np.testing.assert_allclose(xs[:, 2] / np.linalg.norm(xs[:, :3], axis=1), cos_theta_exact(k, ts - r.t_jump), atol=1e-10)
    euler = np.array([charts.vector_to_euler(x[:8]) for x in xs[1:]])
    inv = flight_invariants(body, euler)
    assert np.max(np.abs(inv - inv[0]) / np.maximum(np.abs(inv[0]), 1e-300)) < 1e-10  # (4.6)-(4.8)
    E = m.evaluate("energy", xs, pk.core.Mode.FLIGHT)
    assert np.ptp(E) / abs(E[0]) < 1e-12


def test_touchdown_located_to_1e_10(jump11):
    from scipy.optimize import brentq

    body, m, r = jump11
    f, _ = flight_of(m, r, rtol=1e-13)
    k = flight_constants(body, r.x_jump, f.W_star)
    T = f.t_touchdown - r.t_jump
    t_exact = brentq(lambda s: gap_exact(body, k, s), 0.5 * T, 1.5 * T, xtol=1e-15)
    assert abs(T - t_exact) < 1e-10
    assert f.gap_max > 0 and abs(f.gap_max - gap_exact(body, k, f.t_gap_max - r.t_jump)) < 1e-14


def test_gap_grows_like_t_cubed(jump11):
    body, m, r = jump11
    f0, traj = flight_of(m, r, rtol=1e-14)
    W = f0.W_star
    t = np.geomspace(1e-3 * W, 3e-2 * W, 30)
    gaps = traj.segments[0].states(r.t_jump + t)[:, 8]
    slope = np.polyfit(np.log(t), np.log(gaps), 1)[0]
    assert slope == pytest.approx(3.0, abs=0.05)


def test_series_4_22_4_23_converge_in_the_gyroscopic_limit():
    """Lift-off states obeying (4.15)-(4.16), W* ~ Omega*^(-7/4) as the bound of Fig. 5d implies:
    the errors of (4.22) and (4.23) against the exact flight fall as Omega* grows."""
    body = pk.Spheroid(1.5)
    th = 1.0
    ht = body.h(th)[1]
    errs_max, errs_curve = [], []
    for om in (11.0, 20.0, 30.0, 60.0):
        W = 0.3 * om ** -1.75
        # (4.16) printed Psi* = 1/(Omega* h_theta*); from its own middle expression and R = 0
        # (free flight: thetaddot = Omega Psi, and d2h/dt2 = -1) it is -1/(Omega* h_theta*)
        Psi = -1.0 / (om * ht)
        n = (body.A * om * np.cos(th) - body.A * Psi / np.sin(th)) / body.C  # (3.1)
        y = np.array([0.0, 0.0, om, W / ht, th, n])
        k = flight_constants(body, y, W)
        t = np.linspace(0, 4 * W, 400)
        ex = gap_exact(body, k, t)
        gm, tm = gap_max_series(om, W)
        errs_max.append(abs(gm / ex.max() - 1))
        errs_curve.append(np.max(np.abs(gap_series(om, W, t) - ex)) / ex.max())
    # the whole gap curve (4.22): 6.6%, 2.1%, 0.95%, 0.25% for Omega* = 11, 20, 30, 60
    assert all(b < a for a, b in zip(errs_curve, errs_curve[1:])) and errs_curve[-1] < 0.005
    # its maximum (4.23) is already within 1e-3 and keeps below that, ending ~10x smaller
    assert max(errs_max) < 1e-3 and errs_max[-1] < errs_max[0] / 5


def test_velocities_and_accelerations_continuous_through_lift_off(jump11):
    body, m, r = jump11
    mv = pk.Model(body, pk.Coulomb(0.1), "vector")
    z = charts.euler_to_vector(r.x_jump)
    xf = flight_state(m, r.x_jump)
    a_contact = mv.rhs(z)  # (dk, dw, dv_h) in contact at R = 0
    a_flight = m.rhs(xf, pk.core.Mode.FLIGHT)
    np.testing.assert_allclose(a_flight[:8], a_contact, atol=1e-9)
    # vertical: in contact dW/dt = R - 1 = -1 at lift-off, so G's vertical acceleration is that of
    # free fall on both sides; in flight it is the gap's acceleration plus d2h/dt2
    assert abs(m.evaluate("gap_acc", xf, pk.core.Mode.FLIGHT)) < 1e-9
    # the vertical velocity of G carries over: W in contact (2.5) equals gap rate + dh/dt in flight
    assert m.evaluate("W", xf, pk.core.Mode.FLIGHT) == pytest.approx(mv.evaluate("W", z), abs=1e-12)
