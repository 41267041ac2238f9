"""The steady-state structure of a body with an edge or a tip (pk.Disk, pk.Cone), on the body's
range of theta: its branches end at the range's limits (an end of kind "limit", named as the run's
event), checked against closed forms derived by hand from h = sin(theta) + a cos(theta) (the
rim of a face a from G), the thin disk's spinning in place (Omega^2 = 1 / (A sin theta), n = 0:
Moffatt's Omega^2 sin(alpha) = 4 g / a) and pk.fixed_points; the states at a rate or spin on it
agree with pk.fixed_points; a tip's structure is degenerate, and the Lagrange top's precession
its note names is a zero of the rolling field; the command line prints the limits."""

import math

import phasekit as pk
from phasekit.steady.pieces import tip_precession
from phasekit.steady.precessions import intermediate_omega, precession_state

import numpy as np
import pytest

from ..helpers import run_cli, strict_json

DISK, COIN, L = pk.Disk(0.0), pk.Disk(0.1), 0.1
RIM, TIP = pk.Cone(2.0, "rim"), pk.Cone(2.0, "tip")  # l = 2: the uniform cone has A = C = 0.3
LAW = pk.Coulomb(0.3)


@pytest.fixture(scope="module")
def structures():
    return {b: pk.steady_structure(b, LAW) for b in (DISK, COIN, RIM, TIP)}


def rim_precession(body, a, theta):
    """(Omega, n) on the rim of a face a from G, h = s + a c, by hand: q = c/s - a, rho_2 = 1/s,
    z = a, D = A c/s - C a, so Omega^2 = (c - a s) / (s (A c - C a s)), n = Omega a s."""
    c, s = np.cos(theta), np.sin(theta)
    om = np.sqrt((c - a * s) / (s * (body.A * c - body.C * a * s)))
    return om, om * a * s


def rounding(theta, *roots):
    """The closed forms' rounding near a face, where c = cos(theta) keeps ~1e-16 / theta^2 of 1 - c,
    and near a root of q or D (``roots``), where they lose ~1e-16 / distance."""
    d = np.minimum(theta, np.pi - theta)
    near = np.min([np.abs(theta - r) for r in roots], axis=0) if roots else np.inf
    return 1e-12 + 4e-16 / d**2 + 4e-16 / near


def test_the_thin_disk_spins_in_place_on_one_branch_between_its_faces(structures):
    s = structures[DISK]
    assert s.status is pk.Status.COMPLETED and s.signature == "limit-cross-limit"
    (b,) = s.branches
    lo, hi = b.ends
    assert (lo.kind, lo.limit, lo.theta, hi.limit, hi.theta) == ("limit", "face down", 0.0, "face down", math.pi)
    assert lo.Omega == hi.Omega == math.inf and lo.n == hi.n == 0.0  # Omega^2 sin(theta) = 1/A: it diverges
    assert b.crossings == (math.pi / 2,)  # the upright disk spinning about its vertical diameter, at any rate
    # Moffatt's relation, exact here: A Omega^2 sin(theta) = 1 (Omega^2 sin = 4 g/b for A = 1/4), n = 0
    assert np.all(np.abs(DISK.A * b.Omega**2 * np.sin(b.theta) - 1) <= rounding(b.theta))
    assert np.max(np.abs(b.n)) < 1e-12 and b.theta.size > 50
    inner = np.abs(b.theta - math.pi / 2) > 1e-3  # intermediate_omega: h_theta / x_P, 0/0 at the crossing
    om = np.array([intermediate_omega(DISK, t) for t in b.theta[inner]])
    assert np.all(np.abs(om / b.Omega[inner] - 1) <= rounding(b.theta[inner]))
    assert [(x.theta, x.kind) for x in s.static_equilibria] == [(math.pi / 2, "tilted")]  # G above the rim: a maximum
    assert [(f.kind, f.theta) for f in s.families] == [("precession", math.pi / 2), ("rolling", math.pi / 2)]
    assert s.families[0].critical == pytest.approx(1 / math.sqrt(DISK.A), rel=1e-14)  # where the branch crosses


@pytest.mark.parametrize("omega0", [2.5, 4.0, 10.0, 30.0])
def test_the_spin_in_place_at_a_rate_is_that_of_fixed_points_and_the_closed_form(structures, omega0):
    model = pk.Model(DISK, LAW)
    found, listed = structures[DISK].at(omega0=omega0), pk.fixed_points(model, omega0=omega0)
    assert [p.kind for p in found] == [p.kind for p in listed] == ["horizontal", "intermediate"]
    for a, b in zip(found, listed):
        assert np.allclose(a.x, b.x, rtol=1e-10, atol=1e-10)
    theta = math.asin(1 / (DISK.A * omega0**2))  # below pi/2 (the other is its mirror image)
    exact = precession_state(DISK, theta, omega0=omega0)
    assert np.allclose(found[1].x, exact, rtol=1e-10, atol=1e-10) and exact[5] == pytest.approx(0.0, abs=1e-14)
    assert intermediate_omega(DISK, found[1].x[4]) == pytest.approx(omega0, rel=1e-10)


def test_a_coin_ends_face_down_and_side_down_on_the_closed_forms(structures):
    s = structures[COIN]
    assert s.signature == "limit-inf | static-limit"
    (face, inf), (static, side) = (b.ends for b in s.branches)
    assert (face.limit, face.theta, face.Omega, face.n) == ("face down", 0.0, math.inf, 0.0)
    assert inf.theta == pytest.approx(math.atan(2 * COIN.A / (COIN.C * L)), abs=1e-14)  # D = 0
    assert static.theta == pytest.approx(math.atan(2 / L), abs=1e-14)  # q = 0: G above the rim
    # the side touches at pi/2: q = -L/2, rho_2 = 1, D = -C L/2, so Omega = 1/sqrt(C), n = Omega L/2
    assert (side.limit, side.theta) == ("side down", math.pi / 2)
    assert side.Omega == pytest.approx(1 / math.sqrt(COIN.C), rel=1e-14) and side.n == pytest.approx(side.Omega * L / 2, rel=1e-14)
    for b in s.branches:
        om, n = rim_precession(COIN, L / 2, b.theta)
        bound = rounding(b.theta, inf.theta, static.theta)
        assert np.all(np.abs(b.Omega / om - 1) <= bound) and np.all(np.abs(b.n / n - 1) <= bound)
    first = s.branches[0]  # near the face the coin spins in place as the thin disk: A Omega^2 sin -> 1,
    k = int(np.flatnonzero(first.theta == 1e-4)[0])  # as 1 + (C/A - 1) (L/2) theta
    moffatt = COIN.A * first.Omega[k] ** 2 * math.sin(1e-4) - 1
    assert moffatt == pytest.approx((COIN.C / COIN.A - 1) * L / 2 * 1e-4, rel=1e-3)
    assert [x.theta for x in s.static_equilibria] == [static.theta]
    assert [f.kind for f in s.families] == ["rolling"]


def test_a_cone_on_its_rim_with_a_equal_to_c_crosses_a_family_up_to_its_side(structures):
    s = structures[RIM]
    assert RIM.A == pytest.approx(RIM.C, rel=1e-15) and s.signature == "limit-cross-limit"
    (b,) = s.branches
    face, side = b.ends
    assert (face.limit, face.Omega, side.limit, side.theta) == ("face down", math.inf, "side down", RIM.theta_side)
    om, n = rim_precession(RIM, 0.5, RIM.theta_side)  # a = l/4
    assert side.Omega == pytest.approx(om, rel=1e-14) and side.n == pytest.approx(n, rel=1e-14)
    assert b.crossings == pytest.approx((math.atan(2.0),), abs=1e-14)  # q = D = 0 together where A = C
    # with A = C, D = C q: Omega^2 = rho_2 / C = 1 / (C sin theta) all along, the crossing too
    assert np.all(np.abs(RIM.C * b.Omega**2 * np.sin(b.theta) - 1) <= rounding(b.theta))


@pytest.mark.parametrize("body", [DISK, COIN, RIM, TIP], ids=["disk", "coin", "cone-rim", "cone-tip"])
def test_the_states_at_a_rate_or_a_spin_are_those_of_fixed_points(structures, body):
    model = pk.Model(body, LAW)
    lo, hi = body.theta_range
    for kw in ({"omega0": 0.5}, {"omega0": 1.9}, {"omega0": 3.0}, {"omega0": 30.0}, {"omega0": 1e4},
               {"n0": 0.0}, {"n0": 0.01}, {"n0": 0.3}, {"n0": -0.05}):
        found, listed = structures[body].at(**kw), pk.fixed_points(model, **kw)
        assert [p.kind for p in found] == [p.kind for p in listed], kw
        for a, b in zip(found, listed):
            assert np.allclose(a.x, b.x, rtol=1e-10, atol=1e-10) and lo < a.y[4] <= hi, kw
    assert len(structures[COIN].at(n0=0.01)) == 2 and len(structures[RIM].at(omega0=1.9)) == 3


def test_the_thin_disk_has_no_isolated_state_at_a_spin():
    # every precession of the thin disk has n = 0 (a continuum at n0 = 0), and its poles lie flat:
    # fixed_points once failed there (Newton at theta = 0, where H' diverges)
    model = pk.Model(DISK, LAW)
    assert pk.fixed_points(model, n0=0.0) == pk.fixed_points(model, n0=2.0) == []


def test_a_tip_is_degenerate_with_the_lagrange_tops_precession_in_its_note(structures):
    s = structures[TIP]
    assert s.status is pk.Status.COMPLETED and s.signature == "degenerate" and not s.branches
    assert "a tip: rho_2" in s.degenerate and "Lagrange top" in s.degenerate and "d = 1.5" in s.degenerate
    assert [(x.theta, x.kind, x.stable) for x in s.static_equilibria] == [(math.pi, "pole", False)]
    assert [(f.kind, f.theta) for f in s.families] == [("pole", math.pi)]
    model = pk.Model(TIP, LAW)
    assert s.at(omega0=2.0) == pk.fixed_points(model, omega0=2.0) == []
    (a,), (b,) = s.at(n0=3.0), pk.fixed_points(model, n0=3.0)
    assert a.kind == b.kind == "inverted" and np.array_equal(a.x, b.x)


@pytest.mark.parametrize("theta", [2.2, 2.6, 3.0])
@pytest.mark.parametrize("omega", [0.3, 1.0, -5.0])
def test_the_lagrange_tops_precession_is_a_zero_of_the_rolling_field(theta, omega):
    d = 0.75 * TIP.altitude
    x = tip_precession(TIP, theta, omega)
    # by hand: Omega (C n - (A + d^2) Omega cos) = -d, the tip at rest, G at V = -d Omega sin
    assert omega * (TIP.C * x[5] - (TIP.A + d * d) * omega * math.cos(theta)) == pytest.approx(-d, rel=1e-14)
    rolling = pk.Model(TIP, LAW)
    assert np.max(np.abs(rolling.rhs(x, "rolling"))) <= 1e-13 * (1 + omega**2)
    assert rolling.normal_reaction(x, "rolling") == pytest.approx(1.0, rel=1e-12)
    # a viscous law has no force at zero slip: G does not turn, dU/dt = Omega V = -d Omega^2 sin
    viscous = pk.Model(TIP, pk.Viscous(0.3))
    assert viscous.rhs(x)[0] == pytest.approx(-d * omega**2 * math.sin(theta), rel=1e-12)
    # and with G at rest the tip allows Omega = 0 only, where the gravity couple is unbalanced
    assert abs(viscous.rhs(np.array([0.0, 0.0, 0.0, 0.0, theta, 2.0]))[3]) > 0.1


def test_the_command_line_prints_the_limits():
    code, out, err = run_cli("steady-states", "--body", "disk", "--mu", "0.3")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[0].startswith("signature: limit-cross-limit")
    assert lines[1].startswith("branch 1: limit at theta = 0.0000000000 (face down: the face comes down onto the table "
                               "at theta = 0; Omega = infinite, spin n = 0) -> limit at theta = 3.1415926536 (face down")
    code, out, err = run_cli("steady-states", "--body", "disk", "--thickness", "0.1", "--mu", "0.3", "--json")
    d = strict_json(out)
    assert code == 0 and d["status"] == "completed" and d["signature"] == "limit-inf | static-limit"
    face, side = d["branches"][0]["ends"][0], d["branches"][1]["ends"][1]
    assert (face["kind"], face["limit"], face["Omega"], face["diverges"], face["n"]) == ("limit", "face down", None,
                                                                                         ["Omega"], 0.0)
    assert side["limit"] == "side down" and side["diverges"] == [] and side["Omega"] == pytest.approx(math.sqrt(2), rel=1e-14)
    code, out, err = run_cli("steady-states", "--body", "cone", "--on", "tip", "--height", "2", "--mu", "0.3")
    assert code == 0 and out.startswith("signature: degenerate") and "(a tip: rho_2" in out
