"""A uniform solid cone on the rim of its base or on its tip: the support functions are the rim's
and the tip's (on the tip both radii of curvature are zero), they meet where the side lies on
the table, the ends of each range are stated; a top spinning on its point without friction keeps
its energy, L_Z and its spin, sleeping on its point with Coulomb friction it stays put, and the
Euler and vector charts agree on it."""

import math

import phasekit as pk
from phasekit.bodies import Body
from phasekit.bodies.edged import FLAT_ANGLE

import numpy as np
import pytest

Cone = pk.bodies.Cone
HEIGHTS = [0.05, 0.5, 2.0, 10.0]
#: a top of height 2 on its point, tilted 25 deg from the vertical (theta = 2.7), spinning fast and
#: precessing near its steady rate: it nutates a little, well clear of its side (theta_side = 2.03)
TOP_START = np.array([0.05, -0.03, -0.3, 0.1, 2.7, 12.0])


@pytest.mark.parametrize("height", HEIGHTS)
def test_the_support_functions_are_the_rims_and_the_tips(height):
    rim, tip = Cone(height), Cone(height, on="tip")
    for cone, (zP_want, xP_want) in ((rim, (-height / 4, 1.0)), (tip, (0.75 * height, 0.0))):
        lo, hi = cone.theta_range
        th = np.linspace(lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo), 101)
        h, h1, _ = cone.h(th)
        s, c = np.sin(th), np.cos(th)
        want = s + 0.25 * height * c if cone.on == "rim" else -0.75 * height * c
        assert np.max(np.abs(h - want)) < 1e-13 * max(1.0, height)  # sqrt(1 - c^2) near c = 1: 1e-14
        # the contact point relative to G stays on the rim, or on the tip
        xP, zP = h * s + h1 * c, h1 * s - h * c
        assert np.max(np.abs(xP - xP_want)) < 1e-12 * max(1.0, height)
        assert np.max(np.abs(zP - zP_want)) < 1e-12 * max(1.0, height)
        r1, r2 = cone.radii_of_curvature(th)
        assert np.max(np.abs(r1)) < 1e-11 * max(1.0, height)  # an edge, or a tip: zero meridional radius
        if cone.on == "tip":  # a tip: the azimuthal radius is zero too
            assert np.max(np.abs(r2)) < 1e-13 * height
        else:
            assert np.max(np.abs(r2 * s - 1.0)) < 1e-12 * max(1.0, height)


@pytest.mark.parametrize("height", HEIGHTS)
def test_the_rim_and_the_tip_meet_where_the_side_lies_on_the_table(height):
    rim, tip = Cone(height), Cone(height, on="tip")
    side = rim.theta_side
    assert side == tip.theta_side and side == pytest.approx(math.pi / 2 + math.atan(1 / height), rel=1e-15)
    assert rim.h(side)[0] == pytest.approx(tip.h(side)[0], rel=1e-14)
    # on either side of it the lower of the two supports is the one not in contact: the body's is the higher
    assert rim.h(side - 0.01)[0] > tip.h(side - 0.01)[0] and tip.h(side + 0.01)[0] > rim.h(side + 0.01)[0]
    # the side lies level there: the slant from the rim (-l/4, 1) to the tip (3l/4, 0) rises by
    # l cos(theta) + sin(theta) (a point (z, r) of the meridian on the low side is z cos - r sin above G)
    assert math.cos(side) * height + math.sin(side) == pytest.approx(0.0, abs=1e-13 * max(1.0, height))
    assert rim.theta_range == (0.0, side) and tip.theta_range == (side, math.pi)


def test_the_ends_of_each_range_are_stated():
    rim, tip = Cone(2.0), Cone(2.0, on="tip")
    assert [(lim.name, lim.theta, lim.direction) for lim in rim.limits] == [
        ("face down", FLAT_ANGLE, -1), ("side down", rim.theta_side, +1)]
    assert [(lim.name, lim.theta, lim.direction) for lim in tip.limits] == [("side down", tip.theta_side, -1)]
    assert rim.limits[0].reason.format(t=2.5) == "the base reached the table at t = 2.5: the cone stands on its base"
    assert tip.limits[0].reason.format(t=3) == \
        "the side touched the table at t = 3: a cone on its side (a line contact) is not modelled"
    assert tip.check_theta(math.pi) == math.pi  # a top sleeping on its point is a state of the tip's model
    for cone, theta, says in ((rim, 2.1, "must lie in (0, 2.03444) for this cone (on its rim; at 0 it stands on its "
                                         "base, at 2.03444 its side touches the table)"),
                              (tip, 2.0, "must lie in (2.03444, pi] for this cone (on its tip; at 2.03444 its side "
                                         "touches the table)"), (rim, 0.0, "must lie in (0, 2.03444)")):
        with pytest.raises(pk.ParameterError) as err:
            cone.check_theta(theta, "theta0")
        assert err.value.param == "theta0" and says in str(err.value)


def test_the_base_check_refuses_the_tip_and_the_edged_check_accepts_it():
    tip = Cone(2.0, on="tip")
    with pytest.raises(pk.ParameterError, match="strictly convex"):
        Body.check_convex(tip, "height", (2.1, 3.1))
    tip.check_convex("height")  # both radii zero: a tip, not a concave profile
    Cone(2.0).check_convex("height")


@pytest.mark.parametrize("kwargs, name", [
    (dict(height=0.0), "height"), (dict(height=-1.0), "height"), (dict(height=float("nan")), "height"),
    (dict(height=2e3), "height"), (dict(height=1.0, on="side"), "on"), (dict(height=1.0, A=0.7, C=1.2), "C"),
    (dict(height=1.0, A=0.1, C=0.3), "C"), (dict(height=1.0, A=-1.0), "A"),
])
def test_bad_parameters_are_named(kwargs, name):
    with pytest.raises(pk.ParameterError) as err:
        Cone(**kwargs)
    assert err.value.param == name


def test_a_moment_beyond_the_farthest_point_is_refused_when_a_model_is_built():
    with pytest.raises(pk.ParameterError) as err:
        pk.Model(Cone(2.0, on="tip", A=2.5, C=0.3), pk.Coulomb(0.1))
    assert err.value.param == "A" and "2.25" in str(err.value)  # the tip, 3 l/4 = 1.5 from G
    pk.Model(Cone(0.1, on="tip"), pk.Coulomb(0.1))  # a flat cone: its rim, not its tip, is the farthest


def test_cones_share_a_compiled_structure_per_contact_and_describe_themselves():
    assert Cone(0.5).structure_key == Cone(3.0).structure_key != Cone(0.5, on="tip").structure_key
    assert Cone(0.5, on="tip").structure_key == Cone(3.0, on="tip").structure_key
    top = Cone(2.0, on="tip")
    assert repr(top) == "Cone(height=2, on='tip')" and repr(Cone(2.0, A=0.4)) == "Cone(height=2, on='rim', A=0.4, C=0.3)"
    assert top.to_dict() == {"body": "cone", "height": 2.0, "on": "tip", "A": 0.3, "C": 0.3,
                             "description": "cone, height 2 radii (on its tip), A=0.3, C=0.3"}
    assert top.kind == "cone" and not top.flip_symmetric and not top.is_prolate and top == Cone(2.0, on="tip")


def test_the_outline_drawn_is_the_base_and_the_side():
    z, r = Cone(2.0).outline(15)
    assert (z[0], r[0], z[-1], r[-1]) == (-0.5, 0.0, 1.5, 0.0)  # the base's centre, the tip
    assert np.all(np.abs((z + 0.5) / 2.0 + r - 1.0)[5:] < 1e-15) and np.all(z[:5] == -0.5)


@pytest.mark.timeout(600)
@pytest.mark.parametrize("chart", ["euler", pytest.param("vector", marks=pytest.mark.slow)])
def test_a_frictionless_top_on_its_point_keeps_energy_L_Z_and_spin(chart):
    """Viscous(0): the reaction at the tip is vertical, on the axis: no couple about the vertical
    through G nor about k, so L_Z and n are invariants, and the energy is."""
    top = Cone(2.0, on="tip")
    m = pk.Model(top, pk.Viscous(0.0), chart)
    te = np.linspace(0.0, 400.0, 801)
    r = pk.simulate(m, m.chart.from_paper(TOP_START), 400.0, rtol=1e-13, t_eval=te, stop_at="none")
    assert r.status is pk.Status.COMPLETED and len(r.events) == 0 and r.R_min > 0.4  # on its point all along
    for name in ("energy", "L_Z", "spin"):
        q = m.evaluate(name, r.ys)
        assert np.max(np.abs(q - q[0])) < 1e-10 * abs(q[0]), name
    theta = m.evaluate("theta", r.ys)
    assert np.ptp(theta) > 0.02 and theta.min() > 2.6  # it nutates, well clear of its side


@pytest.mark.slow  # its own vector-chart integrator (~20 s cold); tests/cli/test_body_cone.py runs the sleeping top by default
@pytest.mark.timeout(600)
def test_a_top_sleeping_on_its_point_stays_put():
    """Upright on its point (theta = pi, the vector chart) spinning, Coulomb friction: no force is
    needed, it sticks at once and stays, its point fixed on the table."""
    top = Cone(2.0, on="tip")
    m = pk.Model(top, pk.Coulomb(0.3), "vector")
    x0 = m.chart.from_paper([0.0, 0.0, 0.0, 0.0, math.pi, 20.0])
    r = pk.simulate(m, x0, 20.0, rtol=1e-12, stop_at="none", dense=True)
    assert r.status is pk.Status.COMPLETED and r.mode == "rolling" and [e.name for e in r.events] == ["stick"]
    assert np.max(np.abs(r.x - x0)) < 1e-12
    pose = r.pose(np.linspace(0.0, 20.0, 11))
    assert max(np.max(np.abs(pose[k])) for k in ("X", "Y", "X_P", "Y_P")) < 1e-12
    assert m.evaluate("R", r.x, "rolling") == pytest.approx(1.0, rel=1e-12)  # it carries its weight, no more


@pytest.mark.timeout(600)
@pytest.mark.parametrize("law, events", [pytest.param(pk.Viscous(0.5), [], marks=pytest.mark.slow), (pk.Coulomb(0.3), ["side down"])])
def test_the_two_charts_agree_on_a_top(law, events):
    """The top run in the Euler and the vector chart: the same state at the end (with Coulomb
    friction the sliding point lets it fall onto its side: the same event at the same time)."""
    ends = []
    for chart in ("euler", "vector"):
        m = pk.Model(Cone(2.0, on="tip"), law, chart)
        r = pk.simulate(m, m.chart.from_paper(TOP_START), 10.0, rtol=1e-13, stop_at="none")
        assert [e.name for e in r.events] == events
        ends.append((r.t, m.chart.to_paper(r.x)))
    assert abs(ends[0][0] - ends[1][0]) <= 1e-9 and np.max(np.abs(ends[0][1] - ends[1][1])) <= 1e-9
    if events:
        assert ends[0][0] < 10.0 and ends[0][1][4] == pytest.approx(Cone(2.0).theta_side, rel=1e-9)


@pytest.mark.timeout(600)
def test_a_cone_at_rest_on_its_rim_falls_back_onto_its_base():
    """Tipped onto its rim at rest, short of balance (tan(theta) = 4/l), it falls back onto its base:
    the run ends face down."""
    cone = Cone(2.0)
    assert cone.h(math.atan(2.0))[1] == pytest.approx(0.0, abs=1e-15)  # the balance on the rim
    r = pk.simulate(pk.Model(cone, pk.Coulomb(0.5)), [0.0, 0.0, 0.0, 0.0, 1.0, 0.0], 50.0, rtol=1e-10, stop_at="none")
    assert r.status is pk.Status.STOPPED and r.events[-1].name == "face down"
    assert r.reason.endswith("the cone stands on its base")
