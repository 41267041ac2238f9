"""The spheroid's support function: (2.10) and its derivatives, its moments, and bad
parameters named."""

import phasekit as pk

import numpy as np
import pytest


@pytest.mark.parametrize("a", [0.2, 2 / 3, 1.0, 1.5, 5.0])
def test_h_matches_2_10_and_finite_differences(a):
    body = pk.Spheroid(a)
    th = np.linspace(0.05, np.pi - 0.05, 41)
    h, h1, h2 = body.h(th)
    # (2.10): h = (a^2 cos^2 + sin^2)^(1/2), h_theta = (1 - a^2) cos sin / h
    np.testing.assert_allclose(h, np.sqrt(a**2 * np.cos(th) ** 2 + np.sin(th) ** 2), rtol=1e-14)
    np.testing.assert_allclose(h1, (1 - a**2) * np.cos(th) * np.sin(th) / h, rtol=1e-12, atol=1e-14)
    d = 1e-5
    hp, h1p, _ = body.h(th + d)
    hm, h1m, _ = body.h(th - d)
    np.testing.assert_allclose(h1, (hp - hm) / (2 * d), atol=1e-9)
    np.testing.assert_allclose(h2, (h1p - h1m) / (2 * d), atol=1e-8)


def test_uniform_moments_and_override():
    b = pk.Spheroid(1.5)
    assert b.A == pytest.approx((1 + 1.5**2) / 5) and b.C == pytest.approx(0.4)
    c = pk.Spheroid(1.5, A=0.5, C=0.3)
    assert (c.A, c.C) == (0.5, 0.3)
    assert not c.uniform and b.uniform


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(a=0.0), "a"),
        (dict(a=-2.0), "a"),
        (dict(a=float("nan")), "a"),
        (dict(a=float("inf")), "a"),
        (dict(a=1.5, A=-1.0), "A"),
        (dict(a=1.5, C=0.0), "C"),
        (dict(a=1.5, A=0.1, C=0.5), "C"),  # violates C <= 2A
    ],
)
def test_bad_body_names_parameter(kwargs, name):
    with pytest.raises(ValueError, match=f"`{name}`"):
        pk.Spheroid(**kwargs)
