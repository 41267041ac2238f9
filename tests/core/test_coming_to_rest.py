"""Bodies that come to rest: with dissipation laws a run ends with status "rest" at the instant
every motion stops, found to the closed form's precision; the spin about the normal stops first
and is held by spin friction; a tippe top spun at 30 rev/s inverts and then comes to rest.
"""

import phasekit as pk
from phasekit.core import to_chart, vertical_spin_start

import numpy as np
import pytest

BUDGET = dict(max_wall=60.0, max_steps=200_000)
#: relative agreement required of every closed form
CLOSED_FORM_RTOL = 1e-8


def _rolling_spinning_start(model, v0, w0):
    """A unit sphere rolling along e_Y at v0 on its equator and spinning about the vertical at w0."""
    return model.chart.from_paper([0.0, -v0, w0, 0.0, np.pi / 2, v0])


@pytest.mark.timeout(300)
@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])  # vector: ~20 s cold
@pytest.mark.parametrize("delta, c1, k1, s0", [(0.01, 0.02, 0.01, 0.5), (0.02, 0.05, 0.0, 1.0), (0.005, 0.0, 0.03, 0.3)])
def test_rolling_resistance_and_linear_air_drag_stop_a_rolling_sphere_at_the_closed_form_time(chart, delta, c1, k1, s0):
    """A unit sphere (Spheroid(1.0), C = 2/5) rolling straight at s = -V = n: the drag force
    -c1 v on G, the couples -k1 w (w = n k) and -delta R k of rolling resistance (R = 1, k the
    horizontal axis). With the friction force F along e_Y, dV/dt = F - c1 V and
    C dn/dt = F - k1 n - delta; rolling keeps V = -n, so
    (1 + C) ds/dt = -delta - kappa s, kappa = c1 + k1. Hence, with lambda = kappa / (1 + C),
    s(t) = (s0 + delta/kappa) exp(-lambda t) - delta/kappa, zero at
    t* = ln(1 + kappa s0 / delta) / lambda. Spin friction is on too (w_Z = 0: it does nothing)."""
    sphere = pk.Spheroid(1.0)
    law = pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(delta), pk.SpinFriction(0.02),
                                           pk.AirDrag(rotation=k1, translation=c1))
    m = pk.Model(sphere, law, chart)
    r = pk.simulate(m, _rolling_spinning_start(m, s0, 0.0), 1000.0, stop_at="rest", **BUDGET)
    kappa = c1 + k1
    lam = kappa / (1.0 + sphere.C)
    t_rest = np.log1p(kappa * s0 / delta) / lam
    assert r.status is pk.Status.REST, r.reason
    assert abs(r.t - t_rest) / t_rest < CLOSED_FORM_RTOL
    ts = np.linspace(0.0, t_rest, 7)[1:-1]
    s = (s0 + delta / kappa) * np.exp(-lam * ts) - delta / kappa
    assert np.max(np.abs(-r.sample(ts)["V"].to_numpy() / s - 1.0)) < CLOSED_FORM_RTOL
    assert t_rest < 0.9 * s0 / (5.0 / 7.0 * delta)  # the drag shortened the roll (a test that could fail)


@pytest.mark.timeout(300)
@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])  # vector: ~25 s cold
@pytest.mark.parametrize("w0", [1.0, -2.5])
def test_the_spin_stops_first_and_is_held_then_the_rolling_stops(chart, w0):
    """A sphere rolling at v0 = 0.5 and spinning about the vertical at w0: spin friction stops the
    spin at C |w0| / mu_s (20 or 50) and then holds it (the no-pivot mode), rolling resistance
    stops the rolling at v0 / ((5/7) delta) = 70: the run ends there at rest, every velocity zero
    and the energy that of the sphere lying still (h = 1)."""
    sphere = pk.EccentricSphere(0.0)
    mu_s, delta, v0 = 0.02, 0.01, 0.5
    m = pk.Model(sphere, pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(delta), pk.SpinFriction(mu_s)), chart)
    r = pk.simulate(m, _rolling_spinning_start(m, v0, w0), 200.0, stop_at="rest", **BUDGET)
    assert r.status is pk.Status.REST and r.reason.startswith("at rest at t = 70")
    assert [e.name for e in r.events] == ["stick", "pivot stick", "rest"]
    t_spin, t_roll = sphere.C * abs(w0) / mu_s, v0 / (5.0 / 7.0 * delta)
    assert abs(r.events[1].t - t_spin) / t_spin < CLOSED_FORM_RTOL
    assert abs(r.t - t_roll) / t_roll < CLOSED_FORM_RTOL and r.events[2].t == r.t
    assert "no_pivot" in r.segments[-1].mode.value
    assert "rolling resistance" in r.events[2].detail
    velocities = [i for i in range(m.n_states) if i not in m.chart.positions]
    assert np.all(r.x[velocities] == 0.0)
    budget = r.energy_budget()
    assert budget.energy_end == pytest.approx(1.0, abs=1e-15)
    assert budget.lost == pytest.approx((1 + sphere.C) * v0 ** 2 / 2 + sphere.C * w0 ** 2 / 2, rel=1e-12)
    # the spin stays held while the rolling goes on (w_Z = L_Z / C for a sphere)
    earlier, later = (r.sample(np.linspace(a, b, 5))["L_Z"].to_numpy() / sphere.C
                      for a, b in ((0.0, t_spin - 1.0), (t_spin + 1.0, t_roll - 1.0)))
    assert earlier == pytest.approx(w0 - np.sign(w0) * mu_s * np.linspace(0.0, t_spin - 1.0, 5) / sphere.C, rel=1e-8)
    assert np.max(np.abs(later)) < 1e-9 * abs(w0)


@pytest.mark.timeout(300)
def test_stop_at_rest_is_stop_at_none_for_a_dissipative_run():
    m = pk.Model(pk.EccentricSphere(0.0), pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(0.01),
                                                                           pk.SpinFriction(0.02)))
    runs = [pk.simulate(m, _rolling_spinning_start(m, 0.5, 1.0), 200.0, stop_at=s, **BUDGET) for s in ("rest", "none")]
    a, b = runs
    assert a.status is b.status is pk.Status.REST
    assert a.t == b.t and np.array_equal(a.x, b.x) and [e.t for e in a.events] == [e.t for e in b.events]


# -- a tippe top -------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def tippe_top():
    """The tippe top of the guide (offset 0.3, A = 0.38, C = 0.4; exact Coulomb mu = 0.3), of ball
    radius 1.5 cm, spun at 30 rev/s about the vertical from theta0 = 0.1, with spin friction
    mu_s = 0.005 b and rolling resistance delta = 0.002 b (75 and 30 micrometres). (The laws in the
    order of the other tests' models: the same compiled equations.)"""
    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    scale = pk.Scale("1.5 cm")
    law = pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(0.002), pk.SpinFriction(0.005))
    m = pk.Model(top, law, "vector")
    x0 = to_chart("vector", vertical_spin_start(0.1, scale.dimensionless("30 rev/s")))
    return m, scale, pk.simulate(m, x0, 1e5, stop_at="rest", max_wall=120.0, max_steps=2_000_000)


@pytest.mark.timeout(600)
def test_a_tippe_top_inverts_then_comes_to_rest_in_finite_time(tippe_top):
    m, scale, r = tippe_top
    assert r.status is pk.Status.REST, r.reason
    seconds = scale.quantity(r.t, "time").to("s").magnitude
    assert 10.0 < seconds < 120.0  # measured: 38.5 s
    df = r.sample(np.linspace(r.t0, r.t, 4001))
    theta = df["theta"].to_numpy()
    assert theta.max() > 2.5  # it inverted (theta past pi/2, to ~2.8)
    t_inverted = df["t"].to_numpy()[np.argmax(theta > np.pi / 2)]
    assert t_inverted < 0.2 * r.t
    # then the spin died and the top rolled back onto its ball: it rests next to theta = 0 (G
    # lowest), where rolling resistance holds it: the weight's lever arm 0.3 sin(theta) <= delta
    assert theta[-1] < 0.01 and r.x[2] > 0.0 and 0.3 * np.sin(theta[-1]) <= 0.002
    assert np.all(r.x[3:] == 0.0)
    energy = df["energy"].to_numpy()
    assert np.all(np.diff(energy) <= 1e-10 * energy[0])  # monotone
    assert energy[-1] == pytest.approx(1.0 - 0.3 * np.cos(theta[-1]), abs=1e-12)  # at rest: the height of G only
    assert energy[0] > 10.0 * energy[-1]


@pytest.mark.timeout(600)
def test_the_tippe_top_spends_its_energy_on_the_three_laws(tippe_top):
    m, scale, r = tippe_top
    b = r.energy_budget()
    assert b.laws == ("sliding friction", "rolling-resistance", "spin-friction")
    assert abs(b.residual) <= 1e-8 * b.lost
    assert all(w > 0.05 * b.lost for w in b.dissipated)  # each took a part of it
    assert [e.name for e in r.events][-1] == "rest"
