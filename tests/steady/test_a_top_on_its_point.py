"""A cone spinning on its tip: the upright spin's stability under friction that holds the point
(exact Coulomb: the rolling linearisation, the classical fast-top condition C^2 n^2 > 4 A' M g l)
and under friction that slides (viscous, regularised Coulomb: unstable at every spin, the
gyroscopic stabilisation of a potential maximum destroyed by dissipation), each checked against
a second formulation: the closed form, the linearisation, a direct simulation."""

import math
import warnings

import phasekit as pk
from phasekit.bodies.cone import Cone
from phasekit.cli.params import run_start

import numpy as np
import pytest

TOP = Cone(1.5, on="tip")


def _classical(body):
    """sqrt(4 A' M g l) / C for a top on a fixed point, A' = A + l^2 about the point, l = 3 h / 4."""
    lever = 0.75 * body.altitude
    return math.sqrt(4.0 * (body.A + lever * lever) * lever) / body.C


def _n_unstable(structure, n, pole="inverted"):
    [state] = [p for p in structure.at(n0=n) if p.kind == ("vertical" if pole == "upright" else "inverted")]
    return state.n_unstable


@pytest.mark.parametrize("height", [0.5, 1.5, 4.0])
def test_the_rolling_criterion_on_a_point_is_the_classical_fast_top_condition(height):
    body = Cone(height, on="tip")
    crit = pk.theory.pole_stability_threshold(body, "inverted")
    assert crit.rho == pytest.approx(0.0, abs=1e-15)
    assert crit.rolling_threshold == pytest.approx(_classical(body), rel=1e-14)
    assert crit.threshold is None  # sliding: no spin holds it up


@pytest.mark.parametrize("body, pole", [(TOP, "inverted"), (pk.Spheroid(1.5), "upright"),
                                        (pk.EccentricSphere(0.3, A=0.38, C=0.4), "inverted")])
def test_the_rolling_linearisation_changes_stability_at_the_closed_form(body, pole):
    s = pk.steady_structure(body, pk.Coulomb(0.5), samples=False)
    n_c = pk.theory.pole_stability_threshold(body, pole).rolling_threshold
    assert _n_unstable(s, n_c * (1 - 1e-6), pole) == 2 and _n_unstable(s, n_c * (1 + 1e-6), pole) == 0


def test_the_structure_states_the_rolling_criterion_under_exact_coulomb_and_the_sliding_one_beside_it():
    [fam] = pk.steady_structure(TOP, pk.Coulomb(0.5), samples=False).families
    assert fam.criticals == (pytest.approx(8.660254037844386, rel=1e-14),) and fam.stable_on == (False, True)
    assert fam.sliding_criticals == () and fam.to_dict()["sliding_criticals"] == []
    [fam] = pk.steady_structure(TOP, pk.Viscous(0.5), samples=False).families
    assert fam.criticals == () and fam.stable_on == (False,) and fam.sliding_criticals is None


def _tilt(friction, mu, start, t_end):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res, _ = run_start(body=TOP, friction=friction, mu=mu, start=start, t_end=t_end, stop_at="none")
    ts = np.linspace(0.0, res.t, 4001)
    return res, ts, np.pi - res.sample(ts)["theta"].to_numpy()


def test_held_by_friction_a_fast_top_nutates_about_upright_and_a_slow_one_falls():
    """Released tilted 0.02 with zero precession (it nutates): above n_c = 8.66 the tilt stays
    bounded, below it the cone comes down on its side."""
    fast, _, tilt = _tilt("coulomb", 0.5, dict(kind="state", state=[0, 0, 0, 0, np.pi - 0.02, 12.0]), 100.0)
    assert fast.status is pk.Status.COMPLETED and tilt.max() < 0.05
    slow, _, tilt = _tilt("coulomb", 0.5, dict(kind="state", state=[0, 0, 0, 0, np.pi - 0.02, 7.0]), 100.0)
    assert slow.status is pk.Status.STOPPED and "side touched" in slow.reason and slow.t < 30.0


@pytest.mark.parametrize("mu, n", [(0.5, 12.0), (0.05, 12.0)])
def test_sliding_friction_tips_it_over_at_the_linearisations_rate(mu, n):
    """Viscous friction: the upright spin is unstable above n_c too; the tilt's envelope grows at
    the real part of the linearisation's unstable pair (within 3%)."""
    [pole] = [p for p in pk.steady_structure(TOP, pk.Viscous(mu), samples=False).at(n0=n) if p.kind == "inverted"]
    rate = float(pole.eigenvalues.real.max())
    assert pole.n_unstable == 2 and rate > 0
    res, ts, tilt = _tilt("viscous", mu, dict(kind="spun-about-axis", theta0=np.pi - 0.02, n0=n), 300.0)
    k = len(ts) // 8
    env = np.array([tilt[i * k:(i + 1) * k].max() for i in range(8)])
    mid = np.array([ts[i * k:(i + 1) * k].mean() for i in range(8)])
    small = env < 0.5  # the linear regime
    assert small.sum() >= 4 and env[-1] > 4 * env[0]
    assert np.polyfit(mid[small], np.log(env[small]), 1)[0] == pytest.approx(rate, rel=0.03)
