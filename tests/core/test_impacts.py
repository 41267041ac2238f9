"""Impacts: the impulse never adds energy and obeys Newton's restitution law; bad input is refused
naming the argument, and the upright drop gives its closed form."""

import phasekit as pk
from phasekit.core import impact
from phasekit.core.impact import collision_matrix, contact_point

import numpy as np
import pytest

from ..helpers import raises_param

NAN, INF = float("nan"), float("inf")
B = pk.Spheroid(1.5)
A_UNIFORM = (1 + 1.5**2) / 5  # the uniform spheroid's A (C = 2/5)


@pytest.mark.parametrize("e, mu", [(0.0, 0.1), (0.5, 0.1), (0.9, 0.3), (1.0, 0.0)])
def test_impacts_never_gain_energy(e, mu):
    body = pk.Spheroid(1.5)
    rng = np.random.default_rng(7)
    for _ in range(200):
        k = rng.standard_normal(3)
        k /= np.linalg.norm(k)
        w = rng.standard_normal(3) * 10
        v = rng.standard_normal(3)
        res = impact(body, k, w, v, e=e, mu=mu)
        assert res.energy_after <= res.energy_before * (1 + 1e-12)
        if res.v_normal_before < 0:
            assert res.v_normal_after == pytest.approx(-e * res.v_normal_before, abs=1e-10)
            if e < 1:
                assert res.energy_after < res.energy_before
            if e == 1.0 and mu == 0.0:
                assert res.energy_after == pytest.approx(res.energy_before, rel=1e-12)


GOOD_IMPACT = dict(k=[0.0, 0.0, 1.0], w=[0.0, 0.0, 0.0], v=[0.0, 0.0, -1.0], e=0.5, mu=0.1)


@pytest.mark.parametrize("name, bad", [
    ("k", [0.0, 0.0, NAN]),
    ("k", [0.0, 0.0, 2.0]),  # not a unit vector
    ("k", [1.0, 1.0, 1.0]),
    ("k", [0.0, 1.0]),
    ("k", "up"),
    ("w", [0.0, INF, 0.0]),
    ("w", [1.0, 2.0]),
    ("v", [0.0, 0.0, NAN]),
    ("v", None),
    ("e", 1.5),
    ("e", NAN),
    ("e", -0.1),
    ("mu", NAN),
    ("mu", -1.0),
    ("body", "spheroid"),
])
def test_impact_rejects(name, bad):
    args = dict(GOOD_IMPACT, body=B) | {name: bad}
    raises_param(name, lambda: pk.core.impact(args["body"], args["k"], args["w"], args["v"], e=args["e"], mu=args["mu"]))


@pytest.mark.parametrize("fn", [contact_point, collision_matrix])
def test_impact_geometry_rejects(fn):
    raises_param("k", lambda: fn(B, [0.0, 0.0, 3.0]))
    raises_param("k", lambda: fn(B, [NAN, 0.0, 1.0]))
    raises_param("body", lambda: fn(None, [0.0, 0.0, 1.0]))


def test_impact_valid_upright_drop():
    """Upright (k = e_Z) and falling straight: the impulse passes through G, so it only reverses
    the fall by Newton's law and spins nothing: v = (0, 0, e), w = 0, P = (0, 0, 1 + e)."""
    r = pk.core.impact(B, **GOOD_IMPACT)
    np.testing.assert_allclose(r.v, [0.0, 0.0, 0.5], atol=1e-15)
    np.testing.assert_allclose(r.w, [0.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(r.impulse, [0.0, 0.0, 1.5], atol=1e-15)
    assert r.energy_after == pytest.approx(0.5 * 0.25, rel=1e-15)
    # the contact point is the end of the axis (h(0) = a), K = diag(1 + a^2/A, 1 + a^2/A, 1)
    np.testing.assert_allclose(contact_point(B, [0, 0, 1]), [0.0, 0.0, -1.5], atol=1e-15)
    k11 = 1 + 1.5**2 / A_UNIFORM
    np.testing.assert_allclose(collision_matrix(B, [0, 0, 1]), np.diag([k11, k11, 1.0]), rtol=1e-14, atol=1e-15)
