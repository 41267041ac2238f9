"""Zeros of the steps' polynomials (phasekit/core/engines/roots.py): every zero of a derivative
in each step, in its direction, to rounding, against closed forms and numpy's roots."""

from math import factorial

from phasekit.core.engines.roots import derivative_zeros

import numpy as np
import pytest


def _cosine_steps(omega, phase, h, order_p):
    """Steps of z = -cos(w t + phase) / w^2 (z'' = cos(w t + phase)): each step's Taylor
    coefficients at its start, to order_p, as a Taylor integrator records them."""
    starts = np.concatenate([[0.0], np.cumsum(h)[:-1]])
    j = np.arange(order_p + 1)
    # z^(j)(t) = -w^(j-2) cos(w t + phase + j pi / 2)
    coefs = np.array([-omega ** (j - 2.0) * np.cos(omega * t + phase + j * np.pi / 2) / [float(factorial(i)) for i in j]
                      for t in starts])
    return starts, coefs


@pytest.mark.parametrize("direction", [1, -1, 0])
def test_the_zeros_of_a_cosine_s_steps_are_its_closed_form_zeros(direction):
    """Steps of 0.5 to 3.5 radians of phase (some hold a rising and a falling zero, which the
    Bernstein test halves): every zero of z'' = cos, in its direction, to 1e-12 of the period
    (the truncated z'' is off by 1e-10 at the end of the longest steps: a zero there is located
    on the next step's expansion)."""
    rng = np.random.default_rng(7)
    omega, phase = 3.7, 0.3
    h = rng.uniform(0.5, 3.5, 120) / omega
    starts, coefs = _cosine_steps(omega, phase, h, 24)
    k, tau = derivative_zeros(h, coefs, 2, direction)
    t = starts[k] + tau
    end = starts[-1] + h[-1]
    # cos(w t + phase) = 0 at w t + phase = pi/2 + m pi: falling for even m, rising for odd m
    m = np.arange(0, int((omega * end + phase) / np.pi) + 1)
    exact = (np.pi / 2 + m * np.pi - phase) / omega
    rising = m % 2 == 1
    want = (exact > 0) & (exact <= end) & {1: rising, -1: ~rising, 0: np.ones_like(rising)}[direction]
    assert len(t) == want.sum() > 30
    np.testing.assert_allclose(t, exact[want], rtol=0, atol=1e-12 * 2 * np.pi / omega)
    assert np.all(np.diff(t) > 0)
    assert np.all((tau > 0) & (tau <= h[k]))


def test_the_zeros_of_random_polynomials_are_numpy_s_real_roots():
    """Degree-9 polynomials with 1 to 5 real roots in (0, 1], some 1e-3 apart (two in one halving
    of the step), as one step each: the zeros (order 0) and the zeros of the derivative
    (order 1) are numpy's real roots there, each in its direction."""
    rng = np.random.default_rng(11)
    for trial in range(200):
        roots = np.sort(rng.uniform(0.02, 0.98, rng.integers(1, 6)))
        if trial % 3 == 0:
            roots = np.sort(np.append(roots, roots[0] + 1e-3))
        extra = rng.uniform(1.5, 3.0, 10 - len(roots)) * rng.choice([-1, 1], 10 - len(roots))  # roots off [0, 1]
        c = np.polynomial.polynomial.polyfromroots(np.concatenate([roots, extra]))
        for order in (0, 1):
            poly = np.polynomial.Polynomial(c).deriv(order)
            real = np.sort([r.real for r in poly.roots() if abs(r.imag) < 1e-12 and 0 < r.real <= 1])
            slope = poly.deriv()(real)
            for direction in (1, -1, 0):
                k, tau = derivative_zeros(np.array([1.0]), c[None], order, direction)
                want = real[np.sign(slope) == direction] if direction else real
                assert np.all(k == 0) and len(tau) == len(want), (trial, order, direction)
                # a pair 1e-3 apart is ill-conditioned for both: ours is at least as good a zero
                np.testing.assert_allclose(tau, want, rtol=0, atol=1e-7)
                rounding = 1e-14 * np.abs(poly.coef).sum()
                assert np.all(np.abs(poly(tau)) <= np.maximum(4 * np.abs(poly(want)), rounding)), (trial, order)


def test_a_step_without_a_sign_change_has_no_zero():
    c = np.array([[1.0, 0.0, 0.5, 0.0, 0.1]])  # 1 + t^2/2 + t^4/10 > 0
    k, tau = derivative_zeros(np.array([2.0]), c, 0, 0)
    assert len(k) == len(tau) == 0
