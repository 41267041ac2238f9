"""Each dissipation law against its closed form (a uniform sphere, both charts), and the sliding
laws unchanged when no dissipation law is carried.

The sphere is ``EccentricSphere(0.0)``: radius 1, G at the centre, A = C = 2/5 (units M, b, g;
g = b = 1). Every closed form below is derived in its test's docstring from the Newton-Euler
equations of the sphere and the law's wrench (phasekit.friction.dissipation).
"""

import json

import phasekit as pk

import numpy as np
import pytest
from scipy.optimize import brentq

SPHERE = pk.EccentricSphere(0.0)
C = SPHERE.C
CHARTS = ("euler", "vector")
#: relative agreement required of every closed form
CLOSED_FORM_RTOL = 1e-8
#: budgets of every run: a hang guard, reported by the run's own status
BUDGET = dict(max_wall=60.0, max_steps=200_000)


def _model(law, chart):
    return pk.Model(SPHERE, law, chart)


def _rel(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b)) / np.maximum(np.abs(np.asarray(b)), 1e-300))


def _rolling_start(model, v0):
    """Rolling straight along e_Y on the equator (theta = pi/2): V = -n (zero slip, x_P = 1)."""
    return model.chart.from_paper([0.0, -v0, 0.0, 0.0, np.pi / 2, v0])


def _spinning_start(model, n0):
    """Spinning in place about the vertical: Omega = n0, no spin about the (horizontal) axis."""
    return model.chart.from_paper([0.0, 0.0, n0, 0.0, np.pi / 2, 0.0])


@pytest.mark.timeout(300)
@pytest.mark.parametrize("chart", CHARTS)
@pytest.mark.parametrize("delta, v0", [(0.01, 0.5), (0.004, 0.3), (0.03, 0.2)])
def test_rolling_resistance_decelerates_a_rolling_sphere_at_five_sevenths_delta(chart, delta, v0):
    """Rolling straight at speed s = -V = n (e_Y, axis horizontal): the couple of rolling
    resistance is -delta R along the axis, R = 1. With the friction force F along e_Y,
    dV/dt = F and C dn/dt = F x_P - delta = F - delta (x_P = r = 1); rolling keeps V = -n, so
    F = delta / (1 + C) and ds/dt = -delta / (1 + C) = -(5/7) delta (C = 2/5). The speed falls
    linearly, s(t) = v0 - (5/7) delta t, and the sphere rests at t* = v0 / ((5/7) delta).
    Spin friction is carried too (mu_s = 0.02): w_Z = 0 in this motion, so it does nothing."""
    law = pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(delta), pk.SpinFriction(0.02))
    m = _model(law, chart)
    r = pk.simulate(m, _rolling_start(m, v0), 2.0 * v0 / delta, stop_at="rest", **BUDGET)
    t_rest = v0 / (5.0 / 7.0 * delta)
    assert r.status is pk.Status.REST, r.reason
    assert abs(r.t - t_rest) / t_rest < CLOSED_FORM_RTOL
    ts = np.linspace(0.0, t_rest, 9)[1:-1]
    df = r.sample(ts)
    s = v0 - 5.0 / 7.0 * delta * ts
    assert _rel(-df["V"].to_numpy(), s) < CLOSED_FORM_RTOL
    assert _rel(df["n"].to_numpy(), s) < CLOSED_FORM_RTOL
    assert np.max(np.abs(df["R"].to_numpy() - 1.0)) < 1e-12


@pytest.mark.timeout(300)
# vector: its own integrators (~15 s cold), the full run only (spin friction in the vector chart stays in the
# default run with tests/core/test_coming_to_rest.py's tippe top and tests/core/test_energy_budget.py)
@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])
@pytest.mark.parametrize("mu_s, n0", [(0.02, 3.0), (0.05, -1.0), (0.005, 0.4)])
def test_spin_friction_stops_a_sphere_spinning_in_place_linearly(chart, mu_s, n0):
    """Spinning in place about the vertical at rate w_Z = n0 (v = 0, R = 1): the only couple is
    spin friction's -mu_s R sign(w_Z) e_Z, so C dw_Z/dt = -mu_s sign(w_Z) (R = 1 = r):
    w_Z(t) = n0 - sign(n0) mu_s t / C, zero at t* = C |n0| / (mu_s R). Air drag on translation
    is carried too (c1 = 0.1): G does not move here, so it does nothing."""
    law = pk.Coulomb(0.3).with_dissipation(pk.SpinFriction(mu_s), pk.AirDrag(translation=0.1))
    m = _model(law, chart)
    t_rest = C * abs(n0) / mu_s
    r = pk.simulate(m, _spinning_start(m, n0), 2.0 * t_rest, stop_at="rest", **BUDGET)
    assert r.status is pk.Status.REST, r.reason
    assert abs(r.t - t_rest) / t_rest < CLOSED_FORM_RTOL
    ts = np.linspace(0.0, t_rest, 9)[1:-1]
    w_z = r.sample(ts)["Omega"].to_numpy()
    assert _rel(w_z, n0 - np.sign(n0) * mu_s * ts / C) < CLOSED_FORM_RTOL
    assert np.max(np.abs(r.sample(ts)[["U", "V", "n"]].to_numpy())) < 1e-9 * abs(n0)  # it stays in place


@pytest.mark.timeout(300)
@pytest.mark.parametrize("chart", CHARTS)
@pytest.mark.parametrize("k1, k2, n0, t_end", [(0.1, 0.0, 3.0, 20.0), (0.03, 0.0, -2.0, 40.0),
                                               (0.0, 0.05, 3.0, 20.0), (0.0, 0.2, -1.5, 10.0)])
def test_air_drag_spin_down_of_a_sphere_spinning_in_place(chart, k1, k2, n0, t_end):
    """Spinning in place about the vertical (v = 0, so the drag force vanishes): the air's couple
    is -(k1 + k2 |w|) w with w = w_Z e_Z, so C dw_Z/dt = -k1 w_Z - k2 w_Z |w_Z|. Linear law
    (k2 = 0): w_Z = n0 exp(-k1 t / C). Quadratic law (k1 = 0): d(1/w_Z)/dt = k2 sign(w_Z) / C,
    so w_Z = n0 / (1 + k2 |n0| t / C). Neither reaches rest in finite time: the run completes.
    (Spin friction is carried with mu_s = 0: the same compiled model as the test above.)"""
    law = pk.Coulomb(0.3).with_dissipation(pk.SpinFriction(0.0), pk.AirDrag(rotation=k1, rotation_quadratic=k2))
    m = _model(law, chart)
    r = pk.simulate(m, _spinning_start(m, n0), t_end, stop_at="rest", **BUDGET)
    assert r.status is pk.Status.COMPLETED and r.t == t_end
    ts = np.linspace(0.0, t_end, 11)
    w_z = r.sample(ts)["Omega"].to_numpy()
    exact = n0 * np.exp(-k1 * ts / C) if k2 == 0.0 else n0 / (1.0 + k2 * abs(n0) * ts / C)
    assert _rel(w_z, exact) < CLOSED_FORM_RTOL
    assert abs(w_z[-1]) < 0.5 * abs(n0)  # the test is not of a motion that barely decays


@pytest.mark.timeout(300)
@pytest.mark.parametrize("chart", CHARTS)
@pytest.mark.parametrize("c, k, vz0", [(0.2, 0.1, 2.0), (0.05, 0.02, 0.7), (1.0, 0.0, 3.0)])
def test_air_drag_on_a_sphere_in_flight(chart, c, k, vz0):
    """A sphere thrown off the table (gap 0, rising at vz0) with linear drag: m dv/dt = -c v - m e_Z
    and I dw/dt = -k w (I = A = C, isotropic). So the horizontal velocity is v_h0 exp(-c t),
    w = w0 exp(-k t / C), and the vertical velocity vz = (vz0 + 1/c) exp(-c t) - 1/c; G's
    height above its resting height (the gap, h = 1) is
    gap(t) = (vz0 + 1/c)(1 - exp(-c t))/c - t/c, and the run stops at its root t_td > 0.
    Spin friction (a contact law) is carried too: in flight R = 0 and it does nothing."""
    law = pk.Coulomb(0.3).with_dissipation(pk.SpinFriction(0.05), pk.AirDrag(rotation=k, translation=c))
    m = _model(law, chart)
    k_axis = np.array([np.sin(1.0), 0.0, np.cos(1.0)])
    w0, vh0 = np.array([0.3, -0.5, 2.0]), np.array([0.7, 0.4])
    x0 = np.concatenate([k_axis, w0, vh0, [0.0, vz0]])
    r = pk.simulate(m, x0, 50.0, mode="flight", stop_at="touchdown", **BUDGET)
    assert r.status is pk.Status.TOUCHDOWN and len(r.segments) == 1

    def gap(t):
        return (vz0 + 1.0 / c) * (1.0 - np.exp(-c * t)) / c - t / c

    t_td = brentq(gap, 1e-6, 50.0, xtol=1e-15, rtol=1e-15)
    assert abs(r.t - t_td) / t_td < CLOSED_FORM_RTOL
    ts = np.linspace(0.0, r.t, 9)
    X = r.segments[0].states(ts)
    assert _rel(X[:, 6:8], vh0 * np.exp(-c * ts)[:, None]) < CLOSED_FORM_RTOL
    assert _rel(X[:, 3:6], w0 * np.exp(-k * ts / C)[:, None]) < CLOSED_FORM_RTOL
    gap_max = gap(np.log(1.0 + c * vz0) / c)  # where vz = 0
    assert np.max(np.abs(X[:, 8] - gap(ts))) < CLOSED_FORM_RTOL * gap_max
    assert np.allclose(r.sample(ts)["gap"].to_numpy(), X[:, 8], rtol=0, atol=1e-14)


# -- without the laws: nothing changes -------------------------------------------------------------


def _keys(obj):
    """Every key of a nested JSON document."""
    if isinstance(obj, dict):
        return set(obj) | set().union(*(_keys(v) for v in obj.values()))
    if isinstance(obj, list):
        return set().union(*(_keys(v) for v in obj)) if obj else set()
    return set()


def test_a_law_without_dissipation_is_the_law_itself():
    law = pk.Coulomb(0.1)
    bare = law.with_dissipation()
    assert bare == law and bare.dissipation == () and np.array_equal(bare.params, law.params)
    assert bare.to_dict() == law.to_dict() and "dissipation" not in law.to_dict()
    assert bare.describe() == law.describe() == "coulomb(mu=0.1)" and repr(bare) == repr(law)
    body = pk.Spheroid(1.5)
    for chart in CHARTS:
        a, b = pk.Model(body, law, chart), pk.Model(body, bare, chart)
        assert a.compiled is b.compiled  # one cache entry: the same compiled equations
        assert a.compiled.signature == b.compiled.signature and np.array_equal(a.p, b.p)
    spun = law.with_dissipation(pk.SpinFriction(0.02))
    assert pk.Model(body, spun).compiled.signature != pk.Model(body, law).compiled.signature


@pytest.mark.timeout(300)
def test_a_run_without_dissipation_is_bitwise_the_same_and_its_json_has_no_dissipation(prolate, standard_start):
    law = pk.Coulomb(0.1)
    runs = [pk.simulate(pk.Model(prolate, f), standard_start, 60.0, t_eval=np.linspace(0.0, 40.0, 81), **BUDGET)
            for f in (law, law.with_dissipation())]
    a, b = runs
    assert a.status is b.status is pk.Status.JUMPED
    assert np.array_equal(a.ys, b.ys) and np.array_equal(a.x, b.x) and a.t == b.t
    assert [(e.name, e.t) for e in a.events] == [(e.name, e.t) for e in b.events]
    assert all(np.array_equal(s.x1, z.x1) and s.n_steps == z.n_steps for s, z in zip(a.segments, b.segments))
    da, db = (json.loads(json.dumps(r.to_dict())) for r in runs)
    da.pop("wall_s", None), db.pop("wall_s", None)
    assert "dissipation" not in _keys(da) and da["model"] == db["model"]
    # with a law, the model's description says so, and rebuilds it
    m = pk.Model(prolate, law.with_dissipation(pk.RollingResistance(0.01), pk.AirDrag(translation=0.1)))
    d = m.to_dict()
    assert [x["law"] for x in d["dissipation"]] == ["rolling-resistance", "air-drag"]
    rebuilt = [pk.friction.dissipation.dissipation_from_dict(x) for x in d["dissipation"]]
    assert tuple(rebuilt) == m.friction.dissipation


def test_a_model_with_dissipation_is_rebuilt_from_its_description(prolate):
    m = pk.Model(prolate, pk.Coulomb(0.1).with_dissipation(pk.RollingResistance(0.01), pk.AirDrag(translation=0.1)))
    assert pk.Model.from_dict(json.loads(json.dumps(m.to_dict()))) == m
