"""Steady states under dissipation laws: a steady state keeps its energy, so only those at which
every law's power vanishes remain (phasekit.steady.dissipative). Spin friction and air drag on
rotation leave no spin or precession (spin friction only the straight rolling on the equator,
w horizontal); rolling resistance leaves the spins with w vertical;
air drag on translation leaves every state with G still. steady_structure says so in its note,
fixed_points finds only those states and find_fixed_point names the law that takes the energy.
A simulation from the states confirms it (the energy stays, or the body stops at the closed-form
time).
"""

import json

import phasekit as pk

import numpy as np
import pytest

PROLATE_OFFSET = pk.Spheroid(1.5, offset=0.2)
TIPPE_TOP = pk.EccentricSphere(0.3, A=0.38, C=0.4)
BODIES = [pk.Spheroid(1.5), PROLATE_OFFSET, pk.Spheroid(2.0 / 3.0), TIPPE_TOP]


@pytest.mark.parametrize("body", BODIES, ids=repr)
@pytest.mark.parametrize("extra", [pk.SpinFriction(0.01), pk.AirDrag(rotation=0.01)], ids=["spin", "air"])
def test_no_spinning_steady_state_survives_spin_friction_or_air_drag_on_rotation(body, extra):
    bare = pk.steady_structure(body, pk.Coulomb(0.1))
    s = pk.steady_structure(body, pk.Coulomb(0.1).with_dissipation(extra))
    assert bare.branches and bare.note is None and "note" not in bare.to_dict()
    assert s.status is pk.Status.COMPLETED and s.reason is None
    assert s.branches == () and s.signature == "none"
    # spin friction leaves the straight rolling on the equator of a flip-symmetric body (w_Z = 0)
    rolling = [f for f in bare.families if f.kind == "rolling" and f.theta == np.pi / 2]
    assert s.families == (tuple(rolling) if extra.name == "spin-friction" else ())
    assert s.static_equilibria == bare.static_equilibria  # at rest no law acts
    assert s.note.startswith(f"no steady precession with dissipation ({extra.name})")
    assert "energy decreases along every motion except rest" in s.note
    assert all(f"the branch {b.label}" in s.note for b in bare.branches)
    d = json.loads(json.dumps(s.to_dict(), allow_nan=False))
    assert d["note"] == s.note and d["signature"] == "none" and d["model"]["dissipation"][0]["law"] == extra.name
    m = pk.Model(body, pk.Coulomb(0.1).with_dissipation(extra))
    for kw in (dict(omega0=10.0), dict(n0=10.0)):
        assert pk.fixed_points(m, **kw) == [] and s.at(**kw) == []
        assert bare.at(**kw) or kw == dict(omega0=10.0)  # without the law there are states to lose


def test_find_fixed_point_names_the_law_that_takes_the_energy():
    m = pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1).with_dissipation(pk.SpinFriction(0.01)))
    with pytest.raises(pk.ConvergenceError, match="no horizontal fixed point with Omega = 10 under dissipation: "
                                                  "spin-friction takes energy out") as info:
        pk.steady.find_fixed_point(m, pk.steady.horizontal_state(10.0), kind="horizontal", value=10.0)
    assert "energy decreases along every motion except rest" in str(info.value)
    # the same state is found without the law
    bare = pk.steady.find_fixed_point(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0),
                                      kind="horizontal", value=10.0)
    assert bare.residual < 1e-10


@pytest.mark.parametrize("body", BODIES, ids=repr)
def test_rolling_resistance_leaves_the_spins_with_w_vertical(body):
    """Rolling resistance acts on the rolling part w_h of w only: the spins about the vertical at
    the poles (w = n e_Z) and, on a flip-symmetric body, the horizontal state (w = Omega e_Z) keep
    their energy; every branch (w tilted) and the straight rolling lose it."""
    delta = 0.01
    bare = pk.steady_structure(body, pk.Coulomb(0.1))
    s = pk.steady_structure(body, pk.Coulomb(0.1).with_dissipation(pk.RollingResistance(delta)))
    assert s.branches == () and s.signature == "none"
    kept = {(f.kind, f.theta) for f in s.families}
    assert {("pole", 0.0), ("pole", np.pi)} <= kept
    assert all(f.kind in ("pole", "precession") for f in s.families)
    assert all(f in bare.families for f in s.families)
    assert f"|h_theta| <= delta = {delta:g}" in s.note
    m = pk.Model(body, pk.Coulomb(0.1).with_dissipation(pk.RollingResistance(delta)))
    found = [p.kind for p in pk.fixed_points(m, n0=10.0)]
    assert found == [p.kind for p in bare.at(n0=10.0) if p.kind in ("vertical", "inverted")] == [p.kind for p in s.at(n0=10.0)]
    horizontal = [p.kind for p in pk.fixed_points(m, omega0=10.0)]
    assert horizontal == (["horizontal"] if body.flip_symmetric else [])


@pytest.mark.parametrize("body", BODIES, ids=repr)
def test_air_drag_on_translation_leaves_every_state_with_g_still(body):
    """The steady precessions hold G still: air drag on G's motion takes nothing from them, so the
    branches and the spins remain; the straight rolling (G moving) does not."""
    bare = pk.steady_structure(body, pk.Viscous(0.1), stability=False)
    s = pk.steady_structure(body, pk.Viscous(0.1).with_dissipation(pk.AirDrag(translation=0.05)), stability=False)
    assert s.signature == bare.signature != "none"
    assert [f.kind for f in s.families] == [f.kind for f in bare.families if f.kind != "rolling"]
    assert s.note.startswith("with dissipation (air-drag) only the steady states that keep their energy remain")


def test_a_sphere_with_g_at_its_centre_stays_degenerate_with_its_note():
    s = pk.steady_structure(pk.EccentricSphere(0.0), pk.Coulomb(0.1).with_dissipation(pk.SpinFriction(0.01)))
    assert s.degenerate is not None and s.signature == "degenerate" and "spin-friction" in s.note


@pytest.mark.timeout(300)
def test_a_simulation_from_the_vertical_spin_agrees():
    """The upright tippe top spinning at n0 about the vertical: with rolling resistance only it
    keeps every digit of its energy (a steady state: fixed_points lists it); with spin friction it
    stops at C n0 / (mu_s R), R = 1 (fixed_points lists nothing)."""
    n0, mu_s = 10.0, 0.05
    x0 = pk.steady.vertical_state(n0)
    kept = pk.Model(TIPPE_TOP, pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(0.002), pk.SpinFriction(0.0)),
                    "vector")
    r = pk.simulate(kept, x0, 50.0, stop_at="rest", max_wall=60.0, max_steps=100_000)
    assert r.status is pk.Status.COMPLETED and np.array_equal(r.x, x0)
    assert [p.kind for p in pk.fixed_points(kept, n0=n0)] == ["vertical", "inverted"]
    lost = pk.Model(TIPPE_TOP, pk.Coulomb(0.3).with_dissipation(pk.RollingResistance(0.0), pk.SpinFriction(mu_s)),
                    "vector")
    r = pk.simulate(lost, x0, 200.0, stop_at="rest", max_wall=60.0, max_steps=100_000)
    t_rest = TIPPE_TOP.C * n0 / mu_s
    assert r.status is pk.Status.REST and abs(r.t - t_rest) / t_rest < 1e-8
    assert pk.fixed_points(lost, n0=n0) == []
