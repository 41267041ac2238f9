"""The closed-form stability criteria of the vertical spin and the horizontal precession (uniform and
non-uniform spheroids) are where the exact linearisation changes sign."""

import phasekit as pk
from phasekit.steady import horizontal_state, linearise, vertical_state
from phasekit.studies.linear_stability import vertical_is_stable
from phasekit.theory import horizontal_stability_threshold, vertical_stability_threshold

import numpy as np
import pytest


@pytest.mark.parametrize("a", [1.2, 1.5, 2.0, 3.0, 0.6, 0.9])
@pytest.mark.parametrize("mu", [0.01, 0.3])
def test_vertical_stability_criterion(a, mu):
    """Stability changes at (a^2 C - A) n0^2 = a^3 (a^2 - 1): n0 = sqrt(5 a^3) for the uniform
    spheroid, whatever mu: prolate stable above it, oblate unstable above it."""
    body = pk.Spheroid(a)
    nc = vertical_stability_threshold(body.A, body.C, a)
    assert nc == pytest.approx(np.sqrt(5 * a**3), rel=1e-12)
    m = pk.Model(body, pk.Viscous(mu), "vector")
    below = linearise(m, vertical_state(0.97 * nc))
    above = linearise(m, vertical_state(1.03 * nc))
    if a > 1:
        assert not below.stable and above.stable
    else:
        assert below.stable and not above.stable
    assert vertical_is_stable(body.A, body.C, a, 1.03 * nc) == above.stable


@pytest.mark.parametrize("a, A, C", [(2.0, 0.8, 0.5), (1.5, 0.5, 0.7), (1.1, 0.5, 0.45)])
def test_vertical_criterion_nonuniform(a, A, C):
    body = pk.Spheroid(a, A=A, C=C)
    nc = vertical_stability_threshold(A, C, a)
    m = pk.Model(body, pk.Viscous(0.05), "vector")
    assert not linearise(m, vertical_state(0.99 * nc)).stable
    assert linearise(m, vertical_state(1.01 * nc)).stable
    # the frictionless (sleeping-top) threshold C^2 n^2 = 4 A (a - 1/a) lies below it
    m0 = pk.Model(body, pk.Viscous(0.0), "vector")
    n_top = np.sqrt(4 * A * (a - 1 / a)) / C
    assert n_top <= nc and linearise(m0, vertical_state(1.01 * n_top)).n_unstable == 0


@pytest.mark.parametrize("a, A, C", [(1.5, None, None), (0.5, None, None), (2.0, 0.8, 0.5), (0.6, 0.3, 0.5)])
def test_horizontal_criterion(a, A, C):
    """The horizontal precession changes stability at (a^2 C - A) Omega0^2 = a^2 - 1 (sqrt 5 if uniform)."""
    body = pk.Spheroid(a, A=A, C=C)
    oc = horizontal_stability_threshold(body.A, body.C, a)
    if A is None:
        assert oc == pytest.approx(np.sqrt(5.0), rel=1e-12)
    m = pk.Model(body, pk.Viscous(0.1))
    lo, hi = linearise(m, horizontal_state(0.98 * oc)), linearise(m, horizontal_state(1.02 * oc))
    if a > 1:
        assert lo.stable and hi.n_unstable == 1
    else:
        assert lo.n_unstable == 1 and hi.stable
