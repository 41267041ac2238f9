"""The steady-state structure of a compound body (the tippe top with its stem), piece by piece:
each part of a branch is the steady precessions of its piece's own support, checked against
one-piece bodies built independently (the ball: pk.EccentricSphere; the stem's rounded end: a
user's Body with h = r - l cos(theta), the support of a sphere of radius r centred l from G),
at the same samples, in the linearisation and in pk.fixed_points; every part within its piece's
range, the switch ends at the body's switch angle with the piece's closed-form limits there; a
one-piece body's structure names no piece; the command line prints the pieces and switches."""

import json
import math

import phasekit as pk
from phasekit.bodies.compound import PieceSupport
from phasekit.steady.branch_stability import linearise_precession
from phasekit.steady.pieces import parts

import casadi as ca
import numpy as np
import pytest

from ..helpers import run_cli, strict_json

OFFSET, A, C, L, R = 0.3, 0.38, 0.4, 0.375, 0.2
TOP = pk.bodies.TippeTop(OFFSET, L, R, A=A, C=C)
TIP = OFFSET + 1.0 + L - R  # l, G to the centre of the stem's rounded end
LAW = pk.Viscous(0.3)  # friction drives the modes: the linearisation's eigenvalues are all informative


class StemEnd(pk.bodies.Body):
    """The stem's rounded end alone: a sphere of radius R centred TIP from G on +k, h = R - TIP c,
    the top's moments. Written as a user's Body: pk.CustomBody (and pk.EccentricSphere, whose
    offset must be below its radius) refuse it, as h < 0 for theta below acos(R / TIP), off the
    stem's range (G lies outside this sphere)."""

    def __init__(self):
        super().__init__(A, C)

    @property
    def shape_params(self):
        return ()

    def height(self, c, shape):
        return R - TIP * c


def stem_alone():
    return StemEnd()


def ball_alone():
    return pk.EccentricSphere(OFFSET, A=A, C=C)


class TwoSpheres(pk.bodies.Body):
    """The top's ball and stem end as one support written with fmax, the body's moments."""

    def __init__(self):
        super().__init__(A, C)

    @property
    def shape_params(self):
        return ()

    def height(self, c, shape):
        return ca.fmax(1 - OFFSET * c, R - TIP * c)


@pytest.fixture(scope="module")
def structure():
    return pk.steady_structure(TOP, LAW)


def closed_form(theta, radius, centre):
    """(Omega, n) of the steady precession of a sphere of ``radius`` whose centre lies ``centre``
    from G on +k (h = radius - centre cos): q = centre, rho_2 = radius, z = radius c - centre."""
    c = np.cos(theta)
    om = np.sqrt(centre * radius / ((A - C) * c * radius + C * centre))
    return om, om * (radius * c - centre) / radius


def test_the_branch_is_cut_at_the_switch_into_a_part_on_each_piece(structure):
    assert structure.status.value == "completed" and structure.signature == "pole0-switch | switch-polePi"
    ball, stem = structure.branches
    assert (ball.piece, stem.piece) == ("ball", "stem")
    assert [e.kind for e in ball.ends] == ["pole", "switch"] and [e.kind for e in stem.ends] == ["switch", "pole"]
    assert ball.ends[1].theta == stem.ends[0].theta == TOP.theta_switch == TOP.transfers[0].theta
    assert (ball.ends[1].to_piece, stem.ends[0].to_piece) == ("stem", "ball")
    assert ball.ends[1].describe() == f"the contact passes to the stem at theta = {TOP.theta_switch:.6g}"
    for b in structure.branches:  # every sample on its own piece's side of the switch
        lo, hi = (0.0, TOP.theta_switch) if b.piece == "ball" else (TOP.theta_switch, math.pi)
        assert b.theta.size > 20 and np.all((b.theta > lo) & (b.theta < hi))
        assert {TOP.piece(float(t)) for t in b.theta} == {b.piece}


def test_the_switch_ends_are_each_pieces_closed_form_limits_and_they_jump(structure):
    ball, stem = structure.branches
    t = TOP.theta_switch
    for end, (radius, centre) in ((ball.ends[1], (1.0, OFFSET)), (stem.ends[0], (R, TIP))):
        om, n = closed_form(t, radius, centre)
        assert end.Omega == pytest.approx(om, rel=1e-13) and end.n == pytest.approx(n, rel=1e-13)
    # H' jumps at the kink: so do the steady precessions (the rate halves, the spin quadruples)
    assert ball.ends[1].Omega / stem.ends[0].Omega == pytest.approx(2.1239, abs=1e-4)
    assert stem.ends[0].n / ball.ends[1].n == pytest.approx(3.8669, abs=1e-4)


@pytest.mark.parametrize("piece, alone", [("ball", ball_alone), ("stem", stem_alone)])
def test_each_part_is_the_one_piece_body_of_its_support(structure, piece, alone):
    """The samples, the ends' limits and the linearisation at the samples of each part are those
    of a one-piece body with that piece's support alone (another body, another model)."""
    body = alone()
    part = next(b for b in structure.branches if b.piece == piece)
    one = pk.steady_structure(body, LAW, stability=False)
    om, n = one.precession(part.theta)
    assert part.Omega == pytest.approx(om, rel=1e-12) and part.n == pytest.approx(n, rel=1e-12)
    radius, centre = (1.0, OFFSET) if piece == "ball" else (R, TIP)
    assert part.Omega == pytest.approx(closed_form(part.theta, radius, centre)[0], rel=1e-12)
    model = pk.Model(body, LAW)
    for k in range(0, part.theta.size, max(part.theta.size // 6, 1)):
        fp = linearise_precession(model, float(part.theta[k]), float(part.Omega[k]), float(part.n[k]))
        ours = part.points[k]
        assert fp.n_unstable == ours.n_unstable and fp.stable == ours.stable
        assert np.sort_complex(fp.eigenvalues) == pytest.approx(np.sort_complex(ours.eigenvalues), rel=1e-9, abs=1e-10)


@pytest.mark.parametrize("omega0", [0.7049, 0.7053, 1.6, 1.7])
def test_fixed_points_of_the_top_at_a_rate_are_those_of_the_piece_they_stand_on(structure, omega0):
    """pk.fixed_points of the whole top and of the piece alone (restricted to the piece's range)
    find the same states, and the part of the branch passes through them."""
    t_switch = TOP.theta_switch
    whole = [p for p in pk.fixed_points(pk.Model(TOP, LAW, "euler"), omega0=omega0) if p.kind == "intermediate"]
    assert len(whole) == 1
    theta = float(whole[0].x[4])
    piece, body = ("ball", ball_alone()) if theta < t_switch else ("stem", stem_alone())
    lo, hi = (0.0, t_switch) if piece == "ball" else (t_switch, math.pi)
    alone = [float(p.x[4]) for p in pk.fixed_points(pk.Model(body, LAW, "euler"), omega0=omega0)
             if p.kind == "intermediate" and lo < p.x[4] < hi]
    assert alone == [pytest.approx(theta, abs=1e-10)]
    om, n = structure.precession(theta)
    assert om[0] == pytest.approx(omega0, rel=1e-10) and n[0] == pytest.approx(float(whole[0].x[5]), rel=1e-9)
    part = next(b for b in structure.branches if b.piece == piece)
    assert part.ends[0].theta < theta < part.ends[1].theta
    # the structure's own states at that rate are the same (a switch end is a finite limit, not an infinite spin)
    at = [p for p in structure.at(omega0=omega0) if p.kind == "intermediate"]
    assert [float(p.x[4]) for p in at] == [pytest.approx(theta, abs=1e-10)]


def test_statics_and_pole_families_name_their_piece(structure):
    ball, stem = ball_alone(), stem_alone()
    statics = {s.theta: s for s in structure.static_equilibria}
    assert sorted(statics) == [0.0, math.pi]
    assert (statics[0.0].piece, statics[math.pi].piece) == ("ball", "stem")
    assert statics[0.0].height == pytest.approx(1.0 - OFFSET, rel=1e-15) and statics[0.0].h_tt == pytest.approx(OFFSET)
    assert statics[math.pi].height == pytest.approx(R + TIP, rel=1e-15) and statics[math.pi].h_tt == pytest.approx(-TIP)
    poles = {f.theta: f for f in structure.families if f.kind == "pole"}
    assert (poles[0.0].piece, poles[math.pi].piece) == ("ball", "stem") and len(structure.families) == 2
    ref = (pk.theory.pole_stability_threshold(ball, "upright"), pk.theory.pole_stability_threshold(stem, "inverted"))
    assert poles[0.0].critical == pytest.approx(ref[0].threshold, rel=1e-12)
    assert poles[math.pi].critical == pytest.approx(ref[1].threshold, rel=1e-12)
    assert structure.to_dict()["static_equilibria"][1]["piece"] == "stem"


def test_a_piece_is_read_off_the_whole_bodys_support_switch_by_switch():
    """PieceSupport freezes the if_else at the branch taken inside the piece: its H is the
    piece's analytic support on all of [0, pi], the body's own inside the piece."""
    ball, stem = parts(TOP)
    theta = np.linspace(0.0, np.pi, 41)
    c = np.cos(theta)
    assert ball.support.h(theta)[0] == pytest.approx(1.0 - OFFSET * c, rel=1e-15)
    assert stem.support.h(theta)[0] == pytest.approx(R - TIP * c, rel=1e-14, abs=1e-15)
    inside = theta[theta > TOP.theta_switch]
    assert np.array_equal(stem.support.h(inside)[0], TOP.h(inside)[0])
    assert (ball.edges[1].theta, ball.edges[1].switch) == (TOP.theta_switch, "stem") and stem.edges[0].switch == "ball"
    for theta_in, want in ((1.0, 1.0 - OFFSET * c), (3.0, R - TIP * c)):  # a body written with fmax instead
        assert PieceSupport(TwoSpheres(), "?", theta_in).h(theta)[0] == pytest.approx(want, rel=1e-14, abs=1e-15)


def test_a_one_piece_body_names_no_piece():
    s = pk.steady_structure(pk.EccentricSphere(OFFSET, A=A, C=C), LAW, samples=False)
    assert s.signature == "pole0-polePi" and [b.piece for b in s.branches] == [None]
    assert not any(hasattr(x, "piece") for x in s.static_equilibria + s.families)
    text = json.dumps(s.to_dict())
    assert '"piece"' not in text and "switch" not in text


def test_the_command_line_prints_the_pieces_and_the_switches():
    args = ("steady-states", "--body", "tippe-top", "--offset", OFFSET, "--A", A, "--C", C, "--mu", 0.3,
            "--stem-length", L)
    code, out, err = run_cli(*args)
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[0].startswith("signature: pole0-switch | switch-polePi")
    assert lines[1].startswith("branch 1 (on the ball): pole at theta = 0.0000000000")
    assert f"switch at theta = {TOP.theta_switch:.10f} (the contact passes to the stem; Omega = 1.4984068" in lines[1]
    assert lines[2].startswith(f"branch 2 (on the stem): switch at theta = {TOP.theta_switch:.10f} (the contact passes "
                               "to the ball; Omega = 0.70548043")
    assert "static equilibrium at theta = 3.1415926536 (pole, on the stem)" in out
    assert "spin about the vertical family at theta = 3.141593 (any n, on the stem)" in out
    code, out, err = run_cli(*args, "--json")
    d = strict_json(out)
    assert code == 0 and [b["piece"] for b in d["branches"]] == ["ball", "stem"]
    end = d["branches"][0]["ends"][1]
    assert end["kind"] == "switch" and end["to_piece"] == "stem" and end["theta"] == TOP.theta_switch
    assert end["Omega"] == pytest.approx(closed_form(TOP.theta_switch, 1.0, OFFSET)[0], rel=1e-13)
    assert [s["piece"] for s in d["static_equilibria"]] == ["ball", "stem"]
    assert [f["piece"] for f in d["families"]] == ["ball", "stem"]
