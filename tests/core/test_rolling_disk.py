"""A disk on its rim: without friction it keeps its energy and the two invariants of axisymmetric
motion (L_Z and the spin n); rolling upright it keeps its speed and goes straight; rolling in a
steady circle (closed form) it stays on it; spinning in place it is the steady precession of
phasekit.steady; with a dissipation law it falls to its face in finite time, and a cylinder tipped
past its balance falls onto its side: both end with the named event."""

import math

import phasekit as pk
from phasekit.steady.precessions import intermediate_omega, precession_state

import numpy as np
import pytest

THIN, COIN = pk.Disk(0.0), pk.Disk(0.1)


def limit_events(body):
    """The body's ends as the user's events (the same names and angles as the built-in ones)."""
    return [pk.Event("theta", lim.theta, direction=lim.direction, name=lim.name) for lim in body.limits]


def spinning_in_place(body, theta):
    """The steady precession with G at rest: Omega^2 = h_t / (sin [(A - C) cos + C h_t / x_P])."""
    return precession_state(body, theta, omega0=intermediate_omega(body, theta))


def steady_circle(body, theta, omega):
    """Rolling in a steady circle at (theta, Omega): Lambda = U = 0, V from zero slip, n from (2.7d)
    with R = 1 and the centripetal friction F_X = -Omega V; for the disk x_P = 1."""
    s, c, half = math.sin(theta), math.cos(theta), 0.5 * body.thickness
    h, ht = s + half * c, c - half * s
    n = (body.A * omega**2 * s * c - ht * (1 + h * omega**2) + h * omega**2 * c) / (omega * (body.C * s + h))
    return np.array([0.0, -omega * ht - (n - omega * c), omega, 0.0, theta, n])


@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])  # vector: ~15 s cold
@pytest.mark.parametrize("disk", [THIN, COIN], ids=["thin", "coin"])
def test_frictionless_disk_keeps_energy_L_Z_and_spin(disk, chart):
    """Viscous(0): no horizontal force; the vertical reaction at the rim has no couple about the
    vertical nor about k, so L_Z and n are invariants (Coulomb(0) would stick where the slip vanishes)."""
    m = pk.Model(disk, pk.Viscous(0.0), chart)
    y0 = spinning_in_place(disk, 0.7) + np.array([0.05, -0.03, 0.1, 0.1, 0.0, 0.5])
    te = np.linspace(0.0, 400.0, 801)
    r = pk.simulate(m, m.chart.from_paper(y0), 400.0, rtol=1e-13, t_eval=te, stop_at="none")
    assert r.status is pk.Status.COMPLETED and len(r.events) == 0 and r.R_min > 0.5  # on its rim all along
    for name in ("energy", "L_Z", "spin"):
        q = m.evaluate(name, r.ys)
        assert np.max(np.abs(q - q[0])) < 1e-10 * abs(q[0]), name
    theta = m.evaluate("theta", r.ys)
    assert np.ptp(theta) > 0.2 and theta.min() > 0.4  # it nutates, well inside its range


@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])  # vector: ~50 s cold
def test_thin_disk_rolling_upright_keeps_its_speed_and_goes_straight(chart):
    n0 = 2.0  # above sqrt(1/3): upright rolling is stable
    m = pk.Model(THIN, pk.Coulomb(0.5), chart)
    r = pk.simulate(m, m.chart.from_paper([0.0, -n0, 0.0, 0.0, math.pi / 2, n0]), 200.0, rtol=1e-13, dense=True,
                    stop_at="none")
    assert r.status is pk.Status.COMPLETED and [e.name for e in r.events] == ["stick"] and r.mode == "rolling"
    ts = np.linspace(0.0, 200.0, 41)
    s = r.sample(ts)
    assert np.max(np.abs(np.hypot(s["U"], s["V"]) - n0)) < 1e-10 and np.max(np.abs(s["theta"] - math.pi / 2)) < 1e-10
    pose = r.pose(ts)  # the axis along X: G runs along -Y at speed n0
    assert np.max(np.abs(pose["X"])) < 1e-10 and np.max(np.abs(pose["Y"] + n0 * ts)) < 1e-9


@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])  # vector: ~30 s cold
@pytest.mark.parametrize("disk", [THIN, COIN], ids=["thin", "coin"])
def test_disk_rolling_in_a_steady_circle_stays_on_it(disk, chart):
    y0 = steady_circle(disk, 1.2, 1.5)
    m = pk.Model(disk, pk.Coulomb(2.0), chart)
    x0 = m.chart.from_paper(y0)
    assert m.evaluate("slip_speed", x0) < 1e-15
    if chart == "euler":  # a fixed point of the axes turning with the precession
        assert np.max(np.abs(m.rhs(x0, "rolling"))) < 1e-15
    assert abs(m.evaluate("friction", x0, "rolling")[0] + y0[2] * y0[1]) < 1e-15  # the centripetal force
    r = pk.simulate(m, x0, 200.0, rtol=1e-13, dense=True, stop_at="none")
    assert r.status is pk.Status.COMPLETED and r.mode == "rolling"
    assert np.max(np.abs(m.chart.to_paper(r.x) - y0)) < 1e-11
    # G on the circle of radius |V/Omega| about (-V/Omega, 0) (the axis starts along X)
    pose = r.pose(np.linspace(0.0, 200.0, 37))
    rho = y0[1] / y0[2]
    assert np.max(np.abs(np.hypot(pose["X"] + rho, pose["Y"]) - abs(rho))) < 1e-10


@pytest.mark.parametrize("disk", [THIN, COIN], ids=["thin", "coin"])
def test_spinning_in_place_is_the_closed_form_precession(disk):
    """Omega^2 = 1 / (A sin(theta)) for the thin disk (Moffatt's 4 g / (a alpha) as alpha -> 0),
    n = Omega (L/2) sin(theta) (zero slip at the rim); it stays put, rolling."""
    th = math.pi / 6
    y = spinning_in_place(disk, th)
    s, c, half = math.sin(th), math.cos(th), 0.5 * disk.thickness
    ht = c - half * s
    omega = math.sqrt(ht / (s * ((disk.A - disk.C) * c + disk.C * ht)))
    assert y[2] == pytest.approx(omega, rel=1e-14) and y[5] == pytest.approx(omega * half * s, rel=1e-13, abs=1e-15)
    if disk is THIN:
        assert y[2] == pytest.approx(1 / math.sqrt(disk.A * s), rel=1e-14)
    m = pk.Model(disk, pk.Coulomb(0.5))
    r = pk.simulate(m, y, 100.0, rtol=1e-13, stop_at="none")
    assert r.status is pk.Status.COMPLETED and np.max(np.abs(r.euler_end - y)) < 1e-11


@pytest.mark.parametrize("chart, law", [
    ("euler", pk.RollingResistance(0.05)), pytest.param("vector", pk.RollingResistance(0.05), marks=pytest.mark.slow),
    ("euler", pk.AirDrag(rotation=0.05))],
    ids=["rolling-resistance-euler", "rolling-resistance-vector", "air-drag-euler"])
def test_eulers_disk_falls_to_its_face_in_finite_time(chart, law):
    """Launched spinning in place at 30 deg, the precession speeds up as theta falls (Omega^2 ~ 4/theta
    on the spin-in-place manifold) and the run ends face down, with the energy accounted for."""
    m = pk.Model(THIN, pk.Viscous(1.0).with_dissipation(law), chart)
    y0 = spinning_in_place(THIN, math.pi / 6)
    r = pk.simulate(m, m.chart.from_paper(y0), 500.0, rtol=1e-12, stop_at="none", events=limit_events(THIN), dense=True)
    assert r.status is pk.Status.STOPPED and [e.name for e in r.events] == ["face down"]
    end = m.chart.to_paper(r.x)
    assert end[4] == pytest.approx(1e-3, rel=1e-9) and abs(end[2]) > 20 * y0[2]
    t_face = {"rolling-resistance": 20.8348090098, "air-drag": 40.4638942261}[law.name]
    assert r.t == pytest.approx(t_face, rel=1e-10)  # the two charts agree on it (measured: 2e-12)
    budget = r.energy_budget()
    assert abs(budget.residual) < 1e-10 and budget.energy_end < 0.01 * budget.energy_start


@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])
@pytest.mark.parametrize("theta0, name", [(1.2, "side down"), (1.0, "face down")])
def test_a_cylinder_tipped_past_its_balance_falls_onto_its_side_or_its_face(chart, theta0, name):
    """At rest on its rim, a cylinder of thickness 1 balances at tan(theta) = 1/(L/2) = 2 (1.107 rad):
    from 1.2 it falls onto its side (not modelled), from 1.0 onto its face."""
    cyl = pk.Disk(1.0)
    assert cyl.h(math.atan(2.0))[1] == pytest.approx(0.0, abs=1e-15)
    m = pk.Model(cyl, pk.Coulomb(0.5), chart)
    r = pk.simulate(m, m.chart.from_paper([0.0, 0.0, 0.0, 0.0, theta0, 0.0]), 50.0, rtol=1e-10, stop_at="none",
                    events=limit_events(cyl))
    assert r.status is pk.Status.STOPPED and r.events[-1].name == name
    assert m.chart.theta(r.x) == pytest.approx(math.pi / 2 if name == "side down" else 1e-3, rel=1e-9)


@pytest.mark.parametrize("body, y0, name, reason", [
    (THIN, spinning_in_place(THIN, math.pi / 6), "face down", "the flat face reached the table at t = 20.8348090"),
    (pk.Disk(1.0), [0.0, 0.0, 0.0, 0.0, 1.2, 0.0], "side down", "the side touched the table at t = 2.73318648"),
])
def test_the_run_ends_at_the_limit_with_its_reason_without_a_users_event(body, y0, name, reason):
    law = pk.Viscous(1.0).with_dissipation(pk.RollingResistance(0.05)) if body is THIN else pk.Coulomb(0.5)
    r = pk.simulate(pk.Model(body, law), y0, 500.0, rtol=1e-12, stop_at="none")
    assert r.status is pk.Status.STOPPED and r.events[-1].name == name and r.reason.startswith(reason)
    assert r.reason.endswith(": the disk lies flat" if name == "face down" else "(a line contact) is not modelled")
