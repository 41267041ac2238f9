"""Friction laws: odd in the slip, dissipative, the documented forms, bad laws named; a law a
user writes runs and keeps its name, and the base classes say what a subclass must provide."""


import phasekit as pk
from phasekit.friction import laws as friction

import casadi as ca
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


# -- a law written by a user ---------------------------------------------------------------------


class LoadViscous(pk.friction.FrictionLaw):
    """A user's law, F = -mu R u (viscous, scaled by the load)."""

    name = "load-viscous"

    @staticmethod
    def sliding_force(u, mu, eps):
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0], -mu * u[1], 1)


def test_user_friction_law_runs_and_keeps_its_name(prolate, standard_start):
    law = LoadViscous(0.1)
    assert repr(law) == "LoadViscous(mu=0.1)" and law.describe() == "load-viscous(mu=0.1)"
    model = pk.Model(prolate, law)
    traj = pk.simulate(model, standard_start, 20.0)
    assert traj.status is pk.Status.COMPLETED
    # F = -mu R u: dissipative, and equal to the sampled friction force at a sampled state
    x = traj.states([10.0])[0]
    u = model.evaluate("slip", x)
    np.testing.assert_allclose(model.evaluate("friction", x), -0.1 * model.evaluate("R", x) * u, rtol=1e-12)
    E = traj.sample(np.linspace(0, 20, 500))["energy"].to_numpy()
    assert np.all(np.diff(E) <= 1e-9 * E[0])
    fp = pk.fixed_points(pk.Model(prolate, law), omega0=10.0)
    assert fp[0].kind == "horizontal" and fp[0].residual < 1e-10
    assert pk.Model(prolate, law).to_dict()["law"] == "load-viscous"


def test_base_classes_document_what_a_subclass_must_provide():
    for name in ("shape_params", "height(c, shape)"):
        assert name in pk.bodies.Body.__doc__
    assert "sliding_force(u, mu, eps)" in pk.friction.FrictionLaw.__doc__
    with pytest.raises(NotImplementedError, match="must define `shape_params`"):
        pk.bodies.Body(1.0, 1.0).shape_params
