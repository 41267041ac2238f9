"""Poincare sections (``pk.core.poincare``) against an independent integration, on any observable
and in either direction."""

import phasekit as pk
from phasekit import ParameterError
from phasekit.core import trajectory

import numpy as np
import pytest


@pytest.fixture(scope="module")
def model(prolate):
    return pk.Model(prolate, pk.Coulomb(0.1))


def test_poincare_matches_an_independent_integration_refined_by_brent(prolate, standard_start):
    """Lambda = 0 upward crossings of a long sliding run: phasekit's events (Taylor polynomial
    roots) against scipy's DOP853 on the NumPy transcription, sign changes on a fine t_eval
    grid refined by Brent's method on that integration's dense output."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    model = pk.Model(prolate, pk.Coulomb(0.1))
    df = pk.core.poincare(model, standard_start, 40.0, on="Lambda", value=0.0, direction=+1, rtol=1e-13)
    sol = solve_ivp(pk.baseline.numpy_rhs, (0.0, 40.0), standard_start, method="DOP853", rtol=1e-12, atol=1e-14,
                    args=(1.5, prolate.A, prolate.C, 0.1), dense_output=True)
    grid = np.linspace(0.0, 40.0, 40001)
    L = sol.sol(grid)[3]
    k = np.flatnonzero((L[:-1] < 0) & (L[1:] >= 0))
    t_ref = np.array([brentq(lambda s: sol.sol(s)[3], grid[i], grid[i + 1], xtol=1e-14) for i in k])
    assert df["t"].iloc[0] == 0.0  # the start lies on the section (Lambda = 0, rising)
    crossings = df.iloc[1:]
    assert len(crossings) == len(t_ref) >= 5
    np.testing.assert_allclose(crossings["t"], t_ref, rtol=0, atol=1e-8)
    np.testing.assert_allclose(crossings["theta"], sol.sol(t_ref)[4], atol=1e-8)
    assert np.max(np.abs(df["Lambda"])) < 1e-12
    assert list(df.columns) == ["t", "mode", *trajectory.SAMPLE_COLUMNS]


def test_poincare_on_any_observable_and_direction(model, standard_start):
    up = pk.core.poincare(model, standard_start, 45.0, on="R", value=0.9, direction=-1)
    assert len(up) >= 3 and np.all(np.abs(up["R"] - 0.9) < 1e-10)
    both = pk.core.poincare(model, standard_start, 45.0, on="R", value=0.9, direction=0)
    assert len(both) == 2 * len(up) or len(both) == 2 * len(up) - 1
    with pytest.raises(ParameterError, match="`dense`"):
        pk.core.poincare(model, standard_start, 10.0, dense=False)
