"""Bodies with an edge: the disk's support function is that of its rim (the contact point stays on
the rim, the meridian's radius of curvature is zero), its moments are the uniform cylinder's
(checked against a quadrature over the solid), the convexity check accepts the edge and refuses
a concave profile, and the ends of its valid range are stated."""

import math

import phasekit as pk
from phasekit.bodies import Body
from phasekit.bodies.by_name import make_body
from phasekit.bodies.edged import FLAT_ANGLE, EdgedBody, Limit

import casadi as ca
import numpy as np
import pytest

THICKNESSES = [0.0, 0.1, 0.6, 2.0, 10.0]


def solid_cylinder_moments(L: float, n: int = 8) -> tuple[float, float]:
    """(A, C) per unit mass of the uniform cylinder of radius 1 and length L about its centre, by
    Gauss-Legendre quadrature over the solid in (r, z) (exact for these polynomial integrands):
    C = <r^2>, A = <r^2/2 + z^2> (the mean of x^2 + z^2 over the azimuth)."""
    x, w = np.polynomial.legendre.leggauss(n)
    r, wr = 0.5 * (x + 1.0), 0.5 * w  # r in [0, 1]
    z, wz = 0.5 * L * x, 0.5 * L * w  # z in [-L/2, L/2]
    if L == 0.0:  # a thin disk: the mass on the plane z = 0
        z, wz = np.zeros(1), np.ones(1)
    R, Z = np.meshgrid(r, z, indexing="ij")
    W = np.outer(wr * r, wz)  # the volume element 2 pi r dr dz, up to 2 pi
    m = W.sum()
    return float(np.sum(W * (0.5 * R**2 + Z**2)) / m), float(np.sum(W * R**2) / m)


@pytest.mark.parametrize("L", THICKNESSES)
def test_the_default_moments_are_the_uniform_cylinders(L):
    disk = pk.Disk(L)
    A, C = solid_cylinder_moments(L)
    assert disk.A == pytest.approx(A, rel=1e-12, abs=0) and disk.C == pytest.approx(C, rel=1e-12, abs=0)
    # the closed forms M r^2/4 + M L^2/12 and M r^2/2
    assert abs(disk.A - (0.25 + L * L / 12)) <= 1e-12 and disk.C == 0.5
    assert disk.uniform and repr(disk) == f"Disk(thickness={L:g})"


@pytest.mark.parametrize("L", THICKNESSES)
def test_the_support_function_is_the_rims_and_the_contact_stays_on_it(L):
    disk = pk.Disk(L)
    lo, hi = disk.theta_range
    th = np.linspace(lo + 0.02, hi - 0.02, 101)
    h, h1, h2 = disk.h(th)
    s, c = np.sin(th), np.cos(th)
    assert np.max(np.abs(h - (s + 0.5 * L * c))) < 1e-14 * max(1.0, L)
    assert np.max(np.abs(h1 - (c - 0.5 * L * s))) < 1e-12 * max(1.0, L)
    # the contact point relative to G: on the rim (distance 1 from the axis, -L/2 along k)
    xP, zP = h * s + h1 * c, h1 * s - h * c
    assert np.max(np.abs(xP - 1.0)) < 1e-12 * max(1.0, L) and np.max(np.abs(zP + 0.5 * L)) < 1e-12 * max(1.0, L)
    # an edge: the meridian's radius of curvature is zero, the azimuthal one is 1/sin(theta)
    r1, r2 = disk.radii_of_curvature(th)
    assert np.max(np.abs(r1)) < 1e-11 * max(1.0, L) and np.max(np.abs(r2 * s - 1.0)) < 1e-12 * max(1.0, L)


def test_the_valid_range_and_its_ends():
    thin, coin = pk.Disk(0.0), pk.Disk(0.1)
    assert thin.theta_range == (0.0, math.pi) and coin.theta_range == (0.0, math.pi / 2)
    assert [(lim.name, lim.theta, lim.direction) for lim in thin.limits] == [
        ("face down", FLAT_ANGLE, -1), ("face down", math.pi - FLAT_ANGLE, +1)]
    assert [(lim.name, lim.theta, lim.direction) for lim in coin.limits] == [
        ("face down", FLAT_ANGLE, -1), ("side down", math.pi / 2, +1)]
    assert coin.limits[0].reason.format(t=12.5) == "the flat face reached the table at t = 12.5: the disk lies flat"
    assert pk.Disk(2.0).limits[1].reason.format(t=3) == \
        "the side touched the table at t = 3: a cylinder on its side (a line contact) is not modelled"
    # a thin disk rolls upright through pi/2: its support function is even about it
    assert thin.flip_symmetric and not coin.flip_symmetric
    assert thin.describe().startswith("disk, thickness 0") and pk.Disk(2.0).describe().startswith("cylinder")


def test_the_base_check_refuses_the_edge_and_the_edged_check_accepts_it():
    disk = pk.Disk(0.1)
    with pytest.raises(pk.ParameterError, match="strictly convex"):
        Body.check_convex(disk, "thickness", (0.01, 1.5))
    disk.check_convex("thickness")  # the edge: zero meridian radius, not a concave profile


class Dented(EdgedBody):
    """A rim whose meridian bends inward near the face: h = sin - 0.1 sin^2, h + h'' = 0.3 sin^2 - 0.2 < 0
    for sin^2 < 2/3: concave, whatever the edge check allows."""

    def __init__(self):
        super().__init__(0.25, 0.5)

    @property
    def shape_params(self):
        return ()

    def height(self, c, shape):
        return ca.sqrt((1 - c) * (1 + c)) - 0.1 * (1 - c * c)

    @property
    def theta_range(self):
        return (0.0, math.pi / 2)

    @property
    def limits(self):
        return (Limit("face down", FLAT_ANGLE, -1, "face at {t}"),)


def test_a_concave_profile_is_refused_naming_the_parameter():
    with pytest.raises(pk.ParameterError) as err:
        Dented().check_convex("dent")
    assert err.value.param == "dent" and "convex surface" in str(err.value)


@pytest.mark.parametrize("kwargs, name", [
    (dict(thickness=-0.1), "thickness"), (dict(thickness=float("nan")), "thickness"), (dict(thickness=2e3), "thickness"),
    (dict(thickness=0.1, A=0.7, C=1.2), "C"), (dict(thickness=0.1, A=0.2, C=0.5), "C"), (dict(thickness=0.1, A=-1), "A"),
    (dict(flat_angle=1e-7), "flat_angle"), (dict(flat_angle=0.2), "flat_angle"), (dict(flat_angle=float("inf")), "flat_angle"),
])
def test_bad_parameters_are_named(kwargs, name):
    with pytest.raises(pk.ParameterError) as err:
        pk.Disk(**kwargs)
    assert err.value.param == name


def test_a_moment_beyond_the_rims_distance_is_refused_when_a_model_is_built():
    with pytest.raises(pk.ParameterError) as err:
        pk.Model(pk.Disk(0.1, A=1.5, C=0.9), pk.Coulomb(0.1))
    assert err.value.param == "A" and "1.0025" in str(err.value)  # r_max^2 = 1 + L^2/4


def test_disks_share_one_compiled_structure_and_round_trip_through_their_description():
    assert pk.Disk(0.0).structure_key == pk.Disk(0.1).structure_key == pk.Disk(3.0).structure_key
    for disk in (pk.Disk(0.0), pk.Disk(0.12), pk.Disk(0.3, A=0.3, C=0.45), pk.Disk(0.0, flat_angle=1e-6)):
        m = pk.Model(disk, pk.Coulomb(0.4))
        back = pk.Model.from_dict(m.to_dict())
        assert back == m and back.body.to_dict() == disk.to_dict() and back.body.to_dict()["body"] == "disk"
        assert back.body.limits == disk.limits
    # a description written before the face-down angle was a parameter reads as the default
    assert "flat_angle" not in pk.Disk(0.1).to_dict() and pk.Disk(0.0, flat_angle=1e-5) != pk.Disk(0.0)
    assert [lim.theta for lim in pk.Disk(0.0, flat_angle=1e-5).limits] == [1e-5, math.pi - 1e-5]
    assert make_body("disk") == pk.Disk(0.0) and make_body("disk", thickness=0.1) == pk.Disk(0.1)
    with pytest.raises(pk.ParameterError) as err:
        make_body("disk", a=1.5)
    assert err.value.param == "a"
    with pytest.raises(pk.ParameterError) as err:
        make_body("egg", thickness=0.1)
    assert err.value.param == "thickness"


def test_the_outline_drawn_is_the_faces_the_rims_and_the_side():
    z, r = pk.Disk(0.4).outline(15)
    assert (z[0], r[0], z[-1], r[-1]) == (-0.2, 0.0, 0.2, 0.0)  # the centres of the faces, on the axis
    assert np.all((np.abs(np.abs(z) - 0.2) < 1e-15) | (r == 1.0)) and {(-0.2, 1.0), (0.2, 1.0)} <= set(zip(z, r))
