"""The gyroscopic solution and the multiple-scale quantities, against each other and against the
exact dynamics; the theory helpers refuse NaN and never return it."""


import phasekit as pk
from phasekit.theory import (
    amplitude_growth_closed,
    gyroscopic,
    gyroscopic_closed,
    gyroscopic_nutation_frequency,
    jellett_constant,
    mean_over_periods,
    nutation_perturbation,
)
from phasekit.theory.gyroscopic import gyroscopic_numeric, mean_slip, rise_time
from phasekit.theory.multiscale import I1_closed, I2_dominant, I3_closed, growth_integral, nutation_frequency_squared
from phasekit.theory.nutation import nutation_amplitude_phase

import numpy as np
import pytest


@pytest.mark.parametrize("a, theta0, omega0", [(1.5, np.pi / 2 - 0.01, 10.5), (2 / 3, 0.05, 14.0), (3.0, 1.0, 5.0), (0.3, 0.8, 8.0)])
def test_closed_form_3_18_equals_integration_of_3_16(a, theta0, omega0):
    body = pk.Spheroid(a)
    J = jellett_constant(body, theta0, omega0)
    T = np.linspace(0, 0.999 * rise_time(a, J, theta0), 40)
    th_c, om_c = gyroscopic_closed(a, J, theta0, T)
    th_n, om_n = gyroscopic_numeric(body, theta0, omega0, T)
    np.testing.assert_allclose(th_c, th_n, atol=1e-10)
    np.testing.assert_allclose(om_c, om_n, rtol=1e-10)
    # it rises: toward 0 (prolate) or pi/2 (oblate)
    assert (th_c[-1] < 0.05) if a > 1 else (th_c[-1] > np.pi / 2 - 0.05)


def test_mean_slip_is_3_10_for_the_spheroid():
    body = pk.Spheroid(1.5)
    th, om = np.linspace(0.1, 1.4, 9), 7.0
    h = body.h(th)[0]
    np.testing.assert_allclose(mean_slip(body, th, om), (body.A - 1.5**2 * body.C) / (body.C * h) * om * np.sin(th) * np.cos(th), rtol=1e-13)


@pytest.mark.parametrize("a, theta0, omega0, targets", [(1.5, 1.3, 10.2, (1.1, 0.8, 0.4)), (2 / 3, 0.3, 12.0, (0.5, 0.9, 1.2))])
def test_closed_forms_equal_quadrature_away_from_0_and_pi_over_2(a, theta0, omega0, targets):
    body = pk.Spheroid(a)
    J = jellett_constant(body, theta0, omega0)
    th = np.array(targets)
    parts = growth_integral(body, J, theta0, th, parts=True)
    np.testing.assert_allclose(I1_closed(body, J, theta0, th), parts[:, 0], atol=1e-8)  # (3.53)
    np.testing.assert_allclose(I3_closed(theta0, th), parts[:, 2], atol=1e-8)  # (3.52)
    # (3.57) is only the dominant part of I2: away from 0 and pi/2 it is measurably different
    assert np.max(np.abs(I2_dominant(body, theta0, th) - parts[:, 1])) > 1e-2
    # (3.58)-(3.60) are exactly omega^-1/2 exp(I1 + I2_dominant + I3)
    w = gyroscopic_nutation_frequency(body, th, J / (body.A * body.h(th)[0]))
    expect = w**-0.5 * np.exp(I1_closed(body, J, theta0, th) + I2_dominant(body, theta0, th) + I3_closed(theta0, th))
    np.testing.assert_allclose(amplitude_growth_closed(body, J, theta0, th), expect, rtol=1e-10)


def test_3_57_is_the_dominant_part_near_pi_over_2():
    """Near theta-bar = pi/2 the log-singular part carries I2: the relative error of (3.57) falls."""
    body = pk.Spheroid(1.5)
    theta0 = np.pi / 2 - 1e-6
    J = jellett_constant(body, theta0, 10.0)
    rel = []
    for d in (1e-1, 1e-2, 1e-3):
        q = growth_integral(body, J, theta0, [np.pi / 2 - d], parts=True)[0, 1]
        rel.append(abs(I2_dominant(body, theta0, np.pi / 2 - d) - q) / abs(q))
    assert rel[0] > rel[1] > rel[2] and rel[2] < 0.01


def test_omega_3_30_tends_to_3_47():
    body = pk.Spheroid(1.5)
    th = 0.9
    errs = [abs(np.sqrt(nutation_frequency_squared(body, th, om)) / gyroscopic_nutation_frequency(body, th, om) - 1) for om in (5.0, 20.0, 80.0)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-3


def test_c_xi_round_trip():
    body = pk.Spheroid(1.5)
    for c, xi in [(-0.00054, 0.0), (0.001, 1.0), (0.0003, -2.0)]:
        th_p, lam_p, _ = nutation_perturbation(body, 1.2, 9.0, 0.1, c, xi)
        c2, xi2 = nutation_amplitude_phase(body, 1.2, 9.0, 0.1, th_p, lam_p)
        assert c2 * np.cos(xi2) == pytest.approx(c * np.cos(xi), rel=1e-10)
        assert c2 * np.sin(xi2) == pytest.approx(c * np.sin(xi), rel=1e-10, abs=1e-15)


def test_period_means_remove_the_fast_oscillation():
    t = np.linspace(0, 20, 20001)
    w = 2 * np.pi / 0.7
    f = 0.3 * t + 0.05 * np.sin(w * t)
    marks = np.arange(0.35, 20, 0.7)
    tm, fm = mean_over_periods(t, f, marks)
    np.testing.assert_allclose(fm, 0.3 * tm, atol=1e-6)


def gyro_error(omega0):
    """RMS of (period-mean theta - gyroscopic theta-bar) over a prolate rise up to the jump."""
    body = pk.Spheroid(1.5)
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=omega0)
    m = pk.Model(body, pk.Coulomb(0.1))
    r = pk.simulate(m, y0, 300.0, events=[pk.Event("theta", 0.05, direction=-1)])
    ts = np.arange(0, r.t, 0.005)
    tm, thm = mean_over_periods(ts, r.sample(ts)["theta"].to_numpy(), r.minima[:, 0])
    J = jellett_constant(body, y0[4], y0[2])
    th_g, _ = gyroscopic_closed(1.5, J, y0[4], 0.1 * tm)
    return float(np.sqrt(np.mean((thm - th_g) ** 2)))


def test_gyroscopic_mean_error_shrinks_with_omega0():
    errs = [gyro_error(w) for w in (10.5, 20.0, 40.0)]
    print("theta-bar RMS errors for Omega0 = 10.5, 20, 40:", errs)
    assert errs[0] > 3 * errs[1] > 9 * errs[2]
    assert errs[0] < 0.02


@pytest.mark.parametrize("call, name", [
    (lambda b: pk.core.impact(b, [np.sin(1.0), 0, np.cos(1.0)], [0, 0, 1e308], [0, 0, -1e308], e=0.5, mu=0.1), "w"),
    (lambda b: pk.theory.flight_constants(b, [0, 0, 1e200, 0, 1.0, 1.0], 1e200), "euler_state"),
    (lambda b: pk.theory.nutation.nutation_amplitude_phase(b, 1.0, 1e300, 0.1, 0.01, 0.0), "Omega_bar0"),
    (lambda b: pk.theory.multiscale.nutation_frequency_squared(b, 1.0, 1e300), "Omega"),
    (lambda b: pk.theory.multiscale.growth_integral(b, 1e300, 1.0, 0.5), "J"),
    (lambda b: pk.theory.reaction_envelope(b, 1e300, 1.0, 0.5, 0.01), "J"),
    (lambda b: pk.theory.multiscale.nutation_frequency_squared(b, 0.0, 10.0), "theta"),
    (lambda b: pk.theory.multiscale.nutation_frequency_squared(b, float("nan"), 10.0), "theta"),
    (lambda b: pk.theory.multiscale.growth_integral(b, 0.0, 1.0, 0.5), "J"),
    (lambda b: pk.theory.nutation.nutation_amplitude_phase(b, 1.0, 10.0, 0.1, float("nan"), 0.0), "dtheta0"),
    (lambda b: pk.theory.flight_constants(b, [0, 0, 10.0, 0, 1.0, 1.0], float("nan")), "W"),
])
def test_the_theory_helpers_take_no_nan_and_give_none(call, name):
    with pytest.raises(pk.ParameterError) as info:
        call(pk.Spheroid(1.5))
    assert info.value.param == name


def test_gyroscopic_numeric_with_no_times_is_refused_instead_of_hanging():
    with pytest.raises(pk.ParameterError, match="^`T` "):
        gyroscopic.gyroscopic_numeric(pk.Spheroid(1.5), 1.0, 10.0, None)
