"""The tippe top with its stem: its support function is the larger of the ball's and the stem end's,
they are equal at the switch angle (closed form), the contact point lies on the ball below it and on
the stem's rounded end above it; the default moments are a ball plus a rod by the parallel-axis
theorem (closed form); the outline is the ball, the shaft and the rounded end; bad dimensions are
refused naming them; without a stem the tippe top is the eccentric sphere it always was."""

import math

import phasekit as pk
from phasekit import ParameterError
from phasekit.bodies.by_name import make_body
from phasekit.bodies.compound import STEM, STEM_MASS, default_moments

import numpy as np
import pytest

TippeTop = pk.bodies.TippeTop
DIMENSIONS = [(0.3, 0.375, 0.2), (0.1, 0.05, 0.6), (0.4, 2.0, 0.05)]


@pytest.mark.parametrize("offset, L, r", DIMENSIONS)
def test_the_support_is_the_larger_of_the_pieces_and_they_meet_at_the_switch(offset, L, r):
    top = TippeTop(offset, L, r, A=0.3, C=0.4)
    th = np.linspace(0.0, math.pi, 721)
    h = top.h(th)[0]
    ball, stem = 1 - offset * np.cos(th), r - (offset + 1 + L - r) * np.cos(th)
    assert np.max(np.abs(h - np.maximum(ball, stem))) < 1e-15
    c_switch = -(1 - r) / (1 - r + L)
    assert math.cos(top.theta_switch) == pytest.approx(c_switch, rel=1e-15)
    hb, hs = top.piece_heights(top.theta_switch)
    assert hb == pytest.approx(hs, rel=1e-15)
    for tr, (frm, to, d) in zip(top.transfers, (("ball", "stem", 1), ("stem", "ball", -1))):
        assert (tr.from_piece, tr.to_piece, tr.direction, tr.theta) == (frm, to, d, top.theta_switch)
        assert tr.name == f"{to} touches"
    assert top.h(math.pi)[0] == pytest.approx(offset + 1 + L, rel=1e-15)  # on the stem's end


@pytest.mark.parametrize("offset, L, r", DIMENSIONS)
def test_the_contact_point_is_on_the_ball_below_the_switch_and_on_the_stems_end_above_it(offset, L, r):
    top = TippeTop(offset, L, r, A=0.3, C=0.4)
    for th, centre, radius in ((top.theta_switch - 0.2, offset, 1.0), (top.theta_switch + 0.2, top.tip_centre, r),
                               (0.0, offset, 1.0), (math.pi, top.tip_centre, r)):
        h, h1, h2 = top.h(th)
        zP, xP = h1 * math.sin(th) - h * math.cos(th), h * math.sin(th) + h1 * math.cos(th)
        assert math.hypot(zP - centre, xP) == pytest.approx(radius, rel=1e-14)
        assert h + h2 == pytest.approx(radius, rel=1e-13)  # the meridian's radius of curvature
        assert top.piece(th) == ("ball" if centre == offset else "stem")


def test_the_default_moments_are_a_ball_and_a_rod_by_the_parallel_axis_theorem():
    offset, L = 0.3, STEM[0]
    whole = default_moments(offset, L)
    m_rod, m_ball, z_rod = STEM_MASS, 1 - STEM_MASS, 1 + L / 2  # the rod from the ball's pole, O at 0
    # about O: the ball's 2/5 m_ball, the rod's m (L^2/12 + z^2); about G (at -offset): minus offset^2
    A = 0.4 * m_ball + m_rod * (L * L / 12 + z_rod * z_rod) - offset**2
    assert whole.z == pytest.approx(-offset, abs=1e-15) and whole.mass == pytest.approx(1.0, rel=1e-15)
    assert whole.A == pytest.approx(A, rel=1e-12) and whole.C == pytest.approx(0.4 * m_ball, rel=1e-12)
    top = TippeTop(offset)
    assert (top.A, top.C) == (whole.A, whole.C) and top.shape_params == (offset, *STEM)
    with pytest.raises(ParameterError) as err:
        TippeTop(0.5)
    assert err.value.param == "offset"


def test_the_outline_is_the_ball_the_shaft_and_the_rounded_end():
    top = TippeTop(0.3, 0.375, 0.2, A=0.38, C=0.4)
    z, r = top.outline(48)
    assert z[0] == pytest.approx(-0.7, rel=1e-15) and r[0] == 0.0 and np.all(np.diff(z) >= 0)
    assert z[-1] == pytest.approx(top.h(math.pi)[0], rel=1e-15) and abs(r[-1]) < 1e-15
    on_ball = np.abs(np.hypot(z - 0.3, r) - 1.0) < 1e-12
    on_end = (np.abs(np.hypot(z - top.tip_centre, r) - 0.2) < 1e-12) & (z >= top.tip_centre)
    shaft = (np.abs(r - 0.2) < 1e-15) & (z <= top.tip_centre)
    assert np.all(on_ball | on_end | shaft)
    # the support is the depth of the outline's lowest point below G: none reaches below the table
    th = np.linspace(0.0, math.pi, 181)
    depth = (np.outer(np.sin(th), r) - np.outer(np.cos(th), z)).max(axis=1)
    h = top.h(th)[0]
    assert np.all(depth <= h + 1e-12) and np.all(depth >= h - 0.02)


@pytest.mark.parametrize("kw, name", [({"stem_length": 0.0}, "stem_length"), ({"stem_length": 11.0}, "stem_length"),
                                      ({"stem_radius": 1.0}, "stem_radius"), ({"stem_radius": 0.0}, "stem_radius"),
                                      ({"stem_radius": float("nan")}, "stem_radius")])
def test_bad_dimensions_are_refused_naming_them(kw, name):
    with pytest.raises(ParameterError) as err:
        TippeTop(0.3, A=0.38, C=0.4, **kw)
    assert err.value.param == name


def test_without_a_stem_the_tippe_top_is_the_eccentric_sphere():
    plain = make_body("tippe-top", offset=0.3, A=0.38, C=0.4)
    assert type(plain) is pk.EccentricSphere and plain == pk.EccentricSphere(0.3, A=0.38, C=0.4)
    assert "stem_length" not in plain.to_dict()
    stemmed = make_body("tippe-top", offset=0.3, stem_radius=0.3, A=0.38, C=0.4)
    assert stemmed == TippeTop(0.3, STEM[0], 0.3, A=0.38, C=0.4)
    model = pk.Model(stemmed, pk.Coulomb(0.3))
    assert pk.Model.from_dict(model.to_dict()) == model
    with pytest.raises(ParameterError) as err:
        make_body("spheroid", a=1.5, stem_length=0.3)
    assert err.value.param == "stem_length"
