"""Exact Coulomb stick-slip: the sphere's analytic rolling onset, and the paper's start (5.2) sticking."""

import phasekit as pk

import numpy as np
import pytest

from ..reference_values import PAPER_START_5_2, PITFALL_5_2_JUMP_T


@pytest.mark.parametrize("mu", [0.1, 0.5])
@pytest.mark.parametrize(
    "x0",
    [[1.0, 0.0, 0.0, 0.0, np.pi / 2, 0.0], [0.7, -0.4, 2.0, 0.3, 1.0, 3.0]],
    ids=["translating", "spinning"],
)
def test_sphere_slip_to_roll_time_matches_analytic(mu, x0):
    """A sliding sphere's slip |u| falls at the constant rate (7/2) mu g: onset 2 |u0| / (7 mu)."""
    m = pk.Model(pk.Spheroid(1.0), pk.Coulomb(mu))
    u0 = np.linalg.norm(m.evaluate("slip", np.array(x0)))
    r = pk.simulate(m, x0, 10.0, rtol=1e-12)
    [onset] = r.events_named("stick")
    assert onset.mode_after == "rolling"
    assert onset.t == pytest.approx(2 * u0 / (7 * mu), abs=1e-9)
    # it then rolls: slip stays zero and the guard was ~0 at the event
    assert np.linalg.norm(m.evaluate("slip", r.x)) < 1e-9
    assert r.mode == "rolling"


def paper_start(omega0=10.5):
    s = PAPER_START_5_2
    return [s["U"], s["V"], omega0, s["Lambda"], s["theta"], s["n"]]


def test_paper_start_5_2_sticks_under_exact_coulomb(prolate):
    r = pk.simulate(pk.Model(prolate, pk.Coulomb(0.1)), paper_start(), 200.0)
    assert r.stuck and r.events[0].kind == "stick" and r.events[0].t < 0.1
    assert r.status is pk.Status.COMPLETED and r.mode == "rolling"
    assert abs(r.x[4] - np.pi / 2) < 2e-3  # never rises


def test_paper_start_5_2_depends_on_regularisation(prolate):
    """docs/physics.md, pitfall 1, reproduced: the answer from (5.2) moves with eps, i.e. with numerics."""
    results = {eps: pk.simulate(pk.Model(prolate, pk.RegularisedCoulomb(0.1, eps)), paper_start(), 300.0) for eps in (1e-3, 1e-4, 1e-6)}
    for eps, t_expected in PITFALL_5_2_JUMP_T.items():
        assert results[eps].status is pk.Status.JUMPED
        assert results[eps].t_jump == pytest.approx(t_expected, abs=1.0)
    assert results[1e-6].status is pk.Status.COMPLETED and results[1e-6].stuck
