"""The compiled model: (6.1), R against (2.8) on a computed trajectory, exact Jacobians."""

import phasekit as pk
from phasekit.core.zero_slip import project_no_slip

import numpy as np
import pytest

from ..helpers import central_jacobian


def states(rng, n=5):
    base = np.array([0.05, -0.03, 4.0, 0.3, 1.0, 2.5])
    return [base + rng.standard_normal(6) * np.array([0.05, 0.05, 1.0, 0.2, 0.4, 1.0]) for _ in range(n)]


@pytest.mark.parametrize("a", [1.5, 0.6])
def test_coulomb_R_is_6_1(a):
    body = pk.Spheroid(a)
    mu = 0.3
    m = pk.Model(body, pk.Coulomb(mu))
    A, C = body.A, body.C
    for x in states(np.random.default_rng(0)):
        U, V, Om, Lam, th, n = x
        h, ht, htt = body.h(th)
        uP = m.evaluate("slip", x)
        Uhat = uP[0] / np.linalg.norm(uP)
        R61 = (A + A * htt * Lam**2 + Om * ht * np.sin(th) * (A * Om * np.cos(th) - C * n)) / (A + ht * (ht - mu * h * Uhat))
        assert m.normal_reaction(x) == pytest.approx(R61, rel=1e-13)


def test_viscous_R_matches_notes_formula():
    body = pk.Spheroid(1.5)
    mu = 0.3
    m = pk.Model(body, pk.Viscous(mu))
    A, C = body.A, body.C
    for x in states(np.random.default_rng(1)):
        U, V, Om, Lam, th, n = x
        h, ht, htt = body.h(th)
        FX = -mu * m.evaluate("slip", x)[0]
        R = (A + A * htt * Lam**2 + Om * ht * np.sin(th) * (A * Om * np.cos(th) - C * n) - h * ht * FX) / (A + ht**2)
        assert m.normal_reaction(x) == pytest.approx(R, rel=1e-13)


@pytest.mark.parametrize("law", [pk.Coulomb(0.1), pk.Viscous(0.1)], ids=["coulomb", "viscous"])
def test_R_agrees_with_2_8_on_a_trajectory(law, prolate):
    """R(x(t)) from the model equals 1 + d/dt(Lambda h_theta) differentiated along the solution."""
    m = pk.Model(prolate, law)
    x0 = pk.gyroscopic_start(prolate, 1.2, omega0=6.0) + np.array([0.01, 0.0, 0.0, 0.05, 0.0, 0.0])
    d = 1e-3
    tc = np.linspace(2.0, 8.0, 13)
    te = np.concatenate([tc + k * d for k in (-2, -1, 0, 1, 2)])
    r = pk.simulate(m, x0, 9.0, rtol=1e-13, t_eval=te, stop_at="none")
    assert r.ys is not None

    def W(t):
        idx = np.searchsorted(r.ts, t)
        y = r.ys[idx]
        return y[:, 3] * prolate.h(y[:, 4])[1]

    # fourth-order central difference of W = Lambda h_theta
    Wdot = (8 * (W(tc + d) - W(tc - d)) - (W(tc + 2 * d) - W(tc - 2 * d))) / (12 * d)
    R_model = m.normal_reaction(r.ys[np.searchsorted(r.ts, tc)])
    np.testing.assert_allclose(R_model, 1 + Wdot, atol=1e-6)
    assert np.ptp(R_model) > 1e-3  # the check is not vacuous: R does oscillate


@pytest.mark.parametrize("chart", ["euler", "vector"])
@pytest.mark.parametrize("law", [pk.Coulomb(0.2), pk.Viscous(0.2), pk.RegularisedCoulomb(0.2, 1e-3)], ids=["coulomb", "viscous", "reg"])
def test_casadi_jacobian_matches_central_differences(chart, law):
    m = pk.Model(pk.Spheroid(1.5), law, chart)
    rng = np.random.default_rng(2)
    for x in states(rng, 3):
        z = pk.core.to_chart(chart, x)
        for mode in (md for md in m.modes if md is not pk.core.Mode.FLIGHT):
            zm = project_no_slip(m, z) if mode is pk.core.Mode.ROLLING and law.has_rolling_mode else z
            J = m.jacobian(zm, mode)
            J_fd = central_jacobian(lambda y: m.rhs(y, mode), zm)
            np.testing.assert_allclose(J, J_fd, atol=1e-6 * max(1.0, np.abs(J).max()))
