"""Starts on an unstable manifold: seeds leave along the unstable eigenvector at its rate, with the
documented signs, for the spheroid's, the tippe top's and the egg's states; the paper's (5.2) is
such a seed."""

import phasekit as pk
from phasekit.bodies import Egg
from phasekit.steady import inverted_state, linearise, unstable_manifold_start, vertical_state
from phasekit.steady.manifolds import unstable_seeds

import numpy as np
import pytest

from ..reference_values import PAPER_START_5_2


def test_seeds_leave_along_the_eigenvector(prolate):
    m, x0, fp = unstable_manifold_start(prolate, pk.Viscous(0.1), state="horizontal", delta=1e-6, omega0=10.0, seed_law="same")
    v = (x0 - fp.x) / np.linalg.norm(x0 - fp.x)
    lam = fp.eigenvalues[0].real
    T = np.log(100.0) / lam
    te = np.linspace(0, T, 30)
    r = pk.simulate(m, x0, T * 1.01, rtol=1e-12, t_eval=te)
    d = r.ys - fp.x
    norms = np.linalg.norm(d, axis=1)
    assert norms[-1] / norms[0] > 90
    cosang = np.abs(d @ v) / norms
    assert np.all(cosang > 0.99)


def test_paper_start_5_2_is_the_viscous_eigenvector(prolate):
    """(5.2) is the horizontal state at Omega0 = 10.5 plus 0.02 x the viscous unstable eigenvector,
    to the one significant figure printed."""
    _, x0, fp = unstable_manifold_start(prolate, pk.Coulomb(0.1), state="horizontal", delta=0.02, omega0=10.5)
    s = PAPER_START_5_2
    printed = np.array([s["U"], s["V"], 10.5, s["Lambda"], s["theta"], s["n"]])
    for i in (0, 1, 3, 5):
        assert x0[i] == pytest.approx(printed[i], rel=0.15)
    assert (np.pi / 2 - x0[4]) == pytest.approx(np.pi / 2 - printed[4], rel=0.2)


def test_seed_signs_and_vertical_seed():
    body = pk.Spheroid(0.6)
    fp = linearise(pk.Model(body, pk.Viscous(0.1), "vector"), vertical_state(12.0), kind="vertical")
    seeds = dict(unstable_seeds(fp, 0.01))
    assert set(seeds) == {"+0", "-0", "+1", "-1"}  # a complex pair spans two real directions
    assert seeds["+0"][0] > 0 and np.linalg.norm(seeds["+0"] - fp.x) == pytest.approx(0.01)
    with pytest.raises(ValueError, match="`n0` gives a vertical state without an unstable direction"):
        unstable_manifold_start(pk.Spheroid(1.5), pk.Viscous(0.1), state="vertical", delta=0.01, n0=10.0)


# -- unstable directions of the new states -----------------------------------------------------------
def test_unstable_manifold_of_the_inverted_tippe_top_and_the_horizontal_like_egg():
    top = pk.EccentricSphere(0.3)  # default moments: inverted state unstable below n_inv = 1.554
    model, x0, fp = unstable_manifold_start(top, pk.Coulomb(0.3), state="inverted", delta=0.01, n0=1.0)
    assert fp.kind == "inverted" and fp.n_unstable == 2 and model.chart.name == "vector"
    assert np.linalg.norm(x0 - inverted_state(1.0)) == pytest.approx(0.01) and x0[0] > 0
    egg = Egg(1.3, 0.05)
    model, x0, fp = unstable_manifold_start(egg, pk.Coulomb(0.1), state="horizontal-like", delta=0.01, omega0=10.0)
    assert fp.kind == "horizontal-like" and fp.n_unstable == 1 and x0[4] < fp.x[4]
    with pytest.raises(ValueError, match="horizontal-like"):
        unstable_manifold_start(pk.Spheroid(1.5), pk.Coulomb(0.1), state="horizontal-like", delta=0.01, omega0=10.0)
