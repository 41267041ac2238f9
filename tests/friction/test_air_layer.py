"""Moffatt's air layer (AirLayer): its couple's power is exactly -k psidot^2 / sin(theta), it lies
in the plane of e_Z and the axis, the Euler and vector charts agree on a disk it slows, and the
energy it takes matches an independent quadrature of its power along the run."""

import math

import phasekit as pk
from phasekit.steady.precessions import intermediate_omega, precession_state

import casadi as ca
import numpy as np
import pytest

THIN = pk.Disk(0.0)
K = 1e-3


def start():
    return precession_state(THIN, math.pi / 6, omega0=intermediate_omega(THIN, math.pi / 6))


def test_the_couple_takes_k_psidot_squared_over_sin_and_brakes_the_precession_only():
    """At random states in the Euler chart's variables, with w = Omega e_Z + Lambda e_Y +
    (n - Omega cos) k: Gamma.w = -k Omega^2 / sin(theta) (psidot = Omega), Gamma.k = 0 and
    Gamma.e_Y = 0 (no couple on the spin nor on the rate of theta)."""
    law = pk.friction.AirLayer(K)
    w, k = ca.SX.sym("w", 3), ca.SX.sym("k", 3)
    f, G = law.wrench(w, ca.SX.zeros(3), ca.SX.sym("R"), ca.DM([K]), k)
    fn = ca.Function("g", [w, k], [G, law.power(w, ca.SX.zeros(3), 1.0, ca.DM([K]), k)])
    rng = np.random.default_rng(3)
    for _ in range(20):
        Om, Lam, n = rng.normal(size=3) * 3
        th = rng.uniform(0.01, math.pi - 0.01)
        kv = np.array([math.sin(th), 0.0, math.cos(th)])
        wv = Om * np.array([0, 0, 1.0]) + Lam * np.array([0, 1.0, 0]) + (n - Om * math.cos(th)) * kv
        Gv, P = (np.array(a, dtype=float).ravel() for a in fn(wv, kv))
        assert float(P[0]) == pytest.approx(-K * Om**2 / math.sin(th), rel=1e-12)
        assert abs(Gv @ kv) < 1e-12 * np.linalg.norm(Gv) and abs(Gv[1]) < 1e-12 * np.linalg.norm(Gv)
        assert float(Gv @ wv) == pytest.approx(float(P[0]), rel=1e-12)


@pytest.mark.slow  # the vector chart's integrators with the air layer: ~40 s cold
@pytest.mark.timeout(600)
def test_euler_and_vector_charts_agree_on_a_disk_slowed_by_the_air_layer():
    law = pk.Coulomb(10.0).with_dissipation(pk.friction.AirLayer(K))
    ts = np.linspace(0.0, 8.0, 17)
    ends = {}
    for chart in ("euler", "vector"):
        m = pk.Model(THIN, law, chart)
        r = pk.simulate(m, m.chart.from_paper(start()), 8.0, rtol=1e-13, stop_at="none", dense=True)
        assert r.status is pk.Status.COMPLETED
        s = r.sample(ts)
        ends[chart] = np.column_stack([s[c] for c in ("U", "V", "Omega", "Lambda", "theta", "n")])
    scale = np.max(np.abs(ends["euler"]), axis=0)
    assert np.max(np.abs(ends["euler"] - ends["vector"]) / scale) < 1e-9
    assert ends["euler"][-1, 4] < ends["euler"][0, 4] - 1e-3  # it is falling


def test_the_air_layers_work_is_the_quadrature_of_its_power_and_the_balance_closes():
    m = pk.Model(THIN, pk.Coulomb(10.0).with_dissipation(pk.friction.AirLayer(K)))
    r = pk.simulate(m, start(), 60.0, rtol=1e-12, stop_at="none", dense=True)
    budget = r.energy_budget()
    assert abs(budget.residual) <= 1e-8 * budget.energy_start
    work = dict(zip(budget.laws, budget.dissipated))["air-layer"]
    # independent: 8-point Gauss-Legendre on 3000 panels of k Omega^2 / sin(theta) from the samples
    x, wq = np.polynomial.legendre.leggauss(8)
    edges = np.linspace(0.0, r.t, 3001)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    ts = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    s = r.sample(ts)
    power = K * s["Omega"].to_numpy() ** 2 / np.sin(s["theta"].to_numpy())
    quad = float(np.sum((power.reshape(-1, 8) * wq[None, :]).sum(axis=1) * half))
    assert work == pytest.approx(quad, rel=1e-9)
    assert work > 0.05  # a good part of the start's energy 0.75


def test_spinning_in_place_it_loses_energy_at_k_over_A_sin_squared():
    """On the spin-in-place manifold Omega^2 = 1/(A sin(theta)): the power k Omega^2/sin(theta) is
    k / (A sin^2(theta)), 4 k / sin^2 for the uniform thin disk: the energy falls at that rate at
    the start (where the disk is exactly spinning in place)."""
    m = pk.Model(THIN, pk.Coulomb(10.0).with_dissipation(pk.friction.AirLayer(K)))
    dt = 1e-3
    r = pk.simulate(m, start(), 2 * dt, rtol=1e-14, stop_at="none", dense=True)
    E = r.sample([0.0, dt, 2 * dt])["energy"].to_numpy()
    rate = (-3 * E[0] + 4 * E[1] - E[2]) / (2 * dt)
    assert rate == pytest.approx(-K / (THIN.A * math.sin(math.pi / 6) ** 2), rel=1e-5)


def test_the_law_round_trips_through_a_models_description():
    m = pk.Model(THIN, pk.Coulomb(1.0).with_dissipation(pk.friction.AirLayer(2e-4)))
    again = pk.Model.from_dict(m.to_dict())
    assert again.friction.dissipation == (pk.friction.AirLayer(2e-4),)
    with pytest.raises(pk.ParameterError):
        pk.friction.AirLayer(-1.0)


def test_the_air_layer_on_a_body_that_is_not_a_disk_is_warned_about_once():
    """The law is derived for the film under a disk on its rim: on a disk nothing is said, on a
    spheroid one warning naming the body."""
    import warnings

    law = pk.Coulomb(0.1).with_dissipation(pk.friction.AirLayer(1e-3))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pk.Model(THIN, law)
    with pytest.warns(UserWarning, match="disk on its rim; a Spheroid") as caught:
        pk.Model(pk.Spheroid(0.6), law)
    assert len(caught) == 1
