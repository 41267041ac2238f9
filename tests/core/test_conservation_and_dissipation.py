"""Conservation and dissipation: mu = 0 conserves energy, spin and L_Z; friction never adds energy."""

import phasekit as pk

import numpy as np
import pytest


@pytest.mark.parametrize("a", [1.5, 0.6])
def test_frictionless_invariants_over_t_1000(a):
    body = pk.Spheroid(a)
    m = pk.Model(body, pk.Coulomb(0.0))
    start = pk.gyroscopic_start(body, 1.0, omega0=4.0) if a > 1 else pk.gyroscopic_start(body, 0.6, n0=8.0)
    x0 = start + np.array([0.1, 0.05, 0.0, 0.05, 0.0, 0.0])
    assert m.normal_reaction(x0) > 0.2  # a state in contact
    te = np.linspace(0.0, 1000.0, 201)
    r = pk.simulate(m, x0, 1000.0, rtol=1e-13, t_eval=te, stop_at="none")
    assert r.status is pk.Status.COMPLETED and r.ts[-1] == 1000.0
    for name in ("energy", "L_Z", "spin"):
        q = m.evaluate(name, r.ys)
        assert np.max(np.abs(q - q[0])) / abs(q[0]) < 1e-9, name
    # the motion is not trivial: theta nutates, and the body stays in contact
    assert np.ptp(r.ys[:, 4]) > 0.005
    assert r.R_min > 0


@pytest.mark.parametrize("law", [pk.Coulomb(0.1), pk.Viscous(0.1)], ids=["coulomb", "viscous"])
def test_energy_non_increasing_with_friction(law, prolate, standard_start):
    m = pk.Model(prolate, law)
    te = np.linspace(0.0, 40.0, 2001)
    r = pk.simulate(m, standard_start, 40.0, rtol=1e-12, t_eval=te)
    E = m.evaluate("energy", r.ys)
    assert np.all(np.diff(E) <= 1e-10)
    assert E[0] - E[-1] > 1e-4  # friction did dissipate
