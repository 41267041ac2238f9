"""Friction-law conformance: odd in the slip, dissipative, and the documented forms."""

import phasekit as pk
from phasekit.friction import laws as friction

import numpy as np
import pytest

LAWS = [pk.Coulomb(0.3), pk.RegularisedCoulomb(0.3, 1e-3), pk.Viscous(0.3)]


def check_friction_law(law, rng):
    for _ in range(20):
        u = rng.standard_normal(2) * 10 ** rng.uniform(-2, 1)
        R = rng.uniform(0.1, 2.0)
        F = law.force(u, R)
        np.testing.assert_allclose(law.force(-u, R), -F, rtol=1e-14)  # odd
        assert F @ u <= 0  # dissipative
        assert np.linalg.norm(F) <= max(law.mu * R, law.mu * np.linalg.norm(u)) * (1 + 1e-12)


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.name)
def test_friction_law_conformance(law):
    check_friction_law(law, np.random.default_rng(3))


def test_forms():
    u = np.array([3e-3, -4e-3])
    R = 0.8
    np.testing.assert_allclose(pk.Coulomb(0.2).force(u, R), -0.2 * R * u / 5e-3, rtol=1e-14)
    np.testing.assert_allclose(pk.RegularisedCoulomb(0.2, 1e-3).force(u, R), -0.2 * R * u / np.sqrt(25e-6 + 1e-6), rtol=1e-14)
    np.testing.assert_allclose(pk.Viscous(0.2).force(u, R), -0.2 * u, rtol=1e-14)


@pytest.mark.parametrize("name, mu, eps, what", [("coulomb", -0.1, None, "mu"), ("coulomb", 0.1, 0.0, "eps"), ("wet", 0.1, None, "friction")])
def test_bad_law(name, mu, eps, what):
    with pytest.raises(ValueError, match=f"`{what}`"):
        friction.friction_law(name, mu, eps)
